/* SPDX-License-Identifier: BSD-2-Clause */
/* Extension records after the header (docs/FORMAT.md, Extensions): written
 * by the batch and the streaming encoder alike, covered by the CRC, walked
 * by readers; a payload with records is version 7, one without stays 6;
 * malformed records and unknown critical types are refused. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_codec.h"
#include "bw_config.h"
#include "bw_crc32.h"
#include "bw_le.h"

#define N_IN 6u
#define BANDS 40u
#define N (N_IN * BANDS)

static int32_t samples[N], work[BW_WORK_BOUND(N, BANDS)], ver[BW_WORK_BOUND(N, BANDS)];
static uint8_t out[BW_PAYLOAD_BOUND(N) + 64 + BW_EXT_OVERHEAD];

/* two ancillary records: 0x81 "abc", 0x9F with 200 bytes (a 2-byte length) */
static uint8_t ext[5 + 3 + 200];
static size_t ext_len;

static void setup_data(void)
{
    for (size_t i = 0; i < N; i++)
        samples[i] = (int32_t)(1000 + (i % BANDS) * 7 + (i / BANDS) * 3 + (i * 2654435761u >> 28));
    size_t k = 0;
    ext[k++] = BW_EXT_METADATA;
    ext[k++] = 3;
    memcpy(ext + k, "abc", 3);
    k += 3;
    ext[k++] = 0x9F;
    ext[k++] = 200 | 0x80;
    ext[k++] = 1;
    for (unsigned i = 0; i < 200; i++)
        ext[k++] = (uint8_t)i;
    ext_len = k;
}

static bw_params_t params(unsigned mode)
{
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = (uint8_t)mode;
    p.basis = BW_BASIS_53;
    p.max_error = 2;
    p.scale_bits = 0x3F800000u;
    return p;
}

static size_t encode(const bw_params_t *p, bw_status_t want)
{
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, N_IN, BANDS), BW_OK);
    size_t len = 0;
    assert_int_equal(bw_encode(&d, p, samples, work, ver, out, sizeof out, &len), want);
    return len;
}

static void records_travel_with_the_payload_and_make_it_version_7(void **state)
{
    (void)state;
    setup_data();
    bw_params_t p = params(BW_MODE_LOSSLESS);
    size_t plain = encode(&p, BW_OK);
    bw_header_t h;
    assert_int_equal(bw_header_read(out, plain, &h), BW_OK);
    assert_int_equal(h.version, 6);
    assert_int_equal(h.ext_len, 0);
    p.ext = ext;
    p.ext_len = (uint32_t)ext_len;
    size_t len = encode(&p, BW_OK);
    /* the records and their 2-byte length are all the payload grows by */
    assert_int_equal(len, plain + ext_len + 2u);
    assert_int_equal(bw_header_read(out, len, &h), BW_OK);
    assert_int_equal(h.version, 7);
    assert_true(h.flags & BW_FLAG_EXT);
    assert_int_equal(h.ext_len, ext_len);
    assert_memory_equal(out + h.ext_off, ext, ext_len);
    size_t pos = 0;
    uint8_t type;
    const uint8_t *d;
    uint32_t dl;
    assert_true(bw_ext_next(out + h.ext_off, h.ext_len, &pos, &type, &d, &dl));
    assert_int_equal(type, BW_EXT_METADATA);
    assert_int_equal(dl, 3);
    assert_memory_equal(d, "abc", 3);
    assert_true(bw_ext_next(out + h.ext_off, h.ext_len, &pos, &type, &d, &dl));
    assert_int_equal(type, 0x9F);
    assert_int_equal(dl, 200);
    assert_false(bw_ext_next(out + h.ext_off, h.ext_len, &pos, &type, &d, &dl));
    /* the samples are the same as without the records */
    bw_header_t hd;
    assert_int_equal(bw_decode(out, len, ver, N, work, sizeof work / sizeof *work, &hd), BW_OK);
    assert_memory_equal(ver, samples, sizeof samples);
    /* a byte budget counts the records */
    p.mode = BW_MODE_BYTES;
    p.byte_budget = (uint32_t)(plain * 3 / 4 + ext_len);
    len = encode(&p, BW_OK);
    assert_true(len <= p.byte_budget);
    assert_int_equal(bw_header_read(out, len, &h), BW_OK);
    assert_int_equal(h.ext_len, ext_len);
}

