#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The command line as people expect it of lz4, zstd and xz: --version, the
# summary line of encode (measured: the numbers agree with info and compare),
# a progress line on a terminal and never on a pipe, --json that parses,
# misspelt options named with the one meant for every command, `make help`
# listing every goal, and the pictures of `brdfwave plot`.
set -u
cd "$(dirname "$0")/../.."
BW=${BW:-build/host/brdfwave}
BWREF=${BWREF:-build/host/bwref}
PY=/usr/bin/python3
DATA=tests/data
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
key() { sed -n "s/^$1: //p" "$2"; }
# no command below may write into the tree's tracked files
tracked_before=$(git status --porcelain --untracked-files=no 2>/dev/null)

# expect_status NAME STATUS CMD...: that exit status, one line on stderr
expect_status() {
    local name=$1 want=$2 rc
    shift 2
    "$@" >"$T/out" 2>"$T/err"
    rc=$?
    if [ "$rc" != "$want" ]; then bad "$name: exit $rc, not $want: $(head -2 "$T/err")"; return; fi
    [ "$(wc -l <"$T/err")" = 1 ] && ok || bad "$name: stderr $(cat "$T/err")"
}

# ---- --version --------------------------------------------------------------
V=$(sed -n 's/^#define BRDFWAVE_VERSION_STRING "\(.*\)"/\1/p' include/brdfwave/brdfwave.h)
for args in "--version" "-V" "encode --version" "plot hemisphere --version"; do
    # shellcheck disable=SC2086
    out=$("$BW" $args 2>&1) && [ "$(echo "$out" | head -1)" = "brdfwave $V (libbrdfwave $V)" ] && ok ||
        bad "brdfwave $args: $out"
done
"$BWREF" --version | grep -q "^bwref $V " && ok || bad "bwref --version: $("$BWREF" --version 2>&1)"
"$BW" --help | grep -q -- "--version" && ok || bad "--help does not mention --version"

# ---- encode's summary line ----------------------------------------------------
"$BW" synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16 -o "$T/p.f32" ||
    bad "synth"
# SUMMARY FILE: the numbers of the line "OUT: N samples -> B bytes, X bits/sample,
# R:1 against FMT, max error E, relative L2 P %" as "n bytes bps ratio fmt maxerr l2"
summary() {
    sed -n 's/^.*: \([0-9]*\) samples -> \([0-9]*\) bytes, \([0-9.]*\) bits\/sample, \([0-9.]*\):1 against \([a-z0-9]*\), max error \([-0-9.e+]*\), relative L2 \([-0-9.e+]*\) %$/\1 \2 \3 \4 \5 \6 \7/p' "$1"
}
# check_summary NAME ERRFILE PAYLOAD REFERENCE.f32 DECODED.f32 FMT BYTES_PER_SAMPLE
check_summary() {
    local name=$1 err=$2 bwv=$3 ref=$4 dec=$5 fmt=$6 bps=$7 s
    [ "$(wc -l <"$err")" = 1 ] || { bad "$name: not one line: $(cat "$err")"; return; }
    s=$(summary "$err")
    [ -n "$s" ] || { bad "$name: no summary line: $(cat "$err")"; return; }
    "$BW" info "$bwv" >"$T/info" && "$BW" decode -i "$bwv" -o "$dec" &&
        "$BW" compare "$ref" "$dec" >"$T/cmp" || { bad "$name: info, decode or compare"; return; }
    # shellcheck disable=SC2086
    set -- $s
    $PY - "$@" "$(key samples "$T/info")" "$(key payload_bytes "$T/info")" \
        "$(key max_abs_error "$T/cmp")" "$(key relative_l2_percent "$T/cmp")" "$fmt" "$bps" <<'PY' &&
import sys
n, nbytes, bits, ratio, fmt, maxerr, l2, n_i, b_i, m_c, l2_c, want_fmt, own = sys.argv[1:]
assert n == n_i and nbytes == b_i, (n, n_i, nbytes, b_i)
assert abs(float(bits) - 8 * int(nbytes) / int(n)) < 1e-4, bits
assert abs(float(ratio) - int(own) * int(n) / int(nbytes)) < 0.01, (ratio, own)
assert fmt == want_fmt, fmt
assert abs(float(maxerr) - float(m_c)) <= 1e-6 * max(1, float(m_c)), (maxerr, m_c)
assert abs(float(l2) - float(l2_c)) <= 1e-5 * max(1e-3, float(l2_c)), (l2, l2_c)
PY
        ok || bad "$name: summary '$s' against info and compare"
}
"$BW" encode -i "$T/p.f32" -o "$T/p.bwv" --bands 1 --level 4 --incoming 16 --max-error 0.002 \
    2>"$T/enc.err" >"$T/enc.out" || bad "encode max-error"
