/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The codec core's integer transforms (firmware/codec) against the float
 * reference model (host-tools/ref) on the same integer data, in LSB of the
 * input samples. This test links both; the reference library itself does
 * not use the core.
 *
 * Conventions matched:
 *  - spectral axis: the core's Haar (S-transform) and LeGall 5/3 are
 *    unnormalised reversible liftings with whole-sample symmetric
 *    boundaries, approximation first (Mallat order). The reference runs
 *    PyWavelets' haar and bior2.2 one level at a time (periodization):
 *    haar on the approximation itself (an odd length is extended by its last
 *    sample, which leaves that sample alone, as the lifting does), bior2.2
 *    on the whole-sample mirror of the approximation (length 2m - 2, whose
 *    periodic extension is the symmetric one). Per level the lifting's
 *    s = a / sqrt(2) and d = -sqrt(2) d_ref (d = odd sample - prediction);
 *  - hemisphere: both compute d_m = s_m - s_0 and the area average
 *    s_P = sum_i L_i s_i, the core with Q16 weights and a rounded update.
 *
 * Error bounds (E = the largest error of the scaling values going into a
 * level; the float transform has none):
 *  - Haar: s = floor((x0 + x1) / 2) is the mean of values with error in
 *    [-E, 0], minus up to 1/2: errors stay in [-l/2, 0] after l levels, and
 *    the details of level l differ by at most (l - 1)/2;
 *  - Bio-Haar: s_P's error is the L-weighted mean of its children's, plus
 *    the rounding (1/2) plus sum_m |Lq_m - L_m| |d_m| (the Q16 weights):
 *    E grows by at most 1/2 + delta D a level (delta: the largest weight
 *    error sum of a parent, D: the largest detail), details by twice E.
 *    With 16-bit samples (|d| < 2^17) that is under 2 LSB a level; with
 *    23-bit samples the Q16 weights dominate (about 2e-5 of the range).
 *  - 5/3: one level is within 3/4 (1/2 in d, 1/2 + 2 (1/2) / 4 in s); the
 *    worst case then compounds (the low-pass has an l-infinity gain of 1.5),
 *    but the measured maxima grow at most linearly: the test bounds them by
 *    1/2 + 3l/4. The measured maxima are printed.
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

#include "bw_biohaar.h"
#include "bw_codec.h"
#include "bw_geodesic.h"
#include "bw_spectral.h"

#include "bwr_biohaar.h"
#include "bwr_dwt.h"
#include "bwr_type.h"
#include "ref_test_util.h"

#define SQRT2 1.41421356237309504880
#define MAX_N 4096u
#define MAX_LEVELS 10u

/* random integer in [lo, hi] */
static int32_t rand_int(int32_t lo, int32_t hi)
{
    return lo + (int32_t)floor(rt_uniform() * ((double)hi - (double)lo + 1.0));
}

/* One level of the reference on y[0..m) (m >= 2), in the lifting's
 * convention: s -> y[0 .. ceil(m/2)), d -> y[ceil(m/2) .. m). */
static void ref_spec_level(const bwr_filter_t *f, int mirror, double *y, size_t m)
{
    static double z[2 * MAX_N], c[4 * MAX_N];
    size_t len = m;
    memcpy(z, y, m * sizeof *z);
    if (mirror) {
        for (size_t j = m; j < 2 * m - 2; j++)
            z[j] = y[2 * m - 2 - j];
        len = 2 * m - 2;
    }
    bwr_dwt_plan_t p;
    assert_int_equal(bwr_dwt_plan(&p, f, len, 1), 0);
    assert_true(p.ncoef <= 4 * MAX_N);
    assert_int_equal(bwr_dwt_forward(&p, &bwr_type_real, z, c), 0);
    size_t ns = (m + 1) / 2, nd = m / 2, h = p.len[1]; /* a = c[0..h), d = c[h..2h) */
    assert_true(h >= ns);
    for (size_t k = 0; k < ns; k++)
        y[k] = c[k] / SQRT2;
    for (size_t k = 0; k < nd; k++)
        y[ns + k] = -SQRT2 * c[h + k];
}

static void ref_spec_fwd(unsigned basis, double *y, size_t n, unsigned levels)
{
    const bwr_filter_t *f = bwr_filter_find(basis == BW_BASIS_HAAR ? "haar" : "bior2.2");
    assert_non_null(f);
    for (unsigned l = 0; l < levels && n >= 2; l++) {
        ref_spec_level(f, basis != BW_BASIS_HAAR, y, n);
        n = (n + 1) / 2;
    }
}

/* levels the core actually runs on n samples (it stops below 2) */
static unsigned effective_levels(uint32_t n, unsigned levels)
{
    unsigned l = 0;
    while (l < levels && n >= 2) {
        n = (n + 1) / 2;
        l++;
    }
    return l;
}

