/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Projection of scattered measurements onto the geodesic grid
 * (bwr_project.h): the paper's 474 goniometer directions, imitated by a
 * spherical Fibonacci set on the hemisphere, carrying the modified Phong
 * BRDF; projected to level 4 (1024 triangles) and compared with the BRDF
 * sampled at the triangle centres, as `brdfwave synth` does.
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

#include "bwr_project.h"
#include "bwr_geodesic.h"
#include "ref_test_util.h"

#define PI 3.14159265358979323846

/* modified Phong (Lafortune and Willems), as host-tools/lib/brdf_models.h */
typedef struct {
    double kd, ks, n;
} phong_t;

static double phong(const phong_t *p, const double wi[3], const double wo[3])
{
    double c = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2];
    double f = p->kd / PI;
    if (c > 0.0)
        f += p->ks * (p->n + 2.0) / (2.0 * PI) * pow(c, p->n);
    return f;
}

static const phong_t phong1 = {0.75, 0.25, 20.0}, phong2 = {0.5, 0.5, 50.0};

/* n points of a spherical Fibonacci set on the upper hemisphere: equal-area
 * bands in z = cos theta, golden-angle steps in phi */
static void fibonacci(size_t n, double (*d)[3])
{
    const double golden = PI * (3.0 - sqrt(5.0));
    for (size_t i = 0; i < n; i++) {
        double z = 1.0 - ((double)i + 0.5) / (double)n, r = sqrt(1.0 - z * z);
        double phi = golden * (double)i;
        d[i][0] = r * cos(phi);
        d[i][1] = r * sin(phi);
        d[i][2] = z;
    }
}

/* Relative L2 error (paper eq. 8) of the projection of Phong measured at n
 * Fibonacci directions, incidence theta_deg, against Phong at the centres. */
static double projection_error(const phong_t *p, double theta_deg, size_t n, unsigned level,
                               unsigned k)
{
    size_t nt = bwr_grid_count(level);
    double(*d)[3] = malloc(n * sizeof *d), *v = malloc(n * sizeof *v);
    double(*c)[3] = malloc(nt * sizeof *c), *out = malloc(nt * sizeof *out);
    assert_non_null(d);
    assert_non_null(v);
    assert_non_null(c);
    assert_non_null(out);
    double wi[3];
    bwr_dir_from_degrees(theta_deg, 0.0, wi);
    fibonacci(n, d);
    for (size_t i = 0; i < n; i++)
        v[i] = phong(p, wi, d[i]);
    assert_int_equal(bwr_project((const double(*)[3])d, v, n, 1, level, k, out), 0);
    assert_int_equal(bwr_grid_centres(level, c, NULL), 0);
    double e = 0.0, f = 0.0;
    for (size_t t = 0; t < nt; t++) {
        double x = phong(p, wi, c[t]);
        e += (out[t] - x) * (out[t] - x);
        f += x * x;
    }
    free(d);
    free(v);
    free(c);
    free(out);
    return sqrt(e / f);
}

static void phong_474_directions_to_level_4(void **state)
{
    (void)state;
    const struct {
        const char *name;
        const phong_t *p;
        double bound;
    } sets[] = {{"phong1", &phong1, 0.05}, {"phong2", &phong2, 0.15}};
    for (size_t s = 0; s < 2; s++)
        for (double th = 0.0; th <= 75.0; th += 25.0) {
            double e = projection_error(sets[s].p, th, 474, 4, 0);
            double e1 = projection_error(sets[s].p, th, 474, 4, 1);
            double e4x = projection_error(sets[s].p, th, 4 * 474, 4, 0);
            printf("%s theta_i %2.0f: relative L2 error %.4f (k = %u), nearest only %.4f, "
                   "1896 directions %.4f\n",
                   sets[s].name, th, e, BWR_PROJECT_K_DEFAULT, e1, e4x);
            assert_true(e < sets[s].bound);
            assert_true(e < 0.8 * e1);   /* better than the nearest measurement */
            assert_true(e4x < 0.6 * e);  /* converges with denser measurements */
        }
}

