/* SPDX-License-Identifier: BSD-2-Clause */
/* Sparse strip arrays: the operators on the compressed form agree with the
 * same arithmetic on dense arrays. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_strip.h"

static uint64_t rng = 88172645463325252ull;
static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

typedef struct {
    bw_sparse_t s;
    uint32_t *no, *mask, *first;
    int32_t *val;
} owned_t;

static void owned_init(owned_t *o, uint32_t length)
{
    size_t ns = bw_sparse_strips_bound(length) + 1;
    o->no = malloc(ns * 4);
    o->mask = malloc(ns * 4);
    o->first = malloc(ns * 4);
    o->val = malloc((length + 1) * 4);
    assert_int_equal(bw_sparse_init(&o->s, length, o->no, o->mask, o->first, (uint32_t)ns, o->val,
                                     length + 1),
                     BW_OK);
}

static void owned_free(owned_t *o)
{
    free(o->no);
    free(o->mask);
    free(o->first);
    free(o->val);
}

/* Random sparse-ish data: runs of zeros, whole empty strips, extremes. */
static void fill(int32_t *d, uint32_t n, unsigned density_pct)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t r = rnd();
        if ((i / 32) % 5 == 3 || r % 100 >= density_pct)
            d[i] = 0;
        else if (r % 97 == 0)
            d[i] = (r & 1) ? INT32_MAX : INT32_MIN;
        else
            d[i] = (int32_t)(rnd() % 20001) - 10000;
    }
}

static int32_t sat(int64_t v) { return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v; }

static const uint32_t lengths[] = {0, 1, 31, 32, 33, 64, 100, 1000, 4096, 16411};

static void dense_round_trip_keeps_every_non_zero_element(void **state)
{
    (void)state;
    for (size_t li = 0; li < sizeof lengths / sizeof *lengths; li++) {
        uint32_t n = lengths[li];
        int32_t *d = malloc((n + 1) * 4), *e = malloc((n + 1) * 4);
        owned_t a;
        owned_init(&a, n);
        fill(d, n, 30);
        assert_int_equal(bw_sparse_from_dense(&a.s, d, 0), BW_OK);
        bw_sparse_to_dense(&a.s, e);
        assert_memory_equal(d, e, n * 4);
        uint32_t nz = 0;
        for (uint32_t i = 0; i < n; i++) {
            nz += d[i] != 0;
            assert_int_equal(bw_sparse_get(&a.s, i), d[i]);
        }
        assert_int_equal(a.s.n_values, nz);
        /* empty strips are absent */
        for (uint32_t k = 0; k < a.s.n_strips; k++) {
            assert_int_not_equal(a.s.mask[k], 0);
            if (k)
                assert_true(a.s.strip_no[k] > a.s.strip_no[k - 1]);
        }
        owned_free(&a);
        free(d);
        free(e);
    }
}

static void threshold_drops_small_elements(void **state)
{
    (void)state;
    uint32_t n = 1000;
    int32_t d[1000], e[1000];
    owned_t a;
    owned_init(&a, n);
    fill(d, n, 60);
    assert_int_equal(bw_sparse_from_dense(&a.s, d, 5000), BW_OK);
    bw_sparse_to_dense(&a.s, e);
    for (uint32_t i = 0; i < n; i++)
        assert_int_equal(e[i], (d[i] > 5000 || d[i] < -5000) ? d[i] : 0);
    owned_free(&a);
}

