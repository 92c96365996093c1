#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The Debian packages: make deb (dpkg-buildpackage -us -uc -b with
# debhelper, from a copy of the tree) gives libbrdfwave1, libbrdfwave-dev,
# brdfwave and python3-brdfwave; lintian finds no error; the packages
# install with dpkg into a root of their own (its own dpkg database, so
# the machine's /usr is not touched) and work from there: a C program
# built with pkg-config alone, the command line, the Python package.
# Then, as root and with none of the four packages installed already, they
# install on the machine itself with apt-get, work there and are purged
# (BRDFWAVE_DEB_SYSTEM=0 leaves that out, =1 asks for it).
set -u
cd "$(dirname "$0")/../.."
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
V=$(sed -n 's/^#define BRDFWAVE_VERSION_STRING "\(.*\)"/\1/p' include/brdfwave/brdfwave.h)
D=build/deb
MA=$(dpkg-architecture -qDEB_HOST_MULTIARCH)

for p in debhelper dh-python lintian fakeroot; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        { bad "$p is not installed (tests/deps.sh)"; }
done
head -1 debian/changelog | grep -q "^brdfwave ($V)" && ok || bad "debian/changelog is not at $V"

make --no-print-directory deb >"$T/build.log" 2>&1 && ok || bad "make deb: $(tail -20 "$T/build.log")"
debs=""
for p in libbrdfwave1 libbrdfwave-dev brdfwave python3-brdfwave; do
    f=$(ls "$D/${p}_${V}_"*.deb 2>/dev/null | head -1)
    [ -n "$f" ] && ok || { bad "no package $p"; continue; }
    debs="$debs $f"
done
[ -n "$debs" ] || { echo "RESULT: $pass passed, $fail failed"; exit 1; }

lintian --tag-display-limit 0 "$D"/brdfwave_"$V"_*.changes >"$T/lintian" 2>&1
grep -q '^E: ' "$T/lintian" && bad "lintian errors: $(grep '^E: ' "$T/lintian" | head -10)" || ok
grep '^W: ' "$T/lintian" | sed 's/^/lintian: /'

# the contents
dpkg-deb -c "$D/libbrdfwave1_${V}_"*.deb | grep -q "usr/lib/$MA/libbrdfwave.so.1 -> libbrdfwave.so.$V" && ok ||
    bad "libbrdfwave1: no libbrdfwave.so.1"
dpkg-deb -c "$D/libbrdfwave-dev_${V}_"*.deb >"$T/dev"
for f in usr/include/brdfwave/brdfwave.h "usr/lib/$MA/libbrdfwave.a" "usr/lib/$MA/pkgconfig/brdfwave.pc" \
    usr/share/man/man3/libbrdfwave.3.gz; do
    grep -q "\./$f" "$T/dev" && ok || bad "libbrdfwave-dev lacks $f"
done
dpkg-deb -c "$D/brdfwave_${V}_"*.deb | grep -q "usr/share/man/man1/brdfwave.1.gz" && ok || bad "brdfwave: no man page"
dpkg-deb -f "$D/python3-brdfwave_${V}_all.deb" Depends | grep -q "libbrdfwave1" && ok ||
    bad "python3-brdfwave does not depend on libbrdfwave1"

# installed with dpkg into a root of its own
R=$T/root
A=$T/admin
mkdir -p "$R" "$A/info" "$A/updates" "$A/triggers"
: >"$A/status"
# shellcheck disable=SC2086
dpkg --admindir="$A" --instdir="$R" --force-depends --force-not-root --force-script-chrootless \
    --unpack $debs >"$T/dpkg.log" 2>&1 && ok || bad "dpkg --unpack: $(tail -5 "$T/dpkg.log")"
for p in libbrdfwave1 libbrdfwave-dev brdfwave python3-brdfwave; do
    dpkg --admindir="$A" -L "$p" >/dev/null 2>&1 && ok || bad "dpkg does not list $p"
