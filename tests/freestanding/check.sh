#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The codec core builds and links freestanding, for Cortex-M4 (arm-none-eabi-gcc)
# and RV32IMAC (riscv64-unknown-elf-gcc), without a C library:
#   1. every firmware/codec/*.c compiles with -Wall -Wextra -Werror;
#   2. it includes (directly, or through the core's own headers) no header
#      besides stdint.h, stddef.h, stdbool.h, string.h (checked with -H);
#   3. no object references malloc/calloc/realloc/free, the printf family,
#      libm, or a floating-point helper (__aeabi_f*/__aeabi_d*, __*sf*/__*df*
#      soft-float routines, __float*, __fix*);
#   4. the objects link with tests/freestanding/entry.c (which calls
#      bw_encode_ctx/bw_decode_ctx on static buffers) into an image with -nostdlib
#      -nostartfiles ... -lgcc, leaving no undefined symbol;
#   5. the linked image has none of the symbols of 3 and holds the codec
#      entry points.
# The -Os image, the device's, is built with the device's switches
# (mk/core-device.mk) and link-time optimisation, and must fit 16 KiB.
# Prints the section sizes of the images and "RESULT: N passed, M failed".
# Environment: CORE_DIR (default firmware/codec), FREESTANDING_BUILD (build/freestanding).
set -eu
cd "$(dirname "$0")/../.."

