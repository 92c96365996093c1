# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave for Python: payloads to numpy arrays and back, the geodesic grid,
and the acquisition service.

    import brdfwave
    m = brdfwave.decode("payload-1.bwv")      # Measurement (a numpy ndarray)
    m.shape, m.header["bands"], m.directions   # directions: unit vectors
    p = brdfwave.encode(m, level=4, max_error=1e-3)
    g = brdfwave.grid(4)                       # the scan order of `brdfwave grid`

The codec itself is libbrdfwave (the C library), loaded with ctypes from
build/host/libbrdfwave.so (`make pylib`) or $BRDFWAVE_LIB. The acquisition
service over I2C is brdfwave.acquire (python3 -m brdfwave.acquire --help); it
does not load numpy, so it starts fast on a small host.
"""
from ._lib import BrdfwaveError, header_of

__all__ = ["BrdfwaveError", "Measurement", "decode", "decode_bytes", "encode", "grid",
           "header_of", "plot_hemisphere", "plot_spectra", "plot_rd"]


def __getattr__(name):
    # numpy is loaded with the first use of the array API
    if name in ("Measurement", "decode", "decode_bytes", "encode", "grid"):
        from . import codec
        return getattr(codec, name)
    # and matplotlib with the first picture (brdfwave.plot)
    if name in ("plot_hemisphere", "plot_spectra", "plot_rd"):
        from . import plot
        return getattr(plot, name)
    raise AttributeError("module 'brdfwave' has no attribute %r" % name)
