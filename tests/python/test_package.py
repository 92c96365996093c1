#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""The Python package against the CLI: decode of codec payloads equals
`brdfwave decode` bit for bit, encode equals `brdfwave encode` byte for byte,
grid equals `brdfwave grid`; metadata and the readers as the CLI has them;
bad input raises a clear exception in Python's terms; the ctypes structures
are checked against the library; the register map module matches
firmware/link/bw_i2cmap.h.
Prints "RESULT: N passed, M failed"."""
import ctypes
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import traceback
import zlib

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "host-tools", "python"))
BW = os.path.join(ROOT, os.environ.get("BUILD", "build/host"), "brdfwave")

import numpy as np  # noqa: E402

import brdfwave  # noqa: E402
from brdfwave import i2cmap  # noqa: E402

TMP = tempfile.mkdtemp(prefix="bw-py-")
passed = failed = 0


def refused(fn, *args, **kw):
    """Whether fn(*args, **kw) raises BrdfwaveError."""
    try:
        fn(*args, **kw)
    except brdfwave.BrdfwaveError:
        return True
    return False


def case(fn):
    global passed, failed
    try:
        fn()
        print("ok     %s" % fn.__name__)
        passed += 1
    except Exception:
        print("FAIL   %s" % fn.__name__)
        traceback.print_exc(file=sys.stdout)
        failed += 1
    return fn


def bw(*args):
    r = subprocess.run([BW] + list(args), capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError("brdfwave %s: %s" % (" ".join(args), r.stderr))
    return r.stdout


def tmp(name):
    return os.path.join(TMP, name)


def cli_decoded(payload):
    bw("decode", "-i", payload, "-o", tmp("cli.f32"))
    return np.fromfile(tmp("cli.f32"), dtype="<f4")


def assert_same_bits(a, b):
    a = np.ascontiguousarray(a, dtype=np.float32).ravel()
    b = np.ascontiguousarray(b, dtype=np.float32).ravel()
    assert a.shape == b.shape, (a.shape, b.shape)
    diff = np.flatnonzero(a.view(np.uint32) != b.view(np.uint32))
    assert diff.size == 0, "%d values differ, first at %d: %r vs %r" % (
        diff.size, diff[0], a[diff[0]], b[diff[0]])


@case
def decode_of_a_lossy_brdf_equals_the_cli_output():
    bw("synth", "--model", "phong", "--kd", "0.6", "--ks", "0.3", "--n", "12", "--level", "3",
       "--incoming", "5", "-o", tmp("phong.f32"))
    bw("encode", "-i", tmp("phong.f32"), "-o", tmp("phong.bwv"), "--bands", "1", "--level", "3",
       "--incoming", "5", "--max-error", "0.002")
    m = brdfwave.decode(tmp("phong.bwv"))
    assert m.shape == (5, 4 * 4 ** 3, 1), m.shape
    assert m.dtype == np.float32
    assert_same_bits(m, cli_decoded(tmp("phong.bwv")))
    src = np.fromfile(tmp("phong.f32"), dtype="<f4").reshape(m.shape)
    assert np.max(np.abs(m - src)) <= 0.002
    assert m.header["shape"] == "brdf" and m.header["n_in"] == 5
    assert m.directions.shape == (256, 3)
    assert np.allclose(np.linalg.norm(m.directions, axis=1), 1.0)
    assert m.incoming is None


@case
def decode_of_field_spectra_equals_the_cli_output_and_the_integers():
    seds = sorted(glob.glob(os.path.join(ROOT, "tests", "data", "field_psr3500", "*.sed")))
    assert seds
    bw("encode", "--input-format", "sed", "-o", tmp("field.bwv"), "--lossless",
       *sum([["-i", s] for s in seds], []))
    m = brdfwave.decode(tmp("field.bwv"))
    assert m.shape == (len(seds), m.header["bands"]), m.shape
    assert_same_bits(m, cli_decoded(tmp("field.bwv")))
    ints = brdfwave.decode(tmp("field.bwv"), integers=True)
    bw("decode", "-i", tmp("field.bwv"), "-o", tmp("cli.i32"), "--output-format", "i32")
    assert np.array_equal(ints.ravel(), np.fromfile(tmp("cli.i32"), dtype="<i4"))
    w = np.linspace(350, 2500, m.header["bands"])
    assert np.array_equal(brdfwave.decode(tmp("field.bwv"), wavelengths=w).wavelengths, w)


@case
def decode_of_a_full_brdf_has_both_direction_sets():
    bw("synth", "--model", "ward", "--level", "2", "--level-in", "1", "-o", tmp("ward.f32"))
    bw("encode", "-i", tmp("ward.f32"), "-o", tmp("ward.bwv"), "--bands", "1", "--level", "2",
       "--level-in", "1", "--ratio", "8")
    m = brdfwave.decode(tmp("ward.bwv"))
    assert m.shape == (16, 64, 1) and m.incoming.shape == (16, 3)
    assert_same_bits(m, cli_decoded(tmp("ward.bwv")))


@case
def encode_equals_the_cli_payload_byte_for_byte():
    x = np.fromfile(tmp("phong.f32"), dtype="<f4").reshape(5, 256, 1)
    for opts, kw in ((["--max-error", "0.002"], {"max_error": 0.002}),
                     (["--ratio", "20", "--basis", "haar"], {"ratio": 20, "basis": "haar"}),
                     (["--max-error", "0.002", "--symmetry", "none"],
                      {"max_error": 0.002, "symmetry": "none"}),
                     (["--max-error", "0.002", "--symmetry", "mirror"],
                      {"max_error": 0.002, "symmetry": "mirror"})):
        bw("encode", "-i", tmp("phong.f32"), "-o", tmp("cli.bwv"), "--bands", "1", "--level",
           "3", "--incoming", "5", *opts)
        p = brdfwave.encode(x, level=3, incoming=True, path=tmp("py.bwv"), **kw)
        with open(tmp("cli.bwv"), "rb") as f:
            assert p == f.read(), opts
        with open(tmp("py.bwv"), "rb") as f:
            assert p == f.read()


@case
def encode_then_decode_is_lossless_for_integer_spectra():
    rng = np.random.default_rng(7)
    x = rng.integers(0, 4000, size=(3, 100)).astype(np.float32)
    m = brdfwave.decode_bytes(brdfwave.encode(x, lossless=True))
    assert np.array_equal(m, x)


@case
def prediction_codes_spectra_within_the_bound_and_names_its_basis():
    rng = np.random.default_rng(8)
    x = (2000 + np.cumsum(rng.integers(-30, 31, size=(4, 300)), axis=1)).astype(np.float32)
    for kw in ({"lossless": True}, {"max_error": 5}):
        p = brdfwave.encode(x, basis="pred", **kw)
        m = brdfwave.decode_bytes(p)
        assert m.header["basis"] == "pred", m.header
        assert np.max(np.abs(np.asarray(m) - x)) <= kw.get("max_error", 0)
    try:
        brdfwave.encode(x, basis="pred", ratio=8)
    except brdfwave.BrdfwaveError:
        pass
    else:
        raise AssertionError("prediction under a byte budget was not refused")


@case
def a_payload_in_segments_decodes_in_part_with_its_mask():
    bw("synth", "--model", "phong", "--level", "4", "--incoming", "8", "-o", tmp("seg.f32"))
    x = np.fromfile(tmp("seg.f32"), dtype="<f4").reshape(8, 1024, 1)
    p = brdfwave.encode(x, level=4, incoming=True, max_error=0.001, segments=4)
    assert p == brdfwave.encode(x, level=4, incoming=True, max_error=0.001, segments=4)
    whole = brdfwave.decode_bytes(p)
    assert whole.header["segments"] == 4 and whole.mask is None, whole.header
    m = brdfwave.decode_bytes(p, salvage=True)
    assert m.segments == 4 and m.lost_segments == 0 and not m.mask.any()
    cut = p[:len(p) * 3 // 4]
    try:
        brdfwave.decode_bytes(cut)
    except brdfwave.BrdfwaveError as e:
        assert "salvage" in str(e), e
    else:
        raise AssertionError("a cut payload decoded without salvage")
    m = brdfwave.decode_bytes(cut, salvage=True)
    assert m.mask.shape == m.shape and m.lost_segments >= 1, (m.mask.shape, m.lost_segments)
    exact = m.mask == 0
    assert exact.any() and (m.mask == 2).any()
    assert np.array_equal(np.asarray(m)[exact], np.asarray(whole)[exact])
    assert m.tail_lost is False
    # a float payload kept bit for bit (a tail of low bits) cut in its tail:
    # every segment whole, every value approximate, the tail named lost
    f = np.exp(np.random.default_rng(5).normal(0, 3, (8, 1024, 1))).astype(np.float32)
    fp = brdfwave.encode(f, level=4, incoming=True, lossless=True, segments=8)
    fm = brdfwave.decode_bytes(fp[:len(fp) * 9 // 10], salvage=True)
    assert fm.tail_lost and fm.lost_segments == 0 and (fm.mask == 1).all(), (fm.tail_lost,
                                                                             fm.lost_segments)
    assert np.max(np.abs(np.asarray(fm) - f) / f) < 2.0 ** -18
    assert np.array_equal(np.asarray(brdfwave.decode_bytes(fp)), f)
    # one incoming direction alone: that row of the whole decode
    r = brdfwave.decode_bytes(p, incoming=5)
    assert r.layout == "reflectance" and r.shape == (1024, 1), (r.layout, r.shape)
    assert np.array_equal(np.asarray(r), np.asarray(whole)[5])
    # a coarser level: each triangle the mean of what lies below it
    c = brdfwave.decode_bytes(p, level=2)
    assert c.shape == (8, 64, 1) and c.level == 2, (c.shape, c.level)
    fine = np.asarray(whole).reshape(8, 64, 16)
    assert np.max(np.abs(np.asarray(c)[..., 0] - fine.mean(axis=2))) < 0.05
    for bad_row in (8, -1):
        assert refused(brdfwave.decode_bytes, p, incoming=bad_row), "incoming=%d" % bad_row
    # a set of rows: those rows of the whole decode, in order, named in .rows
    s = brdfwave.decode_bytes(p, rows=[6, 1, 3])
    assert s.shape == (3, 1024, 1) and list(s.rows) == [1, 3, 6], (s.shape, s.rows)
    assert np.array_equal(np.asarray(s), np.asarray(whole)[[1, 3, 6]])
    mk = np.zeros(8, dtype=bool)
    mk[2:5] = True
    assert np.array_equal(np.asarray(brdfwave.decode_bytes(p, rows=mk)), np.asarray(whole)[2:5])
    for bad in (dict(rows=[8]), dict(rows=[]), dict(rows=[[1]]), dict(rows=np.ones(7, bool)),
                dict(rows=[1], incoming=1), dict(region=(89, 0, 0.5))):
        assert refused(brdfwave.decode_bytes, p, **bad), bad
    # an isotropic BRDF's region: the incidences within the radius of theta
    assert list(brdfwave.decode_bytes(p, region=(10, 0, 30)).rows) == [0, 1, 2, 3]
    pi = brdfwave.encode(x, level=4, incoming=True, max_error=0.001, segments=4,
                         incidence=np.arange(8) * 10.0)
    assert list(brdfwave.decode_bytes(pi, region=(30, 0, 6)).rows) == [3]
    # a region of a full BRDF's incoming hemisphere: the rows whose
    # directions lie within the radius, as in the whole decode
    bw("synth", "--model", "ward", "--ax", "0.3", "--ay", "0.1", "--level", "2", "--level-in",
       "2", "-o", tmp("wr.f32"))
    w = np.fromfile(tmp("wr.f32"), dtype="<f4").reshape(64, 64, 1)
    q = brdfwave.encode(w, level=2, level_in=2, max_error=0.001, segments=64, symmetry="mirror")
    wall = np.asarray(brdfwave.decode_bytes(q))
    g = brdfwave.decode_bytes(q, region=(40, 100, 25))
    u = np.array([np.sin(np.radians(40)) * np.cos(np.radians(100)),
                  np.sin(np.radians(40)) * np.sin(np.radians(100)), np.cos(np.radians(40))])
    inside = np.flatnonzero(brdfwave.decode_bytes(q).incoming @ u >= np.cos(np.radians(25)))
    assert 0 < len(inside) < 64 and list(g.rows) == list(inside), (g.rows, inside)
    assert np.array_equal(np.asarray(g), wall[inside])
    assert np.all(g.incoming @ u >= np.cos(np.radians(25)))
    # f straight from the payload: at the triangles' centres, the samples
    dec = brdfwave.decode_bytes(q)
    ii, oo = np.array([0, 5, 40, 63]), np.array([3, 17, 30, 60])
    f = brdfwave.evaluate(q, dec.incoming[ii], dec.directions[oo])
    assert f.shape == (4,) and np.allclose(f, wall[ii, oo, 0], rtol=1e-5, atol=1e-7), (
        f, wall[ii, oo, 0])
    assert np.isclose(brdfwave.evaluate(q, dec.incoming[5], dec.directions[17], band=0),
                      wall[5, 17, 0], rtol=1e-5)
    assert np.isnan(brdfwave.evaluate(q, dec.incoming[5], [0.0, 0.6, -0.8]))
    for bad in (dict(wi=[[0, 0, 1]] * 2, wo=[[0, 0, 1]] * 3), dict(wi=[0, 1], wo=[0, 1]),
                dict(wi=[0, 0, 1], wo=[0, 0, 1], band=1),
                dict(wi=[0, 0, 1], wo=[0, 0, 1], band=0, wavelength=500)):
        assert refused(brdfwave.evaluate, q, **bad), bad
    # a coarser level of both hemispheres: each value near the mean of the
    # 4 x 4 pairs below it; the incoming one alone keeps the outgoing level
    c = brdfwave.decode_bytes(q, level=1, level_in=1)
    assert c.shape == (16, 16, 1) and c.level == 1 and c.level_in == 1, (c.shape, c.level_in)
    assert c.incoming.shape == (16, 3)
    means = wall.reshape(16, 4, 16, 4).mean(axis=(1, 3))
    assert np.max(np.abs(np.asarray(c)[..., 0] - means)) < 0.05 * np.max(np.abs(means))
    assert brdfwave.decode_bytes(q, level_in=0).shape == (4, 64, 1)
    for bad in (dict(level_in=3), dict(level_in=-1), dict(level_in=1, rows=[1])):
        assert refused(brdfwave.decode_bytes, q, **bad), bad
    assert refused(brdfwave.decode_bytes, p, level_in=0), "level_in= for a BRDF of incidences"
    for bad in (0, -1, 2.5, 1 << 29):
        assert refused(brdfwave.encode, x, level=4, incoming=True, max_error=0.001,
                       segments=bad), "segments=%r" % (bad,)


class FakeWindow:
    """The register window of docs/I2C.md as an SMBus object (smbus2's
    read_word_data / write_byte_data / write_word_data), a payload offered;
    page `bad` reads corrupted while `bad_left` is not 0 (-1: always)."""

    def __init__(self, pid, payload):
        self.pid, self.p, self.page, self.hi, self.acked = pid, payload, 0, 0, False
        self.bad, self.bad_left, self.page_reads = 0, 0, []

    def _pages(self):
        return (len(self.p) + 31) // 32

    def _cur(self):
        return self.p[(self.page - 1) * 32:self.page * 32] if 1 <= self.page <= self._pages() else b""

    def read_word_data(self, addr, reg):
        import zlib
        M = i2cmap
        crc, n = zlib.crc32(self.p), len(self.p)
        cur = self._cur()
        ready = 0 if self.acked else M.ST_READY
        regs = {M.MAGIC: M.MAGIC_VALUE, M.VERSION: M.PAGE_SIZE << 8 | M.MAP_VERSION,
                M.STATUS: ready, M.ID_LO: self.pid & 0xFFFF, M.ID_HI: self.pid >> 16,
                M.LEN_LO: n & 0xFFFF, M.LEN_HI: n >> 16, M.PAGES: self._pages(),
                M.CRC_LO: crc & 0xFFFF, M.CRC_HI: crc >> 16, M.PNUM: self.page if cur else 0,
                M.PLEN: len(cur), M.PCRC_LO: zlib.crc32(cur) & 0xFFFF,
                M.PCRC_HI: zlib.crc32(cur) >> 16, M.RETRY: 0, M.CMD: 0}
        if M.DATA <= reg < M.DATA + 16:
            k = reg - M.DATA
            b = (cur + b"\xff" * 32)[2 * k:2 * k + 2]
            v = b[0] | b[1] << 8
            if k == 0:
                self.page_reads.append(self.page)
                if self.page == self.bad and self.bad_left:
                    v ^= 0x5A
                    self.bad_left -= self.bad_left > 0
            return v
        return regs.get(reg, 0)

    def write_byte_data(self, addr, reg, v):
        if reg == i2cmap.PAGE:
            self.page = self.hi << 8 | v
        elif reg == i2cmap.PAGE_HI:
            self.hi = v
        elif reg == i2cmap.CMD and v == i2cmap.CMD_ACK:
            self.acked = True

    def write_word_data(self, addr, reg, v):
        pass


@case
def acquisition_keeps_an_incomplete_payload_and_reads_only_its_missing_pages():
    from brdfwave import acquire
    bw("encode", "--input-format", "sed", "-i", *sorted(glob.glob(os.path.join(
        ROOT, "tests", "data", "field_psr3500", "*.sed")))[:8], "-o", tmp("acq.bwv"),
       "--max-error", "0.002", "--segments", "4")
    payload = open(tmp("acq.bwv"), "rb").read()
    bus = FakeWindow(21, payload)
    bus.bad, bus.bad_left = bus._pages() - 2, -1  # a page in the last segment, never right
    dev = acquire.Client(bus, i2cmap.ADDR)
    out = tempfile.mkdtemp(prefix="acq-", dir=TMP)
    try:
        dev.read_payload(retries=1)
        raise AssertionError("a page that never verified was accepted")
    except acquire.Incomplete as e:
        assert e.pid == 21 and e.missing == 1 and e.pages == bus._pages(), (e.missing, e.pages)
        assert "failed its CRC-32" in str(e), str(e)
    rec = dev.keep(out)
    assert os.path.basename(rec) == "payload-21-%08x.part" % zlib.crc32(payload), rec
    held = open(rec + ".bwv", "rb").read()
    lo = (bus.bad - 1) * 32
    assert held == payload[:lo] + bytes(32) + payload[lo + 32:]
    assert "missing %d\n" % (bus.bad - 1) in open(rec).read()
    # what arrived decodes in part: the lost segment reported, the rest exact
    m = brdfwave.decode_bytes(held, salvage=True)
    whole = brdfwave.decode_bytes(payload)
    assert m.lost_segments == 1 and (m.mask == 0).any() and (m.mask != 0).any()
    assert np.array_equal(np.asarray(m)[m.mask == 0], np.asarray(whole)[m.mask == 0])
    # later, in a new client from the record: only the missing page is read
    dev.close()
    bus.bad_left, bus.page_reads = 0, []
    dev = acquire.Client(bus, i2cmap.ADDR)
    dev.resume(rec)
    pid, got, bad = dev.read_payload(retries=1)
    assert pid == 21 and got == payload and bus.page_reads == [bus.bad], bus.page_reads
    path, before = acquire.store(out, pid, got)
    assert not before and open(path, "rb").read() == payload
    assert sorted(os.listdir(out)) == [os.path.basename(path)], os.listdir(out)
    dev.close()
    try:
        dev.resume(rec)
        raise AssertionError("a removed record loaded")
    except acquire.AcquireError as e:
        assert rec in str(e), str(e)


@case
def a_progressive_payload_decodes_from_any_prefix():
    bw("synth", "--model", "phong", "--level", "3", "--incoming", "6", "-o", tmp("emb.f32"))
    x = np.fromfile(tmp("emb.f32"), dtype="<f4").reshape(6, 256, 1)
    p = brdfwave.encode(x, level=3, incoming=True, max_error=0.0005, progressive=True)
    m = brdfwave.decode_bytes(p)
    assert m.header["embedded"] and m.header["segments"] == 1, m.header
    assert np.max(np.abs(np.asarray(m) - x)) <= 0.0005 + 1e-7
    # a prefix decodes to an approximation, closer with more bytes
    errs = []
    start = m.header["header_len"] + 12 + 6  # the segment table, its start
    for f in (0.1, 0.25, 0.5):
        c = brdfwave.decode_bytes(p[:start + int((len(p) - start) * f)], salvage=True)
        assert c.mask.shape == c.shape and (c.mask == 1).all(), np.unique(c.mask)
        errs.append(float(np.sqrt(np.mean((np.asarray(c) - x) ** 2))))
    assert errs[0] > errs[1] > errs[2] > 0, errs
    # a byte budget: the exact coding cut there
    b = brdfwave.encode(x, level=3, incoming=True, nbytes=len(p) // 3, progressive=True)
    assert len(p) // 3 * 0.99 <= len(b) <= len(p) // 3, (len(b), len(p))
    assert brdfwave.decode_bytes(b).header["embedded"]
    assert not brdfwave.encode(x, level=3, incoming=True, max_error=0.0005) == p
    try:
        brdfwave.encode(x, level=3, incoming=True, basis="pred", progressive=True)
    except brdfwave.BrdfwaveError:
        pass
    else:
        raise AssertionError("prediction accepted with progressive")


@case
def a_band_access_payload_decodes_the_bands_asked_for():
    rng = np.random.default_rng(6)
    x = (0.5 + np.cumsum(rng.normal(0, 1e-3, (9, 300)), axis=1)).astype(np.float32)
    wl = np.linspace(400.0, 1000.0, 300)
    p = brdfwave.encode(x, wavelengths=wl, band_access=True)
    m = brdfwave.decode_bytes(p)
    assert m.header["band_access"] and np.array_equal(np.asarray(m), x), m.header
    k = brdfwave.decode_bytes(p, bands=[0, 150, 299])
    assert np.array_equal(np.asarray(k), x[:, [0, 150, 299]]) and list(k.bands) == [0, 150, 299]
    assert np.array_equal(k.wavelengths, wl[[0, 150, 299]]), k.wavelengths
    r = brdfwave.decode_bytes(p, wavelength_range=(500, 520))
    sel = (wl >= 500) & (wl <= 520)
    assert np.array_equal(np.asarray(r), x[:, sel]) and np.array_equal(r.wavelengths, wl[sel])
    # the same bands and metadata as the host's payload gives
    q = brdfwave.decode_bytes(brdfwave.encode(x, wavelengths=wl), wavelength_range=(500, 520))
    assert q.metadata == r.metadata, (q.metadata, r.metadata)
    e = brdfwave.encode(x, max_error=1e-4, band_access=True)
    assert np.max(np.abs(np.asarray(brdfwave.decode_bytes(e)) - x)) <= 1e-4
    try:
        brdfwave.encode(x, nbytes=2000, band_access=True)
    except brdfwave.BrdfwaveError:
        pass
    else:
        raise AssertionError("a byte budget accepted with band access")


@case
def float_lossless_keeps_every_bit_and_says_so():
    rng = np.random.default_rng(32)
    x = (rng.standard_normal((7, 33)) * 10.0 ** rng.integers(-30, 30, (7, 33))).astype(np.float32)
    x[0, :4] = [np.float32(-0.0), np.float32(1e-45), np.inf, -np.inf]
    x[1, 0] = np.nan
    p = brdfwave.encode(x, lossless=True, path=tmp("fl.bwv"))
    m = brdfwave.decode_bytes(p)
    assert_same_bits(m, x)
    assert m.guarantee["kind"] == "exact", m.guarantee
    assert brdfwave.check_guarantee(p, x, m) == 0
    assert_same_bits(m, cli_decoded(tmp("fl.bwv")))


@case
def relative_bound_holds_on_every_sample_and_is_recorded():
    rng = np.random.default_rng(7)
    x = (np.exp(rng.uniform(-8, 3, (9, 40))) * rng.choice([-1, 1], (9, 40))).astype(np.float32)
    x[2, 5:9] = 0
    for kw, rule in (({"max_rel_error": 1e-3}, "relative"),
                     ({"max_rel_error": 1e-2, "rel_floor": 1e-3}, "relative"),
                     ({"max_rel_error": 1e-3, "max_error": 0.05}, "both")):
        p = brdfwave.encode(x, **kw)
        m = brdfwave.decode_bytes(p)
        g = brdfwave.guarantee(p)
        assert g["kind"] == rule and g["recorded"], (g, kw)
        assert g["max_rel_error"] == kw["max_rel_error"], (g, kw)
        R, F, E = kw["max_rel_error"], kw.get("rel_floor", 0.0), kw.get("max_error", np.inf)
        bound = np.minimum(E, np.maximum(R * np.abs(x.astype(np.float64)), F))
        err = np.abs(m.astype(np.float64) - x)
        assert np.all(err <= bound), (kw, np.max(err / np.maximum(bound, 1e-300)))
        assert brdfwave.check_guarantee(p, x, m) == 0
        # a decoded file that moves one value past its bound is caught
        bad = np.array(m)
        bad.flat[17] = x.flat[17] + 2 * bound.flat[17] + np.float32(1e-30)
        assert brdfwave.check_guarantee(p, x, bad) == 1
    assert brdfwave.guarantee(brdfwave.encode(x, ratio=8))["kind"] == "none"


@case
def grid_equals_the_cli_csv():
    for level in (0, 2, 4):
        rows = bw("grid", "--level", str(level)).strip().split("\n")
        g = brdfwave.grid(level)
        assert rows[0] == ",".join(g.dtype.names)
        assert len(rows) - 1 == len(g) == 4 * 4 ** level
        for r, row in zip(g, rows[1:]):
            ours = "%d,%s" % (r["index"], ",".join("%.9g" % (r[k] + 0.0) for k in g.dtype.names[1:]))
            assert ours == row, (ours, row)


@case
def bad_input_raises_a_clear_error():
    for data, what in ((b"", "truncated"), (b"XXXX" + bytes(60), "magic")):
        with open(tmp("bad.bwv"), "wb") as f:
            f.write(data)
        try:
            brdfwave.decode(tmp("bad.bwv"))
            raise AssertionError("no error for %r" % data[:8])
        except brdfwave.BrdfwaveError as e:
            assert what in str(e) and "bad.bwv" in str(e), str(e)
    with open(tmp("phong.bwv"), "rb") as f:
        p = bytearray(f.read())
    p[60] ^= 0x10
    try:
        brdfwave.decode_bytes(p)
        raise AssertionError("corrupted payload decoded")
    except brdfwave.BrdfwaveError as e:
        assert "CRC" in str(e), str(e)
    try:
        brdfwave.decode(tmp("missing.bwv"))
        raise AssertionError("missing file decoded")
    except FileNotFoundError as e:
        assert e.filename == tmp("missing.bwv")
    for kw in ({"level": 3}, {"level": 9}, {"max_error": -1}, {"symmetry": "rotate"}):
        try:
            brdfwave.encode(np.zeros((2, 5), np.float32), **kw)
            raise AssertionError("encode accepted %r" % kw)
        except brdfwave.BrdfwaveError:
            pass
    try:
        brdfwave.grid(7)
        raise AssertionError("grid(7) accepted")
    except brdfwave.BrdfwaveError:
        pass


@case
def decode_refuses_payloads_beyond_the_sample_limit_and_float32():
    p = open(tmp("phong.bwv"), "rb").read()
    n = brdfwave.decode_bytes(p).size
    assert brdfwave.decode_bytes(p, max_samples=n).size == n
    try:
        brdfwave.decode_bytes(p, max_samples=n - 1)
        raise AssertionError("payload above max_samples decoded")
    except brdfwave.BrdfwaveError as e:
        assert "more than the limit of %d" % (n - 1) in str(e), str(e)
    np.array([1, 2, 3, 4], "<i4").tofile(tmp("two.i32"))
    bw("encode", "-i", tmp("two.i32"), "--input-format", "i32", "--bands", "4", "--scale", "3e38",
       "-o", tmp("huge.bwv"))
    try:
        brdfwave.decode(tmp("huge.bwv"))
        raise AssertionError("values beyond float32 decoded")
    except brdfwave.BrdfwaveError as e:
        assert "beyond float32" in str(e), str(e)
    assert list(brdfwave.decode(tmp("huge.bwv"), integers=True).ravel()) == [1, 2, 3, 4]


@case
def encode_on_the_linux_device_from_outside_the_checkout_equals_the_host_payload():
    # the library finds the device image beside itself (not beside the Python
    # interpreter, whatever the working directory)
    x = np.fromfile(tmp("phong.f32"), dtype="<f4").reshape(5, 256, 1)
    x.tofile(tmp("dev_in.f32"))
    prog = (
        "import sys, numpy as np, brdfwave\n"
        "x = np.fromfile(sys.argv[1], dtype='<f4').reshape(5, 256, 1)\n"
        "p = brdfwave.encode(x, level=3, incoming=True, max_error=0.002, device='linux')\n"
        "open(sys.argv[2], 'wb').write(p)\n")
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "host-tools", "python"))
    for k in ("BW_FIRMWARE", "BW_FIRMWARE_LINUX", "BRDFWAVE_LIB"):
        env.pop(k, None)
    outside = tempfile.mkdtemp(prefix="bw-py-elsewhere-")
    assert not os.path.realpath(outside).startswith(os.path.realpath(ROOT) + os.sep)
    r = subprocess.run([sys.executable, "-c", prog, tmp("dev_in.f32"), tmp("dev.bwv")],
                       cwd=outside, env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    with open(tmp("dev.bwv"), "rb") as f:
        on_device = f.read()
    # the device's default effort is "fast" and its coder "auto"; the host's,
    # "best" and "range"
    assert on_device == brdfwave.encode(x, level=3, incoming=True, max_error=0.002,
                                        effort="fast", coder="auto")
    assert on_device[5] & 0x80, "the device's payload is not multi-symbol coded (header flags)"
    for name, value in (("coder", "fastest"), ("effort", "slow")):
        try:
            brdfwave.encode(x, level=3, incoming=True, max_error=0.002, **{name: value})
        except brdfwave.BrdfwaveError as e:
            assert name in str(e)
        else:
            raise AssertionError("%s=%r was taken" % (name, value))


@case
def the_shared_and_the_static_library_hold_the_same_functions():
    lib_dir = os.path.dirname(BW)

    def functions(path, *flags):
        out = subprocess.run(["nm", "-g", "--defined-only", *flags, path], capture_output=True,
                             text=True, check=True).stdout
        return {f[2] for f in (line.split() for line in out.splitlines()) if len(f) == 3
                and f[1] == "T"}

    static = functions(os.path.join(lib_dir, "libbrdfwave.a"))
    shared = functions(os.path.join(lib_dir, "libbrdfwave.so"), "-D")
    assert static and static == shared, sorted(static ^ shared)[:10]
    assert {"bwh_sampler_build", "bwh_brdf_data_load", "bwh_i2c_read_payload",
            "bwh_shape_dims", "bw_encode"} <= shared


@case
def register_map_matches_the_c_header():
    with open(os.path.join(ROOT, "firmware", "link", "bw_i2cmap.h")) as f:
        defs = dict(re.findall(r"#define BW_I2C_(\w+) (0x[0-9A-Fa-f]+|\d+)u", f.read()))
    assert len(defs) > 30
    for name, v in defs.items():
        assert getattr(i2cmap, name) == int(v, 0), name


@case
def metadata_travels_with_the_array():
    wl = np.array([400.5, 401.7, 403.1, 410.0, 500.25])
    x = np.linspace(0.1, 0.9, 15, dtype=np.float32).reshape(3, 5)
    p = brdfwave.encode(x, wavelengths=wl, quantity="radiance", max_error=1e-4,
                        fields={"site": "plot 4"}, metadata={"instrument": "bench",
                                                             "serial": "7"})
    m = brdfwave.decode(p)
    assert m.layout == "spectra" and m.shape == (3, 5)
    assert np.array_equal(m.wavelengths, wl) and m.wavelength_unit == "nm"
    assert m.quantity == "radiance" and m.unit == "W m^-2 sr^-1 nm^-1"
    assert m.metadata["instrument"] == "bench" and m.metadata["fields"] == {"site": "plot 4"}
    assert float(np.abs(m - x).max()) <= 1e-4
    # the CLI reads the same metadata
    with open(tmp("meta.bwv"), "wb") as f:
        f.write(p)
    assert json.loads(bw("info", "--json", tmp("meta.bwv")))["metadata"] == m.metadata
    # a decoded measurement encodes again with its metadata and layout
    assert brdfwave.decode(brdfwave.encode(m, max_error=1e-4)).metadata == m.metadata
    # without metadata: no metadata record
    assert brdfwave.decode_bytes(brdfwave.encode(x, max_error=1e-4)).metadata == {}
    assert brdfwave.header_of(p)["version"] == 7


@case
def a_band_range_keeps_those_bands_and_their_metadata():
    wl = np.array([400.5, 401.7, 403.1, 410.0, 500.25])
    x = np.linspace(0.1, 0.9, 15, dtype=np.float32).reshape(3, 5)
    p = brdfwave.encode(x, wavelengths=wl, max_error=1e-4)
    whole = np.asarray(brdfwave.decode(p))
    b = brdfwave.decode(p, bands=[4, 0])
    assert b.shape == (3, 2) and list(b.bands) == [0, 4], (b.shape, b.bands)
    assert np.array_equal(np.asarray(b), whole[:, [0, 4]])
    assert np.array_equal(b.wavelengths, wl[[0, 4]]) and b.layout == "spectra"
    r = brdfwave.decode(p, wavelength_range=(401, 405))
    assert list(r.bands) == [1, 2] and np.array_equal(r.wavelengths, wl[1:3]), r.bands
    assert np.array_equal(np.asarray(brdfwave.decode(p, bands=np.arange(5) > 2)), whole[:, 3:])
    # the CLI keeps the same
    with open(tmp("bands.bwv"), "wb") as f:
        f.write(p)
    bw("decode", "-i", tmp("bands.bwv"), "--bands", "0,4", "-o", tmp("bands.f32"))
    assert np.array_equal(np.fromfile(tmp("bands.f32"), dtype="<f4").reshape(3, 2),
                          np.asarray(b))
    # with rows, and with the mask of a salvage decode
    rb = brdfwave.decode(p, rows=[1, 2], bands=[3])
    assert np.array_equal(np.asarray(rb), whole[1:3, 3:4])
    sv = brdfwave.decode(p, salvage=True, bands=[2])
    assert sv.mask.shape == (3, 1) and (sv.mask == 0).all()
    # missing samples: their runs follow the bands kept
    with open(tmp("miss.csv"), "w") as f:
        f.write("wavelength_nm,a,b,c\n400,0.1,-1,0.3\n410,-1,0.2,-1\n"
                "420,0.1,-1,0.3\n430,-1,0.2,-1\n")
    bw("encode", "-i", tmp("miss.csv"), "--ignore-value", "-1", "--max-error", "0.001", "-o",
       tmp("miss.bwv"))
    mm = brdfwave.decode(tmp("miss.bwv"), bands=[1, 3])
    assert np.array_equal(np.asarray(mm) == -1, [[True, True], [False, False], [True, True]])
    assert mm.metadata["missing"]["runs"] == [[0, 2], [4, 2]], mm.metadata["missing"]
    for bad in (dict(bands=[5]), dict(bands=[]), dict(bands=[-1]), dict(bands=[[1]]),
                dict(bands=np.ones(4, bool)), dict(bands=[1.5]),
                dict(bands=[1], wavelength_range=(400, 500)),
                dict(wavelength_range=(600, 700)), dict(wavelength_range=(500, 400)),
                dict(wavelength_range=(1, 2, 3))):
        assert refused(brdfwave.decode_bytes, p, **bad), bad
    assert refused(brdfwave.decode_bytes, brdfwave.encode(x, max_error=1e-4),
                   wavelength_range=(400, 500)), "wavelength_range= without wavelengths"


@case
def incidence_angles_in_the_callers_units():
    x = np.fromfile(tmp("phong.f32"), dtype="<f4").reshape(5, 256, 1)
    for unit, a in (("deg", [0.0, 27.67, 39.86, 49.94, 59.27]),
                    ("rad", [0.0, 0.48, 0.69, 0.87, 1.03])):
        m = brdfwave.decode(brdfwave.encode(x, level=3, incoming=True, max_error=0.002,
                                            incidence=a, incidence_unit=unit))
        assert m.layout == "brdf-iso" and m.incidence_unit == unit
        assert list(m.incidence) == a and m.directions.shape == (256, 3)
    try:
        brdfwave.encode(x, level=3, incoming=True, max_error=0.002, incidence=[0, 10])
        raise AssertionError("2 angles for 5 incoming directions accepted")
    except brdfwave.BrdfwaveError as e:
        assert "incidence" in str(e), str(e)


@case
def integers_are_coded_as_integers():
    for dt in (np.uint8, np.int16, np.uint16, np.int32):
        x = (np.arange(24).reshape(3, 8) * 37 % 200).astype(dt)
        if dt == np.int32:
            x[0, 0] = 2 ** 24 - 1
        m = brdfwave.decode(brdfwave.encode(x), integers=True)
        assert np.array_equal(np.asarray(m), x.astype(np.int32)), dt
        assert m.metadata["sample_type"] == {np.uint8: "u8", np.int16: "i16",
                                             np.uint16: "u16", np.int32: "i32"}[dt]
    try:
        brdfwave.encode(np.array([[16777217, 1]], dtype=np.int64))
        raise AssertionError("16777217 accepted")
    except brdfwave.BrdfwaveError as e:
        assert "16777217" in str(e)


@case
def every_mode_and_option_of_the_cli():
    x = np.fromfile(tmp("phong.f32"), dtype="<f4").reshape(5, 256, 1)
    x.tofile(tmp("opts.f32"))
    for kw, opts in (({"ratio": 16, "relative": True}, ["--ratio", "16", "--relative"]),
                     ({"max_error": 0.002, "coder": "rice", "stream": True, "basis": "53"},
                      ["--max-error", "0.002", "--coder", "rice", "--stream", "--basis", "53"]),
                     ({"nbytes": 600, "symmetry": "mirror"},
                      ["--bytes", "600", "--symmetry", "mirror"]),
                     ({"max_error": 0.001, "coder": "tab", "basis": "haar"},
                      ["--max-error", "0.001", "--coder", "tab", "--basis", "haar"])):
        p = brdfwave.encode(x, level=3, incoming=True, **kw)
        bw("encode", "-i", tmp("opts.f32"), "-o", tmp("opts.bwv"), "--bands", "1", "--level",
           "3", "--incoming", "5", *opts)
        with open(tmp("opts.bwv"), "rb") as f:
            assert p == f.read(), kw


@case
def errors_speak_python():
    x = np.linspace(0.1, 0.9, 10, dtype=np.float32).reshape(2, 5)
    try:
        brdfwave.encode(x, scale=0.3)
        raise AssertionError("lossless float off the scale accepted")
    except ValueError as e:
        assert "max_error=" in str(e) and "--" not in str(e), str(e)
    try:
        brdfwave.encode(x, max_error=0.01, path="/nonexistent/a.bwv")
        raise AssertionError("written to a missing folder")
    except FileNotFoundError as e:
        assert e.filename == "/nonexistent/a.bwv", e
    try:
        brdfwave.encode(x, level="3")
        raise AssertionError("level '3' accepted")
    except TypeError:
        pass
    try:
        brdfwave.read_sed(tmp("none.sed"))
        raise AssertionError("missing .sed read")
    except FileNotFoundError as e:
        assert e.filename == tmp("none.sed")
    p = brdfwave.encode(x, max_error=0.01, path=tmp("h.bwv"))
    assert brdfwave.header_of(tmp("h.bwv")) == brdfwave.header_of(p)
    info = bw("info", tmp("h.bwv"))
    want = float(re.search(r"^max_error: (\S+)$", info, re.M).group(1))
    assert abs(brdfwave.header_of(p)["max_error"] - want) <= 1e-9 * want, (want, info)


@case
def readers_give_what_the_cli_encodes():
    data = os.path.join(ROOT, "tests", "data")
    seds = sorted(glob.glob(os.path.join(data, "field_psr3500", "*.sed")))[:4]
    s = brdfwave.read_sed(seds)
    assert s.shape == (4, 1024) and s.metadata["serial"] == "1116037"
    assert s.metadata["spectrum_names"] == [os.path.basename(f) for f in seds]
    bw("encode", "-i", *seds, "-o", tmp("sed.bwv"), "--lossless")
    with open(tmp("sed.bwv"), "rb") as f:
        assert brdfwave.encode(s, lossless=True, scale=1e-5) == f.read()
    inst = os.path.join(data, "instruments")
    for path, fmt, bands in ((os.path.join(inst, "asd", "soil.asd"), "asd", 2151),
                             (os.path.join(inst, "svc_sig", "gr070214_003.sig"), "sig", 991),
                             (os.path.join(inst, "envi", "s06av95a_envi.hdr"), "envi", 224)):
        m = getattr(brdfwave, "read_" + fmt)(path)
        assert m.shape[-1] == bands and len(m.wavelengths) == bands, (path, m.shape)
    r = brdfwave.read_bsdf(os.path.join(data, "rgl", "paper_white_rgb.bsdf"), channel="g")
    assert r.layout == "brdf-iso" and r.shape == (7, 1024, 1)
    assert [round(float(np.degrees(a)), 2) for a in r.incidence] == \
        [0, 27.67, 39.86, 49.94, 59.27, 68.57, 78.46]


@case
def the_structures_are_checked_against_the_library():
    from brdfwave import _abi, _lib
    L = _lib.lib()
    _abi.check(L, {"bw_header_t": _lib.Header, "bwh_encode_opts_t": _lib.EncodeOpts})

    class Short(ctypes.Structure):  # without its last two ints (one would leave padding)
        _fields_ = _lib.EncodeOpts._fields_[:-2]
    try:
        _abi.check(L, {"bwh_encode_opts_t": Short})
        raise AssertionError("a structure of the wrong size passed")
    except ImportError as e:
        assert "bwh_encode_opts_t" in str(e), str(e)


@case
def the_package_has_a_version_and_docstrings():
    assert re.match(r"^\d+\.\d+\.\d+$", brdfwave.__version__)
    for name in brdfwave.__all__:
        if name != "__version__":
            assert getattr(brdfwave, name).__doc__, name


print("RESULT: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
