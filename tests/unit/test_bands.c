/* SPDX-License-Identifier: BSD-2-Clause */
/* Band access (docs/FORMAT.md, Band access): sets of spectra whose whole
 * decode gives the samples back (exactly, or within the max error), whose
 * every band and band range decodes alone to the same samples, and whose
 * damaged bytes are found: by the whole decode always, by a band's decode
 * where it reads them, while the bands that do not read them still decode
 * exactly. */
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
#include "bwh_ext.h"
#include "test_payload.h"

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

/* Smooth spectra with noise (kind 0), noise over the whole range (1), or
 * steps between the range's ends (2). */
static void fill(int32_t *x, uint32_t n_in, uint32_t bands, unsigned kind)
{
    for (uint32_t s = 0; s < n_in; s++) {
        int64_t v = 100000 + (int64_t)s * 313;
        for (uint32_t k = 0; k < bands; k++) {
            int32_t y;
            if (kind == 0) {
                v += (int32_t)(rnd() % 7) - 3 + (int32_t)(k % 50 == 0 ? rnd() % 2001 : 0) - 1000 * (k % 50 == 0);
                y = (int32_t)v + (int32_t)(rnd() % 3);
            } else if (kind == 1) {
                y = (int32_t)(rnd() % (2u * BW_SAMPLE_MAX + 1u)) - BW_SAMPLE_MAX;
            } else {
                y = (rnd() & 1u) ? BW_SAMPLE_MAX : -BW_SAMPLE_MAX;
            }
            x[(size_t)s * bands + k] = y;
        }
    }
}

static void params(bw_params_t *pa, unsigned mode, uint32_t E)
{
    memset(pa, 0, sizeof *pa);
    pa->mode = (uint8_t)mode;
    pa->max_error = mode == BW_MODE_MAX_ERROR ? E : 0u;
    pa->basis = BW_BASIS_AUTO;
    pa->band_access = 1u;
}

static void whole(const payload_t *p, const bw_dims_t *d, int32_t *out, bw_status_t want)
{
    size_t n = bw_dims_samples(d), wb = bw_work_bound(n, d->bands);
    int32_t *w = xmalloc(wb * 4);
    assert_int_equal(bw_decode(p->p, p->len, out, n, w, wb, NULL), want);
    free(w);
}

static bw_status_t range(const uint8_t *p, size_t len, const bw_dims_t *d, uint32_t b0,
                         uint32_t b1, int32_t *out)
{
    size_t wb = bw_band_range_work(d->n_in, b1 - b0);
    int32_t *w = xmalloc(wb * 4);
    bw_status_t st = bw_decode_band_range(p, len, b0, b1, out, (size_t)d->n_in * (b1 - b0), w,
                                          wb, NULL);
    free(w);
    return st;
}

/* A set of spectra, its payload and its whole decode; r: room for as many
 * samples. */
typedef struct {
    bw_dims_t d;
    size_t n;
    int32_t *x, *y, *r;
    payload_t p;
} set_t;

static void set_make(set_t *t, uint32_t n_in, uint32_t bands, unsigned kind, unsigned mode,
                     uint32_t E)
{
    assert_int_equal(bw_dims_make(&t->d, BW_SHAPE_SPECTRA, 0, 0, n_in, bands), BW_OK);
    t->n = bw_dims_samples(&t->d);
    t->x = xmalloc(t->n * 4);
    t->y = xmalloc(t->n * 4);
    t->r = xmalloc(t->n * 4);
    fill(t->x, n_in, bands, kind);
    bw_params_t pa;
    params(&pa, mode, E);
    bw_status_t st = test_encode(&t->d, &pa, t->x, &t->p);
    if (st != BW_OK)
        fail_msg("%u x %u kind %u mode %u: %s", n_in, bands, kind, mode, bw_strerror(st));
    whole(&t->p, &t->d, t->y, BW_OK);
}

static void set_free(set_t *t)
{
    free(t->p.p);
    free(t->x);
    free(t->y);
    free(t->r);
}

/* A payload of tests/golden/v7/ into p (allocated). */
static void read_golden(const char *name, payload_t *p)
{
    FILE *f = fopen(name, "rb");
    if (!f)
        fail_msg("%s: cannot open", name);
    p->p = xmalloc(1u << 16);
    p->len = fread(p->p, 1, 1u << 16, f);
    fclose(f);
}

/* The samples of bands b0..b1-1 of the whole decode y. */
static void assert_range_is(const int32_t *got, const int32_t *y, const bw_dims_t *d, uint32_t b0,
                            uint32_t b1)
{
    for (uint32_t s = 0; s < d->n_in; s++)
        for (uint32_t k = b0; k < b1; k++)
            if (got[(size_t)s * (b1 - b0) + (k - b0)] != y[(size_t)s * d->bands + k])
                fail_msg("bands %u..%u of %u x %u: spectrum %u band %u is %d, the whole decode %d",
                         b0, b1, d->n_in, d->bands, s, k, got[(size_t)s * (b1 - b0) + (k - b0)],
                         y[(size_t)s * d->bands + k]);
}

