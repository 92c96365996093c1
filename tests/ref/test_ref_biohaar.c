/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Float spherical Bio-Haar of the reference model (host-tools/ref): the
 * weights, the exact inverse at every level, constants, the area-weighted
 * mean, the norms and orthogonality of the wavelets, and the same code on
 * reals, Spectrum vectors and sparse arrays.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_biohaar.h"
#include "bwr_sparse.h"
#include "bwr_geodesic.h"
#include "ref_test_util.h"

#define PI 3.14159265358979323846

static void weights_are_area_fractions_and_areas_tile(void **state)
{
    (void)state;
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, 7), -1);
    assert_int_equal(bwr_sphere_init(&s, 5), 0);
    for (unsigned j = 0; j <= 5; j++) {
        size_t nt = (size_t)4 << (2 * j);
        double sum = 0.0;
        for (size_t t = 0; t < nt; t++)
            sum += bwr_sphere_area(&s, j, t);
        assert_true(fabs(sum - 2.0 * PI) < 1e-12);
        if (j == 5)
            break;
        for (size_t p = 0; p < nt; p++) {
            double ch = 0.0;
            for (unsigned i = 0; i < 4; i++)
                ch += bwr_sphere_area(&s, j + 1, 4 * p + i);
            /* the four children tile their parent */
            assert_true(fabs(ch - bwr_sphere_area(&s, j, p)) < 1e-14);
        }
    }
    /* level 1 by hand: base 0 = (Z, X, Y), its children from bwr_geodesic.c */
    bwr_tri_t tri[16];
    bwr_grid_triangles(1, tri);
    double a[4], tot = 0.0;
    for (unsigned i = 0; i < 4; i++) {
        a[i] = bwr_tri_area(tri[i].v[0], tri[i].v[1], tri[i].v[2]);
        tot += a[i];
    }
    assert_true(fabs(tot - PI / 2.0) < 1e-14);
    assert_true(a[0] > a[1]); /* the centre child is the largest */
    for (unsigned i = 0; i < 4; i++)
        assert_true(fabs(s.weight[i] - a[i] / tot) < 1e-15);
    bwr_sphere_free(&s);
}

static void round_trip_every_level_within_1e_12(void **state)
{
    (void)state;
    rt_seed(1);
    for (unsigned L = 0; L <= 6; L++) {
        bwr_sphere_t s;
        assert_int_equal(bwr_sphere_init(&s, L), 0);
        double *x = malloc(s.n * sizeof *x), *c = malloc(s.n * sizeof *c),
               *y = malloc(s.n * sizeof *y);
        rt_fill(x, s.n, -1.0, 3.0);
        x[s.n / 3] = 1e3; /* a narrow peak */
        assert_int_equal(bwr_biohaar_forward(&s, &bwr_type_real, x, c), 0);
        assert_int_equal(bwr_biohaar_inverse(&s, &bwr_type_real, c, y), 0);
        assert_true(rt_max_abs_diff(x, y, s.n) < 1e-12 * 1e3);
        /* the transform really changes the data */
        if (L > 0)
            assert_true(rt_max_abs_diff(x, c, s.n) > 0.1);
        free(x);
        free(c);
        free(y);
        bwr_sphere_free(&s);
    }
}