[ ! -s "$T/enc.out" ] && ok || bad "encode wrote to standard output: $(cat "$T/enc.out")"
check_summary "f32 max-error" "$T/enc.err" "$T/p.bwv" "$T/p.f32" "$T/pd.f32" float32 4
"$BW" encode -i "$T/p.f32" -o "$T/pr.bwv" --bands 1 --level 4 --incoming 16 --ratio 40 \
    2>"$T/enc.err" || bad "encode ratio"
check_summary "f32 ratio 40" "$T/enc.err" "$T/pr.bwv" "$T/p.f32" "$T/prd.f32" float32 4
grep -q ' 40.0[0-9]:1 against float32' "$T/enc.err" && ok || bad "ratio 40: $(cat "$T/enc.err")"
head -c $((2 * 256 * 5)) /dev/urandom >"$T/r.u16"
"$BW" encode -i "$T/r.u16" --input-format u16 --bands 5 --level 3 --lossless -o "$T/r.bwv" \
    2>"$T/enc.err" || bad "encode u16"
$PY -c "import numpy as n; n.fromfile('$T/r.u16', '<u2').astype('<f4').tofile('$T/r.f32')"
check_summary "u16 lossless" "$T/enc.err" "$T/r.bwv" "$T/r.f32" "$T/rd.f32" uint16 2
grep -q 'max error 0, relative L2 0 %' "$T/enc.err" && ok || bad "lossless errors: $(cat "$T/enc.err")"
"$BW" encode --input-format sed -i $DATA/field_psr3500/*.sed -o "$T/f.bwv" --max-error 0.0005 \
    2>"$T/enc.err" || bad "encode sed"
"$BW" decode -i "$T/f.bwv" -o "$T/f_any.f32" # the reference: the exact decimals as float32
"$BW" encode --input-format sed -i $DATA/field_psr3500/*.sed -o "$T/fl.bwv" -q 2>"$T/q.err" &&
    [ ! -s "$T/q.err" ] && ok || bad "encode -q printed: $(cat "$T/q.err")"
"$BW" decode -i "$T/fl.bwv" -o "$T/f_exact.f32"
check_summary "sed max-error" "$T/enc.err" "$T/f.bwv" "$T/f_exact.f32" "$T/fd.f32" float32 4
"$BW" encode -i "$T/p.f32" -o - --bands 1 --level 4 --incoming 16 --ratio 40 2>"$T/enc.err" |
    cmp -s - "$T/pr.bwv" && grep -q '^(stdout): 16384 samples' "$T/enc.err" && ok ||
    bad "encode -o -: $(cat "$T/enc.err")"

# ---- --json -------------------------------------------------------------------
json_check() { # NAME TEXT_FILE JSON_FILE: valid JSON, the same keys and values as the text
    $PY - "$2" "$3" <<'PY' && ok || bad "$1: JSON"
import json, math, sys
lines = open(sys.argv[1]).read().splitlines()
# info: the metadata's own lines follow metadata_bytes; its JSON has them as "metadata"
keys = [l.split(': ', 1)[0] for l in lines]
if 'metadata_bytes' in keys:
    lines = lines[:keys.index('metadata_bytes') + 1]
text = dict(l.split(': ', 1) for l in lines)
obj = json.load(open(sys.argv[2]))
if 'metadata_bytes' in text:
    assert isinstance(obj.pop('metadata'), dict)
assert list(obj) == list(text), (list(obj), list(text))
for k, v in obj.items():
    t = text[k]
    if v is None:
        assert t in ('inf', 'nan'), (k, t)
    elif isinstance(v, str):
        assert v == t, (k, v, t)
    else:
        assert isinstance(v, (int, float)) and math.isclose(v, float(t), rel_tol=1e-12), (k, v, t)
PY
}
for f in tests/golden/v6/*.bwv "$T/p.bwv" "$T/r.bwv"; do
    "$BW" info "$f" >"$T/i.txt" && "$BW" info --json "$f" >"$T/i.json" || { bad "info --json $f"; continue; }
    json_check "info --json $(basename "$f")" "$T/i.txt" "$T/i.json"
done
"$BW" compare "$T/p.f32" "$T/pd.f32" >"$T/c.txt" && "$BW" compare --json "$T/p.f32" "$T/pd.f32" >"$T/c.json"
json_check "compare --json" "$T/c.txt" "$T/c.json"
"$BW" compare --json "$T/p.f32" "$T/p.f32" >"$T/c.json" && $PY -c "
import json; d = json.load(open('$T/c.json')); assert d['psnr_db'] is None and d['max_abs_error'] == 0" &&
    ok || bad "compare --json of identical files: $(cat "$T/c.json")"

# ---- progress: on a terminal, never on a pipe ------------------------------------
# on_tty FILE CMD...: runs CMD with standard error on a pseudo-terminal; its
# bytes go to FILE
on_tty() {
    local f=$1
    shift
    $PY - "$f" "$@" <<'PY'
import os, pty, subprocess, sys
m, s = pty.openpty()
p = subprocess.Popen(sys.argv[2:], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=s)
os.close(s)
got = b''
while True:
    try:
        d = os.read(m, 65536)
    except OSError:
        break
    if not d:
        break
    got += d
open(sys.argv[1], 'wb').write(got)
sys.exit(p.wait())
PY
}
# a progress line: "\rbrdfwave CMD: ..." shown (redrawn while the work lasts), then blanked, then the command's own line
progress_seen() { # FILE COMMAND_NAME
    $PY - "$1" "$2" <<'PY'
import sys
b = open(sys.argv[1], 'rb').read()
head = b'\rbrdfwave ' + sys.argv[2].encode() + b': '
assert b.count(head) >= 1, b[:300]
last = b.rindex(head)
cleared = b.index(b'\r', last + 1)
rest = b[cleared:]
assert rest[:1] == b'\r' and rest[1:].lstrip(b' ')[:1] in (b'\r',), rest[:80]
PY
}
"$BW" synth --model phong --kd 0.5 --ks 0.4 --n 30 --level 6 --incoming 16 -o "$T/big.f32"
export BRDFWAVE_PROGRESS_DELAY=0.02 # well inside the shortest of the commands below
on_tty "$T/tty" "$BW" encode -i "$T/big.f32" -o "$T/big.bwv" --bands 1 --level 6 --incoming 16 \
    --ratio 30 && progress_seen "$T/tty" encode && ok || bad "encode: no progress line on a terminal: $(head -c 300 "$T/tty" | od -c | head -5)"
grep -q -a 'big.bwv: 262144 samples -> ' "$T/tty" && ok || bad "encode on a terminal: no summary"
"$BW" encode -i "$T/big.f32" -o "$T/big.bwv" --bands 1 --level 6 --incoming 16 --ratio 30 2>"$T/pipe" &&
    ! grep -q -a $'\r' "$T/pipe" && [ "$(wc -l <"$T/pipe")" = 1 ] && ok ||
    bad "encode: a progress line in a pipe: $(od -c "$T/pipe" | head -3)"
on_tty "$T/tty" "$BW" plot rd -i "$T/big.f32" --bands 1 --level 6 --incoming 16 --ratios 10,30,100 \
    -o "$T/rd_tty.png" && progress_seen "$T/tty" "plot rd" && ok || bad "plot rd: no progress line"
on_tty "$T/tty" "$BW" render --size 64x48 --time 0.6 --threads 1 --sampling uniform -o "$T/r.png" &&
    progress_seen "$T/tty" render && ok || bad "render: no progress line on a terminal"
"$BW" render --size 64x48 --spp 4 -o "$T/r.png" >/dev/null 2>"$T/pipe" && [ ! -s "$T/pipe" ] && ok ||
    bad "render: a progress line in a pipe"
# decode: a large payload
"$BW" encode -i "$T/big.f32" -o "$T/bigl.bwv" --bands 1 --level 6 --incoming 16 --max-error 1e-5 -q
BRDFWAVE_PROGRESS_DELAY=0 on_tty "$T/tty" "$BW" decode -i "$T/bigl.bwv" -o "$T/bigl.f32"
$PY -c "
b = open('$T/tty', 'rb').read()
assert b == b'' or (b.startswith(b'\rbrdfwave decode: ') and b.rstrip(b' ').endswith(b'\r')), b[:200]" &&
    ok || bad "decode on a terminal: $(head -c 200 "$T/tty")"
unset BRDFWAVE_PROGRESS_DELAY

# ---- a misspelt option of every command is named with the one meant -------------
while read -r cmd typo meant; do
    cmd=${cmd/_/ } # plot_rd: plot rd
    # shellcheck disable=SC2086
    expect_status "$cmd $typo" 2 "$BW" $cmd "$typo" 1
    grep -q "^brdfwave $cmd: unknown option '$typo' (did you mean '$meant'?)" "$T/err" && ok ||
        bad "$cmd $typo: $(cat "$T/err")"
done <<'EOF'
encode --levle --level
decode --outptu --output
info --jsno --json
compare --fromat --format
grid --levl --level
synth --modle --model
receive --prot --port
acquire --chpi --chip
import-rgl --chanel --channel
render --scnee --scene
plot_hemisphere --edgse --edges
plot_spectra --paylod --payload
plot_rd --ratois --ratios
EOF
while read -r cmd typo meant; do
    expect_status "bwref $cmd $typo" 2 "$BWREF" "$cmd" "$typo" 1
    grep -q "did you mean '$meant'" "$T/err" && ok || bad "bwref $cmd $typo: $(cat "$T/err")"
done <<'EOF'
wavedec --bsis --basis
ratios --levle --level
project --outptu --output
EOF
expect_status "plot without a kind" 2 "$BW" plot
expect_status "plot, an unknown kind" 2 "$BW" plot histogram -i x -o y
expect_status "plot, an option before the kind" 2 "$BW" plot -i x hemisphere

# ---- make help lists every goal -------------------------------------------------
make --no-print-directory help >"$T/help" 2>&1 || bad "make help"
goals=$(sed -n 's/^\.PHONY: *//p' Makefile mk/*.mk | tr ' ' '\n' | grep -v '^$' | sort -u)
missing=""
for g in $goals; do
    grep -q "^  make $g\b" "$T/help" || missing="$missing $g"
