# SPDX-License-Identifier: BSD-2-Clause
"""ctypes view of libbrdfwave (build/host/libbrdfwave.so, `make pylib`)."""
import ctypes
import ctypes.util
import os
import struct

_HERE = os.path.dirname(os.path.abspath(__file__))


class BrdfwaveError(ValueError):
    """A payload, an input or an option the library rejected (a ValueError)."""


class Dims(ctypes.Structure):
    _fields_ = [("shape", ctypes.c_uint8), ("level_out", ctypes.c_uint8),
                ("level_in", ctypes.c_uint8), ("n_in", ctypes.c_uint32),
                ("n_out", ctypes.c_uint32), ("bands", ctypes.c_uint32)]


class Header(ctypes.Structure):
    _fields_ = [("version", ctypes.c_uint8), ("band_access", ctypes.c_uint8), ("dims", Dims),
                ("basis", ctypes.c_uint8), ("spectral_levels", ctypes.c_uint8), ("mode", ctypes.c_uint8),
                ("flags", ctypes.c_uint8), ("prequant", ctypes.c_uint32),
                ("step_q8", ctypes.c_uint32), ("max_error", ctypes.c_uint32),
                ("scale_bits", ctypes.c_uint32), ("offset_bits", ctypes.c_uint32),
                ("payload_len", ctypes.c_uint32), ("header_len", ctypes.c_uint32),
                ("body_len", ctypes.c_uint32), ("crc", ctypes.c_uint32),
                ("ext_off", ctypes.c_uint32), ("ext_len", ctypes.c_uint32),
                ("segment_vectors", ctypes.c_uint32), ("segments", ctypes.c_uint32),
                ("embedded", ctypes.c_uint32)]


class Shape(ctypes.Structure):
    """bwh_shape_t (host-tools/lib/bwh_shape.h): the shape options."""
    _fields_ = [("level", ctypes.c_int), ("level_in", ctypes.c_int),
                ("incoming", ctypes.c_uint32), ("bands", ctypes.c_uint32)]


class DeviceJob(ctypes.Structure):
    """struct bwh_device_job (host-tools/lib/bwh_device.h): an encode on a device."""
    _fields_ = [("device", ctypes.c_char_p), ("firmware", ctypes.c_char_p),
                ("timeout", ctypes.c_double), ("drop_chunk", ctypes.c_int),
                ("instructions", ctypes.POINTER(ctypes.c_uint64))]


class EncodeOpts(ctypes.Structure):
    """bwh_encode_opts_t (host-tools/lib/bwh_encode.h)."""
    _fields_ = [("mode", ctypes.c_int), ("max_error", ctypes.c_double),
                ("byte_budget", ctypes.c_size_t), ("basis", ctypes.c_uint),
                ("scale", ctypes.c_double), ("flags", ctypes.c_uint),
                ("device", ctypes.POINTER(DeviceJob)),
                ("max_rel_error", ctypes.c_double), ("rel_floor", ctypes.c_double),
                ("ext", ctypes.c_void_p), ("ext_len", ctypes.c_size_t),
                ("effort", ctypes.c_uint), ("coder", ctypes.c_uint),
                ("segments", ctypes.c_uint32), ("progressive", ctypes.c_uint32),
                ("band_access", ctypes.c_uint32)]


class Salvage(ctypes.Structure):
    """bwh_salvage_t (host-tools/lib/bwh_decode.h): what a decode in part found."""
    _fields_ = [("segments", ctypes.c_uint32), ("lost_segments", ctypes.c_uint32),
                ("approx", ctypes.c_size_t), ("missing", ctypes.c_size_t),
                ("tail_lost", ctypes.c_uint32)]


# the I2C client's transport (bwh_i2c_t, host-tools/lib/bwh_i2c.h)
I2C_READ_WORD = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_uint8,
                                 ctypes.POINTER(ctypes.c_uint16))
I2C_WRITE_BYTE = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_uint8, ctypes.c_uint8)
I2C_WRITE_WORD = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_uint8, ctypes.c_uint16)
I2C_LOG = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p)
I2C_STOP = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p)


class I2C(ctypes.Structure):
    """bwh_i2c_t: the SMBus transfers the library's I2C client reads the window with."""
    _fields_ = [("read_word", I2C_READ_WORD), ("write_byte", I2C_WRITE_BYTE),
                ("write_word", I2C_WRITE_WORD), ("log", I2C_LOG), ("stop", I2C_STOP),
                ("ctx", ctypes.c_void_p), ("addr", ctypes.c_uint), ("bus_name", ctypes.c_char_p)]


