#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The unit tests (tests/unit/test_*.c) built with AddressSanitizer and
# UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the first finding
# aborts) and run with BW_TEST_QUICK=1, which leaves out the largest round
# trips. Compiles the sources directly (firmware/codec/*.c, the link frames
# and the I2C window, host-tools/lib/*.c, the renderer's meshes for
# test_mesh, the reference model's RGL loader, projection and grid for the
# library's RGL and goniometer readers, each test)
# into $SANITIZE_BUILD (default build/sanitize), independent of the
# Makefile's build. The codec core is
# compiled as for the device (-Os and the switches of mk/core-device.mk:
# the small code forms, the encoder without prediction), so that those forms
# run here, and the tests are compiled with the same switches (they read
# them, firmware/codec/bw_config.h); the other builds run the default forms.
# test_codec, test_segments and test_embed then run once more with the core
# and the test built with the default switches, for what the device's core
# leaves out (prediction, segments, embedded segments).
# Prints one line per test program and "RESULT: N passed, M failed" (cmocka
# test cases); each program's output is kept in $SANITIZE_BUILD/<name>.log.
# Environment: SANITIZE_CC (gcc), SANITIZE_BUILD, BW_TEST_QUICK (default 1).
set -eu
cd "$(dirname "$0")/.."

OUT=${SANITIZE_BUILD:-build/sanitize}
CC=${SANITIZE_CC:-gcc}
CFLAGS="-std=c11 -Wall -Wextra -Wshadow -Wstrict-prototypes -Werror -O1 -g -fno-omit-frame-pointer
        -fsanitize=address,undefined -fno-sanitize-recover=all
        -Ifirmware/codec -Ifirmware/link -Ifirmware/app -Ihal -Ihost-tools/lib -Iinclude -Ihost-tools/render -Ihost-tools/ref -Itests/unit"
DEVICE_CFG=$(sed -n 's/^BW_DEVICE_CFG := //p' mk/core-device.mk)
LIB_SRC="$(ls firmware/codec/*.c) firmware/link/bw_frame.c firmware/link/bw_i2cwin.c $(ls host-tools/lib/*.c)
         host-tools/render/render_mesh.c host-tools/ref/bwr_rgl.c host-tools/ref/bwr_project.c
         host-tools/ref/bwr_geodesic.c"
export BW_TEST_QUICK=${BW_TEST_QUICK:-1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

mkdir -p "$OUT/obj" "$OUT/obj-O1"
echo "== building with $CC -fsanitize=address,undefined into $OUT"
objs=()
core_o1=()
for src in $LIB_SRC; do
    obj="$OUT/obj/$(echo "${src%.c}" | tr / _).o"
    opt=
    case $src in firmware/codec/*) opt="-Os $DEVICE_CFG" ;; esac
    # shellcheck disable=SC2086
    $CC $CFLAGS $opt -c "$src" -o "$obj"
    case $src in
    firmware/codec/*)
        # the core once more with the default switches: what the device's
        # switches leave out (the prediction encoder) runs in the second pass
        # of test_codec
        o1="$OUT/obj-O1/$(echo "${src%.c}" | tr / _).o"
        # shellcheck disable=SC2086
        $CC $CFLAGS -c "$src" -o "$o1"
        core_o1+=("$o1")
        ;;
    *) core_o1+=("$obj") ;;
    esac
    objs+=("$obj")
done

passed=0
failed=0
# run_test NAME SOURCE SWITCHES OBJECTS...: SWITCHES, those of the core in
# OBJECTS, for the test to read
run_test() {
    local name=$1 t=$2 cfg=$3
    shift 3
    local bin="$OUT/$name" log="$OUT/$name.log"
    # shellcheck disable=SC2086
    if ! $CC $CFLAGS $cfg "$t" "$@" -lcmocka -lm -o "$bin" >"$log" 2>&1; then
        printf '  %-24s does not build\n' "$name"
        sed 's/^/    | /' "$log" | tail -20
        failed=$((failed + 1))
        return
    fi
    local t0 rc=0 secs p f
    t0=$(date +%s)
    "$bin" >"$log" 2>&1 || rc=$?
    secs=$(($(date +%s) - t0))
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
    if [ "$rc" != 0 ] && [ "$f" = 0 ]; then f=1; fi # a sanitizer abort ends the program early
    passed=$((passed + p))
    failed=$((failed + f))
    if [ "$f" = 0 ]; then
        printf '  %-24s %4d passed            (%ss)\n' "$name" "$p" "$secs"
    else
        printf '  %-24s %4d passed %4d FAILED (%ss, exit %s); last lines of %s:\n' \
            "$name" "$p" "$f" "$secs" "$rc" "$log"
        grep -E 'runtime error|ERROR: AddressSanitizer|SUMMARY|FAILED|ERROR' "$log" | head -20 | sed 's/^/    | /'
        tail -25 "$log" | sed 's/^/    | /'
    fi
}
for t in tests/unit/test_*.c; do
    run_test "$(basename "${t%.c}")" "$t" "$DEVICE_CFG" "${objs[@]}"
done
run_test test_codec_O1_core tests/unit/test_codec.c "" "${core_o1[@]}"
run_test test_segments_O1_core tests/unit/test_segments.c "" "${core_o1[@]}"
run_test test_embed_O1_core tests/unit/test_embed.c "" "${core_o1[@]}"
echo "RESULT: $passed passed, $failed failed"
[ "$failed" = 0 ]