static void spectral_transforms(void **state)
{
    (void)state;
    static int32_t x[MAX_N], tmp[MAX_N];
    static double y[MAX_N];
    const unsigned bases[2] = {BW_BASIS_HAAR, BW_BASIS_53};
    const char *names[2] = {"haar", "5/3"};
    for (int b = 0; b < 2; b++) {
        double worst[MAX_LEVELS + 1] = {0}, worst_app[MAX_LEVELS + 1] = {0};
        double haar_lo[MAX_LEVELS + 1] = {0}; /* most negative approximation error */
        rt_seed(300 + (uint64_t)b);
        for (int trial = 0; trial < 600; trial++) {
            uint32_t n = trial < 40 ? (uint32_t)(2 + trial) /* every short length */
                         : trial % 5 == 0 ? 1024u           /* the paper's bands */
                         : trial % 7 == 0 ? MAX_N
                                          : (uint32_t)rand_int(2, 1500);
            unsigned levels = effective_levels(n, 1 + (unsigned)(trial % MAX_LEVELS));
            int wide = trial % 3 == 0; /* 2^24 range or 16-bit samples */
            for (uint32_t k = 0; k < n; k++) {
                x[k] = wide ? rand_int(-(1 << 24), 1 << 24) : rand_int(0, 65535);
                y[k] = (double)x[k];
            }
            bw_spec_fwd(x, n, bases[b], levels, tmp);
            ref_spec_fwd(bases[b], y, n, levels);
            for (uint32_t k = 0; k < n; k++) {
                double e = (double)x[k] - y[k];
                unsigned sb = bw_spec_subband(n, levels, k);
                if (sb == 0) {
                    worst_app[levels] = fmax(worst_app[levels], fabs(e));
                    haar_lo[levels] = fmin(haar_lo[levels], e);
                    if (bases[b] == BW_BASIS_HAAR)
                        assert_true(e <= 1e-6 && e >= -0.5 * levels - 1e-6);
                } else if (bases[b] == BW_BASIS_HAAR) {
                    assert_true(fabs(e) <= 0.5 * (double)(sb - 1) + 1e-6);
                }
                worst[levels] = fmax(worst[levels], fabs(e));
            }
        }
        printf("spectral %s: max |core - reference| in LSB by depth (all coefficients; "
               "approximation)\n",
               names[b]);
        for (unsigned l = 1; l <= MAX_LEVELS; l++)
            printf("  levels %2u: %6.3f  %6.3f\n", l, worst[l], worst_app[l]);
        for (unsigned l = 1; l <= MAX_LEVELS; l++) {
            assert_true(worst[l] > 0.0); /* rounding does show */
            if (bases[b] == BW_BASIS_HAAR)
                assert_true(worst[l] <= 0.5 * (double)l + 1e-6);
            else /* one level: 1/2 in d, 1/2 + 2 (1/2) / 4 in s */
                assert_true(worst[l] <= (l == 1 ? 0.75 : 0.5 + 0.75 * (double)l) + 1e-6);
        }
        if (bases[b] == BW_BASIS_HAAR)
            for (unsigned l = 1; l <= MAX_LEVELS; l++)
                assert_true(haar_lo[l] >= -0.5 * l - 1e-6);
    }
}

/* Largest sum_m |Lq_m - L_m| over the parents of levels 0..level-1 between
 * the core's Q16 weights and the reference's. */
static double weight_error(const bwr_sphere_t *s, unsigned level)
{
    double worst = 0.0;
    size_t before = 0;
    for (unsigned j = 0; j < level; j++) {
        uint32_t per_base = 1u << (2u * j);
        for (uint32_t p = 0; p < 4u * per_base; p++) {
            uint16_t w[3];
            bw_geo_weights(j, p & (per_base - 1u), w);
            double e = 0.0;
            for (int m = 1; m <= 3; m++)
                e += fabs((double)w[m - 1] / 65536.0 - s->weight[4 * (before + p) + (size_t)m]);
            worst = fmax(worst, e);
        }
        before += 4u * per_base;
    }
    return worst;
}

/* The core's Bio-Haar on x (n triangles of vlen values, in place) against the
 * reference on y (the same values as doubles, or carrying the errors e0 of
 * an earlier stage); returns the largest |difference| and checks every
 * coefficient against the bound. */
