#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The bwref command line: help, errors (one line, non-zero exit), and the
# ratios it reports on a synthetic set (counts, exactness at 1:1, byte budgets).
set -u
cd "$(dirname "$0")/../.."
BWREF=${BWREF:-build/host/bwref}
BW=${BW:-build/host/brdfwave}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

expect_error() { # name cmd...: non-zero exit, one line on stderr
    local name=$1 rc
    shift
    "$@" >"$T/out" 2>"$T/err"
    rc=$?
    if [ "$rc" = 0 ]; then bad "$name: exit 0"; return; fi
    if [ "$rc" -ge 128 ]; then bad "$name: signal $((rc - 128))"; return; fi
    [ "$(wc -l <"$T/err")" = 1 ] && ok || bad "$name: stderr $(cat "$T/err")"
}

for c in "" wavedec ratios import-rgl project; do
    if "$BWREF" $c --help >"$T/out" 2>&1 && grep -q "usage: bwref" "$T/out"; then ok; else bad "help $c"; fi
done
if "$BWREF" >/dev/null 2>"$T/err"; then bad "no command: exit 0"; else grep -q "usage: bwref" "$T/err" && ok || bad "no command: no usage"; fi
expect_error "unknown command" "$BWREF" frobnicate
expect_error "wavedec without input" "$BWREF" wavedec
expect_error "wavedec missing file" "$BWREF" wavedec -i "$T/none"
echo "1 2 3 x" >"$T/bad.txt"
expect_error "wavedec bad number" "$BWREF" wavedec -i "$T/bad.txt"
echo "1 2 3 4" >"$T/s.txt"
expect_error "wavedec unknown basis" "$BWREF" wavedec -i "$T/s.txt" --basis db99
expect_error "wavedec bad mode" "$BWREF" wavedec -i "$T/s.txt" --mode zero
expect_error "ratios without input" "$BWREF" ratios
expect_error "ratios wrong size" "$BWREF" ratios -i "$T/s.txt" --format text --level 1 --incoming 3
expect_error "ratios bad ratio" "$BWREF" ratios -i "$T/s.txt" --format text --ratios 0
expect_error "ratios bad format" "$BWREF" ratios -i "$T/s.txt" --format png
expect_error "ratios unknown basis" "$BWREF" ratios -i "$T/s.txt" --format text --bands 4 --basis nope
expect_error "ratios in-basis on a full BRDF" "$BWREF" ratios -i "$T/s.txt" --format text \
    --level 0 --level-in 0 --in-basis haar

# a synthetic isotropic set: 16 x 1024 samples
"$BW" synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16 -o "$T/p.f32" || bad synth
"$BWREF" ratios -i "$T/p.f32" --level 4 --incoming 16 --ratios 1,8,64 >"$T/r.csv" || bad "ratios run"
/usr/bin/python3 - "$T/r.csv" <<'PY' && ok || bad "ratios: counts, 1:1 exactness, monotone error"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows[0]['target'] == 'initial' and int(rows[0]['values']) == 16384, rows[0]
assert int(rows[0]['strips_flat']) == 512 and int(rows[0]['bytes_flat']) == 16384 * 8 + 512 * 8
r1, r8, r64 = rows[1:]
assert float(r1['rel_l2']) < 1e-10, r1
assert int(r8['kept']) == 2048 and int(r64['kept']) == 256, (r8, r64)
assert float(r64['rel_l2']) > float(r8['rel_l2']) > 0.0
assert int(r64['values']) == 256 and int(r64['bytes_flat']) == 256 * 8 + int(r64['strips_flat']) * 8
PY
"$BWREF" ratios -i "$T/p.f32" --level 4 --incoming 16 --bytes 1000,4000 --value-bytes 4 >"$T/b.csv" || bad "bytes run"
/usr/bin/python3 - "$T/b.csv" <<'PY' && ok || bad "ratios --bytes: budget respected and nearly used"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))[1:]
for r in rows:
    b, used = float(r['target']), int(r['bytes_flat'])
    assert used <= b and used > 0.9 * b, r