static void one_case(uint32_t n_in, uint32_t bands, unsigned kind, unsigned mode, uint32_t E)
{
    set_t t;
    set_make(&t, n_in, bands, kind, mode, E);
    const bw_dims_t *d = &t.d;
    int32_t *x = t.x, *y = t.y, *r = t.r;
    bw_header_t h;
    assert_int_equal(bw_header_read(t.p.p, t.p.len, &h), BW_OK);
    assert_int_equal(h.band_access, 1);
    assert_int_equal(h.basis, BW_BASIS_PRED);
    for (size_t i = 0; i < t.n; i++) {
        int64_t e = (int64_t)y[i] - x[i];
        if (e > (int64_t)E || -e > (int64_t)E)
            fail_msg("%u x %u mode %u: sample %zu is %d, input %d", n_in, bands, mode, i, y[i],
                     x[i]);
    }
    /* every band alone (every eighth of the larger), then ranges */
    uint32_t step = bands > 300u ? 7u : 1u;
    for (uint32_t k = 0; k < bands; k += step) {
        assert_int_equal(range(t.p.p, t.p.len, d, k, k + 1u, r), BW_OK);
        assert_range_is(r, y, d, k, k + 1u);
    }
    for (unsigned u = 0; u < 12u; u++) {
        uint32_t a = rnd() % bands, b = a + 1u + rnd() % (bands - a);
        if (u == 0) {
            a = 0;
            b = bands;
        }
        assert_int_equal(range(t.p.p, t.p.len, d, a, b, r), BW_OK);
        assert_range_is(r, y, d, a, b);
    }
    /* the arguments a band range refuses */
    assert_int_equal(range(t.p.p, t.p.len, d, 0, bands + 1u, r), BW_ERR_ARG);
    set_free(&t);
}

static void test_round_trip(void **state)
{
    (void)state;
    if (!BW_CFG_BANDS)
        skip();
    static const uint32_t bands[] = {1, 2, 3, 4, 5, 7, 8, 9, 16, 17, 31, 32, 33, 37, 64, 65, 100, 257, 2151};
    static const uint32_t n_in[] = {1, 2, 3, 4, 5, 71};
    for (size_t b = 0; b < sizeof bands / sizeof *bands; b++)
        for (size_t s = 0; s < sizeof n_in / sizeof *n_in; s++) {
            if (bands[b] * n_in[s] > 40000u)
                continue;
            for (unsigned kind = 0; kind < 3u; kind++) {
                one_case(n_in[s], bands[b], kind, BW_MODE_LOSSLESS, 0);
                one_case(n_in[s], bands[b], kind, BW_MODE_MAX_ERROR, 1u + kind * 40u);
            }
        }
    one_case(71, 2151, 0, BW_MODE_LOSSLESS, 0);
}

/* 9 spectra of 600 bands: a band's decode is smaller than the whole's
 * and reads few groups; the columns it does not read may be damaged. */
static void test_damage(void **state)
{
    (void)state;
    if (!BW_CFG_BANDS)
        skip();
    set_t t;
    set_make(&t, 9, 600, 0, BW_MODE_LOSSLESS, 0);
    const bw_dims_t d = t.d;
    const payload_t p = t.p;
    size_t n = t.n;
    int32_t *y = t.y, *r = t.r;
    uint8_t *c = xmalloc(p.len);
    unsigned caught = 0, kept = 0;
    for (size_t i = 0; i < p.len; i++) {
        memcpy(c, p.p, p.len);
        c[i] ^= (uint8_t)(1u << (i % 8u));
        payload_t q = {c, p.len};
        whole(&q, &d, r, i < 2u ? BW_ERR_MAGIC : i == 2u ? BW_ERR_VERSION : BW_ERR_CRC);
        /* band 300: refused, or the whole decode's */
        uint32_t k = 300;
        bw_status_t st = range(c, p.len, &d, k, k + 1u, r);
        if (st == BW_OK) {
            assert_range_is(r, y, &d, k, k + 1u);
            kept++;
        } else {
            caught++;
        }
    }
    /* most bytes are not band 300's: it decodes past them */
    assert_true(kept > p.len / 2u);
    assert_true(caught > 0u);
    /* every cut is refused, by both */
    for (size_t l = 0; l < p.len; l++) {
        assert_int_not_equal(bw_decode(p.p, l, r, n, r, 0, NULL), BW_OK);
        assert_int_not_equal(range(p.p, l, &d, 0, 1, r), BW_OK);
    }
    free(c);
    set_free(&t);
}

/* Records added to the payload (the host's): the tables' CRC, which covers
 * the header, follows. */
