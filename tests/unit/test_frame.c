/* SPDX-License-Identifier: BSD-2-Clause */
/* Link frames: packing, byte-at-a-time reception with resynchronisation,
 * and the job record. */
#include <setjmp.h>
#include <stdbool.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "bw_frame.h"

static bw_frame_rx_t rx;
static bw_frame_t got;

/* Feeds bytes; returns the number of frames completed. */
static int feed(const uint8_t *p, size_t n, bw_frame_t *last)
{
    int frames = 0;
    for (size_t i = 0; i < n; i++)
        if (bw_frame_rx_byte(&rx, p[i], &got)) {
            frames++;
            if (last)
                *last = got;
        }
    return frames;
}

static void packed_frames_are_received_intact_at_every_length(void **state)
{
    (void)state;
    static uint8_t buf[BW_FRAME_MAX], data[BW_FRAME_MAX_DATA];
    for (unsigned i = 0; i < sizeof data; i++)
        data[i] = (uint8_t)(i * 37u + 11u);
    for (uint16_t len = 0; len <= BW_FRAME_MAX_DATA; len += (len < 40 ? 1 : 97)) {
        bw_frame_rx_init(&rx);
        size_t n = bw_frame_pack(buf, BW_FT_DATA, (uint16_t)(len * 3u), data, len);
        assert_int_equal(n, BW_FRAME_OVERHEAD + len);
        bw_frame_t f;
        assert_int_equal(feed(buf, n, &f), 1);
        assert_int_equal(f.type, BW_FT_DATA);
        assert_int_equal(f.seq, (uint16_t)(len * 3u));
        assert_int_equal(f.len, len);
        assert_memory_equal(f.data, data, len);
    }
    assert_int_equal(bw_frame_pack(buf, BW_FT_DATA, 0, data, BW_FRAME_MAX_DATA + 1), 0);
}

static void receiver_resynchronises_after_noise_and_corrupted_frames(void **state)
{
    (void)state;
    uint8_t stream[4 * BW_FRAME_MAX];
    size_t n = 0;
    const uint8_t noise[] = {0x00, 0xB5, 0x00, 0xB5, 0xB5, 0x57, 0x11, 0x00};
    memcpy(stream, noise, sizeof noise); /* ends in a false header start */
    n += sizeof noise;
    uint8_t d1[5] = {1, 2, 3, 4, 5}, d2[3] = {9, 8, 7};
    size_t a = bw_frame_pack(stream + n, BW_FT_ACK, 1, d1, 5);
    stream[n + 10] ^= 0x01; /* corrupt the data of frame 1 */
    n += a;
    n += bw_frame_pack(stream + n, BW_FT_RESEND, 2, d2, 3);
    /* a truncated frame, then a good one */
    size_t t = bw_frame_pack(stream + n, BW_FT_END, 3, d1, 5);
    n += t - 3;
    n += bw_frame_pack(stream + n, BW_FT_END, 4, d2, 3);
    bw_frame_rx_init(&rx);
    int frames = 0;
    uint16_t seqs[4];
    for (size_t i = 0; i < n; i++)
        if (bw_frame_rx_byte(&rx, stream[i], &got))
            seqs[frames++] = got.seq;
    assert_int_equal(frames, 2);
    assert_int_equal(seqs[0], 2);
    assert_int_equal(seqs[1], 4);
    assert_true(rx.bad_crc >= 1);
}

static void a_header_with_an_impossible_length_is_skipped(void **state)
{
    (void)state;
    uint8_t bad[8] = {BW_FRAME_SYNC0, BW_FRAME_SYNC1, BW_FT_DATA, 0, 0, 0, 0xFF, 0xFF};
    uint8_t good[BW_FRAME_OVERHEAD];
    size_t g = bw_frame_pack(good, BW_FT_QUIT, 9, NULL, 0);
    bw_frame_rx_init(&rx);
    bw_frame_t f;
    assert_int_equal(feed(bad, sizeof bad, NULL), 0);
    assert_int_equal(feed(good, g, &f), 1);
    assert_int_equal(f.type, BW_FT_QUIT);
    assert_int_equal(f.seq, 9);
}

/* A false header that claims 40 data bytes swallows two real frames; when its
 * CRC fails, both are in the receiver's buffer. Both must come out without
 * waiting for another byte, and a feed stops at the end of the frame it
 * completes, leaving the rest to the caller. */
