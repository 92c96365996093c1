/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Interpolation (sec. 4.5): cubic B-spline on the spectral axis, barycentric
 * (C0) and modified Shepard (C1) on the geodesic sphere: exact at the
 * samples / centres, constants reproduced, continuity and convergence.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_interp.h"
#include "bwr_geodesic.h"
#include "ref_test_util.h"

static void bspline_exact_at_samples_and_constants(void **state)
{
    (void)state;
    rt_seed(40);
    double f[64], c[64];
    for (size_t n = 1; n <= 64; n++) {
        rt_fill(f, n, -1.0, 2.0);
        bwr_bspline_coefficients(f, n, c);
        for (size_t k = 0; k < n; k++)
            assert_true(fabs(bwr_bspline_eval(c, n, (double)k) - f[k]) < 1e-12);
        /* the coefficients differ from the samples (it is not the identity) */
        if (n >= 3) {
            double d = 0.0;
            for (size_t k = 0; k < n; k++)
                d = fmax(d, fabs(c[k] - f[k]));
            assert_true(d > 1e-3);
        }
    }
    for (size_t k = 0; k < 20; k++)
        f[k] = 0.37;
    bwr_bspline_coefficients(f, 20, c);
    for (double x = -2.0; x < 22.0; x += 0.137)
        assert_true(fabs(bwr_bspline_eval(c, 20, x) - 0.37) < 1e-13);
}

static double smooth1(double x)
{
    return sin(x) + 0.3 * cos(2.3 * x);
}

static void bspline_converges_at_fourth_order(void **state)
{
    (void)state;
    /* samples of a smooth function on [0, 4] with h and h/2; error at the
     * midpoints of the interior */
    double err[2];
    for (int r = 0; r < 2; r++) {
        size_t n = r == 0 ? 41 : 81;
        double h = 4.0 / (double)(n - 1), f[81], c[81];
        for (size_t k = 0; k < n; k++)
            f[k] = smooth1((double)k * h);
        bwr_bspline_coefficients(f, n, c);
        double e = 0.0;
        for (size_t k = n / 4; k < 3 * n / 4; k++) {
            double x = ((double)k + 0.5) * h;
            e = fmax(e, fabs(bwr_bspline_eval(c, n, (double)k + 0.5) - smooth1(x)));
        }
        err[r] = e;
    }
    assert_true(err[0] < 1e-4);
    assert_true(err[0] / err[1] > 12.0); /* ~16 for h^4 */
}

/* a smooth test function on the hemisphere */
static double sfun(const double d[3])
{
    return 1.0 + 0.5 * d[0] - 0.3 * d[1] + d[2] * d[2];
}

static void random_direction(double d[3])
{
    for (;;) {
        d[0] = 2.0 * rt_uniform() - 1.0;
        d[1] = 2.0 * rt_uniform() - 1.0;
        d[2] = rt_uniform();
        double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (r > 0.1 && r <= 1.0) {
            d[0] /= r;
            d[1] /= r;
            d[2] /= r;
            return;
        }
    }
}

static void sphere_exact_at_centres_and_constants(void **state)
{
    (void)state;
    rt_seed(41);
    for (unsigned L = 0; L <= 4; L++) {
        bwr_sinterp_t s;
        assert_int_equal(bwr_sinterp_init(&s, L), 0);
        /* Euler: V - E + F on the hemisphere (a disc) = 1 */
        size_t E = (3 * s.n + (4u << L)) / 2; /* boundary edges counted once */
        assert_int_equal((long)s.nv - (long)E + (long)s.n, 1);
        double *v = malloc(s.n * sizeof *v);
        rt_fill(v, s.n, 0.0, 1.0);
        for (size_t t = 0; t < s.n; t++) {
            assert_true(fabs(bwr_sinterp_linear(&s, v, s.centre[t]) - v[t]) < 1e-12);
            assert_true(fabs(bwr_sinterp_smooth(&s, v, s.centre[t]) - v[t]) < 1e-12);
        }
        for (size_t t = 0; t < s.n; t++)
            v[t] = 2.5;
        for (int q = 0; q < 200; q++) {
            double d[3];
            random_direction(d);
            assert_true(fabs(bwr_sinterp_linear(&s, v, d) - 2.5) < 1e-12);
            assert_true(fabs(bwr_sinterp_smooth(&s, v, d) - 2.5) < 1e-12);
        }
        double below[3] = {0.0, 0.6, -0.8};
        assert_true(isnan(bwr_sinterp_linear(&s, v, below)));
        assert_true(isnan(bwr_sinterp_smooth(&s, v, below)));
        free(v);
        bwr_sinterp_free(&s);
    }
}