static void the_streaming_encoder_writes_the_same_records(void **state)
{
    (void)state;
    setup_data();
    bw_params_t p = params(BW_MODE_MAX_ERROR);
    p.flags = BW_FLAG_STREAM_ORDER;
    p.ext = ext;
    p.ext_len = (uint32_t)ext_len;
    size_t len = encode(&p, BW_OK);
    static uint8_t batch[sizeof out], streamed[sizeof out];
    memcpy(batch, out, len);
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, N_IN, BANDS), BW_OK);
    static bw_stream_t s;
    static int32_t mem[BW_STREAM_MEM_BOUND(0, BANDS)];
    assert_int_equal(bw_stream_init(&s, &d, &p, mem, sizeof mem / sizeof *mem, streamed,
                                    sizeof streamed),
                     BW_OK);
    for (unsigned i = 0; i < N_IN; i++)
        assert_int_equal(bw_stream_push(&s, samples + i * BANDS), BW_OK);
    size_t slen = 0;
    assert_int_equal(bw_stream_finish(&s, &slen), BW_OK);
    assert_int_equal(slen, len);
    assert_memory_equal(streamed, batch, len);
}

static void malformed_records_are_refused_by_the_encoder(void **state)
{
    (void)state;
    setup_data();
    bw_params_t p = params(BW_MODE_LOSSLESS);
    uint8_t bad[8] = {0x81, 5, 'a', 'b'}; /* claims 5 bytes, holds 2 */
    p.ext = bad;
    p.ext_len = 4;
    encode(&p, BW_ERR_ARG);
    uint8_t crit[3] = {0x07, 1, 0}; /* a critical type no decoder knows */
    p.ext = crit;
    p.ext_len = 3;
    encode(&p, BW_ERR_ARG);
    p.ext = NULL; /* a length without records */
    encode(&p, BW_ERR_ARG);
}

/* rewrites the payload's CRC after an edit */
static void recrc(uint8_t *p, size_t len)
{
    bw_put_u32(p + len - 4, bw_crc32(p, len - 4));
}

static void decoders_refuse_unknown_critical_records_and_inconsistent_versions(void **state)
{
    (void)state;
    setup_data();
    bw_params_t p = params(BW_MODE_LOSSLESS);
    uint8_t rec[3] = {0x81, 1, 0x42};
    p.ext = rec;
    p.ext_len = 3;
    size_t len = encode(&p, BW_OK);
    bw_header_t h;
    assert_int_equal(bw_header_read(out, len, &h), BW_OK);
    size_t at = h.ext_off;
    static uint8_t edit[sizeof out];

    memcpy(edit, out, len);
    edit[at] = 0x07; /* the record becomes critical and unknown */
    recrc(edit, len);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_EXTENSION);
    assert_int_equal(bw_decode(edit, len, ver, N, work, sizeof work / sizeof *work, NULL),
                     BW_ERR_EXTENSION);

    memcpy(edit, out, len);
    edit[at + 1] = 9; /* a record longer than the area */
    recrc(edit, len);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);

    memcpy(edit, out, len);
    edit[2] = 6; /* records in a version-6 header */
    recrc(edit, len);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);

    size_t plain = encode(&(bw_params_t){.mode = BW_MODE_LOSSLESS, .basis = BW_BASIS_53}, BW_OK);
    memcpy(edit, out, plain);
    edit[2] = 7; /* version 7 without records */
    recrc(edit, plain);
    assert_int_equal(bw_header_read(edit, plain, &h), BW_ERR_HEADER);
    edit[2] = 8; /* a version no decoder knows yet */
    recrc(edit, plain);
    assert_int_equal(bw_header_read(edit, plain, &h), BW_ERR_VERSION);
}

/* Builds at dst the payload src[len] (a version-6 payload) with the records
 * recs[rlen] after its header's fields and tail[tlen] before its CRC;
 * returns the new length. */
