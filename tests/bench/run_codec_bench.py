#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Codec benchmark: brdfwave against standard compressors.

Writes build/bench/codec.md (one table per data set) and build/bench/codec.csv
with bits/sample against error for

  * the 60 field reflectance spectra (PSR-3500, 1024 channels), as float32
    reflectance and as 16-bit integers round(10000 * reflectance);
  * the paper's virtual goniometer sets Phong1, Phong2 (16 x 1024, level 4)
    and Ward (1024 x 1024, level-in 4 x level 4), made with `brdfwave synth`.

Usage: /usr/bin/python3 tests/bench/run_codec_bench.py [PATH/TO/brdfwave]
       (or set BW; default build/host/brdfwave). `make bench` runs it.
Environment: BW, PEER_JPEGLS (default build/bench/peer_jpegls), BENCH_KEEP_TMP=1
keeps the intermediate files in build/bench/tmp.

Exit status: 0 on success; 1 if the brdfwave CLI failed on any input or broke
its own contract (lossless not exact, --max-error exceeded, --ratio budget
exceeded, wrong decoded size). The report is written in every case.
"""

import csv
import datetime
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT_DIR = os.path.join(ROOT, "build", "bench")
TMP_DIR = os.path.join(OUT_DIR, "tmp")
REPORT_MD = os.path.join(OUT_DIR, "codec.md")
REPORT_CSV = os.path.join(OUT_DIR, "codec.csv")
TABLES_MD = "/work/shared/paper/tables.md"
SPECTRA_DIRS = [
    os.path.join(ROOT, "tests", "data", "field_psr3500"),
    "/work/shared/data/spectra/field_psr3500",
]

RATIOS = [8, 16, 64, 128, 256]          # brdfwave --ratio (vs float32 bytes)
NEARS = [1, 2, 4, 8, 16]                # JPEG-LS NEAR and brdfwave --max-error on integers
OPJ_RATES = [2, 4, 8, 16, 32, 64, 128]  # opj_compress -r (vs the 16-bit image)
SPECTRA_TOLS = [5e-6, 5e-5, 1e-4, 2e-4, 4e-4, 8e-4, 1.6e-3, 6.4e-3]   # float units
SYNTH_TOL_STEPS = [0.5, 1, 2, 4, 8, 16, 64, 256]   # x (max / 65535)

DPKG_PACKAGES = ["libcharls2", "libcharls-dev", "libopenjp2-7", "libopenjp2-tools",
                 "zfp", "libzfp1", "libaec-tools", "libaec0", "xz-utils", "zstd"]


# --------------------------------------------------------------------------
# small helpers

# The paper's synthetic sets: key, `brdfwave synth` arguments, the layout
# arguments for `brdfwave encode`, description (shared with run_rd_bench.py).
PAPER_SETS = [
    ("Phong1", ["--model", "phong", "--kd", "0.75", "--ks", "0.25", "--n", "20",
                "--level", "4", "--incoming", "16"], ["--level", "4", "--incoming", "16"],
     "modified Phong kd=0.75 ks=0.25 n=20; 16 incoming (phi=0) x 1024 outgoing (level 4)"),
    ("Phong2", ["--model", "phong", "--kd", "0.5", "--ks", "0.5", "--n", "50",
                "--level", "4", "--incoming", "16"], ["--level", "4", "--incoming", "16"],
     "modified Phong kd=0.5 ks=0.5 n=50; 16 incoming (phi=0) x 1024 outgoing (level 4)"),
    ("Ward", ["--model", "ward", "--ax", "0.35", "--ay", "0.05", "--kd", "0.75",
              "--ks", "0.25", "--level", "4", "--level-in", "4"],
     ["--level", "4", "--level-in", "4"],
     "Ward anisotropic ax=0.35 ay=0.05 kd=0.75 ks=0.25; 1024 incoming (level-in 4) x "
     "1024 outgoing (level 4)"),
]


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def rel(path):
    """Path relative to the repository root if it lies inside it."""
    ap = os.path.abspath(path)
    if ap.startswith(ROOT + os.sep):
        return os.path.relpath(ap, ROOT)
    return path


class ToolError(Exception):
    pass


def run(cmd, what):
    """Run cmd (list); raise ToolError with a one-line reason on failure."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=600)
    except OSError as e:
        raise ToolError("%s: cannot run %s: %s" % (what, cmd[0], e))
    except subprocess.TimeoutExpired:
        raise ToolError("%s: timed out: %s" % (what, " ".join(cmd)))
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        err = p.stderr.decode("utf-8", "replace").strip().splitlines()
        tail = " | ".join(err[-3:]) if err else "(no message)"
        raise ToolError("%s: exit status %d: %s [%s]" % (what, p.returncode, tail,
                                                        " ".join(cmd)))
    return p.stdout.decode("utf-8", "replace"), dt


def fsize(path):
    return os.path.getsize(path)


def cmdline(cmd):
    return " ".join(rel(c) if os.path.isabs(c) else c for c in cmd)


# --------------------------------------------------------------------------
# metrics (paper eq. 7 and 8)