static void add_sub_scale_dot_match_dense_arithmetic(void **state)
{
    (void)state;
    for (size_t li = 0; li < sizeof lengths / sizeof *lengths; li++) {
        for (unsigned dens = 0; dens <= 100; dens += 25) {
            uint32_t n = lengths[li];
            size_t sz = (n + 1) * 4;
            int32_t *da = malloc(sz), *db = malloc(sz), *r = malloc(sz), *got = malloc(sz);
            owned_t a, b, o;
            owned_init(&a, n);
            owned_init(&b, n);
            owned_init(&o, n);
            fill(da, n, dens);
            fill(db, n, 100 - dens / 2);
            /* make some elements cancel exactly */
            for (uint32_t i = 0; i < n; i += 7)
                db[i] = da[i];
            assert_int_equal(bw_sparse_from_dense(&a.s, da, 0), BW_OK);
            assert_int_equal(bw_sparse_from_dense(&b.s, db, 0), BW_OK);

            assert_int_equal(bw_sparse_add(&a.s, &b.s, &o.s), BW_OK);
            bw_sparse_to_dense(&o.s, got);
            for (uint32_t i = 0; i < n; i++)
                r[i] = sat((int64_t)da[i] + db[i]);
            assert_memory_equal(got, r, n * 4);
            for (uint32_t k = 0; k < o.s.n_strips; k++)
                assert_int_not_equal(o.s.mask[k], 0);

            assert_int_equal(bw_sparse_sub(&a.s, &b.s, &o.s), BW_OK);
            bw_sparse_to_dense(&o.s, got);
            uint32_t nz = 0;
            for (uint32_t i = 0; i < n; i++) {
                r[i] = sat((int64_t)da[i] - db[i]);
                nz += r[i] != 0;
            }
            assert_memory_equal(got, r, n * 4);
            assert_int_equal(o.s.n_values, nz); /* cancelled elements invalidated */

            int32_t nums[] = {0, 1, -1, 3, 12345, -70000};
            for (size_t ni = 0; ni < 6; ni++) {
                for (unsigned sh = 0; sh < 32; sh += 5) {
                    assert_int_equal(bw_sparse_scale(&a.s, nums[ni], sh, &o.s), BW_OK);
                    bw_sparse_to_dense(&o.s, got);
                    for (uint32_t i = 0; i < n; i++) {
                        int64_t p = (int64_t)da[i] * nums[ni];
                        if (sh)
                            p = (p + ((int64_t)1 << (sh - 1))) >> sh; /* arithmetic on gcc */
                        assert_int_equal(got[i], sat(p));
                    }
                }
            }

            /* the dot product wraps modulo 2^64 like the core's */
            int64_t dot;
            uint64_t ref = 0;
            assert_int_equal(bw_sparse_dot(&a.s, &b.s, &dot), BW_OK);
            for (uint32_t i = 0; i < n; i++)
                ref += (uint64_t)((int64_t)da[i] * db[i]);
            assert_true((uint64_t)dot == ref);

            owned_free(&a);
            owned_free(&b);
            owned_free(&o);
            free(da);
            free(db);
            free(r);
            free(got);
        }
    }
}

static void scale_works_in_place(void **state)
{
    (void)state;
    uint32_t n = 4096;
    int32_t *d = malloc(n * 4), *got = malloc(n * 4);
    owned_t a;
    owned_init(&a, n);
    fill(d, n, 40);
    assert_int_equal(bw_sparse_from_dense(&a.s, d, 0), BW_OK);
    assert_int_equal(bw_sparse_scale(&a.s, 3, 2, &a.s), BW_OK);
    bw_sparse_to_dense(&a.s, got);
    for (uint32_t i = 0; i < n; i++)
        assert_int_equal(got[i], sat(((int64_t)d[i] * 3 + 2) >> 2));
    owned_free(&a);
    free(d);
    free(got);
}

static void operators_reject_mismatched_or_small_storage(void **state)
{
    (void)state;
    owned_t a, b, o;
    owned_init(&a, 100);
    owned_init(&b, 101);
    owned_init(&o, 100);
    int64_t dot;
    assert_int_equal(bw_sparse_add(&a.s, &b.s, &o.s), BW_ERR_MISMATCH);
    assert_int_equal(bw_sparse_dot(&a.s, &b.s, &dot), BW_ERR_MISMATCH);
    assert_int_equal(bw_sparse_add(&a.s, &o.s, &a.s), BW_ERR_ARG);
    /* storage for one strip only */
    int32_t d[100];
    for (int i = 0; i < 100; i++)
        d[i] = i + 1;
    uint32_t no[1], mask[1], first[1];
    int32_t val[32];
    bw_sparse_t small;
    assert_int_equal(bw_sparse_init(&small, 100, no, mask, first, 1, val, 32), BW_OK);
    assert_int_equal(bw_sparse_from_dense(&small, d, 0), BW_ERR_OUTPUT_FULL);
    assert_int_equal(bw_sparse_init(NULL, 1, no, mask, first, 1, val, 1), BW_ERR_ARG);
    owned_free(&a);
    owned_free(&b);
    owned_free(&o);
}

static void memory_accounting_counts_values_and_strips(void **state)
{
    (void)state;
    int32_t d[96] = {0};
    d[0] = 1;
    d[5] = 2;
    d[70] = 3;
    owned_t a;
    owned_init(&a, 96);
    assert_int_equal(bw_sparse_from_dense(&a.s, d, 0), BW_OK);
    assert_int_equal(a.s.n_strips, 2);
    assert_int_equal(a.s.n_values, 3);
    assert_int_equal(bw_sparse_bytes(&a.s), 3 * 4 + 2 * 12);
    owned_free(&a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dense_round_trip_keeps_every_non_zero_element),
        cmocka_unit_test(threshold_drops_small_elements),
        cmocka_unit_test(add_sub_scale_dot_match_dense_arithmetic),
        cmocka_unit_test(scale_works_in_place),
        cmocka_unit_test(operators_reject_mismatched_or_small_storage),
        cmocka_unit_test(memory_accounting_counts_values_and_strips),
    };
    return cmocka_run_group_tests_name("strip", tests, NULL, NULL);
}
