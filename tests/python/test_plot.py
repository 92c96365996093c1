#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave.plot (matplotlib) against `brdfwave plot`: the rate-distortion
points are the command line's, the hemisphere map has its peak at the
mirror direction, the spectra are drawn, bad input raises BrdfwaveError.
Prints "RESULT: N passed, M failed"."""
import csv
import os
import subprocess
import sys
import tempfile
import traceback

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "host-tools", "python"))
BW = os.path.join(ROOT, os.environ.get("BUILD", "build/host"), "brdfwave")

import numpy as np  # noqa: E402

import brdfwave  # noqa: E402
from brdfwave import BrdfwaveError  # noqa: E402

TMP = tempfile.mkdtemp(prefix="bw-plot-")
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


def path(name):
    return os.path.join(TMP, name)


subprocess.run([BW, "synth", "--model", "phong", "--kd", "0.75", "--ks", "0.25", "--n", "20",
                "--level", "4", "--incoming", "16", "-o", path("p.f32")], check=True)
SHAPE = ["--bands", "1", "--level", "4", "--incoming", "16"]
subprocess.run([BW, "encode", "-q", "-i", path("p.f32"), "-o", path("p.bwv"), "--max-error",
                "0.002"] + SHAPE, check=True)
P = np.fromfile(path("p.f32"), dtype="<f4").reshape(16, 1024, 1)


@case
def rate_distortion_points_are_those_of_the_command_line():
    ratios = (8, 16, 32, 64)
    fig, pts = brdfwave.plot_rd(P, ratios=ratios, level=4, incoming=True, path=path("rd.png"))
    out = subprocess.run([BW, "plot", "rd", "-i", path("p.f32"), "--ratios", "8,16,32,64",
                          "-o", path("rd_cli.png")] + SHAPE, check=True, capture_output=True,
                         text=True).stdout
    rows = list(csv.DictReader(out.splitlines()))
    assert len(pts) == len(rows) == 4, (pts, rows)
    for p, r in zip(pts, rows):
        assert p[0] == float(r["ratio"]) and p[1] == int(r["bytes"]), (p, r)
        assert abs(p[3] - float(r["relative_l2_percent"])) <= 1e-4 * float(r["relative_l2_percent"])
        assert abs(p[4] - float(r["max_abs_error"])) <= 1e-5 * float(r["max_abs_error"])
    bps = [p[2] for p in pts]
    assert bps == sorted(bps, reverse=True), bps
    assert open(path("rd.png"), "rb").read(8) == b"\x89PNG\r\n\x1a\n"


@case
def hemisphere_map_is_brightest_at_the_mirror_direction():
    import matplotlib.image as mpimg
    m = brdfwave.decode(path("p.bwv"))
    fig = brdfwave.plot_hemisphere(m, incoming=12, path=path("h.png"))
    img = mpimg.imread(path("h.png"))[..., :3]
    # the disc in pixels: the axes' data limits mapped through the figure
    ax = fig.axes[0]
    to_px = ax.transData.transform
    (cx, cy), (rx, _) = to_px((0, 0)), to_px((90, 0))
    h = img.shape[0]
    cy = h - cy  # image rows go down
    score = img[..., 0] + img[..., 1] - 2 * img[..., 2]  # viridis' top is yellow
    yy, xx = np.mgrid[0:h, 0:img.shape[1]]
    r = rx - cx
    score[(xx - cx) ** 2 + (yy - cy) ** 2 > (0.97 * r) ** 2] = -9
    ys, xs = np.nonzero(score >= score.max() - 0.03)
    theta = (12 + 0.5) * 90 / 16
    want = cx - r * theta / 90  # phi = 180 degrees: left of the centre
    assert abs(xs.mean() - want) < 0.05 * r and abs(ys.mean() - cy) < 0.05 * r, \
        (xs.mean(), ys.mean(), want, cy, r)


@case
def spectra_before_and_after_are_drawn():
    d = brdfwave.decode(path("p.bwv"))
    fig = brdfwave.plot_spectra(P, d, spectra=(0, 5), path=path("s.png"))
    top, bot = fig.axes[:2]
    y = top.lines[0].get_ydata()
    assert np.allclose(y, P.reshape(-1, 1)[0]), y
    err = bot.lines[1].get_ydata()  # spectrum 5's error
    assert np.allclose(err, np.asarray(d).reshape(-1, 1)[5] - P.reshape(-1, 1)[5], atol=1e-7)


@case
def bad_input_raises_a_clear_error():
    spectra = brdfwave.decode_bytes(brdfwave.encode(np.ones((4, 8), np.float32), lossless=True))
    for fn, why in ((lambda: brdfwave.plot_hemisphere(spectra), "directions"),
                    (lambda: brdfwave.plot_spectra(P, np.ones((3, 3), np.float32)), "shapes")):
        try:
            fn()
        except BrdfwaveError as e:
            assert why in str(e), str(e)
        else:
            raise AssertionError("no error: " + why)


print("RESULT: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
