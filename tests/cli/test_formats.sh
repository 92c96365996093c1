#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Measurements in and out with their metadata, on the real files of
# tests/data: every reader gives the wavelengths, units, instrument, time,
# location and angles its file holds (the values of
# tests/data/instruments/FORMATS.md); every output format that holds the
# data gives all of it back to 'encode' (the same metadata, the same
# samples); '-' is standard input and output; damaged files get one line.
set -u
cd "$(dirname "$0")/../.."
BW=${BW:-build/host/brdfwave}
PY=/usr/bin/python3
D=tests/data
I=$D/instruments
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0

ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

expect_ok() {
    local name=$1
    shift
    if "$@" >"$T/out" 2>"$T/err"; then ok; else bad "$name (exit $?): $(head -3 "$T/err")"; fi
}

# expect_error NAME WORD CMD...: non-zero exit below 128, one line on stderr
# that contains WORD (the file's name, or what is wrong)
expect_error() {
    local name=$1 word=$2 rc
    shift 2
    "$@" >"$T/out" 2>"$T/err"
    rc=$?
    if [ "$rc" = 0 ]; then bad "$name: exit 0 on bad input"; return; fi
    if [ "$rc" -ge 128 ]; then bad "$name: killed by signal $((rc - 128))"; return; fi
    if [ "$(wc -l <"$T/err")" != 1 ]; then bad "$name: not one line: $(cat "$T/err")"; return; fi
    grep -qF -- "$word" "$T/err" && ok || bad "$name: '$word' not in: $(cat "$T/err")"
}

# metajson PAYLOAD: the "metadata" object of 'info --json'
metajson() {
    "$BW" info --json "$1" | $PY -c 'import json, sys; print(json.dumps(json.load(sys.stdin)["metadata"]))'
}

# check NAME PYTHON-EXPRESSION: true, with m the metadata JSON of $T/x.bwv and
# a the decoded samples (numpy, the payload's shape)
check() {
    local name=$1 expr=$2
    metajson "$T/x.bwv" >"$T/m.json" && "$BW" decode -i "$T/x.bwv" -o "$T/x.npy" ||
        { bad "$name: info/decode failed"; return; }
    if $PY - "$T/m.json" "$T/x.npy" "$expr" <<'EOF'; then ok; else bad "$name: $expr"; fi
import json, sys
import numpy as np
m = json.load(open(sys.argv[1]))
a = np.load(sys.argv[2])
w = m.get("wavelengths", [])
f = m.get("fields", {})
if not eval("(" + sys.argv[3] + ")"):
    print("metadata:", {k: (v if not isinstance(v, list) or len(v) < 8 else v[:4] + ["..."])
                        for k, v in m.items()}, "shape", a.shape, "first", a.ravel()[:3])
    sys.exit(1)
EOF
}

# roundtrip NAME PAYLOAD [ENCODE-ARGS]: decoded to every format that holds
# the data and encoded again from it: the same metadata, the same samples
roundtrip() {
    local name=$1 p=$2 fmt out in
    shift 2
    metajson "$p" >"$T/rt0.json" && "$BW" decode -i "$p" -o "$T/rt0.f32" ||
        { bad "$name: decode"; return; }
    # the decoded values are whole multiples of the payload's scale: coded
    # again with it, without loss, they come back bit for bit
    "$BW" info "$p" >"$T/rt.info"
    set -- --lossless --scale "$(sed -n 's/^scale: //p' "$T/rt.info")"
    for fmt in raw npy csv envi; do
        rm -f "$T"/rt.*
        out=$T/rt.$fmt
        [ "$fmt" = envi ] && out=$T/rt.img
        expect_ok "$name: decode to $fmt" "$BW" decode -i "$p" -o "$out" --output-format "$fmt"
        in=$out
        [ "$fmt" = envi ] && in=$T/rt.hdr
        expect_ok "$name: encode from $fmt" "$BW" encode -i "$in" -o "$T/rt.bwv" "$@"
        metajson "$T/rt.bwv" >"$T/rt1.json" 2>&1
        cmp -s "$T/rt0.json" "$T/rt1.json" && ok ||
            bad "$name via $fmt: metadata differs: $(diff <(tr ',' '\n' <"$T/rt0.json") \
                <(tr ',' '\n' <"$T/rt1.json") | head -6)"
        "$BW" decode -i "$T/rt.bwv" -o "$T/rt1.f32" >/dev/null 2>&1
        cmp -s "$T/rt0.f32" "$T/rt1.f32" && ok || bad "$name via $fmt: samples differ"
    done
}

