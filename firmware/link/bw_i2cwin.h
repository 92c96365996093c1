/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The I2C register window of docs/I2C.md: the payload the application keeps
 * for the host, offered in 32-byte pages with a CRC-32 each, and the
 * registers a host reads and writes to fetch and acknowledge it.
 * Freestanding, no heap: a board keeps one bw_i2cwin_t and serves it from
 * its I2C target interrupt; tests/unit/test_i2cwin.c drives it as a host
 * would.
 *
 * Two sides:
 *   the device   bw_i2cwin_offer (a payload, or none), bw_i2cwin_job_failed,
 *                bw_i2cwin_set_fault: what STATUS and the window show;
 *   the bus      a transfer as an I2C target controller reports it:
 *                bw_i2cwin_addressed (START or repeated START, direction),
 *                bw_i2cwin_received (a byte from the host),
 *                bw_i2cwin_transmit (the next byte for the host),
 *                bw_i2cwin_stop, bw_i2cwin_bus_error.
 *
 * A write transfer's first byte selects the register; the following bytes
 * (one for a byte register, low then high for a word) are applied at its end
 * (STOP or repeated START); FRAMES takes any number, which go to the
 * application (ops->to_app) as bytes of its incoming frame stream. A read
 * returns the selected register and the following ones, two bytes each, low
 * first; BLOCK is an SMBus block read of the selected page. Values are
 * computed as the bytes are asked for.
 *
 *   idle --START+W--> write: [reg] [data ...] --STOP/Sr--> apply, idle
 *   idle --START+R--> read: reg, reg+1, ... (2 bytes each) --STOP--> idle
 *
 * CMD = ACK with ACK_LO/ACK_HI equal to ID releases the payload at once
 * (STATUS.ready and data-ready low) and hands the application the ACK frame
 * of docs/LINK.md through ops->to_app, as if it had come over the UART.
 *
 * Concurrency: the device side and the bus side change the same state. On a
 * board the bus side runs in the I2C interrupt; call the device side with
 * that interrupt masked (each call is short: no CRC of the payload is
 * computed inside).
 */
#ifndef BW_I2CWIN_H
#define BW_I2CWIN_H

#include <stddef.h>
#include <stdint.h>

#include "bw_i2cmap.h"

/* the longest payload the window can address: 65535 pages */
#define BW_I2CWIN_MAX_LEN (65535u * BW_I2C_PAGE_SIZE)

typedef struct {
    /* bytes for the application's incoming frame stream (FRAMES writes, and
     * the ACK frame of CMD = ACK); NULL: dropped */
    void (*to_app)(void *ctx, const uint8_t *bytes, size_t n);
    /* STATUS.ready changed: the board's data-ready line follows it; NULL:
     * none */
    void (*ready)(void *ctx, int offered);
    void *ctx;
} bw_i2cwin_ops_t;

typedef struct {
    const bw_i2cwin_ops_t *ops;
    /* the offered payload (STATUS.ready): the application's buffer */
    const uint8_t *payload;
    uint32_t id, len, crc;
    uint8_t offered;
    /* STATUS bits and their codes */
    uint8_t error, lost, nak, fault_valid;
    uint16_t errcode;
    uint32_t fault;
    /* registers the host writes */
    uint16_t page, page_hi, ack_lo, ack_hi;
    /* the transfer under way */
    uint8_t state, reg, first;
    uint32_t index; /* bytes sent in this read / received in this write */
    uint8_t wbuf[2];
} bw_i2cwin_t;

void bw_i2cwin_init(bw_i2cwin_t *w, const bw_i2cwin_ops_t *ops);

/* ---- the device side ------------------------------------------------------ */

/* Offers payload[len] (its CRC-32 crc) under id until the next call; len 0
 * offers nothing (the application is about to reuse the buffer). A payload
 * longer than BW_I2CWIN_MAX_LEN is not offered and sets STATUS.lost. */
void bw_i2cwin_offer(bw_i2cwin_t *w, uint32_t id, const uint8_t *payload, uint32_t len,
                     uint32_t crc);

/* The last job ended with an ERROR frame of this status: STATUS.error,
 * ERRCODE. */
void bw_i2cwin_job_failed(bw_i2cwin_t *w, int32_t status);

/* A fault code recorded before the last reset: STATUS.fault, FAULT. */
void bw_i2cwin_set_fault(bw_i2cwin_t *w, uint32_t code);

/* Bytes for the application were lost (the board had no room for them):
 * STATUS.lost. */
void bw_i2cwin_lost(bw_i2cwin_t *w);

/* ---- the bus side ------------------------------------------------------------ */

/* START (or repeated START) with this target's address; host_reads: the
 * host reads (the target transmits). Ends the transfer before it. */
void bw_i2cwin_addressed(bw_i2cwin_t *w, int host_reads);
/* a byte written by the host */
void bw_i2cwin_received(bw_i2cwin_t *w, uint8_t byte);
/* the next byte the host reads */
uint8_t bw_i2cwin_transmit(bw_i2cwin_t *w);
/* STOP: a write's data is applied */
void bw_i2cwin_stop(bw_i2cwin_t *w);
/* a bus error, arbitration loss or overrun: the transfer is abandoned and
 * STATUS.lost set */
void bw_i2cwin_bus_error(bw_i2cwin_t *w);

/* The value of register reg as a read would return it now (0 for a
 * register the map does not have). */
uint16_t bw_i2cwin_register(const bw_i2cwin_t *w, uint32_t reg);

#endif
