#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""The Python package against the CLI: decode of codec payloads equals
`brdfwave decode` bit for bit, encode equals `brdfwave encode` byte for byte,
grid equals `brdfwave grid`; bad input raises a clear BrdfwaveError; the
register map module matches firmware/link/bw_i2cmap.h.
Prints "RESULT: N passed, M failed"."""
import glob
import os
import re
import subprocess
import sys
import tempfile
import traceback

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "host-tools", "python"))
BW = os.path.join(ROOT, os.environ.get("BUILD", "build/host"), "brdfwave")

import numpy as np  # noqa: E402

import brdfwave  # noqa: E402
from brdfwave import i2cmap  # noqa: E402

TMP = tempfile.mkdtemp(prefix="bw-py-")
passed = failed = 0


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
    except brdfwave.BrdfwaveError as e:
        assert "missing.bwv" in str(e)
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
    assert on_device == brdfwave.encode(x, level=3, incoming=True, max_error=0.002)


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


print("RESULT: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
