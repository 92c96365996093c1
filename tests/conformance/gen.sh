#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Writes the conformance vectors of tests/conformance/ (make conformance):
# for each line of VECTORS below, NAME.bwv (the payload), NAME.i32 (its
# int32 samples), NAME.f32 (its float32 values) and NAME.json (its header,
# `brdfwave info --json`). The inputs are made here from small analytic
# functions and the shared data; see docs/FORMAT.md, Conformance vectors.
# The vectors are committed: regenerating them replaces them.
set -eu
cd "$(dirname "$0")/../.."
BW=${BW:-build/host/brdfwave}
OUT=tests/conformance
PY=/usr/bin/python3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# inputs: spectra (u16 and float, 37 bands: odd, not a power of two), a
# 3-band reflectance at level 2, an isotropic Phong BRDF at level 2 with 8
# incoming directions, a full Ward BRDF at level 1 (both hemispheres)
$PY - "$T" <<'PY'
import sys
import numpy as np
t = sys.argv[1]
b = np.arange(37)
s = np.array([1000 + 800 * np.sin(0.2 * b + k) + 30 * k * b for k in range(6)])
s.round().astype('<u2').tofile(t + '/spectra.u16')
(s / 4000.0).astype('<f4').tofile(t + '/spectra.f32')
PY
"$BW" grid --level 2 | $PY -c "
import sys, numpy as np
g = np.loadtxt(sys.stdin, delimiter=',', skiprows=1)
z = g[:, 5]
v = np.stack([0.2 + 0.6 * z, 0.1 + 0.3 * z ** 2, 0.05 + 0.02 * g[:, 3]], axis=1)
v.astype('<f4').tofile('$T/refl.f32')
(v * 10000).round().astype('<u2').tofile('$T/refl.u16')"
"$BW" synth --model phong --kd 0.6 --ks 0.3 --n 15 --level 2 --incoming 8 -o "$T/iso.f32"
"$BW" synth --model ward --kd 0.5 --ks 0.2 --ax 0.3 --ay 0.3 --level 1 --level-in 1 -o "$T/full.f32"
SED=$(ls tests/data/field_psr3500/*.sed | head -3)

# NAME INPUT FORMAT SHAPE... -- ENCODE OPTIONS
while read -r name rest; do
    [ -z "$name" ] || [ "${name#\#}" != "$name" ] && continue
    in=${rest%% -- *}
    opts=${rest#* -- }
    # shellcheck disable=SC2086
    "$BW" encode -q $in $opts -o "$OUT/$name.bwv"
    "$BW" decode -i "$OUT/$name.bwv" -o "$OUT/$name.i32" --output-format i32
    "$BW" decode -i "$OUT/$name.bwv" -o "$OUT/$name.f32"
    "$BW" info --json "$OUT/$name.bwv" >"$OUT/$name.json"
done <<EOF2
spectra_lossless_haar        -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis haar --symmetry none --no-metadata
spectra_lossless_53_rice     -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis 53 --coder rice
spectra_lossless_97          -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis 97
spectra_lossless_pred_rice   -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis pred --coder rice
spectra_maxerr_pred          -i $T/spectra.f32 --bands 37 -- --max-error 0.001 --basis pred
spectra_maxerr_97_stream     -i $T/spectra.f32 --bands 37 -- --max-error 0.001 --basis 97 --stream
spectra_bytes_53             -i $T/spectra.f32 --bands 37 -- --bytes 120 --basis 53
spectra_sed_decimal_lossless --input-format sed -i $(echo $SED | sed 's/ / -i /g') -- --lossless --basis 53
refl_lossless_53             -i $T/refl.u16 --input-format u16 --bands 3 --level 2 -- --lossless --basis 53 --symmetry none
refl_maxerr_haar_stream_rice -i $T/refl.f32 --bands 3 --level 2 -- --max-error 0.002 --basis haar --stream --coder rice --symmetry none
refl_bytes_97_mirror         -i $T/refl.f32 --bands 3 --level 2 -- --bytes 150 --basis 97 --symmetry mirror
iso_ratio_relative           -i $T/iso.f32 --bands 1 --level 2 --incoming 8 -- --ratio 16 --relative --symmetry none
iso_maxerr_mirror_rice       -i $T/iso.f32 --bands 1 --level 2 --incoming 8 -- --max-error 0.01 --symmetry mirror --coder rice
iso_maxerr_stream            -i $T/iso.f32 --bands 1 --level 2 --incoming 8 -- --max-error 0.01 --stream --basis haar --symmetry none
full_maxerr_reciprocal       -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --max-error 0.005 --symmetry reciprocal
full_bytes_both              -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --bytes 200 --symmetry both
full_maxerr_none_rice        -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --max-error 0.001 --symmetry none --coder rice
spectra_lossless_53_ms       -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis 53 --coder ms
refl_maxerr_haar_stream_ms   -i $T/refl.f32 --bands 3 --level 2 -- --max-error 0.002 --basis haar --stream --coder ms --symmetry none
iso_maxerr_mirror_ms         -i $T/iso.f32 --bands 1 --level 2 --incoming 8 -- --max-error 0.01 --symmetry mirror --coder ms
full_bytes_both_ms           -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --bytes 200 --symmetry both --coder ms
full_maxerr_both_segments    -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --max-error 0.005 --symmetry both --segments 5
spectra_lossless_pred_segments_rice -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis pred --coder rice --segments 3
refl_maxerr_53_segments_ms   -i $T/refl.f32 --bands 3 --level 2 -- --max-error 0.002 --basis 53 --coder ms --symmetry none --segments 7
iso_maxerr_embedded          -i $T/iso.f32 --bands 1 --level 2 --incoming 8 -- --max-error 0.002 --symmetry none --progressive
spectra_bytes_97_embedded_segments -i $T/spectra.f32 --bands 37 -- --bytes 300 --basis 97 --progressive --segments 3
full_maxerr_both_embedded    -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --max-error 0.001 --symmetry both --progressive
spectra_lossless_53_embedded -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis 53 --progressive
spectra_lossless_97_tab      -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --basis 97 --coder tab
spectra_maxerr_haar_stream_tab -i $T/spectra.f32 --bands 37 -- --max-error 0.001 --basis haar --stream --coder tab
refl_maxerr_53_mirror_tab    -i $T/refl.f32 --bands 3 --level 2 -- --max-error 0.002 --basis 53 --symmetry mirror --coder tab
full_maxerr_both_segments_tab -i $T/full.f32 --bands 1 --level 1 --level-in 1 -- --max-error 0.005 --symmetry both --segments 5 --coder tab
spectra_lossless_bands       -i $T/spectra.u16 --input-format u16 --bands 37 -- --lossless --band-access
spectra_maxerr_bands         -i $T/spectra.f32 --bands 37 -- --max-error 0.001 --band-access
EOF2
# version 7: the first vector with an ancillary extension record (type 0xC3,
# unassigned: a decoder skips it) in front of the same body
ext() { # NAME BASE TYPE TEXT
    $PY tests/conformance/add_ext.py "$OUT/$2.bwv" "$OUT/$1.bwv" "$3" "$(printf '%s' "$4" | od -An -tx1 | tr -d ' \n')"
    "$BW" decode -i "$OUT/$1.bwv" -o "$OUT/$1.i32" --output-format i32
    "$BW" decode -i "$OUT/$1.bwv" -o "$OUT/$1.f32"
    "$BW" info --json "$OUT/$1.bwv" >"$OUT/$1.json"
}
ext v7_ext_ancillary spectra_lossless_haar 0xc3 conformance
ls "$OUT"/*.bwv | wc -l
