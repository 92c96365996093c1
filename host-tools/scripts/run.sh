#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The main job end to end: the firmware on the emulated co-processor (QEMU
# mps2-an386, Cortex-M4) reads each measurement as its sensor input, encodes
# it and sends the payload over its UART to the host, which checks, stores,
# decodes and compares it with the input. Writes build/run/summary.md and
# prints it. DEVICE=host encodes on the host instead.
#   data: the field spectra in tests/data (Spectral Evolution .sed, 60 x 1024)
#         and the paper's synthetic Phong set (16 incoming x 1024 outgoing)
set -eu
cd "$(dirname "$0")/../.."
BW=${BW:-build/host/brdfwave}
DEVICE=${DEVICE:-qemu}
OUT=build/run
mkdir -p "$OUT"
S="$OUT/summary.md"

enc() { # encode on the device, keeping its instruction count
    "$BW" encode --device "$DEVICE" "$@" | tee "$OUT/device.out"
}

row() { # label payload reference decoded
    local bytes samples l2 maxe instr
    bytes=$(sed -n 's/^payload_bytes: //p' "$OUT/info")
    samples=$(sed -n 's/^samples: //p' "$OUT/info")
    "$BW" compare "$3" "$4" >"$OUT/cmp"
    l2=$(sed -n 's/^relative_l2_percent: //p' "$OUT/cmp")
    maxe=$(sed -n 's/^max_abs_error: //p' "$OUT/cmp")
    instr=$(sed -n 's/.*instructions (\([0-9.]*\) per sample).*/\1/p' "$OUT/device.out" 2>/dev/null)
    how="$(sed -n 's/^basis: //p' "$OUT/info"), $(sed -n 's/^coder: //p' "$OUT/info")"
    printf '| %s | %s | %s | %s | %.3f | %.2f | %s | %s | %s |\n' "$1" "$how" "$samples" "$bytes" \
        "$(echo "8 * $bytes / $samples" | bc -l)" "$(echo "4 * $samples / $bytes" | bc -l)" "$l2" "$maxe" \
        "${instr:--}" >>"$S"
}

{
    echo "# brdfwave: encode on the $DEVICE co-processor, receive, decode, compare"
    echo
    echo "| measurement and mode | basis, coder | samples | payload bytes | bits/sample | ratio vs float32 | rel. L2 % | max abs error | device instructions/sample |"
    echo "|---|---|---|---|---|---|---|---|---|"
} >"$S"

# field spectra, exact on the file's 5 decimals
: >"$OUT/device.out"
enc --input-format sed -i tests/data/field_psr3500/*.sed -o "$OUT/field.bwv" --lossless
"$BW" decode -i "$OUT/field.bwv" -o "$OUT/field.f32"
"$BW" info "$OUT/field.bwv" >"$OUT/info"
cp "$OUT/field.f32" "$OUT/field_ref.f32"
row "field spectra, lossless" "$OUT/field.bwv" "$OUT/field_ref.f32" "$OUT/field.f32"
for E in 0.0005 0.002; do
    enc --input-format sed -i tests/data/field_psr3500/*.sed -o "$OUT/field_e.bwv" --max-error $E
    "$BW" decode -i "$OUT/field_e.bwv" -o "$OUT/field_e.f32"
    "$BW" info "$OUT/field_e.bwv" >"$OUT/info"
    row "field spectra, max-error $E" "$OUT/field_e.bwv" "$OUT/field_ref.f32" "$OUT/field_e.f32"
done

# the device's bounded-RAM path: spectrum by spectrum, coded as produced
enc --input-format sed -i tests/data/field_psr3500/*.sed -o "$OUT/field_s.bwv" --stream --basis 97 --max-error 0.0005
"$BW" decode -i "$OUT/field_s.bwv" -o "$OUT/field_s.f32"
"$BW" info "$OUT/field_s.bwv" >"$OUT/info"
row "field spectra, streamed, max-error 0.0005" "$OUT/field_s.bwv" "$OUT/field_ref.f32" "$OUT/field_s.f32"

# the paper's Phong (1) set, at the paper's ratios
"$BW" synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16 -o "$OUT/phong1.f32"
for R in 8 16 64 128 256; do
    enc -i "$OUT/phong1.f32" --bands 1 --level 4 --incoming 16 --ratio $R -o "$OUT/phong1.bwv"
    "$BW" decode -i "$OUT/phong1.bwv" -o "$OUT/phong1_d.f32"
    "$BW" info "$OUT/phong1.bwv" >"$OUT/info"
    row "Phong kd=0.75 ks=0.25 n=20, ratio $R:1" "$OUT/phong1.bwv" "$OUT/phong1.f32" "$OUT/phong1_d.f32"
done
echo >>"$S"
echo "Made by \`make run\` on $(date -u +%Y-%m-%d). Instructions are counted on the emulated Cortex-M4 (-icount shift=0, SysTick) for the whole encode, including the basis choice and the byte-budget search." >>"$S"
cat "$S"
