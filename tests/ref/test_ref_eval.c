/* SPDX-License-Identifier: BSD-2-Clause */
/* Evaluation of a sampled BRDF at any directions and wavelength. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "bwr_eval.h"
#include "bwr_geodesic.h"

#define PI 3.14159265358979323846

static uint64_t rs = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rs ^= rs << 13;
    rs ^= rs >> 7;
    rs ^= rs << 17;
    return (double)(rs >> 11) / 9007199254740992.0;
}

static void dir(double theta, double phi, double d[3])
{
    d[0] = sin(theta) * cos(phi);
    d[1] = sin(theta) * sin(phi);
    d[2] = cos(theta);
}

static double (*centres(unsigned level))[3]
{
    double(*c)[3] = malloc(bwr_grid_count(level) * sizeof *c);
    assert_non_null(c);
    assert_int_equal(bwr_grid_centres(level, c, NULL), 0);
    return c;
}

static void evaluation_at_the_samples_returns_the_samples(void **state)
{
    (void)state;
    for (int smooth = 0; smooth <= 1; smooth++) {
        /* reflectance, 5 bands at 400..800 nm */
        {
            size_t n = bwr_grid_count(2), bands = 5;
            float *v = malloc(n * bands * sizeof *v);
            for (size_t i = 0; i < n * bands; i++)
                v[i] = (float)(0.1 + urand());
            bwr_brdf_t b;
            assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_REFLECTANCE, 2, 0, 1, bands, v, NULL, 400,
                                           800, smooth),
                             0);
            double(*c)[3] = centres(2), wi[3] = {0, 0, 1};
            for (size_t o = 0; o < n; o++)
                for (size_t k = 0; k < bands; k++) {
                    double got = bwr_brdf_eval(&b, wi, c[o], 400 + 100.0 * (double)k);
                    assert_true(fabs(got - v[o * bands + k]) < 1e-9);
                }
            free(c);
            free(v);
            bwr_brdf_free(&b);
        }
        /* full BRDF, incoming level 1, outgoing level 2 */
        {
            size_t ni = bwr_grid_count(1), no = bwr_grid_count(2);
            float *v = malloc(ni * no * sizeof *v);
            for (size_t i = 0; i < ni * no; i++)
                v[i] = (float)(0.1 + urand());
            bwr_brdf_t b;
            assert_int_equal(
                bwr_brdf_init(&b, BWR_EVAL_FULL, 2, 1, 0, 1, v, NULL, 0, 0, smooth), 0);
            double(*ci)[3] = centres(1), (*co)[3] = centres(2);
            for (size_t i = 0; i < ni; i++)
                for (size_t o = 0; o < no; o++)
                    assert_true(fabs(bwr_brdf_eval(&b, ci[i], co[o], 0) - v[i * no + o]) < 1e-9);
            free(ci);
            free(co);
            free(v);
            bwr_brdf_free(&b);
        }
        /* isotropic, 4 incoming directions in the plane phi = 0, 3 bands */
        {
            size_t ni = 4, no = bwr_grid_count(2), bands = 3;
            float *v = malloc(ni * no * bands * sizeof *v);
            for (size_t i = 0; i < ni * no * bands; i++)
                v[i] = (float)(0.1 + urand());
            bwr_brdf_t b;
            assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_ISO, 2, 0, ni, bands, v, NULL, 500, 700,
                                           smooth),
                             0);
            double(*co)[3] = centres(2);
            for (size_t i = 0; i < ni; i++) {
                double wi[3];
                dir((i + 0.5) * 90.0 / ni * PI / 180.0, 0, wi);
                for (size_t o = 0; o < no; o++)
                    for (size_t k = 0; k < bands; k++) {
                        double got = bwr_brdf_eval(&b, wi, co[o], 500 + 100.0 * (double)k);
                        assert_true(fabs(got - v[(i * no + o) * bands + k]) < 1e-9);
                    }
            }
            free(co);
            free(v);
            bwr_brdf_free(&b);
        }
    }
}