static void constant_has_no_details_and_scaling_is_area_weighted_mean(void **state)
{
    (void)state;
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, 4), 0);
    double *x = malloc(s.n * sizeof *x), *c = malloc(s.n * sizeof *c);
    for (size_t i = 0; i < s.n; i++)
        x[i] = 0.37;
    bwr_biohaar_forward(&s, &bwr_type_real, x, c);
    for (size_t i = 0; i < 4; i++)
        assert_true(fabs(c[i] - 0.37) < 1e-15);
    for (size_t i = 4; i < s.n; i++)
        assert_true(fabs(c[i]) < 1e-15);
    /* a random signal: the base coefficient is sum(a_t x_t) / sum(a_t) */
    rt_seed(2);
    rt_fill(x, s.n, 0.0, 1.0);
    bwr_biohaar_forward(&s, &bwr_type_real, x, c);
    size_t per = s.n / 4;
    for (size_t b = 0; b < 4; b++) {
        double num = 0.0, den = 0.0;
        for (size_t t = b * per; t < (b + 1) * per; t++) {
            num += bwr_sphere_area(&s, 4, t) * x[t];
            den += bwr_sphere_area(&s, 4, t);
        }
        assert_true(fabs(c[b] - num / den) < 1e-14);
    }
    /* one parent by hand: d_m = x_m - x_0 relative to the centre child */
    size_t p = 77; /* parent at level 3 */
    for (unsigned m = 1; m < 4; m++)
        assert_true(fabs(c[bwr_sphere_level_start(3) + 3 * p + m - 1] -
                         (x[4 * p + m] - x[4 * p])) < 1e-15);
    free(x);
    free(c);
    bwr_sphere_free(&s);
}

/* weighted inner product of two level-L signals */
static double wdot(const bwr_sphere_t *s, const double *a, const double *b)
{
    double d = 0.0;
    for (size_t t = 0; t < s->n; t++)
        d += bwr_sphere_area(s, s->level, t) * a[t] * b[t];
    return d;
}

static void wavelet_norms_and_orthogonality(void **state)
{
    (void)state;
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, 3), 0);
    double *c = calloc(s.n, sizeof *c), *f = malloc(s.n * sizeof *f), *g = malloc(s.n * sizeof *g);
    /* every basis function: |psi|^2 = psi2, and zero mean for details */
    for (size_t k = 0; k < s.n; k++) {
        c[k] = 1.0;
        bwr_biohaar_inverse(&s, &bwr_type_real, c, f);
        c[k] = 0.0;
        assert_true(fabs(wdot(&s, f, f) - s.psi2[k]) < 1e-14);
        double mean = 0.0;
        for (size_t t = 0; t < s.n; t++)
            mean += bwr_sphere_area(&s, 3, t) * f[t];
        if (k >= 4)
            assert_true(fabs(mean) < 1e-15);
    }
    /* details of different parents are orthogonal; of one parent, -a_m a_k / a_P */
    size_t pairs[][2] = {{4, 16}, {5, 70}, {20, 100}, {16, 17}, {100, 101}, {200, 255}};
    for (size_t q = 0; q < sizeof pairs / sizeof pairs[0]; q++) {
        size_t k1 = pairs[q][0], k2 = pairs[q][1];
        c[k1] = 1.0;
        bwr_biohaar_inverse(&s, &bwr_type_real, c, f);
        c[k1] = 0.0;
        c[k2] = 1.0;
        bwr_biohaar_inverse(&s, &bwr_type_real, c, g);
        c[k2] = 0.0;
        int j1 = s.coef_level[k1], j2 = s.coef_level[k2];
        size_t p1 = (k1 - bwr_sphere_level_start((unsigned)j1)) / 3;
        size_t p2 = (k2 - bwr_sphere_level_start((unsigned)j2)) / 3;
        double d = wdot(&s, f, g);
        if (j1 == j2 && p1 == p2) {
            unsigned m1 = (unsigned)((k1 - bwr_sphere_level_start((unsigned)j1)) % 3) + 1;
            unsigned m2 = (unsigned)((k2 - bwr_sphere_level_start((unsigned)j2)) % 3) + 1;
            double am = bwr_sphere_area(&s, (unsigned)j1 + 1, 4 * p1 + m1);
            double ak = bwr_sphere_area(&s, (unsigned)j1 + 1, 4 * p1 + m2);
            double aP = bwr_sphere_area(&s, (unsigned)j1, p1);
            assert_true(fabs(d + am * ak / aP) < 1e-15);
        } else {
            assert_true(fabs(d) < 1e-15);
        }
    }
    free(c);
    free(f);
    free(g);
    bwr_sphere_free(&s);
}

/* the same transform code on Spectrum vectors gives, band by band, the
 * transform of the reals */
