# SPDX-License-Identifier: BSD-2-Clause
"""brdfwave for Python: payloads to numpy arrays and back, the geodesic grid,
and the acquisition service.

    import brdfwave
    m = brdfwave.decode("payload-1.bwv")      # Measurement (a numpy ndarray)
    m.shape, m.header["bands"], m.directions   # directions: unit vectors
    p = brdfwave.encode(m, level=4, max_error=1e-3)
    g = brdfwave.grid(4)                       # the scan order of `brdfwave grid`
    f = brdfwave.evaluate("brdf.bwv", wi, wo)  # f(wi, wo) straight from a payload

The codec itself is libbrdfwave (the C library), loaded with ctypes from
build/host/libbrdfwave.so (`make pylib`) or $BRDFWAVE_LIB. The acquisition
service over I2C is brdfwave.acquire (python3 -m brdfwave.acquire --help); it
does not load numpy, so it starts fast on a small host.
"""
from ._lib import BrdfwaveError, header_of
from .guarantee import check_guarantee, guarantee
from ._version import __version__

_ARRAY_API = ("Measurement", "decode", "decode_bytes", "encode", "evaluate", "grid", "read",
              "read_sed",
              "read_sig", "read_asd", "read_usgs", "read_envi", "read_csv", "read_npy",
              "read_bsdf", "read_gonio")
__all__ = ["BrdfwaveError", "check_guarantee", "guarantee", "header_of", "plot_hemisphere",
           "plot_spectra", "plot_rd", "__version__"] + list(_ARRAY_API)


def __getattr__(name):
    # numpy is loaded with the first use of the array API
    if name in _ARRAY_API:
        from . import codec
        return getattr(codec, name)
    # and matplotlib with the first picture (brdfwave.plot)
    if name in ("plot_hemisphere", "plot_spectra", "plot_rd"):
        from . import plot
        return getattr(plot, name)
    raise AttributeError("module 'brdfwave' has no attribute %r" % name)