static size_t with_records(uint8_t *dst, const uint8_t *src, size_t len, const uint8_t *recs,
                           size_t rlen, const uint8_t *tail, size_t tlen)
{
    bw_header_t h;
    assert_int_equal(bw_header_read(src, len, &h), BW_OK);
    assert_int_equal(h.ext_len, 0);
    assert_true(rlen < 128);
    size_t k = h.header_len;
    memcpy(dst, src, k);
    dst[2] = 7;
    dst[5] |= BW_FLAG_EXT;
    dst[k++] = (uint8_t)rlen;
    memcpy(dst + k, recs, rlen);
    k += rlen;
    memcpy(dst + k, src + h.header_len, h.body_len);
    k += h.body_len;
    if (tlen) /* no tail: tail may be NULL */
        memcpy(dst + k, tail, tlen);
    k += tlen;
    recrc(dst, k + 4);
    return k + 4;
}

static void the_float_records_are_known_and_their_tail_is_left_to_the_host(void **state)
{
    (void)state;
    setup_data();
    bw_params_t p = params(BW_MODE_LOSSLESS);
    size_t plain = encode(&p, BW_OK);
    static uint8_t src[sizeof out], edit[sizeof out + 300];
    memcpy(src, out, plain);
    bw_header_t h0, h;
    assert_int_equal(bw_header_read(src, plain, &h0), BW_OK);

    /* record 0x01 says the last 200 bytes before the CRC are not the coder's */
    static uint8_t tail[200];
    for (unsigned i = 0; i < sizeof tail; i++)
        tail[i] = (uint8_t)(i * 37u + 5u);
    const uint8_t rec[] = {BW_EXT_FLOAT_EXACT, 3, 200 | 0x80, 1, 0,
                           BW_EXT_LOG_MAP, 2, 0xAA, 0xBB};
    size_t len = with_records(edit, src, plain, rec, sizeof rec, tail, sizeof tail);
    assert_int_equal(bw_header_read(edit, len, &h), BW_OK);
    assert_int_equal(h.body_len, h0.body_len);
    assert_int_equal(h.payload_len - 4 - h.header_len - h.body_len, sizeof tail);
    memset(ver, 0, sizeof ver);
    assert_int_equal(bw_decode(edit, len, ver, N, work, sizeof work / sizeof *work, NULL), BW_OK);
    assert_memory_equal(ver, samples, sizeof samples);

    /* a tail longer than what follows the header */
    const uint8_t big[] = {BW_EXT_FLOAT_EXACT, 3, 0xFF, 0xFF, 0x03};
    len = with_records(edit, src, plain, big, sizeof big, tail, 10);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    /* a record 0x01 without its length field */
    const uint8_t empty[] = {BW_EXT_FLOAT_EXACT, 0};
    len = with_records(edit, src, plain, empty, sizeof empty, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    /* 0x07 is critical and unknown */
    const uint8_t seven[] = {0x07, 1, 0};
    len = with_records(edit, src, plain, seven, sizeof seven, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_EXTENSION);
    /* 0x04 (embedded) follows a segments record and holds no data */
    const uint8_t four[] = {BW_EXT_EMBEDDED, 0};
    len = with_records(edit, src, plain, four, sizeof four, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h),
                     BW_CFG_EMBED ? BW_ERR_HEADER : BW_ERR_NOT_BUILT);
    /* 0x03 (segments) needs V >= 1, and a core built with segments */
    const uint8_t three[] = {BW_EXT_SEGMENTS, 1, 0};
    len = with_records(edit, src, plain, three, sizeof three, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h),
                     BW_CFG_SEGMENTS ? BW_ERR_HEADER : BW_ERR_NOT_BUILT);
    /* type 0 too */
    const uint8_t zero[] = {0x00, 1, 0};
    len = with_records(edit, src, plain, zero, sizeof zero, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_EXTENSION);

    /* the encoder writes them, but no tail: it codes no bytes past its body */
    const uint8_t no_tail[] = {BW_EXT_FLOAT_EXACT, 2, 0, 0, BW_EXT_LOG_MAP, 1, 7};
    p.ext = no_tail;
    p.ext_len = sizeof no_tail;
    len = encode(&p, BW_OK);
    assert_int_equal(bw_header_read(out, len, &h), BW_OK);
    p.ext = rec;
    p.ext_len = sizeof rec;
    encode(&p, BW_ERR_ARG);
}


/* ---- record 0x05: a step per chunk of vectors --------------------------- */

/* The step of a chunk with step change d, from docs/FORMAT.md (Chunk
 * steps): floor(S m_f 2^e / 2^15), d = 32 e + f, m_f = round(2^15 2^(f / 32)),
 * at least 257. */
