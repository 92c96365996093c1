/* SPDX-License-Identifier: BSD-2-Clause */
/* Embedded segments (docs/FORMAT.md, Embedded segments): a whole payload
 * decodes to the samples of the strip coder's, every prefix decodes to an
 * approximation whose error falls as bytes are added, a byte budget is the
 * exact coding cut, and the payload's rules are kept. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_codec.h"
#include "bw_config.h"
#include "test_payload.h"
#include "test_rng.h"

/* Smooth surfaces with noise: every level and band holds details. */
static void fill(int32_t *x, const bw_dims_t *d, uint64_t *rng)
{
    size_t nv = (size_t)d->n_in * d->n_out;
    for (size_t v = 0; v < nv; v++)
        for (uint32_t k = 0; k < d->bands; k++)
            x[v * d->bands + k] = (int32_t)(3000 + (v * 53 % 97) * 25 + k * 17 +
                                            (int32_t)(test_uniform(rng) * 80.0) - 40);
}

static const shape_t shapes[] = {
    {BW_SHAPE_SPECTRA, 0, 0, 9, 70},
    {BW_SHAPE_REFLECTANCE, 3, 0, 1, 5},
    {BW_SHAPE_BRDF_ISO, 2, 0, 6, 1},
    {BW_SHAPE_BRDF_FULL, 2, 2, 0, 1},
};

/* test_encode with the bytes and the length apart */
static size_t encode(const bw_dims_t *d, const bw_params_t *pa, const int32_t *x, uint8_t **out,
                     bw_status_t *st)
{
    payload_t pl;
    *st = test_encode(d, pa, x, &pl);
    *out = pl.p;
    return pl.len;
}

static double sse(const int32_t *a, const int32_t *b, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
    return s;
}

/* Lossless, max-error and fixed-step payloads, embedded in one segment or
 * several, with and without the symmetry steps, on every transform basis:
 * the samples of the strip coder's payload of the same settings. */
static void embedded_payloads_decode_to_the_samples_of_the_strip_coder(void **state)
{
    (void)state;
    uint64_t rng = 7;
    unsigned cases = 0;
    for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++) {
        const shape_t *s = &shapes[si];
        bw_dims_t d;
        assert_int_equal(bw_dims_make(&d, (bw_shape_t)s->shape, s->lo, s->li, s->n_in, s->bands),
                         BW_OK);
        size_t n = bw_dims_samples(&d);
        int32_t *x = xmalloc(n * 4), *a = xmalloc(n * 4), *b = xmalloc(n * 4);
        fill(x, &d, &rng);
        for (unsigned mode = 0; mode < 4; mode++)
            for (unsigned basis = 0; basis < BW_BASIS_COUNT; basis++)
                for (unsigned var = 0; var < 4; var++) {
                    if (mode == BW_MODE_BYTES)
                        continue;
                    bw_params_t pa;
                    memset(&pa, 0, sizeof pa);
                    pa.mode = (uint8_t)mode;
                    pa.basis = (uint8_t)basis;
                    pa.max_error = 5;
                    pa.step_q8 = 256u * 30u;
                    if (var & 1u)
                        pa.segment_vectors = 5;
                    if ((var & 2u) && s->shape != BW_SHAPE_SPECTRA)
                        pa.flags = BW_FLAG_MIRROR |
                                   (s->shape == BW_SHAPE_BRDF_FULL ? BW_FLAG_RECIPROCAL : 0u);
                    else if (var & 2u)
                        continue;
                    bw_status_t st;
                    uint8_t *pe, *ps;
                    pa.progressive = 1;
                    size_t le = encode(&d, &pa, x, &pe, &st);
                    if (st != BW_OK)
                        fail_msg("shape %u mode %u basis %u var %u: %s", s->shape, mode, basis,
                                 var, bw_strerror(st));
                    pa.progressive = 0;
                    size_t ls = encode(&d, &pa, x, &ps, &st);
                    assert_int_equal(st, BW_OK);
                    assert_int_equal(test_decode(pe, le, &d, false, a, NULL, 0, NULL), BW_OK);
                    assert_int_equal(test_decode(ps, ls, &d, false, b, NULL, 0, NULL), BW_OK);
                    if (memcmp(a, b, n * 4))
                        fail_msg("shape %u mode %u basis %u var %u: samples differ", s->shape,
                                 mode, basis, var);
                    if (mode == BW_MODE_LOSSLESS)
                        assert_memory_equal(a, x, n * 4);
                    bw_header_t h;
                    assert_int_equal(bw_header_read(pe, le, &h), BW_OK);
                    /* the current forms: 4 for one band, else 5 */
                    assert_int_equal(h.embedded, d.bands == 1u ? 5 : 6);
                    assert_true(h.segment_vectors > 0);
                    free(pe);
                    free(ps);
                    cases++;
                }
        free(x);
        free(a);
        free(b);
    }
    assert_true(cases >= 40u);
}

