#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""The per-sample guarantees of float input against ZFP, with targets.

Float lossless: brdfwave --lossless (every float32 bit kept) against ZFP's
reversible mode (-R), on every float set of the rate-distortion benchmark;
target: at most 0.9 x ZFP's bytes on each set, and bit-exact. fpzip's
lossless mode is reported beside it.

Relative bound: brdfwave --max-rel-error R (|x' - x| <= R |x| on every
sample) for R = 1e-2, 1e-3, 1e-4 on the field spectra, Spectralon and RGL
sets, against what meets the same guarantee without a relative mode: an
absolute bound E = R x the smallest non-zero |value|, by brdfwave
--max-error E and by ZFP fixed accuracy (-a E); target: at most 0.8 x the
smaller of the two. Every sample of every payload is checked against its
rule (ours, and ZFP's, whose tolerance is checked too).

ZFP runs on the array and on its transpose (-2 in both orders); the better
counts. Writes build/bench/guarantee.md and guarantee.csv.

Usage: /usr/bin/python3 tests/bench/run_guarantee_bench.py  (`make bench-guarantee`,
also run by `make bench-rd`). Environment: BW (default build/host/brdfwave),
RD_SETS (comma-separated subset of the set keys, as run_rd_bench.py),
BENCH_KEEP_TMP=1 keeps build/bench/guarantee_tmp.

Exit status 0, or 1 if brdfwave failed on an input or broke a guarantee.
Missed targets are reported, not failed.
"""

import csv
import datetime
import os
import shutil
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_codec_bench as cb  # noqa: E402
import run_rd_bench as rd  # noqa: E402

OUT_DIR = cb.OUT_DIR
TMP_DIR = os.path.join(OUT_DIR, "guarantee_tmp")
REPORT_MD = os.path.join(OUT_DIR, "guarantee.md")
REPORT_CSV = os.path.join(OUT_DIR, "guarantee.csv")

TARGET_LOSSLESS = 0.9   # x ZFP reversible's bytes
TARGET_RELATIVE = 0.8   # x the best absolute coding of R x min |x|
REL_BOUNDS = [1e-2, 1e-3, 1e-4]
REL_SETS = ("field", "spectralon", "rgl_paper_white", "rgl_satin_rosaline", "rgl_cc_ibiza_sunset")

log = cb.log


def tmp(name):
    return os.path.join(TMP_DIR, name)


def ours(bw, s, raw, args, tag):
    """brdfwave encode + decode: (bytes, decoded float32 array, seconds)."""
    enc, dec = tmp("%s_%s.bwv" % (s.key, tag)), tmp("%s_%s.dec" % (s.key, tag))
    cmd = [bw, "encode", "-i", raw, "-o", enc] + s.layout + args
    _, t1 = cb.run(cmd, "brdfwave encode %s" % " ".join(args))
    _, t2 = cb.run([bw, "decode", "-i", enc, "-o", dec], "brdfwave decode")
    return os.path.getsize(enc), np.fromfile(dec, dtype="<f4"), t1 + t2, cb.cmdline(cmd)


def zfp(raw, shape, flags, tag):
    """ZFP on the array and its transpose: the smaller of the two (bytes,
    decoded values in the array's order, orientation) or None without zfp."""
    if not cb.have("zfp"):
        return None
    h, w = shape
    a = np.fromfile(raw, dtype="<f4").reshape(h, w)
    best = None
    for orient, arr, dims in (("rows", a, [str(w), str(h)]), ("cols", a.T.copy(), [str(h), str(w)])):
        src, out = tmp("zfp_%s_%s.f32" % (tag, orient)), tmp("zfp_%s_%s.zfp" % (tag, orient))
        arr.astype("<f4").tofile(src)
        cb.run(["zfp", "-q", "-h", "-f", "-2"] + dims + flags + ["-i", src, "-z", out], "zfp")
        cb.run(["zfp", "-q", "-h", "-z", out, "-o", out + ".f32"], "zfp decompress")
        d = np.fromfile(out + ".f32", dtype="<f4").reshape(arr.shape)
        if orient == "cols":
            d = d.T
        n = os.path.getsize(out)
        if best is None or n < best[0]:
            best = (n, d.ravel(), orient)
    return best


def fpzip(raw, shape, tag):
    """fpzip (lossless) on the array and its transpose: the smaller (bytes,
    bit-exact) or None without fpzip."""
    if not cb.have("fpzip"):
        return None
    h, w = shape
    a = np.fromfile(raw, dtype="<f4").reshape(h, w)
    best = None
    for orient, arr, dims in (("rows", a, [str(w), str(h)]), ("cols", a.T.copy(), [str(h), str(w)])):
        src, out = tmp("fpz_%s_%s.f32" % (tag, orient)), tmp("fpz_%s_%s.fpz" % (tag, orient))
        arr.astype("<f4").tofile(src)
        cb.run(["fpzip", "-q", "-2"] + dims + ["-i", src, "-o", out], "fpzip")
        cb.run(["fpzip", "-q", "-d", "-2"] + dims + ["-i", out, "-o", out + ".f32"],
               "fpzip decompress")
        exact = open(out + ".f32", "rb").read() == open(src, "rb").read()
        n = os.path.getsize(out)
        if best is None or n < best[0]:
            best = (n, exact, orient)
    return best


def bits(nbytes, n):
    return 8.0 * nbytes / n


def main():
    bw = os.path.abspath(os.environ.get("BW", os.path.join(cb.ROOT, "build", "host", "brdfwave")))
    if not (os.path.isfile(bw) and os.access(bw, os.X_OK)):
        log("run_guarantee_bench: brdfwave CLI not found at %s (run `make`)" % bw)
        return 2
    wanted = [k for k in os.environ.get("RD_SETS", "").split(",") if k]
    t0 = time.perf_counter()
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
    shutil.rmtree(TMP_DIR, ignore_errors=True)
    os.makedirs(TMP_DIR)
    rd.TMP_DIR = cb.TMP_DIR = TMP_DIR
    try:
        sets = rd.load_sets(bw, wanted)
    except cb.ToolError as e:
        log("run_guarantee_bench: " + str(e))
        return 1
    failures, rows, lossless, relative = [], [], [], []
    met = missed = 0
    for s in sets:
        raw = tmp("%s.f32" % s.key)
        s.f.astype("<f4").tofile(raw)
        x = s.f.ravel()
        n = x.size
        # float lossless against ZFP reversible
        try:
            nb, d, dt, cmd = ours(bw, s, raw, ["--lossless"], "lossless")
        except cb.ToolError as e:
            failures.append(str(e))
            continue
        exact = d.view(np.uint32).size == n and np.array_equal(d.view(np.uint32), x.view(np.uint32))
        if not exact:
            failures.append("%s: --lossless not bit-exact" % s.key)
        z = zfp(raw, s.f.shape, ["-R"], s.key)
        zexact = z is not None and np.array_equal(z[1].view(np.uint32), x.view(np.uint32))
        ratio = nb / z[0] if z else float("nan")
        ok = exact and z is not None and ratio <= TARGET_LOSSLESS
        met, missed = met + ok, missed + (not ok)
        fz = fpzip(raw, s.f.shape, s.key)
        lossless.append((s, nb, z, ratio, ok, exact, zexact, fz))
        if fz:
            rows.append([s.key, "lossless", "", "fpzip (%s)" % fz[2], fz[0], bits(fz[0], n), 0.0,
                         fz[1], ""])
        rows.append([s.key, "lossless", "", "brdfwave", nb, bits(nb, n), 0.0, exact, cmd])
        if z:
            rows.append([s.key, "lossless", "", "zfp -R (%s)" % z[2], z[0], bits(z[0], n), 0.0,
                         zexact, ""])
        log("%-22s lossless: %d B (%.3f b/s) vs zfp -R %s B: %.3f %s; fpzip %s B"
            % (s.key, nb, bits(nb, n), z[0] if z else "-", ratio, "met" if ok else "MISSED",
               fz[0] if fz else "-"))
        if s.key not in REL_SETS:
            continue
        ax = np.abs(x.astype(np.float64))
        mn = float(ax[ax > 0].min())
        for R in REL_BOUNDS:
            E = R * mn
            ent = {"R": R, "E": E}
            try:
                nb, d, dt, cmd = ours(bw, s, raw, ["--max-rel-error", "%g" % R], "rel")
                err = np.abs(d.astype(np.float64) - x)
                held = bool(np.all(err <= R * ax))
                if not held:
                    failures.append("%s: --max-rel-error %g broken at %d samples"
                                    % (s.key, R, int(np.sum(err > R * ax))))
                ent["ours"] = (nb, held, float(np.max(err / np.maximum(ax, 1e-300))))
                rows.append([s.key, "relative", R, "brdfwave --max-rel-error", nb, bits(nb, n),
                             float(np.max(err)), held, cmd])
            except cb.ToolError as e:
                failures.append(str(e))
                continue
            try:
                nb, d, dt, cmd = ours(bw, s, raw, ["--max-error", "%.9g" % E], "abs")
                err = np.abs(d.astype(np.float64) - x)
                held = bool(np.all(err <= R * ax))
                ent["abs"] = (nb, held)
                rows.append([s.key, "relative", R, "brdfwave --max-error R*min", nb, bits(nb, n),
                             float(np.max(err)), held, cmd])
            except cb.ToolError as e:
                ent["abs"] = None
                # the CLI's own line, between "exit status N: " and the command
                msg = str(e).rsplit(" [", 1)[0]
                ent["abs_err"] = msg.split(": ", 2)[-1].replace("brdfwave encode: ", "")
            z = zfp(raw, s.f.shape, ["-a", "%.9g" % E], "%s_a" % s.key)
            if z:
                err = np.abs(z[1].astype(np.float64) - x)
                ent["zfp"] = (z[0], bool(np.all(err <= E)), bool(np.all(err <= R * ax)), z[2])
                rows.append([s.key, "relative", R, "zfp -a R*min (%s)" % z[2], z[0],
                             bits(z[0], n), float(np.max(err)), ent["zfp"][2], ""])
            peers = [v[0] for v in (ent.get("abs"), ent.get("zfp")) if v]
            best = min(peers) if peers else None
            ent["ratio"] = ent["ours"][0] / best if best else float("nan")
            ok = ent["ours"][1] and best is not None and ent["ratio"] <= TARGET_RELATIVE
            ent["ok"] = ok
            met, missed = met + ok, missed + (not ok)
            relative.append((s, ent))
            log("%-22s R=%g: ours %d B vs abs %s, zfp %s: %.3f %s"
                % (s.key, R, ent["ours"][0], ent["abs"][0] if ent.get("abs") else "refused",
                   ent["zfp"][0] if ent.get("zfp") else "-", ent["ratio"],
                   "met" if ok else "MISSED"))
    elapsed = time.perf_counter() - t0
    write_report(sets, lossless, relative, failures, met, missed, started, elapsed)
    with open(REPORT_CSV, "w", newline="") as fh:
        wr = csv.writer(fh)
        wr.writerow(["set", "guarantee", "R", "codec", "bytes", "bits_per_sample", "max_abs_error",
                     "guarantee_held", "command"])
        wr.writerows(rows)
    log("wrote %s (%d targets met, %d missed; %.0f s)" % (cb.rel(REPORT_MD), met, missed, elapsed))
    if os.environ.get("BENCH_KEEP_TMP", "") in ("", "0"):
        shutil.rmtree(TMP_DIR, ignore_errors=True)
    if failures:
        for f in failures:
            log("run_guarantee_bench: " + f)
        return 1
    return 0


def write_report(sets, lossless, relative, failures, met, missed, started, elapsed):
    L = ["# Guarantees of float input against ZFP", "",
         "Started %s, %.0f s. Targets met: %d, missed: %d." % (started, elapsed, met, missed), ""]
    if failures:
        L += ["**Failures:**", ""] + ["- " + f for f in failures] + [""]
    L += ["## Float lossless: every bit, against ZFP reversible (-R)", "",
          "Target: bit-exact, and at most %.1f x ZFP -R's bytes (the better orientation)."
          % TARGET_LOSSLESS, "",
          "fpzip (lossless) for comparison.", "",
          "| set | samples | brdfwave bytes | bits/sample | bit-exact | zfp -R bytes | bits/sample "
          "| zfp exact | ratio | target | fpzip bytes | bits/sample | ours / fpzip |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s, nb, z, ratio, ok, exact, zexact, fz in lossless:
        n = s.f.size
        L.append("| %s | %d | %d | %.3f | %s | %s | %s | %s | %.3f | %s | %s | %s | %s |"
                 % (s.key, n, nb, bits(nb, n), "yes" if exact else "NO",
                    z[0] if z else "-", "%.3f" % bits(z[0], n) if z else "-",
                    "yes" if zexact else "no", ratio, "met" if ok else "missed",
                    fz[0] if fz else "-", "%.3f" % bits(fz[0], n) if fz else "-",
                    "%.3f" % (nb / fz[0]) if fz else "-"))
    L += ["", "## Relative bound |x' - x| <= R |x|", "",
          "Against the same guarantee met by an absolute bound E = R x min |x| (the smallest "
          "non-zero value): brdfwave --max-error E and ZFP -a E. Target: at most %.1f x the "
          "smaller. Every sample checked; 'held' is the relative rule on every sample."
          % TARGET_RELATIVE, "",
          "| set | R | E = R min | brdfwave rel bytes (b/s) | held | max rel err | brdfwave abs "
          "bytes | zfp -a bytes (held) | ratio | target |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for s, e in relative:
        n = s.f.size
        o = e["ours"]
        a = "%d" % e["abs"][0] if e.get("abs") else \
            "refused (%s)" % e.get("abs_err", "")[:90].replace("|", "\\|")
        z = "%d (%s)" % (e["zfp"][0], "yes" if e["zfp"][2] else "NO") if e.get("zfp") else "-"
        L.append("| %s | %g | %.3g | %d (%.3f) | %s | %.3g | %s | %s | %.3f | %s |"
                 % (s.key, e["R"], e["E"], o[0], bits(o[0], n), "yes" if o[1] else "NO", o[2],
                    a, z, e["ratio"], "met" if e["ok"] else "missed"))
    L += ["", "Sets: " + "; ".join("%s: %s" % (s.key, s.desc) for s in sets), ""]
    with open(REPORT_MD, "w") as fh:
        fh.write("\n".join(L))


if __name__ == "__main__":
    sys.exit(main())
