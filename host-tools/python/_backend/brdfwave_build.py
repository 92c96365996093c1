# SPDX-License-Identifier: BSD-2-Clause
"""A PEP 517 build backend for the brdfwave package that needs nothing but
the standard library: `pip install ./host-tools/python` builds
libbrdfwave.so from the checkout around it (`make pylib`; or takes the one
$BRDFWAVE_LIB names) and writes a wheel of the package with the library
inside, tagged for this platform. No index is asked for anything, so the
install works offline (numpy, the one dependency, from the system)."""
import base64
import hashlib
import os
import re
import shutil
import subprocess
import sysconfig
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
PKG_ROOT = os.path.dirname(HERE)                       # host-tools/python
SRC_ROOT = os.path.dirname(os.path.dirname(PKG_ROOT))  # the checkout
NAME = "brdfwave"


def _version():
    with open(os.path.join(PKG_ROOT, NAME, "_version.py")) as f:
        return re.search(r'__version__ = "([^"]+)"', f.read()).group(1)


def _library():
    """The path of libbrdfwave.so: $BRDFWAVE_LIB, or built from the checkout."""
    env = os.environ.get("BRDFWAVE_LIB")
    if env:
        if not os.path.isfile(env):
            raise RuntimeError("BRDFWAVE_LIB=%s: no such file" % env)
        return env
    if not os.path.isfile(os.path.join(SRC_ROOT, "Makefile")):
        raise RuntimeError("%s is not in a brdfwave checkout: set BRDFWAVE_LIB to a built "
                           "libbrdfwave.so" % PKG_ROOT)
    r = subprocess.run(["make", "-C", SRC_ROOT, "--no-print-directory", "pylib"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise RuntimeError("building libbrdfwave.so (make pylib) failed:\n" + r.stdout[-4000:])
    return os.path.join(SRC_ROOT, "build", "host", "libbrdfwave.so")


def _tag():
    plat = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return "py3-none-" + plat


def _metadata(version):
    return ("Metadata-Version: 2.1\nName: %s\nVersion: %s\n"
            "Summary: Wavelet compression of spectral reflectance and BRDF measurements, "
            "with their metadata\nRequires-Python: >=3.9\nRequires-Dist: numpy\n"
            % (NAME, version))


def _record_line(arc, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (arc, digest, len(data))


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    version = _version()
    di = "%s-%s.dist-info" % (NAME, version)
    os.makedirs(os.path.join(metadata_directory, di), exist_ok=True)
    with open(os.path.join(metadata_directory, di, "METADATA"), "w") as f:
        f.write(_metadata(version))
    return di


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    version = _version()
    lib = _library()
    tag = _tag()
    di = "%s-%s.dist-info" % (NAME, version)
    files = []
    pkg = os.path.join(PKG_ROOT, NAME)
    for fn in sorted(os.listdir(pkg)):
        if fn.endswith(".py"):
            with open(os.path.join(pkg, fn), "rb") as f:
                files.append(("%s/%s" % (NAME, fn), f.read()))
    with open(lib, "rb") as f:
        files.append(("%s/libbrdfwave.so" % NAME, f.read()))
    files.append(("%s/METADATA" % di, _metadata(version).encode()))
    files.append(("%s/WHEEL" % di, ("Wheel-Version: 1.0\nGenerator: brdfwave_build\n"
                                    "Root-Is-Purelib: false\nTag: %s\n" % tag).encode()))
    files.append(("%s/top_level.txt" % di, (NAME + "\n").encode()))
    record = [_record_line(a, d) for a, d in files] + ["%s/RECORD,," % di]
    files.append(("%s/RECORD" % di, ("\n".join(record) + "\n").encode()))
    name = "%s-%s-%s.whl" % (NAME, version, tag)
    tmp = os.path.join(wheel_directory, name + ".part")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for arc, data in files:
            info = zipfile.ZipInfo(arc, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o755 if arc.endswith(".so") else 0o644) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    shutil.move(tmp, os.path.join(wheel_directory, name))
    return name


def build_sdist(sdist_directory, config_settings=None):
    raise RuntimeError("brdfwave is installed from its checkout (pip install "
                       "./host-tools/python); there is no source distribution")
