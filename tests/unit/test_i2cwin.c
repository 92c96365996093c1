/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The I2C register window (firmware/link/bw_i2cwin.c) driven over a
 * simulated SMBus by the host's I2C client (host-tools/lib/bwh_i2c.c), as
 * `brdfwave acquire` and the Python service read it: pages and their CRCs,
 * a page corrupted on the bus and read again, one that never verifies, the
 * ACK that releases the payload (and reaches the application as an ACK
 * frame), a NAK, a device that does not answer, FRAMES, errors and faults,
 * and pages beyond 255.
 */
#define _DEFAULT_SOURCE
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bw_crc32.h"
#include "bw_frame.h"
#include "bw_i2cwin.h"
#include "bwh_i2c.h"
#include "bwhost.h"
#include "test_rng.h"

/* ---- the device: a window, the application's side of it -------------------- */

static bw_i2cwin_t win;
static uint8_t app_in[4096]; /* bytes the window handed the application */
static size_t app_len;
static int drdy;

static void to_app(void *ctx, const uint8_t *b, size_t n)
{
    (void)ctx;
    assert_true(app_len + n <= sizeof app_in);
    memcpy(app_in + app_len, b, n);
    app_len += n;
}

static void ready(void *ctx, int offered)
{
    (void)ctx;
    drdy = offered;
}

static const bw_i2cwin_ops_t ops = {to_app, ready, NULL};

/* ---- the bus: SMBus transfers as a target controller reports them ---------- */

static struct {
    int absent;            /* the device does not answer (NAK) */
    unsigned corrupt_page; /* DATA0 of this page reads flipped ... */
    int corrupt_times;     /* ... this many times (-1: always) */
    unsigned transfers;
} bus;

static int read_word(void *ctx, uint8_t reg, uint16_t *v)
{
    bw_i2cwin_t *w = ctx;
    if (bus.absent)
        return -ENXIO;
    bus.transfers++;
    bw_i2cwin_addressed(w, 0);
    bw_i2cwin_received(w, reg);
    bw_i2cwin_addressed(w, 1); /* repeated START */
    uint8_t lo = bw_i2cwin_transmit(w), hi = bw_i2cwin_transmit(w);
    bw_i2cwin_stop(w);
    *v = (uint16_t)(lo | hi << 8);
    if (reg == BW_I2C_DATA && bus.corrupt_page && w->page == bus.corrupt_page &&
        bus.corrupt_times != 0) {
        *v ^= 0x5A;
        if (bus.corrupt_times > 0)
            bus.corrupt_times--;
    }
    return 0;
}

static int write_bytes(bw_i2cwin_t *w, uint8_t reg, const uint8_t *b, size_t n)
{
    if (bus.absent)
        return -ENXIO;
    bus.transfers++;
    bw_i2cwin_addressed(w, 0);
    bw_i2cwin_received(w, reg);
    for (size_t i = 0; i < n; i++)
        bw_i2cwin_received(w, b[i]);
    bw_i2cwin_stop(w);
    return 0;
}

static int write_byte(void *ctx, uint8_t reg, uint8_t v) { return write_bytes(ctx, reg, &v, 1); }

static int write_word(void *ctx, uint8_t reg, uint16_t v)
{
    uint8_t b[2] = {(uint8_t)v, (uint8_t)(v >> 8)};
    return write_bytes(ctx, reg, b, 2);
}

static char last_log[256];
static unsigned logs;

static void log_line(void *ctx, const char *line)
{
    (void)ctx;
    snprintf(last_log, sizeof last_log, "%s", line);
    logs++;
}

static const bwh_i2c_t host = {read_word, write_byte, write_word, log_line, NULL, &win,
                               BW_I2C_ADDR, "the test bus"};

static uint16_t reg(uint8_t r)
{
    uint16_t v = 0;
    assert_int_equal(read_word(&win, r, &v), 0);
    return v;
}

/* ---- payloads ---------------------------------------------------------------- */

/* a real payload: n random 16-bit samples as spectra of 64 bands, lossless */
static uint8_t *make_payload(size_t n, size_t *len)
{
    static uint64_t rng = 0x9e3779b97f4a7c15ull;
    int32_t *x = malloc(n * sizeof *x);
    assert_non_null(x);
    for (size_t i = 0; i < n; i++)
        x[i] = (int32_t)(test_uniform(&rng) * 65536.0);
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, (uint32_t)(n / 64), 64), BW_OK);
    bwh_encode_opts_t o = {.mode = BW_MODE_LOSSLESS, .basis = BW_BASIS_53};
    uint8_t *p;
    assert_int_equal(bwh_encode_i32(&d, x, &o, 1.0f, 0.0f, &p, len), 0);
    free(x);
    return p;
}