def metrics(ref, dec):
    ref = np.asarray(ref, dtype=np.float64).ravel()
    dec = np.asarray(dec, dtype=np.float64).ravel()
    err = dec - ref
    out = {
        "max_abs_err": float(np.max(np.abs(err))) if err.size else 0.0,
        "rmse": float(np.sqrt(np.mean(err * err))) if err.size else 0.0,
    }
    nz = ref != 0
    skipped = int(ref.size - np.count_nonzero(nz))
    if np.any(nz):
        r = err[nz] / np.abs(ref[nz])
        out["rel_l1_pct"] = float(100.0 * np.mean(np.abs(r)))
        out["rel_l2_pct"] = float(100.0 * np.sqrt(np.mean(r * r)))
    else:
        out["rel_l1_pct"] = float("nan")
        out["rel_l2_pct"] = float("nan")
    out["skipped_zero"] = skipped
    out["finite"] = bool(np.all(np.isfinite(dec)))
    return out


# --------------------------------------------------------------------------
# data sets

class Table:
    """One report table: a reference array plus the rows measured against it."""

    def __init__(self, key, title, ref, desc):
        self.key = key
        self.title = title
        self.ref = ref              # float64 2-D [rows][cols], reference values
        self.desc = desc
        self.rows = []
        self.notes = []

    @property
    def n(self):
        return int(self.ref.size)


class DataSet:
    def __init__(self, key, title, f32, bw_args, kind):
        self.key = key
        self.title = title
        self.f32 = f32               # float32 2-D array
        self.bw_args = bw_args       # layout arguments for brdfwave encode
        self.kind = kind             # "spectra" or "brdf"


def read_sed(path):
    with open(path, "r", encoding="latin-1") as f:
        lines = f.read().splitlines()
    try:
        i = next(k for k, l in enumerate(lines) if l.strip().startswith("Data:"))
    except StopIteration:
        raise ValueError("%s: no 'Data:' line" % path)
    titles = [t.strip() for t in lines[i + 1].split("\t")]
    col = next((k for k, t in enumerate(titles) if t.startswith("Reflect. [1.0]")), 4)
    wvl, refl = [], []
    for l in lines[i + 2:]:
        if not l.strip():
            continue
        parts = l.split("\t")
        wvl.append(float(parts[0]))
        refl.append(float(parts[col]))
    return np.array(wvl), np.array(refl)


def load_spectra():
    for d in SPECTRA_DIRS:
        files = sorted(glob.glob(os.path.join(d, "*.sed")))
        if files:
            break
    else:
        raise SystemExit("run_codec_bench: no .sed files in %s" % " or ".join(SPECTRA_DIRS))
    wvl0, rows = None, []
    for p in files:
        wvl, r = read_sed(p)
        if r.size != 1024:
            raise SystemExit("run_codec_bench: %s has %d channels, expected 1024" % (p, r.size))
        if wvl0 is None:
            wvl0 = wvl
        elif not np.array_equal(wvl, wvl0):
            raise SystemExit("run_codec_bench: %s has different wavelengths" % p)
        rows.append(r)
    return d, files, np.array(rows)


# --------------------------------------------------------------------------
# brdfwave CLI

