#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Rate regression and guarantee checks of the codec on a fixed small set.

Every case encodes a fixed input with the brdfwave CLI, decodes it and checks:
  * the guarantee of its mode: --lossless decodes bit-exactly, --max-error E
    keeps every sample within E, --ratio R never exceeds 4 n / R bytes;
    float32 input: --lossless-f32 (--lossless on the float32 values) gives
    back every bit, --max-rel-error R keeps every value within R |x| (with
    --max-error E as well, within min(E, R |x|));
  * the rate against tests/rd/baseline.txt: the payload of a lossless,
    max-error or relative case, and the RMSE (with --relative the relative L2 error) of a
    byte-budget case, whose rate is the budget, may not grow by more than 1 %.
RD_BASELINE_UPDATE=1 rewrites the baseline from this run (after a deliberate
change; a smaller rate passes without it). Prints one line per case and
"RESULT: N passed, M failed".

Usage: /usr/bin/python3 tests/rd/check_rd.py [build/host/brdfwave]
"""
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BASELINE = os.path.join(ROOT, "tests", "rd", "baseline.txt")
TOLERANCE = 1.01


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=300)
    if p.returncode != 0:
        raise RuntimeError("%s: exit %d: %s" % (" ".join(cmd), p.returncode,
                                               p.stderr.decode(errors="replace").strip()))
    return p.stdout.decode()


def inputs(bw, tmp):
    """name -> (float32 array, integer array, layout args)."""
    sets = {}
    raw = os.path.join(tmp, "phong1.f32")
    run([bw, "synth", "--model", "phong", "--kd", "0.75", "--ks", "0.25", "--n", "20",
         "--level", "4", "--incoming", "16", "-o", raw])
    f = np.fromfile(raw, dtype="<f4")
    sets["phong1"] = (f, np.rint(f / (f.max() / 65535.0)),
                      ["--bands", "1", "--level", "4", "--incoming", "16"])
    seds = sorted(glob.glob(os.path.join(ROOT, "tests", "data", "field_psr3500", "*.sed")))[:20]
    rows = []
    for p in seds:
        with open(p, encoding="latin-1") as fh:
            lines = fh.read().splitlines()
        i = next(k for k, l in enumerate(lines) if l.strip().startswith("Data:"))
        rows.append([float(l.split("\t")[4]) for l in lines[i + 2:] if l.strip()])
    f = np.array(rows, dtype=np.float32).ravel()
    sets["field20"] = (f, np.rint(f.astype(np.float64) * 10000.0), ["--bands", "1024"])
    raw = os.path.join(tmp, "paper.f32")
    run([bw, "import-rgl", "-i", os.path.join(ROOT, "tests", "data", "rgl",
                                             "paper_white_rgb.bsdf"),
         "-o", raw, "--level", "4", "--channel", "g"])
    f = np.fromfile(raw, dtype="<f4")
    sets["rgl_paper"] = (f, np.rint(f / (f.max() / 65535.0)),
                         ["--bands", "1", "--level", "4", "--incoming", str(f.size // 1024)])
    a = np.loadtxt(os.path.join(ROOT, "tests", "data", "spectralon",
                                "BRF_normalization_factor.csv"), delimiter=",")[::10, 1:]
    f = a.astype(np.float32).ravel()
    sets["spectralon8"] = (f, np.rint(f / (f.max() / 65535.0)), ["--bands", str(a.shape[1])])
    return sets


CASES = [  # set, mode arguments, extra layout arguments
    ("phong1", ["--lossless"], []),
    ("phong1", ["--max-error", "1"], []),
    ("phong1", ["--max-error", "4"], []),
    ("phong1", ["--max-error", "16"], []),
    ("phong1", ["--lossless"], ["--stream", "--basis", "haar"]),
    ("phong1", ["--ratio", "16"], []),
    ("phong1", ["--ratio", "64"], []),
    ("phong1", ["--ratio", "256"], []),
    ("phong1", ["--ratio", "256"], ["--relative"]),
    ("field20", ["--lossless"], []),
    ("field20", ["--max-error", "2"], []),
    ("field20", ["--max-error", "8"], []),
    ("field20", ["--max-error", "4"], ["--stream", "--basis", "53"]),
    ("field20", ["--ratio", "32"], []),
    ("field20", ["--ratio", "128"], []),
    ("rgl_paper", ["--lossless"], []),
    ("rgl_paper", ["--max-error", "4"], []),
    ("rgl_paper", ["--ratio", "64"], []),
    ("rgl_paper", ["--ratio", "64"], ["--relative"]),
    ("spectralon8", ["--lossless"], []),
    ("spectralon8", ["--max-error", "4"], []),
    ("spectralon8", ["--ratio", "64"], []),
    # float32 input: bit for bit, and the relative bound alone and with the absolute one
    ("field20", ["--lossless-f32"], []),
    ("rgl_paper", ["--lossless-f32"], []),
    ("field20", ["--max-rel-error", "0.001"], []),
    ("rgl_paper", ["--max-rel-error", "0.01"], []),
    ("rgl_paper", ["--max-rel-error", "0.0001"], []),
    ("spectralon8", ["--max-rel-error", "0.001"], ["--max-error", "0.0005"]),
]


def main():
    bw = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                         os.path.join(ROOT, "build", "host", "brdfwave"))
    update = os.environ.get("RD_BASELINE_UPDATE", "") not in ("", "0")
    base = {}
    if os.path.exists(BASELINE):
        with open(BASELINE) as fh:
            for l in fh:
                if l.strip() and not l.startswith("#"):
                    k, v = l.rsplit(None, 1)
                    base[k] = float(v)
    passed = failed = 0
    new = []
    with tempfile.TemporaryDirectory() as tmp:
        sets = inputs(bw, tmp)
        for name, mode, extra in CASES:
            f, q, layout = sets[name]
            key = "%s %s" % (name, " ".join(mode + extra))
            enc = os.path.join(tmp, "c.bwv")
            errs = []
            try:
                ratio = mode[0] == "--ratio"
                floats = mode[0] in ("--lossless-f32", "--max-rel-error")
                if floats:
                    src, fmt = os.path.join(tmp, "in.f32"), "f32"
                    f.astype("<f4").tofile(src)
                    if mode[0] == "--lossless-f32":
                        mode = ["--lossless"]
                elif ratio:
                    src, fmt = os.path.join(tmp, "in.f32"), "f32"
                    f.astype("<f4").tofile(src)
                else:
                    src, fmt = os.path.join(tmp, "in.u16"), "u16"
                    q.astype("<u2").tofile(src)
                # the codec's bytes: no metadata record (a u16 input would
                # otherwise record its sample type)
                run([bw, "encode", "-i", src, "-o", enc, "--input-format", fmt, "--no-metadata"] +
                    layout + mode + extra)
                nbytes = os.path.getsize(enc)
                dec = os.path.join(tmp, "c.out")
                if floats:
                    run([bw, "decode", "-i", enc, "-o", dec])
                    d = np.fromfile(dec, dtype="<f4")
                    x = f.astype(np.float32)
                    if d.size != x.size:
                        errs.append("decoded %d values, expected %d" % (d.size, x.size))
                    elif mode[0] == "--lossless":
                        nbad = int(np.sum(d.view(np.uint32) != x.view(np.uint32)))
                        if nbad:
                            errs.append("%d values not bit for bit" % nbad)
                    else:
                        R = float(mode[1])
                        ax = np.abs(x.astype(np.float64))
                        bound = R * ax
                        if "--max-error" in extra:
                            bound = np.minimum(bound, float(extra[extra.index("--max-error") + 1]))
                        nbad = int(np.sum(~(np.abs(d.astype(np.float64) - x) <= bound)))
                        if nbad:
                            errs.append("%d values beyond the bound" % nbad)
                    value = float(nbytes)
                    what = "%d B = %.4f bits/sample (float32)" % (nbytes, 8.0 * nbytes / x.size)
                elif ratio:
                    run([bw, "decode", "-i", enc, "-o", dec])
                    d = np.fromfile(dec, dtype="<f4").astype(np.float64)
                    budget = int(4 * f.size / float(mode[1]))
                    if nbytes > budget:
                        errs.append("payload %d B over the budget %d B" % (nbytes, budget))
                    ref = f.astype(np.float64)
                    if "--relative" in extra:
                        value = float(np.sqrt(np.mean(((d - ref) / ref) ** 2)))
                        what = "rel L2 %.6g (%d B of %d)" % (value, nbytes, budget)
                    else:
                        value = float(np.sqrt(np.mean((d - ref) ** 2)))
                        what = "RMSE %.6g (%d B of %d)" % (value, nbytes, budget)
                else:
                    run([bw, "decode", "-i", enc, "-o", dec, "--output-format", "i32"])
                    d = np.fromfile(dec, dtype="<i4").astype(np.int64)
                    e = int(np.max(np.abs(d - q.astype(np.int64)))) if d.size == q.size else -1
                    bound = 0 if mode[0] == "--lossless" else int(mode[1])
                    if d.size != q.size:
                        errs.append("decoded %d samples, expected %d" % (d.size, q.size))
                    elif e > bound:
                        errs.append("max error %d > bound %d" % (e, bound))
                    value = float(nbytes)
                    what = "%d B = %.4f bits/sample, max err %d" % (nbytes, 8.0 * nbytes / q.size, e)
            except RuntimeError as ex:
                errs.append(str(ex))
                value, what = None, "-"
            if value is not None:
                new.append((key, value))
                ref = base.get(key)
                if ref is None and not update:
                    errs.append("no baseline (run with RD_BASELINE_UPDATE=1)")
                elif ref is not None and not update and value > ref * TOLERANCE:
                    errs.append("grew %.2f %% over the baseline %.6g" % (100 * (value / ref - 1), ref))
                if ref is not None:
                    what += " (baseline %.6g, %+.2f %%)" % (ref, 100 * (value / ref - 1) if ref else 0)
            if errs:
                failed += 1
                print("FAIL %s: %s: %s" % (key, what, "; ".join(errs)))
            else:
                passed += 1
                print("ok   %s: %s" % (key, what))
    if update:
        with open(BASELINE, "w") as fh:
            fh.write("# tests/rd/check_rd.py baseline: payload bytes (lossless, max-error) or\n"
                     "# RMSE / relative L2 (ratio). Rewrite with RD_BASELINE_UPDATE=1 after a deliberate change.\n")
            for k, v in new:
                fh.write("%s %.9g\n" % (k, v))
        print("baseline written: %s" % BASELINE)
    print("RESULT: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