static void frames_buffered_behind_a_false_header_come_out_without_more_bytes(void **state)
{
    (void)state;
    uint8_t stream[64];
    uint8_t fake[8] = {BW_FRAME_SYNC0, BW_FRAME_SYNC1, BW_FT_DATA, 0, 0, 0, 40, 0};
    size_t n = 0;
    memcpy(stream, fake, sizeof fake);
    n += sizeof fake;
    n += bw_frame_pack(stream + n, BW_FT_ACK, 1, NULL, 0);
    n += bw_frame_pack(stream + n, BW_FT_QUIT, 2, NULL, 0);
    memset(stream + n, 0x11, BW_FRAME_OVERHEAD + 40 - n); /* the false frame's length */
    n = BW_FRAME_OVERHEAD + 40;
    n += bw_frame_pack(stream + n, BW_FT_END, 3, NULL, 0);
    bw_frame_rx_init(&rx);
    bool have;
    bw_frame_t f;
    size_t used = bw_frame_rx_feed(&rx, stream, n, &f, &have);
    assert_true(have);
    assert_int_equal(f.type, BW_FT_ACK);
    assert_int_equal(used, BW_FRAME_OVERHEAD + 40); /* where the false frame ended */
    assert_int_equal(bw_frame_rx_feed(&rx, stream + used, 0, &f, &have), 0);
    assert_true(have); /* from the buffer alone */
    assert_int_equal(f.type, BW_FT_QUIT);
    assert_int_equal(bw_frame_rx_feed(&rx, stream + used, 0, &f, &have), 0);
    assert_false(have);
    assert_int_equal(bw_frame_rx_feed(&rx, stream + used, n - used, &f, &have), n - used);
    assert_true(have);
    assert_int_equal(f.type, BW_FT_END);
    assert_int_equal(rx.bad_crc, 1);
    /* the same through the byte-at-a-time call: three frames, none late */
    bw_frame_rx_init(&rx);
    uint8_t types[3];
    int k = 0;
    for (size_t i = 0; i < n; i++) {
        if (bw_frame_rx_byte(&rx, stream[i], &f))
            types[k++] = f.type;
        if (i + 1 == BW_FRAME_OVERHEAD + 40) {
            assert_int_equal(k, 1); /* ACK at the byte that failed the false frame */
            assert_true(bw_frame_rx_feed(&rx, NULL, 0, &f, &have) == 0 && have);
            types[k++] = f.type;
        }
    }
    assert_int_equal(k, 3);
    assert_int_equal(types[0], BW_FT_ACK);
    assert_int_equal(types[1], BW_FT_QUIT);
    assert_int_equal(types[2], BW_FT_END);
}

static void jobs_round_trip_and_bad_jobs_are_refused(void **state)
{
    (void)state;
    bw_job_t j, k;
    memset(&j, 0, sizeof j);
    j.shape = 3;
    j.level_out = 4;
    j.level_in = 2;
    j.mode = 2;
    j.basis = 255;
    j.flags = 1;
    j.effort = BW_EFFORT_FAST;
    j.coder = BW_CODER_AUTO;
    j.n_in = 256;
    j.bands = 2151;
    j.max_error = 7;
    j.byte_budget = 123456;
    j.scale_bits = 0x3727C5ACu;
    j.offset_bits = 0x80000000u;
    strcpy(j.source, "/tmp/brdfwave-sensor-abc");
    uint8_t b[BW_JOB_SIZE];
    assert_int_equal(bw_job_pack(&j, b), BW_JOB_SIZE);
    assert_true(bw_job_unpack(b, sizeof b, &k));
    assert_memory_equal(&j, &k, sizeof j);
    assert_false(bw_job_unpack(b, sizeof b - 1, &k));
    assert_int_equal(b[6], BW_EFFORT_FAST);
    b[6] = BW_EFFORT_FAST + 1; /* no such effort */
    assert_false(bw_job_unpack(b, sizeof b, &k));
    b[6] = BW_EFFORT_FAST;
    assert_int_equal(b[7], BW_CODER_AUTO);
    b[7] = BW_CODER_AUTO + 1; /* no such coder choice */
    assert_false(bw_job_unpack(b, sizeof b, &k));
    b[7] = BW_CODER_AUTO;
    memset(b + 32, 'x', 128); /* no terminating NUL */
    assert_false(bw_job_unpack(b, sizeof b, &k));

    /* the extension records travel after the fixed part, up to a frame */
    static uint8_t ext[BW_JOB_EXT_MAX], big[BW_FRAME_MAX_DATA + 1];
    for (size_t i = 0; i < sizeof ext; i++)
        ext[i] = (uint8_t)(i * 7 + 1);
    j.ext = ext;
    j.ext_len = 5;
    assert_int_equal(bw_job_pack(&j, big), BW_JOB_SIZE + 5);
    assert_true(bw_job_unpack(big, BW_JOB_SIZE + 5, &k));
    assert_int_equal(k.ext_len, 5);
    assert_ptr_equal(k.ext, big + BW_JOB_SIZE);
    assert_memory_equal(k.ext, ext, 5);
    j.ext_len = BW_JOB_EXT_MAX;
    assert_int_equal(bw_job_pack(&j, big), BW_FRAME_MAX_DATA);
    assert_true(bw_job_unpack(big, BW_FRAME_MAX_DATA, &k));
    assert_memory_equal(k.ext, ext, BW_JOB_EXT_MAX);
    assert_false(bw_job_unpack(big, BW_FRAME_MAX_DATA + 1, &k));
    bw_params_t p;
    bw_job_params(&k, &p);
    assert_int_equal(p.effort, BW_EFFORT_FAST);
    assert_int_equal(p.coder, BW_CODER_AUTO);
    assert_ptr_equal(p.ext, k.ext);
    assert_int_equal(p.ext_len, BW_JOB_EXT_MAX);
}

