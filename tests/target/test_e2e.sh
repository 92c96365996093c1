#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# End to end: the firmware in QEMU reads the measurement as its sensor input,
# encodes it on the emulated Cortex-M4 and sends the payload over its UART
# (a pseudo-terminal) to the host, which checks the frames, asks for resends,
# stores the payload, decodes it and compares it with the host encoder's
# payload and with the input. Also `brdfwave receive` against a scripted
# device on a pseudo-terminal that corrupts and drops frames.
set -u
cd "$(dirname "$0")/../.."
BW=${BW:-build/host/brdfwave}
PY=/usr/bin/python3
DATA=tests/data/field_psr3500
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
# seconds since $1 (a `date +%s.%N`), and whether a number is below a bound
since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }'; }
below() { awk -v t="$1" -v m="$2" 'BEGIN { exit !(t < m) }'; }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

make --no-print-directory -s TARGET=qemu all || { echo "RESULT: 0 passed, 1 failed"; exit 1; }

# same_payload NAME ENCODE-ARGS...: device and host payloads are identical
# (the host with the device's default effort and coder), and the device's decodes
# within the mode's guarantee
same_payload() {
    local name=$1
    shift
    if ! "$BW" encode --device qemu "$@" -o "$T/dev.bwv" >"$T/dev.out" 2>"$T/dev.err"; then
        bad "$name: device encode: $(cat "$T/dev.err")"
        return
    fi
    grep -q "instructions (" "$T/dev.out" && ok || bad "$name: no instruction count reported"
    "$BW" encode --coder auto "$@" --effort fast -o "$T/host.bwv" 2>"$T/host.err" || { bad "$name: host encode: $(cat "$T/host.err")"; return; }
    cmp -s "$T/dev.bwv" "$T/host.bwv" && ok || bad "$name: device payload differs from the host's"
    "$BW" decode -i "$T/dev.bwv" -o "$T/dev.f32" && ok || bad "$name: decode"
}

