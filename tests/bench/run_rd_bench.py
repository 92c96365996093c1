#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Rate-distortion benchmark: brdfwave against the standard codecs, with targets.

Writes build/bench/rd.md (targets met / missed, one table and one plot per data
set), build/bench/rd.csv (every row, with its command line) and
build/bench/rd_<set>.png (rate against relative L2 and against RMSE).

Data sets (directional ones at geodesic level 4):
  * the paper's synthetic sets Phong1, Phong2 (16 x 1024) and Ward (1024 x 1024),
    made with `brdfwave synth`;
  * the 60 field spectra (PSR-3500, 1024 channels), as float32 and as 16-bit
    integers round(10000 x reflectance);
  * the Spectralon set of grit-lab (71 incidence angles x 2151 bands);
  * the three RGL measured BRDFs, green channel, on the geodesic grid
    (`brdfwave import-rgl`, the file's incidence angles x 1024 outgoing).
Every set is measured twice: as float32 (rate-distortion curves; the peers that
need integers see q = round(f / s) and are scaled back by s) and as integers
(lossless and bounded error, errors in integer units).

Peers in the same run, on the same samples: CharLS JPEG-LS (lossless, NEAR 1-16),
OpenJPEG (5/3 lossless, 9/7 at several rates), ZFP (reversible, fixed accuracy),
libaec (CCSDS 121.0), xz -9e and zstd -19. 2-D peers (and the 1-D ones, whose
result depends on the sample order) run on the array and on its transpose; the
targets use the better of the two. The peer runners are those of
run_codec_bench.py (`make bench`).

Usage: /usr/bin/python3 tests/bench/run_rd_bench.py  (`make bench-rd`)
Environment: BW (default build/host/brdfwave), PEER_JPEGLS (default
build/bench/peer_jpegls), RD_SETS (comma-separated subset of the set keys),
BENCH_KEEP_TMP=1 keeps build/bench/rd_tmp.

Exit status 0, or 1 if brdfwave failed on an input or broke a guarantee
(lossless not exact, a max-error bound exceeded on some sample, a byte budget
exceeded). Missed targets are reported, not failed.
"""

import csv
import datetime
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_codec_bench as cb  # noqa: E402  (the shared peer runners)

ROOT = cb.ROOT
OUT_DIR = cb.OUT_DIR
TMP_DIR = os.path.join(OUT_DIR, "rd_tmp")
REPORT_MD = os.path.join(OUT_DIR, "rd.md")
REPORT_CSV = os.path.join(OUT_DIR, "rd.csv")

# brdfwave --ratio R (payload <= 4 n / R bytes): 0.05 .. 10 bits/sample (below the
# peers' 0.1, so that our rate at a peer's RMSE there is interpolated, not bounded)
RATIOS = [3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 320, 480, 640]
TABLE2_RATIOS = [8, 16, 64, 128, 256]
NEARS = [1, 2, 4, 8, 16]
# opj_compress -r R against the 16-bit image: 16 / R bits/sample, 0.08 .. 4
OPJ_RATES = [4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 160, 200]
ZFP_TOL_EXP = list(range(0, 19))   # zfp -a max|f| * 2^-k
RATE_RANGE = (0.1, 2.0)            # bits/sample of the lossy target

TARGET_LOSSLESS = 0.95   # x the best lossless peer
TARGET_NEAR = 0.9        # x JPEG-LS at the same NEAR
TARGET_OPJ = 0.7         # x OpenJPEG 9/7 bytes at equal RMSE
TARGET_ZFP = 0.5         # x ZFP bytes at equal RMSE
TARGET_BUDGET = 0.02     # the payload lands at most 2 % under the budget

log = cb.log


# --------------------------------------------------------------------------
# data sets

class Set:
    def __init__(self, key, title, f, layout, desc, q=None, qscale=None, qdesc=""):
        self.key = key
        self.title = title
        self.f = np.asarray(f, dtype=np.float32)   # [rows][cols]
        self.layout = layout                       # brdfwave layout arguments
        self.desc = desc
        if q is None:                              # round(f / s), s = max / 65535
            qscale = float(self.f.max()) / 65535.0
            q = np.clip(np.rint(self.f.astype(np.float64) / qscale), 0, 65535)
            qdesc = "round(f / s), s = max / 65535 = %.6g" % qscale
        self.q = np.asarray(q).astype(np.uint16)
        self.qscale = qscale
        self.qdesc = qdesc


def synth(bw, key, args):
    raw = os.path.join(TMP_DIR, "%s_synth.f32" % key)
    cb.run([bw, "synth"] + args + ["-o", raw], "brdfwave synth (%s)" % key)
    return np.fromfile(raw, dtype="<f4").reshape(-1, 1024)


def load_sets(bw, wanted):
    sets = []

    def want(k):
        return not wanted or k in wanted

    for key, args, layout, desc in cb.PAPER_SETS:
        if want(key):
            f = synth(bw, key, args)
            sets.append(Set(key, key, f, ["--bands", "1"] + layout,
                            "`brdfwave synth %s`: %s." % (" ".join(args), desc)))
    if want("field"):
        src, files, refl = cb.load_spectra()
        q = np.clip(np.rint(refl * 10000.0), 0, 65535)
        sets.append(Set("field", "Field spectra", refl, ["--bands", str(refl.shape[1])],
                        "%d PSR-3500 field spectra x %d channels (`%s`)."
                        % (refl.shape[0], refl.shape[1], cb.rel(src)),
                        q=q, qscale=1e-4, qdesc="round(10000 x reflectance)"))
    if want("spectralon"):
        a = np.loadtxt(os.path.join(ROOT, "tests/data/spectralon/BRF_normalization_factor.csv"),
                       delimiter=",")[:, 1:]
        sets.append(Set("spectralon", "Spectralon", a, ["--bands", str(a.shape[1])],
                        "Spectralon A(theta_i, lambda) of grit-lab: %d incidence angles x %d "
                        "bands (350-2500 nm), coded as %d spectra." % (a.shape + (a.shape[0],))))
    for m in ("paper_white", "satin_rosaline", "cc_ibiza_sunset"):
        key = "rgl_" + m
        if not want(key):
            continue
        raw = os.path.join(TMP_DIR, "%s.f32" % key)
        out, _ = cb.run([bw, "import-rgl", "-i",
                         os.path.join(ROOT, "tests/data/rgl/%s_rgb.bsdf" % m),
                         "-o", raw, "--level", "4", "--channel", "g"], "brdfwave import-rgl")
        nin = int([l for l in out.splitlines() if l.startswith("incoming:")][0].split()[1])
        f = np.fromfile(raw, dtype="<f4").reshape(nin, 1024)
        sets.append(Set(key, "RGL %s" % m, f,
                        ["--bands", "1", "--level", "4", "--incoming", str(nin)],
                        "RGL measured BRDF `%s_rgb.bsdf`, green channel, `brdfwave import-rgl "
                        "--level 4`: %d measured incidence angles x 1024 outgoing. %s"
                        % (m, nin, out.splitlines()[0])))
    return sets


# --------------------------------------------------------------------------
# runners

def both_orientations(b, table, fn, key, arr, to_ref):
    """Runs fn(b, table, key, a, to_ref) on arr and on its transpose; the rows
    it adds get the orientation in their setting and field `orient`."""
    for o in ("rows", "cols"):
        a = arr if o == "rows" else np.ascontiguousarray(arr.T)
        tr = to_ref if o == "rows" else (lambda d, f=to_ref: f(np.asarray(d).T))
        n0 = len(table.rows)
        fn(b, table, "%s_%s" % (key, o), a, tr)
        for r in table.rows[n0:]:
            r["setting"] += " [%s]" % o
            r["orient"] = o


def gp_u16(b, table, key, a, to_ref):
    raw = b.tmp("%s.u16" % key)
    a.astype("<u2").tofile(raw)
    cb.general_purpose(b, table, key, raw, "u16", lambda buf: to_ref(
        np.frombuffer(buf, dtype="<u2").astype(np.int64).reshape(a.shape)))


def gp_f32(b, table, key, a, to_ref):
    raw = b.tmp("%s.f32" % key)
    a.astype("<f4").tofile(raw)
    cb.general_purpose(b, table, key, raw, "f32", lambda buf: to_ref(
        np.frombuffer(buf, dtype="<f4").astype(np.float64).reshape(a.shape)))


def zfp_int(b, table, key, a, to_ref):
    """ZFP reversible on the integers (as int32)."""
    if not cb.have("zfp"):
        cb.note(b, table, "zfp", "zfp not found")
        return
    h, w = a.shape
    raw = b.tmp("%s.i32" % key)
    a.astype("<i4").tofile(raw)
    out = raw + ".zfp"
    dec = out + ".i32"
    cmd = ["zfp", "-q", "-h", "-t", "i32", "-2", str(w), str(h), "-R", "-i", raw, "-z", out]
    try:
        _, t1 = cb.run(cmd, "zfp -R -t i32")
        _, t2 = cb.run(["zfp", "-q", "-h", "-z", out, "-o", dec], "zfp decompress")
        d = np.fromfile(dec, dtype="<i4").astype(np.int64)
        if d.size != a.size:
            raise cb.ToolError("zfp: %d values back, expected %d" % (d.size, a.size))
    except cb.ToolError as e:
        b.peer_fail(table, str(e))
        return
    b.add_row(table, "zfp", "-R -t i32 (-2 %d %d)" % (w, h), "i32", cb.fsize(out),
              to_ref(d.reshape(h, w)), t1 + t2, cb.cmdline(cmd))


def tag(table, n0, **kw):
    for r in table.rows[n0:]:
        r.update(kw)


def ours(b, table, s, infile, fmt, mode, setting, check, **kw):
    n0 = len(table.rows)
    b.bw_row(table, cb.DataSet(s.key, s.title, s.f, s.layout, ""), infile, fmt, mode, setting,
             check, **kw)
    return table.rows[n0] if len(table.rows) > n0 else None


def run_set(b, s):
    tables = {}
    n = s.f.size
    # ---- float: rate-distortion
    tf = cb.Table(s.key, "%s, float32 (%d x %d)" % (s.title, s.f.shape[0], s.f.shape[1]),
                  s.f.astype(np.float64),
                  "%s Values %.6g .. %.6g; %d samples. Errors in value units. Integer peers "
                  "saw q = %s and are scaled back." % (s.desc, float(s.f.min()),
                                                      float(s.f.max()), n, s.qdesc))
    log("== %s" % tf.title)
    raw = b.tmp("%s.f32" % s.key)
    s.f.astype("<f4").tofile(raw)
    for R in RATIOS:
        r = ours(b, tf, s, raw, "f32", ["--ratio", str(R)], "--ratio %d" % R, ("ratio", R))
        if r:
            r.update(kind="ratio", R=R, budget=int(math.floor(4.0 * n / R)))
    if float(s.f.min()) > 0:   # relative accuracy: log(values) coded
        for R in RATIOS:
            r = ours(b, tf, s, raw, "f32", ["--ratio", str(R), "--relative"],
                     "--ratio %d --relative" % R, ("ratio", R))
            if r:
                r.update(kind="ratio_rel", R=R, budget=int(math.floor(4.0 * n / R)))
    back = lambda d, sc=s.qscale: np.asarray(d, dtype=np.float64) * sc
    n0 = len(tf.rows)
    cb.openjpeg_u16(b, tf, s.key, s.q, back, rates=OPJ_RATES)
    tag(tf, n0, orient=None)
    fmax = float(np.max(np.abs(s.f)))
    tols = [fmax * 2.0 ** -k for k in ZFP_TOL_EXP]
    both_orientations(b, tf, lambda b_, t, k, a, tr: cb.zfp_f32(
        b_, t, k, a, ["-2", str(a.shape[1]), str(a.shape[0])], tols, tr), s.key, s.f, lambda d: d)
    both_orientations(b, tf, lambda b_, t, k, a, tr: cb.jpegls_u16(b_, t, k, a, tr, NEARS),
                      s.key + "_q", s.q, back)
    both_orientations(b, tf, gp_f32, s.key, s.f, lambda d: d)
    tables["f"] = tf

    # ---- integers: lossless and bounded error
    ti = cb.Table(s.key + "_int", "%s, integers q = %s (%d x %d)"
                  % (s.title, s.qdesc, s.q.shape[0], s.q.shape[1]),
                  s.q.astype(np.float64),
                  "The integers q (max %d). Errors in integer units; every bound is checked "
                  "on every sample of brdfwave's int32 output." % int(s.q.max()))
    log("== %s" % ti.title)
    rawq = b.tmp("%s.u16" % s.key)
    s.q.astype("<u2").tofile(rawq)
    qref = s.q.astype(np.float64)
    r = ours(b, ti, s, rawq, "u16", ["--lossless"], "--lossless", ("lossless", 0),
             native_ref=qref, native_i32=True)
    if r:
        r.update(kind="lossless")
    for E in NEARS:
        r = ours(b, ti, s, rawq, "u16", ["--max-error", str(E)], "--max-error %d" % E,
                 ("max_error", E), native_ref=qref, native_i32=True)
        if r:
            r.update(kind="maxerr", E=E)
    ident = lambda d: np.asarray(d, dtype=np.float64)
    both_orientations(b, ti, lambda b_, t, k, a, tr: cb.jpegls_u16(b_, t, k, a, tr, NEARS),
                      s.key, s.q, ident)
    n0 = len(ti.rows)
    cb.openjpeg_u16(b, ti, s.key + "_int", s.q, ident, rates=[])
    tag(ti, n0, orient=None)
    both_orientations(b, ti, cb.libaec_u16, s.key, s.q, ident)
    both_orientations(b, ti, zfp_int, s.key, s.q, ident)
    both_orientations(b, ti, gp_u16, s.key, s.q, ident)
    tables["i"] = ti
    return tables


# --------------------------------------------------------------------------
# targets

class Verdicts:
    def __init__(self):
        self.rows = []   # (target, set, point, ours, reference, limit, value, met, note)

    def add(self, target, dset, point, ours_s, ref_s, limit_s, value, limit, note=""):
        met = value is not None and value <= limit + 1e-12
        if value is None:
            verdict = "n/a"
        elif met:
            verdict = "met"
        else:
            verdict = "missed by %.1f %%" % (100.0 * (value / limit - 1.0))
        self.rows.append((target, dset, point, ours_s, ref_s, limit_s,
                          "-" if value is None else "%.3f" % value, verdict, note))

    def count(self):
        met = sum(1 for r in self.rows if r[7] == "met")
        missed = sum(1 for r in self.rows if r[7].startswith("missed"))
        return met, missed


def peer_rows(t, codec, pred=lambda r: True):
    return [r for r in t.rows if r["codec"] == codec and pred(r)]


def is_lossless(r):
    return r["max_abs_err"] == 0.0


def ours_curve(t):
    """(bits, rmse, relL2) of brdfwave's --ratio rows, lower hull in rmse by bits."""
    pts = sorted((r["bits_per_sample"], r["rmse"], r["rel_l2_pct"]) for r in t.rows
                 if r["codec"] == "brdfwave" and r.get("kind") == "ratio" and r["rmse"] > 0)
    hull = []
    for p in pts:   # keep points whose rmse is below every cheaper point's
        if not hull or p[1] < hull[-1][1]:
            hull.append(p)
    return hull


def bits_at(curve, rmse):
    """Our bits/sample at this RMSE, log-log interpolation; None outside. An
    RMSE above our coarsest point gets that point's rate (an upper bound)."""
    if curve and rmse >= curve[0][1]:
        return curve[0][0]
    if len(curve) < 2:
        return None
    for (b0, e0, _), (b1, e1, _) in zip(curve, curve[1:]):
        if e1 <= rmse <= e0 and e0 > e1:
            w = (math.log(e0) - math.log(rmse)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(b0) + w * (math.log(b1) - math.log(b0)))
    return None


def base_setting(r):
    s = r["setting"]
    for o in (" [rows]", " [cols]"):
        s = s.replace(o, "")
    return s


def exact_bytes(tf, kind):
    """The smallest exact coding of the input that budget rows of this kind
    (ratio or ratio_rel) made, if any did."""
    sizes = [r["bytes"] for r in tf.rows if r["codec"] == "brdfwave" and
             r.get("kind") == kind and "step=1.0000" in r["notes"]]
    return min(sizes) if sizes else None


def next_payload(r):
    """For a budget row: the smallest payload above ours that the encoder
    makes from a larger budget (same command, --bytes instead of --ratio),
    and the smallest budget that gives it; None if none within 64 x."""
    argv = r["cmd"].split()
    i = argv.index("--ratio")
    del argv[i:i + 2]
    o = argv.index("-o")
    out = argv[o + 1] + ".next"
    argv[o + 1] = out
    ours = r["bytes"]

    def size(b):
        cb.run(argv + ["--bytes", str(b)], "brdfwave encode (next payload size)")
        return os.path.getsize(out)

    lo, hi, step = r["budget"], r["budget"], max(1, r["budget"] // 64)
    while True:
        s = size(hi)
        if s > ours:
            break
        lo, hi, step = hi, hi + step, 2 * step
        if hi > 64 * r["budget"]:
            return None
    while hi - lo > 1:
        mid = (lo + hi) // 2
        m = size(mid)
        if m > ours:
            hi, s = mid, m
        else:
            lo = mid
    return s, hi


def evaluate(v, sets_tables, paper):
    for key, tabs in sets_tables:
        tf, ti = tabs["f"], tabs["i"]
        # Table 2
        if key in ("Phong1", "Phong2", "Ward") and paper:
            for R in TABLE2_RATIOS:
                cand = [r for r in tf.rows if r["codec"] == "brdfwave" and r.get("R") == R]
                r = min(cand, key=lambda r: r["rel_l2_pct"]) if cand else None
                pv = paper.get(R, {}).get(key)
                if r is None or pv is None:
                    continue
                lim = float(pv[1]) / 2.0
                v.add("Table 2: rel L2 <= paper / 2", key, "%d:1" % R,
                      "%.4g %% (%.3g b/s, %s)" % (r["rel_l2_pct"], r["bits_per_sample"],
                                                 r["setting"]),
                      "paper %s %%" % pv[1], "%.4g %%" % lim, r["rel_l2_pct"] / lim, 1.0)
        # lossless
        r = next((r for r in ti.rows if r["codec"] == "brdfwave" and r.get("kind") == "lossless"),
                 None)
        peers = [p for p in ti.rows if p["codec"] != "brdfwave" and is_lossless(p)]
        if r is not None and peers:
            p = min(peers, key=lambda p: p["bits_per_sample"])
            v.add("lossless <= 0.95 x best lossless peer", key, "integers",
                  "%.4g b/s" % r["bits_per_sample"],
                  "%s %s: %.4g b/s" % (p["codec"], p["setting"], p["bits_per_sample"]),
                  "0.95", r["bits_per_sample"] / p["bits_per_sample"], TARGET_LOSSLESS)
        # bounded error
        for E in NEARS:
            r = next((r for r in ti.rows if r["codec"] == "brdfwave" and r.get("E") == E), None)
            js = [p for p in ti.rows if p["codec"] == "JPEG-LS"
                  and base_setting(p).startswith("NEAR=%d " % E)]
            if r is None or not js:
                continue
            p = min(js, key=lambda p: p["bits_per_sample"])
            v.add("max error E: <= 0.9 x JPEG-LS NEAR=E", key, "E = %d" % E,
                  "%.4g b/s (max err %g)" % (r["bits_per_sample"], r["max_abs_err_native"]),
                  "%s: %.4g b/s" % (p["setting"], p["bits_per_sample"]), "0.9",
                  r["bits_per_sample"] / p["bits_per_sample"], TARGET_NEAR)
        # lossy at equal RMSE
        curve = ours_curve(tf)
        for codec, pred, lim in (("OpenJPEG", lambda r: r["setting"].startswith("9/7"),
                                  TARGET_OPJ),
                                 ("zfp", lambda r: r["setting"].startswith("-a"), TARGET_ZFP)):
            worst = {}   # base setting -> (ratio, peer row, our bits); worse orientation kept
            outside = 0
            for p in peer_rows(tf, codec, pred):
                if not (RATE_RANGE[0] <= p["bits_per_sample"] <= RATE_RANGE[1]):
                    continue
                ob = bits_at(curve, p["rmse"])
                if ob is None:
                    outside += 1
                    continue
                q = ob / p["bits_per_sample"]
                k = base_setting(p)
                if k not in worst or q > worst[k][0]:
                    worst[k] = (q, p, ob)
            if not worst:
                v.add("lossy: <= %.1f x %s bytes at equal RMSE" % (lim, codec), key,
                      "0.1-2 b/s", "-", "no %s point in range with an RMSE we measured" % codec,
                      "%.1f" % lim, None, lim)
                continue
            q, p, ob = max(worst.values(), key=lambda w: w[0])
            note = "worst of %d %s points in 0.1-2 b/s" % (len(worst), codec)
            if outside:
                note += "; %d outside our measured RMSE range" % outside
            v.add("lossy: <= %.1f x %s bytes at equal RMSE" % (lim, codec), key,
                  "RMSE %.3g" % p["rmse"], "%.4g b/s" % ob,
                  "%s %s: %.4g b/s" % (codec, p["setting"], p["bits_per_sample"]),
                  "%.1f" % lim, q, lim, note)
        # byte budget
        under = []
        exact = 0
        for r in tf.rows:
            if r["codec"] != "brdfwave" or r.get("kind") not in ("ratio", "ratio_rel"):
                continue
            if "step=1.0000" in r["notes"]:
                exact += 1      # the exact coding fits: nothing to spend the rest on
                continue
            under.append(((r["budget"] - r["bytes"]) / r["budget"], r))
        if under:
            u, r = max(under, key=lambda x: x[0])
            over = [x for x in under if x[0] < 0]
            note = "%d budgets" % len(under)
            if exact:
                note += "; %d more where the exact coding fits under the budget" % exact
            if over:
                note += "; %d OVER budget" % len(over)
            if u > TARGET_BUDGET:
                nxt = next_payload(r)
                if nxt:
                    note += ("; the next larger payload the encoder makes is %d B (%s from a "
                             "budget of %d B)" % (nxt[0], "the exact coding" if nxt[0] ==
                                                  exact_bytes(tf, r.get("kind")) else "lossy", nxt[1]))
            v.add("byte budget: <= 2 % under, never over", key, r["setting"],
                  "%d B" % r["bytes"], "budget %d B" % r["budget"], "2 %",
                  max(u, 0.0) / TARGET_BUDGET if not over else float("inf"), 1.0, note)


# --------------------------------------------------------------------------
# plots and report

def plot(tabs, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    tf = tabs["f"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    series = [("brdfwave", lambda r: r.get("kind") == "ratio", "k", "o", "-"),
              ("brdfwave --relative", lambda r: r.get("kind") == "ratio_rel", "tab:red", "D",
               "-")]
    for o, ls in (("rows", "-"), ("cols", "--")):
        series += [
            ("OpenJPEG", lambda r, o=o: r["setting"].startswith("9/7")
             and r["setting"].endswith("[%s]" % o), "tab:blue", "s", ls),
            ("zfp", lambda r, o=o: r["setting"].startswith("-a") and r.get("orient") == o,
             "tab:orange", "^", ls),
            ("JPEG-LS", lambda r, o=o: "NEAR" in r["setting"] and r.get("orient") == o,
             "tab:green", "v", ls),
        ]
    for ax, metric, label in ((axes[0], "rel_l2_pct", "relative L2 error (%)"),
                              (axes[1], "rmse", "RMSE (value units)")):
        for codec, pred, col, mk, ls in series:
            pts = sorted((r["bits_per_sample"], r[metric]) for r in tf.rows
                         if r["codec"] == codec.split()[0] and pred(r) and r[metric] > 0
                         and np.isfinite(r[metric]))
            if not pts:
                continue
            orient = ""
            if not codec.startswith("brdfwave"):
                orient = " (cols)" if ls == "--" else " (rows)"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], ls, color=col, marker=mk,
                    ms=4, lw=2 if codec.startswith("brdfwave") else 1.2,
                    label=codec + orient)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("bits per sample (payload)")
        ax.set_ylabel(label)
        ax.axvspan(RATE_RANGE[0], RATE_RANGE[1], color="0.9", zorder=0)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle(tf.title)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return True


def write_report(b, sets_tables, v, started, elapsed, plots):
    os.makedirs(OUT_DIR, exist_ok=True)
    fields = ["dataset", "codec", "setting", "input", "samples", "bytes", "bits_per_sample",
              "ratio_vs_f32", "max_abs_err", "max_abs_err_native", "rmse", "rel_l1_pct",
              "rel_l2_pct", "skipped_zero", "seconds", "notes", "cmd"]
    with open(REPORT_CSV, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        wr.writeheader()
        for _, tabs in sets_tables:
            for t in (tabs["f"], tabs["i"]):
                for r in t.rows:
                    wr.writerow(r)
    met, missed = v.count()
    L = ["# Rate-distortion benchmark: brdfwave against the standard codecs", ""]
    L.append("Rerun with `make bench-rd` (`tests/bench/run_rd_bench.py`). Generated %s in %.0f s; "
             "every number below was measured in that run (`build/bench/rd.csv` has each row "
             "with its command line)." % (started, elapsed))
    L.append("")
    L.append("Rate = payload bytes (brdfwave: header, strip map, values and CRC; peers: their "
             "whole output file) x 8 / samples. Ratios R:1 are bytes against float32 "
             "(4 bytes per sample). Distortion against the original values: relative L1 "
             "and L2 (paper eq. 7-8, over samples != 0), RMSE, max absolute error. Integer "
             "peers see q = round(f / s) and are scaled back by s; in the integer tables "
             "errors are in integer units and every brdfwave bound is checked on every "
             "sample of its int32 output. 1-D and 2-D peers run on the array and its "
             "transpose (`[rows]` / `[cols]`); the targets take the orientation better for "
             "the peer. brdfwave runs each budget twice on positive data: `--ratio R` "
             "(absolute error) and `--ratio R --relative` (the logarithm of the values is "
             "coded, so the budget buys relative error); Table 2 takes the one with the smaller "
             "relative L2, the equal-RMSE targets use the plain curve, interpolated log-log "
             "between its points (a peer point with a larger RMSE than our coarsest point is "
             "compared with that point's rate, an upper bound of ours).")
    L.append("")
    if b.cli_failures or b.violations:
        L.append("## GUARANTEES BROKEN OR brdfwave FAILED")
        L.append("")
        for m in b.cli_failures:
            L.append("- FAILED: %s" % m)
        for m in b.violations:
            L.append("- BROKEN: %s" % m)
        L.append("")
    else:
        L.append("Guarantees: every lossless row exact, every --max-error bound held on every "
                 "sample, no payload over its budget (checked in this run).")
        L.append("")
    L.append("## Targets: %d met, %d missed" % (met, missed))
    L.append("")
    L.append("`value` is ours / reference (the target holds when value <= 1 for Table 2 and the "
             "byte budget, <= limit for the others; budget value = worst shortfall / 2 %).")
    L.append("")
    L.append("| target | data set | point | ours | reference | limit | value | verdict | note |")
    L.append("|---|---|---|---|---|---|---:|---|---|")
    for row in v.rows:
        L.append("| " + " | ".join(str(c).replace("|", "\\|") for c in row) + " |")
    L.append("")
    if b.peer_missing or b.peer_failures:
        L.append("## Peers skipped or failed")
        L.append("")
        for m in b.peer_missing:
            L.append("- missing: %s" % m)
        for m in b.peer_failures:
            L.append("- failed: %s" % m)
        L.append("")
    L.append("## Tool versions")
    L.append("")
    L.append("| package | version |")
    L.append("|---|---|")
    for k, val in cb.tool_versions(b.bw):
        L.append("| %s | %s |" % (k, val))
    L.append("")
    for key, tabs in sets_tables:
        L.append("## %s" % tabs["f"].title.split(",")[0])
        L.append("")
        if key in plots:
            L.append("![%s](%s)" % (key, os.path.basename(plots[key])))
            L.append("")
        for t in (tabs["f"], tabs["i"]):
            L.append("### %s" % t.title)
            L.append("")
            L.append(t.desc)
            L.append("")
            L.extend(cb.md_table(t) if t.rows else ["(no rows)"])
            for m in t.notes:
                L.append("")
                L.append("Note: %s" % m)
            L.append("")
    with open(REPORT_MD, "w") as f:
        f.write("\n".join(L) + "\n")


def main():
    bw = os.path.abspath(os.environ.get("BW", os.path.join(ROOT, "build", "host", "brdfwave")))
    cb.PEER_JPEGLS = os.path.abspath(os.environ.get("PEER_JPEGLS",
                                                    os.path.join(OUT_DIR, "peer_jpegls")))
    cb.TMP_DIR = TMP_DIR
    if not (os.path.isfile(bw) and os.access(bw, os.X_OK)):
        log("run_rd_bench: brdfwave CLI not found at %s (run `make`)" % bw)
        return 2
    wanted = [k for k in os.environ.get("RD_SETS", "").split(",") if k]
    t0 = time.perf_counter()
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
    shutil.rmtree(TMP_DIR, ignore_errors=True)
    os.makedirs(TMP_DIR)
    b = cb.Bench(bw)
    try:
        sets = load_sets(bw, wanted)
    except cb.ToolError as e:
        log("run_rd_bench: " + str(e))
        return 1
    sets_tables = []
    for s in sets:
        sets_tables.append((s.key, run_set(b, s)))
    v = Verdicts()
    evaluate(v, sets_tables, cb.paper_table2())
    plots = {}
    for key, tabs in sets_tables:
        p = os.path.join(OUT_DIR, "rd_%s.png" % key)
        if plot(tabs, p):
            plots[key] = p
    if not plots:
        log("run_rd_bench: matplotlib missing: no plots (tests/deps.sh bench installs it)")
    elapsed = time.perf_counter() - t0
    write_report(b, sets_tables, v, started, elapsed, plots)
    met, missed = v.count()
    log("wrote %s (%d targets met, %d missed; %.0f s)" % (cb.rel(REPORT_MD), met, missed, elapsed))
    if os.environ.get("BENCH_KEEP_TMP", "") in ("", "0"):
        shutil.rmtree(TMP_DIR, ignore_errors=True)
    if b.cli_failures or b.violations:
        log("run_rd_bench: %d brdfwave failure(s), %d broken guarantee(s); see the report"
            % (len(b.cli_failures), len(b.violations)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
