/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The analytic BRDFs of the virtual goniometer (host-tools/lib/brdf_models.c,
 * the models of `brdfwave synth`): reciprocity, energy conservation over the
 * paper's data sets, and the modified Phong's albedo at normal incidence.
 *
 * Integrals over the hemisphere are midpoint sums over the geodesic grid:
 *   int g(wo) dw_o  ~  sum_t g(c_t) a_t,
 * c_t the centre and a_t the solid angle of triangle t (the a_t add up to
 * 2 pi exactly). The rule is second order: its error falls by about 4 per
 * level; the error at level L is estimated as |A_L - A_{L-1}| / 3.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "brdf_models.h"
#include "geodesic.h"
#include "test_rng.h"

#define PI BWH_BRDF_PI

typedef double (*brdf_fn)(const bwh_brdf_params_t *p, const double wi[3], const double wo[3]);

/* The paper's data sets (the presets of `brdfwave synth --help`). */
static const bwh_brdf_params_t phong1 = {.kd = 0.75, .ks = 0.25, .n = 20.0};
static const bwh_brdf_params_t phong2 = {.kd = 0.5, .ks = 0.5, .n = 50.0};
static const bwh_brdf_params_t ward = {.kd = 0.75, .ks = 0.25, .ax = 0.35, .ay = 0.05};

/* grid[l]: centres and solid angles at level l = 4..6 */
static double (*centre[BWH_GRID_MAX_LEVEL + 1])[3];
static double *area[BWH_GRID_MAX_LEVEL + 1];