static uint8_t *payload;
static size_t payload_len;

static int setup(void **state)
{
    (void)state;
    bw_i2cwin_init(&win, &ops);
    memset(&bus, 0, sizeof bus);
    app_len = 0;
    drdy = 0;
    logs = 0;
    payload = make_payload(64 * 40, &payload_len); /* a few pages */
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(payload);
    return 0;
}

static void offer(uint32_t id, const uint8_t *p, size_t n)
{
    bw_i2cwin_offer(&win, id, p, (uint32_t)n, bw_crc32(p, n));
}

/* ---- cases ---------------------------------------------------------------------- */

static void an_empty_window_shows_the_map_and_offers_nothing(void **state)
{
    (void)state;
    assert_int_equal(reg(BW_I2C_MAGIC), BW_I2C_MAGIC_VALUE);
    assert_int_equal(reg(BW_I2C_VERSION), BW_I2C_PAGE_SIZE << 8 | BW_I2C_MAP_VERSION);
    assert_int_equal(reg(BW_I2C_STATUS), 0);
    assert_int_equal(reg(BW_I2C_PNUM), 0);
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), -1);
    assert_string_equal(bwh_last_error(), "no payload offered (STATUS 0x00)");
    assert_int_equal(reg(0x99), 0); /* unknown registers read 0 */
}

static void the_host_reads_an_offered_payload_page_by_page(void **state)
{
    (void)state;
    offer(7, payload, payload_len);
    assert_int_equal(drdy, 1);
    uint32_t pages = (uint32_t)((payload_len + 31) / 32);
    assert_int_equal(reg(BW_I2C_STATUS), BW_I2C_ST_READY);
    assert_int_equal(reg(BW_I2C_ID_LO) | (uint32_t)reg(BW_I2C_ID_HI) << 16, 7);
    assert_int_equal(reg(BW_I2C_LEN_LO) | (uint32_t)reg(BW_I2C_LEN_HI) << 16, payload_len);
    assert_int_equal(reg(BW_I2C_PAGES), pages);
    assert_int_equal(reg(BW_I2C_CRC_LO) | (uint32_t)reg(BW_I2C_CRC_HI) << 16,
                     bw_crc32(payload, payload_len));
    /* the last page: its length, CRC, and 0xFF past its end */
    assert_int_equal(write_byte(&win, BW_I2C_PAGE, (uint8_t)pages), 0);
    uint32_t plen = (uint32_t)(payload_len - 32 * (pages - 1));
    const uint8_t *last = payload + 32 * (pages - 1);
    assert_int_equal(reg(BW_I2C_PNUM), pages);
    assert_int_equal(reg(BW_I2C_PLEN), plen);
    assert_int_equal(reg(BW_I2C_PCRC_LO) | (uint32_t)reg(BW_I2C_PCRC_HI) << 16,
                     bw_crc32(last, plen));
    for (unsigned k = 0; k < 16; k++) {
        unsigned lo = 2 * k < plen ? last[2 * k] : 0xFF;
        unsigned hi = 2 * k + 1 < plen ? last[2 * k + 1] : 0xFF;
        assert_int_equal(reg((uint8_t)(BW_I2C_DATA + k)), lo | hi << 8);
    }
    /* the whole of it through the client */
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), 0);
    assert_int_equal(got.id, 7);
    assert_int_equal(got.len, payload_len);
    assert_memory_equal(got.payload, payload, payload_len);
    assert_int_equal(got.bad_pages, 0);
    assert_int_equal(reg(BW_I2C_PAGE), 0); /* the client deselects the page */
    free(got.payload);
}

static void a_page_corrupted_on_the_bus_is_read_again(void **state)
{
    (void)state;
    offer(9, payload, payload_len);
    bus.corrupt_page = 3;
    bus.corrupt_times = 1;
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), 0);
    assert_int_equal(got.bad_pages, 1);
    assert_int_equal(logs, 1);
    assert_string_equal(last_log, "payload 9: page 3 failed its CRC-32, asking again (1/3)");
    assert_memory_equal(got.payload, payload, payload_len);
    free(got.payload);
}

