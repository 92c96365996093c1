# SPDX-License-Identifier: BSD-2-Clause
"""Payloads in segments (docs/FORMAT.md, Segments): what they cost, and what a
lost part of a payload costs (make bench-progressive).

For each set and mode, with the host's defaults:
- bytes: the payload in 1 (no segments), 4, 16 and 64 segments;
- loss: the payload in 16 segments, each segment lost in turn (its bytes
  zeroed), then each 1 KiB chunk lost in turn (zeroed): `brdfwave decode`
  writes what is left with its mask; every sample the mask marks exact must
  equal the whole payload's (else the row says so), and the share of samples
  affected (approximate or missing) is set against the share of bytes lost.
- one incoming direction (one spectrum) decoded alone against the whole
  decode, on the host, in the same run;
- on the device: the level-4 x 81-band reflectance encoded by the emulated
  board's streaming encoder (`encode --device qemu --stream`), without and
  with segments: instructions per sample (QEMU -icount), bytes, and the
  streaming encoder's RAM (its context in the firmware image, and the
  caller's memory BW_STREAM_MEM_BOUND).
Writes build/bench/progressive.md and progressive.csv. Environment: BW (the
brdfwave CLI), BENCH_DIR, FIRMWARE (build/qemu/brdfwave-fw.elf).
"""
import csv
import glob
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BW = os.environ.get("BW", os.path.join(ROOT, "build/host/brdfwave"))
OUT = os.environ.get("BENCH_DIR", os.path.join(ROOT, "build/bench"))
TMP = tempfile.mkdtemp(prefix="bw_prog_")
SEGMENTS = (1, 4, 16, 64)
LOSS_SEGMENTS = 16
CHUNK = 1024


def run(args, ok=(0,)):
    r = subprocess.run([BW] + args, capture_output=True)
    if r.returncode not in ok:
        sys.exit("bench-progressive: brdfwave %s: exit %d: %s"
                 % (" ".join(args), r.returncode, r.stderr.decode().strip()))
    return r


def tmp(name):
    return os.path.join(TMP, name)


def best_of(fn, k=5):
    """The least time of k calls of fn, and what the last call returned."""
    best, got = None, None
    for _ in range(k):
        t0 = time.perf_counter()
        got = fn()
        t = time.perf_counter() - t0
        best = t if best is None else min(best, t)
    return best, got


def sets():
    """(key, description, encode input arguments)"""
    out = []
    sed = sorted(glob.glob(os.path.join(ROOT, "tests/data/field_psr3500/*.sed")))
    args = []
    for p in sed:
        args += ["-i", p]
    out.append(("field", "%d PSR-3500 field spectra (.sed) x 1024 bands" % len(sed),
                args + ["--input-format", "sed"], ["--max-error", "0.001"]))
    a = np.loadtxt(os.path.join(ROOT, "tests/data/spectralon/BRF_normalization_factor.csv"),
                   delimiter=",")[:, 1:]
    a.astype("<f4").tofile(tmp("spectralon.f32"))
    out.append(("spectralon", "Spectralon A(theta_i, lambda): %d incidences x %d bands, as "
                "spectra" % a.shape, ["-i", tmp("spectralon.f32"), "--bands", str(a.shape[1])],
                ["--max-error", "0.0005"]))
    run(["synth", "--model", "phong", "--kd", "0.75", "--ks", "0.25", "--n", "20", "--level", "4",
         "--incoming", "16", "-o", tmp("phong.f32")])
    out.append(("phong", "Phong kd 0.75 ks 0.25 n 20, 16 incoming x 1024 outgoing",
                ["-i", tmp("phong.f32"), "--bands", "1", "--level", "4", "--incoming", "16"],
                ["--max-error", "0.001"]))
    run(["synth", "--model", "ward", "--ax", "0.35", "--ay", "0.05", "--kd", "0.75", "--ks",
         "0.25", "--level", "4", "--level-in", "4", "-o", tmp("ward.f32")])
    out.append(("ward", "Ward ax 0.35 ay 0.05, 1024 incoming x 1024 outgoing (full BRDF)",
                ["-i", tmp("ward.f32"), "--bands", "1", "--level", "4", "--level-in", "4"],
                ["--max-error", "0.001"]))
    g = run(["grid", "--level", "4"]).stdout.decode().splitlines()[1:]
    z = np.array([float(l.split(",")[5]) for l in g])
    wl = np.linspace(0, 1, 81)
    refl = (0.2 + 0.5 * z[:, None] * (0.6 + 0.4 * np.sin(6 * wl[None, :])) +
            0.05 * z[:, None] ** 8)
    refl.astype("<f4").tofile(tmp("refl81.f32"))
    out.append(("refl81", "a reflectance at level 4 (1024 directions) x 81 bands",
                ["-i", tmp("refl81.f32"), "--bands", "81", "--level", "4"],
                ["--max-error", "0.0005"]))
    return out


def decode_i32(payload, mask=None):
    out = tmp("d.i32")
    args = ["decode", "-i", payload, "-o", out, "--output-format", "i32"]
    if mask:
        args += ["--mask", mask]
    r = run(args, ok=(0, 1, 3))
    if r.returncode == 1:
        return None, None, r.stderr.decode().strip()
    m = np.fromfile(mask, np.uint8) if mask else None
    return np.fromfile(out, "<i4"), m, ""


