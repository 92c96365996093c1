# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave.plot: the pictures of `brdfwave plot` with matplotlib (when it is
installed): a hemisphere map of a BRDF or reflectance, spectra before and
after compression with the error below, and a rate-distortion curve.

    import brdfwave
    m = brdfwave.decode("satin.bwv")
    brdfwave.plot_hemisphere(m, incoming=8, path="hemisphere.png")
    brdfwave.plot_spectra(original, brdfwave.decode("field.bwv"), spectra=(0, 30),
                          wavelengths=w, path="spectra.png")
    brdfwave.plot_rd(original, level=4, incoming=True, path="rd.png")

Each returns the matplotlib Figure (written to `path` when given). The
projection is the command line's: the hemisphere seen from above, the
zenith angle linear in the radius (90 degrees at the rim), the azimuth
counter-clockwise from the right.
"""
import ctypes

import numpy as np

from ._lib import BrdfwaveError, lib

__all__ = ["plot_hemisphere", "plot_spectra", "plot_rd", "DEFAULT_RATIOS"]

DEFAULT_RATIOS = (2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256)


def _pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt
    except ImportError:
        raise BrdfwaveError("brdfwave.plot needs matplotlib (Debian: python3-matplotlib)") \
            from None
    return plt


def _triangles(level):
    """(n, 3, 3): the vertices of the triangles of one level, grid order."""
    L = lib()
    n = L.bwh_grid_count(int(level))
    if n == 0:
        raise BrdfwaveError("level must be 0..6")
    v = np.zeros((n, 3, 3), dtype=np.float64)
    L.bwh_grid_triangles.restype = ctypes.c_int
    L.bwh_grid_triangles.argtypes = [ctypes.c_uint, ctypes.c_void_p]
    if L.bwh_grid_triangles(int(level), v.ctypes.data) != 0:
        raise BrdfwaveError("grid: level %d rejected" % level)
    return v


def _polar(d):
    """unit vectors (..., 3) to the disc: theta in degrees along the radius"""
    theta = np.degrees(np.arccos(np.clip(d[..., 2], -1.0, 1.0)))
    phi = np.arctan2(d[..., 1], d[..., 0])
    return np.stack([theta * np.cos(phi), theta * np.sin(phi)], axis=-1)


def _outlines(level, steps=6):
    """each triangle's outline along its great-circle edges, projected"""
    tri = _triangles(level)
    pts = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        for k in range(steps):
            t = k / steps
            p = (1 - t) * tri[:, a] + t * tri[:, b]
            pts.append(p / np.linalg.norm(p, axis=1, keepdims=True))
    return _polar(np.stack(pts, axis=1))


def plot_hemisphere(m, incoming=None, band=None, level=None, log=False, edges=False,
                    path=None, title=None, ax=None):
    """A BRDF or reflectance over the outgoing hemisphere as a disc of
    geodesic triangles. m: a Measurement (decode()), or values per triangle
    (n_out,) with level. incoming: the incoming direction's index (default:
    the middle one); band: one band (default: the mean over the bands)."""
    plt = _pyplot()
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import LogNorm, Normalize
    a = np.asarray(m, dtype=np.float64)
    header = getattr(m, "header", None)
    if header is not None:
        if header["shape"] == "spectra":
            raise BrdfwaveError("a set of spectra has no directions (plot_spectra shows it)")
        level = header["level_out"]
        if a.ndim == 2:
            a = a[np.newaxis]
        if incoming is None:
            incoming = a.shape[0] // 2
        a = a[incoming]
        a = a.mean(axis=-1) if band is None else a[:, band]
    elif level is None:
        raise BrdfwaveError("values per triangle need the level")
    vals = a.reshape(-1)
    if vals.size != 4 * 4 ** level:
        raise BrdfwaveError("%d values for level %d" % (vals.size, level))
    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(7, 6))
    else:
        fig = ax.figure
    norm = LogNorm(vmin=vals[vals > 0].min(), vmax=vals.max()) if log else \
        Normalize(vmin=vals.min(), vmax=vals.max())
    pc = PolyCollection(_outlines(level), array=np.clip(vals, norm.vmin, None) if log else vals,
                        cmap="viridis", norm=norm, edgecolors="white" if edges else "face",
                        linewidths=0.3 if edges else 0.2)
    ax.add_collection(pc)
    for r in (30, 60):
        ax.add_patch(plt.Circle((0, 0), r, fill=False, color="white", lw=0.8))
        ax.text(2, r - 7, "theta %d\u00b0" % r, color="white", fontsize=8)
    ax.add_patch(plt.Circle((0, 0), 90, fill=False, color="black", lw=1.2))
    ax.plot([-90, 90], [0, 0], color="white", lw=0.6, ls="--")
    ax.plot([0, 0], [-90, 90], color="white", lw=0.6, ls="--")
    for label, xy, ha in (("0\u00b0", (93, 0), "left"), ("phi 90\u00b0", (0, 93), "center"),
                          ("180\u00b0", (-93, 0), "right"), ("270\u00b0", (0, -97), "center")):
        ax.text(xy[0], xy[1], label, ha=ha, va="center", fontsize=9)
    if header is not None and header["shape"] in ("brdf", "brdf-full"):
        wi = m.incoming[incoming] if m.incoming is not None else None
        if wi is None:  # isotropic: in the plane phi = 0
            t = np.radians((incoming + 0.5) * 90.0 / header["n_in"])
            wi = np.array([np.sin(t), 0.0, np.cos(t)])
        x, y = _polar(np.asarray(wi))
        ax.plot([x], [y], "o", mfc="none", mec="white", ms=9, mew=2)
        ax.text(x + 4, y + 4, "in", color="white", fontsize=9)
    ax.set_xlim(-100, 100)
    ax.set_ylim(-100, 100)
    ax.set_aspect("equal")
    ax.axis("off")
    fig.colorbar(pc, ax=ax, label="value" + ("" if band is None else ", band %d" % band))
    if title:
        ax.set_title(title)
    if path and own:
        fig.savefig(path, dpi=100)
    return fig