static void a_page_that_never_verifies_is_refused(void **state)
{
    (void)state;
    offer(10, payload, payload_len);
    bus.corrupt_page = 2;
    bus.corrupt_times = -1;
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 2, 0, &got), -1);
    assert_string_equal(bwh_last_error(),
                        "payload 10: page 2 failed its CRC-32 3 times; payload not acknowledged");
    assert_null(got.payload);
    assert_int_equal(reg(BW_I2C_STATUS), BW_I2C_ST_READY); /* still offered */
}

/* The reads that keep what arrives: a page that never verifies is left
 * missing, the rest read; the record is stored and loaded again; a later
 * read of the same offered payload reads only the missing page (counted on
 * the bus) and completes it; a record of another payload is replaced. */
static void a_page_that_never_verifies_is_kept_missing_and_read_later(void **state)
{
    (void)state;
    offer(11, payload, payload_len);
    uint32_t pages = (uint32_t)((payload_len + 31) / 32);
    bus.corrupt_page = 2;
    bus.corrupt_times = -1;
    bwh_partial_t part;
    memset(&part, 0, sizeof part);
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_partial(&host, 1, 0, &part, &got), 1);
    assert_null(got.payload);
    char want[200];
    snprintf(want, sizeof want,
             "payload 11: page 2 failed its CRC-32 2 times; payload not acknowledged "
             "(1 of %u pages missing)", pages);
    assert_string_equal(bwh_last_error(), want);
    assert_int_equal(part.id, 11);
    assert_int_equal(part.len, payload_len);
    assert_int_equal(part.unit, 32);
    assert_int_equal(bwh_partial_missing(&part), 1);
    assert_int_equal(part.have[1], 0);
    for (uint32_t k = 0; k < pages; k++) /* every page but 2 as offered, 2 zero */
        for (size_t i = 32u * k; i < payload_len && i < 32u * (k + 1u); i++)
            assert_int_equal(part.payload[i], k == 1 ? 0 : payload[i]);
    /* stored and loaded again as it was */
    char dir[] = "/tmp/bw-part-XXXXXX", path[4096];
    assert_non_null(mkdtemp(dir));
    assert_int_equal(bwh_partial_store(dir, &part, path, sizeof path), 0);
    char name[4200];
    snprintf(name, sizeof name, "%s/payload-11-%08x.part", dir, bw_crc32(payload, payload_len));
    assert_string_equal(path, name);
    bwh_partial_t back;
    strcat(name, ".bwv"); /* either file names the record */
    assert_int_equal(bwh_partial_load(name, &back), 0);
    assert_int_equal(back.id, part.id);
    assert_int_equal(back.crc, part.crc);
    assert_int_equal(back.len, part.len);
    assert_int_equal(back.parts, part.parts);
    assert_memory_equal(back.have, part.have, part.parts);
    assert_memory_equal(back.payload, part.payload, part.len);
    bwh_partial_free(&part);
    /* later, the bus healed: only page 2 is read (its window: a few dozen
     * transfers, not the whole payload's) */
    bus.corrupt_times = 0;
    unsigned before = bus.transfers;
    assert_int_equal(bwh_i2c_read_partial(&host, 1, 0, &back, &got), 0);
    assert_true(bus.transfers - before < 40u);
    assert_int_equal(got.id, 11);
    assert_int_equal(got.len, payload_len);
    assert_memory_equal(got.payload, payload, payload_len);
    assert_null(back.payload);
    free(got.payload);
    bwh_partial_remove(path);
    FILE *f = fopen(path, "r");
    assert_null(f);
    assert_int_equal(rmdir(dir), 0); /* both files gone */
    /* a record of another payload: the offered one is read whole */
    assert_int_equal(bwh_partial_init(&back, 99, 1234u, payload_len, 32), 0);
    assert_int_equal(bwh_i2c_read_partial(&host, 1, 0, &back, &got), 0);
    assert_memory_equal(got.payload, payload, payload_len);
    assert_non_null(strstr(last_log, "not payload 99"));
    free(got.payload);
}

/* A record that is not one, or whose bytes do not match it, is refused
 * with a message that says so. */
