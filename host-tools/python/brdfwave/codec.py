# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave.codec: numpy arrays to payloads and back, with their metadata;
the measurement files of the field read to arrays; the geodesic grid.

    import numpy as np, brdfwave
    wl = np.linspace(350.0, 2500.0, 2151)
    p = brdfwave.encode(spectra, wavelengths=wl, quantity="reflectance factor",
                        max_error=1e-4)                    # bytes
    m = brdfwave.decode(p)                                 # a Measurement
    m.wavelengths, m.quantity, m.unit, m.metadata
    s = brdfwave.read_sed(["a.sed", "b.sed"])              # a Measurement too
    p = brdfwave.encode(s, lossless=True, scale=1e-5)      # with its metadata

The codec itself is libbrdfwave (the C library), loaded with ctypes; its
structures are checked against this package's at load (brdfwave._abi).
"""
import ctypes
import errno
import json
import os
import tempfile

import numpy as np

from ._lib import (BrdfwaveError, DeviceJob, Dims, EncodeOpts, Header, Salvage, Shape,
                   _header_dict,
                   free, last_error, lib)
from .guarantee import guarantee

__all__ = ["BrdfwaveError", "Measurement", "decode", "decode_bytes", "encode", "grid",
           "read", "read_sed", "read_sig", "read_asd", "read_usgs", "read_envi", "read_csv",
           "read_npy", "read_bsdf", "read_gonio"]

_SHAPE_NAMES = ("spectra", "reflectance", "brdf-iso", "brdf-full")
_INT_TYPES = {np.dtype(np.uint8): "u8", np.dtype(np.int16): "i16", np.dtype(np.uint16): "u16",
              np.dtype(np.int32): "i32"}
_SOURCE_DTYPES = {"u8": np.uint8, "i16": np.int16, "u16": np.uint16, "i32": np.int32,
                  "f32": np.float32, "f64": np.float64}

# the library's messages name command-line options; Python callers know
# the keyword arguments
_OPTION_NAMES = (("--max-rel-error", "max_rel_error="), ("--rel-floor", "rel_floor="),
                 ("--max-error", "max_error="), ("--bytes", "nbytes="), ("--ratio", "ratio="),
                 ("--scale", "scale="), ("--lossless", "lossless=True"),
                 ("--max-samples", "max_samples="), ("--relative", "relative=True"),
                 ("--basis", "basis="), ("--symmetry", "symmetry="), ("--coder", "coder="),
                 ("--level-in", "level_in="), ("--level", "level="),
                 ("--incoming", "incoming="), ("--bands", "the last axis"))


def _pythonic(msg):
    for opt, kw in _OPTION_NAMES:
        msg = msg.replace(opt, kw)
    return msg


def _error():
    return BrdfwaveError(_pythonic(last_error()))


class Measurement(np.ndarray):
    """A measurement: its values as a numpy array with its axes and metadata.

    Shape: spectra (n_spectra, bands); reflectance (n_out, bands); BRDF
    (n_in, n_out, bands), directions in grid order.
      metadata         the metadata as a dict ('brdfwave info --json' "metadata")
      wavelengths      (bands,) array in wavelength_unit ("nm", "um", "cm-1"), or None
      quantity, unit   what the values are ("reflectance factor", "1"; "brdf",
                       "sr^-1"; ...), or None
      incidence        (n_in,) zenith angles of an isotropic BRDF's incoming
                       directions in incidence_unit ("deg" or "rad"), or None
      directions       (n_out, 3) unit vectors of the outgoing triangles, or None
      incoming         (n_in, 3) unit vectors of the incoming triangles (full BRDF),
                       else None
      layout           "spectra", "reflectance", "brdf-iso", "brdf-full", or None
      level, level_in  grid levels of directional data
      header           the payload header as a dict (decoded payloads)
      guarantee        what the payload promises of every value (brdfwave.guarantee),
                       for decoded payloads
      mask             decode(..., salvage=True): per value 0 exact, 1 approximate
                       (rebuilt from coarser levels), 2 missing; else None
      segments, lost_segments   decode(..., salvage=True): the payload's segments,
                       and how many of them were lost
      tail_lost        decode(..., salvage=True): True when a float payload's tail
                       (its values' low bits and exceptions, record 0x01) was not
                       used: the values from the samples alone, approximate
      rows             decode(..., rows=) or region=: the source's rows decoded
                       (indices, ascending), else None
      bands            decode(..., bands=) or wavelength_range=: the source's bands
                       kept (indices, ascending), else None
    """

    _ATTRS = ("metadata", "header", "layout", "level", "level_in", "directions", "incoming",
              "guarantee", "mask", "segments", "lost_segments", "tail_lost", "rows",
              "bands")

    def __new__(cls, values, metadata=None, layout=None, level=None, level_in=None,
                header=None, wavelengths=None):
        obj = np.asarray(values).view(cls)
        obj.metadata = dict(metadata or {})
        if wavelengths is not None:
            obj.metadata["wavelengths"] = [float(w) for w in np.asarray(wavelengths).ravel()]
        obj.layout = layout
        obj.level = level
        obj.level_in = level_in
        obj.header = header
        obj.directions = _directions(level) if layout and layout != "spectra" else None
        obj.incoming = _directions(level_in) if layout == "brdf-full" else None
        obj.guarantee = None
        obj.mask = obj.segments = obj.lost_segments = obj.tail_lost = obj.rows = None
        obj.bands = None
        return obj

    def __array_finalize__(self, obj):
        if obj is None:
            return
        for a in self._ATTRS:
            setattr(self, a, getattr(obj, a, None))
        if self.metadata is None:
            self.metadata = {}

    def _meta(self, key, array=False):
        v = self.metadata.get(key)
        if v is None:
            return None
        return np.asarray(v, dtype=np.float64) if array else v

    @property
    def wavelengths(self):
        return self._meta("wavelengths", True)

    @property
    def wavelength_unit(self):
        return self.metadata.get("wavelength_unit", "nm" if "wavelengths" in self.metadata
                                 else None)

    @property
    def incidence(self):
        return self._meta("incidence", True)

    @property
    def incidence_unit(self):
        return self.metadata.get("incidence_unit", "deg" if "incidence" in self.metadata
                                 else None)

    @property
    def quantity(self):
        return self.metadata.get("quantity")

    @property
    def unit(self):
        return self.metadata.get("unit")


def grid(level):
    """The geodesic triangles of one level in codec (scan) order, as
    `brdfwave grid --level L` prints them: a structured array with the fields
    index, theta_deg, phi_deg, x, y, z, solid_angle_sr."""
    L = lib()
    if not isinstance(level, (int, np.integer)) or isinstance(level, bool):
        raise TypeError("level must be an integer 0..6, not %s" % type(level).__name__)
    if not 0 <= level <= 6:
        raise BrdfwaveError("level must be an integer 0..6")
    n = L.bwh_grid_count(int(level))
    xyz = np.zeros((n, 3), dtype=np.float64)
    sa = np.zeros(n, dtype=np.float64)
    if L.bwh_grid_centres(int(level), xyz.ctypes.data, sa.ctypes.data) != 0:
        raise BrdfwaveError("grid: level %d rejected" % level)
    out = np.zeros(n, dtype=[("index", np.int64), ("theta_deg", np.float64),
                             ("phi_deg", np.float64), ("x", np.float64), ("y", np.float64),
                             ("z", np.float64), ("solid_angle_sr", np.float64)])
    out["index"] = np.arange(n)
    # as cmd_grid.c: theta = acos(clamped z), phi = atan2(y, x) in [0, 360)
    out["theta_deg"] = np.degrees(np.arccos(np.clip(xyz[:, 2], -1.0, 1.0)))
    phi = np.degrees(np.arctan2(xyz[:, 1], xyz[:, 0]))
    phi = np.where(phi < 0.0, phi + 360.0, phi)
    out["phi_deg"] = np.where(phi >= 360.0, 0.0, phi)
    out["x"], out["y"], out["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    out["solid_angle_sr"] = sa
    return out


def _directions(level):
    if level is None:
        return None
    g = grid(level)
    return np.stack([g["x"], g["y"], g["z"]], axis=1)


def _read_bytes(source):
    if isinstance(source, (bytes, bytearray, memoryview)):
        return bytes(source), None
    if isinstance(source, (str, os.PathLike)):
        with open(source, "rb") as f:  # FileNotFoundError etc. name the file
            return f.read(), os.fspath(source)
    raise TypeError("a payload is bytes or a path, not %s" % type(source).__name__)


def _put_missing(values, meta):
    miss = meta.get("missing")
    if not miss or values.dtype.kind != "f":
        return
    flat = values.reshape(-1)
    for start, n in miss.get("runs", []):
        flat[start:start + n] = miss["value"]


def decode_bytes(payload, wavelengths=None, integers=False, max_samples=0, salvage=False,
                 incoming=None, level=None, rows=None, region=None, level_in=None, bands=None,
                 wavelength_range=None):
    """Decodes a payload held in memory; see decode()."""
    return decode(payload, wavelengths=wavelengths, integers=integers, max_samples=max_samples,
                  salvage=salvage, incoming=incoming, level=level, rows=rows, region=region,
                  level_in=level_in, bands=bands, wavelength_range=wavelength_range)


def decode(source, *, wavelengths=None, integers=False, max_samples=0, salvage=False,
           incoming=None, level=None, rows=None, region=None, level_in=None, bands=None,
           wavelength_range=None):
    """Decodes a payload (bytes, or the path of a payload file) to a
    Measurement: float32 values (integers=True: the codec's int32 samples) in
    the layout of `brdfwave decode`, [incoming][outgoing][band], with the
    metadata the payload carries (wavelengths, quantity and unit, incidence
    angles, instrument, time, location, free fields), in the units it was
    given in. Samples the source marked missing get its missing value back.
    wavelengths: for payloads without them. Payloads that decode to more
    than max_samples samples (0: the library's default, 2**26) are refused
    before anything is allocated. salvage=True: a payload coded in segments
    (encode(..., segments=N)) that is damaged or cut decodes in part: every
    whole segment is decoded, the rest rebuilt from the coarser levels it
    has; the Measurement's `mask` (uint8, the values' shape) is then 0 where
    a value is exact, 1 approximate, 2 missing, and `lost_segments` and
    `segments` count the segments (without salvage such a payload is
    refused, as every payload that is not whole). incoming=K: only incoming
    direction K of a BRDF (a reflectance, (n_out, bands)) or spectrum K of a
    set of spectra ((1, bands)), decoding only what it depends on (with
    segments, only the segments that hold it); not for a full BRDF coded
    with the reciprocity step. level=L: a directional measurement at a
    coarser outgoing level L (level of detail), each triangle's value the
    mean of the samples below it, decoding only the coarser levels;
    level_in=Li (alone or with level=): a full BRDF at a coarser incoming
    level too, decoding only the coarser incoming blocks. rows=[K, ...] (indices, or a boolean array of n_in): only those incoming
    directions of a BRDF, or those spectra, in ascending order, as a BRDF
    of that many incoming directions ((k, n_out, bands)) or that many
    spectra, decoding what they share once; region=(theta, phi, radius), in
    degrees: the incoming directions of a full BRDF whose triangles'
    centres lie within radius of the direction (theta, phi), or the
    incidences of an isotropic BRDF within radius of theta. With either,
    the Measurement's `rows` names the source rows decoded (and `incoming`
    their directions, for a full BRDF). bands=[K, ...] (indices, or a
    boolean array of bands), or wavelength_range=(lo, hi) (the bands whose
    wavelength lies in [lo, hi], in the payload's wavelength unit), with any
    of the above: only those bands, in order, with their wavelengths,
    bandwidths and names (`bands` names the source bands kept); the payload
    is decoded as without them, but for one coded with band_access=True
    without any of the above, whose bands from the first chosen to the last
    alone are decoded."""
    payload, path = _read_bytes(source)
    try:
        if bands is not None and wavelength_range is not None:
            raise BrdfwaveError("give bands= or wavelength_range=, not both")
        h = Header()
        if ((bands is not None or wavelength_range is not None) and incoming is None and
                level is None and level_in is None and rows is None and region is None and
                not salvage and lib().bw_header_parse_fields(payload, len(payload),
                                                             ctypes.byref(h)) == 0 and
                h.band_access):
            return _decode_band_range(payload, h.dims.bands, bands, wavelength_range,
                                      wavelengths, integers)
        if bands is not None or wavelength_range is not None:
            return _keep_bands(decode(payload, wavelengths=wavelengths, integers=integers,
                                      max_samples=max_samples, salvage=salvage,
                                      incoming=incoming, level=level, rows=rows, region=region,
                                      level_in=level_in), bands, wavelength_range)
        lod = level is not None or level_in is not None
        if ((incoming is not None) + lod + bool(salvage) + (rows is not None) +
                (region is not None) > 1):
            raise BrdfwaveError("give one of incoming=, rows=, region=, level= (level_in=) and "
                                "salvage=True")
        if rows is not None or region is not None:
            return _decode_rows(payload, rows, region, wavelengths, integers)
        if incoming is not None:
            return _decode_row(payload, incoming, wavelengths, integers)
        if lod:
            return _decode_lod(payload, level, level_in, wavelengths, integers)
        return _decode(payload, wavelengths, integers, max_samples, salvage)
    except BrdfwaveError as e:
        if path is None:
            raise
        raise BrdfwaveError("%s: %s" % (path, e)) from None


def _keep_bands(m, bands, wavelength_range):
    """The bands of Measurement m chosen by decode()'s bands= or
    wavelength_range=, with their metadata as the library cuts it
    (bwh_meta_json_bands: the missing samples' runs moved to the values
    kept)."""
    sel = _band_selection(m.shape[-1], m.wavelengths, m.wavelength_unit, bands, wavelength_range)
    return _cut_bands(m, sel)


def _decode_band_range(payload, nb, bands, wavelength_range, wavelengths, integers):
    """decode(bands=, wavelength_range=) of a payload with band access: only
    the bands from the first chosen to the last are decoded
    (bwh_decode_bands), then those chosen kept."""
    meta = _meta_of(payload)
    wl = _wavelengths_for(wavelengths, nb)
    if wl is None and meta.get("wavelengths") is not None:
        wl = np.asarray(meta["wavelengths"], dtype=np.float64)
    sel = _band_selection(nb, wl, meta.get("wavelength_unit", ""), bands, wavelength_range)
    idx = np.flatnonzero(sel)
    lo, hi = int(idx[0]), int(idx[-1]) + 1
    L = lib()
    vals, h, d = _decode_part(lambda p, n, a, *rest: L.bwh_decode_bands(p, n, a[0], a[1], *rest),
                              payload, (lo, hi), integers)
    marks = np.zeros(nb, dtype=np.uint8)
    marks[lo:hi] = 1
    meta = _meta_bands(meta, nb, marks)
    m = _measurement(vals, meta, d, h, payload, None if wavelengths is None else wl[lo:hi])
    _put_missing(m, meta)
    out = _cut_bands(m, sel[lo:hi])
    out.bands = idx
    return out


def _meta_bands(meta, nb, marks):
    """The metadata dict of the nb bands marked in marks (uint8), as the
    library cuts it (bwh_meta_json_bands)."""
    j = ctypes.c_char_p()
    if lib().bwh_meta_json_bands(json.dumps(meta).encode("utf-8"), nb, marks.ctypes.data,
                                 ctypes.byref(j)) != 0:
        raise _error()
    try:
        return json.loads(j.value.decode("utf-8"))
    finally:
        free(j)


def _band_selection(nb, wl, unit, bands, wavelength_range):
    """The bands (a boolean per band of nb) that decode()'s bands= or
    wavelength_range= (over the wavelengths wl, or None) choose."""
    if wavelength_range is not None:
        try:
            lo, hi = (float(x) for x in wavelength_range)
        except (TypeError, ValueError):
            raise BrdfwaveError("wavelength_range must be two numbers, (lo, hi)") from None
        if not lo <= hi:
            raise BrdfwaveError("wavelength_range: lo must not exceed hi")
        if wl is None or wl.shape != (nb,):
            raise BrdfwaveError("the payload has no wavelength per band: choose bands by "
                                "number (bands=)")
        sel = (wl >= lo) & (wl <= hi)
        if not sel.any():
            raise BrdfwaveError("no band's wavelength lies in [%g, %g] %s" % (lo, hi, unit))
    else:
        b = np.asarray(bands)
        if b.dtype == bool:
            if b.shape != (nb,):
                raise BrdfwaveError("bands= as booleans needs one per band (%d)" % nb)
            sel = b
        else:
            if b.ndim > 1 or b.size == 0 or b.dtype.kind not in "iu":
                raise BrdfwaveError("bands= must be band indices, or a boolean per band")
            if b.min() < 0 or b.max() >= nb:
                raise BrdfwaveError("bands= past the last band (%d)" % (nb - 1))
            sel = np.zeros(nb, dtype=bool)
            sel[b] = True
        if not sel.any():
            raise BrdfwaveError("no band chosen")
    return sel


def _cut_bands(m, sel):
    """Measurement m's bands marked in sel, with their metadata."""
    nb = m.shape[-1]
    idx = np.flatnonzero(sel)
    out = Measurement(np.ascontiguousarray(np.asarray(m)[..., idx]), m.metadata, m.layout,
                      m.level, m.level_in, m.header)
    for a in Measurement._ATTRS:
        if a not in ("metadata", "mask"):
            setattr(out, a, getattr(m, a))
    out.metadata = _meta_bands(m.metadata, nb, np.ascontiguousarray(sel, dtype=np.uint8))
    out.mask = None if m.mask is None else np.ascontiguousarray(m.mask[..., idx])
    out.bands = idx
    return out


def evaluate(source, wi, wo, *, wavelength=None, band=None):
    """f(wi, wo) of a BRDF or reflectance payload (bytes, or a path) straight
    from the payload: only the incoming directions that the wi read are
    decoded (a full BRDF's triangle holding each, an isotropic BRDF's two
    incidences about each; with segments only the segments that hold
    them; a payload coded with the reciprocity step or keeping float bits
    in a tail is decoded whole), then f is interpolated as brdfwave's
    renderer does: barycentric over the outgoing triangle centres, linear
    in the incidence angle between tables, a B-spline over the bands at
    `wavelength` (in the payload's wavelength range, nm), or band `band`,
    else the mean over the bands. wi, wo: unit vectors, (3,) or (n, 3)
    (z the surface normal). Returns a float, or an (n,) array; NaN below
    the horizon."""
    payload, path = _read_bytes(source)
    wi = np.ascontiguousarray(wi, dtype=np.float64)
    wo = np.ascontiguousarray(wo, dtype=np.float64)
    one = wi.ndim == 1
    wi, wo = np.atleast_2d(wi), np.atleast_2d(wo)
    if wi.shape != wo.shape or wi.ndim != 2 or wi.shape[1] != 3:
        raise BrdfwaveError("wi and wo must be unit vectors of the same shape, (3,) or (n, 3)")
    if wavelength is not None and band is not None:
        raise BrdfwaveError("give wavelength= or band=, not both")
    n = wi.shape[0]
    lam = None
    if wavelength is not None:
        lam = np.ascontiguousarray(np.broadcast_to(np.asarray(wavelength, dtype=np.float64),
                                                   (n,)))
    if band is not None and not (isinstance(band, (int, np.integer)) and band >= 0):
        raise BrdfwaveError("band must be a whole number from 0")
    out = np.empty(n, dtype=np.float64)
    if lib().bwh_payload_eval(payload, len(payload), n, wi.ctypes.data, wo.ctypes.data,
                              None if lam is None else lam.ctypes.data,
                              -1 if band is None else int(band), out.ctypes.data) != 0:
        e = _error()
        raise BrdfwaveError("%s: %s" % (path, e)) if path else e
    return float(out[0]) if one else out


def _meta_of(payload, row=None):
    """The payload's metadata as a dict (of one row alone: what decode with
    incoming= keeps)."""
    L = lib()
    j = ctypes.c_char_p()
    rc = (L.bwh_meta_json_of_payload(payload, len(payload), ctypes.byref(j)) if row is None else
          L.bwh_meta_row_json(payload, len(payload), int(row), ctypes.byref(j)))
    if rc != 0:
        raise _error()
    try:
        return json.loads(j.value.decode("utf-8"))
    finally:
        free(j)


def _wavelengths_for(wavelengths, bands):
    """The caller's wavelengths for a payload without them: one per band."""
    if wavelengths is None:
        return None
    wavelengths = np.asarray(wavelengths, dtype=np.float64)
    if wavelengths.shape != (bands,):
        raise BrdfwaveError("%d wavelengths given for %d bands" % (wavelengths.size, bands))
    return wavelengths


def _shape_of(d):
    """The array shape of a measurement of dims d."""
    if d.shape == 0:
        return (d.n_in, d.bands)
    if d.shape == 1:
        return (d.n_out, d.bands)
    return (d.n_in, d.n_out, d.bands)


def _measurement(vals, meta, d, h, payload, wavelengths):
    """The Measurement of decoded values of dims d from a payload of header h."""
    m = Measurement(vals.reshape(_shape_of(d)), meta, _SHAPE_NAMES[d.shape],
                    d.level_out if d.shape > 0 else None, d.level_in if d.shape == 3 else None,
                    _header_dict(h, payload), _wavelengths_for(wavelengths, d.bands))
    m.guarantee = guarantee(payload)
    return m


def _decode_part(call, payload, arg, integers):
    """A partial decode (bwh_decode_incoming, bwh_decode_level,
    bwh_decode_rows): its values (or integers), the payload's header and the
    dims decoded."""
    h, d = Header(), Dims()
    s = ctypes.POINTER(ctypes.c_int32)()
    v = ctypes.POINTER(ctypes.c_float)()
    if call(payload, len(payload), arg, ctypes.byref(h), ctypes.byref(d),
            ctypes.byref(s) if integers else None, None if integers else ctypes.byref(v)) != 0:
        raise _error()
    try:
        n = d.n_in * d.n_out * d.bands
        vals = np.ctypeslib.as_array(s if integers else v, shape=(n,)).copy()
    finally:
        free(s)
        free(v)
    return vals, h, d


def _decode_lod(payload, level, level_in, wavelengths, integers):
    for name, v in (("level", level), ("level_in", level_in)):
        if v is not None and not (isinstance(v, (int, np.integer)) and 0 <= v <= 6):
            raise BrdfwaveError("%s must be a whole number from 0 to 6" % name)
    L = lib()
    vals, h, d = _decode_part(
        lambda p, n, a, *rest: L.bwh_decode_levels(p, n, a[0], a[1], *rest), payload,
        (-1 if level is None else int(level), -1 if level_in is None else int(level_in)),
        integers)
    meta = _meta_of(payload)
    meta.pop("missing", None)  # the source's missing samples are at its own level
    return _measurement(vals, meta, d, h, payload, wavelengths)


def _decode_row(payload, incoming, wavelengths, integers):
    if not (isinstance(incoming, (int, np.integer)) and 0 <= incoming < 2 ** 32 - 1):
        raise BrdfwaveError("incoming must be a whole number from 0")
    vals, h, d = _decode_part(lib().bwh_decode_incoming, payload, int(incoming), integers)
    return _measurement(vals, _meta_of(payload, incoming), d, h, payload, wavelengths)


def _row_marks(payload, rows, region):
    """The rows to decode as one byte per row of the payload, and its header."""
    L = lib()
    h = Header()
    st = L.bwh_header_salvage(payload, len(payload), ctypes.byref(h))
    if st != 0:
        raise BrdfwaveError(L.bw_strerror(st).decode())
    n = h.dims.n_in
    marks = np.zeros(n, dtype=np.uint8)
    if region is not None:
        try:
            theta, phi, radius = (float(x) for x in region)
        except (TypeError, ValueError):
            raise BrdfwaveError("region must be (theta, phi, radius) in degrees") from None
        inc = None
        if h.dims.shape == 2:  # an isotropic BRDF: the payload's incidence angles
            meta = _meta_of(payload)
            if len(meta.get("incidence", [])) == n:
                inc = np.asarray(meta["incidence"], dtype=np.float64)
                if meta.get("incidence_unit") == "rad":
                    inc = np.degrees(inc)
                inc = np.ascontiguousarray(inc)
        k = L.bwh_region_rows(ctypes.byref(h), None if inc is None else inc.ctypes.data, theta,
                              phi, radius, marks.ctypes.data)
        if k < 0:
            raise _error()
        if k == 0:
            raise BrdfwaveError("no incoming direction lies within %g degrees of (%g, %g)"
                                % (radius, theta, phi))
        return marks, h
    r = np.asarray(rows)
    if r.dtype == np.bool_:
        if r.shape != (n,):
            raise BrdfwaveError("rows as a mask needs %d values, one per row" % n)
        marks[r] = 1
    else:
        if r.ndim != 1 or not np.issubdtype(r.dtype, np.integer) or not r.size:
            raise BrdfwaveError("rows must be row indices (or a boolean mask of the rows)")
        if r.min() < 0 or r.max() >= n:
            raise BrdfwaveError("rows must lie in 0..%d" % (n - 1))
        marks[r] = 1
    return marks, h


def _decode_rows(payload, rows, region, wavelengths, integers):
    L = lib()
    marks, src = _row_marks(payload, rows, region)
    vals, h, d = _decode_part(L.bwh_decode_rows, payload, marks.ctypes.data, integers)
    j = ctypes.c_char_p()
    if L.bwh_meta_rows_json(payload, len(payload), marks.ctypes.data, ctypes.byref(j)) != 0:
        raise _error()
    try:
        meta = json.loads(j.value.decode("utf-8"))
    finally:
        free(j)
    m = _measurement(vals, meta, d, h, payload, wavelengths)
    m.rows = np.flatnonzero(marks)
    if src.dims.shape == 3:
        m.incoming = _directions(src.dims.level_in)[m.rows]
    return m


def _decode(payload, wavelengths, integers, max_samples, salvage=False):
    L = lib()
    h = Header()
    s = ctypes.POINTER(ctypes.c_int32)()
    v = ctypes.POINTER(ctypes.c_float)()
    mk = ctypes.POINTER(ctypes.c_uint8)()
    sv = Salvage()
    args = (payload, len(payload), int(max_samples), ctypes.byref(h),
            ctypes.byref(s) if integers else None, None if integers else ctypes.byref(v))
    if salvage:
        rc = L.bwh_decode_salvage(*args, ctypes.byref(mk), ctypes.byref(sv))
    else:
        rc = L.bwh_decode_limit(*args)
    if rc < 0:
        raise _error()
    try:
        d = h.dims
        n = d.n_in * d.n_out * d.bands
        if integers:
            vals = np.ctypeslib.as_array(s, shape=(n,)).copy()
        else:
            vals = np.ctypeslib.as_array(v, shape=(n,)).copy()
        mask = np.ctypeslib.as_array(mk, shape=(n,)).copy() if salvage and n else None
    finally:
        free(s)
        free(v)
        free(mk)
    meta = _meta_of(payload)
    m = _measurement(vals, meta, d, h, payload, wavelengths)
    _put_missing(m, meta)
    if salvage:
        m.mask = None if mask is None else mask.reshape(m.shape)
        m.segments, m.lost_segments = int(sv.segments), int(sv.lost_segments)
        m.tail_lost = bool(sv.tail_lost)
    return m


def _metadata_json(metadata, wavelengths, wavelength_unit, incidence, incidence_unit,
                   quantity, unit, fields, integer_type):
    m = dict(metadata or {})
    if wavelengths is not None:
        m["wavelengths"] = [float(w) for w in np.asarray(wavelengths, dtype=np.float64).ravel()]
        if wavelength_unit is not None:
            m["wavelength_unit"] = wavelength_unit
    if incidence is not None:
        m["incidence"] = [float(a) for a in np.asarray(incidence, dtype=np.float64).ravel()]
        if incidence_unit is not None:
            m["incidence_unit"] = incidence_unit
    if quantity is not None:
        m["quantity"] = quantity
    if unit is not None:
        m["unit"] = unit
    if fields:
        f = dict(m.get("fields") or {})
        f.update({str(k): str(v) for k, v in fields.items()})
        m["fields"] = f
    if integer_type and "sample_type" not in m:
        m["sample_type"] = integer_type
    m.pop("shape", None)
    return json.dumps(m) if m else None


def _write_payload(path, payload):
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise FileNotFoundError(errno.ENOENT, "no such directory for the payload", path)
    fd, tmp = tempfile.mkstemp(prefix=".%s." % os.path.basename(path), dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(payload)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def encode(values, *, wavelengths=None, wavelength_unit=None, incidence=None,
           incidence_unit=None, quantity=None, unit=None, fields=None, metadata=None,
           level=None, incoming=False, level_in=None, lossless=None, max_error=None,
           nbytes=None, ratio=None, relative=False, basis="auto", scale=None, coder=None,
           stream=False, symmetry="auto", path=None, device=None, firmware=None,
           max_rel_error=None, rel_floor=None, effort=None, segments=None,
           progressive=False, band_access=False):
    """Encodes a numpy array to a payload (bytes; also written to `path` if
    given), as `brdfwave encode` does, with its metadata.

    Layout (a Measurement from decode() or read() brings its own):
      level=None                 a set of spectra, values (n_spectra, bands)
      level=L                    a spectral reflectance, values (4*4^L, bands)
      level=L, incoming=True     an isotropic BRDF, values (n_in, 4*4^L, bands)
      level=L, level_in=Li       a full BRDF, values (4*4^Li, 4*4^L, bands)
    Metadata (merged over a Measurement's and `metadata`, a dict with the
    keys of the "metadata" object of 'brdfwave info --json'): wavelengths (one per band) in
    wavelength_unit ("nm" default, "um", "cm-1"); incidence (one zenith angle
    per incoming direction of an isotropic BRDF) in incidence_unit ("deg"
    default, "rad"); quantity ("reflectance factor", "radiance", "brdf",
    "counts", ...) and unit; fields, a dict of free text fields.
    Mode, one of: lossless=True (the default; with scale= float values must
    be whole multiples of it), max_error=E (every value within E), nbytes=N or
    ratio=R (a byte budget; relative=True spends it on relative accuracy of
    positive values); or max_rel_error=R (every value within max(R |x|, F) of
    its input, F = rel_floor or 0), alone or with max_error=E (within the
    tighter of the two). Float values come back bit for bit when lossless.
    The payload records its guarantee (brdfwave.guarantee). Integer arrays (uint8, int16, uint16, int32) are coded
    as they are (never through float32) and decode as those integers; their
    max_error is in their units. basis: "haar", "53", "97", "pred" or "auto";
    effort: "best" (basis="auto" codes the data with each basis, a byte
    budget searches its step) or "fast" (the wavelets ranked on an eighth of
    it, the first and prediction coded there, then the whole once with the
    best; the budget's step estimated and corrected by each encode's size); None: "best" on this host, "fast" with device;
    coder: "range", "ms", "tab" (static tables, for sets of spectra), "rice"
    or "auto" (rice for prediction errors of a bit or more a sample, tab for
    spectra transformed, else ms); None: "range" on this host, "auto" with
    device; segments=N: the body in about N segments, each decodable alone,
    so that a payload damaged or cut on its way still decodes in part
    (decode(..., salvage=True)); progressive=True: embedded segments (bit
    planes, the most significant first): any prefix of the payload decodes
    to an approximation (decode(..., salvage=True)), and with nbytes or
    ratio the payload is the exact coding cut at the budget (transform
    bases); band_access=True: a set of spectra (lossless or max_error) coded
    so that decode(..., bands=) decodes only the bands asked for, at a cost
    that follows them (prediction along the bands, coded by columns);
    stream=True: streamed order; symmetry: "auto",
    "mirror", "reciprocal", "both" or "none". device: None (this host),
    "linux" or "qemu" (the device application encodes, as `brdfwave encode
    --device`; firmware: its image, else found beside the library or named by
    $BW_FIRMWARE_LINUX / $BW_FIRMWARE). The options of reading a file
    (--input-format, --channel, --column, --ignore-value, --wavelength-table)
    are read()'s. For a payload without a metadata record (the CLI's
    --no-metadata) give a plain numpy array (np.asarray(m) of a Measurement)
    and no metadata arguments."""
    L = lib()
    src_meta = {}
    if isinstance(values, Measurement):
        src_meta = values.metadata or {}
        if level is None and not incoming and level_in is None and values.layout:
            if values.layout != "spectra":
                level = values.level
            incoming = values.layout == "brdf-iso"
            level_in = values.level_in if values.layout == "brdf-full" else None
    arr = np.asarray(values)
    if arr.dtype.kind not in "fiub":
        raise TypeError("values must be numbers, not %s" % arr.dtype)
    integer_type = _INT_TYPES.get(arr.dtype) if arr.dtype.kind in "iu" else None
    if arr.dtype.kind in "iu":
        if arr.size and (arr.min() < -(2 ** 24 - 1) or arr.max() > 2 ** 24 - 1):
            raise BrdfwaveError("integer values must lie within +-(2**24 - 1) (the codec's "
                                "samples); %d does not" % (arr.max() if arr.max() > 2 ** 24 - 1
                                                          else arr.min()))
        x = np.ascontiguousarray(arr, dtype=np.int32)
    else:
        x = np.ascontiguousarray(arr, dtype=np.float32)
    if x.ndim < 2:
        raise BrdfwaveError("values need at least 2 dimensions (..., bands)")
    for name, v in (("level", level), ("level_in", level_in)):
        if v is not None and (not isinstance(v, (int, np.integer)) or isinstance(v, bool)):
            raise TypeError("%s must be an integer, not %s" % (name, type(v).__name__))
    s = Shape(-1 if level is None else level, -1 if level_in is None else level_in, 0,
              x.shape[-1])
    if incoming:
        if level is not None and x.ndim != 3:
            raise BrdfwaveError("an isotropic BRDF is (n_in, n_out, bands)")
        s.incoming = x.shape[0]
    d = Dims()
    if L.bwh_shape_dims(ctypes.byref(s), x.size, ctypes.byref(d)) != 0:
        raise _error()
    need = d.n_in * d.n_out * d.bands
    o = EncodeOpts()
    modes = [m for m in (lossless, max_error, nbytes, ratio) if m not in (None, False)]
    if len(modes) > 1:
        raise BrdfwaveError("give only one of lossless, max_error, nbytes, ratio")
    if max_rel_error is not None:
        if not 0 < max_rel_error < 1:
            raise BrdfwaveError("max_rel_error must lie between 0 and 1")
        if lossless or nbytes is not None or ratio is not None:
            raise BrdfwaveError("max_rel_error goes alone or with max_error")
        o.max_rel_error = float(max_rel_error)
    if rel_floor is not None:
        if max_rel_error is None or not rel_floor > 0:
            raise BrdfwaveError("rel_floor needs max_rel_error and must be positive")
        o.rel_floor = float(rel_floor)
    if max_error is not None:
        if not max_error > 0:
            raise BrdfwaveError("max_error must be positive")
        o.mode, o.max_error = 1, float(max_error)
    elif nbytes is not None or ratio is not None:
        o.mode = 2
        if ratio is not None:
            if not ratio > 0:
                raise BrdfwaveError("ratio must be positive")
            nbytes = max(1, int(np.floor(4.0 * need / ratio)))
        if not nbytes >= 1:
            raise BrdfwaveError("nbytes must be at least 1")
        o.byte_budget = int(nbytes)
    if relative:
        if o.mode != 2 or integer_type:
            raise BrdfwaveError("relative=True is for float values with nbytes= or ratio=")
        o.flags |= 0x08
    b = L.bwh_basis_from_name(basis.encode()) if isinstance(basis, str) else -1
    if b < 0:
        raise BrdfwaveError("basis must be haar, 53, 97, pred or auto")
    if effort is None:
        effort = "best" if device is None else "fast"
    if effort not in ("best", "fast"):
        raise BrdfwaveError("effort must be best or fast")
    o.effort = 0 if effort == "best" else 1
    o.basis = b
    if coder is None:
        coder = "range" if device is None else "auto"
    if coder not in ("range", "rice", "ms", "tab", "auto"):
        raise BrdfwaveError("coder must be range, ms, tab, rice or auto")
    if coder == "auto":
        o.coder = 1  # BW_CODER_AUTO
    elif coder == "rice":
        o.flags |= 0x04
    elif coder == "ms":
        o.flags |= 0x80
    elif coder == "tab":
        o.flags |= 0x84
    if scale is not None:
        if not scale > 0:
            raise BrdfwaveError("scale must be positive")
        o.scale = float(scale)
    if stream:
        o.flags |= 0x02
    if segments is not None:
        if not (isinstance(segments, (int, np.integer)) and 1 <= segments <= 1 << 28):
            raise BrdfwaveError("segments must be a whole number from 1 to 2**28")
        o.segments = int(segments)
    if progressive:
        o.progressive = 1
    if band_access:
        o.band_access = 1
    sym = L.bwh_symmetry_from_name(symmetry.encode()) if isinstance(symmetry, str) else -1
    if sym < 0:
        raise BrdfwaveError("symmetry must be auto, mirror, reciprocal, both or none")
    o.flags |= sym
    if device is not None:
        if device not in ("linux", "qemu"):
            raise BrdfwaveError("device must be None, 'linux' or 'qemu'")
        job = DeviceJob(device.encode(), None if firmware is None else os.fsencode(firmware),
                        0.0, -1, None)
        o.device = ctypes.pointer(job)
    merged = dict(src_meta)
    merged.update(metadata or {})
    mj = _metadata_json(merged, wavelengths, wavelength_unit, incidence, incidence_unit,
                        quantity, unit, fields, integer_type)
    area = ctypes.POINTER(ctypes.c_uint8)()
    alen = ctypes.c_size_t()
    if mj is not None and L.bwh_meta_area_from_json(mj.encode("utf-8"), ctypes.byref(d),
                                                     ctypes.byref(area), ctypes.byref(alen)):
        raise BrdfwaveError("metadata: " + _pythonic(last_error()))
    out = ctypes.POINTER(ctypes.c_uint8)()
    n = ctypes.c_size_t()
    try:
        o.ext = ctypes.cast(area, ctypes.c_void_p)
        o.ext_len = alen.value
        if integer_type:
            rc = L.bwh_encode_scaled(ctypes.byref(d), x.ctypes.data_as(
                ctypes.POINTER(ctypes.c_int32)), ctypes.byref(o), float(scale or 1.0),
                ctypes.byref(out), ctypes.byref(n))
        else:
            rc = L.bwh_encode_f32(ctypes.byref(d), x.ctypes.data_as(
                ctypes.POINTER(ctypes.c_float)), ctypes.byref(o), ctypes.byref(out),
                ctypes.byref(n))
        if rc != 0:
            raise _error()
        payload = ctypes.string_at(out, n.value)
    finally:
        free(out)
        free(area)
    if path is not None:
        _write_payload(path, payload)
    return payload


_CHANNELS = ("rgb", "r", "g", "b")
_COLUMNS = ("reflectance", "target", "reference")


def read(paths, *, format=None, level=None, channel="rgb", column="reflectance",
         wavelength_table=None, ignore_value=None):
    """Reads measurement files (one path or a list: several make one set of
    spectra) to a Measurement with their metadata, as `brdfwave encode`
    reads them. format: None (from the content and the name), "sed", "sig",
    "asd", "usgs", "envi", "csv", "npy", "bsdf", "gonio", "f32", "u16",
    "i32". level: the grid of bsdf and goniometer data (default 4);
    channel: bsdf "rgb", "r", "g" or "b"; column: sed, sig, asd
    "reflectance", "target" or "reference"; wavelength_table: a USGS
    wavelength file; ignore_value: samples equal to it are missing. Raw
    samples without a sidecar come back flat (1 dimension)."""
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    paths = [os.fspath(p) for p in paths]
    if not paths:
        raise BrdfwaveError("no file to read")
    for p in paths:
        if p != "-" and not os.path.exists(p):
            raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), p)
    if channel not in _CHANNELS:
        raise BrdfwaveError("channel must be rgb, r, g or b")
    if column not in _COLUMNS:
        raise BrdfwaveError("column must be reflectance, target or reference")
    L = lib()
    arr = (ctypes.c_char_p * len(paths))(*[os.fsencode(p) for p in paths])
    v = ctypes.POINTER(ctypes.c_float)()
    count = ctypes.c_size_t()
    d = Dims()
    j = ctypes.c_void_p()
    if L.bwh_read_flat(arr, len(paths), format.encode() if format else None,
                       -1 if level is None else int(level), _CHANNELS.index(channel),
                       _COLUMNS.index(column),
                       os.fsencode(wavelength_table) if wavelength_table else None,
                       ignore_value is not None,
                       float(ignore_value) if ignore_value is not None else 0.0,
                       ctypes.byref(v), ctypes.byref(count), ctypes.byref(d),
                       ctypes.byref(j)) != 0:
        raise _error()
    try:
        vals = np.ctypeslib.as_array(v, shape=(count.value,)).copy() if count.value else \
            np.zeros(0, np.float32)
        meta = json.loads(ctypes.string_at(j).decode("utf-8"))
    finally:
        free(v)
        free(j)
    layout = meta.pop("shape", None)
    if not d.bands:
        return Measurement(vals, meta)
    if d.shape == 0:
        shape = (d.n_in, d.bands)
    elif d.shape == 1:
        shape = (d.n_out, d.bands)
    else:
        shape = (d.n_in, d.n_out, d.bands)
    return Measurement(vals.reshape(shape), meta, layout or _SHAPE_NAMES[d.shape],
                       d.level_out if d.shape > 0 else None,
                       d.level_in if d.shape == 3 else None)


def _reader(fmt, what):
    def r(paths, **kw):
        return read(paths, format=fmt, **kw)
    r.__name__ = "read_" + fmt
    r.__doc__ = "Reads %s to a Measurement: read(paths, format=%r, **kw)." % (what, fmt)
    return r


read_sed = _reader("sed", "Spectral Evolution .sed files (one or several)")
read_sig = _reader("sig", "Spectra Vista SVC .sig files")
read_asd = _reader("asd", "ASD FieldSpec / Indico binary files (every version)")
read_usgs = _reader("usgs", "USGS splib07 ASCII spectra (wavelength_table=, else beside)")
read_envi = _reader("envi", "an ENVI header with its spectral library or image cube")
read_csv = _reader("csv", "CSV: a wavelength column and a column per spectrum, or angles")
read_npy = _reader("npy", "a numpy .npy array with its JSON sidecar, if any")
read_bsdf = _reader("bsdf", "an RGL .bsdf BRDF sampled on the grid at its incidence angles")
read_gonio = _reader("gonio", "a goniometer CSV projected onto the grid")