def loss_rows(key, mode, payload):
    """Each segment, then each 1 KiB chunk, lost in turn."""
    data = open(payload, "rb").read()
    ref, _, _ = decode_i32(payload)
    info = run(["info", payload]).stdout.decode().splitlines()
    kv = dict(l.split(": ", 1) for l in info if ": " in l)
    segs = int(kv["segments"])
    hl = int(kv["segment_table_offset"])
    lens = [int(x) for x in kv["segment_bytes"].split(",")]
    starts = np.cumsum([hl + 8 * segs + 4] + lens[:-1])
    rows = []
    for what, spans in (("segment", [(int(s), int(s) + l) for s, l in zip(starts, lens)]),
                        ("1 KiB chunk", [(c, min(c + CHUNK, len(data)))
                                         for c in range(0, len(data), CHUNK)])):
        shares, byte_shares, exact_ok, whole_lost, t0 = [], [], True, 0, time.time()
        for a, b in spans:
            if b <= a:
                continue
            q = bytearray(data)
            q[a:b] = bytes(b - a)
            p = tmp("lost.bwv")
            open(p, "wb").write(q)
            got, m, err = decode_i32(p, tmp("lost.mask"))
            byte_shares.append((b - a) / len(data))
            if got is None:  # header or table hit: the payload is lost whole
                whole_lost += 1
                shares.append(1.0)
                continue
            if not np.array_equal(got[m == 0], ref[m == 0]):
                exact_ok = False
            shares.append(float(np.mean(m != 0)))
        shares, byte_shares = np.array(shares), np.array(byte_shares)
        rows.append({"set": key, "mode": mode, "segments": segs, "lost": what,
                     "cases": len(shares), "bytes_lost_mean_pct": 100 * byte_shares.mean(),
                     "samples_affected_mean_pct": 100 * shares.mean(),
                     "samples_affected_max_pct": 100 * shares.max(),
                     "lost_whole": whole_lost, "exact_elsewhere": "yes" if exact_ok else "NO",
                     "seconds": time.time() - t0})
    return rows


