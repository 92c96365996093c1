#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# make install into a temporary prefix: a C program builds against it with
# `pkg-config --cflags --libs brdfwave` alone and runs (shared and static
# library), the shared library is libbrdfwave.so.1 by its SONAME, the
# installed headers hold the public interface only, the command line, its
# man pages and the Python package work from there; DESTDIR stages the same
# files under another root; make uninstall removes every file.
set -u
cd "$(dirname "$0")/../.."
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
V=$(sed -n 's/^#define BRDFWAVE_VERSION_STRING "\(.*\)"/\1/p' include/brdfwave/brdfwave.h)
MAJOR=${V%%.*}
P=$T/prefix

make --no-print-directory install PREFIX="$P" >"$T/log" 2>&1 && ok || { bad "make install: $(tail -5 "$T/log")"; }
for f in bin/brdfwave lib/libbrdfwave.so.$V lib/libbrdfwave.a lib/pkgconfig/brdfwave.pc \
    include/brdfwave/brdfwave.h include/brdfwave/codec.h include/brdfwave/brdf.h \
    share/man/man1/brdfwave.1 share/man/man3/libbrdfwave.3; do
    [ -f "$P/$f" ] && ok || bad "not installed: $f"
done
[ "$(readlink "$P/lib/libbrdfwave.so.$MAJOR")" = "libbrdfwave.so.$V" ] &&
    [ "$(readlink "$P/lib/libbrdfwave.so")" = "libbrdfwave.so.$MAJOR" ] && ok ||
    bad "links: $(ls -l "$P/lib")"
readelf -d "$P/lib/libbrdfwave.so.$V" | grep -q "SONAME.*\[libbrdfwave.so.$MAJOR\]" && ok ||
    bad "SONAME: $(readelf -d "$P/lib/libbrdfwave.so.$V" | grep SONAME)"

# the public interface only: no test hooks, no device link, no process spawning
# (an encode on a device is an opaque struct bwh_device_job of the tools)
if grep -l -E 'drop_chunk|char \*firmware|bwh_device_[a-z]+ *\(|bwh_link|bwh_i2c|bwh_rx_|fork|exec[lv]|posix_spawn|popen' \
    "$P/include/brdfwave/"*.h >"$T/leak"; then
    bad "installed headers expose internals: $(cat "$T/leak")"
else
    ok
fi

# a user's program with pkg-config alone
cat >"$T/prog.c" <<'C'
#include <brdfwave/brdfwave.h>
#include <brdfwave/brdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(void)
{
    enum { N = 8, B = 64 };
    static float x[N * B];
    for (int i = 0; i < N * B; i++)
        x[i] = 0.3f + 0.2f * sinf(0.1f * (float)(i % B)) + 0.01f * (float)(i / B);
    bw_dims_t d;
    if (bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, N, B) != BW_OK)
        return 1;
    bwh_encode_opts_t o = {.mode = BW_MODE_MAX_ERROR, .max_error = 1e-3, .basis = BW_BASIS_AUTO};
    uint8_t *p;
    size_t len;
    if (bwh_encode_f32(&d, x, &o, &p, &len) != 0) {
        fprintf(stderr, "encode: %s\n", bwh_last_error());
        return 1;
    }
    bw_header_t h;
    float *y;
    if (bwh_decode(p, len, &h, NULL, &y) != 0) {
        fprintf(stderr, "decode: %s\n", bwh_last_error());
        return 1;
    }
    bwh_metrics_t m;
    bwh_metrics(x, y, (size_t)N * B, &m);
    printf("%s %s %zu %.6g\n", BRDFWAVE_VERSION_STRING, bwh_version(), len, m.max_abs);
    int bad = strcmp(BRDFWAVE_VERSION_STRING, bwh_version()) != 0 || m.max_abs > 1e-3 ||
              len >= sizeof x || bwh_grid_count(2) != 64;
    free(p);
    free(y);
    return bad;
}
C
export PKG_CONFIG_PATH="$P/lib/pkgconfig"
[ "$(pkg-config --modversion brdfwave)" = "$V" ] && ok || bad "pkg-config --modversion"
flags=$(pkg-config --cflags --libs brdfwave) && ok || bad "pkg-config --cflags --libs"
# shellcheck disable=SC2086
cc -std=c11 -Wall -Wextra -Werror "$T/prog.c" $flags -lm -o "$T/prog" 2>"$T/err" && ok ||
    bad "build against the prefix: $(head -5 "$T/err")"
