#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Device benchmark: the codec core on the emulated Cortex-M4.

Prepares the data sets as 16-bit sample files under build/bench/device/data/,
runs the image build/bench/device/bench_device.elf once per data set on
`qemu-system-arm -M mps2-an386 -icount shift=0` (deterministic: SysTick
advances one tick per 40 instructions), parses the image's lines and writes
build/bench/device.md (and the raw logs build/bench/device/<set>.log).

Data sets (16-bit unsigned integers):
  spectra32  the first 32 field spectra (name order) of tests/data/field_psr3500,
             round(reflectance * 10000), 32 x 1024 bands
  phong      brdfwave synth Phong kd=.75 ks=.25 n=20, level 4, 16 incoming,
             scaled so that the maximum is 65535
  ward       brdfwave synth Ward ax=.35 ay=.05 kd=.75 ks=.25, level 4 with
             --level-in 3 (level-in 4 does not fit the board's 4 MiB RAM), scaled
  refl81     a level-4 spectral reflectance, 1024 directions x 81 bands: the 60
             field spectra interpolated to 430..830 nm every 5 nm; direction t
             (geodesic order) takes spectrum floor(t * 60 / 1024)

Usage: /usr/bin/python3 tests/bench/device/run_device_bench.py
Environment: BW (default build/host/brdfwave), QEMU (qemu-system-arm),
BENCH_DEVICE_TIMEOUT (seconds per QEMU run, default 300).
`make bench-device` builds the image, the core libraries and runs this.
Exit status 0 if every run completed, every guarantee held and every payload
size equals the host CLI's; 1 otherwise (the report is written in every case).
"""

import bisect
import collections
import concurrent.futures
import datetime
import glob
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
OUT = os.path.join(ROOT, "build", "bench", "device")
DATA = os.path.join(OUT, "data")
REPORT = os.path.join(ROOT, "build", "bench", "device.md")
ELF = os.path.join(OUT, "bench_device.elf")
BW = os.environ.get("BW", os.path.join(ROOT, "build", "host", "brdfwave"))
QEMU = os.environ.get("QEMU", "qemu-system-arm")
TIMEOUT = int(os.environ.get("BENCH_DEVICE_TIMEOUT", "300"))
SPECTRA_DIR = os.path.join(ROOT, "tests", "data", "field_psr3500")
CROSS = "arm-none-eabi-"

SHAPE_SPECTRA, SHAPE_REFLECTANCE, SHAPE_ISO, SHAPE_FULL = 0, 1, 2, 3
MODES = ["lossless", "maxerr1", "maxerr4", "maxerr16", "ratio8", "ratio32"]
PRED_TARGET = 200  # instructions per sample of a prediction encode on the device
MODE_LABEL = {"lossless": "lossless", "maxerr1": "max-error 1", "maxerr4": "max-error 4",
              "maxerr16": "max-error 16", "ratio8": "bytes, ratio 8", "ratio32": "bytes, ratio 32"}
BASIS = {0: "haar", 1: "5/3", 2: "9/7", 3: "pred"}

failures = []


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def rel(p):
    return os.path.relpath(p, ROOT)


def run(cmd, timeout=600):
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError("%s: exit status %d: %s" % (" ".join(cmd), p.returncode,
                                                      p.stderr.decode(errors="replace")[-400:]))
    return p.stdout.decode(errors="replace")


# --------------------------------------------------------------------------
# data sets

class DataSet:
    def __init__(self, key, title, shape, level_out, level_in, n_in, bands, cli_args, desc):
        self.key, self.title = key, title
        self.shape, self.level_out, self.level_in = shape, level_out, level_in
        self.n_in, self.bands = n_in, bands
        self.cli_args = cli_args
        self.desc = desc
        self.path = os.path.join(DATA, key + ".u16")


def read_sed(path):
    with open(path, "r", encoding="latin-1") as f:
        lines = f.read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.strip().startswith("Data:"))
    titles = [t.strip() for t in lines[i + 1].split("\t")]
    col = next((k for k, t in enumerate(titles) if t.startswith("Reflect. [1.0]")), 4)
    wvl, refl = [], []
    for l in lines[i + 2:]:
        if l.strip():
            parts = l.split("\t")
            wvl.append(float(parts[0]))
            refl.append(float(parts[col]))
    return np.array(wvl), np.array(refl)


def to_u16(v, what):
    v = np.round(v)
    if v.min() < 0 or v.max() > 65535:
        raise SystemExit("run_device_bench: %s out of 16-bit range" % what)
    return v.astype("<u2")


def synth_scaled(args, name):
    f32 = os.path.join(DATA, name + ".f32")
    run([BW, "synth"] + args + ["-o", f32])
    a = np.fromfile(f32, dtype="<f4").astype(np.float64)
    return to_u16(a * (65535.0 / a.max()), name), float(a.max())


def prepare():
    os.makedirs(DATA, exist_ok=True)
    files = sorted(glob.glob(os.path.join(SPECTRA_DIR, "*.sed")))
    if len(files) < 32:
        raise SystemExit("run_device_bench: fewer than 32 .sed files in %s" % rel(SPECTRA_DIR))
    spectra = [read_sed(p) for p in files]
    sets = []

    rows = np.array([r for _, r in spectra[:32]])
    to_u16(rows * 10000.0, "spectra32").tofile(os.path.join(DATA, "spectra32.u16"))
    sets.append(DataSet(
        "spectra32", "field spectra", SHAPE_SPECTRA, 0, 0, 32, rows.shape[1],
        ["--bands", str(rows.shape[1])],
        "the first 32 of the %d field spectra in %s (file-name order, %s .. %s), "
        "round(reflectance x 10000): 32 spectra x %d bands"
        % (len(files), rel(SPECTRA_DIR), os.path.basename(files[0]),
           os.path.basename(files[31]), rows.shape[1])))

    u, mx = synth_scaled(["--model", "phong", "--kd", "0.75", "--ks", "0.25", "--n", "20",
                          "--level", "4", "--incoming", "16"], "phong")
    u.tofile(os.path.join(DATA, "phong.u16"))
    sets.append(DataSet(
        "phong", "Phong, level 4, 16 incoming", SHAPE_ISO, 4, 0, 16, 1,
        ["--bands", "1", "--level", "4", "--incoming", "16"],
        "`brdfwave synth --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16`, "
        "round(v x 65535 / %.7g): 16 incoming x 1024 outgoing" % mx))

    u, mx = synth_scaled(["--model", "ward", "--ax", "0.35", "--ay", "0.05", "--kd", "0.75",
                          "--ks", "0.25", "--level", "4", "--level-in", "3"], "ward")
    u.tofile(os.path.join(DATA, "ward.u16"))
    sets.append(DataSet(
        "ward", "Ward, level-in 3 x level 4", SHAPE_FULL, 4, 3, 0, 1,
        ["--bands", "1", "--level", "4", "--level-in", "3"],
        "`brdfwave synth --model ward --ax 0.35 --ay 0.05 --kd 0.75 --ks 0.25 --level 4 "
        "--level-in 3`, round(v x 65535 / %.7g): 256 incoming x 1024 outgoing. "
        "The paper's set has --level-in 4 (1024 x 1024 = 1,048,576 samples): its int32 "
        "samples alone would take the board's whole 4 MiB RAM, before the work buffer "
        "and the payload, so the incoming hemisphere is one level coarser here" % mx))

    wl_out = np.arange(430.0, 830.0 + 0.1, 5.0)
    res = []
    for wvl, r in spectra:
        m = (wvl >= 400.0) & (wvl <= 860.0)
        w, v = wvl[m], r[m]
        if np.any(np.diff(w) <= 0):
            raise SystemExit("run_device_bench: wavelengths not increasing in 400..860 nm")
        res.append(np.interp(wl_out, w, v))
    res = np.array(res)
    n_dir = 1024
    idx = (np.arange(n_dir) * len(files)) // n_dir
    refl = res[idx]
    to_u16(refl * 10000.0, "refl81").tofile(os.path.join(DATA, "refl81.u16"))
    sets.append(DataSet(
        "refl81", "spectral reflectance, level 4 x 81 bands", SHAPE_REFLECTANCE, 4, 0, 1,
        len(wl_out), ["--bands", str(len(wl_out)), "--level", "4"],
        "the %d field spectra linearly interpolated to 81 bands, 430..830 nm every 5 nm, "
        "round(reflectance x 10000); outgoing direction t = 0..1023 (geodesic order, where "
        "every subtree is a contiguous range) takes spectrum floor(t x %d / 1024), so runs of "
        "16-17 neighbouring triangles share one spectrum: 1024 directions x 81 bands"
        % (len(files), len(files))))
    return sets


# --------------------------------------------------------------------------
# the image

def qemu_cmd(ds):
    args = ["bench_device", ds.key, rel(ds.path), str(ds.shape), str(ds.level_out),
            str(ds.level_in), str(ds.n_in), str(ds.bands)]
    for a in args:
        if "," in a or " " in a:
            raise SystemExit("run_device_bench: argument %r has a comma or space" % a)
    return [QEMU, "-M", "mps2-an386", "-nographic", "-monitor", "none", "-icount", "shift=0",
            "-semihosting-config", "enable=on,target=native," + ",".join("arg=" + a for a in args),
            "-kernel", rel(ELF)]


def run_image(ds):
    cmd = qemu_cmd(ds)
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=TIMEOUT)
        out, rc = p.stdout.decode(errors="replace"), p.returncode
        err = p.stderr.decode(errors="replace")
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace")
        rc, err = None, "timed out after %d s" % TIMEOUT
    dt = time.perf_counter() - t0
    with open(os.path.join(OUT, ds.key + ".log"), "w") as f:
        f.write(out)
    return cmd, out, rc, err, dt


def kv(line):
    d = {}
    for tok in line.split()[1:]:
        if "=" in tok:
            k, v = tok.split("=", 1)
            d[k] = v
    return d


def parse(out):
    r = {"floors": {}, "rows": {}, "choice": {}, "fast": [], "pred": [], "phases": collections.OrderedDict(),
         "prof": {}, "stack": None, "mem": None, "end": None, "errors": []}
    cur = None
    for line in out.splitlines():
        tag = line.split(" ", 1)[0]
        if tag == "FLOOR":
            d = kv(line)
            r["floors"][d["name"]] = int(d["instr"])
        elif tag == "ROW":
            d = kv(line)
            r["rows"][d["mode"]] = d
        elif tag == "CHOICE":  # the basis choice with the device's coder
            d = kv(line)
            r["choice"][d["mode"]] = d
        elif tag == "FAST":  # prediction's rows apart from the transforms'
            d = kv(line)
            r["pred" if d["basis"] == "3" else "fast"].append(d)
        elif tag == "PHASE":
            d = kv(line)
            r["phases"][d["name"]] = d
        elif tag == "PROF":
            d = kv(line)
            cur = collections.Counter()
            r["prof"][d["what"]] = (d, cur)
        elif tag == "P" and cur is not None:
            _, a, c = line.split()
            cur[int(a, 16)] += int(c)
        elif tag == "STACK":
            r["stack"] = {k: int(v) for k, v in kv(line).items()}
        elif tag == "MEM":
            r["mem"] = {k: int(v) for k, v in kv(line).items()}
        elif tag == "END":
            r["end"] = kv(line)
        elif tag == "ERROR":
            r["errors"].append(line)
    return r


# --------------------------------------------------------------------------
# host cross-check: the CLI must produce payloads of the same size

def cli_size(ds, mode, n):
    out = os.path.join(DATA, "%s_%s.bwv" % (ds.key, mode))
    margs = {"lossless": ["--lossless"], "maxerr1": ["--max-error", "1"],
             "maxerr4": ["--max-error", "4"], "maxerr16": ["--max-error", "16"],
             "ratio8": ["--bytes", str(2 * n // 8)], "ratio32": ["--bytes", str(2 * n // 32)]}
    cmd = ([BW, "encode", "--input-format", "u16", "--symmetry", "none", "--no-metadata", "-i",
            ds.path, "-o", out]
           + ds.cli_args + margs[mode])
    try:
        run(cmd)
    except (RuntimeError, subprocess.TimeoutExpired) as e:
        return None, str(e)
    return os.path.getsize(out), " ".join([rel(BW)] + [rel(c) if os.path.isabs(c) else c
                                                       for c in cmd[1:]])


# --------------------------------------------------------------------------
# profile: PC bins -> functions (symbol table) and inlined functions (debug info)

def symbols():
    out = run([CROSS + "nm", "-n", "-S", ELF])
    syms = []
    for l in out.splitlines():
        p = l.split()
        if len(p) == 4 and p[2] in "tTW":
            syms.append((int(p[0], 16) & ~1, int(p[1], 16), p[3]))
        elif len(p) == 3 and p[1] in "tT":
            syms.append((int(p[0], 16) & ~1, 0, p[2]))
    syms.sort()
    return syms


def by_symbol(hist, syms):
    starts = [s[0] for s in syms]
    c = collections.Counter()
    for a, n in hist.items():
        i = bisect.bisect_right(starts, a) - 1
        c[syms[i][2] if i >= 0 else "?"] += n
    return c


def inline_names(addrs):
    """Innermost function (inlined or not) of each address, by addr2line."""
    if not addrs:
        return {}
    addrs = sorted(addrs)
    # without -i, addr2line names the innermost (possibly inlined) function
    out = run([CROSS + "addr2line", "-f", "-e", ELF] + ["0x%x" % a for a in addrs])
    lines = out.splitlines()
    inner = {}
    for k, a in enumerate(addrs):
        inner[a] = lines[2 * k] if 2 * k < len(lines) else "?"
    return inner


# --------------------------------------------------------------------------
# sizes and stack

def size_of(path):
    out = run([CROSS + "size", "-t", path])
    last = out.strip().splitlines()[-1].split()
    return int(last[0]), int(last[1]), int(last[2])


def core_linked_size(mapfile):
    """Bytes of the core's input sections kept in the image (after --gc-sections)."""
    text = data = bss = 0
    if not os.path.exists(mapfile):
        return None
    with open(mapfile) as f:
        lines = f.read().splitlines()
    try:
        start = next(i for i, l in enumerate(lines) if l.startswith("Linker script and memory map"))
    except StopIteration:
        return None
    pending = None
    for l in lines[start:]:
        m = re.match(r"^ (\.\S+)\s*$", l)
        if m:
            pending = m.group(1)
            continue
        m = re.match(r"^ (\.\S+)?\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S+\.o)\s*$", l)
        if m:
            name = m.group(1) or pending
            pending = None
            if "obj-O2/" not in m.group(4) or name is None:
                continue
            sz = int(m.group(3), 16)
            if name.startswith((".text", ".rodata")):
                text += sz
            elif name.startswith(".data"):
                data += sz
            elif name.startswith(".bss") or name.startswith("COMMON"):
                bss += sz
        else:
            pending = None
    return text, data, bss


def callgraph(objdir):
    """Nodes (function -> own frame bytes) and edges from GCC's .ci files of the
    core's current sources (not those a removed or renamed source left behind)."""
    frame, edges, local = {}, collections.defaultdict(set), {}
    for ci in sorted(glob.glob(os.path.join(objdir, "*.ci"))):
        src = os.path.join(ROOT, "firmware", "codec", os.path.basename(ci)[:-3] + ".c")
        if not os.path.exists(src):
            continue
        with open(ci) as f:
            for l in f:
                m = re.match(r'node: \{ title: "([^"]+)" label: "([^"]*)"', l)
                if m:
                    title, label = m.group(1), m.group(2)
                    b = re.search(r"\\n(\d+) bytes \(", label)
                    if b:
                        frame[title] = int(b.group(1))
                        local[title.rsplit(":", 1)[-1]] = title
                    continue
                m = re.match(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', l)
                if m:
                    edges[m.group(1)].add(m.group(2))
    def resolve(t):
        if t in frame:
            return t
        return local.get(t, t)  # a global defined in another file, or external
    g = {k: {resolve(t) for t in v} for k, v in edges.items()}
    return frame, g


def deepest(frame, g, root, skip=()):
    memo = {}

    def walk(n, stack):
        if n in memo:
            return memo[n]
        if n in stack:
            return (0, [n + " (recursion)"])
        own = frame.get(n)
        if own is None:
            return (0, [n + " (not in the core)"] if n not in ("__aeabi_uldivmod",) else [n])
        best = (0, [])
        for t in sorted(g.get(n, ())):
            if short(t) in skip:
                continue
            r = walk(t, stack | {n})
            if r[0] > best[0]:
                best = r
        res = (own + best[0], [n] + best[1])
        memo[n] = res
        return res

    titles = [t for t in frame if t.rsplit(":", 1)[-1] == root]
    if not titles:
        return None
    return walk(titles[0], frozenset())


def short(fn):
    return fn.rsplit(":", 1)[-1]


# --------------------------------------------------------------------------
# report

def fmt(x, d=1):
    return ("%." + str(d) + "f") % x


def peer_bits(ds):
    """Lossless bits/sample of CharLS (JPEG-LS, both orientations) and libaec
    (CCSDS-121, blocks of 16/32/64, RSI 128) on the data set's 16-bit file, as
    (name, bits, how) tuples; the device bench's peers for "fewer bits"."""
    res = []
    raw = ds.path
    n = os.path.getsize(raw) // 2
    w = ds.bands if ds.bands > 1 else 1024  # spectra, or the outgoing hemisphere, as rows
    h = n // w
    tmp = os.path.join(OUT, "peers")
    os.makedirs(tmp, exist_ok=True)
    jls = os.environ.get("PEER_JPEGLS", os.path.join(ROOT, "build", "bench", "peer_jpegls"))
    if os.path.exists(jls) and h * w == n:
        a = np.fromfile(raw, dtype="<u2").reshape(h, w)
        best = None
        for orient, arr in (("spectra as rows", a), ("spectra as columns", a.T)):
            src = os.path.join(tmp, ds.key + ".jls.u16")
            np.ascontiguousarray(arr).astype("=u2").tofile(src)
            out = os.path.join(tmp, ds.key + ".jls")
            dec = out + ".dec"
            p = subprocess.run([jls, "-b", "16", str(arr.shape[1]), str(arr.shape[0]), "0", src,
                                out, dec], capture_output=True)
            if p.returncode == 0 and np.array_equal(np.fromfile(dec, dtype="=u2"),
                                                      arr.reshape(-1)):
                bits = 8.0 * os.path.getsize(out) / n
                if best is None or bits < best[1]:
                    best = ("CharLS JPEG-LS lossless", bits, orient)
        if best:
            res.append(best)
    if shutil.which("aec"):
        best = None
        for j in (16, 32, 64):
            out = os.path.join(tmp, ds.key + ".aec")
            dec = out + ".dec"
            flags = ["-n", "16", "-j", str(j), "-r", "128"]
            p = subprocess.run(["aec"] + flags + [raw, out], capture_output=True)
            q = subprocess.run(["aec", "-d"] + flags + [out, dec], capture_output=True)
            if p.returncode == 0 and q.returncode == 0 and open(dec, "rb").read() == \
                    open(raw, "rb").read():
                bits = 8.0 * os.path.getsize(out) / n
                if best is None or bits < best[1]:
                    best = ("libaec CCSDS-121 lossless", bits, "-n 16 -j %d -r 128" % j)
        if best:
            res.append(best)
    return res


FAST_MODES = ["lossless", "maxerr1", "maxerr4", "maxerr16", "step8", "step64"]
BASIS_NAMES = {0: "Haar", 1: "5/3", 2: "9/7", 3: "prediction"}
LOSSY_TARGET = 40.0
LOSSLESS_TARGET = 85.0


def rice_rows(p):
    return [d for d in p["fast"] if d.get("coder", "rice") == "rice"]


MS_INSTR_TARGET = 120.0
MS_BYTES_TARGET = 1.03


def coders_section(A, sets, parsed):
    """The coders on the same one-pass encodes: bytes and instructions."""
    A("## The coders side by side (measured)")
    A("")
    A("The same one-pass encodes (basis fixed, no search) with each coder: the binary "
      "range coder (the default), the multi-symbol range coder (`BW_FLAG_MS`, `--coder ms`), "
      "the static-table coder (`BW_FLAG_RICE | BW_FLAG_MS`, `--coder tab`: tables counted "
      "over part of the body and sent ahead of it, docs/FORMAT.md, Body with TAB), Rice "
      "strips, and `BW_CODER_AUTO` (`--coder auto`, the device's default: for a set of "
      "spectra transformed the static tables, unless their counts put the body under half a "
      "bit a coefficient, else the multi-symbol coder). *encode* and *decode* in instructions per "
      "sample, every stage included; every row is decoded on the device and checked. Target: "
      "the device's coder within %g %% of the range coder's bytes for the same basis and "
      "mode, at no more than %g instructions per sample." % (
          (MS_BYTES_TARGET - 1) * 100, MS_INSTR_TARGET))
    A("")
    A("| data set | basis | mode | range bytes | range encode | ms bytes | ms / range | "
      "ms encode | ms decode | tab bytes | tab / range | tab encode | tab decode | "
      "rice bytes | rice encode | auto chose | auto encode |")
    A("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|")
    for ds in sets:
        by = {}
        for d in parsed[ds.key]["fast"]:
            by[(d.get("coder", "rice"), d["basis"], d["mode"])] = d
        for (coder, basis, mode), r in by.items():
            if coder != "range" or ("ms", basis, mode) not in by:
                continue
            n = int(r["samples"])
            cells = []
            for c in ("ms", "tab"):
                d = by.get((c, basis, mode))
                cells += ([d["bytes"], "%.4f" % (int(d["bytes"]) / int(r["bytes"])),
                           "%.1f" % (int(d["enc"]) / n), "%.1f" % (int(d["dec"]) / n)]
                          if d else ["-"] * 4)
                if d and d["status"] != "ok":
                    failures.append("%s %s %s basis %s: guarantee failed" % (
                        ds.key, c, mode, basis))
            ri, au = by.get(("rice", basis, mode)), by.get(("auto", basis, mode))
            cells += [ri["bytes"] if ri else "-", "%.1f" % (int(ri["enc"]) / n) if ri else "-",
                      au.get("chosen", "-") if au else "-",
                      "%.1f" % (int(au["enc"]) / n) if au else "-"]
            A("| %s | %s | %s | %s | %.1f | %s |" % (
                ds.key, BASIS_NAMES.get(int(basis), basis) if ds.bands > 1 else "-", mode,
                r["bytes"], int(r["enc"]) / n, " | ".join(cells)))
    A("")


def pred_section(A, sets, parsed):
    if not any(parsed[ds.key]["pred"] for ds in sets):
        return
    A("## Prediction with each coder (measured)")
    A("")
    A("Prediction (`BW_BASIS_PRED`) on the sets of spectra, one pass, with each strip coder "
      "and with `BW_CODER_AUTO` (`--coder auto`, the device's default: Rice strips for "
      "prediction errors whose bit lengths average at least 7/8 and whose Rice payload "
      "stays within 248/256 of an order-0 coding of them, else the multi-symbol coder). "
      "Bytes and instructions per sample (encode, every stage included); every row is "
      "decoded on the device and checked. Target: at most %g instructions per sample with "
      "the device's coder, within %g %% of the range coder's bytes." % (
          PRED_TARGET, (MS_BYTES_TARGET - 1) * 100))
    A("")
    A("| data set | mode | range bytes | range encode | ms bytes | ms encode | rice bytes | "
      "rice encode | auto chose | auto bytes | auto / range | auto encode | auto decode |")
    A("|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")
    for ds in sets:
        by = {(d["coder"], d["mode"]): d for d in parsed[ds.key]["pred"]}
        for mode in FAST_MODES:
            a, g = by.get(("auto", mode)), by.get(("range", mode))
            if not (a and g):
                continue
            n = int(a["samples"])
            cells = []
            for c in ("range", "ms", "rice"):
                d = by.get((c, mode))
                cells += [d["bytes"], "%.1f" % (int(d["enc"]) / n)] if d else ["-", "-"]
            A("| %s | %s | %s | %s | %s | %.4f | %.1f | %.1f |" % (
                ds.key, mode, " | ".join(cells), a.get("chosen", "-"), a["bytes"],
                int(a["bytes"]) / int(g["bytes"]), int(a["enc"]) / n, int(a["dec"]) / n))
            for d in by.values():
                if d["mode"] == mode and d["status"] != "ok":
                    failures.append("%s prediction %s %s: guarantee failed" % (
                        ds.key, d["coder"], mode))
    A("")


def choice_row(A, ds, rows, label, every_bytes, every_basis, every_enc, fixed_enc):
    """Target 2, the basis choice of BW_EFFORT_FAST, from rows by mode: its
    encode against the same with the basis named, its payload against
    trying every basis (every_bytes, every_basis; a byte budget: the squared
    error against the fast encode with each basis named) and what trying
    every basis costs (every_enc against fixed_enc)."""
    worst, worst_b, worst_all, worst_best = None, None, None, None
    for m in MODES:
        row = rows.get(m)
        if not (row and "bytes_quick" in row and int(row.get("enc_quick", 0))):
            continue
        if row.get("status") != "ok":
            worst = (float("inf"), m, 0.0)
        x = int(row["enc_quick"]) / int(row["enc_quick_fixed"])
        if m.startswith("ratio"):
            # every payload fills the budget: the error, against the same
            # encode with each basis named (its smallest)
            e = int(row["sse_quick"]) / max(1, int(row["sse_every_fast"]))
            every = int(row["basis_every_fast"])
            if "sse" in row:  # against the search, which holds the budget's own error
                eb = int(row["sse_quick"]) / max(1, int(row["sse"]))
                if worst_best is None or eb > worst_best[0]:
                    worst_best = (eb, m)
        else:
            e = int(row["bytes_quick"]) / int(row[every_bytes])
            every = int(row[every_basis])
        xa = int(row[every_enc]) / int(row[fixed_enc])
        if worst is None or x > worst[0]:
            worst = (x, m, int(row["enc_quick"]) / int(row["samples"]))
        if worst_b is None or e > worst_b[0]:
            worst_b = (e, m, BASIS_NAMES.get(int(row["basis_quick"]), "-"),
                       BASIS_NAMES.get(every, "-"))
        if worst_all is None or xa > worst_all[0]:
            worst_all = (xa, m)
    if not worst or not worst_b:
        return
    ok = worst[0] <= 1.5 and worst_b[0] <= 1.01
    A("| %s | basis choice%s <= 1.5 x the fixed basis, payload within 1 %% of trying every "
      "basis | %.2f x at most (%s, %.1f instr/sample); payload (byte budget: squared error) at "
      "most %.4f x (%s: chose %s, every basis %s)%s; trying every basis: %.2f x (%s) | %s |" % (
          ds.key, label, worst[0], worst[1], worst[2], worst_b[0], worst_b[1], worst_b[2],
          worst_b[3],
          "" if worst_best is None else
          "; byte budget against the search (`BW_EFFORT_BEST`) instead: "
          "squared error at most %.4f x (%s)" % worst_best,
          worst_all[0], worst_all[1], "yes" if ok else "no"))


def device_targets_section(A, sets, parsed):
    """The device encode's targets: the byte budget and the basis choice of
    BW_EFFORT_FAST (the device's default) against one fixed encode of the
    same run."""
    A("## Targets of the device encode (measured)")
    A("")
    A("`BW_EFFORT_FAST` is the default of a device encode (`--effort fast`; the host's is "
      "`best`). Byte budget: the whole encode with the basis fixed to the one chosen "
      "(one encode whose quantiser runs ahead of the coder a chunk of vectors at a time, "
      "each chunk at a step of its own steered by the bytes coded so far against the "
      "estimate, recorded in the payload (record 0x05, docs/FORMAT.md, Chunk steps); where "
      "that one does not land within 1 % under the budget, the step estimated from a "
      "histogram of the coefficients and corrected by the size of each encode until one "
      "does) against one encode at a "
      "fixed step with the same coder and basis (the `step8` row of 'The coders side by "
      "side'); target at most 1.5 x, landing within 1 % under the budget (or the lossless "
      "payload, where that fits). *the search* is the same figure for `BW_EFFORT_BEST` (the "
      "*encode, basis fixed* column above), *error* the fast payload's squared error against "
      "the search's. Basis choice: on parts of the measurement, an eighth of it, the "
      "wavelets are ranked by the bits of an order-0 coding of their coefficients, "
      "subband by subband (no coding), the first of them and prediction (where it "
      "applies) code the parts, then the whole is coded once with the basis that coded "
      "them smallest; for a byte budget, half of the parts, ranked by their exact "
      "coefficients; "
      "against one encode with the basis it chose fixed, target at most 1.5 x, with "
      "payloads within 1 % of trying every basis (`BW_EFFORT_BEST`, the *encode* column "
      "above, the host's default); for a byte budget, whose payloads all fill the budget, "
      "the squared error within 1 % of the smallest of the same encode (`BW_EFFORT_FAST`) "
      "with each transform basis named (the budget's own error against the search's is "
      "in the budget rows; the figure against the search's, which holds both, follows "
      "it). *trying every basis* gives the same ratio for `BW_EFFORT_BEST`. The rows "
      "*with the device's coder* measure the same with `BW_CODER_AUTO` (`--coder auto`, "
      "the device's default: Rice strips or the multi-symbol coder for prediction, the "
      "multi-symbol coder for the wavelets), against the same encode with the basis "
      "named and against `BW_EFFORT_BEST` with the same coder; where a byte budget's "
      "search is the host's default, *trying every basis* includes it.")
    A("")
    A("| data set | target | figure | met |")
    A("|---|---|---|---|")
    for ds in sets:
        r = parsed[ds.key]
        fast = {(d.get("coder", "rice"), d["basis"], d["mode"]): d for d in r["fast"]}
        for m in ("ratio8", "ratio32"):
            row = r["rows"].get(m)
            if not row or "bytes" not in row or not int(row.get("enc_quick_fixed", 0)):
                continue
            n = int(row["samples"])
            one = fast.get(("range", row["basis_quick"], "step8")) if ds.bands > 1 else next(
                (d for k, d in fast.items() if k[0] == "range" and k[2] == "step8"), None)
            if not one:
                continue
            enc = int(row["enc_quick_fixed"])
            search = int(row["enc_fixed"]) or int(row["enc"])
            x = enc / int(one["enc"])
            land = int(row["bytes_quick"]) / int(row["budget"])
            exact = row.get("worst_quick") == "0"
            err = ("exact" if int(row["sse_quick"]) == 0 else "error %.3f x the search's" % (
                int(row["sse_quick"]) / max(1, int(row["sse"]))))
            A("| %s | budget %s: <= 1.5 x one encode, within 1 %% under | %.2f x (%.1f vs %.1f "
              "instr/sample), %d of %s bytes (%s), %s; the search: %.1f x | %s |" % (
                  ds.key, m[5:], x, enc / n, int(one["enc"]) / n, int(row["bytes_quick"]),
                  row["budget"], "lossless, it fits" if exact else "%.4f" % land,
                  err, search / int(one["enc"]),
                  "yes" if x <= 1.5 and (exact or 0.99 <= land <= 1.0) else "no"))
        if ds.bands > 1:
            choice_row(A, ds, r["rows"], "", "bytes", "basis", "enc", "enc_fixed")
            choice_row(A, ds, r["choice"], " with the device's coder (`--coder auto`)",
                       "bytes_every", "basis_every", "enc_every", "enc_quick_fixed")
        # the device's coder (auto), every transform basis and mode of the
        # one-pass rows
        by = {(d.get("coder", "rice"), d["basis"], d["mode"]): d for d in r["fast"]}
        worst_x, worst_b, chose = None, None, collections.Counter()
        for (coder, basis, mode), d in by.items():
            if coder != "auto" or ("range", basis, mode) not in by:
                continue
            x = int(d["enc"]) / int(d["samples"])
            b = int(d["bytes"]) / int(by[("range", basis, mode)]["bytes"])
            label = "%s %s, %s" % (BASIS_NAMES.get(int(basis), "-") if ds.bands > 1 else "-",
                                   mode, d.get("chosen", "-"))
            chose[d.get("chosen", "-")] += 1
            if worst_x is None or x > worst_x[0]:
                worst_x = (x, label)
            if worst_b is None or b > worst_b[0]:
                worst_b = (b, label)
        if worst_x:
            A("| %s | the device's coder (auto) <= %g instr/sample, within %g %% of the "
              "range coder's bytes, every basis and mode | %.1f instr/sample at most (%s); "
              "bytes %.4f x at most (%s); chose %s | %s |" % (
                  ds.key, MS_INSTR_TARGET, (MS_BYTES_TARGET - 1) * 100, worst_x[0], worst_x[1],
                  worst_b[0], worst_b[1],
                  ", ".join("%s %d" % kv for kv in sorted(chose.items())),
                  "yes" if worst_x[0] <= MS_INSTR_TARGET and worst_b[0] <= MS_BYTES_TARGET
                  else "no (%.2f x the instructions, %.4f x the bytes)" % (
                      worst_x[0] / MS_INSTR_TARGET, worst_b[0])))
        # prediction with the device's coder (auto), every mode of 'Prediction
        # with each coder'
        by = {(d["coder"], d["mode"]): d for d in r["pred"]}
        rows = []
        for (coder, mode), d in by.items():
            g = by.get(("range", mode))
            if coder == "auto" and g:
                rows.append((int(d["enc"]) / int(d["samples"]), int(d["bytes"]) / int(g["bytes"]),
                             mode, d.get("chosen", "-")))
        if rows:
            miss = [x for x in rows if x[0] > PRED_TARGET or x[1] > MS_BYTES_TARGET]
            A("| %s | prediction with the device's coder (auto) <= %g instr/sample, within %g %% "
              "of the range coder's bytes, every mode | %s; the range coder: %s | %s |" % (
                  ds.key, PRED_TARGET, (MS_BYTES_TARGET - 1) * 100,
                  ", ".join("%s %.1f (%s, bytes %.4f x)" % (m, x, c, b)
                            for x, b, m, c in sorted(rows, key=lambda t: FAST_MODES.index(t[2]))),
                  ", ".join("%s %.1f" % (m, int(by[("range", m)]["enc"]) / int(
                      by[("range", m)]["samples"])) for m in FAST_MODES if ("range", m) in by),
                  "yes" if not miss else "no: %s" % ", ".join(
                      "%s (%.2f x the instructions)" % (x[2], x[0] / PRED_TARGET) for x in miss)))
    A("")


def fast_section(A, sets, parsed, peers):
    A("## The Rice coder on the device (measured)")
    A("")
    A("`BW_FLAG_RICE` (`brdfwave encode --coder rice`): the strips of 32 coded with adaptive "
      "Rice codes (bw_rice.h) instead of the range coder, with the basis fixed (one pass). "
      "Same image, same samples, same run as above. *encode* is `bw_encode` without a "
      "verify buffer; every row is decoded on the device and checked (lossless exact, "
      "max-error within E). step S: `BW_MODE_STEP` with a quantiser step of S sample units.")
    A("")
    A("| data set | basis | mode | payload bytes | bits/sample | max abs error | encode | "
      "decode |")
    A("|---|---|---|---:|---:|---:|---:|---:|")
    best = {}
    for ds in sets:
        for d in rice_rows(parsed[ds.key]):
            n = int(d["samples"])
            bits = 8.0 * int(d["bytes"]) / n
            enc = int(d["enc"]) / n
            A("| %s | %s | %s | %s | %.3f | %s | %.1f | %.1f |" % (
                ds.key, BASIS_NAMES.get(int(d["basis"]), d["basis"]) if ds.bands > 1 else "-",
                d["mode"], d["bytes"], bits, d["worst"], enc, int(d["dec"]) / n))
            if d["status"] != "ok":
                failures.append("%s rice %s basis %s: guarantee failed" % (ds.key, d["mode"],
                                                                        d["basis"]))
            key = (ds.key, "lossless" if d["mode"] == "lossless" else "lossy")
            if key not in best or enc < best[key][0]:
                best[key] = (enc, bits, d)
    A("")
    A("### Targets")
    A("")
    A("Lossless: encode below %g instructions per sample (libaec's 85-97, published anchor "
      "above) while coding fewer bits than CharLS JPEG-LS and libaec on the same samples "
      "(both measured by this run on the host, bits are platform independent). Lossy: a full "
      "encode (one pass, fixed basis, any lossy row above) within %g instructions per "
      "sample. The targets are set against the anchors, which were measured on spectra32; "
      "the other data sets are held to the same figures here for comparison." % (
          LOSSLESS_TARGET, LOSSY_TARGET))
    A("")
    A("| data set | target | ours: fastest row | peers (same samples) | met |")
    A("|---|---|---|---|---|")
    for ds in sets:
        pk = peers.get(ds.key, [])
        # lossless: the fastest lossless row that codes fewer bits than every peer
        rows = [d for d in rice_rows(parsed[ds.key]) if d["mode"] == "lossless"]
        peer_txt = "; ".join("%s %.3f b/s (%s)" % p for p in pk) or "not measured"
        if rows:
            cands = []
            for d in rows:
                n = int(d["samples"])
                bits = 8.0 * int(d["bytes"]) / n
                if pk and all(bits < p[1] for p in pk):
                    cands.append((int(d["enc"]) / n, bits, d))
            if cands:
                enc, bits, d = min(cands, key=lambda c: c[0])
                met = "yes" if enc < LOSSLESS_TARGET else "no (%.2f x the target)" % (
                    enc / LOSSLESS_TARGET)
                A("| %s | lossless < %g instr/sample, fewer bits than the peers | %.1f instr/"
                  "sample, %.3f b/s (%s) | %s | %s |" % (
                      ds.key, LOSSLESS_TARGET, enc, bits,
                      BASIS_NAMES.get(int(d["basis"]), "-"), peer_txt, met))
            elif pk:
                e, b, d = best[(ds.key, "lossless")]
                A("| %s | lossless < %g instr/sample, fewer bits than the peers | no row codes "
                  "fewer bits (fastest: %.1f instr/sample at %.3f b/s) | %s | no |" % (
                      ds.key, LOSSLESS_TARGET, e, b, peer_txt))
        if (ds.key, "lossy") in best:
            enc, bits, d = best[(ds.key, "lossy")]
            met = "yes" if enc <= LOSSY_TARGET else "no (%.2f x the target)" % (
                enc / LOSSY_TARGET)
            A("| %s | lossy <= %g instr/sample | %.1f instr/sample (%s, %s, %.3f b/s) | | %s |"
              % (ds.key, LOSSY_TARGET, enc, d["mode"], BASIS_NAMES.get(int(d["basis"]), "-"),
                 bits, met))
    A("")


def main():
    if not os.path.exists(ELF):
        raise SystemExit("run_device_bench: %s missing (make bench-device builds it)" % rel(ELF))
    t_start = time.perf_counter()
    sets = prepare()
    log("device bench: %d data sets, QEMU runs in parallel" % len(sets))

    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(sets) + 1) as ex:
        futs = {ex.submit(run_image, ds): ds.key for ds in sets}
        # the smallest set a second time: the counts must repeat exactly
        rep = ex.submit(run_image, next(d for d in sets if d.key == "phong"))
        cli = {}
        for ds in sets:
            n = os.path.getsize(ds.path) // 2
            for m in MODES:
                cli[(ds.key, m)] = ex.submit(cli_size, ds, m, n)
        for f, key in futs.items():
            results[key] = f.result()
        rep_res = rep.result()
        cli = {k: v.result() for k, v in cli.items()}

    parsed = {}
    for ds in sets:
        cmd, out, rc, err, dt = results[ds.key]
        r = parse(out)
        r["cmd"], r["rc"], r["err"], r["wall"] = cmd, rc, err, dt
        parsed[ds.key] = r
        if rc != 0 or not r["end"] or r["end"].get("status") != "ok":
            failures.append("%s: image exit status %s %s %s" % (ds.key, rc, err.strip()[-200:],
                                                                " ".join(r["errors"])))
        log("  %-10s exit %s, %.1f s wall" % (ds.key, rc, dt))
    def numeric(o):
        return [l for l in o.splitlines() if not l.startswith("MEM")]
    repeat_same = rep_res[2] == 0 and numeric(rep_res[1]) == numeric(results["phong"][1])
    if not repeat_same:
        failures.append("phong: a second run printed different counts")

    syms = symbols()
    mem_sizes = {}
    for t, opt in (("mcu", "-Os"), ("qemu", "-O2")):
        lib = os.path.join(ROOT, "build", t, "libbwcore.a")
        mem_sizes[t] = (opt, lib, size_of(lib) if os.path.exists(lib) else None)
    img = size_of(ELF)
    core_img = core_linked_size(os.path.join(OUT, "bench_device.map"))
    stacks = {}
    for opt in ("O2", "Os"):
        frame, g = callgraph(os.path.join(OUT, "obj-" + opt))
        stacks[opt] = {r: deepest(frame, g, r) for r in ("bw_encode_ctx", "bw_decode_ctx")}
        stacks[opt]["device"] = deepest(frame, g, "bw_encode_ctx", skip=("verify_payload",))

    L = []
    A = L.append
    qv = run([QEMU, "--version"]).splitlines()[0]
    gv = run([CROSS + "gcc", "--version"]).splitlines()[0]
    A("# Codec core on the emulated Cortex-M4")
    A("")
    A("Written by `make bench-device` (tests/bench/device/run_device_bench.py) on %s."
      % datetime.datetime.now().strftime("%Y-%m-%d %H:%M"))
    A("")
    A("Every number in the tables below was measured by this run unless it is marked as a "
      "published anchor. Board: QEMU `mps2-an386` (Cortex-M4), %s, "
      "`-icount shift=0`: one instruction per ns of virtual time, SysTick (25 MHz) one tick per "
      "40 instructions, so counts are deterministic and have a resolution of 40 instructions. "
      "Image: %s, core at `-O2 -mcpu=cortex-m4 -mthumb -mfloat-abi=soft`, newlib with "
      "semihosting (rdimon). One QEMU run of the one image per data set measures the floors "
      "and the codec on the same samples; the samples reach the image as a 16-bit file read "
      "through semihosting, and are given to the codec as int32."
      % (qv, gv))
    A("")
    A("Instructions are per input sample. *encode* is `bw_encode` without a verify buffer "
      "(the device path); *encode + verify* passes the verify buffer (the encoder decodes its "
      "own payload and checks the guarantee); *decode* is `bw_decode`. The basis is "
      "`BW_BASIS_AUTO` (the CLI's default): for a set with a spectral axis the encoder codes "
      "every basis (for sets of spectra in lossless and max-error modes also prediction, "
      "`pred`) and keeps the best, so *basis fixed* gives the same encode with the "
      "chosen basis named up front (same payload); *effort fast* is the device's default "
      "(`BW_EFFORT_FAST`: the basis chosen on an eighth of the data, a byte budget met in "
      "one encode that steers a step per chunk; 'Targets of the device encode' below). "
      "Modes: lossless; max-error E; bytes: "
      "budget = 2 x samples / R bytes (ratio R against the 16-bit raw samples), payload "
      "including its header and CRC. ÷ memcpy: instructions per sample divided by "
      "the memcpy floor of the same data set in the same run.")
    A("")

    # main table
    A("## Instructions per sample (measured)")
    A("")
    A("| data set | mode | samples | payload bytes | bits/sample | max abs error | basis "
      "| encode | encode, basis fixed | encode + verify | decode | encode ÷ memcpy "
      "| decode ÷ memcpy | = host CLI | encode, effort fast: bytes, instr/sample |")
    A("|---|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---|---|")
    for ds in sets:
        r = parsed[ds.key]
        fl = r["floors"]
        for m in MODES:
            row = r["rows"].get(m)
            if not row or "bytes" not in row:
                A("| %s | %s | | | | | | failed | | | | | | | |" % (ds.key, MODE_LABEL[m]))
                continue
            n = int(row["samples"])
            b = int(row["bytes"])
            mc = fl["memcpy"] / n
            enc, encv, dec = int(row["enc"]) / n, int(row["enc_verify"]) / n, int(row["dec"]) / n
            encf = int(row["enc_fixed"]) / n if int(row["enc_fixed"]) else None
            hb, hcmd = cli[(ds.key, m)]
            bv = int(row["bytes_verify"])
            if hb is None:
                hostcol = "CLI failed"
                failures.append("%s %s: host CLI failed: %s" % (ds.key, m, hcmd))
            elif hb == bv:
                hostcol = "yes"
            else:
                hostcol = "no (%d)" % hb
                failures.append("%s %s: device %d bytes, host CLI %d" % (ds.key, m, bv, hb))
            bcol = str(b) if bv == b else "%d (verify: %d)" % (b, bv)
            fastcol = ("%s, %s" % (row["bytes_quick"], fmt(int(row["enc_quick"]) / n))
                       if int(row.get("enc_quick", 0)) else "as *encode*")
            A("| %s | %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                ds.key, MODE_LABEL[m], n, bcol, fmt(8.0 * b / n, 3), row["worst"],
                BASIS.get(int(row["basis"]), row["basis"]) if ds.bands > 4 else "-",
                fmt(enc), fmt(encf) if encf else "-", fmt(encv), fmt(dec),
                fmt(enc / mc), fmt(dec / mc), hostcol, fastcol))
            if row.get("status") != "ok":
                failures.append("%s %s: guarantee or payload check failed" % (ds.key, m))
    A("")
    A("= host CLI: the payload size equals that of `brdfwave encode --input-format u16 "
      "--symmetry none` with the same mode on the same file (the image encodes without the "
      "mirror flag, which the CLI otherwise tries on directional data; the CLI encodes with its verify buffer, so this "
      "compares with the *encode + verify* payload; where the two differ the table gives "
      "both). Max abs error: decoded against the input, in sample units (16-bit scale).")
    A("")

    peers = {}
    for ds in sets:
        try:
            peers[ds.key] = peer_bits(ds)
        except (OSError, ValueError) as e:
            log("  peers on %s: %s" % (ds.key, e))
    fast_section(A, sets, parsed, peers)
    coders_section(A, sets, parsed)
    pred_section(A, sets, parsed)
    device_targets_section(A, sets, parsed)

    # floors
    A("## Floors (measured, same image and samples)")
    A("")
    A("| data set | samples | memcpy | first difference | CRC-32, 256-entry table | "
      "CRC-32, the core's nibble table |")
    A("|---|---:|---:|---:|---:|---:|")
    for ds in sets:
        fl = parsed[ds.key]["floors"]
        if "memcpy" not in fl:
            continue
        n = int(parsed[ds.key]["rows"].get("lossless", {}).get("samples", 0)) or None
        if not n:
            continue
        A("| %s | %d | %s | %s | %s | %s |" % (
            ds.key, n, fmt(fl["memcpy"] / n, 2), fmt(fl["diff"] / n, 2),
            fmt(fl["crc32_table"] / n, 2), fmt(fl["crc32_core"] / n, 2)))
    A("")
    A("Instructions per sample. memcpy: newlib's `memcpy` of the 2 x samples bytes; first "
      "difference: `d[i] = x[i] - x[i-1]` from the uint16 buffer into an int32 buffer; CRC-32: "
      "reflected 0xEDB88320, a byte at a time over the 2 x samples bytes, with a 256-entry "
      "table (1 KiB) and with the core's 16-entry nibble table (`bw_crc32`, two lookups a "
      "byte, which the encoder and decoder run over the payload). An empty interval "
      "(two counter reads) measured %s instructions (the counter's step is 40) and is not "
      "subtracted." % " or ".join(sorted({str(parsed[d.key]["floors"].get("empty"))
                                           for d in sets})))
    A("")
    A("### Published anchors (not measured by this run)")
    A("")
    A("Quoted for reading the tables above against; measured the same way on this board "
      "(QEMU mps2-an386, -icount shift=0, SysTick) on the same data:")
    A("")
    A("| | instructions per sample | bits/sample |")
    A("|---|---:|---:|")
    A("| memcpy | 1.1 | |")
    A("| first difference | 6.0 | |")
    A("| table CRC-32 | 14.0 | |")
    A("| libaec 1.0.6 lossless encode, -O2 | 85-97 | 6.57 |")
    A("| CharLS 2.4.1 JPEG-LS lossless encode | 216 | 6.35 |")
    A("")

    # phases and profile
    A("## Where the instructions go (measured)")
    A("")
    A("The transforms alone, called on the same samples in the same run (`bw_spec_fwd` on "
      "every spectrum with the basis the lossless encode chose, 5/3 where it chose "
      "prediction, `bw_biohaar_fwd` on the "
      "outgoing and incoming hemispheres, and their inverses), the core's CRC-32 over the "
      "lossless payload, and an encode/decode with a quantiser step so large that every "
      "coefficient becomes zero (`BW_MODE_STEP`, `step_q8` = 0xFFFFFFFF: load, range "
      "check, transform, per-element quantiser, one presence flag per strip of 32, CRC — "
      "everything but the coding of values). Instructions per sample:")
    A("")
    A("| data set | encode lossless (basis fixed) | spectral fwd | Bio-Haar fwd | "
      "payload CRC | all-zero encode | decode lossless | spectral inv | Bio-Haar inv | "
      "all-zero decode |")
    A("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for ds in sets:
        r = parsed[ds.key]
        row = r["rows"].get("lossless")
        ph = r["phases"]
        if not row or "enc" not in row:
            continue
        n = int(row["samples"])

        def ps(*names):
            v = [int(ph[k]["instr"]) for k in names if k in ph]
            return fmt(sum(v) / n) if v else "-"
        encl = int(row["enc_fixed"]) or int(row["enc"])
        A("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            ds.key, fmt(encl / n), ps("spectral_fwd"), ps("biohaar_out_fwd", "biohaar_in_fwd"),
            ps("payload_crc"), ps("encode_all_zero"), fmt(int(row["dec"]) / n),
            ps("spectral_inv"), ps("biohaar_out_inv", "biohaar_in_inv"), ps("decode_all_zero")))
    A("")
    A("PC sampling in the same image (separate runs, not the timed ones): CMSDK timer 0 "
      "interrupts every 920 instructions and the handler counts the interrupted address; "
      "shares of the samples by function as linked (-O2 inlines the range coder, the strip "
      "walk and `code_body` into `encode_pass` / `decode_checked`) and, second, by the "
      "innermost source function (debug line info) at the sampled address.")
    A("")
    all_addrs = set()
    for ds in sets:
        for _, (_, hist) in parsed[ds.key]["prof"].items():
            all_addrs.update(hist.keys())
    inner = inline_names(all_addrs)
    for what, label in (("encode_lossless", "lossless encode, basis fixed"),
                        ("decode_lossless", "lossless decode"),
                        ("encode_ratio8", "bytes encode, ratio 8, basis fixed"),
                        ("encode_rice_lossless", "Rice lossless encode, 5/3"),
                        ("encode_rice_maxerr4", "Rice max-error 4 encode, 5/3"),
                        ("encode_ms_lossless", "multi-symbol lossless encode, 5/3"),
                        ("encode_ms_maxerr4", "multi-symbol max-error 4 encode, 5/3")):
        A("**%s** — share of samples, top functions:" % label)
        A("")
        A("| data set | samples | as linked | innermost source function |")
        A("|---|---:|---|---|")
        for ds in sets:
            pr = parsed[ds.key]["prof"].get(what)
            if not pr:
                continue
            d, hist = pr
            tot = sum(hist.values())
            if not tot:
                continue
            c1 = by_symbol(hist, syms)
            c2 = collections.Counter()
            for a, k in hist.items():
                c2[inner.get(a, "?")] += k
            top1 = ", ".join("%s %d%%" % (f, round(100.0 * k / tot)) for f, k in c1.most_common(6)
                             if round(100.0 * k / tot) >= 1)
            top2 = ", ".join("%s %d%%" % (f, round(100.0 * k / tot)) for f, k in c2.most_common(8)
                             if round(100.0 * k / tot) >= 1)
            A("| %s | %d | %s | %s |" % (ds.key, tot, top1, top2))
        A("")

    # memory
    A("## Flash and RAM (measured)")
    A("")
    A("`arm-none-eabi-size` (text includes read-only data; bytes):")
    A("")
    A("| what | text | data | bss |")
    A("|---|---:|---:|---:|")
    for t, (opt, lib, sz) in mem_sizes.items():
        if sz:
            A("| codec core library %s (`make TARGET=%s`, %s), every object | %d | %d | %d |"
              % (opt, t, rel(lib), sz[0], sz[1], sz[2]))
        else:
            A("| codec core library %s (`make TARGET=%s`) | not built | | |" % (opt, t))
    if core_img:
        A("| codec core -O2 as linked into the bench image (after --gc-sections) | %d | %d | %d |"
          % core_img)
    A("| bench image %s (core, startup, board, newlib with semihosting, the arena) | %d | %d | %d |"
      % (rel(ELF), img[0], img[1], img[2]))
    A("")
    A("The image's bss is the %d-byte arena from which each run carves its buffers, plus "
      "a 128 KiB profile histogram. Buffers per data set as the image carved them (bytes; the "
      "codec itself needs `work` and, for decoding, the output; `verify` only for the "
      "self-check; the payload area is what was left, capped at `bw_payload_bound`):"
      % (parsed[sets[0].key]["mem"] or {}).get("arena", 0))
    A("")
    A("| data set | samples as int32 | work | verify | payload area |")
    A("|---|---:|---:|---:|---:|")
    for ds in sets:
        m = parsed[ds.key]["mem"]
        if m:
            A("| %s | %d | %d | %d | %d |" % (ds.key, m["x"], m["work"], m["verify"],
                                              m["out_cap"]))
    A("")
    A("Stack. Static: GCC's `-fstack-usage` / `-fcallgraph-info=su` frames of the core "
      "compiled in build/bench/device/obj-O2 and obj-Os, summed along the deepest call "
      "chain from the entry point (inlined functions are inside their caller's frame; "
      "library calls such as memset/memcpy and the 64-bit division helpers count 0). "
      "Measured: the stack painted with a pattern before each call and scanned after, "
      "bytes below the caller's stack pointer, maximum over all modes and data sets "
      "(includes the SysTick interrupt's frame if it hit at the deepest point).")
    A("")
    A("| entry | static -O2 | chain -O2 | static -Os | measured -O2 (max) |")
    A("|---|---:|---|---:|---:|")
    meas = {"bw_encode_ctx": max((parsed[d.key]["stack"] or {}).get("encode", 0) for d in sets),
            "bw_decode_ctx": max((parsed[d.key]["stack"] or {}).get("decode", 0) for d in sets)}
    meas_v = max((parsed[d.key]["stack"] or {}).get("encode_verify", 0) for d in sets)
    rows = (("bw_encode_ctx without verify (the device path)", "device", meas["bw_encode_ctx"]),
            ("bw_encode_ctx with verify", "bw_encode_ctx", meas_v),
            ("bw_decode_ctx", "bw_decode_ctx", meas["bw_decode_ctx"]))
    for label, key, mv in rows:
        s2, ss = stacks["O2"][key], stacks["Os"][key]
        A("| %s | %s | %s | %s | %d |" % (
            label, s2[0] if s2 else "-", " → ".join(short(x) for x in s2[1]) if s2 else "-",
            ss[0] if ss else "-", mv))
    frames = {}
    for opt in ("O2", "Os"):
        fr, _ = callgraph(os.path.join(OUT, "obj-" + opt))
        frames[opt] = {short(k): v for k, v in fr.items()}
    A("")
    stack_ctx = ("bw_encode", "bw_decode", "bw_decode_unchecked")  # a bw_ctx_t on their stack
    big = {opt: max(((k, v) for k, v in frames[opt].items() if k not in stack_ctx),
                    key=lambda kv: kv[1]) for opt in ("O2", "Os")}
    A("Largest frames: %s %s bytes (-O2), %s %s bytes (-Os). The range coder's probability "
      "models (`bw_models_t`, in the strip coder's state) are in the caller's `bw_ctx_t` "
      "(sizeof %s bytes on this core), not on the stack; `bw_encode`, `bw_decode` and "
      "`bw_decode_unchecked`, the calls without `_ctx`, keep one on theirs (%s, %s and %s "
      "bytes at -O2)." % (big["O2"][0], big["O2"][1], big["Os"][0], big["Os"][1],
                          (parsed[sets[0].key]["mem"] or {}).get("ctx", "?"),
                          *(frames["O2"].get(k, "?") for k in stack_ctx)))
    A("")
    with open(os.path.join(ROOT, "linker", "stm32l476.ld")) as f:
        m = re.search(r"^STACK_SIZE\s*=\s*(0x[0-9a-fA-F]+|\d+)\s*;", f.read(), re.M)
    A("The board's stack region is %s bytes (linker/mps2-an386.ld); linker/stm32l476.ld "
      "reserves %s." % ((parsed[sets[0].key]["stack"] or {}).get("stack_region", "?"),
                         int(m.group(1), 0) if m else "?"))
    A("")

    # data sets and commands
    A("## Data sets")
    A("")
    for ds in sets:
        A("- **%s** (%s): %s." % (ds.key, ds.title, ds.desc))
    A("")
    A("## Runs")
    A("")
    A("Repeat: the phong run was made twice; every count printed was %s."
      % ("identical" if repeat_same else "NOT identical"))
    A("")
    A("```sh")
    A("make bench-device      # also part of make bench")
    for ds in sets:
        A("timeout %d %s" % (TIMEOUT, " ".join(parsed[ds.key]["cmd"])))
    A("```")
    A("")
    A("Wall time of the QEMU runs (in parallel): %s; whole script %.0f s."
      % (", ".join("%s %.1f s" % (d.key, parsed[d.key]["wall"]) for d in sets),
         time.perf_counter() - t_start))
    if failures:
        A("")
        A("## Failures")
        A("")
        for f in failures:
            A("- %s" % f)
    A("")
    os.makedirs(os.path.dirname(REPORT), exist_ok=True)
    with open(REPORT, "w") as f:
        f.write("\n".join(L))
    log("device bench: wrote %s%s" % (rel(REPORT), "" if not failures else
                                       " (%d failures)" % len(failures)))
    for f in failures:
        log("  FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
