#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""The conformance vectors (tests/conformance/, docs/FORMAT.md): every
payload decodes to its stored int32 samples and float32 values bit for bit
and its header reads as stored; together they cover every shape, mode,
basis, coder, order and header flag; a damaged vector is refused.
Prints "RESULT: N passed, M failed"."""
import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
BW = os.path.join(ROOT, os.environ.get("BUILD", "build/host"), "brdfwave")
DIR = os.path.join(ROOT, "tests", "conformance")
TMP = tempfile.mkdtemp(prefix="bw-conf-")
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL: " + what)


def run(*args):
    return subprocess.run([BW] + list(args), capture_output=True)


vectors = sorted(glob.glob(os.path.join(DIR, "*.bwv")))
check(len(vectors) >= 17, "only %d vectors" % len(vectors))
seen = {k: set() for k in ("shape", "mode", "basis", "coder", "order", "symmetry", "values")}
flags = 0
for v in vectors:
    name = os.path.basename(v)[:-4]
    stem = v[:-4]
    for fmt, ext in (("i32", ".i32"), ("f32", ".f32")):
        out = os.path.join(TMP, name + ext)
        r = run("decode", "-i", v, "-o", out, "--output-format", fmt)
        check(r.returncode == 0 and open(out, "rb").read() == open(stem + ext, "rb").read(),
              "%s: decoded %s differ from %s%s %s" % (name, fmt, name, ext, r.stderr.decode()))
    r = run("info", "--json", v)
    want = json.load(open(stem + ".json"))
    got = json.loads(r.stdout) if r.returncode == 0 else None
    check(got == want, "%s: header %s, stored %s" % (name, got, want))
    check(os.path.getsize(stem + ".i32") == 4 * want["samples"], name + ": .i32 size")
    for k in seen:
        seen[k].add(want[k])
    # the values from the samples, as docs/FORMAT.md says a decoder computes them
    s = np.fromfile(stem + ".i32", "<i4")
    sc, of = np.float32(want["scale"]), np.float32(want["offset"])
    data = open(v, "rb").read()
    if want["values"].startswith("exp"):
        val = np.exp(np.float64(of) + np.float64(sc) * s)
    elif data[5] & 1:  # DECIMAL_SCALE: scale = 10^-k
        val = s / 10.0 ** round(-np.log10(float(sc)))
    else:
        val = of + sc * s.astype(np.float32)
    check(np.array_equal(val.astype(np.float32), np.fromfile(stem + ".f32", "<f4")),
          name + ": values not offset + scale * sample as documented")
    flags |= data[5]
    if want["scale"] != 1:
        flags |= 0x100  # a scale field
    if want["offset"] != 0:
        flags |= 0x200  # an offset field

need = {"shape": {"spectra", "reflectance", "brdf-iso", "brdf-full"},
        "mode": {"lossless", "max-error", "bytes"},
        "basis": {"haar", "53", "97", "pred"},
        "coder": {"range", "rice", "ms", "tab", "columns (band access: record 0x06)"},
        "order": {"coarse-to-fine", "streamed"},
        "symmetry": {"none", "mirror", "reciprocal", "both"},
        "values": {"offset + scale * sample", "exp(offset + scale * sample)"}}
for k, want in need.items():
    check(want <= seen[k], "no vector with %s %s" % (k, sorted(want - seen[k])))
# flag bits: 0 DECIMAL_SCALE, 1 STREAM_ORDER, 2 RICE, 3 LOG_VALUE, 4 MIRROR,
# 5 RECIPROCAL; and the scale and offset fields
# and the extension area (version 7)
for bit in (0, 1, 2, 3, 4, 5, 6, 8, 9):
    check(flags & (1 << bit), "no vector with flag bit %d" % bit)

# a band range of a vector with band access (record 0x06) decodes alone to
# those bands of the stored samples
for v in vectors:
    stem = v[:-4]
    want = json.load(open(stem + ".json"))
    if not want["coder"].startswith("columns"):
        continue
    out = os.path.join(TMP, "bands.i32")
    r = run("decode", "-i", v, "-o", out, "--output-format", "i32", "--bands", "3,17-20,36")
    s = np.fromfile(stem + ".i32", "<i4").reshape(-1, want["bands"])
    check(r.returncode == 0 and np.array_equal(np.fromfile(out, "<i4"),
                                                s[:, [3, 17, 18, 19, 20, 36]].ravel()),
          "%s: --bands differ from the stored samples %s" % (os.path.basename(stem),
                                                            r.stderr.decode()))

# a damaged vector (one body bit, the length) is refused, nothing written
data = bytearray(open(vectors[0], "rb").read())
for what, bad in (("a flipped bit", data[:20] + bytes([data[20] ^ 4]) + data[21:]),
                  ("cut short", data[:-1])):
    p = os.path.join(TMP, "bad.bwv")
    open(p, "wb").write(bad)
    out = os.path.join(TMP, "bad.f32")
    r = run("decode", "-i", p, "-o", out)
    check(r.returncode == 1 and not os.path.exists(out) and len(r.stderr.splitlines()) == 1,
          "damaged vector (%s): exit %d, %s" % (what, r.returncode, r.stderr))

# an extension record of a critical type no decoder knows (below 0x80) is
# refused; the same record of an ancillary type is skipped
sys.path.insert(0, DIR)
from add_ext import with_ext  # noqa: E402
base = os.path.join(DIR, "spectra_lossless_haar")
for typ, ok_want in ((0x10, False), (0xF7, True)):
    p = os.path.join(TMP, "ext.bwv")
    open(p, "wb").write(with_ext(open(base + ".bwv", "rb").read(), typ, b"\x01\x02"))
    out = os.path.join(TMP, "ext.i32")
    if os.path.exists(out):
        os.remove(out)
    r = run("decode", "-i", p, "-o", out, "--output-format", "i32")
    if ok_want:
        check(r.returncode == 0 and open(out, "rb").read() == open(base + ".i32", "rb").read(),
              "ancillary record 0x%02x: %s" % (typ, r.stderr))
    else:
        check(r.returncode == 1 and b"extension" in r.stderr and not os.path.exists(out),
              "critical record 0x%02x: exit %d, %s" % (typ, r.returncode, r.stderr))

# a payload in segments with its last segment cut: the decoder writes
# what the whole segments hold, exits 3, and every sample its mask marks
# exact (0) is the whole payload's
def info_of(v):
    return json.load(open(v[:-4] + ".json"))


def embedded(v):
    return info_of(v).get("order", "").startswith("embedded")


# (an embedded payload in one segment has no whole segment left: below)
seg = [v for v in vectors if "segments" in info_of(v) and
       not (embedded(v) and info_of(v)["segments"] == 1)]
check(len(seg) >= 3, "no vectors in segments")
for v in seg:
    data = open(v, "rb").read()
    want = json.load(open(v[:-4] + ".json"))
    p = os.path.join(TMP, "cut.bwv")
    open(p, "wb").write(data[:-5])  # the last segment cut
    out, mk = os.path.join(TMP, "cut.i32"), os.path.join(TMP, "cut.mask")
    r = run("decode", "-i", p, "-o", out, "--output-format", "i32", "--mask", mk)
    check(r.returncode == 3 and b"segments lost" in r.stderr,
          "%s cut: exit %d, %s" % (v, r.returncode, r.stderr))
    if r.returncode == 3:
        got, ref = np.fromfile(out, "<i4"), np.fromfile(v[:-4] + ".i32", "<i4")
        m = np.fromfile(mk, np.uint8)
        check(m.size == ref.size and (m == 0).any() and (m != 0).any() and
              np.array_equal(got[m == 0], ref[m == 0]),
              "%s cut: the samples marked exact differ, or the mask is all one state" % v)

# an embedded payload in one segment cut anywhere in its body decodes to an
# approximation of every sample (mask 1), closer with more bytes (in
# several segments the cut loses the later ones: the check above)
emb = [v for v in vectors if embedded(v) and info_of(v)["segments"] == 1]
check(len(emb) >= 2, "no embedded vectors in one segment")
for v in emb:
    data = open(v, "rb").read()
    want = info_of(v)
    ref = np.fromfile(v[:-4] + ".i32", "<i4").astype(np.float64)
    start = want["segment_table_offset"] + 8 * want["segments"] + 4 + 6
    last = None
    for f in (0.3, 0.6, 0.9):
        p = os.path.join(TMP, "cut.bwv")
        open(p, "wb").write(data[:start + int(f * (len(data) - start))])
        out, mk = os.path.join(TMP, "cut.i32"), os.path.join(TMP, "cut.mask")
        r = run("decode", "-i", p, "-o", out, "--output-format", "i32", "--mask", mk)
        check(r.returncode == 3, "%s cut at %.0f %%: exit %d, %s" % (v, 100 * f, r.returncode,
                                                                    r.stderr))
        if r.returncode != 3:
            continue
        got, m = np.fromfile(out, "<i4").astype(np.float64), np.fromfile(mk, np.uint8)
        check(m.size == ref.size and not (m == 2).any() and (m == 1).any(),
              "%s cut: a sample missing, or none approximate" % v)
        e = float(np.sum((got - ref) ** 2))
        check(last is None or e <= last, "%s: more bytes, a larger error" % v)
        last = e

print("RESULT: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
