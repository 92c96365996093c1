/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The Rice strip coder (bw_rice.h) on its own, and the codec with
 * BW_FLAG_RICE: strips of every kind round-trip, the encoder's bytes are
 * those of an independent bit-by-bit encoder that sizes both codes of every
 * strip, a truncated stream is
 * reported, payloads keep every mode's guarantee, and the Rice body stays
 * within a few percent of the range coder's on smooth data.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_codec.h"
#include "bw_rice.h"

typedef struct {
    uint64_t s;
} rng_t;

static uint32_t rng_u32(rng_t *r)
{
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(r->s >> 32);
}
static uint32_t rng_below(rng_t *r, uint32_t n) { return (uint32_t)(((uint64_t)rng_u32(r) * n) >> 32); }

/* A strip of one of several kinds: all zero, sparse, half zero, dense, with
 * amplitudes from 1 to 2^30 and the odd extreme value. */
static void random_strip(rng_t *r, int32_t *v, unsigned cnt)
{
    unsigned kind = rng_below(r, 5);
    int32_t amp = (int32_t)1 << rng_below(r, 31);
    for (unsigned b = 0; b < cnt; b++) {
        int nz = kind == 0 ? 0 : kind == 1 ? rng_below(r, 8) == 0 : kind == 2 ? rng_below(r, 2) : 1;
        int32_t x = nz ? (int32_t)(rng_below(r, 2u * (uint32_t)amp + 1u) - (uint32_t)amp) : 0;
        if (kind == 4 && rng_below(r, 64) == 0)
            x = rng_below(r, 2) ? INT32_MIN : INT32_MAX;
        v[b] = x;
    }
}

static void strips_of_every_kind_round_trip(void **state)
{
    (void)state;
    rng_t r = {7};
    static uint8_t buf[1u << 16];
    enum { STRIPS = 12 };
    for (int trial = 0; trial < 20000; trial++) {
        int32_t v[STRIPS][32], o[32];
        unsigned cnt[STRIPS], ns = 1u + rng_below(&r, STRIPS);
        for (unsigned s = 0; s < ns; s++) {
            cnt[s] = 1u + rng_below(&r, 32);
            random_strip(&r, v[s], cnt[s]);
        }
        bw_rice_enc_t e;
        bw_rice_enc_init(&e, buf, sizeof buf);
        for (unsigned s = 0; s < ns; s++)
            bw_rice_enc_strip(&e, v[s], cnt[s]);
        size_t len = bw_rice_enc_finish(&e);
        assert_false(e.w.overflow);
        /* counting alone gives the same size */
        bw_rice_enc_t c;
        bw_rice_enc_init(&c, NULL, 0);
        for (unsigned s = 0; s < ns; s++)
            bw_rice_enc_strip(&c, v[s], cnt[s]);
        assert_int_equal(bw_rice_enc_finish(&c), len);

        bw_rice_dec_t d;
        bw_rice_dec_init(&d, buf, len);
        for (unsigned s = 0; s < ns; s++) {
            if (!bw_rice_dec_strip(&d, o, cnt[s]) || memcmp(o, v[s], cnt[s] * sizeof *o) != 0)
                fail_msg("trial %d: strip %u of %u (%u values) does not round-trip", trial, s, ns,
                         cnt[s]);
        }
        /* one byte short: some strip must report it (every code ends in the
         * last byte, so losing it loses bits that were written) */
        if (len > 0) {
            bool all = true;
            bw_rice_dec_init(&d, buf, len - 1u);
            for (unsigned s = 0; s < ns && all; s++)
                all = bw_rice_dec_strip(&d, o, cnt[s]);
            /* the last byte may hold only padding and bits of zero strips'
             * modes that decode the same from zeros: then decoding agrees */
            if (all) {
                bw_rice_dec_init(&d, buf, len - 1u);
                for (unsigned s = 0; s < ns; s++) {
                    assert_true(bw_rice_dec_strip(&d, o, cnt[s]));
                    assert_memory_equal(o, v[s], cnt[s] * sizeof *o);
                }
            }
        }
    }
}

/* ---- an independent encoder, bit by bit ---- */

typedef struct {
    uint8_t *out;
    size_t bits;
} ref_w_t;

static void ref_put(ref_w_t *w, uint64_t code, unsigned len)
{
    for (unsigned i = len; i-- > 0;) {
        if ((code >> i) & 1u)
            w->out[w->bits >> 3] |= (uint8_t)(0x80u >> (w->bits & 7u));
        w->bits++;
    }
}

static uint32_t ref_zz(int32_t v) { return v < 0 ? 2u * (0u - (uint32_t)v) - 1u : 2u * (uint32_t)v; }