done
[ -z "$missing" ] && ok || bad "make help leaves out:$missing"
[ "$(echo "$goals" | wc -w)" -ge 20 ] && ok || bad "only $(echo "$goals" | wc -w) goals found"
# and every goal it lists is one make knows
known=$(make -qp 2>/dev/null | sed -n 's/^\([a-z][a-z0-9-]*\):.*/\1/p' | sort -u)
extra=""
for g in $(sed -n 's/^  make \([a-z][a-z0-9-]*\).*/\1/p' "$T/help"); do
    echo "$known" | grep -qx "$g" || extra="$extra $g"
done
[ -z "$extra" ] && ok || bad "make help lists goals make does not know:$extra"

# ---- brdfwave plot ---------------------------------------------------------------
# png_rgb FILE: width height and the pixels, for the checks below (numpy)
cat >"$T/png.py" <<'PY'
import struct, zlib
import numpy as np
def read(path):
    d = open(path, 'rb').read()
    assert d[:8] == b'\x89PNG\r\n\x1a\n'
    pos, idat = 8, b''
    while pos < len(d):
        n, = struct.unpack('>I', d[pos:pos + 4])
        typ, body = d[pos + 4:pos + 8], d[pos + 8:pos + 8 + n]
        assert zlib.crc32(typ + body) & 0xffffffff == struct.unpack('>I', d[pos + 8 + n:pos + 12 + n])[0]
        if typ == b'IHDR':
            w, h, depth, colour = struct.unpack('>IIBB', body[:10])
            assert (depth, colour) == (8, 2)
        if typ == b'IDAT':
            idat += body
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 3 * w + 1)
    assert (raw[:, 0] == 0).all()
    return raw[:, 1:].reshape(h, w, 3).astype(int)