/* second difference along a great circle through d, relative to h */
static double kink(const bwr_sinterp_t *s, const double *v, const double d[3], const double t[3],
                   double h, int smooth)
{
    double p[3][3];
    for (int k = -1; k <= 1; k++) {
        double a = (double)k * h;
        for (int i = 0; i < 3; i++)
            p[k + 1][i] = cos(a) * d[i] + sin(a) * t[i];
    }
    double f0 = smooth ? bwr_sinterp_smooth(s, v, p[0]) : bwr_sinterp_linear(s, v, p[0]);
    double f1 = smooth ? bwr_sinterp_smooth(s, v, p[1]) : bwr_sinterp_linear(s, v, p[1]);
    double f2 = smooth ? bwr_sinterp_smooth(s, v, p[2]) : bwr_sinterp_linear(s, v, p[2]);
    return fabs(f0 - 2.0 * f1 + f2) / h;
}

static void continuity_c0_and_c1(void **state)
{
    (void)state;
    rt_seed(42);
    bwr_sinterp_t s;
    assert_int_equal(bwr_sinterp_init(&s, 3), 0);
    double *v = malloc(s.n * sizeof *v);
    rt_fill(v, s.n, 0.0, 1.0);
    /* across the edge between a centre and a vertex of its triangle: the
     * linear scheme is continuous but has a kink, the smooth one has none */
    int kinks = 0;
    for (size_t t = 5; t < s.n; t += 37) {
        const double *c = s.centre[t], *w = s.vert[s.tv[t][0]];
        double m[3], n[3], tan[3];
        for (int i = 0; i < 3; i++)
            m[i] = 0.5 * (c[i] + w[i]);
        double r = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
        for (int i = 0; i < 3; i++)
            m[i] /= r;
        /* tangent across the arc c-w: normal of the plane (c, w) */
        n[0] = c[1] * w[2] - c[2] * w[1];
        n[1] = c[2] * w[0] - c[0] * w[2];
        n[2] = c[0] * w[1] - c[1] * w[0];
        r = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int i = 0; i < 3; i++)
            tan[i] = n[i] / r;
        /* C0: values on both sides converge */
        double a[3], b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = m[i] + 1e-10 * tan[i];
            b[i] = m[i] - 1e-10 * tan[i];
        }
        assert_true(fabs(bwr_sinterp_linear(&s, v, a) - bwr_sinterp_linear(&s, v, b)) < 1e-8);
        assert_true(fabs(bwr_sinterp_smooth(&s, v, a) - bwr_sinterp_smooth(&s, v, b)) < 1e-8);
        /* slopes: the linear scheme's second difference / h stays finite as
         * h shrinks (a kink), the smooth scheme's goes to 0 */
        double kl1 = kink(&s, v, m, tan, 1e-4, 0), kl2 = kink(&s, v, m, tan, 1e-6, 0);
        double ks1 = kink(&s, v, m, tan, 1e-4, 1), ks2 = kink(&s, v, m, tan, 1e-6, 1);
        if (kl1 > 1e-3 && kl2 > 0.5 * kl1)
            kinks++;
        assert_true(ks2 < 0.05 * ks1 + 1e-7);
    }
    assert_true(kinks > 0);
    free(v);
    bwr_sinterp_free(&s);
}

static void sphere_interpolation_converges(void **state)
{
    (void)state;
    rt_seed(43);
    double prev_l = INFINITY, prev_s = INFINITY;
    for (unsigned L = 2; L <= 5; L++) {
        bwr_sinterp_t s;
        assert_int_equal(bwr_sinterp_init(&s, L), 0);
        double *v = malloc(s.n * sizeof *v);
        for (size_t t = 0; t < s.n; t++)
            v[t] = sfun(s.centre[t]);
        double el = 0.0, es = 0.0;
        rt_seed(44);
        for (int q = 0; q < 300; q++) {
            double d[3];
            random_direction(d);
            el = fmax(el, fabs(bwr_sinterp_linear(&s, v, d) - sfun(d)));
            es = fmax(es, fabs(bwr_sinterp_smooth(&s, v, d) - sfun(d)));
        }
        print_message("level %u: max error linear %.3g, smooth %.3g\n", L, el, es);
        assert_true(el < 0.7 * prev_l);
        assert_true(es < 0.7 * prev_s);
        prev_l = el;
        prev_s = es;
        free(v);
        bwr_sinterp_free(&s);
    }
    /* first order: the vertex values are means of the neighbouring centres */
    assert_true(prev_l < 0.02 && prev_s < 0.02);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bspline_exact_at_samples_and_constants),
        cmocka_unit_test(bspline_converges_at_fourth_order),
        cmocka_unit_test(sphere_exact_at_centres_and_constants),
        cmocka_unit_test(continuity_c0_and_c1),
        cmocka_unit_test(sphere_interpolation_converges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