/* smallest k <= kmax with 1.75 n 2^k >= sum; from a sum of 2^32 on, the
 * encoder takes the mean as 2^32 - 1 and starts at k = 30 */
static unsigned ref_k(uint64_t sum, uint64_t n, unsigned kmax)
{
    unsigned k = sum >> 32 ? 30u : 0u;
    if (k > kmax)
        return kmax;
    while (k < kmax && 7u * (n << k) < 4u * sum)
        k++;
    return k;
}

static uint32_t ref_rice_bits(uint32_t u, unsigned k) { return (u >> k) >= 16u ? 48u : (u >> k) + 1u + k; }

static void ref_rice(ref_w_t *w, uint32_t u, unsigned k)
{
    if ((u >> k) >= 16u) {
        ref_put(w, 0, 16);
        ref_put(w, u, 32);
        return;
    }
    ref_put(w, 1, (u >> k) + 1u);
    ref_put(w, u & ((1ull << k) - 1u), k);
}

static void ref_strip(ref_w_t *w, unsigned *prev, const int32_t *v, unsigned cnt)
{
    uint64_t sum = 0, msum = 0;
    uint32_t any = 0;
    unsigned nz = 0;
    for (unsigned b = 0; b < cnt; b++) {
        sum += ref_zz(v[b]);
        any |= ref_zz(v[b]);
        nz += v[b] == 0;
        if (v[b])
            msum += (v[b] < 0 ? 0u - (uint32_t)v[b] : (uint32_t)v[b]) - 1u;
    }
    unsigned k = ref_k(sum, cnt, 31), mode = 2u + k, km = 0, kg = 0;
    if (sum == 0) {
        mode = 0;
    } else if (nz >= cnt / 4u) {
        unsigned n = cnt - nz;
        km = ref_k(msum, n, 3);
        kg = ref_k(nz, n + 1u, 7);
        /* a code may escape, or a sum may wrap: the exact sizes */
        if ((any >> 26) || (any >> k) >= 16u || ((any >> 1) >> km) >= 16u || (nz >> kg) >= 16u) {
            uint32_t dense = 0, sparse = 5, gap = 0;
            for (unsigned b = 0; b < cnt; b++) {
                dense += ref_rice_bits(ref_zz(v[b]), k);
                if (!v[b]) {
                    gap++;
                    continue;
                }
                uint32_t a = (v[b] < 0 ? 0u - (uint32_t)v[b] : (uint32_t)v[b]) - 1u;
                sparse += ref_rice_bits(gap, kg) + ref_rice_bits(a, km) + 1u;
                gap = 0;
            }
            if (gap)
                sparse += ref_rice_bits(gap, kg);
            if (sparse < dense)
                mode = 1;
        } else {
            /* else the sizes' bounds from the counts, each code the sum of
             * its smallest and largest size: sum over m values of floor(x /
             * 2^k) lies in [floor((s - m (2^k - 1)) / 2^k), floor(s / 2^k)] */
            int64_t dl = (int64_t)sum - (int64_t)cnt * ((1 << k) - 1);
            int64_t ml = (int64_t)msum - (int64_t)n * ((1 << km) - 1);
            int64_t gl = (int64_t)nz - (int64_t)(n + 1u) * ((1 << kg) - 1);
            uint64_t dense2 = 2u * cnt * (k + 1u) + (dl > 0 ? (uint64_t)dl >> k : 0u) + (sum >> k);
            uint64_t base = 5u + n + n * (1u + km) + n * (1u + kg);
            uint64_t sparse2 = 2u * base + 1u + kg + (ml > 0 ? (uint64_t)ml >> km : 0u) +
                               (msum >> km) + (gl > 0 ? (uint64_t)gl >> kg : 0u) + (nz >> kg);
            if (sparse2 < dense2)
                mode = 1;
        }
    }
    uint32_t zz = ref_zz((int32_t)mode - (int32_t)*prev);
    if (zz < 15u) {
        ref_put(w, 1, zz + 1u);
    } else {
        ref_put(w, 0, 15);
        ref_put(w, mode, 6);
    }
    *prev = mode;
    if (mode == 0)
        return;
    if (mode >= 2) {
        for (unsigned b = 0; b < cnt; b++)
            ref_rice(w, ref_zz(v[b]), k);
        return;
    }
    ref_put(w, km | (kg << 2), 5);
    uint32_t gap = 0;
    for (unsigned b = 0; b < cnt; b++) {
        if (!v[b]) {
            gap++;
            continue;
        }
        ref_rice(w, gap, kg);
        ref_rice(w, (v[b] < 0 ? 0u - (uint32_t)v[b] : (uint32_t)v[b]) - 1u, km);
        ref_put(w, v[b] < 0, 1);
        gap = 0;
    }
    if (gap)
        ref_rice(w, gap, kg);
}

