/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Sparse arrays of 32-element strips (sec. 4.3) and the algebra on
 * compressed arrays (sec. 4.4), against dense arithmetic.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_sparse.h"
#include "ref_test_util.h"

/* random vector where each strip is empty with probability pe and each
 * element of a present strip is zero with probability pz */
static void sparse_random(double *x, size_t n, double pe, double pz)
{
    for (size_t b = 0; b < n; b += 32) {
        int empty = rt_uniform() < pe;
        for (size_t i = b; i < b + 32 && i < n; i++)
            x[i] = (empty || rt_uniform() < pz) ? 0.0 : rt_uniform() * 2.0 - 1.0;
    }
}

static size_t strips_needed(const double *x, size_t n)
{
    size_t s = 0;
    for (size_t b = 0; b < n; b += 32) {
        int any = 0;
        for (size_t i = b; i < b + 32 && i < n; i++)
            any |= x[i] != 0.0;
        s += any;
    }
    return s;
}

static void dense_round_trip_and_counts(void **state)
{
    (void)state;
    rt_seed(30);
    const size_t n = 1000;
    double x[1000], y[1000];
    sparse_random(x, n, 0.4, 0.6);
    bwr_sparse_t a;
    bwr_sparse_init(&a, n);
    assert_int_equal(bwr_sparse_from_dense(&a, x, n), 0);
    bwr_sparse_to_dense(&a, y);
    assert_memory_equal(x, y, sizeof x);
    size_t nz = 0;
    for (size_t i = 0; i < n; i++) {
        nz += x[i] != 0.0;
        assert_true(bwr_sparse_get(&a, i) == x[i]);
        assert_int_equal(bwr_sparse_is_valid(&a, i), x[i] != 0.0);
    }
    assert_int_equal(bwr_sparse_count(&a), nz);
    assert_int_equal(a.nstrips, strips_needed(x, n));
    for (size_t k = 1; k < a.nstrips; k++)
        assert_true(a.s[k].number > a.s[k - 1].number);
    /* memory: 8-byte values and 8 bytes per strip */
    bwr_memory_t mem;
    bwr_sparse_memory(&a, 8, &mem);
    assert_int_equal(mem.values, nz);
    assert_int_equal(mem.data_bytes, 8 * nz);
    assert_int_equal(mem.strip_bytes, 8 * a.nstrips);
    assert_int_equal(mem.total_bytes, 8 * nz + 8 * a.nstrips);
    bwr_sparse_free(&a);
    /* a dense array of 2^14 doubles: 512 strips */
    double *d = malloc(16384 * sizeof *d);
    for (size_t i = 0; i < 16384; i++)
        d[i] = 1.0 + (double)i;
    bwr_sparse_init(&a, 16384);
    bwr_sparse_from_dense(&a, d, 16384);
    bwr_sparse_memory(&a, 8, &mem);
    assert_int_equal(mem.strips, 512);
    assert_int_equal(mem.total_bytes, 16384 * 8 + 512 * 8);
    bwr_sparse_free(&a);
    free(d);
}

static void set_invalidate_threshold(void **state)
{
    (void)state;
    bwr_sparse_t a;
    bwr_sparse_init(&a, 200);
    assert_int_equal(bwr_sparse_set(&a, 200, 1.0), -1);
    assert_int_equal(bwr_sparse_set(&a, 150, 3.0), 0);
    assert_int_equal(bwr_sparse_set(&a, 5, -1.0), 0);
    assert_int_equal(bwr_sparse_set(&a, 7, 2.0), 0);
    assert_int_equal(bwr_sparse_set(&a, 6, 0.5), 0);
    assert_int_equal(bwr_sparse_set(&a, 7, 4.0), 0); /* overwrite */
    assert_int_equal(a.nstrips, 2);
    assert_int_equal(a.s[0].number, 0);
    assert_int_equal(a.s[1].number, 4);
    assert_int_equal(a.s[0].valid, (1u << 5) | (1u << 6) | (1u << 7));
    assert_true(a.s[0].v[0] == -1.0 && a.s[0].v[1] == 0.5 && a.s[0].v[2] == 4.0);
    bwr_sparse_invalidate(&a, 6);
    assert_true(bwr_sparse_get(&a, 7) == 4.0 && bwr_sparse_get(&a, 6) == 0.0);
    bwr_sparse_invalidate(&a, 150); /* its strip goes */
    assert_int_equal(a.nstrips, 1);
    bwr_sparse_threshold(&a, 2.0); /* drops -1, keeps 4 */
    assert_int_equal(bwr_sparse_count(&a), 1);
    bwr_sparse_threshold(&a, 5.0);
    assert_int_equal(a.nstrips, 0);
    bwr_sparse_free(&a);
}

