/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The product's interpolation of decoded samples (host-tools/lib/bwh_interp.c,
 * on the codec's host grid) against the reference model's own
 * (host-tools/ref/bwr_interp.c, on its own grid): the same cubic B-spline
 * across the bands to the bit, and the same barycentric interpolation over
 * the triangle centres up to the grids' solid angles (about 1e-13 apart).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_interp.h"
#include "bwr_interp.h"
#include "ref_test_util.h"

#define PI 3.14159265358979323846

static void the_bspline_is_the_same_to_the_bit(void **state)
{
    (void)state;
    rt_seed(3);
    double f[80], ch[80], cr[80];
    for (size_t n = 1; n <= 80; n++) {
        rt_fill(f, n, -2.0, 3.0);
        bwh_bspline_coefficients(f, n, ch);
        bwr_bspline_coefficients(f, n, cr);
        assert_memory_equal(ch, cr, n * sizeof *ch);
        for (double x = -3.0; x < (double)n + 3.0; x += 0.0731) {
            double a = bwh_bspline_eval(ch, n, x), b = bwr_bspline_eval(cr, n, x);
            assert_memory_equal(&a, &b, sizeof a);
        }
    }
}

static void the_sphere_interpolation_agrees_at_every_level(void **state)
{
    (void)state;
    rt_seed(5);
    double worst = 0.0;
    for (unsigned l = 0; l <= 6; l++) {
        bwh_sphere_interp_t h;
        bwr_sinterp_t r;
        assert_int_equal(bwh_sphere_interp_init(&h, l), 0);
        assert_int_equal(bwr_sinterp_init(&r, l), 0);
        assert_int_equal(h.n, r.n);
        assert_int_equal(h.nv, r.nv);
        double *v = malloc(h.n * sizeof *v);
        assert_non_null(v);
        rt_fill(v, h.n, -0.5, 2.0);
        for (int k = 0; k < 20000; k++) {
            double z = rt_uniform(), phi = 2.0 * PI * rt_uniform(), s = sqrt(1.0 - z * z);
            double d[3] = {s * cos(phi), s * sin(phi), z};
            double a = bwh_sphere_interp(&h, v, d), b = bwr_sinterp_linear(&r, v, d);
            worst = fmax(worst, fabs(a - b));
        }
        /* exact at the centres, and NAN below the horizon */
        for (size_t t = 0; t < h.n; t++)
            assert_true(fabs(bwh_sphere_interp(&h, v, h.centre[t]) - v[t]) < 1e-12);
        assert_true(isnan(bwh_sphere_interp(&h, v, (double[3]){0.0, 0.6, -0.8})));
        free(v);
        bwh_sphere_interp_free(&h);
        bwr_sinterp_free(&r);
    }
    printf("largest difference (values in [-0.5, 2]): %.3g\n", worst);
    assert_true(worst < 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_bspline_is_the_same_to_the_bit),
        cmocka_unit_test(the_sphere_interpolation_agrees_at_every_level),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