assert int(rows[1]['kept']) > int(rows[0]['kept'])
PY
# the paper's rule keeps the 64 scaling coefficients at 256:1
"$BWREF" ratios -i "$T/p.f32" --level 4 --incoming 16 --ratios 256 --magnitude raw \
    --keep-coarse 1 >"$T/c.csv" || bad "raw run"
"$BWREF" ratios -i "$T/p.f32" --level 4 --incoming 16 --ratios 256 --magnitude l2 \
    --keep-coarse 1 >"$T/d.csv" || bad "l2 run"
[ "$(sed -n 3p "$T/c.csv" | cut -d, -f2)" = 64 ] && ok || bad "raw rule count"
# at 256:1 both rules keep exactly the coarse coefficients: identical errors
[ "$(sed -n 3p "$T/c.csv" | cut -d, -f4,5)" = "$(sed -n 3p "$T/d.csv" | cut -d, -f4,5)" ] && ok \
    || bad "256:1 keeps exactly the scaling coefficients under both rules"

# import-rgl: a measured BRDF on the grid
R=tests/data/rgl/paper_white_rgb.bsdf
if "$BWREF" import-rgl -i "$R" -o "$T/pw.f32" --level 3 --channel g >"$T/imp" 2>&1; then
    grep -q "^incoming: 7 " "$T/imp" && ok || bad "import-rgl: incoming line $(cat "$T/imp")"
    [ "$(stat -c %s "$T/pw.f32")" = $((7 * 256 * 4)) ] && ok || bad "import-rgl: output size"
else
    bad "import-rgl run: $(cat "$T/imp")"
fi
"$BWREF" import-rgl -i "$R" -o "$T/pw3.f32" --level 2 --incoming 5 >/dev/null && \
    [ "$(stat -c %s "$T/pw3.f32")" = $((5 * 64 * 3 * 4)) ] && ok || bad "import-rgl rgb, 5 incoming"
"$BWREF" import-rgl -i "$R" -o "$T/pwf.f32" --level 1 --level-in 1 --channel r >/dev/null && \
    [ "$(stat -c %s "$T/pwf.f32")" = $((16 * 16 * 4)) ] && ok || bad "import-rgl full BRDF"
expect_error "import-rgl missing file" "$BWREF" import-rgl -i "$T/none.bsdf" -o "$T/x.f32"
expect_error "import-rgl not a tensor file" "$BWREF" import-rgl -i "$T/s.txt" -o "$T/x.f32"
expect_error "import-rgl bad channel" "$BWREF" import-rgl -i "$R" -o "$T/x.f32" --channel uv
expect_error "import-rgl bad incoming" "$BWREF" import-rgl -i "$R" -o "$T/x.f32" --incoming -3
expect_error "import-rgl bad level" "$BWREF" import-rgl -i "$R" -o "$T/x.f32" --level 9
[ ! -e "$T/x.f32" ] && ok || bad "import-rgl wrote a file on error"
# the imported set compresses like any other
"$BWREF" ratios -i "$T/pw.f32" --level 3 --incoming 7 --ratios 1,8 >"$T/pr.csv" && \
    awk -F, 'NR == 3 && $5 < 1e-9 {ok = 1} END {exit !ok}' "$T/pr.csv" && ok || bad "ratios on an import"