static int setup(void **state)
{
    (void)state;
    for (unsigned l = 4; l <= BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        centre[l] = malloc(n * sizeof *centre[l]);
        area[l] = malloc(n * sizeof *area[l]);
        if (centre[l] == NULL || area[l] == NULL ||
            bwh_grid_centres(l, centre[l], area[l]) != 0)
            return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    for (unsigned l = 4; l <= BWH_GRID_MAX_LEVEL; l++) {
        free(centre[l]);
        free(area[l]);
        centre[l] = NULL;
        area[l] = NULL;
    }
    return 0;
}

/* Directional albedo int f(wi, wo) cos(theta_o) dw_o at grid level l. */
static double albedo(brdf_fn f, const bwh_brdf_params_t *p, const double wi[3], unsigned l)
{
    size_t n = bwh_grid_count(l);
    double s = 0.0;
    for (size_t t = 0; t < n; t++)
        s += f(p, wi, centre[l][t]) * centre[l][t][2] * area[l][t];
    return s;
}

static uint64_t rng = 0x853c49e6748fea9bull;

static double uniform(void) { return test_uniform(&rng); }

/* uniform on the upper hemisphere (z = cos theta uniform in (0, 1]) */
static void random_direction(double d[3])
{
    double z = 1.0 - uniform(), phi = 2.0 * PI * uniform(), r = sqrt(fmax(0.0, 1.0 - z * z));
    d[0] = r * cos(phi);
    d[1] = r * sin(phi);
    d[2] = z;
}

/* max over random pairs of |f(a, b) - f(b, a)| / max(|f(a, b)|, |f(b, a)|) */
static double reciprocity_defect(brdf_fn f, const bwh_brdf_params_t *p, int pairs)
{
    double worst = 0.0;
    for (int k = 0; k < pairs; k++) {
        double a[3], b[3];
        random_direction(a);
        random_direction(b);
        if (k % 8 == 0) { /* near the mirror direction of a: the specular peaks */
            b[0] = -a[0] + 0.02 * (uniform() - 0.5);
            b[1] = -a[1] + 0.02 * (uniform() - 0.5);
            b[2] = a[2];
            double nb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            for (int c = 0; c < 3; c++)
                b[c] /= nb;
        }
        double fab = f(p, a, b), fba = f(p, b, a);
        double m = fmax(fabs(fab), fabs(fba));
        if (m > 0.0)
            worst = fmax(worst, fabs(fab - fba) / m);
    }
    return worst;
}

/* Not reciprocal: the measured quantity f cos(theta_i), for the negative check. */
static double phong_times_cos_i(const bwh_brdf_params_t *p, const double wi[3],
                                const double wo[3])
{
    return bwh_brdf_phong(p, wi, wo) * wi[2];
}

static void reciprocity(void **state)
{
    (void)state;
    rng = 0x853c49e6748fea9bull;
    const struct {
        const char *name;
        brdf_fn f;
        const bwh_brdf_params_t *p;
    } sets[] = {{"phong1", bwh_brdf_phong, &phong1},
                {"phong2", bwh_brdf_phong, &phong2},
                {"ward", bwh_brdf_ward, &ward}};
    for (size_t s = 0; s < sizeof sets / sizeof *sets; s++) {
        double d = reciprocity_defect(sets[s].f, sets[s].p, 20000);
        printf("reciprocity %-7s max relative |f(wi,wo) - f(wo,wi)| = %.3g (20000 pairs)\n",
               sets[s].name, d);
        assert_true(d <= 1e-14);
    }
    /* random parameters */
    for (int k = 0; k < 50; k++) {
        bwh_brdf_params_t p = {.kd = uniform(), .ks = uniform(), .n = 200.0 * uniform(),
                               .ax = 0.01 + uniform(), .ay = 0.01 + uniform()};
        assert_true(reciprocity_defect(bwh_brdf_phong, &p, 500) <= 1e-14);
        assert_true(reciprocity_defect(bwh_brdf_ward, &p, 500) <= 1e-14);
    }
    /* the check sees a non-reciprocal function */
    assert_true(reciprocity_defect(phong_times_cos_i, &phong1, 1000) > 0.1);
}

/* Largest albedo over the incoming directions, and whether every one stays
 * within 1 + the estimated quadrature error of its level-6 sum. */
static int conserves_energy(brdf_fn f, const bwh_brdf_params_t *p, const double (*wi)[3],
                            size_t n_in, double *max_albedo, double *max_err)
{
    int ok = 1;
    *max_albedo = 0.0;
    *max_err = 0.0;
    for (size_t i = 0; i < n_in; i++) {
        double a6 = albedo(f, p, wi[i], 6), a5 = albedo(f, p, wi[i], 5);
        double err = fabs(a6 - a5) / 3.0;
        *max_albedo = fmax(*max_albedo, a6);
        *max_err = fmax(*max_err, err);
        if (!(a6 <= 1.0 + err))
            ok = 0;
    }
    return ok;
}

static void energy_conservation(void **state)
{
    (void)state;
    /* Phong1, Phong2: 16 incoming directions at phi = 0,
     * theta_k = (k + 1/2) 90/16 deg; Ward: the 1024 centres at level 4 */
    double phong_in[16][3];
    for (int k = 0; k < 16; k++) {
        double th = ((double)k + 0.5) * (PI / 2.0) / 16.0;
        phong_in[k][0] = sin(th);
        phong_in[k][1] = 0.0;
        phong_in[k][2] = cos(th);
    }
    double amax, emax;
    assert_true(conserves_energy(bwh_brdf_phong, &phong1, (const double(*)[3])phong_in, 16,
                                 &amax, &emax));
    printf("albedo phong1 (16 incoming): max %.6f, quadrature error <= %.2g\n", amax, emax);
    assert_true(amax > 0.99 && amax <= 1.0 + emax);
    assert_true(conserves_energy(bwh_brdf_phong, &phong2, (const double(*)[3])phong_in, 16,
                                 &amax, &emax));
    printf("albedo phong2 (16 incoming): max %.6f, quadrature error <= %.2g\n", amax, emax);
    assert_true(amax > 0.99 && amax <= 1.0 + emax);
    assert_true(conserves_energy(bwh_brdf_ward, &ward, (const double(*)[3])centre[4],
                                 bwh_grid_count(4), &amax, &emax));
    printf("albedo ward (1024 incoming): max %.6f, quadrature error <= %.2g\n", amax, emax);
    assert_true(amax > 0.9);

    /* the modified Phong's albedo never exceeds kd + ks, whatever the
     * incidence: kd + ks = 1 conserves energy at every exponent */
    for (double n = 0.0; n <= 200.0; n += n < 10.0 ? 1.0 : 38.0) {
        bwh_brdf_params_t p = {.kd = 0.3, .ks = 0.7, .n = n};
        assert_true(conserves_energy(bwh_brdf_phong, &p, (const double(*)[3])phong_in, 16,
                                     &amax, &emax));
    }

    /* the check fails on a BRDF that reflects more than it receives */
    bwh_brdf_params_t hot = {.kd = 0.75, .ks = 0.45, .n = 20.0};
    assert_false(conserves_energy(bwh_brdf_phong, &hot, (const double(*)[3])phong_in, 16,
                                  &amax, &emax));
    bwh_brdf_params_t hot_ward = {.kd = 0.8, .ks = 0.25, .ax = 0.35, .ay = 0.05};
    assert_false(conserves_energy(bwh_brdf_ward, &hot_ward, (const double(*)[3])centre[4],
                                  bwh_grid_count(4), &amax, &emax));
}

/* At normal incidence the modified Phong's specular part integrates to ks:
 * (n+2)/(2 pi) int cos^(n+1) theta dw = 1. The albedo is kd + ks up to the
 * quadrature error, which falls about fourfold per level. */
static void phong_albedo_at_normal_incidence(void **state)
{
    (void)state;
    const double up[3] = {0.0, 0.0, 1.0};
    const bwh_brdf_params_t sets[] = {
        phong1, phong2, {.kd = 1.0, .ks = 0.0, .n = 1.0}, {.kd = 0.0, .ks = 1.0, .n = 5.0},
        {.kd = 0.1, .ks = 0.6, .n = 100.0}};
    for (size_t s = 0; s < sizeof sets / sizeof *sets; s++) {
        double e[BWH_GRID_MAX_LEVEL + 1];
        for (unsigned l = 4; l <= 6; l++)
            e[l] = fabs(albedo(bwh_brdf_phong, &sets[s], up, l) - (sets[s].kd + sets[s].ks));
        printf("phong kd %.2f ks %.2f n %5.1f: |albedo(0) - (kd + ks)| level 4 %.3g, "
               "level 5 %.3g, level 6 %.3g (ratio 4/6: %.1f)\n",
               sets[s].kd, sets[s].ks, sets[s].n, e[4], e[5], e[6], e[4] / e[6]);
        assert_true(e[6] < 1e-3);
        assert_true(e[5] < e[4] && e[6] < e[5]);
        assert_true(e[4] / e[6] > 10.0); /* second order: about 16 */
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reciprocity),
        cmocka_unit_test(energy_conservation),
        cmocka_unit_test(phong_albedo_at_normal_incidence),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