/* Segments travel as the job's first record (0x03, V), embedded segments
 * as a record 0x04 without data right after it: bw_job_params takes both
 * out and leaves the payload's own records; a 0x04 elsewhere stays among
 * the records (the encoder then refuses the job); the admission rule
 * refuses embedded segments in stream order. */
static void segments_and_embedding_travel_in_the_job_records(void **state)
{
    (void)state;
    bw_job_t j;
    memset(&j, 0, sizeof j);
    static const uint8_t recs[][12] = {
        {BW_EXT_SEGMENTS, 2, 0x80, 0x01, BW_EXT_EMBEDDED, 0, 0x81, 1, 7},
        {BW_EXT_SEGMENTS, 1, 9, 0x81, 1, 7},
        {BW_EXT_SEGMENTS, 1, 9, BW_EXT_EMBEDDED, 1, 2},
        {BW_EXT_EMBEDDED, 0, 0x81, 1, 7},
    };
    static const struct {
        uint32_t len, v, prog, rest;
    } want[] = {{9, 128, 1, 3}, {6, 9, 0, 3}, {6, 9, 0, 3}, {5, 0, 0, 5}};
    for (unsigned r = 0; r < 4; r++) {
        j.ext = recs[r];
        j.ext_len = want[r].len;
        bw_params_t p;
        bw_job_params(&j, &p);
        assert_int_equal(p.segment_vectors, want[r].v);
        assert_int_equal(p.progressive, want[r].prog);
        assert_int_equal(p.ext_len, want[r].rest);
        assert_memory_equal(p.ext, recs[r] + want[r].len - want[r].rest, want[r].rest);
    }
    bw_limits_t lim = {1u << 20, 4096, 128, 65536, 4};
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_REFLECTANCE, 3, 0, 1, 8), BW_OK);
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.basis = BW_BASIS_53;
    p.progressive = 1;
    bool streamed = true;
    assert_int_equal(bw_limits_admit(&lim, &d, &p, &streamed), BW_OK);
    assert_false(streamed);
    p.flags = BW_FLAG_STREAM_ORDER;
    assert_int_equal(bw_limits_admit(&lim, &d, &p, &streamed), BW_ERR_ARG);
    assert_false(streamed);
    p.progressive = 0;
    assert_int_equal(bw_limits_admit(&lim, &d, &p, &streamed), BW_OK);
    assert_true(streamed);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(packed_frames_are_received_intact_at_every_length),
        cmocka_unit_test(receiver_resynchronises_after_noise_and_corrupted_frames),
        cmocka_unit_test(a_header_with_an_impossible_length_is_skipped),
        cmocka_unit_test(frames_buffered_behind_a_false_header_come_out_without_more_bytes),
        cmocka_unit_test(jobs_round_trip_and_bad_jobs_are_refused),
        cmocka_unit_test(segments_and_embedding_travel_in_the_job_records),
    };
    return cmocka_run_group_tests_name("frame", tests, NULL, NULL);
}