static void constants_exact_and_values_bounded(void **state)
{
    (void)state;
    rt_seed(71);
    size_t n = 474;
    double(*d)[3] = malloc(n * sizeof *d), *v = malloc(n * sizeof *v);
    size_t nt = bwr_grid_count(5);
    double *out = malloc(nt * sizeof *out);
    assert_non_null(d);
    assert_non_null(v);
    assert_non_null(out);
    fibonacci(n, d);
    const double consts[] = {0.0, 1.0, 0.1, -3.7e-5, 1234.5678, 1.0 / 3.0};
    for (size_t q = 0; q < sizeof consts / sizeof *consts; q++) {
        for (size_t i = 0; i < n; i++)
            v[i] = consts[q];
        for (unsigned k = 1; k <= 20; k += 3)
            for (unsigned l = 0; l <= 5; l += 5) {
                assert_int_equal(bwr_project((const double(*)[3])d, v, n, 1, l, k, out), 0);
                for (size_t t = 0; t < bwr_grid_count(l); t++)
                    assert_true(out[t] == consts[q]);
            }
    }
    /* random values: every triangle within the measured range */
    rt_fill(v, n, -2.0, 5.0);
    double lo = v[0], hi = v[0];
    for (size_t i = 1; i < n; i++) {
        lo = fmin(lo, v[i]);
        hi = fmax(hi, v[i]);
    }
    assert_int_equal(bwr_project((const double(*)[3])d, v, n, 1, 5, 0, out), 0);
    for (size_t t = 0; t < nt; t++)
        assert_true(out[t] >= lo && out[t] <= hi);
    free(d);
    free(v);
    free(out);
}

static void measurements_at_the_centres_are_kept(void **state)
{
    (void)state;
    rt_seed(72);
    unsigned level = 3;
    size_t nt = bwr_grid_count(level);
    double(*c)[3] = malloc(nt * sizeof *c), *v = malloc(nt * sizeof *v);
    double *out = malloc(nt * sizeof *out);
    assert_non_null(c);
    assert_non_null(v);
    assert_non_null(out);
    assert_int_equal(bwr_grid_centres(level, c, NULL), 0);
    rt_fill(v, nt, 0.0, 1.0);
    assert_int_equal(bwr_project((const double(*)[3])c, v, nt, 1, level, 0, out), 0);
    assert_memory_equal(out, v, nt * sizeof *v);
    /* one measurement: its value everywhere */
    double up[1][3] = {{0.0, 0.0, 2.0}}, one = 0.42;
    assert_int_equal(bwr_project((const double(*)[3])up, &one, 1, 1, level, 0, out), 0);
    for (size_t t = 0; t < nt; t++)
        assert_true(out[t] == one);
    free(c);
    free(v);
    free(out);
}

static void bands_share_the_weights(void **state)
{
    (void)state;
    size_t n = 474, nt = bwr_grid_count(4);
    double(*d)[3] = malloc(n * sizeof *d), *v2 = malloc(2 * n * sizeof *v2);
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    double *o2 = malloc(2 * nt * sizeof *o2), *oa = malloc(nt * sizeof *oa),
           *ob = malloc(nt * sizeof *ob);
    assert_true(d && v2 && a && b && o2 && oa && ob);
    fibonacci(n, d);
    double wi[3];
    bwr_dir_from_degrees(40.0, 30.0, wi);
    for (size_t i = 0; i < n; i++) {
        a[i] = v2[2 * i] = phong(&phong1, wi, d[i]);
        b[i] = v2[2 * i + 1] = phong(&phong2, wi, d[i]);
    }
    assert_int_equal(bwr_project((const double(*)[3])d, v2, n, 2, 4, 0, o2), 0);
    assert_int_equal(bwr_project((const double(*)[3])d, a, n, 1, 4, 0, oa), 0);
    assert_int_equal(bwr_project((const double(*)[3])d, b, n, 1, 4, 0, ob), 0);
    for (size_t t = 0; t < nt; t++) {
        assert_true(o2[2 * t] == oa[t]);
        assert_true(o2[2 * t + 1] == ob[t]);
    }
    free(d);
    free(v2);
    free(a);
    free(b);
    free(o2);
    free(oa);
    free(ob);
}

static void bad_input(void **state)
{
    (void)state;
    double d[2][3] = {{0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}}, v[2] = {1.0, 2.0}, out[4 * 16];
    const double(*cd)[3] = (const double(*)[3])d;
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, 0, out), 0);
    assert_int_equal(bwr_project(cd, v, 0, 1, 1, 0, out), -1);
    assert_int_equal(bwr_project(cd, v, 2, 0, 1, 0, out), -1);
    assert_int_equal(bwr_project(cd, v, 2, 1, 7, 0, out), -1);
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, BWR_PROJECT_K_MAX + 1, out), -1);
    assert_int_equal(bwr_project(NULL, v, 2, 1, 1, 0, out), -1);
    d[1][2] = -0.1; /* below the horizon */
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, 0, out), -1);
    d[1][2] = 0.0;
    d[1][0] = 0.0; /* zero length */
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, 0, out), -1);
    d[1][0] = NAN;
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, 0, out), -1);
    d[1][0] = 1.0;
    v[1] = INFINITY;
    assert_int_equal(bwr_project(cd, v, 2, 1, 1, 0, out), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(phong_474_directions_to_level_4),
        cmocka_unit_test(constants_exact_and_values_bounded),
        cmocka_unit_test(measurements_at_the_centres_are_kept),
        cmocka_unit_test(bands_share_the_weights),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