def plot_spectra(original, decoded, spectra=(0,), wavelengths=None, path=None, title=None):
    """Spectra of a measurement (solid) and of its payload decoded (dashed),
    with the error (decoded - original) below. original and decoded: arrays
    of the same shape, the bands last; spectra: indices into the spectra
    (all dimensions but the last, flattened)."""
    plt = _pyplot()
    o = np.asarray(original, dtype=np.float64)
    d = np.asarray(decoded, dtype=np.float64)
    if o.shape != d.shape:
        raise BrdfwaveError("shapes differ: %s and %s" % (o.shape, d.shape))
    bands = o.shape[-1]
    o = o.reshape(-1, bands)
    d = d.reshape(-1, bands)
    if wavelengths is None:
        wavelengths = getattr(decoded, "wavelengths", None)
    x = np.arange(bands) if wavelengths is None else np.asarray(wavelengths)
    fig, (top, bot) = plt.subplots(2, 1, figsize=(9, 7), sharex=True,
                                   gridspec_kw={"height_ratios": [2.4, 1]})
    # a few bands: their points are marked (one band would be no line at all)
    mk, mkd = ("o", "x") if bands < 24 else (None, None)
    for k, s in enumerate(spectra):
        c = "C%d" % k
        top.plot(x, o[s], color=c, lw=2.2, marker=mk, label="spectrum %d" % s)
        top.plot(x, d[s], color="black", lw=0.9, ls="--", marker=mkd,
                 label="decoded" if k == len(spectra) - 1 else None)
        bot.plot(x, d[s] - o[s], color=c, lw=0.9, marker=mk)
    bot.axhline(0, color="grey", lw=0.8)
    top.set_ylabel("value")
    top.legend()
    emax = max(np.abs(d[s] - o[s]).max() for s in spectra)
    bot.set_title("decoded - original (max |error| %.4g over these)" % emax, fontsize=10)
    bot.set_ylabel("error")
    bot.set_xlabel("band" if wavelengths is None else "wavelength (nm)")
    if title:
        top.set_title(title)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=100)
    return fig


def plot_rd(values, ratios=DEFAULT_RATIOS, path=None, title=None, **shape):
    """Encodes float values with the byte budgets of encode(ratio=R) for each
    R, decodes them and plots bits/sample against the relative L2 error in
    percent and the max absolute error (`brdfwave plot rd`). shape: encode()'s
    level, incoming, level_in. Returns (figure, points): points a list of
    (ratio, bytes, bits_per_sample, relative_l2_percent, max_abs_error); a
    budget too small for the data is left out."""
    plt = _pyplot()
    from .codec import decode_bytes, encode
    x = np.asarray(values, dtype=np.float32)
    ref = x.astype(np.float64).ravel()
    nz = ref != 0
    points = []
    for r in ratios:
        try:
            p = encode(x, ratio=r, **shape)
        except BrdfwaveError:
            continue
        err = np.asarray(decode_bytes(p), dtype=np.float64).ravel() - ref
        l2 = 100.0 * np.sqrt(np.mean((err[nz] / ref[nz]) ** 2)) if nz.any() else 0.0
        points.append((r, len(p), 8.0 * len(p) / ref.size, l2, float(np.abs(err).max())))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.8))
    shown = [p for p in points if p[4] > 0]  # a log axis has no 0
    bps = [p[2] for p in shown]
    left.loglog(bps, [p[3] for p in shown], "o-")
    right.loglog(bps, [p[4] for p in shown], "o-")
    for ax, yl in ((left, "relative L2 error (%)"), (right, "max absolute error")):
        ax.set_xlabel("bits/sample")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=100)
    return fig, points
