# SPDX-License-Identifier: BSD-2-Clause
"""The guarantee a payload was made under (record 0x82, docs/FORMAT.md), and
a decoded file checked against it.

    import brdfwave
    g = brdfwave.guarantee("f.bwv")      # {'kind': 'relative', 'rule': ..., ...}
    brdfwave.check_guarantee("f.bwv", original, decoded)   # samples that break it

Kinds: none (a byte budget), exact (bit for bit), absolute |x' - x| <= E,
relative |x' - x| <= max(R |x|, F), both |x' - x| <= min(E, max(R |x|, F)).
"""
import ctypes

from ._lib import BrdfwaveError, last_error, lib

KINDS = ("none", "exact", "absolute", "relative", "both")


class _Guarantee(ctypes.Structure):
    """bwh_guarantee_t (host-tools/lib/bwh_guarantee.h)."""
    _fields_ = [("kind", ctypes.c_int), ("recorded", ctypes.c_int), ("width", ctypes.c_int),
                ("max_error", ctypes.c_double), ("max_rel_error", ctypes.c_double),
                ("rel_floor", ctypes.c_double)]


def _setup():
    L = lib()
    if not hasattr(L, "_guarantee_ready"):
        P = ctypes.POINTER
        L.bwh_guarantee_read.restype = ctypes.c_int
        L.bwh_guarantee_read.argtypes = [ctypes.c_char_p, ctypes.c_size_t, P(_Guarantee)]
        L.bwh_guarantee_rule.restype = None
        L.bwh_guarantee_rule.argtypes = [P(_Guarantee), ctypes.c_char_p, ctypes.c_size_t]
        L.bwh_guarantee_check.restype = ctypes.c_size_t
        L.bwh_guarantee_check.argtypes = [P(_Guarantee), ctypes.c_void_p, ctypes.c_void_p,
                                          ctypes.c_size_t, P(ctypes.c_size_t)]
        L._guarantee_ready = True
    return L


def _payload(payload):
    if isinstance(payload, (bytes, bytearray, memoryview)):
        return bytes(payload)
    try:
        with open(payload, "rb") as f:
            return f.read()
    except OSError as e:
        raise BrdfwaveError("%s: %s" % (payload, e.strerror)) from None


def _read(payload):
    L = _setup()
    p = _payload(payload)
    g = _Guarantee()
    if L.bwh_guarantee_read(p, len(p), ctypes.byref(g)) != 0:
        raise BrdfwaveError(last_error())
    return L, g


def guarantee(payload):
    """The guarantee of a payload (bytes, or a path) as a dict: kind (one of
    KINDS), rule (as text), recorded (False: no record, taken from the
    header's mode), max_error, max_rel_error, rel_floor (0 where they do not
    apply), all in the values' units."""
    L, g = _read(payload)
    rule = ctypes.create_string_buffer(160)
    L.bwh_guarantee_rule(ctypes.byref(g), rule, len(rule))
    return {"kind": KINDS[g.kind] if 0 <= g.kind < len(KINDS) else "unknown",
            "rule": rule.value.decode(), "recorded": bool(g.recorded),
            "max_error": g.max_error, "max_rel_error": g.max_rel_error,
            "rel_floor": g.rel_floor}


def check_guarantee(payload, original, decoded):
    """The number of samples of `decoded` (float32, any shape) that break the
    payload's guarantee against `original` (the encoder's float32 input, the
    same number of samples), checked as the encoder checks them."""
    import numpy as np
    L, g = _read(payload)
    x = np.ascontiguousarray(original, dtype=np.float32).ravel()
    v = np.ascontiguousarray(decoded, dtype=np.float32).ravel()
    if x.size != v.size:
        raise BrdfwaveError("%d original and %d decoded samples" % (x.size, v.size))
    first = ctypes.c_size_t()
    return int(L.bwh_guarantee_check(ctypes.byref(g), x.ctypes.data, v.ctypes.data, x.size,
                                     ctypes.byref(first)))