OUT=${FREESTANDING_BUILD:-build/freestanding}
CORE_DIR=${CORE_DIR:-firmware/codec} # another copy of the core, to try the checks out
CORE_SRC=$(ls "$CORE_DIR"/*.c)
ALLOWED_HEADERS='stdint.h|stddef.h|stdbool.h|string.h'
FORBIDDEN='^(malloc|calloc|realloc|free|_malloc_r|_free_r|[a-z]*printf|_[a-z]*printf_r|puts|putchar|abort|exit|sqrtf?|floorf?|ceilf?|powf?|expf?|logf?|fabsf?|roundf?|lroundf?)$'
FLOAT='^__aeabi_[fd]|^__aeabi_u?[il]2[fd]$|^__.*(sf|df|tf)[0-9]?$|^__(add|sub|mul|div|neg)(s|d|t)f[0-9]$|^__float|^__fix'
REQUIRED='bw_encode_ctx bw_decode_ctx bw_decode_unchecked bw_header_read bw_spec_fwd bw_spec_inv bw_biohaar_fwd bw_biohaar_inv bw_crc32_update bw_rc_enc_shift_low bw_stream_push'
# with link-time optimisation the kernels may be inlined into their callers:
# the entry points entry.c calls
REQUIRED_LTO='bw_encode_ctx bw_decode_ctx bw_decode_unchecked bw_header_read bw_stream_push'

passed=0
failed=0
ok() { echo "  ok    $*"; passed=$((passed + 1)); }
bad() { echo "  FAIL  $*"; failed=$((failed + 1)); }

# $1 compiler, $2 source, rest: flags. Prints the offending includes.
check_headers() {
    local cc=$1 src=$2
    shift 2
    "$cc" "$@" -H -fsyntax-only "$src" 2>&1 >/dev/null | grep '^\.\+ ' |
        awk -v src="$src" -v core="$CORE_DIR/" -v allowed="^($ALLOWED_HEADERS)$" '
        {
            match($0, /^\.+/); depth = RLENGTH; path = substr($0, depth + 2)
            sub(/^\.\//, "", path)
            rest = substr(path, length(core) + 1)
            own[depth] = (substr(path, 1, length(core)) == core && rest !~ /\//)
            name[depth] = path
            from_own = depth == 1 ? 1 : own[depth - 1]
            from = depth == 1 ? src : name[depth - 1]
            base = path; sub(/.*\//, "", base)
            if (from_own && !own[depth] && base !~ allowed)
                print path " (included by " from ")"
        }'
}

# $1 label, $2 nm, rest: files. Prints forbidden symbol references.
forbidden_symbols() {
    local nm=$2
    shift 2
    "$nm" "$@" 2>/dev/null | awk 'NF >= 2 {print $NF}' | grep -E "$FORBIDDEN|$FLOAT" | sort -u || true
}

# $1 label, $2 prefix (arm-none-eabi-), rest: flags. With LTO=1 the core is
# compiled for link-time optimisation (fat objects, which the symbol checks
# read as usual) and the images are linked with it; entry.c, the harness
# that provides the string.h routines, is not.
check_target() {
    local label=$1 prefix=$2
    shift 2
    local cc=${prefix}gcc nm=${prefix}nm size=${prefix}size dir="$OUT/$label"
    local flags=("$@") lto=()
    [ "${LTO:-0}" = 1 ] && lto=(-flto -ffat-lto-objects)
    echo "== $label: $cc ${flags[*]} ${lto[*]}"
    if ! command -v "$cc" >/dev/null; then
        bad "$label: $cc not found (tests/deps.sh installs it)"
        return 0
    fi
    rm -rf "$dir"
    mkdir -p "$dir"
    # string.h is not among C11's freestanding headers: a toolchain without a C
    # library (riscv64-unknown-elf-gcc without newlib/picolibc) gets a stand-in
    # that only declares the four routines entry.c defines
    if ! echo '#include <string.h>' | "$cc" "${flags[@]}" -x c -fsyntax-only - 2>/dev/null; then
        mkdir -p "$dir/include"
        cat >"$dir/include/string.h" <<'HDR'
#ifndef BW_FREESTANDING_STRING_H
#define BW_FREESTANDING_STRING_H
#include <stddef.h>
void *memcpy(void *restrict dst, const void *restrict src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);
#endif
HDR
        flags+=(-isystem "$dir/include")
        echo "  note  $label: no C library headers; using a declarations-only string.h ($dir/include)"
    fi

    # 1. compile
    local objs=() src obj n_bad=0
    for src in $CORE_SRC; do
        obj="$dir/$(basename "${src%.c}").o"
        if "$cc" "${flags[@]}" "${lto[@]}" -I"$CORE_DIR" -ffunction-sections -fdata-sections -c "$src" -o "$obj"; then
            objs+=("$obj")
        else
            n_bad=$((n_bad + 1))
        fi
    done
    if [ "$n_bad" = 0 ]; then ok "$label: ${#objs[@]} core sources compile"; else bad "$label: $n_bad core sources do not compile"; return 0; fi

    # 2. headers
    local hdr_bad=""
    for src in $CORE_SRC; do
        hdr_bad="$hdr_bad$(check_headers "$cc" "$src" "${flags[@]}" -I"$CORE_DIR")"
    done
    if [ -z "$hdr_bad" ]; then
        ok "$label: includes only $ALLOWED_HEADERS and the core's own headers"
    else
        bad "$label: other headers included:"
        printf '%s\n' "$hdr_bad" | sed 's/^/          /'
    fi

    # 3. symbols of the objects
    local sym
    sym=$(forbidden_symbols "$label" "$nm" -u "${objs[@]}")
    if [ -z "$sym" ]; then
        ok "$label: objects reference no allocator, printf, libm or float helper"
    else
        bad "$label: objects reference: $(echo "$sym" | tr '\n' ' ')"
    fi

    # 4. link (the whole core, and the parts the entry uses with --gc-sections)
    # the harness in sections of its own too: the string.h routines the core
    # does not call are left out of the image, as the core's unused code is
    "$cc" "${flags[@]}" -I"$CORE_DIR" -ffunction-sections -fdata-sections \
        -fno-tree-loop-distribute-patterns -c tests/freestanding/entry.c -o "$dir/entry.o"
    local linked=1
    local ldflags=(-nostdlib -nostartfiles "-Wl,-e,_start")
    if "$cc" "${flags[@]}" -Wl,--no-warn-rwx-segments -x c -o /dev/null - -nostdlib -nostartfiles \
        -Wl,-e,0 <<<'int x;' 2>/dev/null; then
        ldflags+=("-Wl,--no-warn-rwx-segments")
    fi
    if "$cc" "${flags[@]}" "${lto[@]}" "${ldflags[@]}" "${objs[@]}" "$dir/entry.o" -lgcc \
        -o "$dir/core.elf" &&
        "$cc" "${flags[@]}" "${lto[@]}" "${ldflags[@]}" -Wl,--gc-sections \
            "${objs[@]}" "$dir/entry.o" -lgcc -o "$dir/codec-gc.elf"; then
        local undef
        undef=$("$nm" -u "$dir/core.elf" | awk '{print $NF}' | tr '\n' ' ')
        if [ -z "$undef" ]; then ok "$label: links with -nostdlib -nostartfiles -lgcc ($dir/core.elf)"; else bad "$label: undefined in the image: $undef"; linked=0; fi
    else
        bad "$label: does not link without a C library"
        linked=0
    fi
    [ "$linked" = 1 ] || return 0

    # 5. symbols of the image
    sym=$(forbidden_symbols "$label" "$nm" "$dir/core.elf")
    if [ -z "$sym" ]; then
        ok "$label: image has no allocator, printf, libm or float helper"
    else
        bad "$label: image contains: $(echo "$sym" | tr '\n' ' ')"
    fi
    local missing="" f
    local required=$REQUIRED
    [ "${LTO:-0}" = 1 ] && required=$REQUIRED_LTO
    for f in $required; do
        "$nm" "$dir/codec-gc.elf" | awk '{print $NF}' | grep -qx "$f" || missing="$missing $f"
    done
    if [ -z "$missing" ]; then
        ok "$label: the entry keeps the codec's code after --gc-sections ($required)"
    else
        bad "$label: garbage-collected away:$missing"
    fi
    echo "  sizes (whole core + entry, and what the entry uses after --gc-sections):"
    "$size" "$dir/core.elf" "$dir/codec-gc.elf" | sed 's/^/    /'
    local helpers
    helpers=$("$nm" "$dir/core.elf" | awk '$NF ~ /^__/ && $NF !~ /__$/ &&
        $NF !~ /^__(bss|data|end|stack|global|sdata|exidx|init|fini|preinit|dso)_/ {print $NF}' |
        sort -u | tr '\n' ' ')
    echo "  libgcc helpers linked: $helpers"
}

check_target arm-cortex-m4 arm-none-eabi- \
    -std=c11 -mcpu=cortex-m4 -mthumb -ffreestanding -O2 -Wall -Wextra -Werror

# the device build: the codec (encoder, decoder, streaming encoder and the
# library helpers they pull in) must fit 16 KiB of flash at -Os with the
# device's switches (mk/core-device.mk) and link-time optimisation (as
# mk/mcu.mk builds it)
DEVICE_CFG=$(sed -n 's/^BW_DEVICE_CFG := //p' mk/core-device.mk)
# shellcheck disable=SC2086
LTO=1 check_target arm-cortex-m4-Os arm-none-eabi- \
    -std=c11 -mcpu=cortex-m4 -mthumb -ffreestanding -Os $DEVICE_CFG -Wall -Wextra -Werror
# the image's text less the harness that calls the codec (bw_entry, _start
# in entry.c); the string.h routines it provides stay, as the core calls them
img=$OUT/arm-cortex-m4-Os/codec-gc.elf
image_text=$(arm-none-eabi-size "$img" | awk 'NR == 2 {print $1}')
harness=0
while read -r _ size _ name; do
    case $name in bw_entry | _start) harness=$((harness + 16#$size)) ;; esac
done < <(arm-none-eabi-nm -S "$img")
text=$((image_text - harness))
if [ -n "$image_text" ] && [ "$harness" -gt 0 ] && [ "$text" -le 16384 ]; then
    ok "arm-cortex-m4-Os: codec text $text bytes <= 16384 (image $image_text less the harness's $harness)"
else
    bad "arm-cortex-m4-Os: codec text ${text:-?} bytes > 16384 (image ${image_text:-?} less the harness's ${harness:-?})"
fi

# RV32 if its libgcc multilib is there, else RV64
RV_ARCH="-march=rv32imac -mabi=ilp32"
if command -v riscv64-unknown-elf-gcc >/dev/null; then
    # shellcheck disable=SC2086
    lib=$(riscv64-unknown-elf-gcc $RV_ARCH -print-libgcc-file-name)
    case "$lib" in */rv32imac/ilp32/*) ;; *) RV_ARCH="-march=rv64imac -mabi=lp64"; echo "(no rv32imac/ilp32 libgcc: using $RV_ARCH)" ;; esac
fi
# shellcheck disable=SC2086
check_target riscv riscv64-unknown-elf- \
    -std=c11 -ffreestanding -nostdlib -O2 $RV_ARCH -Wall -Wextra -Werror

echo "RESULT: $passed passed, $failed failed"
[ "$failed" = 0 ]