def partial_rows():
    """One incoming direction (one spectrum) decoded alone against the whole
    decode, through the library (the Python package's ctypes calls), in this
    run: the best of 5 whole decodes against the mean over rows spread over
    the measurement; each row checked against the whole decode's."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import Dims, Header, free, lib
    L = lib()
    cases = [("ward", "no symmetry step, 1024 segments (one incoming block each)",
              ["--symmetry", "none", "--segments", "1024", "--max-error", "0.001"]),
             ("ward", "mirror, 1024 segments (one incoming block each)",
              ["--symmetry", "mirror", "--segments", "1024", "--max-error", "0.001"]),
             ("ward", "mirror, one body", ["--symmetry", "mirror", "--max-error", "0.001"]),
             ("field", "lossless, 60 segments (a spectrum each)", ["--lossless", "--segments",
                                                                   "60"]),
             ("field", "lossless, one body", ["--lossless"])]
    inputs = {k: inp for k, _, inp, _ in sets()}
    rows = []
    for key, what, args in cases:
        pth = tmp("part_%s_%d.bwv" % (key, len(rows)))
        run(["encode", "-q"] + inputs[key] + args + ["-o", pth])
        p = open(pth, "rb").read()

        def whole():
            h, v = Header(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_limit(p, len(p), 0, ctypes.byref(h), None, ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: whole decode failed")
            n = h.dims.n_in * h.dims.n_out * h.dims.bands
            a = np.ctypeslib.as_array(v, shape=(n,)).copy()
            free(v)
            return a, h

        def one(k):
            h, d, v = Header(), Dims(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_incoming(p, len(p), k, ctypes.byref(h), ctypes.byref(d), None,
                                     ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: decode of row %d failed" % k)
            a = np.ctypeslib.as_array(v, shape=(d.n_out * d.bands,)).copy()
            free(v)
            return a

        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            ref, h = whole()
            times.append(time.perf_counter() - t0)
        n_in, row = h.dims.n_in, h.dims.n_out * h.dims.bands
        ks = list(range(0, n_in, max(1, n_in // 64)))
        t0 = time.perf_counter()
        got = [one(k) for k in ks]
        per = (time.perf_counter() - t0) / len(ks)
        same = all(np.array_equal(g, ref[k * row:(k + 1) * row]) for k, g in zip(ks, got))
        rows.append({"set": key, "payload": what, "bytes": len(p), "rows": len(ks),
                     "whole_ms": 1e3 * min(times), "row_ms": 1e3 * per,
                     "ratio": min(times) / per, "same": "yes" if same else "NO"})
    return rows


def region_rows():
    """A region of the Ward set's incoming hemisphere (bwh_region_rows, then
    bwh_decode_rows) against the whole decode and against decoding its rows
    one at a time, through the library, in this run (best of 5 each); each
    region's rows checked against the whole decode's."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import Dims, Header, free, lib
    L = lib()
    inputs = {k: inp for k, _, inp, _ in sets()}
    out = []
    for what, args in (("no symmetry step, 1024 segments", ["--symmetry", "none"]),
                       ("mirror, 1024 segments", ["--symmetry", "mirror"])):
        pth = tmp("region_%d.bwv" % len(out))
        run(["encode", "-q"] + inputs["ward"] + args +
            ["--segments", "1024", "--max-error", "0.001", "-o", pth])
        p = open(pth, "rb").read()

        def whole():
            h, v = Header(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_limit(p, len(p), 0, ctypes.byref(h), None, ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: whole decode failed")
            a = np.ctypeslib.as_array(v, shape=(h.dims.n_in * h.dims.n_out,)).copy()
            free(v)
            return a.reshape(h.dims.n_in, h.dims.n_out), h

        tw, (ref, hw) = best_of(whole)
        for theta, phi, radius in ((30, 0, 5), (30, 0, 10), (30, 0, 20), (45, 60, 45)):
            marks = np.zeros(hw.dims.n_in, dtype=np.uint8)

            def region():
                h, d, v = Header(), Dims(), ctypes.POINTER(ctypes.c_float)()
                if (L.bwh_region_rows(ctypes.byref(hw), None, theta, phi, radius,
                                      marks.ctypes.data) <= 0 or
                        L.bwh_decode_rows(p, len(p), marks.ctypes.data, ctypes.byref(h),
                                          ctypes.byref(d), None, ctypes.byref(v)) != 0):
                    sys.exit("bench-progressive: region decode failed")
                a = np.ctypeslib.as_array(v, shape=(d.n_in * d.n_out,)).copy()
                free(v)
                return a.reshape(d.n_in, d.n_out)

            def one_by_one():
                rows = []
                for k in np.flatnonzero(marks):
                    h, d, v = Header(), Dims(), ctypes.POINTER(ctypes.c_float)()
                    if L.bwh_decode_incoming(p, len(p), int(k), ctypes.byref(h), ctypes.byref(d),
                                             None, ctypes.byref(v)) != 0:
                        sys.exit("bench-progressive: decode of row %d failed" % k)
                    rows.append(np.ctypeslib.as_array(v, shape=(d.n_out,)).copy())
                    free(v)
                return rows

            tr, got = best_of(region)
            to, _ = best_of(one_by_one)
            idx = np.flatnonzero(marks)
            out.append({"payload": what, "bytes": len(p),
                        "region": "(%g, %g), %g deg" % (theta, phi, radius), "rows": len(idx),
                        "whole_ms": 1e3 * tw, "region_ms": 1e3 * tr, "ratio": tw / tr,
                        "one_ms": 1e3 * to, "same": "yes" if np.array_equal(got, ref[idx])
                        else "NO"})
    return out


def eval_rows():
    """f(wi, wo) at random direction pairs of the Ward set (mirror, 1024
    segments) straight from the payload (bwh_payload_eval: the incoming
    rows the pairs read) against decoding it all and evaluating
    (bwh_brdf_data_from_payload of every row, bwh_brdf_data_eval_many), the
    best of 3 each, in this run; *same*: the values equal bit for bit."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import lib
    L = lib()
    L.bwh_abi_size.restype = ctypes.c_size_t
    L.bwh_abi_size.argtypes = [ctypes.c_char_p]
    size = L.bwh_abi_size(b"bwh_brdf_data_t")
    L.bwh_brdf_data_from_payload.restype = ctypes.c_int
    L.bwh_brdf_data_from_payload.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                             ctypes.c_void_p, ctypes.c_size_t]
    L.bwh_brdf_data_eval_many.restype = ctypes.c_int
    L.bwh_brdf_data_eval_many.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p,
                                          ctypes.c_void_p, ctypes.c_void_p, ctypes.c_long,
                                          ctypes.c_void_p]
    L.bwh_brdf_data_free.argtypes = [ctypes.c_void_p]
    inputs = {k: inp for k, _, inp, _ in sets()}
    pth = tmp("eval_ward.bwv")
    run(["encode", "-q"] + inputs["ward"] + ["--symmetry", "mirror", "--max-error", "0.001",
                                             "--segments", "1024", "-o", pth])
    p = open(pth, "rb").read()
    rng = np.random.default_rng(7)
    out = []
    for n in (10, 1000, 100000):
        def hemi():
            v = rng.normal(size=(n, 3))
            v[:, 2] = np.abs(v[:, 2])
            return np.ascontiguousarray(v / np.linalg.norm(v, axis=1)[:, None])
        wi, wo = hemi(), hemi()
        a, b = np.empty(n), np.empty(n)

        def from_payload():
            if L.bwh_payload_eval(p, len(p), n, wi.ctypes.data, wo.ctypes.data, None, -1,
                                  a.ctypes.data) != 0:
                sys.exit("bench-progressive: bwh_payload_eval failed")

        def whole():
            d = ctypes.create_string_buffer(size)
            if (L.bwh_brdf_data_from_payload(d, p, len(p), None, 0) != 0 or
                    L.bwh_brdf_data_eval_many(d, n, wi.ctypes.data, wo.ctypes.data, None, -1,
                                              b.ctypes.data) != 0):
                sys.exit("bench-progressive: whole decode and evaluation failed")
            L.bwh_brdf_data_free(d)

        tp, tw = best_of(from_payload, 3)[0], best_of(whole, 3)[0]
        g = run(["grid", "--level", "4"]).stdout.decode().splitlines()[1:]
        c = np.array([[float(x) for x in l.split(",")[3:6]] for l in g])
        rows = len(np.unique(np.argmax(wi @ c.T, axis=1)))
        out.append({"pairs": n, "rows": rows, "payload_ms": 1e3 * tp, "whole_ms": 1e3 * tw,
                    "ratio": tw / tp, "same": "yes" if np.array_equal(a, b, equal_nan=True)
                    else "NO", "bytes": len(p)})
    return out


def band_rows():
    """One band of the Spectralon set (71 spectra x 2,151 bands, lossless)
    against the whole decode of the same payload, float values out, the
    best of 7 each, in this run: the host's payload (`encode --lossless`),
    whose `decode --bands K` decodes it whole then keeps the band
    (bwh_decode_bands), and the payload with band access (`encode
    --lossless --band-access`), whose band decodes from the columns it
    depends on (bwh_decode_bands, bw_decode_band_range); *same*: the band
    equals that band of the whole decode."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import Dims, Header, free, lib
    L = lib()
    inputs = {k: inp for k, _, inp, _ in sets()}
    out = []
    for key, extra in (("range", []), ("band access", ["--band-access"])):
        pth = tmp("band_spectralon_%s.bwv" % key.replace(" ", "_"))
        run(["encode", "-q"] + inputs["spectralon"] + ["--lossless"] + extra + ["-o", pth])
        p = open(pth, "rb").read()

        def whole():
            h, v = Header(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_limit(p, len(p), 0, ctypes.byref(h), None, ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: decode of the Spectralon payload failed")
            d = h.dims
            a = np.ctypeslib.as_array(v, shape=(d.n_in * d.n_out * d.bands,)).copy()
            free(v)
            return a.reshape(d.n_in * d.n_out, d.bands)

        def band(k):
            h, s, v = Header(), Dims(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_bands(p, len(p), k, k + 1, ctypes.byref(h), ctypes.byref(s), None,
                                  ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: bwh_decode_bands failed")
            a = np.ctypeslib.as_array(v, shape=(s.n_in * s.n_out * s.bands,)).copy()
            free(v)
            return a

        tw, ref = best_of(whole, 7)
        for k in (0, 1075, 2150):
            tb, got = best_of(lambda: band(k), 7)
            out.append({"payload": key, "band": k, "bands": ref.shape[1], "bytes": len(p),
                        "whole_ms": 1e3 * tw, "band_ms": 1e3 * tb, "ratio": tw / tb,
                        "same": "yes" if np.array_equal(got, ref[:, k]) else "NO"})
    return out


def lod_rows():
    """A coarser outgoing level (bwh_decode_level) against the whole decode,
    in this run (best of 5 each)."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import Dims, Header, free, lib
    L = lib()
    inputs = {k: inp for k, _, inp, _ in sets()}
    out = []
    for key, args in (("refl81", ["--max-error", "0.0005", "--segments", "16"]),
                      ("ward", ["--symmetry", "mirror", "--max-error", "0.001",
                                "--segments", "1024"])):
        pth = tmp("lod_%s.bwv" % key)
        run(["encode", "-q"] + inputs[key] + args + ["-o", pth])
        p = open(pth, "rb").read()

        def whole():
            h, v = Header(), ctypes.POINTER(ctypes.c_float)()
            if L.bwh_decode_limit(p, len(p), 0, ctypes.byref(h), None, ctypes.byref(v)) != 0:
                sys.exit("bench-progressive: whole decode failed")
            free(v)

        tw = best_of(whole)[0]
        for lv, li in ((0, -1), (2, -1)) + (((2, 2), (0, 0)) if key == "ward" else ()):
            def coarse():
                h, d, v = Header(), Dims(), ctypes.POINTER(ctypes.c_float)()
                if L.bwh_decode_levels(p, len(p), lv, li, ctypes.byref(h), ctypes.byref(d), None,
                                       ctypes.byref(v)) != 0:
                    sys.exit("bench-progressive: level %d decode failed" % lv)
                free(v)
            tl = best_of(coarse)[0]
            out.append({"set": key, "payload": " ".join(args), "level": lv,
                        "level_in": "own" if li < 0 else str(li),
                        "whole_ms": 1e3 * tw, "lod_ms": 1e3 * tl, "ratio": tw / tl})
    return out


FIRMWARE = os.environ.get("FIRMWARE", os.path.join(ROOT, "build/qemu/brdfwave-fw.elf"))


FRACTIONS = (0.05, 0.10, 0.25, 0.50, 1.00)


def values_of(payload):
    """The float values a payload (or a prefix of one) decodes to, or None."""
    out = tmp("v.f32")
    r = run(["decode", "-i", payload, "-o", out], ok=(0, 1, 3))
    return None if r.returncode == 1 else np.fromfile(out, "<f4").astype(np.float64)


def errors(x, ref):
    e = x - ref
    return (100.0 * np.linalg.norm(e) / np.linalg.norm(ref), float(np.sqrt(np.mean(e * e))))


def budget_bytes_for(inp, ref, rel_target, hi):
    """The fewest bytes of a byte-budget encode (the host's best, no
    embedding) whose relative L2 is at most rel_target, within 1 %: a
    bisection on --bytes; (bytes, its relative L2 and RMSE); hi bytes at
    most (None: not reached there)."""
    def at(b):
        p = tmp("bud.bwv")
        r = run(["encode", "-q"] + inp + ["--bytes", str(b), "-o", p], ok=(0, 1))
        if r.returncode:
            return None
        return errors(values_of(p), ref)
    e = at(hi)
    if e is None or e[0] > rel_target:
        return None, e
    lo, best = 64, (hi, e)
    while hi - lo > max(4, lo // 100):
        mid = (lo + hi) // 2
        e = at(mid)
        if e is not None and e[0] <= rel_target:
            hi, best = mid, (mid, e)
        else:
            lo = mid
    return best


def decode_ms(path):
    """The least time of 5 whole decodes of a payload in this process
    (bwh_decode_limit, float values out), in ms."""
    import ctypes
    sys.path.insert(0, os.path.join(ROOT, "host-tools/python"))
    from brdfwave._lib import Header, free, lib
    L = lib()
    p = open(path, "rb").read()

    def once():
        h, v = Header(), ctypes.POINTER(ctypes.c_float)()
        if L.bwh_decode_limit(p, len(p), 0, ctypes.byref(h), None, ctypes.byref(v)) != 0:
            sys.exit("bench-progressive: decode of %s failed" % path)
        free(v)

    return 1e3 * best_of(once)[0]


def embed_rows():
    """Embedded payloads: what the order costs at equal samples (bytes and
    decode time), and their prefixes against byte-budget encodes at the same
    error."""
    sizes, prefix = [], []
    for key, desc, inp, lossy in sets():
        for mode, margs in (("lossless", ["--lossless"]), ("max-error", lossy)):
            got = {}
            for what, extra in (("best", []), ("embedded", ["--progressive"])):
                p = tmp("emb_%s_%s_%s.bwv" % (key, mode, what))
                run(["encode", "-q"] + inp + margs + extra + ["-o", p])
                got[what] = (os.path.getsize(p), values_of(p))
            same = np.array_equal(got["embedded"][1], got["best"][1])
            basis = dict(l.split(": ", 1) for l in run(["info", tmp(
                "emb_%s_%s_best.bwv" % (key, mode))]).stdout.decode().splitlines()
                if ": " in l)["basis"]
            sizes.append({"set": key, "mode": mode, "best": got["best"][0], "basis": basis,
                          "embedded": got["embedded"][0], "same": "yes" if same else "no",
                          "dec_best_ms": decode_ms(tmp("emb_%s_%s_best.bwv" % (key, mode))),
                          "dec_emb_ms": decode_ms(tmp("emb_%s_%s_embedded.bwv" % (key, mode)))})
        # prefixes of the exact embedded coding of the samples a byte budget
        # codes (a budget that holds it all: the values mapped linearly,
        # where a lossless payload of float input may code their bit
        # patterns), against the input
        ref = values_of(tmp("emb_%s_lossless_best.bwv" % key))
        full = tmp("emb_%s_all.bwv" % key)
        big = 16 * os.path.getsize(tmp("emb_%s_lossless_best.bwv" % key))
        run(["encode", "-q"] + inp + ["--bytes", str(big), "--progressive", "-o", full])
        data = open(full, "rb").read()
        if len(data) >= big:
            sys.exit("bench-progressive: %s: the budget does not hold the exact coding" % key)
        last = None
        for f in FRACTIONS:
            n = int(round(f * len(data)))
            cut = tmp("cut.bwv")
            open(cut, "wb").write(data[:n])
            x = values_of(cut)
            if x is None:
                prefix.append({"set": key, "fraction": f, "bytes": n, "decoded": "no"})
                continue
            rel, rmse = errors(x, ref)
            mono = last is None or (rel <= last[0] and rmse <= last[1])
            last = (rel, rmse)
            row = {"set": key, "fraction": f, "bytes": n, "decoded": "yes", "rel": rel,
                   "rmse": rmse, "monotone": "yes" if mono else "NO"}
            if f < 1.0:
                # the embedded encoder's own budget: the exact coding cut at n bytes
                p = tmp("embbud.bwv")
                run(["encode", "-q"] + inp + ["--bytes", str(n), "--progressive", "-o", p])
                row["emb_budget_rel"] = errors(values_of(p), ref)[0]
                pb = tmp("bud_same.bwv")
                run(["encode", "-q"] + inp + ["--bytes", str(n), "-o", pb])
                row["budget_same_rel"], row["budget_same_rmse"] = errors(values_of(pb), ref)
                b, e = budget_bytes_for(inp, ref, rel, 4 * n)
                row["budget_bytes"] = b
                row["budget_rel"] = e[0] if e else None
            prefix.append(row)
        print("bench-progressive: %s embedded done" % key, flush=True)
    return sizes, prefix


def device_rows(refl_args):
    """The streaming encoder on the emulated board, with 1 (none), 4, 16 and
    64 segments."""
    rows = []
    for s in SEGMENTS:
        p = tmp("dev_%d.bwv" % s)
        seg = ["--segments", str(s)] if s > 1 else []
        r = run(["encode", "--device", "qemu", "--firmware", FIRMWARE, "--stream", "--basis",
                 "53", "--max-error", "0.0005"] + refl_args + seg + ["-o", p])
        line = [l for l in r.stdout.decode().splitlines() if "instructions (" in l][0]
        per = float(line.split("instructions (")[1].split()[0])
        h = tmp("host_%d.bwv" % s)
        run(["encode", "-q", "--coder", "auto", "--effort", "fast", "--stream", "--basis", "53",
             "--max-error", "0.0005"] + refl_args + seg + ["-o", h])
        same = open(p, "rb").read() == open(h, "rb").read()
        rows.append({"segments": s, "bytes": os.path.getsize(p), "instr_per_sample": per,
                     "same": "yes" if same else "NO"})
    return rows


def device_embed_rows(refl_args):
    """The refl81 set encoded on the emulated board in memory (not streamed)
    with the strip coder and with embedded segments, at a max error and at
    byte budgets, the device's defaults: bytes, instructions per sample,
    and whether the payload is the host's with the same options."""
    rows = []
    for mode, margs in (("max-error 0.0005", ["--max-error", "0.0005"]),
                        ("ratio 16", ["--ratio", "16"]), ("ratio 64", ["--ratio", "64"])):
        for emb in (False, True):
            ex = ["--progressive"] if emb else []
            p = tmp("devemb.bwv")
            r = run(["encode", "--device", "qemu", "--firmware", FIRMWARE] + margs + refl_args +
                    ex + ["-o", p])
            line = [l for l in r.stdout.decode().splitlines() if "instructions (" in l][0]
            per = float(line.split("instructions (")[1].split()[0])
            h = tmp("hostemb.bwv")
            run(["encode", "-q", "--coder", "auto", "--effort", "fast"] + margs + refl_args + ex +
                ["-o", h])
            same = open(p, "rb").read() == open(h, "rb").read()
            vals = values_of(p)
            rows.append({"mode": mode, "coder": "embedded" if emb else "strips",
                         "bytes": os.path.getsize(p), "instr_per_sample": per,
                         "same": "yes" if same else "NO", "values": vals})
    return rows


def work_ram():
    """The device's work array for jobs held whole in memory (the app's
    static `work`), in bytes."""
    r = subprocess.run(["arm-none-eabi-nm", "-S", FIRMWARE], capture_output=True, text=True)
    for l in r.stdout.splitlines():
        f = l.split()
        if len(f) == 4 and f[3] == "work":
            return int(f[1], 16)
    return 0


def stream_ram():
    """The streaming encoder's RAM in the firmware: its context (the app's
    static `stream`) and the caller's memory (`stream_mem`)."""
    r = subprocess.run(["arm-none-eabi-nm", "-S", FIRMWARE], capture_output=True, text=True)
    size = {}
    for l in r.stdout.splitlines():
        f = l.split()
        if len(f) == 4 and f[3] in ("stream", "stream_mem"):
            size[f[3]] = int(f[1], 16)
    return size


def main():
    os.makedirs(OUT, exist_ok=True)
    size_rows, loss = [], []
    for key, desc, inp, lossy in sets():
        for mode, margs in (("lossless", ["--lossless"]), ("max-error", lossy)):
            sizes = {}
            for s in SEGMENTS:
                p = tmp("%s_%s_%d.bwv" % (key, mode, s))
                run(["encode", "-q"] + inp + margs + ["--segments", str(s), "-o", p])
                sizes[s] = os.path.getsize(p)
            size_rows.append({"set": key, "desc": desc, "mode": mode,
                              **{"bytes_%d" % s: sizes[s] for s in SEGMENTS}})
            loss += loss_rows(key, mode, tmp("%s_%s_%d.bwv" % (key, mode, LOSS_SEGMENTS)))
            print("bench-progressive: %s %s done" % (key, mode), flush=True)
    emb_sizes, emb_prefix = embed_rows()
    part = partial_rows()
    lods = lod_rows()
    regs = region_rows()
    evals = eval_rows()
    bands = band_rows()
    refl = [x for x in sets() if x[0] == "refl81"][0]
    dev = device_rows(refl[2])
    ram = stream_ram()
    demb = device_embed_rows(refl[2])
    wram = work_ram()
    refl_ref = np.fromfile(tmp("refl81.f32"), "<f4").astype(np.float64)
    with open(os.path.join(OUT, "progressive.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(loss[0].keys()))
        w.writeheader()
        w.writerows(loss)
    md = ["# Payloads in segments", "",
          "`make bench-progressive` (tests/bench/run_progressive_bench.py): the host's encoder "
          "with its defaults and `--segments N`; `brdfwave decode --mask` on payloads with a "
          "part lost (its bytes zeroed).", "",
          "## What segments cost", "",
          "Payload bytes in 1 (no segments), 4, 16 and 64 segments, and the growth against 1.",
          "", "| set | mode | 1 | 4 | 16 | 64 |", "|---|---|---|---|---|---|"]
    for r in size_rows:
        b1 = r["bytes_1"]
        md.append("| %s | %s | %d | %s |" % (r["set"], r["mode"], b1, " | ".join(
            "%d (+%.1f %%)" % (r["bytes_%d" % s], 100.0 * (r["bytes_%d" % s] / b1 - 1))
            for s in SEGMENTS[1:])))
    md += ["", "Sets: " + "; ".join("%s: %s" % (r["set"], r["desc"]) for r in size_rows[::2]),
           "", "## What a lost part costs", "",
           "The payload in %d segments; each segment, then each %d-byte chunk, lost in turn. "
           "*affected*: samples the mask marks approximate (rebuilt from coarser levels) or "
           "missing; a chunk that hits the header or the segment table loses the payload whole "
           "(counted as 100 %%). *exact elsewhere*: every sample marked exact equals the whole "
           "payload's, in every case." % (LOSS_SEGMENTS, CHUNK), "",
           "| set | mode | lost | cases | bytes lost, mean | samples affected, mean | max | "
           "lost whole | exact elsewhere |", "|---|---|---|---|---|---|---|---|---|"]
    for r in loss:
        md.append("| %s | %s | %s | %d | %.2f %% | %.2f %% | %.2f %% | %d | %s |" % (
            r["set"], r["mode"], r["lost"], r["cases"], r["bytes_lost_mean_pct"],
            r["samples_affected_mean_pct"], r["samples_affected_max_pct"], r["lost_whole"],
            r["exact_elsewhere"]))
    md += ["", "## Embedded segments: what the order costs", "",
           "The same sets coded with the host's defaults (*best*: the basis it picks, "
           "prediction included where it applies) and with `--progressive` (embedded, one "
           "segment; a transform basis), lossless and with the max error above. *same "
           "samples*: the two payloads decode to the same samples (the same transform and "
           "quantiser: the bytes compare at equal error). *decode*: the least time of 5 whole "
           "decodes of each payload (`bwh_decode_limit`, float values out), in this run, and "
           "the embedded one's against the other's (the bit plane passes, each walked twice, "
           "against one strip pass).", "",
           "| set | mode | best (basis) | embedded | cost | same samples | decode: best | "
           "decode: embedded | ratio |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in emb_sizes:
        md.append("| %s | %s | %d (%s) | %d | %+.1f %% | %s | %.2f ms | %.2f ms | %.2f x |" % (
            r["set"], r["mode"], r["best"], r["basis"], r["embedded"],
            100.0 * (r["embedded"] / r["best"] - 1), r["same"], r["dec_best_ms"],
            r["dec_emb_ms"], r["dec_emb_ms"] / r["dec_best_ms"]))
    md += ["", "## Embedded segments: prefixes", "",
           "The exact embedded coding of each set's samples as a byte budget maps them "
           "(`--bytes N --progressive` with N more than it needs: the whole coding) cut to 5, "
           "10, 25, 50 and 100 % of its bytes and decoded (`brdfwave decode`, status 3 for a "
           "cut payload): relative L2 and RMSE against the input. *monotone*: neither rises "
           "from the fraction before. "
           "*budget, same bytes*: a byte-budget encode of the host (its best, no embedding) "
           "of that many bytes; *budget bytes, same error*: the fewest bytes such an encode "
           "needs for the prefix's relative L2 (a bisection within 1 %, up to 4 x the "
           "prefix; *-*: not reached), and the prefix's bytes against them; *embedded "
           "budget*: `--bytes N --progressive`, the exact coding cut at N.", "",
           "| set | fraction | bytes | rel. L2 | RMSE | monotone | budget, same bytes: rel. "
           "L2 | budget bytes, same error | prefix / budget | embedded budget: rel. L2 |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r in emb_prefix:
        if r["decoded"] != "yes":
            md.append("| %s | %.0f %% | %d | not decoded | | | | | | |" % (
                r["set"], 100 * r["fraction"], r["bytes"]))
            continue
        if r["fraction"] < 1.0:
            bb = r["budget_bytes"]
            md.append("| %s | %.0f %% | %d | %.4g %% | %.4g | %s | %.4g %% | %s | %s | "
                      "%.4g %% |" % (
                          r["set"], 100 * r["fraction"], r["bytes"], r["rel"], r["rmse"],
                          r["monotone"], r["budget_same_rel"], bb if bb else "-",
                          "%.3f" % (r["bytes"] / bb) if bb else "< 0.25",
                          r["emb_budget_rel"]))
        else:
            md.append("| %s | 100 %% | %d | %.4g %% | %.4g | %s | | | | |" % (
                r["set"], r["bytes"], r["rel"], r["rmse"], r["monotone"]))
    cut = [r for r in emb_prefix if r["fraction"] < 1.0]
    within = [r for r in cut if r["decoded"] == "yes" and r["budget_bytes"] and
              r["bytes"] / r["budget_bytes"] <= 1.05]
    mono = all(r.get("monotone") == "yes" for r in emb_prefix)
    md += ["", "Target: errors that never rise with more bytes, and every fraction within "
           "1.05 x in bytes of the byte-budget encode at the same error: %s (monotone: %s; "
           "within 1.05 x: %d of %d)." % ("met" if mono and len(within) == len(cut) else
                                         "not met", "yes" if mono else "no", len(within),
                                         len(cut))]
    md += ["", "## Decoding one incoming direction, a region, a coarser level", "",
           "One incoming direction of a BRDF (one spectrum of a set) decoded alone "
           "(`bwh_decode_incoming`, `decode --incoming K`, `decode(..., incoming=K)`) against "
           "the whole decode (`bwh_decode_limit`), float values out, in this run: the best of 5 "
           "whole decodes, the mean over the rows decoded (spread over the measurement); "
           "*same*: every row equals that row of the whole decode. The Ward set coded without "
           "the symmetry steps or with the mirror step only (the reciprocity step, which the "
           "host's encoder picks for it by default, ties every row to every other: such a "
           "payload decodes whole; with the mirror a row in the mirrored half needs the "
           "mirrored row's blocks too).", "",
           "| set | payload | bytes | rows | whole decode | one row | ratio | same |",
           "|---|---|---|---|---|---|---|---|"]
    for r in part:
        md.append("| %s | %s | %d | %d | %.2f ms | %.3f ms | %.1f x | %s |" % (
            r["set"], r["payload"], r["bytes"], r["rows"], r["whole_ms"], r["row_ms"],
            r["ratio"], r["same"]))
    md += ["", "A region of the Ward set's incoming hemisphere: the incoming directions whose "
           "triangles' centres lie within a radius of a direction (`bwh_region_rows`, then "
           "`bwh_decode_rows`; `decode --region THETA,PHI,RADIUS`, `decode(..., region=)`), "
           "against the whole decode and against its rows decoded one at a time "
           "(`bwh_decode_incoming` each), float values out, the best of 5 each, in this run; "
           "*same*: the rows equal those of the whole decode.", "",
           "| payload | bytes | region | rows | whole decode | region | ratio | row by row | "
           "same |", "|---|---|---|---|---|---|---|---|---|"]
    for r in regs:
        md.append("| %s | %d | %s | %d | %.2f ms | %.3f ms | %.1f x | %.3f ms | %s |" % (
            r["payload"], r["bytes"], r["region"], r["rows"], r["whole_ms"], r["region_ms"],
            r["ratio"], r["one_ms"], r["same"]))
    md += ["", "f(wi, wo) of the Ward set (mirror, 1024 segments, %d bytes) at random direction "
           "pairs straight from the payload (`bwh_payload_eval`, `brdfwave eval`, "
           "`brdfwave.evaluate`: the incoming rows the pairs read, decoded together, then the "
           "renderer's interpolation read from the decoded float values) against decoding it "
           "all and evaluating (`bwh_brdf_data_from_payload` of every row, its tables of "
           "doubles, `bwh_brdf_data_eval_many`), the best of 3 each, in this run; *rows*: the "
           "incoming triangles the pairs fall in (about); *same*: the values equal bit for bit."
           % (evals[0]["bytes"] if evals else 0), "",
           "| pairs | rows | from the payload | decode all, evaluate | ratio | same |",
           "|---|---|---|---|---|---|"]
    for r in evals:
        md.append("| %d | %d | %.3f ms | %.3f ms | %.2f x | %s |" % (
            r["pairs"], r["rows"], r["payload_ms"], r["whole_ms"], r["ratio"], r["same"]))
    big = [r for r in evals if r["pairs"] == 100000]
    if big:
        md += ["", "Target: 10^5 random pairs evaluated from the payload faster than decoding "
               "it all and evaluating: %s (%.2f x)." % (
                   "met" if big[0]["ratio"] > 1.0 else "not met", big[0]["ratio"])]
    md += ["", "One band of the Spectralon set (%d bands, lossless) as `decode --bands K` "
           "(`bwh_decode_bands`, `decode(..., bands=)`) gives it, against the whole decode of "
           "the same payload, float values out, the best of 7 each, in this run: the host's "
           "payload (`encode --lossless`, the range coder: its bands are coded in one stream "
           "per spectrum, so a band decodes it whole, then keeps the band) and the payload "
           "with band access (`encode --lossless --band-access`: prediction along the bands, "
           "coarse to fine, coded by columns; a band decodes the columns it depends on); "
           "*same*: the band equals that band of the whole decode." % bands[0]["bands"], "",
           "| payload | bytes | band | whole decode | one band | ratio | same |",
           "|---|---|---|---|---|---|---|"]
    for r in bands:
        md.append("| %s | %d | %d | %.3f ms | %.4f ms | %.1f x | %s |" % (
            r["payload"], r["bytes"], r["band"], r["whole_ms"], r["band_ms"], r["ratio"],
            r["same"]))
    ba = [r for r in bands if r["payload"] == "band access"]
    rg = [r for r in bands if r["payload"] == "range"]
    if ba and rg:
        worst = min(r["ratio"] for r in ba)
        md += ["", "Target: one band at least 50 x faster than the whole decode: %s with band "
               "access (%.1f x at the slowest band; its payload %d bytes, the host's %d: %.3f "
               "x; every band equal: %s)." % (
                   "met" if worst >= 50.0 and all(r["same"] == "yes" for r in ba) else "not met",
                   worst, ba[0]["bytes"], rg[0]["bytes"], ba[0]["bytes"] / rg[0]["bytes"],
                   "yes" if all(r["same"] == "yes" for r in bands) else "NO")]
    md += ["", "A coarser outgoing level (`bwh_decode_level`, `decode --level L`, "
           "`decode(..., level=L)`), and for the full BRDF a coarser incoming level too "
           "(`bwh_decode_levels`, `--level-in Li`, `level_in=`), against the whole decode, the "
           "best of 5 each, in this run (level 4 payloads):", "",
           "| set | payload | level | incoming level | whole decode | coarser level | ratio |",
           "|---|---|---|---|---|---|---|"]
    for r in lods:
        md.append("| %s | `%s` | %d | %s | %.2f ms | %.3f ms | %.1f x |" % (
            r["set"], r["payload"], r["level"], r["level_in"], r["whole_ms"], r["lod_ms"],
            r["ratio"]))
    d1 = dev[0]
    md += ["", "## On the device", "",
           "The refl81 set (%s) encoded by the emulated board's streaming encoder: `brdfwave "
           "encode --device qemu --stream --basis 53 --max-error 0.0005 [--segments N]`, "
           "instructions per sample counted by QEMU -icount (the encoder's, the sensor "
           "reads included); *as the host's*: the payload byte for byte that of the host's "
           "encoder with the device's defaults (`--coder auto --effort fast`)." % refl[1], "",
           "| segments | bytes | instructions per sample | against none | as the host's |",
           "|---|---|---|---|---|"]
    for r in dev:
        md.append("| %d | %d | %.1f | %.3f x | %s |" % (
            r["segments"], r["bytes"], r["instr_per_sample"],
            r["instr_per_sample"] / d1["instr_per_sample"], r["same"]))
    mem = (4 * (4 + 1) + 3) * 81 * 4  # BW_STREAM_MEM_BOUND(4, 81) int32
    md += ["", "RAM of the streaming encoder for level 4 x 81 bands: its context, "
           "`bw_stream_t` (the app's static `stream` in the firmware image, `arm-none-eabi-nm "
           "-S build/qemu/brdfwave-fw.elf`), %d bytes, the segments' state in it three "
           "fields; and its memory, BW_STREAM_MEM_BOUND(4, 81) int32 = %d bytes: %d bytes "
           "(%.1f KiB) in all, with or without segments, whose table (8 bytes a segment) "
           "lies in the payload's own buffer." % (ram.get("stream", 0), mem,
                                                  ram.get("stream", 0) + mem,
                                                  (ram.get("stream", 0) + mem) / 1024.0)]
    md += ["", "Embedded segments on the device: the same set encoded in memory (not "
           "streamed: embedding needs coarse-to-fine order) by the emulated board, `brdfwave "
           "encode --device qemu [--progressive] --max-error 0.0005 | --ratio R`, the device's "
           "defaults; *as the host's*: the payload byte for byte that of the host's encoder "
           "with the same options and the device's defaults. The strip coder's byte budget "
           "estimates its step and corrects it by whole encodes; the embedded one is one "
           "encode of the exact coefficients, stopped at the budget.", "",
           "| mode | coder | bytes | relative L2 | instructions per sample | embedded against "
           "strips | as the host's |", "|---|---|---|---|---|---|---|"]
    for a, b in zip(demb[0::2], demb[1::2]):
        for r in (a, b):
            rel = errors(r["values"], refl_ref)[0] if r["values"] is not None else float("nan")
            md.append("| %s | %s | %d | %.4g %% | %.1f | %s | %s |" % (
                r["mode"], r["coder"], r["bytes"], rel, r["instr_per_sample"],
                "%.2f x" % (r["instr_per_sample"] / a["instr_per_sample"]) if r is b else "",
                r["same"]))
    md += ["", "RAM of a job held in memory: the work array (the app's static `work`, "
           "BW_WORK_BOUND(APP_MAX_SAMPLES, APP_MAX_BANDS) int32, %d bytes) holds the embedded "
           "coder's bit per coefficient and per strip beside the samples (n / 16 + 3 words "
           "of BW_WORK_BOUND), its models in the strip coder's (in the context): no more RAM "
           "than the strip coder's jobs." % wram]
    bad = ([r for r in loss if r["exact_elsewhere"] != "yes"] +
           [r for r in emb_prefix if r.get("monotone", "yes") != "yes"] +
           [r for r in dev if r["same"] != "yes"] + [r for r in part if r["same"] != "yes"] +
           [r for r in regs if r["same"] != "yes"] + [r for r in demb if r["same"] != "yes"] +
           [r for r in evals if r["same"] != "yes"])
    md += ["", "Exact outside the lost part in every case: %s." % ("yes" if not bad else
                                                                    "NO (%d rows)" % len(bad))]
    open(os.path.join(OUT, "progressive.md"), "w").write("\n".join(md) + "\n")
    print("bench-progressive: wrote %s" % os.path.join(OUT, "progressive.md"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
