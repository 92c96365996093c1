/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Hardware abstraction of the on-device application. Each board backend
 * fills a bw_hal_t; an operation a board does not have is NULL and its
 * wrapper returns -BW_HAL_ENOSYS. Success is >= 0, errors are < 0.
 */
#ifndef BW_HAL_H
#define BW_HAL_H

#include <stddef.h>
#include <stdint.h>

#define BW_HAL_ENOSYS 38
#define BW_HAL_EIO 5
#define BW_HAL_ETIMEDOUT 110

typedef struct {
    /* free-running count of CPU instructions (cycles on real hardware) */
    uint64_t (*counter)(void);
    /* host link: write all of buf, or read up to cap bytes (0 = none yet) */
    int (*link_write)(const uint8_t *buf, size_t len);
    int (*link_read)(uint8_t *buf, size_t cap);
    /* data-ready line towards the host */
    int (*drdy_set)(int level);
    /* select the measurement to read (a file on the emulated board) */
    int (*sensor_open)(const char *source);
    /* next block of input samples; returns samples read, 0 at the end */
    int (*sensor_read)(int32_t *samples, size_t cap);
    /* a fatal fault: record it for the host and stop */
    void (*fault)(uint32_t code);
    /* what the application keeps for the host, for a board that also
     * serves it on a second link (the I2C register window of docs/I2C.md,
     * firmware/link/bw_i2cwin.h): status 0, payload[len] under id, valid
     * until the next call (len 0: nothing, the application is about to
     * reuse the buffer); status < 0: the job failed with that status */
    int (*offer)(uint32_t id, const uint8_t *payload, size_t len, int32_t status);
} bw_hal_t;

/* The board's operations (one backend is linked into each image). */
const bw_hal_t *bw_board(void);

static inline uint64_t bw_hal_counter(const bw_hal_t *h) { return h->counter ? h->counter() : 0u; }
static inline int bw_hal_link_write(const bw_hal_t *h, const uint8_t *b, size_t n)
{
    return h->link_write ? h->link_write(b, n) : -BW_HAL_ENOSYS;
}
static inline int bw_hal_link_read(const bw_hal_t *h, uint8_t *b, size_t cap)
{
    return h->link_read ? h->link_read(b, cap) : -BW_HAL_ENOSYS;
}
static inline int bw_hal_drdy_set(const bw_hal_t *h, int level)
{
    return h->drdy_set ? h->drdy_set(level) : -BW_HAL_ENOSYS;
}
static inline int bw_hal_sensor_open(const bw_hal_t *h, const char *source)
{
    return h->sensor_open ? h->sensor_open(source) : -BW_HAL_ENOSYS;
}
static inline int bw_hal_sensor_read(const bw_hal_t *h, int32_t *s, size_t cap)
{
    return h->sensor_read ? h->sensor_read(s, cap) : -BW_HAL_ENOSYS;
}
static inline int bw_hal_offer(const bw_hal_t *h, uint32_t id, const uint8_t *payload, size_t len,
                               int32_t status)
{
    return h->offer ? h->offer(id, payload, len, status) : -BW_HAL_ENOSYS;
}

#endif