class Bench:
    def __init__(self, bw):
        self.bw = bw
        self.cli_failures = []
        self.violations = []
        self.peer_missing = []
        self.peer_failures = []
        self.tables = []
        self.seq = 0

    def tmp(self, name):
        self.seq += 1
        return os.path.join(TMP_DIR, "%03d_%s" % (self.seq, name))

    # ---- our codec
    def bw_info(self, path):
        out, _ = run([self.bw, "info", path], "brdfwave info")
        info = {}
        for line in out.splitlines():
            if ":" in line:
                k, v = line.split(":", 1)
                info[k.strip()] = v.strip()
        return info

    def bw_row(self, table, ds, infile, fmt, mode_args, setting, check=None,
               to_ref=None, native_ref=None, layout=None, native_i32=False):
        """Encode/decode with brdfwave and add a row to table. infile is a path
        or a list of paths (one -i each). check = (kind, value) is verified in
        the units the codec saw: native_ref (default the table's reference)
        against the float32 output, or against the int32 samples
        (decode --output-format i32) if native_i32. to_ref maps the decoded
        float32 values to reference units."""
        n = table.n
        enc = self.tmp("%s_%s.bwv" % (ds.key, fmt))
        dec = enc[:-4] + ".f32"
        inputs = infile if isinstance(infile, list) else [infile]
        cmd = [self.bw, "encode"]
        for p in inputs:
            cmd += ["-i", p]
        cmd += (["-o", enc] + (ds.bw_args if layout is None else layout) +
                ["--input-format", fmt] + mode_args)
        try:
            _, t_enc = run(cmd, "brdfwave encode (%s, %s)" % (table.title, setting))
            _, t_dec = run([self.bw, "decode", "-i", enc, "-o", dec],
                           "brdfwave decode (%s, %s)" % (table.title, setting))
            info = self.bw_info(enc)
            if native_i32:
                run([self.bw, "decode", "-i", enc, "-o", dec + ".i32", "--output-format", "i32"],
                    "brdfwave decode --output-format i32 (%s, %s)" % (table.title, setting))
        except ToolError as e:
            log("FAIL " + str(e))
            self.cli_failures.append(str(e))
            return
        size = fsize(dec)
        if size != 4 * n or (native_i32 and fsize(dec + ".i32") != 4 * n):
            msg = ("brdfwave decode (%s, %s): decoded %d bytes, expected %d (%d samples)"
                   % (table.title, setting, size, 4 * n, n))
            log("FAIL " + msg)
            self.cli_failures.append(msg)
            return
        if info.get("samples", str(n)) != str(n):
            self.violate(table, setting, "info reports samples: %s, expected %d"
                         % (info.get("samples"), n))
        d = np.fromfile(dec, dtype="<f4").astype(np.float64).reshape(table.ref.shape)
        dn = d
        if native_i32:
            dn = np.fromfile(dec + ".i32", dtype="<i4").astype(np.float64).reshape(table.ref.shape)
            os.remove(dec + ".i32")
        nbytes = fsize(enc)
        payload = None
        for k, v in info.items():
            if "payload" in k.lower():
                m = re.match(r"^(\d+)", v)
                if m:
                    payload = int(m.group(1))
                    break
        notes = []
        for k in ("basis", "mode", "step", "scale"):
            if k in info:
                notes.append("%s=%s" % (k, info[k]))
        if payload is not None:
            notes.append("payload=%d" % payload)
        nref = table.ref if native_ref is None else native_ref
        native_err = float(np.max(np.abs(dn - nref)))
        if not np.isfinite(native_err):
            native_err = float("inf")
        row = self.add_row(table, "brdfwave", setting, fmt, nbytes,
                           d if to_ref is None else to_ref(d), t_enc + t_dec,
                           cmdline(cmd), "; ".join(notes), native_err=native_err)
        self.check_contract(table, row, setting, check, payload, n, fmt, nref)
        if native_i32 and check is not None and check[0] == "lossless" and \
                row["max_abs_err_native"] == 0.0 and row["max_abs_err"] != 0.0:
            ne = int(np.count_nonzero(d != table.ref))
            table.notes.append(
                "brdfwave %s: the int32 samples (decode --output-format i32) are exact; the "
                "float32 output differs from the float32 reference in %d of %d samples (%.1f %%), "
                "by at most %.3g." % (setting, ne, n, 100.0 * ne / n, row["max_abs_err"]))
        os.remove(dec)

    def check_contract(self, table, row, setting, check, payload, n, fmt, nref):
        if not row["finite"]:
            self.violate(table, setting, "decoded data contain NaN/Inf")
        if check is None:
            return
        kind, value = check
        if kind == "lossless":
            if row["max_abs_err_native"] != 0.0:
                self.violate(table, setting, "--lossless but max abs error %.6g (codec units)"
                             % row["max_abs_err_native"])
        elif kind == "max_error":
            slack = 0.0
            if fmt == "f32":
                # one float32 ulp at the largest reference magnitude
                slack = float(np.spacing(np.float32(np.max(np.abs(nref)))))
            if row["max_abs_err_native"] > value + slack:
                self.violate(table, setting, "--max-error %g but max abs error %.6g"
                             % (value, row["max_abs_err_native"]))
        elif kind == "ratio":
            budget = 4.0 * n / value
            used = payload if payload is not None else row["bytes"]
            what = "payload" if payload is not None else "file size (info shows no payload)"
            if used > budget:
                self.violate(table, setting, "--ratio %g: %s %d bytes > budget %.1f bytes"
                             % (value, what, used, budget))

    def violate(self, table, setting, msg):
        m = "%s, brdfwave %s: %s" % (table.title, setting, msg)
        log("CONTRACT " + m)
        self.violations.append(m)

    # ---- rows
    def add_row(self, table, codec, setting, inp, nbytes, dec_ref, seconds, cmd,
                notes="", native_err=None):
        m = metrics(table.ref, dec_ref)
        n = table.n
        row = {
            "dataset": table.key,
            "codec": codec,
            "setting": setting,
            "input": inp,
            "samples": n,
            "bytes": int(nbytes),
            "bits_per_sample": 8.0 * nbytes / n,
            "ratio_vs_f32": 4.0 * n / nbytes if nbytes else float("inf"),
            "seconds": seconds,
            "cmd": cmd,
            "notes": notes,
        }
        row.update(m)
        row["max_abs_err_native"] = m["max_abs_err"] if native_err is None else native_err
        table.rows.append(row)
        log("  %-10s %-28s %-4s %9d B %7.3f b/s  maxerr %.3g  L1 %.3g%%  L2 %.3g%%"
            % (codec, setting, inp, nbytes, row["bits_per_sample"], m["max_abs_err"],
               m["rel_l1_pct"], m["rel_l2_pct"]))
        return row

    def peer_fail(self, table, msg):
        log("peer failure: " + msg)
        self.peer_failures.append("%s: %s" % (table.title, msg))


# --------------------------------------------------------------------------
# peers

def have(tool):
    return shutil.which(tool) is not None


def write_pgm(path, a):
    h, w = a.shape
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n65535\n" % (w, h))
        f.write(np.ascontiguousarray(a, dtype=">u2").tobytes())


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    tokens, pos = [], 0
    while len(tokens) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            while data[pos:pos + 1] not in (b"\n", b"\r", b""):
                pos += 1
            continue
        start = pos
        while pos < len(data) and not data[pos:pos + 1].isspace():
            pos += 1
        tokens.append(data[start:pos])
    pos += 1
    if tokens[0] != b"P5":
        raise ToolError("%s: not a binary PGM" % path)
    w, h, maxval = int(tokens[1]), int(tokens[2]), int(tokens[3])
    dt = ">u2" if maxval > 255 else "u1"
    return np.frombuffer(data, dtype=dt, count=w * h, offset=pos).reshape(h, w).astype(np.int64)


def opj_levels(shape):
    return max(1, min(6, int(math.floor(math.log2(min(shape)))) + 1))


