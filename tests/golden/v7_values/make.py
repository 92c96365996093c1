#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Writes the archived version-7 payloads of float input: the records 0x01
(float exact: scales, bit planes, exceptions), 0x02 (log map) and 0x82
(guarantee), and their MANIFEST. Run once, by hand, when the archive is made;
tests/unit/test_golden_values.c decodes them ever after, and they must not
be rewritten (a decoder change that alters what they decode to is a format
change). Usage: /usr/bin/python3 tests/golden/v7_values/make.py [brdfwave]"""
import math
import os
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))


def run(*args):
    subprocess.run(list(args), check=True, stdout=subprocess.DEVNULL)


def main():
    bw = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "host", "brdfwave")
    tmp = tempfile.mkdtemp()

    def f32(name, vals):
        p = os.path.join(tmp, name)
        with open(p, "wb") as fh:
            fh.write(b"".join(v if isinstance(v, bytes) else struct.pack("<f", v) for v in vals))
        return p

    phong = os.path.join(tmp, "phong.f32")
    run(bw, "synth", "--model", "phong", "--kd", "0.6", "--ks", "0.4", "--n", "30", "--level", "2",
        "--incoming", "3", "-o", phong)
    odd = f32("odd.f32", [1.5, -0.0, 0.0, 1e-45, -3e-39, float("inf"), float("-inf"), 3.4e38,
                          -2.5e-20, 7.0, struct.pack("<I", 0x7FC00001),
                          struct.pack("<I", 0xFFA00000)] * 3)
    dec = f32("dec.f32", [float("%.3f" % (0.5 + 0.001 * ((i * 37) % 900))) for i in range(64)] +
              [0.75, float("nan")] + [0.25] * 30)
    sig = f32("sig.f32", [0.0 if i % 11 == 0 else
                          math.exp(math.sin(i * 0.37) * 6) * (1 if (i // 7) % 3 else -1)
                          for i in range(8 * 33)])
    cases = [
        ("phong_lossless_planes", phong, ["--bands", "1", "--level", "2", "--incoming", "3",
                                          "--lossless"]),
        ("odd_lossless_exceptions", odd, ["--bands", "12", "--lossless"]),
        ("decimal_lossless_exceptions", dec, ["--bands", "32", "--lossless", "--coder", "rice"]),
        ("phong_maxerr", phong, ["--bands", "1", "--level", "2", "--incoming", "3",
                                 "--max-error", "0.0005"]),
        ("phong_rel_log_value", phong, ["--bands", "1", "--level", "2", "--incoming", "3",
                                        "--max-rel-error", "0.001"]),
        ("signed_rel_logmap", sig, ["--bands", "33", "--max-rel-error", "0.01"]),
        ("signed_rel_floor_pred", sig, ["--bands", "33", "--max-rel-error", "0.001",
                                        "--rel-floor", "0.01", "--basis", "pred"]),
        ("signed_both_97", sig, ["--bands", "33", "--max-rel-error", "0.0001",
                                 "--max-error", "0.5", "--basis", "97"]),
    ]
    lines = ["# payloads of float input written by the format-7 encoder with the records 0x01, "
             "0x02 and 0x82 (make.py);",
             "# every later decoder must decode them to these samples and values and read the "
             "same guarantee",
             "# name samples crc32-of-int32-samples-LE crc32-of-float32-values-LE guarantee-kind "
             "(tests/unit/test_golden_values.c)"]
    for name, src, args in cases:
        out = os.path.join(HERE, name + ".bwv")
        run(bw, "encode", "-i", src, "-o", out, *args)
        si, sf = os.path.join(tmp, "s.i32"), os.path.join(tmp, "s.f32")
        run(bw, "decode", "-i", out, "-o", si, "--output-format", "i32")
        run(bw, "decode", "-i", out, "-o", sf)
        info = subprocess.run([bw, "info", out], check=True, capture_output=True,
                              text=True).stdout
        kind = [l.split(": ", 1)[1] for l in info.splitlines() if l.startswith("guarantee: ")][0]
        s, v = open(si, "rb").read(), open(sf, "rb").read()
        lines.append("%s %d %08x %08x %s" % (name, len(v) // 4, zlib.crc32(s), zlib.crc32(v), kind))
    with open(os.path.join(HERE, "MANIFEST"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
