#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Fuzzing of the codec core: tests/fuzz/fuzz_decode.c (the decoder on arbitrary
# bytes) and tests/fuzz/fuzz_roundtrip.c (encode, decode, check the guarantee),
# of the host library's readers of a payload (tests/fuzz/fuzz_host.c) and of
# measurement files (tests/fuzz/fuzz_inputs.c), and of the link's frame receiver
# (tests/fuzz/fuzz_link.c).
#
#   tests/fuzz/run.sh            libFuzzer builds (clang -fsanitize=fuzzer,address,
#                                undefined), each target fuzzed for $FUZZ_SECONDS
#                                seconds (default 30). For `make fuzz`.
#   tests/fuzz/run.sh --replay   replay builds (gcc -DBW_FUZZ_REPLAY, ASan + UBSan)
#                                that run every corpus input once. For `make check`
#                                (through tests/fuzz/replay.sh).
#
# Corpora, per target: tests/fuzz/corpus/<target> (committed) and seeds made by
# tests/fuzz/gen_corpus.c from the current core in $FUZZ_BUILD/seeds/<target>.
# Fuzzing adds what it finds to $FUZZ_BUILD/corpus/<target> and writes failing
# inputs to $FUZZ_BUILD/artifacts/; replay one with
#   $FUZZ_BUILD/replay_<target> <file>      (after tests/fuzz/run.sh --replay)
# Environment: FUZZ_SECONDS, FUZZ_BUILD (default build/fuzz), FUZZ_CC (clang),
# REPLAY_CC (gcc).
set -eu
cd "$(dirname "$0")/../.."

mode=fuzz
case "${1:-}" in
"") ;;
--replay) mode=replay ;;
*) echo "usage: tests/fuzz/run.sh [--replay]" >&2; exit 2 ;;
esac

