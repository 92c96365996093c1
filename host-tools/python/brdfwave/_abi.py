# SPDX-License-Identifier: BSD-2-Clause
"""The ctypes layer against the library it loaded: every structure this
package lays out itself (_lib.py) must have the size the library was built
with (bwh_abi_size, host-tools/lib/bwh_flat.h), checked once at load. A
mismatch (a library from another version of the sources) would corrupt
memory; it is refused with the names and sizes instead."""
import ctypes


class AbiMismatchError(ImportError):
    """libbrdfwave's structures differ from this package's copies of them."""


def check(L, structs):
    """structs: {C name: ctypes.Structure}. Raises AbiMismatchError."""
    try:
        f = L.bwh_abi_size
    except AttributeError:
        raise AbiMismatchError("%s has no bwh_abi_size: a library older than this package"
                               % getattr(L, "_name", "libbrdfwave")) from None
    f.restype = ctypes.c_size_t
    f.argtypes = [ctypes.c_char_p]
    bad = []
    for name, s in structs.items():
        n = f(name.encode())
        if n != ctypes.sizeof(s):
            bad.append("%s: %d bytes in the library, %d here" % (name, n, ctypes.sizeof(s)))
    if bad:
        raise AbiMismatchError("%s does not match this package (%s): rebuild it from the same "
                               "sources (make pylib) or reinstall the package"
                               % (getattr(L, "_name", "libbrdfwave"), "; ".join(bad)))


def declare(L):
    """Argument and result types of the flat calls (bwh_flat.h)."""
    P = ctypes.POINTER
    L.bwh_meta_area_from_json.restype = ctypes.c_int
    L.bwh_meta_area_from_json.argtypes = [ctypes.c_char_p, ctypes.c_void_p,
                                          P(P(ctypes.c_uint8)), P(ctypes.c_size_t)]
    L.bwh_meta_json_of_payload.restype = ctypes.c_int
    L.bwh_meta_json_of_payload.argtypes = [ctypes.c_char_p, ctypes.c_size_t,
                                           P(ctypes.c_char_p)]
    L.bwh_read_flat.restype = ctypes.c_int
    L.bwh_read_flat.argtypes = [P(ctypes.c_char_p), ctypes.c_int, ctypes.c_char_p, ctypes.c_int,
                                ctypes.c_int, ctypes.c_int, ctypes.c_char_p, ctypes.c_int,
                                ctypes.c_double, P(P(ctypes.c_float)), P(ctypes.c_size_t),
                                ctypes.c_void_p, P(ctypes.c_void_p)]
    L.bwh_encode_scaled.restype = ctypes.c_int
    L.bwh_encode_scaled.argtypes = [ctypes.c_void_p, P(ctypes.c_int32), ctypes.c_void_p,
                                    ctypes.c_float, P(P(ctypes.c_uint8)), P(ctypes.c_size_t)]