# ---- Spectral Evolution .sed: 60 files, one set ----------------------------
SED=$(ls $D/field_psr3500/*.sed)
expect_ok "sed set" "$BW" encode -i $SED -o "$T/x.bwv" --lossless
check "sed metadata" 'len(w) == 1024 and w[0] == 343.4 and m["instrument"] == "PSR-3500"
    and m["serial"] == "1116037" and len(m["spectrum_names"]) == 60
    and m["spectrum_names"][0] == "1116037_00041.sed"
    and m["spectrum_times"][0] == "2019-03-13T12:34:35"
    and m["quantity"] == "reflectance factor" and a.shape == (60, 1024)
    and len(m["spectrum_locations"]) == 60 and m["spectrum_locations"][0][:2] == [-28.16222, 28.95437]
    and abs(float(a[0, 0]) - 0.02452) < 1e-7'
"$BW" encode --no-metadata -i $SED -o "$T/bare.bwv" --lossless >/dev/null 2>&1
b0=$(stat -c %s "$T/bare.bwv")
b1=$(stat -c %s "$T/x.bwv")
"$BW" info "$T/x.bwv" >"$T/info"
mb=$(sed -n 's/^metadata_bytes: //p' "$T/info")
[ "$((b1 - b0))" = "$mb" ] && ok || bad "sed: metadata_bytes $mb, payloads differ by $((b1 - b0))"
echo "metadata bytes: 60 .sed spectra: $mb of $b1 (without: $b0)"
cp "$T/x.bwv" "$T/sed.bwv"
roundtrip "sed" "$T/sed.bwv" --lossless

# ---- RGL .bsdf: the measured incidence angles ------------------------------
expect_ok "bsdf" "$BW" encode -i $D/rgl/paper_white_rgb.bsdf -o "$T/x.bwv" --channel g --level 4 \
    --max-error 0.01
check "bsdf metadata" 'm["incidence_unit"] == "rad" and len(m["incidence"]) == 7
    and [round(x * 180 / np.pi, 2) for x in m["incidence"]] == [0, 27.67, 39.86, 49.94, 59.27, 68.57, 78.46]
    and m["quantity"] == "brdf" and m["unit"] == "sr^-1" and m["band_names"] == ["green"]
    and a.shape == (7, 1024, 1)'
"$BW" encode --no-metadata -i $D/rgl/paper_white_rgb.bsdf -o "$T/bare.bwv" --channel g --level 4 \
    --max-error 0.01 >/dev/null 2>&1
"$BW" info "$T/x.bwv" >"$T/info"
echo "metadata bytes: RGL paper_white (green, level 4, 7 incidences):" \
    "$(sed -n 's/^metadata_bytes: //p' "$T/info") of $(stat -c %s "$T/x.bwv")" \
    "(without: $(stat -c %s "$T/bare.bwv"))"
cp "$T/x.bwv" "$T/rgl.bwv"
roundtrip "bsdf" "$T/rgl.bwv" --max-error 0.01
# import-rgl's raw output keeps the measured angles in its sidecar, and
# encode of the raw file with --incoming 7 carries them into the payload
expect_ok "import-rgl" "$BW" import-rgl -i $D/rgl/paper_white_rgb.bsdf -o "$T/paper.f32" --channel g
expect_ok "encode import-rgl output" "$BW" encode -i "$T/paper.f32" -o "$T/x.bwv" --bands 1 \
    --level 4 --incoming 7 --max-error 0.01
check "import-rgl angles" '[round(x * 180 / np.pi, 2) for x in m["incidence"]] == [0, 27.67, 39.86, 49.94, 59.27, 68.57, 78.46]
    and m["quantity"] == "brdf"'
# the payload carries the measured angles to the evaluator and the renderer
expect_ok "render with measured angles" "$BW" render --scene sphereflake \
    --material payload:"$T/rgl.bwv" --sampling wavelet --level 4 --spp 1 --size 16x12 \
    -o "$T/r.png"

# ---- ASD binary, every version ---------------------------------------------
expect_ok "asd old" "$BW" encode -i $I/asd/3L9257.000 -o "$T/x.bwv" --max-error 1e-6
check "asd old" 'len(w) == 2151 and w[0] == 350 and w[-1] == 2500 and a.shape == (1, 2151)
    and abs(a.mean() - 0.2743279) < 1e-6 and m["quantity"] == "reflectance factor"
    and m["instrument"].startswith("ASD")'
for f in v6sample00000.asd:29.311738:301.529548 PM01_TIAM_B_LC_REFL00005.asd:4.409561:188.360001 \
    v7sample00000.asd:30.425934:303.574841 44231B009-1-FW300000.asd:19.330404:538.966893 \
    soil.asd:15.700499:533.718305; do
    IFS=: read -r name first last <<<"$f"
    expect_ok "asd $name" "$BW" encode -i $I/asd/$name -o "$T/x.bwv" --column target --max-error 0.01
    check "asd $name" "len(w) == 2151 and w[0] == 350 and a.shape == (1, 2151)
        and abs(a[0, 0] - $first) <= 0.01 and abs(a[0, -1] - $last) <= 0.01
        and 'spectrum_times' in m and 'serial' in m and a.dtype == np.float64"
done
expect_ok "asd v7 reflectance" "$BW" encode -i $I/asd/44231B009-1-FW300000.asd -o "$T/x.bwv" \
    --max-error 1e-4
check "asd v7 reflectance" 'abs(a[0, 0] - 19.330404 / 213.966830) < 1e-4'
cp "$T/x.bwv" "$T/asd.bwv"
roundtrip "asd" "$T/asd.bwv" --max-error 1e-4

# ---- SVC .sig: overlapping detectors kept -----------------------------------
expect_ok "sig ACPL" "$BW" encode -i $I/svc_sig/ACPL_D2_P1_T_1_000.sig -o "$T/x.bwv" --max-error 0.001
check "sig ACPL" 'len(w) == 1024 and w[0] == 340.5 and w[-1] == 2522.8
    and any(b < c for b, c in zip(w[1:], w)) and m["serial"] == "1152050"
    and m["quantity"] == "reflectance percent" and abs(a[0, 0] - 7.88) <= 0.001
    and abs(a[0, -1] - 8.08) <= 0.001 and m["spectrum_times"][0] == "2015-08-06T09:34:48"'
expect_ok "sig target" "$BW" encode -i $I/svc_sig/ACPL_D2_P1_T_1_000.sig -o "$T/x.bwv" \
    --column target --max-error 0.1
check "sig target" 'abs(a[0, 0] - 104.22) <= 0.1 and abs(a[0, -1] - 8969.59) <= 0.1'
expect_ok "sig set" "$BW" encode -i $I/svc_sig/ACPL_D2_P1_T_1_000.sig \
    $I/svc_sig/ACPL_D2_P1_T_1_WR_000.sig -o "$T/x.bwv" --max-error 0.001
check "sig set" 'a.shape == (2, 1024) and len(m["spectrum_names"]) == 2
    and abs(a[1, 0] - 97.50) <= 0.001 and m["serial"] == "1152050"'
expect_error "sig set of other bands" "bands" "$BW" encode -i $I/svc_sig/BNL13001_000.sig \
    $I/svc_sig/gr070214_003.sig -o "$T/y.bwv" --max-error 0.001
expect_ok "sig one" "$BW" encode -i $I/svc_sig/gr070214_003.sig -o "$T/sig1.bwv" --max-error 0.001
roundtrip "sig" "$T/sig1.bwv" --max-error 0.001

# ---- USGS splib07 ASCII with its wavelength table --------------------------
U=$I/usgs_splib07_ascii
expect_ok "usgs" "$BW" encode -i "$U/splib07a_Brick_GDS355_Paving_Dk_Gry_ASDFRa_AREF.txt" \
    -o "$T/x.bwv" --max-error 1e-6
check "usgs" 'len(w) == 2151 and m["wavelength_unit"] == "um" and abs(w[0] - 0.35) < 1e-6
    and abs(w[-1] - 2.5) < 1e-6 and a.shape == (1, 2151) and "Brick" in f["title"]'
expect_ok "usgs table" "$BW" encode -i "$U/splib07a_Brilliant(Hansa)yellowGDS785_ASDFRa_AREF.txt" \
    --wavelength-table "$U/s07_ASD_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt" -o "$T/x.bwv" \
    --max-error 1e-6
cp "$T/x.bwv" "$T/usgs.bwv"
roundtrip "usgs" "$T/usgs.bwv" --max-error 1e-6

# ---- ENVI: a spectral library and an image cube ----------------------------
expect_ok "envi sli" "$BW" encode -i $I/envi/s06av95a_envi.hdr --ignore-value -1.23e34 \
    -o "$T/x.bwv" --max-error 1e-5
check "envi sli" 'len(w) == 224 and m["wavelength_unit"] == "um" and a.shape == (1365, 224)
    and len(m["spectrum_names"]) == 1365 and m["spectrum_names"][0].startswith("Acmite NMNH133746")
    and "missing" in m and np.isclose(a, -1.23e34).sum() > 0'
expect_ok "envi cube" "$BW" encode -i $I/envi/ang20150420t182808_corr_v1e_img_4200-4210_70-80.hdr \
    -o "$T/x.bwv" --max-error 1e-4
check "envi cube" 'a.shape[-1] == len(w) and len(w) > 400 and "fwhm" in m and w[0] < 400'
cp "$T/x.bwv" "$T/envi.bwv"
roundtrip "envi cube" "$T/envi.bwv" --max-error 1e-4
# the same cube as BSQ, as BIL, and big-endian: the same samples and metadata
"$BW" decode -i "$T/envi.bwv" -o "$T/cube0.f32" 2>/dev/null
metajson "$T/envi.bwv" >"$T/cube0.json"
$PY - $I/envi/ang20150420t182808_corr_v1e_img_4200-4210_70-80 "$T" <<'EOF'
import re, sys
import numpy as np
src, out = sys.argv[1], sys.argv[2]
hdr = open(src + ".hdr").read()
a = np.fromfile(src + ".img", dtype="<f4").reshape(10, 10, 432)   # BIP: line, sample, band
for name, inter, arr, order in (("bsq", "bsq", a.transpose(2, 0, 1), 0),
                                ("bil", "bil", a.transpose(0, 2, 1), 0),
                                ("be", "bip", a, 1)):
    h = re.sub(r"interleave = \w+", "interleave = " + inter, hdr)
    h = re.sub(r"byte order = \d", "byte order = %d" % order, h)
    open("%s/c_%s.hdr" % (out, name), "w").write(h)
    np.ascontiguousarray(arr).astype(">f4" if order else "<f4").tofile("%s/c_%s.img" % (out, name))
EOF
for v in bsq bil be; do
    expect_ok "envi cube $v" "$BW" encode -i "$T/c_$v.hdr" -o "$T/c.bwv" --max-error 1e-4
    "$BW" decode -i "$T/c.bwv" -o "$T/c.f32" 2>/dev/null
    metajson "$T/c.bwv" >"$T/c.json"
    cmp -s "$T/c.f32" "$T/cube0.f32" && cmp -s "$T/c.json" "$T/cube0.json" && ok ||
        bad "envi cube $v: other samples or metadata than the BIP file's"
done

# ---- goniometer CSV: scattered directions onto the grid --------------------
expect_ok "gonio" "$BW" encode -i $D/goniometer/20200313_mastcamz_spectralon.csv -o "$T/x.bwv" \
    --max-error 1e-4
check "gonio" 'm["incidence"] == [0, 15, 30, 45, 58, 70] and w == [450, 550, 650, 750, 905, 1064]
    and m["fwhm"] == [70, 70, 70, 70, 25, 25] and a.shape == (6, 1024, 6)
    and 0.5 < float(np.median(a)) < 1.5'
cp "$T/x.bwv" "$T/gonio.bwv"
roundtrip "gonio" "$T/gonio.bwv" --max-error 1e-4
# the same data pivoted, a column per geometry: the same samples
expect_ok "gonio wide" "$BW" encode -i $D/goniometer/spectralon.csv -o "$T/x.bwv" --max-error 1e-4
check "gonio wide" 'm["incidence"] == [0, 15, 30, 45, 58, 70] and w == [450, 550, 650, 750, 905, 1064]
    and f["sample"] == "Spectralon" and a.shape == (6, 1024, 6)'
"$BW" decode -i "$T/gonio.bwv" -o "$T/g1.f32" 2>/dev/null
"$BW" decode -i "$T/x.bwv" -o "$T/g2.f32" 2>/dev/null
cmp -s "$T/g1.f32" "$T/g2.f32" && ok || bad "gonio: the pivoted file gives other samples"
head -c 40000 $D/goniometer/spectralon.csv >"$T/cut_wide.csv"
expect_error "gonio wide cut short" "cut_wide.csv" "$BW" encode -i "$T/cut_wide.csv" \
    --input-format gonio -o "$T/y.bwv" --max-error 1

# ---- missing samples: marked, coded as their neighbours, given back --------
printf 'wavelength_nm,a,b,c\n400,0.1,-1,0.3\n410,-1,0.2,-1\n420,0.1,-1,0.3\n430,-1,0.2,-1\n' >"$T/miss.csv"
expect_ok "missing in exact decimals" "$BW" encode -i "$T/miss.csv" --ignore-value -1 -o "$T/x.bwv" \
    --max-error 0.001
check "missing in exact decimals" 'm["missing"]["value"] == -1 and len(m["missing"]["runs"]) == 5
    and a.shape == (3, 4) and (a == -1).sum() == 6 and a[0, 0] == np.float32(0.1)'
expect_ok "missing to csv" "$BW" decode -i "$T/x.bwv" -o "$T/miss2.csv"
grep -v '^#' "$T/miss2.csv" | cmp -s - <(tail -n +1 "$T/miss.csv") && ok ||
    bad "missing samples: the CSV does not come back as it was"

expect_ok "missing, some bands" "$BW" decode -i "$T/x.bwv" --bands 1,3 -o "$T/miss3.csv"
grep -v '^#' "$T/miss3.csv" | cmp -s - <(sed -n '1p;3p;5p' "$T/miss.csv") && ok ||
    bad "missing samples of bands 1 and 3: the CSV rows do not come back as they were"

# ---- metadata from JSON and free fields -------------------------------------
cat >"$T/extra.json" <<'EOF'
{"quantity": "radiance", "instrument": "bench", "time": "2024-05-01T10:00:00+02:00",
 "location": [46.5191, 6.5668, 372], "fields": {"operator": "B. Roux"}}
EOF
expect_ok "--metadata and --field" "$BW" encode -i $I/asd/3L9257.000 -o "$T/x.bwv" \
    --max-error 1e-6 --metadata "$T/extra.json" --field "site=Lausanne" --field "note=a=b"
check "--metadata and --field" 'm["quantity"] == "radiance" and m["unit"] == "W m^-2 sr^-1 nm^-1"
    and m["instrument"] == "bench" and m["time"] == "2024-05-01T10:00:00+02:00"
    and m["location"] == [46.5191, 6.5668, 372] and f["operator"] == "B. Roux"
    and f["site"] == "Lausanne" and f["note"] == "a=b" and len(w) == 2151'
expect_error "bad --metadata" "extra2.json" "$BW" encode -i $I/asd/3L9257.000 -o "$T/y.bwv" \
    --max-error 1e-6 --metadata "$T/extra2.json"
echo '{"wavelengths": [1, 2]}' >"$T/extra2.json"
expect_error "wavelengths that do not fit" "wavelength" "$BW" encode -i $I/asd/3L9257.000 \
    -o "$T/y.bwv" --max-error 1e-6 --metadata "$T/extra2.json"
expect_ok "--no-metadata" "$BW" encode -i $I/asd/3L9257.000 -o "$T/x.bwv" --max-error 1e-6 \
    --no-metadata
"$BW" info "$T/x.bwv" >"$T/info"
grep -q '^metadata_bytes: 0$' "$T/info" && ok || bad "--no-metadata: metadata in the payload"

# ---- u16 in, u16 out ---------------------------------------------------------
$PY -c 'import numpy as np; (np.arange(4 * 300, dtype="<u2") * 53 % 65536).astype("<u2").tofile("'"$T"'/u.u16")'
expect_ok "u16 encode" "$BW" encode -i "$T/u.u16" --input-format u16 --bands 300 -o "$T/u.bwv" --lossless
expect_ok "u16 decode raw" "$BW" decode -i "$T/u.bwv" -o "$T/u2.raw" --output-format raw
cmp -s "$T/u.u16" "$T/u2.raw" && ok || bad "u16 in: raw out is not the same u16 file"
expect_ok "u16 decode npy" "$BW" decode -i "$T/u.bwv" -o "$T/u2.npy"
$PY -c 'import numpy as np, sys; a = np.load(sys.argv[1]); sys.exit(0 if a.dtype == np.uint16 and a.shape == (4, 300) else 1)' "$T/u2.npy" &&
    ok || bad "u16 in: npy out is not uint16 (4, 300)"
cp "$T/rt0.f32" "$T/nosidecar.f32"
expect_ok "f32 raw without sidecar" "$BW" encode -i "$T/nosidecar.f32" --bands 2 -o "$T/f.bwv" --max-error 1
"$BW" info "$T/f.bwv" | grep -q '^metadata_bytes: 0$' && ok ||
    bad "raw f32 without sidecar: metadata in the payload"

# ---- '-': standard input and output ----------------------------------------
"$BW" decode -i - -o - <"$T/sed.bwv" >"$T/std.f32" 2>"$T/err" && ok || bad "decode - -: $(cat "$T/err")"
"$BW" decode -i "$T/sed.bwv" -o "$T/file.f32" 2>/dev/null
cmp -s "$T/std.f32" "$T/file.f32" && ok || bad "decode to '-' differs from a file"
[ ! -e ./- ] && ok || bad "a file named '-' was written"
"$BW" decode -i "$T/sed.bwv" -o - --output-format npy 2>/dev/null | $PY -c '
import sys, io, numpy as np
a = np.load(io.BytesIO(sys.stdin.buffer.read()))
sys.exit(0 if a.shape == (60, 1024) else 1)' && ok || bad "decode npy to '-'"
cat $D/field_psr3500/1116037_00041.sed | "$BW" encode -i - --input-format sed -o - --lossless \
    >"$T/std.bwv" 2>"$T/err" && ok || bad "encode - -: $(cat "$T/err")"
"$BW" info --json - <"$T/std.bwv" >"$T/m.json" 2>"$T/err" && grep -q '"PSR-3500"' "$T/m.json" && ok ||
    bad "info -: $(cat "$T/err")"
expect_error "envi to '-'" "envi" "$BW" decode -i "$T/sed.bwv" -o - --output-format envi

# ---- damaged, truncated and unknown files ----------------------------------
head -c 20000 $I/asd/v7sample00000.asd >"$T/cut.asd"
expect_error "asd cut short" "cut.asd" "$BW" encode -i "$T/cut.asd" -o "$T/y.bwv" --max-error 1
{ printf 'as9'; tail -c +4 $I/asd/soil.asd; } >"$T/v9.asd"
expect_error "asd unknown version" "v9.asd" "$BW" encode -i "$T/v9.asd" -o "$T/y.bwv" \
    --input-format asd --max-error 1
head -c 9000 $I/svc_sig/gr070214_003.sig >"$T/cut.sig"
expect_error "sig cut short" "cut.sig" "$BW" encode -i "$T/cut.sig" -o "$T/y.bwv" --max-error 1
head -c 5000 "$U/splib07a_Brick_GDS355_Paving_Dk_Gry_ASDFRa_AREF.txt" >"$T/cut_AREF.txt"
expect_error "usgs cut short" "cut_AREF.txt" "$BW" encode -i "$T/cut_AREF.txt" --input-format usgs \
    -o "$T/y.bwv" --max-error 1
cp $I/envi/ang20150420t182808_corr_v1e_img_4200-4210_70-80.hdr "$T/c.hdr"
head -c 100000 $I/envi/ang20150420t182808_corr_v1e_img_4200-4210_70-80.img >"$T/c.img"
expect_error "envi data cut short" "c.img" "$BW" encode -i "$T/c.hdr" -o "$T/y.bwv" --max-error 1
head -c 300000 $D/goniometer/20200313_mastcamz_spectralon.csv >"$T/cut_gonio.csv"
expect_error "gonio cut short" "cut_gonio.csv" "$BW" encode -i "$T/cut_gonio.csv" -o "$T/y.bwv" \
    --max-error 1
head -c 100 $D/rgl/paper_white_rgb.bsdf >"$T/cut.bsdf"
expect_error "bsdf cut short" "cut.bsdf" "$BW" encode -i "$T/cut.bsdf" -o "$T/y.bwv" --max-error 1
"$BW" decode -i "$T/sed.bwv" -o "$T/n.npy" 2>/dev/null
head -c 60 "$T/n.npy" >"$T/cut.npy"
expect_error "npy cut short" "cut.npy" "$BW" encode -i "$T/cut.npy" -o "$T/y.bwv" --max-error 1
printf 'wavelength_nm,a\n400,0.1\n401,x\n' >"$T/bad.csv"
expect_error "csv not a number" "bad.csv" "$BW" encode -i "$T/bad.csv" -o "$T/y.bwv" --max-error 1
echo '{"wavelengths": [1, 2' >"$T/s.f32.json"
head -c 8 "$T/file.f32" >"$T/s.f32"
expect_error "broken sidecar" "s.f32.json" "$BW" encode -i "$T/s.f32" --bands 2 -o "$T/y.bwv" \
    --max-error 1
head -c $(($(stat -c %s "$T/sed.bwv") - 10)) "$T/sed.bwv" >"$T/cut.bwv"
expect_error "payload cut short" "cut.bwv" "$BW" info "$T/cut.bwv"
expect_error "unknown input format" "input-format" "$BW" encode -i "$T/s.f32" --input-format xls \
    -o "$T/y.bwv"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