# project: scattered measured directions onto the grid. Phong1 at theta_i = 45
# deg measured at 474 Fibonacci directions, against `brdfwave synth
# --incoming 1` (the same BRDF at the level-4 centres, theta_i = 45 deg)
/usr/bin/python3 - "$T/fib.csv" "$T/const.csv" <<'PY' || bad "project: writing the CSV"
import math, sys
n, g = 474, math.pi * (3 - math.sqrt(5))
wi = (math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4))
with open(sys.argv[1], 'w') as f, open(sys.argv[2], 'w') as h:
    f.write('theta_deg,phi_deg,value\n')
    h.write('# a constant, two bands\n')
    for i in range(n):
        z = 1 - (i + 0.5) / n
        r, phi = math.sqrt(1 - z * z), g * i
        d = (r * math.cos(phi), r * math.sin(phi), z)
        c = -wi[0] * d[0] - wi[1] * d[1] + wi[2] * d[2]
        v = 0.75 / math.pi + (0.25 * 22 / (2 * math.pi) * c ** 20 if c > 0 else 0.0)
        th, ph = math.degrees(math.acos(z)), math.degrees(math.atan2(d[1], d[0]))
        f.write('%r,%r,%r\n' % (th, ph, v))
        h.write('%r, %r, 0.3, 7\n' % (th, ph))
PY
"$BW" synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 1 -o "$T/p45.f32" || bad synth45
if "$BWREF" project -i "$T/fib.csv" -o "$T/fib.f32" --level 4 >"$T/proj" 2>&1; then
    grep -q "^measurements: 474$" "$T/proj" && grep -q "^triangles: 1024 (level 4)$" "$T/proj" && ok \
        || bad "project: summary $(cat "$T/proj")"
    /usr/bin/python3 - "$T/fib.f32" "$T/p45.f32" <<'PY' && ok || bad "project: Phong1 from 474 directions"
import math, struct, sys
a = struct.unpack('<1024f', open(sys.argv[1], 'rb').read())
b = struct.unpack('<1024f', open(sys.argv[2], 'rb').read())
e = math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / sum(y * y for y in b))
print('project: relative L2 error %.4f against the level-4 centres' % e)
assert 0 < e < 0.05, e
PY
else
    bad "project run: $(cat "$T/proj")"
fi
"$BWREF" project -i "$T/const.csv" -o "$T/const.f32" --level 2 --k 5 >/dev/null && \
    /usr/bin/python3 -c '
import struct, sys
v = struct.unpack("<128f", open(sys.argv[1], "rb").read())
assert v[0::2] == (struct.unpack("<f", struct.pack("<f", 0.3))[0],) * 64 and v[1::2] == (7.0,) * 64
' "$T/const.f32" && ok || bad "project: a constant with two bands"
printf '10,0,1\n95,0,1\n' >"$T/p_theta.csv"
printf '10,0,1\n20,0\n' >"$T/p_cols.csv"
printf '10,0,1\n20,0,1,2\n' >"$T/p_ragged.csv"
printf 'theta,phi,value\n10,x,1\n' >"$T/p_num.csv"
printf '# nothing\n\n' >"$T/p_empty.csv"
printf '10,0,nan\n' >"$T/p_nan.csv"
expect_error "project missing file" "$BWREF" project -i "$T/none.csv" -o "$T/y.f32"
expect_error "project without output" "$BWREF" project -i "$T/fib.csv"
expect_error "project theta beyond 90" "$BWREF" project -i "$T/p_theta.csv" -o "$T/y.f32"
expect_error "project too few columns" "$BWREF" project -i "$T/p_cols.csv" -o "$T/y.f32"
expect_error "project ragged columns" "$BWREF" project -i "$T/p_ragged.csv" -o "$T/y.f32"
expect_error "project bad number" "$BWREF" project -i "$T/p_num.csv" -o "$T/y.f32"
expect_error "project no measurements" "$BWREF" project -i "$T/p_empty.csv" -o "$T/y.f32"
expect_error "project NaN value" "$BWREF" project -i "$T/p_nan.csv" -o "$T/y.f32"
expect_error "project bad level" "$BWREF" project -i "$T/fib.csv" -o "$T/y.f32" --level 7
expect_error "project bad k" "$BWREF" project -i "$T/fib.csv" -o "$T/y.f32" --k 0
[ ! -e "$T/y.f32" ] && ok || bad "project wrote a file on error"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
