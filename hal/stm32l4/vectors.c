/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * STM32L476 device interrupt vectors, IRQ 0 to 81 (RM0351 §13.3, the
 * STM32L47x/L48x vector table), following the 16 system vectors of
 * hal/cortex-m/startup.c.
 *
 * Both tables are in the input section .isr_vector, which linker/cortex-m.ld
 * keeps at the start of flash in link order: hal/cortex-m/startup.o must come
 * before this object on the link line (mk/mcu.mk), so that IRQ n lands at
 * offset 0x40 + 4 n. I2C1_EV is IRQ 31: vector 47, offset 0xBC.
 * tests/target/build_boards.sh checks it in the linked image.
 *
 * Only the I2C1 interrupts are enabled; any other one that fires is reported
 * through bw_board_fault() with its vector number.
 */
#include <stdint.h>

void bw_board_fault(uint32_t vector);
void I2C1_EV_IRQHandler(void);
void I2C1_ER_IRQHandler(void);

static void unexpected_irq(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    bw_board_fault(ipsr & 0x1FFu);
}

#define IRQ_COUNT 82u
#define U unexpected_irq

__attribute__((section(".isr_vector"), used)) static void (*const irq_vectors[])(void) = {
    /*  0- 7 */ U, U, U, U, U, U, U, U,
    /*  8-15 */ U, U, U, U, U, U, U, U,
    /* 16-23 */ U, U, U, U, U, U, U, U,
    /* 24-30 */ U, U, U, U, U, U, U,
    /* 31 */ I2C1_EV_IRQHandler,
    /* 32 */ I2C1_ER_IRQHandler,
    /* 33-39 */ U, U, U, U, U, U, U,
    /* 40-47 */ U, U, U, U, U, U, U, U,
    /* 48-55 */ U, U, U, U, U, U, U, U,
    /* 56-63 */ U, U, U, U, U, U, U, U,
    /* 64-71 */ U, U, U, U, U, U, U, U,
    /* 72-79 */ U, U, U, U, U, U, U, U,
    /* 80-81 */ U, U,
};

_Static_assert(sizeof irq_vectors == IRQ_COUNT * sizeof irq_vectors[0],
               "one vector per IRQ, 0 to 81");