static void a_malformed_incomplete_record_is_refused(void **state)
{
    (void)state;
    char dir[] = "/tmp/bw-part-XXXXXX", path[4200];
    assert_non_null(mkdtemp(dir));
    const char *bad[] = {
        "not a record\n",
        "brdfwave incomplete payload 1\nid 3\nlength 100\ncrc 00000001\nunit 32\nmissing 4\n",
        "brdfwave incomplete payload 1\nid 3\nlength 100\ncrc 00000001\nunit 32\nmissing 1 1\n",
        "brdfwave incomplete payload 1\nid 3\nlength 99\ncrc 00000001\nunit 32\nmissing 1\n",
    };
    const char *why[] = {"is not a record", "malformed list", "malformed list", "holds 100 bytes"};
    uint8_t bytes[100] = {0};
    snprintf(path, sizeof path, "%s/x.part.bwv", dir);
    assert_int_equal(bwh_write_file(path, bytes, sizeof bytes), 0);
    snprintf(path, sizeof path, "%s/x.part", dir);
    for (unsigned k = 0; k < 4; k++) {
        assert_int_equal(bwh_write_file(path, bad[k], strlen(bad[k])), 0);
        bwh_partial_t p;
        assert_int_equal(bwh_partial_load(path, &p), -1);
        assert_null(p.payload);
        if (!strstr(bwh_last_error(), why[k]))
            fail_msg("case %u: %s", k, bwh_last_error());
    }
    bwh_partial_remove(path);
    assert_int_equal(rmdir(dir), 0);
}

static void a_payload_that_does_not_decode_is_refused(void **state)
{
    (void)state;
    uint8_t *bad = malloc(payload_len);
    assert_non_null(bad);
    memcpy(bad, payload, payload_len);
    memcpy(bad, "XXXX", 4); /* the page and payload CRCs cover it: only the header check sees it */
    offer(12, bad, payload_len);
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), -1);
    assert_non_null(strstr(bwh_last_error(), "payload 12 does not decode"));
    assert_non_null(strstr(bwh_last_error(), "not acknowledged"));
    bw_i2cwin_offer(&win, 0, NULL, 0, 0);
    free(bad);
}

static void the_ack_releases_the_payload_and_the_application_hears_it(void **state)
{
    (void)state;
    offer(0x00012345u, payload, payload_len);
    assert_int_equal(bwh_i2c_acknowledge(&host, 0x00012345u, 1.0), 1);
    assert_int_equal(drdy, 0);
    assert_int_equal(reg(BW_I2C_STATUS), 0);
    assert_int_equal(reg(BW_I2C_ID_LO), 0);
    /* the application's frame stream holds the ACK of that id */
    bw_frame_rx_t rx;
    bw_frame_t f;
    bool got = false;
    bw_frame_rx_init(&rx);
    size_t used = bw_frame_rx_feed(&rx, app_in, app_len, &f, &got);
    assert_true(got);
    assert_int_equal(used, app_len);
    assert_int_equal(f.type, BW_FT_ACK);
    assert_int_equal(f.len, 4);
    assert_int_equal(bw_get_u32(f.data), 0x00012345u);
}

static void an_ack_for_another_payload_is_a_nak(void **state)
{
    (void)state;
    offer(5, payload, payload_len);
    assert_int_equal(bwh_i2c_acknowledge(&host, 6, 1.0), 0);
    assert_int_equal(reg(BW_I2C_STATUS), BW_I2C_ST_READY | BW_I2C_ST_NAK);
    assert_int_equal(app_len, 0);
    assert_int_equal(drdy, 1);
    assert_int_equal(write_byte(&win, BW_I2C_CMD, BW_I2C_CMD_CLEAR), 0);
    assert_int_equal(reg(BW_I2C_STATUS), BW_I2C_ST_READY);
}

static void a_device_that_does_not_answer_is_a_clear_error(void **state)
{
    (void)state;
    offer(8, payload, payload_len);
    bus.absent = 1;
    bwh_i2c_t other = host;
    other.addr = 0x43;
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&other, 3, 0, &got), -1);
    assert_non_null(strstr(bwh_last_error(), "no answer from the device at 0x43 on the test bus"));
    assert_non_null(strstr(bwh_last_error(), "NAK"));
    assert_int_equal(bwh_i2c_acknowledge(&other, 8, 0.05), -1);
}

static void frames_written_to_frames_reach_the_application(void **state)
{
    (void)state;
    uint8_t f[BW_FRAME_MAX];
    size_t n = bw_frame_pack(f, BW_FT_QUIT, 0, NULL, 0);
    assert_int_equal(write_bytes(&win, BW_I2C_FRAMES, f, n), 0);
    assert_int_equal(app_len, n);
    assert_memory_equal(app_in, f, n);
}