class I2CPayload(ctypes.Structure):
    """bwh_i2c_payload_t."""
    _fields_ = [("id", ctypes.c_uint32), ("payload", ctypes.POINTER(ctypes.c_uint8)),
                ("len", ctypes.c_size_t), ("bad_pages", ctypes.c_uint)]


I2C_STOPPED = -2


class Partial(ctypes.Structure):
    """bwh_partial_t: a payload that arrived in part (host-tools/lib/bwh_store.h)."""
    _fields_ = [("id", ctypes.c_uint32), ("crc", ctypes.c_uint32), ("len", ctypes.c_size_t),
                ("unit", ctypes.c_uint), ("parts", ctypes.c_uint32),
                ("have", ctypes.POINTER(ctypes.c_uint8)),
                ("payload", ctypes.POINTER(ctypes.c_uint8))]


def _find():
    env = os.environ.get("BRDFWAVE_LIB")
    if env:
        return env
    # an installed package carries its library (pip install host-tools/python)
    own = os.path.join(_HERE, "libbrdfwave.so")
    if os.path.exists(own):
        return own
    # in the source tree: host-tools/python/brdfwave -> build/host
    cand = os.path.join(_HERE, "..", "..", "..", "build", "host", "libbrdfwave.so")
    if os.path.exists(cand):
        return os.path.normpath(cand)
    # installed by `make install` (or the Debian package): the library it
    # installed, by path or by SONAME
    try:
        from ._libpath import LIBRARY
        return LIBRARY
    except ImportError:
        pass
    found = ctypes.util.find_library("brdfwave")
    if found:
        return found
    raise BrdfwaveError("libbrdfwave.so not found: run 'make pylib' or set BRDFWAVE_LIB")


_lib = None


