# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave.codec: payloads to numpy arrays and back, the geodesic grid.

    import brdfwave
    m = brdfwave.decode("payload-1.bwv")      # Measurement (a numpy ndarray)
    m.shape, m.header["bands"], m.directions   # directions: unit vectors
    p = brdfwave.encode(m, level=4, max_error=1e-3)
    g = brdfwave.grid(4)                       # the scan order of `brdfwave grid`

The codec itself is libbrdfwave (the C library), loaded with ctypes from
build/host/libbrdfwave.so (`make pylib`) or $BRDFWAVE_LIB. The acquisition
service over I2C is brdfwave.acquire (python3 -m brdfwave.acquire --help).
"""
import ctypes
import os

import numpy as np

from ._lib import (SHAPES, BrdfwaveError, DeviceJob, Dims, EncodeOpts, Header, Shape,
                   _header_dict, free, header_of, last_error, lib)

__all__ = ["BrdfwaveError", "Measurement", "decode", "decode_bytes", "encode", "grid",
           "header_of"]

class Measurement(np.ndarray):
    """A decoded measurement: float32 values with the payload's metadata.

    Shape: spectra (n_spectra, bands); reflectance (n_out, bands); BRDF
    (n_in, n_out, bands), directions in grid order.
      header       the payload header as a dict
      directions   (n_out, 3) unit vectors of the outgoing triangles, None for spectra
      incoming     (n_in, 3) unit vectors of the incoming triangles (full BRDF), else None
      wavelengths  (bands,) in nm if given to decode(), else None (payloads carry none)
    """

    def __new__(cls, values, header=None, directions=None, incoming=None, wavelengths=None):
        obj = np.asarray(values).view(cls)
        obj.header = header
        obj.directions = directions
        obj.incoming = incoming
        obj.wavelengths = wavelengths
        return obj

    def __array_finalize__(self, obj):
        if obj is None:
            return
        self.header = getattr(obj, "header", None)
        self.directions = getattr(obj, "directions", None)
        self.incoming = getattr(obj, "incoming", None)
        self.wavelengths = getattr(obj, "wavelengths", None)


def grid(level):
    """The geodesic triangles of one level in codec (scan) order, as
    `brdfwave grid --level L` prints them: a structured array with the fields
    index, theta_deg, phi_deg, x, y, z, solid_angle_sr."""
    L = lib()
    if not isinstance(level, (int, np.integer)) or not 0 <= level <= 6:
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
    g = grid(level)
    return np.stack([g["x"], g["y"], g["z"]], axis=1)


def decode_bytes(payload, wavelengths=None, integers=False, max_samples=0):
    """Decodes a payload held in memory; see decode()."""
    L = lib()
    payload = bytes(payload)
    h = Header()
    s = ctypes.POINTER(ctypes.c_int32)()
    v = ctypes.POINTER(ctypes.c_float)()
    if L.bwh_decode_limit(payload, len(payload), max_samples, ctypes.byref(h),
                          ctypes.byref(s) if integers else None,
                          None if integers else ctypes.byref(v)) != 0:
        raise BrdfwaveError(last_error())
    try:
        d = h.dims
        n = d.n_in * d.n_out * d.bands
        if integers:
            vals = np.ctypeslib.as_array(s, shape=(n,)).copy()
        else:
            vals = np.ctypeslib.as_array(v, shape=(n,)).copy()
    finally:
        free(s)
        free(v)
    hd = _header_dict(h)
    if d.shape == 0:
        shape = (d.n_in, d.bands)
    elif d.shape == 1:
        shape = (d.n_out, d.bands)
    else:
        shape = (d.n_in, d.n_out, d.bands)
    directions = _directions(d.level_out) if d.shape > 0 else None
    incoming = _directions(d.level_in) if d.shape == 3 else None
    if wavelengths is not None:
        wavelengths = np.asarray(wavelengths, dtype=np.float64)
        if wavelengths.shape != (d.bands,):
            raise BrdfwaveError("%d wavelengths given for %d bands" % (wavelengths.size, d.bands))
    return Measurement(vals.reshape(shape), hd, directions, incoming, wavelengths)


def decode(path, wavelengths=None, integers=False, max_samples=0):
    """Decodes the payload file `path` to a Measurement (float32 values, or the
    codec's int32 samples with integers=True), in the layout of
    `brdfwave decode`: [incoming][outgoing][band]. Payloads that decode to
    more than max_samples samples (0: the library's default, 2**26) are
    refused before anything is allocated."""
    try:
        with open(path, "rb") as f:
            payload = f.read()
    except OSError as e:
        raise BrdfwaveError("%s: %s" % (path, e.strerror)) from None
    try:
        return decode_bytes(payload, wavelengths, integers, max_samples)
    except BrdfwaveError as e:
        raise BrdfwaveError("%s: %s" % (path, e)) from None


def encode(values, level=None, incoming=False, level_in=None, lossless=None, max_error=None,
           nbytes=None, ratio=None, basis="auto", scale=None, stream=False, symmetry="auto",
           path=None, device=None):
    """Encodes float values to a payload (bytes; also written to `path` if given),
    as `brdfwave encode` does with float32 input:
      level=None                 a set of spectra, values (n_spectra, bands)
      level=L                    a spectral reflectance, values (4*4^L, bands)
      level=L, incoming=True     an isotropic BRDF, values (n_in, 4*4^L, bands)
      level=L, level_in=Li       a full BRDF, values (4*4^Li, 4*4^L, bands)
    One of lossless (default), max_error=E, nbytes=N, ratio=R. basis: "haar", "53",
    "97", "pred" (spectra, lossless or max_error only) or "auto". symmetry: "auto" (try
    the mirror image (x, -y, z) for directional data, and reciprocity for a full BRDF
    with level_in == level; keep what pays), "mirror", "reciprocal", "both" or "none".
    device: None (this host), "linux" or "qemu": the device application encodes
    (as `brdfwave encode --device`; its image is found beside the library, or
    named by $BW_FIRMWARE_LINUX / $BW_FIRMWARE) and the payload is checked here."""
    L = lib()
    x = np.ascontiguousarray(values, dtype=np.float32)
    if x.ndim < 2:
        raise BrdfwaveError("values need at least 2 dimensions (..., bands)")
    s = Shape(-1 if level is None else level, -1 if level_in is None else level_in, 0,
              x.shape[-1])
    if incoming:
        if level is not None and x.ndim != 3:
            raise BrdfwaveError("an isotropic BRDF is (n_in, n_out, bands)")
        s.incoming = x.shape[0]
    d = Dims()
    if L.bwh_shape_dims(ctypes.byref(s), x.size, ctypes.byref(d)) != 0:
        raise BrdfwaveError(last_error())
    need = d.n_in * d.n_out * d.bands
    o = EncodeOpts()
    modes = [m for m in (lossless, max_error, nbytes, ratio) if m not in (None, False)]
    if len(modes) > 1:
        raise BrdfwaveError("give only one of lossless, max_error, nbytes, ratio")
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
        o.byte_budget = int(nbytes)
    b = L.bwh_basis_from_name(basis.encode()) if isinstance(basis, str) else -1
    if b < 0:
        raise BrdfwaveError("basis must be haar, 53, 97, pred or auto")
    o.basis = b
    if scale is not None:
        o.scale = float(scale)
    if stream:
        o.flags |= 0x02
    sym = L.bwh_symmetry_from_name(symmetry.encode()) if isinstance(symmetry, str) else -1
    if sym < 0:
        raise BrdfwaveError("symmetry must be auto, mirror, reciprocal, both or none")
    o.flags |= sym
    if device is not None:
        if device not in ("linux", "qemu"):
            raise BrdfwaveError("device must be None, 'linux' or 'qemu'")
        job = DeviceJob(device.encode(), None, 0.0, -1, None)
        o.device = ctypes.pointer(job)
    out = ctypes.POINTER(ctypes.c_uint8)()
    n = ctypes.c_size_t()
    if L.bwh_encode_f32(ctypes.byref(d), x.ctypes.data_as(ctypes.POINTER(ctypes.c_float)),
                        ctypes.byref(o), ctypes.byref(out), ctypes.byref(n)) != 0:
        raise BrdfwaveError(last_error())
    try:
        payload = ctypes.string_at(out, n.value)
    finally:
        free(out)
    if path is not None:
        tmp = "%s.tmp%d" % (path, os.getpid())
        with open(tmp, "wb") as f:
            f.write(payload)
        os.replace(tmp, path)
    return payload
