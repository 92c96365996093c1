#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Runs every test suite and ends with one summary line: "tests: N passed, M failed".
# cmocka suites count their test cases; scripts count the cases they report
# on a line "RESULT: N passed, M failed" (or 1 if they print none).
set -u
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build/host}
passed=0
failed=0
failures=""

count() { # name, exit status, log file
    local name=$1 rc=$2 log=$3 p f
    if grep -q '^\[==========\]' "$log"; then
        p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | awk '{s+=$1} END {print s+0}')
        f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | awk '{s+=$1} END {print s+0}')
    elif grep -q '^RESULT: [0-9]* passed, [0-9]* failed' "$log"; then
        p=$(sed -n 's/^RESULT: \([0-9]*\) passed.*/\1/p' "$log" | tail -1)
        f=$(sed -n 's/^RESULT: [0-9]* passed, \([0-9]*\) failed.*/\1/p' "$log" | tail -1)
    else
        p=$((rc == 0)); f=$((rc != 0))
    fi
    # a crash or a non-zero exit is a failure even if the counts look clean
    if [ "$rc" != 0 ] && [ "$f" = 0 ]; then f=1; fi
    passed=$((passed + p))
    failed=$((failed + f))
    if [ "$f" != 0 ]; then failures="$failures $name"; fi
    printf '%-28s %4d passed %4d failed  (%ss)\n' "$name" "$p" "$f" "$4"
}

run() { # name, command...
    local name=$1 log t0 rc
    shift
    log=$(mktemp)
    t0=$(date +%s)
    "$@" >"$log" 2>&1
    rc=$?
    count "$name" "$rc" "$log" "$(( $(date +%s) - t0 ))"
    if [ "$rc" != 0 ] || grep -q '^\[  FAILED  \]' "$log"; then
        echo "---- $name output (last 40 lines) ----"
        tail -40 "$log"
        echo "----"
    fi
    cat "$log" >>"$BUILD/tests/all.log"
    rm -f "$log"
}

mkdir -p "$BUILD/tests"
: >"$BUILD/tests/all.log"
for t in "$BUILD"/tests/test_*; do
    [ -x "$t" ] || continue
    run "$(basename "$t")" "$t"
done
for s in tests/ref/check_pywt.py tests/rd/check_rd.py tests/ref/test_bwref.sh tests/cli/test_cli.sh tests/cli/test_formats.sh tests/cli/test_render.sh tests/freestanding/check.sh tests/sanitize.sh tests/fuzz/replay.sh \
    tests/target/run.sh tests/target/test_e2e.sh tests/target/build_boards.sh \
    tests/python/test_package.py tests/python/test_install.sh tests/hw/run.sh; do
    [ -x "$s" ] && run "$(basename "$(dirname "$s")")/$(basename "$s")" "$s"
done
# the product: licence lines, the command line's conventions, install, packages
for s in tests/license/test_spdx.sh tests/cli/test_product.sh tests/python/test_plot.py \
    tests/install/test_install.sh tests/conformance/check.py tests/deb/test_deb.sh; do
    [ -x "$s" ] && run "$(basename "$(dirname "$s")")/$(basename "$s")" "$s"
done

echo
[ -n "$failures" ] && echo "failed suites:$failures"
echo "tests: $passed passed, $failed failed"
[ "$failed" = 0 ]