/* Every prefix of an embedded payload in one segment decodes (status
 * INCOMPLETE, every sample approximate, none missing), and at 5, 10, 25,
 * 50 and 100 % of its bytes, and at every sixteenth, the squared error
 * never rises with more bytes; the whole payload is exact. */
static void every_prefix_decodes_and_more_bytes_never_raise_the_error(void **state)
{
    (void)state;
    uint64_t rng = 11;
    for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++) {
        const shape_t *s = &shapes[si];
        bw_dims_t d;
        assert_int_equal(bw_dims_make(&d, (bw_shape_t)s->shape, s->lo, s->li, s->n_in, s->bands),
                         BW_OK);
        size_t n = bw_dims_samples(&d), nv = (size_t)d.n_in * d.n_out;
        int32_t *x = xmalloc(n * 4), *a = xmalloc(n * 4);
        uint8_t *mask = xmalloc(nv);
        fill(x, &d, &rng);
        bw_params_t pa;
        memset(&pa, 0, sizeof pa);
        pa.mode = BW_MODE_LOSSLESS;
        pa.basis = BW_BASIS_53;
        pa.progressive = 1;
        bw_status_t st;
        uint8_t *p;
        size_t len = encode(&d, &pa, x, &p, &st);
        assert_int_equal(st, BW_OK);
        bw_header_t h;
        assert_int_equal(bw_header_read(p, len, &h), BW_OK);
        size_t first = h.header_len + 12u + 8u; /* the table, the segment's start, a byte */
        const double at[] = {0.05, 0.10, 0.25, 0.50};
        double last = -1;
        for (unsigned k = 0; k <= 16u + 4u; k++) {
            size_t cut = k < 4u ? (size_t)(at[k] * (double)len) : first + (len - first) * (k - 4u) / 16u;
            if (k == 4u) /* the fractions done: the sixteenths from the start */
                last = -1;
            if (cut < first)
                cut = first;
            bool whole = cut >= len;
            st = test_decode(p, whole ? len : cut, &d, true, a, NULL, 0, mask);
            if (whole) {
                assert_int_equal(st, BW_OK);
                assert_memory_equal(a, x, n * 4);
                continue;
            }
            if (st != BW_ERR_INCOMPLETE)
                fail_msg("shape %u, %zu of %zu bytes: %s", s->shape, cut, len, bw_strerror(st));
            for (size_t v = 0; v < nv; v++)
                assert_int_equal(mask[v], 1); /* approximate */
            double e = sse(a, x, n);
            if (last >= 0 && e > last)
                fail_msg("shape %u: %zu of %zu bytes: squared error %g, above %g with fewer",
                         s->shape, cut, len, e, last);
            last = e;
        }
        assert_true(last > 0);
        free(p);
        free(x);
        free(a);
        free(mask);
    }
}

/* A byte budget with embedded segments (one, or several: each cut at its
 * share): the exact coding cut, a whole payload within 1 % under the
 * budget that decodes without salvage, the error falling as the budget
 * grows, and the lossless coding once the budget holds it. */
static void budget_case(uint32_t segment_vectors)
{
    uint64_t rng = 13;
    const shape_t *s = &shapes[0];
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, (bw_shape_t)s->shape, s->lo, s->li, s->n_in, s->bands),
                     BW_OK);
    size_t n = bw_dims_samples(&d);
    int32_t *x = xmalloc(n * 4), *a = xmalloc(n * 4);
    fill(x, &d, &rng);
    bw_params_t pa;
    memset(&pa, 0, sizeof pa);
    pa.mode = BW_MODE_LOSSLESS;
    pa.basis = BW_BASIS_97;
    pa.progressive = 1;
    pa.segment_vectors = segment_vectors;
    bw_status_t st;
    uint8_t *p;
    size_t full = encode(&d, &pa, x, &p, &st);
    assert_int_equal(st, BW_OK);
    free(p);
    pa.mode = BW_MODE_BYTES;
    double last = -1;
    for (uint32_t budget = 400; budget < full + 1000u; budget += (uint32_t)full / 7u) {
        pa.byte_budget = budget;
        size_t len = encode(&d, &pa, x, &p, &st);
        assert_int_equal(st, BW_OK);
        assert_true(len <= budget);
        if (budget < full)
            assert_true(len * 100u >= budget * 99u);
        assert_int_equal(test_decode(p, len, &d, false, a, NULL, 0, NULL), BW_OK);
        double e = sse(a, x, n);
        if (last >= 0)
            assert_true(e <= last);
        last = e;
        if (budget >= full) { /* the lossless coding, its header one byte longer (the step) */
            assert_int_equal(len, full + 1u);
            assert_memory_equal(a, x, n * 4);
        }
        free(p);
    }
    assert_true(last == 0);
    pa.byte_budget = 30; /* not even the header */
    encode(&d, &pa, x, &p, &st);
    assert_int_equal(st, BW_ERR_BUDGET);
    free(p);
    free(x);
    free(a);
}