readelf -d "$T/prog" | grep -q "NEEDED.*\[libbrdfwave.so.$MAJOR\]" && ok || bad "prog does not need libbrdfwave.so.$MAJOR"
out=$(LD_LIBRARY_PATH="$P/lib" "$T/prog") && [ "${out%% *}" = "$V" ] && ok || bad "prog: $out"
# shellcheck disable=SC2046
cc -std=c11 "$T/prog.c" $(pkg-config --cflags brdfwave) "$P/lib/libbrdfwave.a" \
    $(pkg-config --static --libs-only-l brdfwave | sed 's/-lbrdfwave//') -lm -o "$T/prog_static" 2>"$T/err" &&
    ! readelf -d "$T/prog_static" | grep -q libbrdfwave && "$T/prog_static" >/dev/null && ok ||
    bad "static: $(head -5 "$T/err")"
# the headers alone compile as C++ too (extern "C")
if command -v g++ >/dev/null; then
    printf '#include <brdfwave/brdfwave.h>\n#include <brdfwave/brdf.h>\nint main() { return bwh_version_number() > 0 ? 0 : 1; }\n' >"$T/p.cc"
    # shellcheck disable=SC2086
    g++ "$T/p.cc" $flags -o "$T/pcc" 2>"$T/err" && LD_LIBRARY_PATH="$P/lib" "$T/pcc" && ok ||
        bad "C++: $(head -3 "$T/err")"
fi

# the command line, its man pages, the Python package
[ "$("$P/bin/brdfwave" --version | head -1)" = "brdfwave $V (libbrdfwave $V)" ] && ok ||
    bad "installed brdfwave --version"
for m in share/man/man1/brdfwave.1 share/man/man3/libbrdfwave.3; do
    w=$(LC_ALL=C.UTF-8 man --warnings -l "$P/$m" 2>&1 >"$T/man.txt")
    [ -z "$w" ] && grep -q "SYNOPSIS" "$T/man.txt" && ok || bad "man $m: $w"
done
MANPATH="$P/share/man" man -w brdfwave 2>/dev/null | grep -q "$P/share/man/man1/brdfwave.1" && ok ||
    bad "man brdfwave from the prefix"
pyd=$(find "$P/lib" -type d -name brdfwave -path '*dist-packages*' | head -1)
[ -n "$pyd" ] && ok || bad "no Python package installed"
(cd "$T" && PYTHONPATH="$(dirname "$pyd")" /usr/bin/python3 - "$P" <<'PY') && ok || bad "Python from the prefix"
import sys
import brdfwave, brdfwave._lib as L
prefix = sys.argv[1]
assert brdfwave.__file__.startswith(prefix), brdfwave.__file__
assert L._find().startswith(prefix + "/lib/libbrdfwave.so"), L._find()
import numpy as np
x = np.linspace(0.1, 0.9, 4 * 32, dtype=np.float32).reshape(4, 32)
y = brdfwave.decode_bytes(brdfwave.encode(x, max_error=1e-3))
assert np.abs(np.asarray(y) - x).max() <= 1e-3
PY

# DESTDIR: the same files under another root, the paths inside still PREFIX's
make --no-print-directory install PREFIX=/usr DESTDIR="$T/stage" >"$T/log" 2>&1 && ok ||
    bad "make install DESTDIR: $(tail -5 "$T/log")"
grep -qx "prefix=/usr" "$T/stage/usr/lib/pkgconfig/brdfwave.pc" && ok || bad "DESTDIR: brdfwave.pc"
grep -q "LIBRARY = \"/usr/lib/libbrdfwave.so.$MAJOR\"" "$T/stage/usr/lib/python3/dist-packages/brdfwave/_libpath.py" &&
    ok || bad "DESTDIR: the Python package's library path"
[ -x "$T/stage/usr/bin/brdfwave" ] && ok || bad "DESTDIR: brdfwave"

# uninstall leaves nothing
make --no-print-directory uninstall PREFIX="$P" >"$T/log" 2>&1 && ok || bad "make uninstall: $(tail -5 "$T/log")"
left=$(find "$P" \( -type f -o -type l \) | head -5)
[ -z "$left" ] && ok || bad "left after uninstall: $left"
make --no-print-directory uninstall PREFIX=/usr DESTDIR="$T/stage" >/dev/null 2>&1 &&
    [ -z "$(find "$T/stage" \( -type f -o -type l \))" ] && ok || bad "uninstall DESTDIR"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