# the 60 files' metadata (1289 bytes) goes to the device in a JOB_EXT frame
# and the JOB's own (docs/LINK.md)
same_payload "field spectra lossless" --input-format sed -i $DATA/*.sed --lossless
"$BW" info "$T/dev.bwv" | grep -q '^metadata_bytes: 1291$' && ok || bad "device payload without the set's metadata"
"$BW" decode -i "$T/dev.bwv" -o "$T/dev.i32" --output-format i32
"$BW" encode --input-format sed -i $DATA/*.sed -o "$T/ref.bwv" --basis haar >/dev/null
"$BW" decode -i "$T/ref.bwv" -o "$T/ref.i32" --output-format i32
cmp -s "$T/dev.i32" "$T/ref.i32" && ok || bad "field spectra: device decode not bit-exact"

same_payload "field spectra max-error" --input-format sed -i $DATA/*.sed --max-error 0.001
"$BW" decode -i "$T/ref.bwv" -o "$T/ref.f32"
"$BW" compare "$T/ref.f32" "$T/dev.f32" >"$T/cmp"
$PY -c "import sys; sys.exit(0 if float('$(sed -n 's/^max_abs_error: //p' "$T/cmp")') <= 0.001 else 1)" && ok ||
    bad "field spectra: max-error bound broken after the device: $(cat "$T/cmp")"

# a job carries the metadata (docs/LINK.md, JOB): the device's payload holds it
same_payload "4 field spectra with metadata" -i $(ls $DATA/*.sed | head -4) --max-error 0.001 --basis 53
"$BW" info "$T/dev.bwv" | grep -q '^instrument: "PSR-3500"$' && ok || bad "device payload without the metadata"

"$BW" synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16 -o "$T/p.f32"
same_payload "phong ratio 64" -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratio 64
same_payload "phong max-error" -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --max-error 0.01 --basis 53
# float input: the host maps the values (bit planes, log map), the device codes the samples
"$BW" import-rgl -i tests/data/rgl/paper_white_rgb.bsdf -o "$T/rgl.f32" --level 4 --channel g >/dev/null
same_payload "RGL float32 lossless" -i "$T/rgl.f32" --bands 1 --level 4 --incoming 7 --lossless
cmp -s "$T/rgl.f32" "$T/dev.f32" && ok || bad "RGL float32 lossless: device payload not bit-exact"
same_payload "RGL relative bound" -i "$T/rgl.f32" --bands 1 --level 4 --incoming 7 --max-rel-error 0.001
"$BW" synth --model ward --level 2 --level-in 2 -o "$T/w.f32"
same_payload "ward full brdf bytes" -i "$T/w.f32" --bands 1 --level 2 --level-in 2 --bytes 2000
head -c $((4 * 256 * 81)) /dev/urandom >"$T/r.i32"
$PY - "$T/r.i32" <<'PY'
import struct, sys
b = open(sys.argv[1], 'rb').read()
v = [x % 60000 for x in struct.unpack('<%dI' % (len(b) // 4), b)]
open(sys.argv[1], 'wb').write(struct.pack('<%di' % len(v), *v))
PY
same_payload "level-3 x 81 reflectance lossless" -i "$T/r.i32" --input-format i32 --bands 81 --level 3

# streamed: the device encodes spectrum by spectrum in bounded RAM, even a
# measurement larger than it could hold (256 x 1024 directions)
same_payload "field spectra streamed" --input-format sed -i $DATA/*.sed --stream --basis 97 --max-error 0.0005
"$BW" synth --model phong --kd 0.5 --ks 0.5 --n 50 --level 4 --incoming 256 -o "$T/p256.f32"
same_payload "phong 256 x 1024 streamed" -i "$T/p256.f32" --bands 1 --level 4 --incoming 256 --stream --basis haar --max-error 0.002
# the Rice coder: whole-measurement and streamed device paths
same_payload "field spectra lossless, rice" --input-format sed -i $DATA/*.sed --lossless --basis 53 --coder rice
same_payload "reflectance streamed, rice" -i "$T/r.i32" --input-format i32 --bands 81 --level 3 --stream --basis 53 --coder rice
"$BW" info "$T/dev.bwv" | grep -q "^order: streamed" && ok || bad "streamed payload not marked in info"
# segments: in the job's records; the device's payload is the host's, streamed or not
same_payload "field spectra in segments, prediction" --input-format sed -i $DATA/*.sed --lossless --basis pred --segments 6
same_payload "reflectance streamed in segments" -i "$T/r.i32" --input-format i32 --bands 81 --level 3 --stream --basis 53 --segments 9
"$BW" info "$T/dev.bwv" | grep -q "^segments: 9" && ok || bad "the device's payload has not its 9 segments"
# embedded segments: a record 0x04 after the segments' in the job; the
# device's payload is the host's; a byte budget the exact coding cut under it
# (16384 samples at 64:1 against float32: 1024 bytes); not in stream order
same_payload "phong ratio 64, embedded" -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratio 64 --progressive
"$BW" info "$T/dev.bwv" | grep -q "^order: embedded" && ok || bad "the device's payload is not embedded: $("$BW" info "$T/dev.bwv" | grep order)"
[ "$(stat -c %s "$T/dev.bwv")" -le 1024 ] && [ "$(stat -c %s "$T/dev.bwv")" -ge 1014 ] && ok ||
    bad "embedded byte budget of 1024: $(stat -c %s "$T/dev.bwv") bytes"
same_payload "reflectance in 4 embedded segments" -i "$T/r.i32" --input-format i32 --bands 81 --level 3 --max-error 0.001 --scale 0.0001 --segments 4 --progressive
"$BW" encode --device qemu -i "$T/r.i32" --input-format i32 --bands 81 --level 3 --stream --basis 53 --progressive -o "$T/x.bwv" >/dev/null 2>"$T/err"
[ $? = 2 ] && [ "$(wc -l <"$T/err")" = 1 ] && ok || bad "embedded segments streamed on the device: $(cat "$T/err")"

# resend: the host loses a chunk and asks for it again
"$BW" encode --device qemu --input-format sed -i $DATA/*.sed --basis 53 -o "$T/dev.bwv" --drop-chunk 5 >/dev/null 2>"$T/err" &&
    "$BW" encode --input-format sed -i $DATA/*.sed --basis 53 --effort fast --coder auto -o "$T/host.bwv" &&
    cmp -s "$T/dev.bwv" "$T/host.bwv" && ok || bad "resend of a lost chunk: $(cat "$T/err")"

# the same application as a host process (hal/linux) gives the same payloads
# (the host with the device's default effort and coder)
for args in "--basis 53 --lossless" "--stream --basis 97 --max-error 0.001" "--ratio 32 --basis haar"; do
    # shellcheck disable=SC2086
    if "$BW" encode --device linux --input-format sed -i $DATA/*.sed $args -o "$T/lin.bwv" >/dev/null 2>"$T/err" &&
        "$BW" encode --input-format sed -i $DATA/*.sed $args --effort fast --coder auto -o "$T/host.bwv" 2>>"$T/err"; then
        cmp -s "$T/lin.bwv" "$T/host.bwv" && ok || bad "linux device ($args): payload differs from the host's"
    else
        bad "linux device ($args): $(cat "$T/err")"
    fi
done
"$BW" encode --device linux -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratio 64 -o "$T/lin.bwv" --drop-chunk 0 >/dev/null 2>"$T/err" &&
    "$BW" encode -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratio 64 --effort fast --coder auto -o "$T/host.bwv" &&
    cmp -s "$T/lin.bwv" "$T/host.bwv" && ok || bad "linux device resend: $(cat "$T/err")"

# too large for the device: one clear line that says what the device holds and
# what to do, non-zero exit, no output, and no wait for a device that is done
"$BW" synth --model ward --level 4 --level-in 4 -o "$T/wbig.f32"
for dev in qemu linux; do
    t0=$(date +%s.%N)
    if timeout 120 "$BW" encode --device $dev -i "$T/wbig.f32" --bands 1 --level 4 --level-in 4 --ratio 64 -o "$T/x.bwv" 2>"$T/err"; then
        bad "$dev: oversized job accepted"
    else
        t=$(since "$t0")
        [ "$(wc -l <"$T/err")" = 1 ] && [ ! -e "$T/x.bwv" ] && ok || bad "$dev: oversized job: $(cat "$T/err")"
        grep -q "holds at most 131072 samples" "$T/err" && grep -q "not streamed" "$T/err" && ok ||
            bad "$dev: the error does not say what the device holds and what to do: $(cat "$T/err")"
        below "$t" 5 && ok || bad "$dev: the failed session took $t s"
    fi
done
# a streamable job too large to hold whole: the advice is --stream
if "$BW" encode --device linux -i "$T/p256.f32" --bands 1 --level 4 --incoming 256 --basis haar --max-error 0.002 -o "$T/x.bwv" 2>"$T/err"; then
    bad "linux: a job larger than the device's memory accepted"
else
    grep -q -- "--stream" "$T/err" && ok || bad "linux: no --stream advice: $(cat "$T/err")"
fi
"$BW" encode --device qemu --firmware "$T/none.elf" -i "$T/p.f32" --bands 1 --level 4 --incoming 16 --ratio 8 -o "$T/x.bwv" 2>"$T/err" &&
    bad "missing firmware accepted" || { [ "$(wc -l <"$T/err")" = 1 ] && ok || bad "missing firmware: $(cat "$T/err")"; }
# an emulator whose brdfwave has exited would be left to init (other runs' are not)
pgrep -P 1 -f "$PWD/build/host/../qemu/brdfwave-fw.elf" >/dev/null && bad "an emulator was left running" || ok

# a small job ends as soon as the payload is in: the device hears the ACK and
# the QUIT that follows it at once (5 runs each; a guard against waiting for a
# device that is done, not a speed benchmark)
"$BW" synth --model phong --kd 0.6 --ks 0.3 --n 12 --level 3 --incoming 3 -o "$T/small.f32"
for dev in qemu linux; do
    times=""
    for _ in 1 2 3 4 5; do
        t0=$(date +%s.%N)
        "$BW" encode --device $dev -i "$T/small.f32" --bands 1 --level 3 --incoming 3 --max-error 0.002 -o "$T/s.bwv" >/dev/null 2>"$T/err" ||
            bad "$dev: small job: $(cat "$T/err")"
        times="$times $(since "$t0")"
    done
    echo "timing: --device $dev small job, wall seconds:$times"
    slow=0
    for t in $times; do below "$t" 2 || slow=1; done
    [ "$slow" = 0 ] && ok || bad "$dev: a small job took 2 s or more:$times"
done

# `brdfwave receive` against a scripted device: garbage, a corrupted frame,
# a lost chunk; the receiver must resynchronise, ask, and store it intact
"$BW" encode --input-format sed -i $DATA/*.sed -o "$T/src.bwv" --max-error 0.002 >/dev/null
crc() { $PY -c "import struct,sys; print('%08x' % struct.unpack('<I', open(sys.argv[1],'rb').read()[-4:])[0])" "$1"; }
# fake MODE ARGS...: runs the scripted device in MODE, its pty in $T/pty
fake() {
    local mode=$1
    shift
    rm -f "$T/pty"
    $PY tests/target/fake_device.py "$T/src.bwv" "$T/pty" "$T/dev.log" "$mode" "$@" &
    fake_pid=$!
    for _ in $(seq 50); do [ -s "$T/pty" ] && break; sleep 0.1; done
}
mkdir -p "$T/rx"
fake damaged
if timeout 60 "$BW" receive --port "$(cat "$T/pty")" --out "$T/rx" --timeout 10 >"$T/rx.out" 2>"$T/rx.err"; then
    cmp -s "$T/src.bwv" "$T/rx/payload-7-$(crc "$T/src.bwv").bwv" && ok || bad "receive: stored payload differs: $(ls "$T/rx")"
    grep -q "resend request" "$T/rx.out" && ok || bad "receive: no summary line"
else
    bad "receive: $(cat "$T/rx.err")"
fi
wait $fake_pid && ok || bad "scripted device: $(cat "$T/dev.log")"
grep -q "RESEND" "$T/dev.log" && ok || bad "receive never asked for the damaged chunk"
grep -q "ACK" "$T/dev.log" && ok || bad "receive never acknowledged"
ls -a "$T/rx" | grep -q '^\.payload' && bad "receive left a temporary file" || ok

# every frame of a payload in one read: all heard, no resend needed
rm -rf "$T/rx" && mkdir "$T/rx"
fake one-write
if timeout 60 "$BW" receive --port "$(cat "$T/pty")" --out "$T/rx" --timeout 10 >"$T/rx.out" 2>"$T/rx.err"; then
    cmp -s "$T/src.bwv" "$T/rx/payload-8-$(crc "$T/src.bwv").bwv" && ok || bad "one read: stored payload differs"
    grep -q "0 resend request" "$T/rx.out" && ok || bad "one read: frames were lost: $(cat "$T/rx.out")"
else
    bad "one read: $(cat "$T/rx.err")"
fi
wait $fake_pid && ok || bad "scripted device (one read): $(cat "$T/dev.log")"

# the same id after a reboot: both payloads kept, neither replaced
"$BW" encode --input-format sed -i $DATA/*.sed -o "$T/src2.bwv" --max-error 0.004 >/dev/null
rm -rf "$T/rx" && mkdir "$T/rx"
fake twice "$T/src2.bwv"
if timeout 60 "$BW" receive --port "$(cat "$T/pty")" --out "$T/rx" --count 2 --timeout 10 >"$T/rx.out" 2>"$T/rx.err"; then
    cmp -s "$T/src.bwv" "$T/rx/payload-1-$(crc "$T/src.bwv").bwv" &&
        cmp -s "$T/src2.bwv" "$T/rx/payload-1-$(crc "$T/src2.bwv").bwv" && ok ||
        bad "repeated id: stored $(ls "$T/rx")"
else
    bad "repeated id: $(cat "$T/rx.err")"
fi
wait $fake_pid && ok || bad "scripted device (twice): $(cat "$T/dev.log")"

# a device that stops mid-payload and then sends only frames that bring
# nothing new: receive gives up after --timeout, not later, and keeps what
# arrived as an incomplete payload (exit 3)
rm -rf "$T/rx" && mkdir "$T/rx"
fake stall
t0=$(date +%s.%N)
timeout 60 "$BW" receive --port "$(cat "$T/pty")" --out "$T/rx" --timeout 2 >"$T/rx.out" 2>"$T/rx.err"
st=$?
t=$(since "$t0")
[ "$st" = 3 ] && ok || bad "stalled device: exit $st, not 3: $(cat "$T/rx.err")"
below "$t" 4 && ok || bad "stalled device: receive gave up after $t s, not about 2"
grep -q "nothing new from the device for 2 s" "$T/rx.err" && ok || bad "stalled device: $(cat "$T/rx.err")"
part=$T/rx/payload-9-$($PY -c "import zlib,sys; print('%08x' % zlib.crc32(open(sys.argv[1],'rb').read()))" "$T/src.bwv").part
[ -f "$part" ] && [ -f "$part.bwv" ] && ok || bad "stalled device: no incomplete payload kept: $(ls -A "$T/rx")"
[ -z "$(ls "$T/rx" | grep -v '\.part')" ] && ok || bad "stalled device: a whole payload stored: $(ls -A "$T/rx")"
kill $fake_pid 2>/dev/null
wait $fake_pid 2>/dev/null

# a payload in segments that the device stops sending with chunk 2 missing:
# kept as incomplete, decoded in part (the lost segments reported), then
# completed later by asking the device for that chunk only
"$BW" encode --input-format sed -i $DATA/*.sed -o "$T/seg.bwv" --max-error 0.002 --segments 12 >/dev/null
rm -rf "$T/rx" && mkdir "$T/rx"
rm -f "$T/pty"
$PY tests/target/fake_device.py "$T/seg.bwv" "$T/pty" "$T/dev.log" later &
fake_pid=$!
for _ in $(seq 50); do [ -s "$T/pty" ] && break; sleep 0.1; done
timeout 60 "$BW" receive --port "$(cat "$T/pty")" --out "$T/rx" --timeout 2 >"$T/rx.out" 2>"$T/rx.err"
st=$?
part=$T/rx/payload-10-$($PY -c "import zlib,sys; print('%08x' % zlib.crc32(open(sys.argv[1],'rb').read()))" "$T/seg.bwv").part
[ "$st" = 3 ] && ok || bad "later: exit $st, not 3: $(cat "$T/rx.err")"
grep -q "(1 of [0-9]* chunks missing)" "$T/rx.err" && grep -q -- "--resume $part" "$T/rx.err" && ok ||
    bad "later: $(cat "$T/rx.err")"
grep -q "^missing 2$" "$part" && ok || bad "later: record: $(cat "$part")"
$PY - "$T/seg.bwv" "$part.bwv" <<'PYEOF' && ok || bad "later: the kept bytes are not the payload's with chunk 2 zero"
import sys
a, b = open(sys.argv[1], 'rb').read(), open(sys.argv[2], 'rb').read()
z = a[:2048] + bytes(len(a[2048:3072])) + a[3072:]
sys.exit(0 if b == z else 1)
PYEOF
"$BW" decode -i "$part.bwv" -o "$T/part.f32" 2>"$T/dec.err"
st=$?
[ "$st" = 3 ] && grep -q "segment" "$T/dec.err" && ok || bad "later: decode of the kept bytes: exit $st: $(cat "$T/dec.err")"
sleep 1.3 # the device listens again after a second of silence
timeout 60 "$BW" receive --port "$(cat "$T/pty")" --resume "$part" --timeout 10 >"$T/rx.out" 2>"$T/rx.err" &&
    ok || bad "later: --resume: $(cat "$T/rx.err")"
cmp -s "$T/seg.bwv" "$T/rx/payload-10-$(crc "$T/seg.bwv").bwv" && ok || bad "later: completed payload differs: $(ls "$T/rx")"
[ ! -e "$part" ] && [ ! -e "$part.bwv" ] && ok || bad "later: the incomplete files were left"
grep -q "completed from what arrived before" "$T/rx.out" && ok || bad "later: $(cat "$T/rx.out")"
wait $fake_pid && ok || bad "scripted device (later): $(cat "$T/dev.log")"
grep -q "RESEND \[2\]" "$T/dev.log" && ok || bad "later: --resume did not ask for chunk 2 only: $(cat "$T/dev.log")"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
