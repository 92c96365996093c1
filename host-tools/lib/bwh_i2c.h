/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The host end of the I2C link (docs/I2C.md): reading the payload the
 * co-processor offers in its register window, page by page, with a CRC-32
 * check of every page (a bad page is asked for again, RETRY), of the whole
 * payload and of its header, and acknowledging it once the caller has
 * stored it. `brdfwave acquire` runs it over i2c-dev, the Python service
 * (python3 -m brdfwave.acquire) over smbus2 through ctypes: both give it the
 * three SMBus transfers it needs.
 */
#ifndef BWH_I2C_H
#define BWH_I2C_H

#include <stddef.h>
#include <stdint.h>

#include "bwh_store.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    /* SMBus transfers to the device: 0, or a negative errno (-ENXIO,
     * -EREMOTEIO, ...: the device did not answer) */
    int (*read_word)(void *ctx, uint8_t reg, uint16_t *value);
    int (*write_byte)(void *ctx, uint8_t reg, uint8_t value);
    int (*write_word)(void *ctx, uint8_t reg, uint16_t value);
    /* optional: one line for the log (a page asked for again) */
    void (*log)(void *ctx, const char *line);
    /* optional: nonzero when the caller wants to stop (a signal arrived);
     * asked before every page read */
    int (*stop)(void *ctx);
    void *ctx;
    unsigned addr;        /* the device's address and */
    const char *bus_name; /* its bus ("/dev/i2c-1"), for messages */
} bwh_i2c_t;

/* the payload read: allocated (free() it) */
typedef struct {
    uint32_t id;
    uint8_t *payload;
    size_t len;
    unsigned bad_pages; /* page reads that failed their CRC-32 */
} bwh_i2c_payload_t;

#define BWH_I2C_STOPPED (-2)

/* Reads and verifies the offered payload: MAGIC and VERSION, ID, LEN, PAGES
 * and CRC, every page (up to `retries` more reads of a page that fails its
 * CRC-32, each after RETRY), the payload's CRC-32, header and a full decode
 * (bwh_payload_check, max_samples 0: the default). PAGE is set back to 0 in
 * any case. 0; -1 (bwh_last_error(): no payload offered, a device that does
 * not answer, a page that never verifies, a payload that does not decode;
 * nothing to acknowledge); BWH_I2C_STOPPED when stop() asked for it. */
int bwh_i2c_read_payload(const bwh_i2c_t *c, unsigned retries, size_t max_samples,
                         bwh_i2c_payload_t *out);

/* As bwh_i2c_read_payload, keeping what arrives: a page that never
 * verifies is left missing and the other pages are read, a transfer that
 * fails ends the read; then 1, the payload in part in *part (its pages in
 * part->have, units of the page size) and bwh_last_error() saying why. Given
 * a *part of the payload offered now (the same id, length, CRC-32 and page
 * size: the last call's, or a record of bwh_partial_load), only the pages
 * it lacks are read, so a payload comes together over several calls; a
 * *part of another payload is replaced. 0 once whole and verified (out as
 * bwh_i2c_read_payload; *part emptied: all zero); -1 and
 * BWH_I2C_STOPPED as there (*part keeps what it held). *part must start
 * all zero or loaded; bwh_partial_free it. */
int bwh_i2c_read_partial(const bwh_i2c_t *c, unsigned retries, size_t max_samples,
                         bwh_partial_t *part, bwh_i2c_payload_t *out);

/* Acknowledges payload id (ACK_LO, ACK_HI, CMD = ACK) and waits up to
 * timeout_s seconds for CMD to read 0. 1 when the device released it
 * (STATUS.ready clear, or another id offered), 0 when it did not confirm
 * (STATUS.nak, or no answer in time), -1 on a bus error (bwh_last_error()). */
int bwh_i2c_acknowledge(const bwh_i2c_t *c, uint32_t id, double timeout_s);

#ifdef __cplusplus
}
#endif

#endif
