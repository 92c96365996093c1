/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * QEMU mps2-an386 backend: SysTick as the instruction counter, the CMSDK
 * APB UART0 as the host link, a file read by semihosting as the sensor
 * (little-endian int32 samples).
 *
 * Under `qemu-system-arm -icount shift=0` one instruction takes 1 ns of
 * virtual time and SysTick, clocked from the 25 MHz CPU clock, advances one
 * tick per 40 instructions, deterministically. The counter extends the 24-bit
 * SysTick with an overflow count kept by its interrupt.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bw_hal.h"
#include "file_sensor.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

#define UART0_BASE 0x40004000u
#define UART_DATA (*(volatile uint32_t *)(UART0_BASE + 0x00u))
#define UART_STATE (*(volatile uint32_t *)(UART0_BASE + 0x04u))
#define UART_CTRL (*(volatile uint32_t *)(UART0_BASE + 0x08u))
#define UART_BAUDDIV (*(volatile uint32_t *)(UART0_BASE + 0x10u))
#define UART_STATE_TXFULL 0x1u
#define UART_STATE_RXFULL 0x2u

#define INSTRUCTIONS_PER_TICK 40u

static volatile uint32_t systick_wraps;
static int started;

void SysTick_Handler(void) { systick_wraps++; }

static void start(void)
{
    if (started)
        return;
    started = 1;
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 0x7u; /* processor clock, interrupt, enable */
    UART_BAUDDIV = 16u;
    UART_CTRL = 0x3u; /* TX and RX enable */
}

static uint64_t counter(void)
{
    uint32_t hi, lo;
    do { /* re-read if the counter wrapped in between */
        hi = systick_wraps;
        lo = SYST_CVR;
    } while (hi != systick_wraps);
    uint64_t ticks = ((uint64_t)hi << 24) + (0x00FFFFFFu - lo);
    return ticks * INSTRUCTIONS_PER_TICK;
}

static int link_write(const uint8_t *buf, size_t len)
{
    for (size_t i = 0; i < len; i++) {
        while (UART_STATE & UART_STATE_TXFULL) {
        }
        UART_DATA = buf[i];
    }
    return (int)len;
}

static int link_read(uint8_t *buf, size_t cap)
{
    size_t n = 0;
    while (n < cap && (UART_STATE & UART_STATE_RXFULL))
        buf[n++] = (uint8_t)UART_DATA;
    return (int)n;
}

static void fault(uint32_t code)
{
    printf("fault: vector %lu\n", (unsigned long)code);
    exit(128 + (int)(code & 0x7Fu));
}

void bw_board_fault(uint32_t vector) { fault(vector); }

static const bw_hal_t board = {
    .counter = counter,
    .link_write = link_write,
    .link_read = link_read,
    .sensor_open = bw_file_sensor_open,
    .sensor_read = bw_file_sensor_read,
    .fault = fault,
};

const bw_hal_t *bw_board(void)
{
    start();
    return &board;
}