def peers_u16(b, table, ds_key, u16, to_ref):
    """JPEG-LS, OpenJPEG, libaec, xz, zstd on a 2-D uint16 array; to_ref maps
    decoded integers to reference units."""
    raw = b.tmp("%s.u16" % ds_key)
    u16.astype("<u2").tofile(raw)
    jpegls_u16(b, table, ds_key, u16, to_ref)
    openjpeg_u16(b, table, ds_key, u16, to_ref)
    libaec_u16(b, table, ds_key, u16, to_ref)
    h, w = u16.shape
    general_purpose(b, table, ds_key, raw, "u16", lambda buf: to_ref(
        np.frombuffer(buf, dtype="<u2").astype(np.int64).reshape(h, w)))


def jpegls_u16(b, table, ds_key, u16, to_ref, nears=None):
    """CharLS JPEG-LS, lossless and NEAR = nears (default NEARS), sample
    precision = the data's bit depth; the image is u16 as it stands (h rows)."""
    raw = b.tmp("%s.u16" % ds_key)
    u16.astype("<u2").tofile(raw)
    h, w = u16.shape
    bits = max(2, int(u16.max()).bit_length())
    if os.path.exists(PEER_JPEGLS) and os.access(PEER_JPEGLS, os.X_OK):
        for near in [0] + (NEARS if nears is None else nears):
            out = b.tmp("%s_near%d.jls" % (ds_key, near))
            dec = out + ".u16"
            cmd = [PEER_JPEGLS, "-b", str(bits), str(w), str(h), str(near), raw, out, dec]
            try:
                so, dt = run(cmd, "JPEG-LS NEAR=%d" % near)
                nb = int(so.split()[0])
                if nb != fsize(out):
                    raise ToolError("JPEG-LS: reported %d bytes, file has %d" % (nb, fsize(out)))
                d = np.fromfile(dec, dtype="<u2").astype(np.int64).reshape(h, w)
            except (ToolError, ValueError, IndexError) as e:
                b.peer_fail(table, str(e))
                continue
            b.add_row(table, "JPEG-LS", ("lossless" if near == 0 else "NEAR=%d" % near)
                      + " (%d-bit)" % bits, "u16", nb, to_ref(d), dt, cmdline(cmd),
                      "CharLS, %d bits/sample" % bits)
    else:
        note(b, table, "JPEG-LS", "helper %s not built (CharLS missing?)" % rel(PEER_JPEGLS))


def openjpeg_u16(b, table, ds_key, u16, to_ref, rates=None):
    """OpenJPEG 5/3 lossless and 9/7 at -r rates (default OPJ_RATES), both
    orientations, the better kept per setting."""
    rates = OPJ_RATES if rates is None else rates
    if have("opj_compress") and have("opj_decompress"):
        variants = {"rows": u16, "cols": np.ascontiguousarray(u16.T)}
        settings = [("5/3 lossless", [])] + [("9/7 -r %g" % r, ["-I", "-r", "%g" % r])
                                             for r in rates]
        pgms = {}
        for o, a in variants.items():
            p = b.tmp("%s_%s.pgm" % (ds_key, o))
            write_pgm(p, a)
            pgms[o] = p
        for name, extra in settings:
            best = None
            for o, a in variants.items():
                out = b.tmp("%s_%s.j2k" % (ds_key, o))
                dec = out[:-4] + "_dec.pgm"
                cmd = ["opj_compress", "-i", pgms[o], "-o", out, "-n",
                       str(opj_levels(a.shape))] + extra
                try:
                    _, t1 = run(cmd, "opj_compress %s" % name)
                    _, t2 = run(["opj_decompress", "-i", out, "-o", dec], "opj_decompress")
                    d = read_pgm(dec)
                except ToolError as e:
                    b.peer_fail(table, str(e))
                    continue
                if d.shape != a.shape:
                    b.peer_fail(table, "opj_decompress %s: shape %s, expected %s"
                                % (name, d.shape, a.shape))
                    continue
                if o == "cols":
                    d = d.T
                dref = to_ref(d)
                nb = fsize(out)
                err = float(np.sqrt(np.mean((dref - table.ref) ** 2)))
                key = (nb, err) if not extra else (err, nb)
                if best is None or key < best[0]:
                    best = (key, o, nb, dref, t1 + t2, cmd)
            if best is not None:
                _, o, nb, dref, dt, cmd = best
                b.add_row(table, "OpenJPEG", "%s [%s]" % (name, o), "u16", nb, dref, dt,
                          cmdline(cmd), "orientation %s (spectra/incoming as %s)" % (o, o))
    else:
        note(b, table, "OpenJPEG", "opj_compress/opj_decompress not found")


def libaec_u16(b, table, ds_key, u16, to_ref):
    """libaec (CCSDS 121.0), lossless, samples in the array's row-major order."""
    n = u16.size
    raw = b.tmp("%s.u16" % ds_key)
    u16.astype("<u2").tofile(raw)
    h, w = u16.shape
    if have("aec"):
        for name, flags in (("-j 64 -r 128 (preprocessing)", ["-n", "16", "-j", "64", "-r", "128"]),
                            ("-j 64 -r 128 -N (no preprocessing)",
                             ["-n", "16", "-j", "64", "-r", "128", "-N"])):
            out = b.tmp("%s.aec" % ds_key)
            dec = out + ".u16"
            cmd = ["aec"] + flags + [raw, out]
            try:
                _, t1 = run(cmd, "aec %s" % name)
                _, t2 = run(["aec", "-d"] + flags + [out, dec], "aec -d %s" % name)
                d = np.fromfile(dec, dtype="<u2").astype(np.int64)
                if d.size != n:
                    raise ToolError("aec -d: %d samples, expected %d" % (d.size, n))
            except ToolError as e:
                b.peer_fail(table, str(e))
                continue
            b.add_row(table, "libaec", name, "u16", fsize(out), to_ref(d.reshape(h, w)),
                      t1 + t2, cmdline(cmd))
    else:
        note(b, table, "libaec", "aec not found")