static void vectors_transform_band_by_band(void **state)
{
    (void)state;
    const size_t B = 5;
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, 3), 0);
    bwr_type_t vt = bwr_type_vector(B);
    double *x = malloc(s.n * B * sizeof *x), *c = malloc(s.n * B * sizeof *c);
    double *xb = malloc(s.n * sizeof *xb), *cb = malloc(s.n * sizeof *cb);
    rt_seed(3);
    rt_fill(x, s.n * B, 0.0, 2.0);
    assert_int_equal(bwr_biohaar_forward(&s, &vt, x, c), 0);
    for (size_t b = 0; b < B; b++) {
        for (size_t t = 0; t < s.n; t++)
            xb[t] = x[t * B + b];
        bwr_biohaar_forward(&s, &bwr_type_real, xb, cb);
        for (size_t t = 0; t < s.n; t++)
            assert_true(fabs(cb[t] - c[t * B + b]) < 1e-14);
    }
    double *y = malloc(s.n * B * sizeof *y);
    assert_int_equal(bwr_biohaar_inverse(&s, &vt, c, y), 0);
    assert_true(rt_max_abs_diff(x, y, s.n * B) < 1e-13);
    free(x);
    free(c);
    free(xb);
    free(cb);
    free(y);
    bwr_sphere_free(&s);
}

/* and on compressed arrays: the inverse run on sparse elements equals the
 * dense inverse of the same (thresholded) coefficients */
static void sparse_elements_give_the_dense_result(void **state)
{
    (void)state;
    const size_t B = 100;
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, 2), 0);
    bwr_type_t vt = bwr_type_vector(B), st = bwr_type_sparse(B);
    double *x = malloc(s.n * B * sizeof *x), *c = malloc(s.n * B * sizeof *c);
    double *y = malloc(s.n * B * sizeof *y);
    rt_seed(4);
    rt_fill(x, s.n * B, -1.0, 1.0);
    for (size_t i = 0; i < s.n * B; i++)
        if (fabs(x[i]) < 0.8)
            x[i] = 0.0; /* mostly empty strips */
    bwr_sparse_t *sc = bwr_array_new(&st, s.n), *sy = bwr_array_new(&st, s.n);
    assert_non_null(sc);
    for (size_t t = 0; t < s.n; t++)
        assert_int_equal(bwr_sparse_from_dense(&sc[t], x + t * B, B), 0);
    unsigned long fails = bwr_sparse_failures();
    assert_int_equal(bwr_biohaar_inverse(&s, &st, sc, sy), 0);
    assert_int_equal(bwr_biohaar_inverse(&s, &vt, x, y), 0);
    assert_int_equal(bwr_sparse_failures(), fails);
    double *row = malloc(B * sizeof *row);
    for (size_t t = 0; t < s.n; t++) {
        bwr_sparse_to_dense(&sy[t], row);
        assert_true(rt_max_abs_diff(row, y + t * B, B) < 1e-14);
    }
    /* and forward on sparse equals forward on dense */
    bwr_sparse_t *sf = bwr_array_new(&st, s.n);
    assert_int_equal(bwr_biohaar_forward(&s, &st, sy, sf), 0);
    for (size_t t = 0; t < s.n; t++) {
        bwr_sparse_to_dense(&sf[t], row);
        assert_true(rt_max_abs_diff(row, x + t * B, B) < 1e-14);
    }
    bwr_array_free(&st, sc, s.n);
    bwr_array_free(&st, sy, s.n);
    bwr_array_free(&st, sf, s.n);
    free(row);
    free(x);
    free(c);
    free(y);
    bwr_sphere_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(weights_are_area_fractions_and_areas_tile),
        cmocka_unit_test(round_trip_every_level_within_1e_12),
        cmocka_unit_test(constant_has_no_details_and_scaling_is_area_weighted_mean),
        cmocka_unit_test(wavelet_norms_and_orthogonality),
        cmocka_unit_test(vectors_transform_band_by_band),
        cmocka_unit_test(sparse_elements_give_the_dense_result),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
