#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Builds the firmware for every board and checks the images (nothing runs the
# STM32 image here):
#   1. `make TARGET=qemu all` and `make TARGET=mcu all` succeed and link
#      build/qemu/brdfwave-fw.elf and build/mcu/brdfwave-fw.elf (for the MCU
#      image, linker/stm32l476.ld asserts that .data + .bss + its stack fit);
#   2. the MCU image fits the STM32L476RG: text + data within 1 MiB of flash,
#      data + bss + the 4 KiB stack of linker/stm32l476.ld within 96 KiB of
#      SRAM1, and at least MIN_STACK bytes left below .bss for the stack (the
#      deepest call chain, the application's through the encoder, takes about
#      1.7 KiB; the coder's state, bw_ctx_t, is in .bss);
#   3. it holds no malloc/free (or calloc/realloc) and no printf family;
#   4. its vector table: initial stack pointer at the top of SRAM1,
#      Reset_Handler at 0x04, I2C1_EV_IRQHandler at 0xBC (IRQ 31, vector 47)
#      and I2C1_ER_IRQHandler at 0xC0.
# Prints "RESULT: N passed, M failed".
set -u
cd "$(dirname "$0")/../.."

CROSS=${CROSS_COMPILE:-arm-none-eabi-}
QEMU_ELF=build/qemu/brdfwave-fw.elf
MCU_ELF=build/mcu/brdfwave-fw.elf
FLASH_BASE=0x08000000
FLASH_SIZE=$((1024 * 1024))
RAM_BASE=0x20000000
RAM_SIZE=$((96 * 1024))
STACK_RESERVED=$((4 * 1024))
MIN_STACK=${MIN_STACK:-$((4 * 1024))}

passed=0
failed=0
ok() { echo "  ok    $*"; passed=$((passed + 1)); }
bad() { echo "  FAIL  $*"; failed=$((failed + 1)); }
check() { # description, command...
    local what=$1
    shift
    if "$@"; then ok "$what"; else bad "$what"; fi
}

log=$(mktemp)
trap 'rm -f "$log"' EXIT

for target in qemu mcu; do
    if make --no-print-directory -s TARGET=$target all >"$log" 2>&1; then
        ok "make TARGET=$target all"
    else
        bad "make TARGET=$target all"
        tail -20 "$log"
    fi
done
check "$QEMU_ELF links (ARM ELF executable)" \
    sh -c "${CROSS}readelf -h '$QEMU_ELF' 2>/dev/null | grep -q 'Machine:.*ARM'"
check "$MCU_ELF links (ARM ELF executable)" \
    sh -c "${CROSS}readelf -h '$MCU_ELF' 2>/dev/null | grep -q 'Machine:.*ARM'"

if [ ! -f "$MCU_ELF" ]; then
    bad "no MCU image, the remaining checks cannot run"
    echo "RESULT: $passed passed, $failed failed"
    exit 1
fi

# ---- sizes ------------------------------------------------------------------
read -r text data bss _ < <("${CROSS}size" -B "$MCU_ELF" | awk 'NR == 2 {print $1, $2, $3}')
"${CROSS}size" -B "$MCU_ELF"
flash=$((text + data))
ram=$((data + bss))
echo "  flash $flash of $FLASH_SIZE bytes, RAM $ram + stack $STACK_RESERVED of $RAM_SIZE bytes," \
    "$((RAM_SIZE - ram)) bytes below .bss for the stack"
check "flash: text + data = $flash <= $FLASH_SIZE" test "$flash" -le "$FLASH_SIZE"
check "RAM: data + bss + stack = $((ram + STACK_RESERVED)) <= $RAM_SIZE" \
    test $((ram + STACK_RESERVED)) -le "$RAM_SIZE"
check "stack room: $((RAM_SIZE - ram)) >= $MIN_STACK bytes" test $((RAM_SIZE - ram)) -ge "$MIN_STACK"

# every allocated section inside its memory
sections_in_place() {
    local listing name addr size flags outside=""
    listing=$("${CROSS}readelf" -SW "$MCU_ELF") || return 1
    while read -r name addr size flags; do
        case $flags in *A*) ;; *) continue ;; esac
        addr=$((16#$addr))
        size=$((16#$size))
        [ "$size" = 0 ] && continue
        if [ "$addr" -ge $((FLASH_BASE)) ] && [ $((addr + size)) -le $((FLASH_BASE + FLASH_SIZE)) ]; then
            continue
        fi
        if [ "$addr" -ge $((RAM_BASE)) ] && [ $((addr + size)) -le $((RAM_BASE + RAM_SIZE)) ]; then
            continue
        fi
        outside="$outside $name"
    done < <(sed -n 's/^ *\[ *[0-9]*\] *//p' <<<"$listing" | awk 'NF >= 7 {print $1, $3, $5, $7}')
    [ -z "$outside" ] || { echo "    outside flash/RAM:$outside"; return 1; }
}
check "allocated sections inside flash (0x08000000) and SRAM1 (0x20000000)" sections_in_place

# ---- no heap, no printf -------------------------------------------------------
forbidden=$("${CROSS}nm" "$MCU_ELF" | awk '{print $NF}' |
    grep -E '^(malloc|calloc|realloc|free|_malloc_r|_calloc_r|_realloc_r|_free_r|.*printf.*)$' | sort -u | tr '\n' ' ')
check "no malloc/free/printf in the MCU image${forbidden:+ (found: $forbidden)}" test -z "$forbidden"

# ---- vector table ---------------------------------------------------------------
# the 32-bit little-endian word at an address of the vector table, as 0x...
word_at() {
    local line w
    line=$("${CROSS}objdump" -s -j .isr_vector --start-address=$(($1)) --stop-address=$(($1 + 4)) \
        "$MCU_ELF" | grep -E '^ [0-9a-f]+ [0-9a-f]+' | head -1)
    w=$(awk '{print $2}' <<<"$line")
    [ ${#w} = 8 ] || return 0
    echo "0x${w:6:2}${w:4:2}${w:2:2}${w:0:2}"
}
symbol() { "${CROSS}nm" "$MCU_ELF" | awk -v s="$1" '$3 == s {print "0x" $1}'; }
vector_is() { # offset, handler
    local w s
    w=$(word_at $((FLASH_BASE + $1)))
    s=$(symbol "$2")
    [ -n "$w" ] && [ -n "$s" ] && [ $((w)) -eq $(($s | 1)) ] ||
        { echo "    word at offset $1: ${w:-none}, $2: ${s:-undefined}"; return 1; }
}
sp_is_top() {
    local w
    w=$(word_at "$FLASH_BASE")
    [ -n "$w" ] && [ $((w)) -eq $((RAM_BASE + RAM_SIZE)) ] || { echo "    initial SP ${w:-none}"; return 1; }
}
check "initial stack pointer = top of SRAM1 (0x20018000)" sp_is_top
check "Reset_Handler at offset 0x04" vector_is 0x04 Reset_Handler
check "I2C1_EV_IRQHandler at offset 0xBC (IRQ 31)" vector_is 0xBC I2C1_EV_IRQHandler
check "I2C1_ER_IRQHandler at offset 0xC0 (IRQ 32)" vector_is 0xC0 I2C1_ER_IRQHandler

echo "RESULT: $passed passed, $failed failed"
[ "$failed" = 0 ]