done
cat >"$T/prog.c" <<'C'
#include <brdfwave/brdfwave.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
int main(void)
{
    float x[3 * 40];
    for (int i = 0; i < 3 * 40; i++)
        x[i] = 0.25f + 0.001f * (float)(i * i % 97);
    bw_dims_t d;
    bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, 3, 40);
    bwh_encode_opts_t o = {.mode = BW_MODE_MAX_ERROR, .max_error = 1e-3, .basis = BW_BASIS_AUTO};
    uint8_t *p;
    size_t n;
    bw_header_t h;
    float *y;
    if (bwh_encode_f32(&d, x, &o, &p, &n) || bwh_decode(p, n, &h, NULL, &y))
        return 1;
    bwh_metrics_t m;
    bwh_metrics(x, y, 3 * 40, &m);
    printf("%s %zu %g\n", bwh_version(), n, m.max_abs);
    return m.max_abs > 1e-3 || strcmp(bwh_version(), BRDFWAVE_VERSION_STRING);
}
C
flags=$(PKG_CONFIG_SYSROOT_DIR="$R" PKG_CONFIG_LIBDIR="$R/usr/lib/$MA/pkgconfig" pkg-config --cflags --libs brdfwave) &&
    ok || bad "pkg-config in the package root"
# shellcheck disable=SC2086
cc "$T/prog.c" $flags -o "$T/prog" 2>"$T/err" && out=$(LD_LIBRARY_PATH="$R/usr/lib/$MA" "$T/prog") &&
    [ "${out%% *}" = "$V" ] && ok || bad "a program against the packages: $(head -3 "$T/err") $out"
[ "$(LD_LIBRARY_PATH="$R/usr/lib/$MA" "$R/usr/bin/brdfwave" --version | head -1)" = "brdfwave $V (libbrdfwave $V)" ] &&
    ok || bad "the packaged brdfwave --version"
(cd "$T" && LD_LIBRARY_PATH="$R/usr/lib/$MA" PYTHONPATH="$R/usr/lib/python3/dist-packages" /usr/bin/python3 -c "
import brdfwave, brdfwave._lib as L, numpy as np
assert brdfwave.__file__.startswith('$R'), brdfwave.__file__
assert L._find() == 'libbrdfwave.so.1', L._find()
x = np.linspace(0.1, 0.9, 64, dtype=np.float32).reshape(2, 32)
assert np.abs(np.asarray(brdfwave.decode_bytes(brdfwave.encode(x, max_error=1e-3))) - x).max() <= 1e-3
") && ok || bad "the packaged Python module"

system=${BRDFWAVE_DEB_SYSTEM:-auto}
if [ "$system" = auto ]; then
    system=0
    if [ "$(id -u)" = 0 ]; then
        system=1
        for p in libbrdfwave1 libbrdfwave-dev brdfwave python3-brdfwave; do
            dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" && system=0
        done
    fi
    [ "$system" = 1 ] || echo "note: the packages are not installed on this machine (not root, or installed already)"
fi
if [ "$system" = 1 ]; then
    # shellcheck disable=SC2086
    apt-get install -y -q $(printf './%s ' $debs) >"$T/apt.log" 2>&1 && ok || bad "apt-get install: $(tail -5 "$T/apt.log")"
    [ "$(/usr/bin/brdfwave --version | head -1)" = "brdfwave $V (libbrdfwave $V)" ] && ok || bad "/usr/bin/brdfwave"
    # shellcheck disable=SC2046
    cc "$T/prog.c" $(pkg-config --cflags --libs brdfwave) -o "$T/prog_sys" && "$T/prog_sys" >/dev/null && ok ||
        bad "a program against the installed packages"
    (cd "$T" && /usr/bin/python3 -c "import brdfwave; brdfwave.grid(2)") && ok || bad "import brdfwave"
    apt-get purge -y -q libbrdfwave1 libbrdfwave-dev brdfwave python3-brdfwave >/dev/null 2>&1 && ok || bad "purge"
fi

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