def lib():
    global _lib
    if _lib is not None:
        return _lib
    L = ctypes.CDLL(_find())
    from . import _abi
    _abi.check(L, {"bw_dims_t": Dims, "bw_header_t": Header, "bwh_shape_t": Shape,
                   "bwh_salvage_t": Salvage,
                   "bwh_encode_opts_t": EncodeOpts, "bwh_i2c_t": I2C,
                   "bwh_i2c_payload_t": I2CPayload, "bwh_partial_t": Partial})
    _abi.declare(L)
    P = ctypes.POINTER
    L.bwh_last_error.restype = ctypes.c_char_p
    L.bwh_last_error.argtypes = []
    L.bwh_decode.restype = ctypes.c_int
    L.bwh_decode.argtypes = [ctypes.c_char_p, ctypes.c_size_t, P(Header),
                             P(P(ctypes.c_int32)), P(P(ctypes.c_float))]
    L.bwh_decode_limit.restype = ctypes.c_int
    L.bwh_decode_limit.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_size_t, P(Header),
                                   P(P(ctypes.c_int32)), P(P(ctypes.c_float))]
    L.bwh_decode_incoming.restype = ctypes.c_int
    L.bwh_decode_incoming.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint32,
                                      P(Header), P(Dims), P(P(ctypes.c_int32)),
                                      P(P(ctypes.c_float))]
    L.bwh_payload_eval.restype = ctypes.c_int
    L.bwh_payload_eval.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_size_t,
                                   ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                                   ctypes.c_long, ctypes.c_void_p]
    L.bwh_decode_levels.restype = ctypes.c_int
    L.bwh_decode_levels.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int, ctypes.c_int,
                                    P(Header), P(Dims), P(P(ctypes.c_int32)),
                                    P(P(ctypes.c_float))]
    L.bwh_decode_level.restype = ctypes.c_int
    L.bwh_decode_level.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint, P(Header),
                                   P(Dims), P(P(ctypes.c_int32)), P(P(ctypes.c_float))]
    L.bwh_decode_rows.restype = ctypes.c_int
    L.bwh_decode_rows.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p, P(Header),
                                  P(Dims), P(P(ctypes.c_int32)), P(P(ctypes.c_float))]
    L.bwh_region_rows.restype = ctypes.c_int
    L.bwh_region_rows.argtypes = [P(Header), ctypes.c_void_p, ctypes.c_double, ctypes.c_double,
                                  ctypes.c_double, ctypes.c_void_p]
    L.bwh_decode_bands.restype = ctypes.c_int
    L.bwh_decode_bands.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint32,
                                   ctypes.c_uint32, P(Header), P(Dims), P(P(ctypes.c_int32)),
                                   P(P(ctypes.c_float))]
    L.bw_header_parse_fields.restype = ctypes.c_int
    L.bw_header_parse_fields.argtypes = [ctypes.c_char_p, ctypes.c_size_t, P(Header)]
    L.bwh_header_salvage.restype = ctypes.c_int
    L.bwh_header_salvage.argtypes = [ctypes.c_char_p, ctypes.c_size_t, P(Header)]
    L.bwh_meta_rows_json.restype = ctypes.c_int
    L.bwh_meta_rows_json.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p,
                                     P(ctypes.c_char_p)]
    L.bwh_meta_json_bands.restype = ctypes.c_int
    L.bwh_meta_json_bands.argtypes = [ctypes.c_char_p, ctypes.c_uint32, ctypes.c_void_p,
                                      P(ctypes.c_char_p)]
    L.bwh_meta_row_json.restype = ctypes.c_int
    L.bwh_meta_row_json.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint32,
                                    P(ctypes.c_char_p)]
    L.bwh_decode_salvage.restype = ctypes.c_int
    L.bwh_decode_salvage.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_size_t,
                                     P(Header), P(P(ctypes.c_int32)), P(P(ctypes.c_float)),
                                     P(P(ctypes.c_uint8)), P(Salvage)]
    L.bwh_encode_f32.restype = ctypes.c_int
    L.bwh_encode_f32.argtypes = [P(Dims), P(ctypes.c_float), P(EncodeOpts),
                                 P(P(ctypes.c_uint8)), P(ctypes.c_size_t)]
    L.bwh_shape_dims.restype = ctypes.c_int
    L.bwh_shape_dims.argtypes = [P(Shape), ctypes.c_size_t, P(Dims)]
    L.bwh_basis_from_name.restype = ctypes.c_int
    L.bwh_basis_from_name.argtypes = [ctypes.c_char_p]
    L.bwh_symmetry_from_name.restype = ctypes.c_int
    L.bwh_symmetry_from_name.argtypes = [ctypes.c_char_p]
    L.bw_strerror.restype = ctypes.c_char_p
    L.bw_strerror.argtypes = [ctypes.c_int]
    L.bw_header_read.restype = ctypes.c_int
    L.bw_header_read.argtypes = [ctypes.c_char_p, ctypes.c_size_t, P(Header)]
    L.bwh_grid_count.restype = ctypes.c_size_t
    L.bwh_grid_count.argtypes = [ctypes.c_uint]
    L.bwh_payload_check.restype = ctypes.c_int
    L.bwh_payload_check.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_size_t, P(Header)]
    L.bwh_store_payload.restype = ctypes.c_int
    L.bwh_store_payload.argtypes = [ctypes.c_char_p, ctypes.c_uint32, ctypes.c_char_p,
                                    ctypes.c_size_t, ctypes.c_char_p, ctypes.c_size_t]
    L.bwh_grid_centres.restype = ctypes.c_int
    L.bwh_grid_centres.argtypes = [ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p]
    L.bwh_i2c_read_payload.restype = ctypes.c_int
    L.bwh_i2c_read_payload.argtypes = [P(I2C), ctypes.c_uint, ctypes.c_size_t, P(I2CPayload)]
    L.bwh_i2c_read_partial.restype = ctypes.c_int
    L.bwh_i2c_read_partial.argtypes = [P(I2C), ctypes.c_uint, ctypes.c_size_t, P(Partial),
                                       P(I2CPayload)]
    L.bwh_partial_store.restype = ctypes.c_int
    L.bwh_partial_store.argtypes = [ctypes.c_char_p, P(Partial), ctypes.c_char_p, ctypes.c_size_t]
    L.bwh_partial_load.restype = ctypes.c_int
    L.bwh_partial_load.argtypes = [ctypes.c_char_p, P(Partial)]
    L.bwh_partial_free.restype = None
    L.bwh_partial_free.argtypes = [P(Partial)]
    L.bwh_partial_remove.restype = None
    L.bwh_partial_remove.argtypes = [ctypes.c_char_p]
    L.bwh_partial_forget.restype = None
    L.bwh_partial_forget.argtypes = [ctypes.c_char_p, ctypes.c_uint32, ctypes.c_char_p,
                                     ctypes.c_size_t]
    L.bwh_partial_missing.restype = ctypes.c_uint32
    L.bwh_partial_missing.argtypes = [P(Partial)]
    L.bwh_i2c_acknowledge.restype = ctypes.c_int
    L.bwh_i2c_acknowledge.argtypes = [P(I2C), ctypes.c_uint32, ctypes.c_double]
    _lib = L
    return L


_free = ctypes.CDLL(None).free
_free.restype = None
_free.argtypes = [ctypes.c_void_p]


def free(p):
    """Releases a buffer the library allocated (malloc)."""
    _free(ctypes.cast(p, ctypes.c_void_p))