static uint64_t format_chunk_step(uint32_t S, int d)
{
    int e = (int)floor(d / 32.0), f = d - 32 * e;
    uint64_t m = (uint64_t)lround(32768.0 * pow(2.0, f / 32.0)), v = (uint64_t)S * m;
    uint64_t st = e >= 0 ? (v << e) >> 15 : v >> (15 - e);
    return st < 257u ? 257u : st > UINT32_MAX ? UINT32_MAX : st;
}

/* the reconstruction of index q at step st (docs/FORMAT.md, Quantisation) */
static int64_t format_dequant(int64_t q, uint64_t st)
{
    int64_t m = (int64_t)(((uint64_t)(q < 0 ? -q : q) * 8u + 3u) * st / 2048u);
    return q == 0 ? 0 : q < 0 ? -m : m;
}

/* the record 0x05 of K vectors per chunk and steps d[c] into rec; its size */
static size_t chunk_record(uint8_t *rec, uint32_t K, const int8_t *d, size_t c)
{
    assert_true(K < 128u && c + 1u < 128u);
    rec[0] = BW_EXT_CHUNK_STEPS;
    rec[1] = (uint8_t)(1u + c);
    rec[2] = (uint8_t)K;
    memcpy(rec + 3, d, c);
    return 3u + c;
}

/* Without a transform (spectra of one band, each coefficient its sample)
 * every sample decodes at its chunk's step: the index the payload codes,
 * read back from the decode at the header's step, reconstructed at
 * step_q8 2^(d / 32) for the d of its chunk of K spectra. */
static void each_chunk_decodes_at_its_own_step(void **state)
{
    (void)state;
    enum { NS = 48, K = 5, C = (NS + K - 1) / K };
    const uint32_t S = 16u * 256u + 37u;
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, NS, 1), BW_OK);
    static int32_t x[NS], r[NS], r2[NS], w[BW_WORK_BOUND(NS, 1)], v[BW_WORK_BOUND(NS, 1)];
    for (unsigned i = 0; i < NS; i++)
        x[i] = (int32_t)((i * 2654435761u >> 17) % 40001u) - 20000;
    bw_params_t p = params(BW_MODE_STEP);
    p.basis = BW_BASIS_HAAR;
    p.step_q8 = S;
    static uint8_t src[BW_PAYLOAD_BOUND(NS)], edit[BW_PAYLOAD_BOUND(NS) + 64];
    size_t len;
    assert_int_equal(bw_encode(&d, &p, x, w, v, src, sizeof src, &len), BW_OK);
    assert_int_equal(bw_decode(src, len, r, NS, w, BW_WORK_BOUND(NS, 1), NULL), BW_OK);
    /* the indices: each decoded value is the reconstruction of one */
    int64_t q[NS];
    for (unsigned i = 0; i < NS; i++) {
        double t = (fabs((double)r[i]) * 2048.0 / S - 3.0) / 8.0;
        q[i] = r[i] == 0 ? 0 : (r[i] < 0 ? -1 : 1) * (int64_t)lround(t);
        assert_int_equal(format_dequant(q[i], S), r[i]);
    }
    const int8_t steps[C] = {0, 32, -32, 5, -7, 127, -128, 1, -1, 64};
    uint8_t rec[3 + C];
    size_t rl = chunk_record(rec, K, steps, C);
    size_t l2 = with_records(edit, src, len, rec, rl, NULL, 0);
    bw_header_t h;
    assert_int_equal(bw_header_read(edit, l2, &h), BW_CFG_CHUNK_STEPS ? BW_OK : BW_ERR_NOT_BUILT);
    if (!BW_CFG_CHUNK_STEPS)
        return;
    assert_int_equal(bw_decode(edit, l2, r2, NS, w, BW_WORK_BOUND(NS, 1), NULL), BW_OK);
    for (unsigned i = 0; i < NS; i++) {
        int64_t want = format_dequant(q[i], format_chunk_step(S, steps[i / K]));
        if (r2[i] != want)
            fail_msg("spectrum %u (chunk %u, d %d): %d, the format says %lld", i, i / K,
                     steps[i / K], r2[i], (long long)want);
    }
    /* every step change is read: one changed, that chunk's samples change */
    edit[l2 - 4u - len + h.header_len - 1u] ^= 0u; /* (the body is unchanged) */
    size_t at = (size_t)h.ext_off + 3u + 4u; /* chunk 4's byte */
    edit[at] = (uint8_t)(edit[at] + 3u);
    recrc(edit, l2);
    assert_int_equal(bw_decode(edit, l2, r2, NS, w, BW_WORK_BOUND(NS, 1), NULL), BW_OK);
    unsigned changed = 0;
    for (unsigned i = 0; i < NS; i++)
        if (r2[i] != format_dequant(q[i], format_chunk_step(S, steps[i / K])))
            changed += i / K == 4u ? 1u : 1000u;
    assert_true(changed > 0u && changed < 1000u);
}