/* The encoder's bytes must be those of the rule above (the sizes' bounds,
 * the exact sizes where a code may escape) on strips of every kind, and on
 * strips that sit near the boundary (many zeros, small values, the odd
 * large one). */
static void the_encoder_makes_the_documented_choices(void **state)
{
    (void)state;
    rng_t r = {11};
    static uint8_t got[1u << 14], want[1u << 14];
    for (int trial = 0; trial < 20000; trial++) {
        bw_rice_enc_t e;
        bw_rice_enc_init(&e, got, sizeof got);
        memset(want, 0, sizeof want);
        ref_w_t w = {want, 0};
        unsigned prev = 0, ns = 1u + rng_below(&r, 16);
        for (unsigned s = 0; s < ns; s++) {
            int32_t v[32];
            unsigned cnt = rng_below(&r, 4) ? 32u : 1u + rng_below(&r, 32);
            if (trial & 1) {
                random_strip(&r, v, cnt);
            } else {
                unsigned zeros = rng_below(&r, 33), amp = 1u + rng_below(&r, 1u << rng_below(&r, 12));
                for (unsigned b = 0; b < cnt; b++) {
                    int32_t x = (int32_t)rng_below(&r, 2u * amp + 1u) - (int32_t)amp;
                    v[b] = rng_below(&r, 32) < zeros ? 0 : x;
                    if (rng_below(&r, 200) == 0)
                        v[b] = (int32_t)rng_below(&r, 1u << 26) - (1 << 25);
                }
            }
            bw_rice_enc_strip(&e, v, cnt);
            ref_strip(&w, &prev, v, cnt);
        }
        size_t n = bw_rice_enc_finish(&e);
        assert_int_equal(n, (w.bits + 7u) / 8u);
        assert_memory_equal(got, want, n);
    }
}

static void a_full_output_buffer_is_reported(void **state)
{
    (void)state;
    uint8_t buf[16];
    int32_t v[32];
    for (unsigned b = 0; b < 32u; b++)
        v[b] = (int32_t)(b * 1000u) - 16000;
    bw_rice_enc_t e;
    bw_rice_enc_init(&e, buf, sizeof buf);
    bw_rice_enc_strip(&e, v, 32);
    size_t len = bw_rice_enc_finish(&e);
    assert_true(len > sizeof buf);
    assert_true(e.w.overflow);
}

static void garbage_streams_decode_or_fail_without_reading_past_the_end(void **state)
{
    (void)state;
    rng_t r = {99};
    uint8_t buf[64];
    int32_t o[32];
    unsigned failed = 0;
    for (int it = 0; it < 50000; it++) {
        size_t len = rng_below(&r, sizeof buf + 1u);
        for (size_t i = 0; i < len; i++)
            buf[i] = (uint8_t)(it % 3 == 0 ? rng_u32(&r) : rng_below(&r, 4) ? 0 : rng_u32(&r));
        bw_rice_dec_t d;
        bw_rice_dec_init(&d, buf, len);
        for (int s = 0; s < 8; s++)
            if (!bw_rice_dec_strip(&d, o, 1u + rng_below(&r, 32))) {
                failed++;
                break;
            }
    }
    assert_true(failed > 0); /* the decoder does notice */
}

/* ---- through the codec --------------------------------------------------- */

static void fill(int32_t *x, size_t vectors, uint32_t bands, rng_t *r)
{
    for (size_t v = 0; v < vectors; v++)
        for (uint32_t k = 0; k < bands; k++)
            x[v * bands + k] = (int32_t)(20000 + 13 * (int32_t)k + (int32_t)((v * 7919u) % 2001u) +
                                         (int32_t)rng_below(r, 60));
}