static void isotropic_evaluation_is_invariant_under_rotation_about_the_normal(void **state)
{
    (void)state;
    size_t ni = 8, no = bwr_grid_count(3);
    float *v = malloc(ni * no * sizeof *v);
    for (size_t i = 0; i < ni * no; i++)
        v[i] = (float)(0.1 + urand());
    bwr_brdf_t b;
    assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_ISO, 3, 0, ni, 1, v, NULL, 0, 0, 1), 0);
    for (int rep = 0; rep < 500; rep++) {
        double ti = urand() * PI / 2, to = urand() * PI / 2, pi = urand() * 2 * PI,
               po = urand() * 2 * PI, rot = urand() * 2 * PI, wi[3], wo[3], wi2[3], wo2[3];
        dir(ti, pi, wi);
        dir(to, po, wo);
        dir(ti, pi + rot, wi2);
        dir(to, po + rot, wo2);
        double a = bwr_brdf_eval(&b, wi, wo, 0), c = bwr_brdf_eval(&b, wi2, wo2, 0);
        assert_true(fabs(a - c) < 1e-9 * fabs(a) + 1e-12);
    }
    double below[3] = {0, 0.6, -0.8}, up[3] = {0, 0, 1};
    assert_true(isnan(bwr_brdf_eval(&b, below, up, 0)));
    assert_true(isnan(bwr_brdf_eval(&b, up, below, 0)));
    bwr_brdf_free(&b);
    free(v);
}

/* the modified Phong of the paper's Table 2, Phong (1) */
static double phong(const double wi[3], const double wo[3])
{
    double r[3] = {-wi[0], -wi[1], wi[2]}, c = r[0] * wo[0] + r[1] * wo[1] + r[2] * wo[2];
    return 0.75 / PI + 0.25 * 22.0 / (2 * PI) * pow(fmax(0, c), 20);
}

/* Relative L2 error of the evaluation of Phong sampled with 16 incoming
 * directions at outgoing level L, at random directions. */
static double phong_error(unsigned level, int smooth)
{
    size_t ni = 16, no = bwr_grid_count(level);
    double(*co)[3] = centres(level);
    float *v = malloc(ni * no * sizeof *v);
    for (size_t i = 0; i < ni; i++) {
        double wi[3];
        dir((i + 0.5) * 90.0 / ni * PI / 180.0, 0, wi);
        for (size_t o = 0; o < no; o++)
            v[i * no + o] = (float)phong(wi, co[o]);
    }
    bwr_brdf_t b;
    assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_ISO, level, 0, ni, 1, v, NULL, 0, 0, smooth), 0);
    uint64_t keep = rs;
    rs = 12345; /* the same directions for every level */
    double num = 0, den = 0;
    for (int rep = 0; rep < 4000; rep++) {
        double wi[3], wo[3];
        dir((0.5 + 14 * urand()) * 90.0 / 16 * PI / 180.0, urand() * 2 * PI, wi);
        dir(urand() * 0.47 * PI, urand() * 2 * PI, wo);
        double f = phong(wi, wo), g = bwr_brdf_eval(&b, wi, wo, 0);
        num += (g - f) * (g - f) / (f * f);
        den += 1;
    }
    rs = keep;
    bwr_brdf_free(&b);
    free(v);
    free(co);
    return sqrt(num / den);
}

static void phong_is_reproduced_between_the_samples_and_converges(void **state)
{
    (void)state;
    for (int smooth = 0; smooth <= 1; smooth++) {
        double e3 = phong_error(3, smooth), e4 = phong_error(4, smooth),
               e5 = phong_error(5, smooth);
        print_message("%s: relative L2 error of Phong (1) between the samples: level 3 %.4f, "
                      "4 %.4f, 5 %.4f\n",
                      smooth ? "C1 scheme" : "barycentric", e3, e4, e5);
        assert_true(e4 < e3);
        assert_true(e5 < e4);
        assert_true(e5 < 0.5 * e3);
        assert_true(e4 < 0.03); /* measured 0.015 (both schemes) */
    }
}

static void bad_arguments_are_refused(void **state)
{
    (void)state;
    float v[4] = {1, 2, 3, 4};
    bwr_brdf_t b;
    assert_int_equal(bwr_brdf_init(&b, 0, 0, 0, 1, 1, v, NULL, 0, 0, 0), -1);
    assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_REFLECTANCE, 7, 0, 1, 1, v, NULL, 0, 0, 0), -1);
    assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_ISO, 0, 0, 0, 1, v, NULL, 0, 0, 0), -1);
    double bad_order[2] = {30, 10};
    float w[2 * 4];
    for (int i = 0; i < 8; i++)
        w[i] = 1;
    assert_int_equal(bwr_brdf_init(&b, BWR_EVAL_ISO, 0, 0, 2, 1, w, bad_order, 0, 0, 0), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(evaluation_at_the_samples_returns_the_samples),
        cmocka_unit_test(isotropic_evaluation_is_invariant_under_rotation_about_the_normal),
        cmocka_unit_test(phong_is_reproduced_between_the_samples_and_converges),
        cmocka_unit_test(bad_arguments_are_refused),
    };
    return cmocka_run_group_tests_name("ref_eval", tests, NULL, NULL);
}
