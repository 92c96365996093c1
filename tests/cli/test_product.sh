#!/usr/bin/env bash
# The command line as people expect it of lz4, zstd and xz: --version, the
# summary line of encode (measured: the numbers agree with info and compare),
# a progress line on a terminal and never on a pipe, --json that parses,
# misspelt options named with the one meant for every command, `make help`
# listing every goal.
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
for args in "--version" "-V" "encode --version"; do
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
text = dict(l.split(': ', 1) for l in open(sys.argv[1]).read().splitlines())
obj = json.load(open(sys.argv[2]))
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
# a progress line: "\rbrdfwave CMD: ..." redrawn, then blanked, then the command's own line
progress_seen() { # FILE COMMAND_NAME
    $PY - "$1" "$2" <<'PY'
import sys
b = open(sys.argv[1], 'rb').read()
head = b'\rbrdfwave ' + sys.argv[2].encode() + b': '
assert b.count(head) >= 2, b[:300]
last = b.rindex(head)
cleared = b.index(b'\r', last + 1)
rest = b[cleared:]
assert rest[:1] == b'\r' and rest[1:].lstrip(b' ')[:1] in (b'\r',), rest[:80]
PY
}
"$BW" synth --model phong --kd 0.5 --ks 0.4 --n 30 --level 6 --incoming 16 -o "$T/big.f32"
export BRDFWAVE_PROGRESS_DELAY=0.1
on_tty "$T/tty" "$BW" encode -i "$T/big.f32" -o "$T/big.bwv" --bands 1 --level 6 --incoming 16 \
    --ratio 30 && progress_seen "$T/tty" encode && ok || bad "encode: no progress line on a terminal: $(head -c 300 "$T/tty" | od -c | head -5)"
grep -q -a 'big.bwv: 262144 samples -> ' "$T/tty" && ok || bad "encode on a terminal: no summary"
"$BW" encode -i "$T/big.f32" -o "$T/big.bwv" --bands 1 --level 6 --incoming 16 --ratio 30 2>"$T/pipe" &&
    ! grep -q -a $'\r' "$T/pipe" && [ "$(wc -l <"$T/pipe")" = 1 ] && ok ||
    bad "encode: a progress line in a pipe: $(od -c "$T/pipe" | head -3)"
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
EOF
while read -r cmd typo meant; do
    expect_status "bwref $cmd $typo" 2 "$BWREF" "$cmd" "$typo" 1
    grep -q "did you mean '$meant'" "$T/err" && ok || bad "bwref $cmd $typo: $(cat "$T/err")"
done <<'EOF'
wavedec --bsis --basis
ratios --levle --level
project --outptu --output
EOF

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

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
