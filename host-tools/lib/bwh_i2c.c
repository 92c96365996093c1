/* SPDX-License-Identifier: BSD-2-Clause */
/* The host end of the I2C link (bwh_i2c.h). */
#define _POSIX_C_SOURCE 200809L
#include "bwh_i2c.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bw_crc32.h"
#include "bw_i2cmap.h"
#include "bwh_decode.h"
#include "bwh_error.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* the message of a failed transfer (a negative errno) */
static int bus_fail(const bwh_i2c_t *c, int e)
{
    e = -e;
    if (e == ENXIO || e == ENODEV || e == EREMOTEIO || e == EIO || e == ETIMEDOUT || e == EAGAIN)
        return bwh_fail("no answer from the device at 0x%02x on %s (NAK: %s)", c->addr,
                        c->bus_name, strerror(e));
    return bwh_fail("I2C transfer to 0x%02x on %s failed: %s", c->addr, c->bus_name, strerror(e));
}

static int rd_word(const bwh_i2c_t *c, uint8_t reg, uint32_t *v)
{
    uint16_t w = 0;
    int e = c->read_word(c->ctx, reg, &w);
    if (e) {
        bus_fail(c, e);
        return -1;
    }
    *v = w;
    return 0;
}

static int rd_u32(const bwh_i2c_t *c, uint8_t lo, uint32_t *v)
{
    uint32_t a, b;
    if (rd_word(c, lo, &a) || rd_word(c, (uint8_t)(lo + 1u), &b))
        return -1;
    *v = a | b << 16;
    return 0;
}

static int wr_byte(const bwh_i2c_t *c, uint8_t reg, uint8_t v)
{
    int e = c->write_byte(c->ctx, reg, v);
    if (e)
        bus_fail(c, e);
    return e ? -1 : 0;
}

static int wr_word(const bwh_i2c_t *c, uint8_t reg, uint16_t v)
{
    int e = c->write_word(c->ctx, reg, v);
    if (e)
        bus_fail(c, e);
    return e ? -1 : 0;
}

/* 1 when reg reads 0 within timeout seconds, 0 if not, -1 on a bus error */
static int wait_zero(const bwh_i2c_t *c, uint8_t reg, double timeout)
{
    double t_end = now_s() + timeout;
    for (;;) {
        uint32_t v;
        if (rd_word(c, reg, &v))
            return -1;
        if (v == 0)
            return 1;
        if (now_s() > t_end)
            return 0;
        nanosleep(&(struct timespec){0, 5000000}, NULL);
    }
}