static void a_byte_budget_is_the_exact_coding_cut(void **state)
{
    (void)state;
    budget_case(0);
    budget_case(3);
}

/* Four spectra of 16 bands, lossless, embedded, Haar. */
static void small_case(bw_dims_t *d, int32_t x[64], bw_params_t *pa)
{
    uint64_t rng = 17;
    assert_int_equal(bw_dims_make(d, BW_SHAPE_SPECTRA, 0, 0, 4, 16), BW_OK);
    fill(x, d, &rng);
    memset(pa, 0, sizeof *pa);
    pa->mode = BW_MODE_LOSSLESS;
    pa->basis = BW_BASIS_HAAR;
    pa->progressive = 1;
}

/* Prediction and stream order do not embed; a payload's record 0x04 must
 * follow a segments record and name a form this decoder knows. */
static void what_does_not_embed_is_refused(void **state)
{
    (void)state;
    bw_dims_t d;
    int32_t x[64];
    bw_params_t pa;
    small_case(&d, x, &pa);
    pa.basis = BW_BASIS_PRED;
    bw_status_t st;
    uint8_t *p;
    encode(&d, &pa, x, &p, &st);
    free(p);
    assert_int_equal(st, BW_CFG_EMBED ? BW_ERR_ARG : BW_ERR_NOT_BUILT);
    pa.basis = BW_BASIS_HAAR;
    pa.flags = BW_FLAG_STREAM_ORDER;
    encode(&d, &pa, x, &p, &st);
    free(p);
    assert_int_equal(st, BW_CFG_EMBED ? BW_ERR_ARG : BW_ERR_NOT_BUILT);
    pa.flags = 0;
    size_t len = encode(&d, &pa, x, &p, &st);
    assert_int_equal(st, BW_OK);
    /* the records end with 0x03 V, then 0x04 and its form (5: groups of
     * strips, the incoming parent block, passes split, subband by
     * subband); changed, the fields are refused (the header's CRC is not
     * read for them) */
    bw_header_t h;
    assert_int_equal(bw_header_read(p, len, &h), BW_OK);
    assert_int_equal(h.embedded, 6);
    uint8_t *q = p + h.ext_off + h.ext_len - 3u;
    assert_int_equal(q[0], BW_EXT_EMBEDDED);
    assert_int_equal(q[1], 1);
    assert_int_equal(q[2], 5);
    q[2] = 6; /* a form this decoder does not know */
    assert_int_equal(bw_header_parse_fields(p, len, &h), BW_ERR_HEADER);
    q[2] = 5;
    q[0] = 0x07; /* an unknown critical record */
    assert_int_equal(bw_header_parse_fields(p, len, &h), BW_ERR_EXTENSION);
    q[0] = BW_EXT_SEGMENTS; /* a second segments record */
    assert_int_equal(bw_header_parse_fields(p, len, &h), BW_ERR_HEADER);
    free(p);
}

/* A core built without them (BW_CFG_EMBED 0, the 16 KiB device core)
 * refuses to code them and says so. */
static void a_core_without_embedding_refuses_it(void **state)
{
    (void)state;
    bw_dims_t d;
    int32_t x[64];
    bw_params_t pa;
    small_case(&d, x, &pa);
    bw_status_t st;
    uint8_t *p;
    encode(&d, &pa, x, &p, &st);
    free(p);
    assert_int_equal(st, BW_CFG_EMBED ? BW_OK : BW_ERR_NOT_BUILT);
}

int main(void)
{
    if (!BW_CFG_EMBED) { /* the rest needs them */
        const struct CMUnitTest only[] = {cmocka_unit_test(a_core_without_embedding_refuses_it)};
        return cmocka_run_group_tests(only, NULL, NULL);
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_core_without_embedding_refuses_it),
        cmocka_unit_test(embedded_payloads_decode_to_the_samples_of_the_strip_coder),
        cmocka_unit_test(every_prefix_decodes_and_more_bytes_never_raise_the_error),
        cmocka_unit_test(a_byte_budget_is_the_exact_coding_cut),
        cmocka_unit_test(what_does_not_embed_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