def last_error():
    return lib().bwh_last_error().decode("utf-8", "replace")


SHAPES = ("spectra", "reflectance", "brdf", "brdf-full")
_MODES = ("lossless", "max-error", "bytes", "step")
_BASIS_NAMES = ("haar", "53", "97", "pred")


def _float_of(bits):
    return struct.unpack("<f", struct.pack("<I", bits))[0]


def _varint(b, i):
    """A LEB128 value at b[i]; returns it and the index after it."""
    v = sh = 0
    while i < len(b):
        v |= (b[i] & 0x7F) << sh
        i += 1
        if not b[i - 1] & 0x80:
            return v, i
        sh += 7
    raise BrdfwaveError("a record's varint runs past the header")


def _chunk_steps(payload, h):
    """Record 0x05 of a payload whose header h was read: (K, [d, ...]), the
    vectors per chunk and each chunk's step change in 1/32 of an octave, or
    (0, []) without it."""
    if not isinstance(payload, (bytes, bytearray, memoryview)) or not h.ext_len:
        return 0, []
    area = bytes(payload[h.ext_off:h.ext_off + h.ext_len])
    i = 0
    while i < len(area):
        t = area[i]
        n, i = _varint(area, i + 1)
        if t == 0x05:
            k, j = _varint(area, i)
            return k, [x - 256 if x > 127 else x for x in area[j:i + n]]
        i += n
    return 0, []


def _header_dict(h, payload=None):
    d = h.dims
    chunk_vectors, chunk_steps = _chunk_steps(payload, h)
    scale = _float_of(h.scale_bits)
    return {"version": h.version, "shape": SHAPES[d.shape], "level_out": d.level_out,
            "level_in": d.level_in, "n_in": d.n_in, "n_out": d.n_out, "bands": d.bands,
            "basis": _BASIS_NAMES[h.basis], "spectral_levels": h.spectral_levels,
            "mode": _MODES[h.mode], "flags": h.flags, "prequant": h.prequant,
            "step_q8": h.step_q8,
            # in the values' units, as 'brdfwave info' prints it; the
            # integer bound in max_error_samples
            "max_error": h.max_error * scale if h.mode == 1 else 0.0,
            "max_error_samples": h.max_error, "scale": scale,
            "offset": _float_of(h.offset_bits), "payload_len": h.payload_len,
            "header_len": h.header_len, "body_len": h.body_len, "crc": h.crc,
            # the body in segments (encode(..., segments=N)): how many, and
            # vectors in each (0: one body)
            "segments": h.segments, "segment_vectors": h.segment_vectors,
            # embedded segments (encode(..., progressive=True))
            "embedded": bool(h.embedded),
            # band access (encode(..., band_access=True))
            "band_access": bool(h.band_access),
            # a step per chunk of that many vectors (record 0x05: a byte
            # budget met in one encode): each chunk's step is step_q8
            # 2^(d / 32) for its d in chunk_steps; 0 and [] without it
            "chunk_vectors": chunk_vectors, "chunk_steps": chunk_steps}


def header_of(payload):
    """Validates a payload's header and CRC (bw_header_read); returns it as a
    dict. payload: bytes, or the path of a payload file."""
    L = lib()
    h = Header()
    if isinstance(payload, (str, os.PathLike)):
        with open(payload, "rb") as f:
            payload = f.read()
    payload = bytes(payload)
    st = L.bw_header_read(payload, len(payload), ctypes.byref(h))
    if st != 0:
        raise BrdfwaveError(L.bw_strerror(st).decode())
    return _header_dict(h, payload)


def payload_check(payload, max_samples=0):
    """What a receiver checks before it stores and acknowledges a payload:
    header, CRC, the sample limit (0: the library's default) and a full
    decode (bwh_payload_check). Returns the header as a dict."""
    L = lib()
    h = Header()
    payload = bytes(payload)
    if L.bwh_payload_check(payload, len(payload), max_samples, ctypes.byref(h)) != 0:
        raise BrdfwaveError(last_error())
    return _header_dict(h, payload)


def store_payload(outdir, pid, payload):
    """Stores a received payload as OUTDIR/payload-ID-CRC.bwv without ever
    replacing a file (bwh_store_payload); returns (path, stored before)."""
    L = lib()
    path = ctypes.create_string_buffer(4096)
    payload = bytes(payload)
    rc = L.bwh_store_payload(os.fsencode(outdir), pid, payload, len(payload), path, len(path))
    if rc < 0:
        raise BrdfwaveError(last_error())
    return os.fsdecode(path.value), rc == 1