/* A record 0x05 that does not fit its payload is a header error: K of 0 or
 * above the vectors, a step missing or one too many, a second record, a
 * payload coded exactly (no step to change). */
static void chunk_records_that_do_not_fit_are_refused(void **state)
{
    (void)state;
    if (!BW_CFG_CHUNK_STEPS)
        skip();
    setup_data();
    bw_params_t p = params(BW_MODE_STEP);
    p.step_q8 = 1000u;
    size_t plain = encode(&p, BW_OK);
    static uint8_t src[sizeof out], edit[sizeof out + 300];
    memcpy(src, out, plain);
    const int8_t z[8] = {0};
    uint8_t rec[40];
    bw_header_t h;
    /* N_IN vectors: K = 2 makes 3 chunks */
    size_t rl = chunk_record(rec, 2, z, 3), len = with_records(edit, src, plain, rec, rl, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_OK);
    rl = chunk_record(rec, 0, z, 3);
    len = with_records(edit, src, plain, rec, rl, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    rl = chunk_record(rec, N_IN + 1u, z, 1);
    len = with_records(edit, src, plain, rec, rl, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    for (size_t c = 2; c <= 4; c += 2) {
        rl = chunk_record(rec, 2, z, c);
        len = with_records(edit, src, plain, rec, rl, NULL, 0);
        assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    }
    rl = chunk_record(rec, 2, z, 3);
    memcpy(rec + rl, rec, rl);
    len = with_records(edit, src, plain, rec, 2u * rl, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    p = params(BW_MODE_LOSSLESS);
    plain = encode(&p, BW_OK);
    memcpy(src, out, plain);
    rl = chunk_record(rec, 2, z, 3);
    len = with_records(edit, src, plain, rec, rl, NULL, 0);
    assert_int_equal(bw_header_read(edit, len, &h), BW_ERR_HEADER);
    /* and the encoder writes its own: a caller's is refused */
    p.ext = rec;
    p.ext_len = (uint32_t)rl;
    encode(&p, BW_ERR_ARG);
}

/* Steps per chunk within an incoming block (one direction, spectra on its
 * hemisphere: chunks of a few outgoing vectors): with every step change 0
 * the decode is that of the payload without the record. */
static void chunks_within_a_block_walk_its_vectors(void **state)
{
    (void)state;
    if (!BW_CFG_CHUNK_STEPS)
        skip();
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_REFLECTANCE, 3, 0, 1, 12), BW_OK);
    size_t n = bw_dims_samples(&d), wb = BW_WORK_BOUND(n, 12);
    int32_t *x = malloc(n * sizeof *x), *r = malloc(n * sizeof *r), *r2 = malloc(n * sizeof *r2),
            *w = malloc(wb * sizeof *w), *v = malloc(wb * sizeof *v);
    uint8_t *src = malloc(BW_PAYLOAD_BOUND(n)), *edit = malloc(BW_PAYLOAD_BOUND(n) + 128);
    assert_non_null(edit);
    for (size_t i = 0; i < n; i++)
        x[i] = (int32_t)(3000 + (i % 12u) * 40u + (i / 12u) * 9u + (i * 2654435761u >> 27));
    bw_params_t p = params(BW_MODE_STEP);
    p.step_q8 = 700u;
    size_t len;
    assert_int_equal(bw_encode(&d, &p, x, w, v, src, BW_PAYLOAD_BOUND(n), &len), BW_OK);
    assert_int_equal(bw_decode(src, len, r, n, w, wb, NULL), BW_OK);
    uint32_t nv = d.n_out, K = 7u, c = (nv + K - 1u) / K;
    int8_t z[64] = {0};
    uint8_t rec[80];
    size_t rl = chunk_record(rec, K, z, c), l2 = with_records(edit, src, len, rec, rl, NULL, 0);
    assert_int_equal(bw_decode(edit, l2, r2, n, w, wb, NULL), BW_OK);
    assert_memory_equal(r, r2, n * sizeof *r);
    /* one chunk coarser: its vectors' coefficients change, so do samples */
    rec[3 + 2] = 32;
    l2 = with_records(edit, src, len, rec, rl, NULL, 0);
    assert_int_equal(bw_decode(edit, l2, r2, n, w, wb, NULL), BW_OK);
    assert_true(memcmp(r, r2, n * sizeof *r) != 0);
    free(x), free(r), free(r2), free(w), free(v), free(src), free(edit);
}

/* Steps per chunk of whole incoming blocks: a direction decoded alone is
 * that direction of the whole decode. */
static void chunk_steps_decode_alike_whole_and_a_direction_at_a_time(void **state)
{
    (void)state;
    if (!BW_CFG_CHUNK_STEPS)
        skip();
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_BRDF_ISO, 3, 0, 12, 1), BW_OK);
    size_t n = bw_dims_samples(&d), wb = BW_WORK_BOUND(n, 1);
    int32_t *x = malloc(n * sizeof *x), *r = malloc(n * sizeof *r), *row = malloc(d.n_out * 4u),
            *w = malloc(wb * sizeof *w), *v = malloc(wb * sizeof *v);
    uint8_t *src = malloc(BW_PAYLOAD_BOUND(n)), *pl = malloc(BW_PAYLOAD_BOUND(n) + 64);
    assert_non_null(pl);
    for (size_t i = 0; i < n; i++) { /* a lobe moving with the incoming direction */
        double t = (double)(i % d.n_out) / d.n_out, c = (double)(i / d.n_out) / 12.0;
        x[i] = (int32_t)(2000.0 + 30000.0 * exp(-200.0 * (t - c) * (t - c)) + (i * 7u % 13u));
    }
    bw_params_t p = params(BW_MODE_STEP);
    p.step_q8 = 3000u;
    size_t len;
    assert_int_equal(bw_encode(&d, &p, x, w, v, src, BW_PAYLOAD_BOUND(n), &len), BW_OK);
    /* chunks of two directions, each at its own step */
    const int8_t steps[6] = {-20, 0, 17, -3, 40, 9};
    uint8_t rec[16];
    size_t rl = 0;
    rec[rl++] = BW_EXT_CHUNK_STEPS;
    rec[rl++] = 2u + 6u;
    rec[rl++] = 0x80u; /* K = 512, a varint of two bytes */
    rec[rl++] = 0x04u;
    memcpy(rec + rl, steps, sizeof steps);
    rl += sizeof steps;
    size_t l2 = with_records(pl, src, len, rec, rl, NULL, 0);
    assert_int_equal(bw_decode(pl, l2, r, n, w, wb, NULL), BW_OK);
    bw_ctx_t *ctx = malloc(sizeof *ctx);
    for (uint32_t i = 0; i < d.n_in; i++) {
        assert_int_equal(bw_decode_incoming(ctx, pl, l2, i, row, d.n_out, w, wb, NULL), BW_OK);
        assert_memory_equal(row, r + (size_t)i * d.n_out, d.n_out * sizeof *row);
    }
    /* and the steps matter: the payload without them decodes otherwise */
    assert_int_equal(bw_decode(src, len, x, n, w, wb, NULL), BW_OK);
    assert_true(memcmp(x, r, n * sizeof *r) != 0);
    free(ctx), free(x), free(r), free(row), free(w), free(v), free(src), free(pl);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(records_travel_with_the_payload_and_make_it_version_7),
        cmocka_unit_test(the_streaming_encoder_writes_the_same_records),
        cmocka_unit_test(malformed_records_are_refused_by_the_encoder),
        cmocka_unit_test(decoders_refuse_unknown_critical_records_and_inconsistent_versions),
        cmocka_unit_test(the_float_records_are_known_and_their_tail_is_left_to_the_host),
        cmocka_unit_test(each_chunk_decodes_at_its_own_step),
        cmocka_unit_test(chunk_records_that_do_not_fit_are_refused),
        cmocka_unit_test(chunks_within_a_block_walk_its_vectors),
        cmocka_unit_test(chunk_steps_decode_alike_whole_and_a_direction_at_a_time),
    };
    return cmocka_run_group_tests_name("ext", tests, NULL, NULL);
}