static void test_records_added(void **state)
{
    (void)state;
    if (!BW_CFG_BANDS)
        skip();
    set_t t;
    set_make(&t, 4, 70, 0, BW_MODE_LOSSLESS, 0);
    static const uint8_t rec[] = {0x90, 3, 'a', 'b', 'c'};
    size_t len = t.p.len;
    assert_int_equal(bwh_ext_add(&t.p.p, &len, rec, sizeof rec, NULL, 0), 0);
    t.p.len = len;
    whole(&t.p, &t.d, t.y, BW_OK);
    assert_memory_equal(t.x, t.y, t.n * 4);
    assert_int_equal(range(t.p.p, t.p.len, &t.d, 3, 60, t.r), BW_OK);
    assert_range_is(t.r, t.y, &t.d, 3, 60);
    set_free(&t);
}

/* The archived payloads of band access (tests/golden/v7/ *_bands): every
 * band alone is the whole decode's. */
static void test_golden(void **state)
{
    (void)state;
    if (!BW_CFG_BANDS)
        skip();
    static const char *names[] = {"tests/golden/v7/spectra8_sed_lossless_bands.bwv",
                                  "tests/golden/v7/spectra8_sed_maxerr_bands.bwv"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        payload_t p;
        read_golden(names[i], &p);
        bw_header_t h;
        assert_int_equal(bw_header_read(p.p, p.len, &h), BW_OK);
        assert_int_equal(h.band_access, 1);
        size_t n = bw_dims_samples(&h.dims);
        int32_t *y = xmalloc(n * 4), *r = xmalloc(n * 4);
        whole(&p, &h.dims, y, BW_OK);
        for (uint32_t k = 0; k < h.dims.bands; k++) {
            assert_int_equal(range(p.p, p.len, &h.dims, k, k + 1u, r), BW_OK);
            assert_range_is(r, y, &h.dims, k, k + 1u);
        }
        free(p.p);
        free(y);
        free(r);
    }
}

/* What band access is not for: refused before anything is written. */
static void test_refused(void **state)
{
    (void)state;
    if (!BW_CFG_BANDS)
        skip();
    bw_dims_t d, dr;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, 3, 20), BW_OK);
    assert_int_equal(bw_dims_make(&dr, BW_SHAPE_REFLECTANCE, 1, 0, 1, 20), BW_OK);
    int32_t *x = xmalloc(bw_dims_samples(&dr) * 4);
    fill(x, 1, (uint32_t)bw_dims_samples(&dr), 0);
    bw_params_t pa;
    payload_t p;
    /* a reflectance, a byte budget, a transform basis, segments, Rice */
    for (unsigned c = 0; c < 5u; c++) {
        params(&pa, c == 1u ? BW_MODE_BYTES : BW_MODE_LOSSLESS, 0);
        pa.byte_budget = c == 1u ? 100u : 0u;
        pa.basis = c == 2u ? (uint8_t)BW_BASIS_53 : pa.basis;
        pa.segment_vectors = c == 3u;
        pa.flags = c == 4u ? BW_FLAG_RICE : 0u;
        assert_int_equal(test_encode(c ? &d : &dr, &pa, x, &p), BW_ERR_ARG);
        free(p.p);
    }
    /* a sample out of range */
    params(&pa, BW_MODE_LOSSLESS, 0);
    x[5] = BW_SAMPLE_MAX + 1;
    assert_int_equal(test_encode(&d, &pa, x, &p), BW_ERR_RANGE);
    free(p.p);
    x[5] = 0;
    /* a band range of a payload without band access */
    params(&pa, BW_MODE_LOSSLESS, 0);
    pa.band_access = 0;
    assert_int_equal(test_encode(&d, &pa, x, &p), BW_OK);
    int32_t r[3];
    assert_int_equal(range(p.p, p.len, &d, 0, 1, r), BW_ERR_ARG);
    free(p.p);
    free(x);
}

/* A core built without it (BW_CFG_BANDS 0, the 16 KiB device core) says
 * so: the encoder refuses it as not built, the decoders its record as an
 * extension they do not know. */
static void a_core_without_band_access_refuses_it(void **state)
{
    (void)state;
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, 2, 20), BW_OK);
    int32_t x[40];
    fill(x, 2, 20, 0);
    bw_params_t pa;
    params(&pa, BW_MODE_LOSSLESS, 0);
    payload_t p;
    assert_int_equal(test_encode(&d, &pa, x, &p), BW_CFG_BANDS ? BW_OK : BW_ERR_NOT_BUILT);
    free(p.p);
    read_golden("tests/golden/v7/spectra8_sed_maxerr_bands.bwv", &p);
    bw_header_t h;
    assert_int_equal(bw_header_read(p.p, p.len, &h), BW_CFG_BANDS ? BW_OK : BW_ERR_EXTENSION);
    free(p.p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_core_without_band_access_refuses_it),
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_damage),
        cmocka_unit_test(test_records_added),
        cmocka_unit_test(test_golden),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