PY
# hemisphere: the specular peak of a Phong BRDF lies opposite the incoming
# direction (phi = 180 degrees, left of the centre) at its zenith angle
for k in 4 12; do
    "$BW" plot hemisphere -i "$T/p.bwv" --in $k -o "$T/h$k.png" >"$T/out" 2>"$T/err" ||
        { bad "plot hemisphere --in $k: $(cat "$T/err")"; continue; }
    [ ! -s "$T/out" ] && [ ! -s "$T/err" ] && ok || bad "plot hemisphere printed something"
    PYTHONPATH=$T $PY - "$T/h$k.png" $k <<'PY' && ok || bad "hemisphere --in $k: peak not at the mirror direction"
import sys, png
np = png.np
img = png.read(sys.argv[1]); k = int(sys.argv[2])
assert img.shape == (640, 780, 3), img.shape
# the disc: centre (300, 350), radius 240 pixels for 90 degrees (cmd_plot.c)
cx, cy, r = 300, 350, 240
theta = (k + 0.5) * 90 / 16
yy, xx = np.mgrid[0:640, 0:780]
inside = (xx - cx) ** 2 + (yy - cy) ** 2 < (r - 3) ** 2
# the top of the colour map is yellow: red and green high, blue low
score = np.where(inside, img[..., 0] + img[..., 1] - 2 * img[..., 2], -999)
# the brightest triangle: its centre within one triangle (about 7 degrees,
# 19 pixels, at level 4) of the mirror direction
ys, xs = np.nonzero(score >= score.max() - 8)
y, x = ys.mean(), xs.mean()
want = cx - r * theta / 90
assert abs(x - want) < 12 and abs(y - cy) < 12, (x, y, want)
PY
done
# --log, --range, --band of a 3-band reflectance, and a raw input with its shape
$PY -c "
import numpy as n
g = n.loadtxt('/dev/stdin', delimiter=',', skiprows=1)
v = n.stack([g[:, 5], 0.5 * g[:, 5] ** 2, 0.1 + 0 * g[:, 5]], axis=1)  # cos theta, ...
v.astype('<f4').tofile('$T/refl.f32')" < <("$BW" grid --level 3)
"$BW" plot hemisphere -i "$T/refl.f32" --bands 3 --level 3 --band 0 -o "$T/refl.png" &&
    PYTHONPATH=$T $PY - "$T/refl.png" <<'PY' && ok || bad "hemisphere of cos(theta): not brightest at the centre"