static void algebra_matches_dense(void **state)
{
    (void)state;
    rt_seed(31);
    const size_t n = 2000;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *r = malloc(n * sizeof *r);
    for (int trial = 0; trial < 50; trial++) {
        sparse_random(x, n, 0.5, 0.5);
        sparse_random(y, n, 0.5, 0.5);
        bwr_sparse_t a, b, c;
        bwr_sparse_init(&a, n);
        bwr_sparse_init(&b, n);
        bwr_sparse_init(&c, n);
        bwr_sparse_from_dense(&a, x, n);
        bwr_sparse_from_dense(&b, y, n);
        /* a + b: the union of strips and of valid elements */
        assert_int_equal(bwr_sparse_add(&c, &a, &b), 0);
        bwr_sparse_to_dense(&c, r);
        size_t su = 0;
        for (size_t i = 0; i < n; i++) {
            assert_true(r[i] == x[i] + y[i]);
            assert_int_equal(bwr_sparse_is_valid(&c, i), x[i] != 0.0 || y[i] != 0.0);
        }
        for (size_t s = 0; s < n; s += 32) {
            int any = 0;
            for (size_t i = s; i < s + 32 && i < n; i++)
                any |= x[i] != 0.0 || y[i] != 0.0;
            su += any;
        }
        assert_int_equal(c.nstrips, su);
        /* a - b, in place into a */
        assert_int_equal(bwr_sparse_sub(&a, &a, &b), 0);
        bwr_sparse_to_dense(&a, r);
        for (size_t i = 0; i < n; i++)
            assert_true(r[i] == x[i] - y[i]);
        /* scale and dot */
        bwr_sparse_from_dense(&a, x, n);
        assert_int_equal(bwr_sparse_scale(&c, &a, -2.5), 0);
        bwr_sparse_to_dense(&c, r);
        double d = 0.0;
        for (size_t i = 0; i < n; i++) {
            assert_true(r[i] == -2.5 * x[i]);
            d += x[i] * y[i];
        }
        assert_true(fabs(bwr_sparse_dot(&a, &b) - d) < 1e-12);
        /* copy is deep */
        bwr_sparse_copy(&c, &a);
        bwr_sparse_scale(&a, &a, 0.0);
        bwr_sparse_to_dense(&c, r);
        assert_memory_equal(r, x, n * sizeof *x);
        bwr_sparse_free(&a);
        bwr_sparse_free(&b);
        bwr_sparse_free(&c);
    }
    /* arrays of different lengths do not combine */
    bwr_sparse_t a, b;
    bwr_sparse_init(&a, 10);
    bwr_sparse_init(&b, 11);
    assert_int_equal(bwr_sparse_add(&a, &a, &b), -1);
    free(x);
    free(y);
    free(r);
}

static void element_type_ops(void **state)
{
    (void)state;
    bwr_type_t t = bwr_type_sparse(64);
    assert_int_equal(t.size, sizeof(bwr_sparse_t));
    bwr_sparse_t *arr = bwr_array_new(&t, 3);
    assert_non_null(arr);
    bwr_sparse_set(&arr[0], 3, 1.0);
    bwr_sparse_set(&arr[1], 40, 2.0);
    t.add(&t, &arr[2], &arr[0], &arr[1]);
    assert_true(bwr_sparse_get(&arr[2], 3) == 1.0 && bwr_sparse_get(&arr[2], 40) == 2.0);
    bwr_axpy(&t, &arr[2], 3.0, &arr[0], &arr[1]); /* arr[1] as scratch */
    assert_true(bwr_sparse_get(&arr[2], 3) == 4.0);
    assert_true(fabs(bwr_norm(&t, &arr[2]) - sqrt(16.0 + 4.0)) < 1e-15);
    t.zero(&t, &arr[2]);
    assert_int_equal(arr[2].nstrips, 0);
    bwr_array_free(&t, arr, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dense_round_trip_and_counts),
        cmocka_unit_test(set_invalidate_threshold),
        cmocka_unit_test(algebra_matches_dense),
        cmocka_unit_test(element_type_ops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