def general_purpose(b, table, ds_key, raw, inp, decode):
    for tool, flags, dflags in (("xz", ["-9e"], ["-d"]), ("zstd", ["-19"], ["-d"])):
        if not have(tool):
            note(b, table, tool, "%s not found" % tool)
            continue
        out = b.tmp("%s_%s.%s" % (ds_key, inp, tool))
        cmd = [tool] + flags + ["-q", "-k", "-f", "-c", raw]
        try:
            t0 = time.perf_counter()
            with open(out, "wb") as f:
                p = subprocess.run(cmd, stdout=f, stderr=subprocess.PIPE)
            if p.returncode != 0:
                raise ToolError("%s: exit status %d: %s" % (tool, p.returncode,
                                                            p.stderr.decode().strip()))
            p = subprocess.run([tool] + dflags + ["-q", "-c", out], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
            if p.returncode != 0:
                raise ToolError("%s -d: exit status %d" % (tool, p.returncode))
            dt = time.perf_counter() - t0
            with open(raw, "rb") as f:
                if f.read() != p.stdout:
                    raise ToolError("%s: round trip differs" % tool)
        except (ToolError, OSError) as e:
            b.peer_fail(table, str(e))
            continue
        b.add_row(table, tool, " ".join(flags), inp, fsize(out), decode(p.stdout), dt,
                  cmdline(cmd))


def peers_f32(b, table, ds_key, f32, zfp_dims, tols):
    """ZFP, xz, zstd on a 2-D float32 array (reference units)."""
    raw = b.tmp("%s.f32" % ds_key)
    f32.astype("<f4").tofile(raw)
    h, w = f32.shape
    zfp_f32(b, table, ds_key, f32, zfp_dims, tols)
    general_purpose(b, table, ds_key, raw, "f32", lambda buf: np.frombuffer(
        buf, dtype="<f4").astype(np.float64).reshape(h, w))


def zfp_f32(b, table, ds_key, f32, zfp_dims, tols, to_ref=None):
    """ZFP reversible (-R) and fixed-accuracy (-a tol) on a float32 array laid
    out as zfp_dims; to_ref maps the decoded [h][w] array to the table's."""
    raw = b.tmp("%s.f32" % ds_key)
    f32.astype("<f4").tofile(raw)
    h, w = f32.shape
    to_ref = (lambda d: d) if to_ref is None else to_ref
    if have("zfp"):
        for name, flags in ([("-R", ["-R"])] + [("-a %g" % t, ["-a", "%.9g" % t]) for t in tols]):
            out = b.tmp("%s.zfp" % ds_key)
            dec = out + ".f32"
            cmd = ["zfp", "-q", "-h", "-f"] + zfp_dims + flags + ["-i", raw, "-z", out]
            try:
                _, t1 = run(cmd, "zfp %s" % name)
                _, t2 = run(["zfp", "-q", "-h", "-z", out, "-o", dec], "zfp decompress")
                d = np.fromfile(dec, dtype="<f4").astype(np.float64)
                if d.size != f32.size:
                    raise ToolError("zfp: %d values back, expected %d" % (d.size, f32.size))
            except ToolError as e:
                b.peer_fail(table, str(e))
                continue
            b.add_row(table, "zfp", "%s (%s)" % (name, " ".join(zfp_dims)), "f32", fsize(out),
                      to_ref(d.reshape(h, w)), t1 + t2, cmdline(cmd))
    else:
        note(b, table, "zfp", "zfp not found")


def note(b, table, peer, msg):
    m = "%s skipped: %s" % (peer, msg)
    if m not in table.notes:
        table.notes.append(m)
    entry = "%s (%s)" % (peer, msg)
    if entry not in b.peer_missing:
        log("peer missing: " + entry + " -- skipped")
        b.peer_missing.append(entry)


# --------------------------------------------------------------------------
# report

def fmt_num(x, spec):
    if isinstance(x, float) and (math.isnan(x) or math.isinf(x)):
        return "n/a" if math.isnan(x) else "inf"
    return spec % x


def md_table(table):
    out = ["| codec | setting | input | bytes | bits/sample | ratio vs f32 | max abs err | RMSE "
           "| rel L1 % | rel L2 % | skipped (ref=0) | enc+dec s |",
           "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    rows = sorted(table.rows, key=lambda r: (r["codec"].lower(), r["input"],
                                             r["bits_per_sample"], r["max_abs_err"]))
    for r in rows:
        out.append("| %s | %s | %s | %d | %s | %s | %s | %s | %s | %s | %d | %s |" % (
            r["codec"], r["setting"].replace("|", "\\|"), r["input"], r["bytes"],
            fmt_num(r["bits_per_sample"], "%.4g"), fmt_num(r["ratio_vs_f32"], "%.2f"),
            fmt_num(r["max_abs_err"], "%.4g"), fmt_num(r["rmse"], "%.4g"),
            fmt_num(r["rel_l1_pct"], "%.4g"), fmt_num(r["rel_l2_pct"], "%.4g"),
            r["skipped_zero"], fmt_num(r["seconds"], "%.2f")))
    return out