import sys, png
img = png.read(sys.argv[1])
centre, rim = img[358, 308], img[358, 300 + 225] # beside the dashed lines
# the colour map's top is yellow, its bottom dark violet (viridis)
assert centre[0] + centre[1] - centre[2] > 300, centre
assert sum(rim) < 200 and rim[2] > rim[0] > rim[1], rim
PY
"$BW" plot hemisphere -i "$T/refl.f32" --bands 3 --level 3 --log --range 0.01,1 --edges \
    --title "a title" -o "$T/refl2.png" && ok || bad "plot hemisphere --log --range"
expect_status "hemisphere of spectra" 1 "$BW" plot hemisphere -i "$T/fl.bwv" -o "$T/x.png"
expect_status "hemisphere --band out of range" 2 "$BW" plot hemisphere -i "$T/refl.f32" --bands 3 --level 3 --band 3 -o "$T/x.png"
expect_status "hemisphere of raw input without a shape" 2 "$BW" plot hemisphere -i "$T/refl.f32" -o "$T/x.png"
expect_status "hemisphere --log of values <= 0" 2 "$BW" plot hemisphere -i "$T/refl.f32" --bands 3 --level 3 --log --range 0,1 -o "$T/x.png"
[ ! -e "$T/x.png" ] && ok || bad "a failed plot left a picture"
# spectra: the original and its payload, the wavelengths of the .sed files
"$BW" plot spectra --input-format sed -i $DATA/field_psr3500/*.sed --payload "$T/f.bwv" \
    --spectrum 0 --spectrum 59 -o "$T/s.png" 2>"$T/err" &&
    PYTHONPATH=$T $PY - "$T/s.png" <<'PY' && ok || bad "plot spectra: $(cat "$T/err")"
import sys, png
img = png.read(sys.argv[1])
assert img.shape == (760, 960, 3)
# the two spectra's colours (cmd_plot: series 0 and 1) are drawn
blue = ((img[..., 0] < 40) & (abs(img[..., 1] - 114) < 30) & (img[..., 2] > 150)).sum()
red = ((img[..., 0] > 190) & (abs(img[..., 1] - 94) < 30) & (img[..., 2] < 50)).sum()
assert blue > 500 and red > 500, (blue, red)
PY
expect_status "spectra without a payload" 2 "$BW" plot spectra -i "$T/p.f32" -o "$T/x.png"
expect_status "spectra of another measurement" 1 "$BW" plot spectra -i "$T/r.u16" --input-format u16 --payload "$T/p.bwv" -o "$T/x.png"
expect_status "spectra, a spectrum out of range" 2 "$BW" plot spectra -i "$T/p.f32" --payload "$T/p.bwv" --spectrum 16384 -o "$T/x.png"
# rd: CSV on standard output, bits/sample falling and errors growing with the ratio
"$BW" plot rd -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratios 8,16,32,64,128 --relative \
    -o "$T/rd.png" >"$T/rd.csv" 2>"$T/err" && [ ! -s "$T/err" ] &&
    $PY - "$T/rd.csv" <<'PY' && ok || bad "plot rd: $(cat "$T/err") $(cat "$T/rd.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 10, rows
for coding in ('absolute', 'relative'):
    r = [x for x in rows if x['coding'] == coding]
    bps = [float(x['bits_per_sample']) for x in r]
    l2 = [float(x['relative_l2_percent']) for x in r]
    assert bps == sorted(bps, reverse=True) and l2 == sorted(l2), (bps, l2)
    assert all(int(x['bytes']) <= 4 * 16384 / float(x['ratio']) for x in r)
PY
PYTHONPATH=$T $PY -c "import png; assert png.read('$T/rd.png').shape == (560, 1100, 3)" && ok || bad "rd.png"
"$BW" plot rd -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratios 32 -o "$T/rd1.png" >"$T/rd1.csv" &&
    "$BW" encode -q -i "$T/p.f32" -o "$T/p32.bwv" --bands 1 --level 4 --incoming 16 --ratio 32 &&
    grep -q "^32,$(stat -c %s "$T/p32.bwv")," "$T/rd1.csv" && ok ||
    bad "plot rd: not the payload of encode --ratio 32 ($(cat "$T/rd1.csv"))"
expect_status "rd: every budget too small" 1 "$BW" plot rd -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratios 100000 -o "$T/x.png"
expect_status "rd --relative of integers" 2 "$BW" plot rd -i "$T/r.u16" --input-format u16 --bands 5 --level 3 --relative -o "$T/x.png"
expect_status "rd: bad --ratios" 2 "$BW" plot rd -i "$T/p.f32" --bands 1 --ratios 4,x -o "$T/x.png"
[ ! -e "$T/x.png" ] && ok || bad "a failed plot left a picture"

[ "$(git status --porcelain --untracked-files=no 2>/dev/null)" = "$tracked_before" ] && ok ||
    bad "tracked files changed: $(git status --porcelain --untracked-files=no | head -5)"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