OUT=${FUZZ_BUILD:-build/fuzz}
FUZZ_SECONDS=${FUZZ_SECONDS:-30}
TARGETS="decode roundtrip host inputs link"
CORE_SRC=$(ls firmware/codec/*.c)
# the host target links libbrdfwave's sources (mk/host.mk, LIB_SRC)
HOST_SRC="$CORE_SRC firmware/link/bw_frame.c $(ls host-tools/lib/*.c) host-tools/ref/bwr_rgl.c
    host-tools/ref/bwr_project.c host-tools/ref/bwr_geodesic.c"
HOST_INC="-Ifirmware/link -Ihost-tools/lib -Ihost-tools/ref -Iinclude"
# the sources and include directories of target $1
# (host, inputs: the library's)
srcs() {
    case $1 in
    host | inputs) echo "$HOST_SRC" ;;
    link) echo "$CORE_SRC $(ls firmware/link/*.c)" ;;
    *) echo "$CORE_SRC" ;;
    esac
}
incs() {
    case $1 in
    host | inputs) echo "-Ifirmware/codec $HOST_INC" ;;
    link) echo "-Ifirmware/codec -Ifirmware/link" ;;
    *) echo "-Ifirmware/codec" ;;
    esac
}
# the seed directories of target $1 made here (host: the decoder's payloads;
# link: none, its corpus only)
seeds() {
    case $1 in
    host) echo "$OUT/seeds/decode" ;;
    link) ;;
    *) echo "$OUT/seeds/$1" ;;
    esac
}
# the inputs target's seeds ($OUT/seeds/inputs): files of tests/data
INPUT_SEEDS="tests/data/instruments/asd tests/data/instruments/svc_sig
    tests/data/instruments/usgs_splib07_ascii tests/data/field_psr3500/1116037_00041.sed
    tests/data/instruments/envi/ang20150420t182808_corr_v1e_img_4200-4210_70-80.hdr
    tests/data/goniometer/spectralon.csv tests/data/rgl/satin_rosaline_rgb.bsdf"
WARN="-std=c11 -Wall -Wextra -Wshadow -Wstrict-prototypes -Werror"
SAN="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
mkdir -p "$OUT"

echo "== seeds from the current core: $OUT/seeds"
# shellcheck disable=SC2086
gcc $WARN -O2 -Ifirmware/codec tests/fuzz/gen_corpus.c $CORE_SRC -o "$OUT/gen_corpus"
rm -rf "$OUT/seeds"
"$OUT/gen_corpus" "$OUT/seeds"
# shellcheck disable=SC2086
mkdir -p "$OUT/seeds/inputs" && cp $(find $INPUT_SEEDS -type f ! -name 'LICENSE*' ! -name 'GPL*' \
    ! -name 'SOURCE*' ! -name 'PUBLIC*' ! -name 'NOTE*') "$OUT/seeds/inputs/"

passed=0
failed=0

if [ "$mode" = replay ]; then
    CC=${REPLAY_CC:-gcc}
    for t in $TARGETS; do
        echo "== replay build: $OUT/replay_$t ($CC -DBW_FUZZ_REPLAY, ASan + UBSan)"
        # shellcheck disable=SC2086
        $CC $WARN -O1 -g $SAN -DBW_FUZZ_REPLAY $(incs $t) "tests/fuzz/fuzz_$t.c" $(srcs $t) \
            -lm -o "$OUT/replay_$t"
    done
    for t in $TARGETS; do
        dirs=$(seeds $t)
        [ -d "tests/fuzz/corpus/$t" ] && dirs="tests/fuzz/corpus/$t $dirs"
        # shellcheck disable=SC2086
        count=$(find $dirs -type f | wc -l)
        echo "== replaying $count inputs through $t: $dirs"
        # shellcheck disable=SC2086
        if "$OUT/replay_$t" $dirs; then
            passed=$((passed + count))
        else
            echo "FAIL: replay of $t (exit $?)"
            failed=$((failed + 1))
        fi
    done
    echo "RESULT: $passed passed, $failed failed"
    [ "$failed" = 0 ]
    exit
fi

CC=${FUZZ_CC:-clang}
command -v "$CC" >/dev/null || { echo "tests/fuzz/run.sh: $CC not found (tests/deps.sh fuzz)" >&2; exit 1; }
for t in $TARGETS; do
    echo "== fuzz build: $OUT/fuzz_$t ($CC -fsanitize=fuzzer,address,undefined)"
    # shellcheck disable=SC2086
    $CC $WARN -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
        $(incs $t) "tests/fuzz/fuzz_$t.c" $(srcs $t) -lm -o "$OUT/fuzz_$t"
done
mkdir -p "$OUT/artifacts"
for t in $TARGETS; do
    mkdir -p "$OUT/corpus/$t"
    dirs="$OUT/corpus/$t $(seeds $t)"
    [ -d "tests/fuzz/corpus/$t" ] && dirs="$dirs tests/fuzz/corpus/$t"
    log="$OUT/fuzz_$t.log"
    echo "== fuzzing $t for ${FUZZ_SECONDS}s (log $log)"
    # shellcheck disable=SC2086
    if "$OUT/fuzz_$t" -max_total_time="$FUZZ_SECONDS" -timeout=20 -rss_limit_mb=2048 \
        -max_len=8192 -print_final_stats=1 -artifact_prefix="$OUT/artifacts/$t-" $dirs \
        >"$log" 2>&1; then
        grep -E '^stat::number_of_executed_units|^Done' "$log" || true
        echo "   corpus: $(find "$OUT/corpus/$t" -type f | wc -l) inputs in $OUT/corpus/$t"
        passed=$((passed + 1))
    else
        echo "FAIL: fuzzing $t found a failing input (last lines of $log):"
        tail -40 "$log"
        ls -1 "$OUT/artifacts/$t-"* 2>/dev/null || true
        failed=$((failed + 1))
    fi
done
echo "RESULT: $passed passed, $failed failed"
[ "$failed" = 0 ]