static void rice_payloads_keep_every_guarantee(void **state)
{
    (void)state;
    static const struct {
        uint8_t shape, lo, li;
        uint32_t n_in, bands;
    } shapes[] = {{BW_SHAPE_SPECTRA, 0, 0, 9, 301}, {BW_SHAPE_REFLECTANCE, 3, 0, 1, 81},
                  {BW_SHAPE_BRDF_ISO, 2, 0, 5, 7},  {BW_SHAPE_BRDF_FULL, 1, 1, 0, 5},
                  {BW_SHAPE_REFLECTANCE, 4, 0, 1, 1}};
    rng_t r = {5};
    unsigned checked = 0;
    for (size_t c = 0; c < sizeof shapes / sizeof *shapes; c++) {
        bw_dims_t d;
        assert_int_equal(bw_dims_make(&d, (bw_shape_t)shapes[c].shape, shapes[c].lo, shapes[c].li,
                                      shapes[c].n_in, shapes[c].bands),
                         BW_OK);
        size_t n = bw_dims_samples(&d), wb = bw_work_bound(n, d.bands), cap = bw_payload_bound(n);
        int32_t *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
        int32_t *work = malloc(wb * sizeof *work), *ver = malloc(wb * sizeof *ver);
        uint8_t *out = malloc(cap);
        assert_non_null(x);
        assert_non_null(y);
        assert_non_null(work);
        assert_non_null(ver);
        assert_non_null(out);
        fill(x, n / d.bands, d.bands, &r);
        for (unsigned m = 0; m < 5; m++) {
            for (unsigned basis = 0; basis < BW_BASIS_COUNT; basis++) {
                bw_params_t p;
                memset(&p, 0, sizeof p);
                p.basis = (uint8_t)basis;
                p.flags = BW_FLAG_RICE;
                p.scale_bits = 0x3F800000u;
                p.mode = m == 0 ? BW_MODE_LOSSLESS : m <= 2 ? BW_MODE_MAX_ERROR : m == 3 ? BW_MODE_STEP : BW_MODE_BYTES;
                p.max_error = m == 1 ? 1u : m == 2 ? 9u : 0u;
                p.step_q8 = m == 3 ? 40u * 256u : 0u;
                size_t range_len = 0, len = 0;
                if (m == 4) { /* a budget of a third of the lossless range-coded size */
                    bw_params_t q = p;
                    q.mode = BW_MODE_LOSSLESS;
                    q.flags = 0;
                    assert_int_equal(bw_encode(&d, &q, x, work, NULL, out, cap, &range_len), BW_OK);
                    p.byte_budget = (uint32_t)(range_len / 3u);
                }
                bw_status_t st = bw_encode(&d, &p, x, work, ver, out, cap, &len);
                assert_int_equal(st, BW_OK);
                bw_header_t h;
                assert_int_equal(bw_decode(out, len, y, n, work, wb, &h), BW_OK);
                assert_true(h.flags & BW_FLAG_RICE);
                for (size_t i = 0; i < n; i++) {
                    int64_t e = (int64_t)y[i] - x[i];
                    if (p.mode == BW_MODE_LOSSLESS && e != 0)
                        fail_msg("shape %zu basis %u: lossless sample %zu differs", c, basis, i);
                    if (p.mode == BW_MODE_MAX_ERROR && (e > p.max_error || -e > p.max_error))
                        fail_msg("shape %zu basis %u: error %lld over %u", c, basis, (long long)e,
                                 p.max_error);
                }
                if (p.mode == BW_MODE_BYTES)
                    assert_true(len <= p.byte_budget);
                checked++;
            }
        }
        free(x);
        free(y);
        free(work);
        free(ver);
        free(out);
    }
    print_message("%u Rice payloads checked\n", checked);
}

/* The Rice body costs at most 8% more than the range coder's on smooth
 * spectra (lossless, 5/3), and the two differ: the flag does select the coder. */
static void rice_stays_close_to_the_range_coder_on_smooth_spectra(void **state)
{
    (void)state;
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, 16, 1024), BW_OK);
    size_t n = bw_dims_samples(&d), wb = bw_work_bound(n, d.bands), cap = bw_payload_bound(n);
    int32_t *x = malloc(n * sizeof *x), *work = malloc(wb * sizeof *work);
    uint8_t *out = malloc(cap);
    assert_non_null(x);
    assert_non_null(work);
    assert_non_null(out);
    rng_t r = {11};
    fill(x, 16, 1024, &r);
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = BW_MODE_LOSSLESS;
    p.basis = BW_BASIS_53;
    size_t lr, lz;
    assert_int_equal(bw_encode(&d, &p, x, work, NULL, out, cap, &lr), BW_OK);
    p.flags = BW_FLAG_RICE;
    assert_int_equal(bw_encode(&d, &p, x, work, NULL, out, cap, &lz), BW_OK);
    print_message("range %zu bytes, rice %zu bytes\n", lr, lz);
    assert_true(lz != lr);
    assert_true(lz * 100u <= lr * 108u);
    free(x);
    free(work);
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(strips_of_every_kind_round_trip),
        cmocka_unit_test(the_encoder_makes_the_documented_choices),
        cmocka_unit_test(a_full_output_buffer_is_reported),
        cmocka_unit_test(garbage_streams_decode_or_fail_without_reading_past_the_end),
        cmocka_unit_test(rice_payloads_keep_every_guarantee),
        cmocka_unit_test(rice_stays_close_to_the_range_coder_on_smooth_spectra),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
