#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Target tests: the codec core built for the Cortex-M4 and run on the emulated
# board (QEMU mps2-an386), deterministic instruction counting (-icount shift=0),
# output and exit status through semihosting. Run from anywhere.
set -eu
cd "$(dirname "$0")/../.."
make --no-print-directory -s TARGET=qemu target-tests
exec timeout 600 qemu-system-arm -M mps2-an386 -nographic -icount shift=0 \
    -semihosting-config enable=on,target=native \
    -kernel build/qemu/tests/test_target.elf