def tool_versions(bw):
    lines = []
    try:
        p = subprocess.run(["dpkg-query", "-W", "-f", "${Package}\t${Version}\n"]
                           + DPKG_PACKAGES, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        got = {}
        for l in p.stdout.decode().splitlines():
            k, _, v = l.partition("\t")
            got[k.split(":")[0]] = v
        for pkg in DPKG_PACKAGES:
            lines.append((pkg, got.get(pkg) or "not installed"))
    except OSError:
        lines.append(("dpkg-query", "not available"))
    lines.append(("python3", sys.version.split()[0]))
    lines.append(("numpy", np.__version__))
    lines.append(("brdfwave", rel(bw)))
    return lines


def paper_table2():
    """Rows of the paper's Table 2 from tables.md: {r_c: {col: value}}."""
    try:
        with open(TABLES_MD, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return None
    m = re.search(r"## Table 2[^\n]*\n(.*?)(?:\n## |\Z)", text, re.S)
    if not m:
        return None
    lines = [l for l in m.group(1).splitlines() if l.startswith("|")]
    if len(lines) < 3:
        return None
    head = [c.strip() for c in lines[0].strip("|").split("|")]
    out = {}
    for l in lines[2:]:
        cells = [c.strip() for c in l.strip("|").split("|")]
        if len(cells) != len(head):
            continue
        rc = cells[0].split(":")[0]
        try:
            rc = int(rc)
        except ValueError:
            continue
        # columns: r_c, #coef, P1 L1, L2, P2 L1, L2, #coef, W L1, L2
        out[rc] = {"Phong1": (cells[2], cells[3]), "Phong2": (cells[4], cells[5]),
                   "Ward": (cells[7], cells[8])}
    return out


SUMMARY_CODECS = ["brdfwave", "JPEG-LS", "OpenJPEG", "libaec", "zfp", "xz", "zstd"]


def summary(b):
    """Summary tables derived from the measured rows (no other numbers)."""
    tabs = [t for t in b.tables if t.rows]
    if not tabs:
        return []
    codecs = [c for c in SUMMARY_CODECS if any(r["codec"] == c for t in tabs for r in t.rows)]
    L = []
    crit = [
        ("Lossless: smallest bits/sample with max abs err = 0 against the table's reference "
         "(for the synthetic sets only float32 inputs can qualify)",
         lambda r: r["max_abs_err"] == 0.0),
        ("Smallest bits/sample with rel L2 <= 1 %", lambda r: r["rel_l2_pct"] <= 1.0),
        ("Smallest bits/sample with rel L2 <= 5 %", lambda r: r["rel_l2_pct"] <= 5.0),
    ]
    L.append("## Summary (bits/sample, picked from the rows of the tables below)")
    L.append("")
    for title, ok in crit:
        L.append("%s; `-` = no row qualifies. The input and setting that achieved it are in parentheses." % title)
        L.append("")
        L.append("| codec | " + " | ".join(t.key for t in tabs) + " |")
        L.append("|---|" + "---:|" * len(tabs))
        for c in codecs:
            cells = []
            for t in tabs:
                cand = [r for r in t.rows if r["codec"] == c and ok(r)]
                if not cand:
                    cells.append("-")
                    continue
                r = min(cand, key=lambda r: (r["bits_per_sample"], r["rmse"]))
                cells.append("%.4g (%s, %s)" % (r["bits_per_sample"], r["input"],
                                               r["setting"].replace("|", "\\|")))
            L.append("| %s | %s |" % (c, " | ".join(cells)))
        L.append("")
    return L


def write_reports(b, spectra_src, started, elapsed, versions):
    os.makedirs(OUT_DIR, exist_ok=True)
    fields = ["dataset", "codec", "setting", "input", "samples", "bytes", "bits_per_sample",
              "ratio_vs_f32", "max_abs_err", "rmse", "rel_l1_pct", "rel_l2_pct",
              "skipped_zero", "seconds", "notes", "cmd"]
    with open(REPORT_CSV, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        wr.writeheader()
        for t in b.tables:
            for r in sorted(t.rows, key=lambda r: (r["codec"].lower(), r["input"],
                                                   r["bits_per_sample"])):
                rr = dict(r)
                for k in ("bits_per_sample", "ratio_vs_f32", "max_abs_err", "rmse",
                          "rel_l1_pct", "rel_l2_pct"):
                    rr[k] = "%.6g" % rr[k]
                rr["seconds"] = "%.3f" % rr["seconds"]
                wr.writerow(rr)

    L = []
    L.append("# Codec benchmark: brdfwave against standard compressors")
    L.append("")
    L.append("Rerun with `make bench` (or `BW=build/host/brdfwave /usr/bin/python3 "
             "tests/bench/run_codec_bench.py`). Generated %s in %.0f s. Every number in the "
             "tables below was measured in that run; `build/bench/codec.csv` holds the same "
             "rows with the exact command lines." % (started, elapsed))
    L.append("")
    L.append("Metrics (numpy, against the original data): bytes = size of the compressed "
             "file (container/headers included); bits/sample = 8 x bytes / samples; ratio "
             "vs f32 = 4 x samples / bytes; max abs err and RMSE in the units of the table's "
             "reference; rel L1 = mean(|f'-f|/f), rel L2 = sqrt(mean((f'-f)^2/f^2)), in percent "
             "(paper eq. 7, 8), over the samples where the reference f is not 0 (the skipped "
             "count is given). Rows are sorted by codec, input, then bits/sample. Input `u16` = "
             "the codec saw the 16-bit integer version; for the synthetic sets that version is "
             "round(f x 65535 / max f) and its errors are computed after scaling back to float.")
    L.append("")
    L.append("## Tool versions")
    L.append("")
    L.append("| package | version |")
    L.append("|---|---|")
    for k, v in versions:
        L.append("| %s | %s |" % (k, v))
    L.append("")
    if b.cli_failures or b.violations:
        L.append("## brdfwave CLI problems in this run")
        L.append("")
        for m in b.cli_failures:
            L.append("- FAILED: %s" % m)
        for m in b.violations:
            L.append("- CONTRACT: %s" % m)
        L.append("")
    if b.peer_missing or b.peer_failures:
        L.append("## Peers skipped or failed")
        L.append("")
        for m in b.peer_missing:
            L.append("- missing: %s" % m)
        for m in b.peer_failures:
            L.append("- failed: %s" % m)
        L.append("")
    L.extend(summary(b))
    for t in b.tables:
        L.append("## %s" % t.title)
        L.append("")
        L.append(t.desc)
        L.append("")
        if t.rows:
            L.extend(md_table(t))
        else:
            L.append("(no rows)")
        for m in t.notes:
            L.append("")
            L.append("Note: %s" % m)
        L.append("")

    p2 = paper_table2()
    synth = {t.key: t for t in b.tables if t.key in ("Phong1", "Phong2", "Ward")}
    if p2 and synth:
        L.append("## Paper Table 2 beside brdfwave --ratio")
        L.append("")
        L.append("Paper values are read from `%s` (the paper counts r_c in kept coefficients "
                 "of 8-byte doubles); brdfwave's R is in bytes against float32 (payload <= "
                 "4 x samples / R), so the columns are not the same quantity. The brdfwave "
                 "numbers come from this run." % TABLES_MD)
        L.append("")
        L.append("| R | data set | paper L1 % | paper L2 % | brdfwave bits/sample | "
                 "brdfwave rel L1 % | brdfwave rel L2 % |")
        L.append("|---:|---|---:|---:|---:|---:|---:|")
        for key in ("Phong1", "Phong2", "Ward"):
            t = synth.get(key)
            if t is None:
                continue
            for R in RATIOS:
                row = next((r for r in t.rows if r["codec"] == "brdfwave" and r["input"] == "f32"
                            and r["setting"] == "--ratio %d" % R), None)
                pv = p2.get(R, {}).get(key)
                if row is None or pv is None:
                    continue
                L.append("| %d | %s | %s | %s | %s | %s | %s |" % (
                    R, key, pv[0], pv[1], fmt_num(row["bits_per_sample"], "%.4g"),
                    fmt_num(row["rel_l1_pct"], "%.4g"), fmt_num(row["rel_l2_pct"], "%.4g")))
        L.append("")
    L.append("Field spectra read from `%s`." % spectra_src)
    L.append("")
    with open(REPORT_MD, "w") as f:
        f.write("\n".join(L))


# --------------------------------------------------------------------------
# main

def main():
    global PEER_JPEGLS
    bw = sys.argv[1] if len(sys.argv) > 1 else os.environ.get(
        "BW", os.path.join(ROOT, "build", "host", "brdfwave"))
    bw = os.path.abspath(bw)
    PEER_JPEGLS = os.path.abspath(os.environ.get("PEER_JPEGLS",
                                                 os.path.join(OUT_DIR, "peer_jpegls")))
    if not (os.path.isfile(bw) and os.access(bw, os.X_OK)):
        log("run_codec_bench: brdfwave CLI not found at %s (build it with `make`, or pass "
            "its path as argument or in BW)" % bw)
        return 2
    t_start = time.perf_counter()
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
    if os.path.isdir(TMP_DIR):
        shutil.rmtree(TMP_DIR)
    os.makedirs(TMP_DIR)

    b = Bench(bw)

    # ---- (a) field spectra
    src, files, refl = load_spectra()
    f32 = refl.astype(np.float32)
    u16 = np.clip(np.rint(refl * 10000.0), 0, 65535).astype(np.uint16)
    nspec, nband = f32.shape
    ds = DataSet("field", "field spectra", f32, ["--bands", str(nband)], "spectra")

    tf = Table("field_f32", "Field spectra, float32 reflectance (%d x %d)" % (nspec, nband),
               f32.astype(np.float64),
               "%d PSR-3500 spectra x %d channels, column `Reflect. [1.0]`, as float32; "
               "brdfwave gets `--bands %d` (a set of spectra). Errors in reflectance units. "
               "%d samples." % (nspec, nband, nband, f32.size))
    b.tables.append(tf)
    log("== %s" % tf.title)
    raw_f = b.tmp("field.f32")
    f32.astype("<f4").tofile(raw_f)
    # Lossless on float data needs values on an integer grid: the .sed files
    # themselves (reflectance in 1e-5 units), checked on the int32 samples.
    b.bw_row(tf, ds, files, "sed", ["--lossless"], "--lossless (.sed input, 1e-5 units)",
             ("lossless", 0), layout=[], native_i32=True,
             native_ref=np.rint(refl * 1e5))
    for tol in SPECTRA_TOLS:
        b.bw_row(tf, ds, raw_f, "f32", ["--max-error", "%g" % tol], "--max-error %g" % tol,
                 ("max_error", tol))
    for R in RATIOS:
        b.bw_row(tf, ds, raw_f, "f32", ["--ratio", str(R)], "--ratio %d" % R, ("ratio", R))
    peers_f32(b, tf, "field", f32, ["-1", str(f32.size)], SPECTRA_TOLS)

    tu = Table("field_u16", "Field spectra, 16-bit integers round(10000 r) (%d x %d)"
               % (nspec, nband), u16.astype(np.float64),
               "The same spectra as integers round(10000 x reflectance), clamped to 0..65535 "
               "(max %d). Errors in integer units (1 = 1e-4 reflectance), against the integers. "
               "%d samples." % (int(u16.max()), u16.size))
    b.tables.append(tu)
    log("== %s" % tu.title)
    raw_u = b.tmp("field.u16")
    u16.astype("<u2").tofile(raw_u)
    b.bw_row(tu, ds, raw_u, "u16", ["--lossless"], "--lossless", ("lossless", 0))
    for e in NEARS:
        b.bw_row(tu, ds, raw_u, "u16", ["--max-error", str(e)], "--max-error %d" % e,
                 ("max_error", e))
    for R in RATIOS:
        b.bw_row(tu, ds, raw_u, "u16", ["--ratio", str(R)], "--ratio %d" % R, ("ratio", R))
    peers_u16(b, tu, "field", u16, lambda d: d.astype(np.float64))

    # ---- (b) synthetic sets
    synth_sets = PAPER_SETS
    for key, synth_args, layout, desc in synth_sets:
        raw = b.tmp("%s.f32" % key)
        cmd = [bw, "synth"] + synth_args + ["-o", raw]
        try:
            run(cmd, "brdfwave synth (%s)" % key)
        except ToolError as e:
            log("FAIL " + str(e))
            b.cli_failures.append(str(e))
            continue
        n_out = 1024
        data = np.fromfile(raw, dtype="<f4")
        if data.size % n_out != 0 or data.size == 0:
            msg = "brdfwave synth (%s): %d floats, not a multiple of %d" % (key, data.size, n_out)
            log("FAIL " + msg)
            b.cli_failures.append(msg)
            continue
        a = data.reshape(-1, n_out)
        if not np.all(np.isfinite(a)):
            msg = "brdfwave synth (%s): non-finite values" % key
            log("FAIL " + msg)
            b.cli_failures.append(msg)
            continue
        fmax = float(a.max())
        scale = fmax / 65535.0
        q = np.clip(np.rint(a.astype(np.float64) / scale), 0, 65535).astype(np.uint16)
        t = Table(key, "%s (%d x %d, float32)" % (key, a.shape[0], a.shape[1]),
                  a.astype(np.float64),
                  "`brdfwave %s`: %s. Values %.6g .. %.6g. Errors in BRDF units (1/sr); `u16` "
                  "rows saw round(f / s) with s = max/65535 = %.6g and are scaled back by s. "
                  "%d samples." % (cmdline(["synth"] + synth_args), desc, float(a.min()), fmax,
                                   scale, a.size))
        b.tables.append(t)
        log("== %s" % t.title)
        dsb = DataSet(key, key, a, ["--bands", "1"] + layout, "brdf")
        tols = [s * scale for s in SYNTH_TOL_STEPS]
        for tol in tols:
            b.bw_row(t, dsb, raw, "f32", ["--max-error", "%.9g" % tol],
                     "--max-error %.4g" % tol, ("max_error", tol))
        for R in RATIOS:
            b.bw_row(t, dsb, raw, "f32", ["--ratio", str(R)], "--ratio %d" % R, ("ratio", R))
        rawq = b.tmp("%s_q.u16" % key)
        q.astype("<u2").tofile(rawq)
        back = lambda d, s=scale: np.asarray(d, dtype=np.float64) * s
        qref = q.astype(np.float64)
        for mode, setting, chk in ([(["--lossless"], "--lossless", ("lossless", 0))] +
                                   [(["--max-error", str(e)], "--max-error %d" % e,
                                     ("max_error", e)) for e in NEARS]):
            # contract checks on the integer data, metrics after scaling back
            b.bw_row(t, dsb, rawq, "u16", mode, setting, chk, to_ref=back, native_ref=qref)
        peers_f32(b, t, key, a, ["-2", str(a.shape[1]), str(a.shape[0])], tols)
        peers_u16(b, t, key, q, back)

    elapsed = time.perf_counter() - t_start
    write_reports(b, rel(src) if src.startswith(ROOT) else src, started, elapsed,
                  tool_versions(bw))
    log("wrote %s and %s (%.0f s)" % (rel(REPORT_MD), rel(REPORT_CSV), elapsed))
    if os.environ.get("BENCH_KEEP_TMP", "") in ("", "0"):
        shutil.rmtree(TMP_DIR, ignore_errors=True)
    if b.cli_failures or b.violations:
        log("run_codec_bench: brdfwave CLI: %d failure(s), %d contract violation(s); "
            "see the report" % (len(b.cli_failures), len(b.violations)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