static void a_failed_job_and_a_fault_show_in_status(void **state)
{
    (void)state;
    bw_i2cwin_job_failed(&win, -7);
    bw_i2cwin_set_fault(&win, 0x80000003u);
    assert_int_equal(reg(BW_I2C_STATUS), BW_I2C_ST_ERROR | BW_I2C_ST_FAULT);
    assert_int_equal((int16_t)reg(BW_I2C_ERRCODE), -7);
    assert_int_equal(reg(BW_I2C_FAULT_LO) | (uint32_t)reg(BW_I2C_FAULT_HI) << 16, 0x80000003u);
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), -1);
    assert_string_equal(bwh_last_error(),
                        "no payload offered (STATUS 0x06): the last job failed with status -7");
    bw_i2cwin_bus_error(&win);
    assert_true(reg(BW_I2C_STATUS) & BW_I2C_ST_LOST);
    assert_int_equal(write_byte(&win, BW_I2C_CMD, BW_I2C_CMD_CLEAR), 0);
    assert_int_equal(reg(BW_I2C_STATUS), 0);
    assert_int_equal(reg(BW_I2C_FAULT_LO), 0);
}

static void withdrawing_the_offer_empties_the_window(void **state)
{
    (void)state;
    offer(3, payload, payload_len);
    assert_int_equal(write_byte(&win, BW_I2C_PAGE, 1), 0);
    assert_int_equal(reg(BW_I2C_PNUM), 1);
    bw_i2cwin_offer(&win, 0, NULL, 0, 0);
    assert_int_equal(drdy, 0);
    assert_int_equal(reg(BW_I2C_STATUS), 0);
    assert_int_equal(reg(BW_I2C_PNUM), 0);
    assert_int_equal(reg(BW_I2C_PLEN), 0);
    assert_int_equal(reg(BW_I2C_DATA), 0);
    assert_int_equal(reg(BW_I2C_PAGES), 0);
}

static void a_block_read_returns_the_page_with_its_length(void **state)
{
    (void)state;
    offer(4, payload, payload_len);
    assert_int_equal(write_byte(&win, BW_I2C_PAGE, 2), 0);
    bw_i2cwin_addressed(&win, 0);
    bw_i2cwin_received(&win, BW_I2C_BLOCK);
    bw_i2cwin_addressed(&win, 1);
    uint8_t n = bw_i2cwin_transmit(&win), b[32];
    for (unsigned i = 0; i < n; i++)
        b[i] = bw_i2cwin_transmit(&win);
    bw_i2cwin_stop(&win);
    assert_int_equal(n, 32);
    assert_memory_equal(b, payload + 32, 32);
}

static void payloads_of_more_than_255_pages_take_page_hi(void **state)
{
    (void)state;
    size_t big_len;
    uint8_t *big = make_payload(64 * 160, &big_len); /* about 20 KiB: over 255 pages */
    assert_true(big_len > 255u * 32u);
    offer(11, big, big_len);
    bwh_i2c_payload_t got;
    assert_int_equal(bwh_i2c_read_payload(&host, 3, 0, &got), 0);
    assert_int_equal(got.len, big_len);
    assert_memory_equal(got.payload, big, big_len);
    free(got.payload);
    free(big);
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, setup, teardown)
    const struct CMUnitTest tests[] = {
        T(an_empty_window_shows_the_map_and_offers_nothing),
        T(the_host_reads_an_offered_payload_page_by_page),
        T(a_page_corrupted_on_the_bus_is_read_again),
        T(a_page_that_never_verifies_is_refused),
        T(a_page_that_never_verifies_is_kept_missing_and_read_later),
        T(a_malformed_incomplete_record_is_refused),
        T(a_payload_that_does_not_decode_is_refused),
        T(the_ack_releases_the_payload_and_the_application_hears_it),
        T(an_ack_for_another_payload_is_a_nak),
        T(a_device_that_does_not_answer_is_a_clear_error),
        T(frames_written_to_frames_reach_the_application),
        T(a_failed_job_and_a_fault_show_in_status),
        T(withdrawing_the_offer_empties_the_window),
        T(a_block_read_returns_the_page_with_its_length),
        T(payloads_of_more_than_255_pages_take_page_hi),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