static void logf_(const bwh_i2c_t *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void logf_(const bwh_i2c_t *c, const char *fmt, ...)
{
    if (!c->log)
        return;
    char line[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    c->log(c->ctx, line);
}

/* Reads page p into buf; *len and *crc as served. */
static int read_page(const bwh_i2c_t *c, unsigned p, unsigned pages, unsigned psize, uint8_t *buf,
                     unsigned *len, uint32_t *crc)
{
    uint32_t pnum, plen;
    if (pages > 255u && wr_byte(c, BW_I2C_PAGE_HI, (uint8_t)(p >> 8)))
        return -1;
    if (wr_byte(c, BW_I2C_PAGE, (uint8_t)p) || rd_word(c, BW_I2C_PNUM, &pnum))
        return -1;
    if (pnum != p)
        return bwh_fail("page %u: the window shows page %u", p, pnum);
    if (rd_word(c, BW_I2C_PLEN, &plen))
        return -1;
    if (plen < 1 || plen > psize)
        return bwh_fail("page %u: length %u out of range", p, plen);
    if (rd_u32(c, BW_I2C_PCRC_LO, crc))
        return -1;
    for (unsigned k = 0; 2 * k < plen; k++) {
        uint32_t w;
        if (rd_word(c, (uint8_t)(BW_I2C_DATA + k), &w))
            return -1;
        buf[2 * k] = (uint8_t)w;
        if (2 * k + 1 < plen)
            buf[2 * k + 1] = (uint8_t)(w >> 8);
    }
    *len = plen;
    return 0;
}

/* MAGIC, VERSION and STATUS; the page size */
static int check_device(const bwh_i2c_t *c, unsigned *psize)
{
    uint32_t magic, version, status;
    if (rd_word(c, BW_I2C_MAGIC, &magic))
        return -1;
    if (magic != BW_I2C_MAGIC_VALUE)
        return bwh_fail("device at 0x%02x is not a brdfwave co-processor (MAGIC 0x%04x)", c->addr,
                        magic);
    if (rd_word(c, BW_I2C_VERSION, &version))
        return -1;
    *psize = version >> 8;
    if ((version & 0xFFu) != BW_I2C_MAP_VERSION || *psize < 2 || *psize > 32 || *psize % 2)
        return bwh_fail("unsupported register map (VERSION 0x%04x)", version);
    if (rd_word(c, BW_I2C_STATUS, &status))
        return -1;
    if (!(status & BW_I2C_ST_READY)) {
        uint32_t code = 0;
        if ((status & BW_I2C_ST_ERROR) && rd_word(c, BW_I2C_ERRCODE, &code) == 0)
            return bwh_fail("no payload offered (STATUS 0x%02x): the last job failed with "
                            "status %d",
                            status, (int)(int16_t)code);
        return bwh_fail("no payload offered (STATUS 0x%02x)", status);
    }
    return 0;
}

/* The pages of the payload that *pt lacks into pt->payload, each verified.
 * With keep, a page that never verifies is left missing and the others are
 * read; a transfer that fails ends the read (what arrived stays in *pt). */
static int read_pages(const bwh_i2c_t *c, bwh_partial_t *pt, unsigned retries, int keep,
                      unsigned *bad)
{
    unsigned pages = pt->parts, psize = pt->unit;
    int rc = 0;
    for (unsigned pg = 1; pg <= pages; pg++) {
        if (pt->have[pg - 1u])
            continue;
        unsigned want = pg < pages ? psize : (unsigned)(pt->len - (size_t)psize * (pages - 1u));
        uint8_t *dst = pt->payload + (size_t)(pg - 1u) * psize;
        for (unsigned attempt = 0;; attempt++) {
            if (c->stop && c->stop(c->ctx))
                return BWH_I2C_STOPPED;
            unsigned got = 0;
            uint32_t pcrc = 0;
            if (read_page(c, pg, pages, psize, dst, &got, &pcrc))
                return -1;
            if (got == want && bw_crc32(dst, got) == pcrc) {
                pt->have[pg - 1u] = 1;
                break;
            }
            memset(dst, 0, want);
            ++*bad;
            if (attempt == retries) {
                rc = bwh_fail("payload %u: page %u failed its CRC-32 %u times; payload not "
                              "acknowledged",
                              pt->id, pg, retries + 1);
                if (!keep)
                    return rc;
                logf_(c, "payload %u: page %u failed its CRC-32 %u times, left missing", pt->id,
                      pg, retries + 1);
                break;
            }
            logf_(c, "payload %u: page %u failed its CRC-32, asking again (%u/%u)", pt->id, pg,
                  attempt + 1, retries);
            if (wr_word(c, BW_I2C_RETRY, (uint16_t)pg))
                return -1;
            int z = wait_zero(c, BW_I2C_RETRY, 1.0);
            if (z < 0)
                return -1;
            if (z == 0)
                return bwh_fail("payload %u: the device did not answer RETRY of page %u",
                                pt->id, pg);
        }
    }
    if (rc != 0) { /* the message of the last page left missing, with the count */
        char why[300];
        snprintf(why, sizeof why, "%s", bwh_last_error());
        rc = bwh_fail("%s (%u of %u pages missing)", why, bwh_partial_missing(pt), pages);
    }
    return rc;
}

/* Reads the offered payload into *pt (keep: as bwh_i2c_read_partial). */
static int read_offered(const bwh_i2c_t *c, unsigned retries, size_t max_samples, int keep,
                        bwh_partial_t *pt, bwh_i2c_payload_t *out)
{
    memset(out, 0, sizeof *out);
    unsigned psize = 0;
    uint32_t id, len, pages, crc;
    if (check_device(c, &psize) != 0)
        return -1;
    if (rd_u32(c, BW_I2C_ID_LO, &id) || rd_u32(c, BW_I2C_LEN_LO, &len) ||
        rd_word(c, BW_I2C_PAGES, &pages) || rd_u32(c, BW_I2C_CRC_LO, &crc))
        return -1;
    if (len == 0 || pages != (len + psize - 1) / psize)
        return bwh_fail("payload %u: length %u does not match %u pages", id, len, pages);
    if (pt->payload && (pt->id != id || pt->len != len || pt->crc != crc || pt->unit != psize)) {
        logf_(c, "the device offers payload %u (%u bytes, CRC-32 %08x), not payload %u "
                 "(%zu bytes, %08x) that arrived in part: reading it whole",
              id, len, crc, pt->id, pt->len, pt->crc);
        bwh_partial_free(pt);
    }
    if (!pt->payload && bwh_partial_init(pt, id, crc, len, psize) != 0)
        return -1;
    unsigned bad = 0;
    int rc = read_pages(c, pt, retries, keep, &bad);
    out->bad_pages = bad;
    (void)c->write_byte(c->ctx, BW_I2C_PAGE, 0);
    if (rc == BWH_I2C_STOPPED)
        return rc;
    if (rc != 0 || bwh_partial_missing(pt))
        return keep && bwh_partial_missing(pt) < pt->parts ? 1 : -1;
    if (bw_crc32(pt->payload, len) != crc) {
        /* every page verified, the whole does not: read it all again */
        rc = bwh_fail("payload %u: CRC-32 0x%08x, the device announced 0x%08x; payload not "
                      "acknowledged",
                      id, bw_crc32(pt->payload, len), crc);
        bwh_partial_free(pt);
        return -1;
    }
    bw_header_t h;
    if (bwh_payload_check(pt->payload, len, max_samples, &h) != 0) {
        char why[400];
        snprintf(why, sizeof why, "%s", bwh_last_error());
        bwh_partial_free(pt);
        return bwh_fail("payload %u does not decode: %s; payload not acknowledged", id, why);
    }
    out->id = id;
    out->payload = pt->payload;
    out->len = len;
    free(pt->have);
    memset(pt, 0, sizeof *pt);
    return 0;
}

int bwh_i2c_read_payload(const bwh_i2c_t *c, unsigned retries, size_t max_samples,
                         bwh_i2c_payload_t *out)
{
    bwh_partial_t pt;
    memset(&pt, 0, sizeof pt);
    int rc = read_offered(c, retries, max_samples, 0, &pt, out);
    bwh_partial_free(&pt);
    return rc;
}

int bwh_i2c_read_partial(const bwh_i2c_t *c, unsigned retries, size_t max_samples,
                         bwh_partial_t *part, bwh_i2c_payload_t *out)
{
    return read_offered(c, retries, max_samples, 1, part, out);
}

int bwh_i2c_acknowledge(const bwh_i2c_t *c, uint32_t id, double timeout_s)
{
    if (wr_word(c, BW_I2C_ACK_LO, (uint16_t)id) ||
        wr_word(c, BW_I2C_ACK_HI, (uint16_t)(id >> 16)) || wr_byte(c, BW_I2C_CMD, BW_I2C_CMD_ACK))
        return -1;
    int z = wait_zero(c, BW_I2C_CMD, timeout_s);
    if (z <= 0)
        return z;
    uint32_t st, now_id;
    if (rd_word(c, BW_I2C_STATUS, &st) || rd_u32(c, BW_I2C_ID_LO, &now_id))
        return -1;
    if (st & BW_I2C_ST_NAK)
        return 0;
    return !(st & BW_I2C_ST_READY) || now_id != id;
}