static double biohaar_compare(const bwr_sphere_t *s, int32_t *x, const double *y, size_t vlen,
                              double e0, double *worst_scaling)
{
    unsigned level = s->level;
    size_t n = s->n;
    bwr_type_t vt = bwr_type_vector(vlen);
    double *c = malloc(n * vlen * sizeof *c);
    assert_non_null(c);
    bw_biohaar_fwd(x, level, vlen);
    assert_int_equal(bwr_biohaar_forward(s, &vt, y, c), 0);
    double delta = weight_error(s, level), dmax = 0.0;
    for (uint32_t idx = 4; idx < n; idx++)
        for (size_t e = 0; e < vlen; e++)
            dmax = fmax(dmax, fabs((double)x[(size_t)bw_biohaar_pos(idx, level) * vlen + e]));
    double step = 0.5 + delta * dmax, worst = 0.0;
    *worst_scaling = 0.0;
    for (uint32_t idx = 0; idx < n; idx++) {
        int j = bw_biohaar_coef_level(idx); /* parent level, -1: scaling */
        assert_int_equal(j, s->coef_level[idx]);
        double t = j < 0 ? (double)level : (double)level - (double)j; /* lifting steps */
        double bound = j < 0 ? e0 + t * step : 2.0 * (e0 + (t - 1.0) * step);
        for (size_t e = 0; e < vlen; e++) {
            double diff =
                fabs((double)x[(size_t)bw_biohaar_pos(idx, level) * vlen + e] - c[idx * vlen + e]);
            assert_true(diff <= bound + 1e-6);
            worst = fmax(worst, diff);
            if (j < 0)
                *worst_scaling = fmax(*worst_scaling, diff);
        }
    }
    free(c);
    return worst;
}

static void biohaar_transforms(void **state)
{
    (void)state;
    rt_seed(310);
    printf("Bio-Haar: max |core - reference| in LSB (all coefficients; base scaling)\n");
    for (unsigned level = 1; level <= BWR_SPHERE_MAX_LEVEL; level++) {
        bwr_sphere_t s;
        assert_int_equal(bwr_sphere_init(&s, level), 0);
        size_t n = s.n, vlen = level <= 4 ? 3 : 1;
        int32_t *x = malloc(n * vlen * sizeof *x);
        double *y = malloc(n * vlen * sizeof *y);
        assert_non_null(x);
        assert_non_null(y);
        double w16 = 0.0, w16s = 0.0, w24 = 0.0, w24s = 0.0, ws;
        for (int trial = 0; trial < 6; trial++) {
            int wide = trial >= 3;
            for (size_t i = 0; i < n * vlen; i++) {
                x[i] = wide ? rand_int(-(1 << 22), 1 << 22) : rand_int(0, 65535);
                y[i] = (double)x[i];
            }
            double w = biohaar_compare(&s, x, y, vlen, 0.0, &ws);
            if (wide) {
                w24 = fmax(w24, w);
                w24s = fmax(w24s, ws);
            } else {
                w16 = fmax(w16, w);
                w16s = fmax(w16s, ws);
            }
        }
        printf("  level %u: 16-bit samples %6.3f  %6.3f;  23-bit samples %7.3f  %7.3f"
               "  (weight error sum <= %.2g)\n",
               level, w16, w16s, w24, w24s, weight_error(&s, level));
        assert_true(w16 > 0.0);
        assert_true(w16 <= 3.0); /* a few LSB on 16-bit data */
        free(x);
        free(y);
        bwr_sphere_free(&s);
    }
}

/* A spectral reflectance as the codec transforms it: 5/3 on every spectrum,
 * then Bio-Haar on the spectral coefficient vectors. */
static void spectral_reflectance(void **state)
{
    (void)state;
    rt_seed(320);
    const unsigned level = 3;
    const uint32_t bands = 61; /* 400..1000 nm in 10 nm steps */
    unsigned sl = bw_spec_levels(bands);
    bwr_sphere_t s;
    assert_int_equal(bwr_sphere_init(&s, level), 0);
    size_t n = s.n;
    int32_t *x = malloc(n * bands * sizeof *x), tmp[64];
    double *y = malloc(n * bands * sizeof *y);
    assert_non_null(x);
    assert_non_null(y);
    for (size_t i = 0; i < n * bands; i++) {
        x[i] = rand_int(0, 65535);
        y[i] = (double)x[i];
    }
    double e0 = 0.0;
    for (size_t t = 0; t < n; t++) {
        bw_spec_fwd(x + t * bands, bands, BW_BASIS_53, sl, tmp);
        ref_spec_fwd(BW_BASIS_53, y + t * bands, bands, sl);
        for (size_t k = 0; k < bands; k++)
            e0 = fmax(e0, fabs((double)x[t * bands + k] - y[t * bands + k]));
    }
    double ws, w = biohaar_compare(&s, x, y, bands, e0, &ws);
    printf("spectral reflectance (level %u, %u bands, 5/3 with %u levels, then Bio-Haar): "
           "max |core - reference| %.3f LSB after the spectral stage, %.3f after both "
           "(base scaling %.3f)\n",
           level, bands, sl, e0, w, ws);
    assert_true(w <= 1.0 + (double)sl + (double)level);
    free(x);
    free(y);
    bwr_sphere_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(spectral_transforms),
        cmocka_unit_test(biohaar_transforms),
        cmocka_unit_test(spectral_reflectance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
