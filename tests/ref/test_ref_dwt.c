/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * 1-D wavelets of the reference model: filter identities of every shipped
 * basis (independent of any other implementation: normalisation, perfect
 * reconstruction, orthonormality, vanishing moments), the exact inverse at
 * even and odd lengths, Parseval for the orthogonal bases, the generic
 * transform on vectors, and best-basis selection.
 * (tests/ref/check_pywt.py compares the same bases with PyWavelets.)
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

#include "bwr_compress.h"
#include "bwr_dwt.h"
#include "ref_test_util.h"

static int parse_orders(const char *name, unsigned *a, unsigned *b)
{
    return sscanf(name + 4, "%u.%u", a, b) == 2 ? 0 : -1;
}

/* |sum_k k^p h_k| relative to sum_k |k^p h_k| */
static double moment(const double *h, size_t n, unsigned p, double centre)
{
    double s = 0.0, a = 0.0;
    for (size_t k = 0; k < n; k++) {
        double t = pow((double)k - centre, (double)p) * h[k];
        s += t;
        a += fabs(t);
    }
    return a > 0.0 ? fabs(s) / a : 0.0;
}

static void filter_identities_of_every_basis(void **state)
{
    (void)state;
    assert_int_equal(BWR_NUM_FILTERS, 54);
    for (size_t i = 0; i < BWR_NUM_FILTERS; i++) {
        const bwr_filter_t *f = &bwr_filters[i];
        assert_ptr_equal(bwr_filter_find(f->name), f);
        assert_true(f->len % 2 == 0 && f->len <= BWR_MAX_FILTER_LEN);
        double sd = 0.0, sr = 0.0, dh[BWR_MAX_FILTER_LEN], rh[BWR_MAX_FILTER_LEN];
        for (size_t k = 0; k < f->len; k++) {
            sd += f->dec_lo[k];
            sr += f->rec_lo[k];
        }
        assert_true(fabs(sd - sqrt(2.0)) < 1e-12);
        assert_true(fabs(sr - sqrt(2.0)) < 1e-12);
        bwr_filter_dec_hi(f, dh);
        bwr_filter_rec_hi(f, rh);
        /* biorthogonality: sum_k dec_lo[k] rec_lo[k + 2m] = delta_m (same for
         * the high-pass pair) and the cross terms vanish */
        int F = (int)f->len;
        for (int m = -F / 2; m <= F / 2; m++) {
            double ll = 0.0, hh = 0.0, lh = 0.0;
            for (int k = 0; k < F; k++) {
                int q = k + 2 * m;
                if (q < 0 || q >= F)
                    continue;
                ll += f->dec_lo[F - 1 - k] * f->rec_lo[q];
                hh += dh[F - 1 - k] * rh[q];
                lh += f->dec_lo[F - 1 - k] * rh[q];
            }
            assert_true(fabs(ll - (m == 0)) < 1e-10);
            assert_true(fabs(hh - (m == 0)) < 1e-10);
            assert_true(fabs(lh) < 1e-10);
        }
        if (f->orthogonal)
            for (size_t k = 0; k < f->len; k++)
                assert_true(fabs(f->dec_lo[k] - f->rec_lo[f->len - 1 - k]) < 1e-15);
        /* vanishing moments of the analysis wavelet (dec_hi) */
        unsigned vm = 1, a = 0, b = 0;
        if (strncmp(f->name, "db", 2) == 0 || strncmp(f->name, "sym", 3) == 0)
            vm = (unsigned)atoi(f->name + (f->name[0] == 'd' ? 2 : 3));
        else if (strncmp(f->name, "coif", 4) == 0)
            vm = 2u * (unsigned)atoi(f->name + 4);
        else if (parse_orders(f->name, &a, &b) == 0) {
            /* dec_hi inherits the zeros at z = -1 of rec_lo: Nr for bior, Nd
             * for rbio; bior5.5 is the 6/4 split (see gen_filters.py) */
            if (a == 5 && b == 5)
                a = 6, b = 4;
            vm = f->name[0] == 'b' ? a : b;
        }
        for (unsigned p = 0; p < vm; p++) {
            double mo = moment(dh, f->len, p, 0.5 * (double)(f->len - 1));
            if (!(mo < 1e-9))
                print_error("%s: moment %u of dec_hi is %g\n", f->name, p, mo);
            assert_true(mo < 1e-9);
        }
        /* and not one more for the orthogonal families (sharpness of the test) */
        if (f->orthogonal && strcmp(f->name, "haar") != 0)
            assert_true(moment(dh, f->len, vm, 0.5 * (double)(f->len - 1)) > 1e-6);
        /* coiflets: 2N - 1 vanishing moments of the scaling function too */
        if (strncmp(f->name, "coif", 4) == 0) {
            double m0 = 0.0, c = 0.0;
            for (size_t k = 0; k < f->len; k++) {
                m0 += f->rec_lo[k];
                c += (double)k * f->rec_lo[k];
            }
            c /= m0;
            for (unsigned p = 1; p < vm - 1; p++)
                assert_true(moment(f->rec_lo, f->len, p, c) < 1e-8);
        }
    }
}

static void exact_inverse_even_and_odd_lengths(void **state)
{
    (void)state;
    static const size_t lens[] = {2, 3, 7, 16, 37, 81, 128, 255, 1024, 2151};
    rt_seed(10);
    double *x = malloc(2151 * sizeof *x), *y = malloc(2151 * sizeof *y);
    double *c = malloc(8000 * sizeof *c);
    for (size_t i = 0; i < BWR_NUM_FILTERS; i++) {
        for (size_t q = 0; q < sizeof lens / sizeof lens[0]; q++) {
            size_t n = lens[q];
            bwr_dwt_plan_t p;
            /* the maximum level, a fixed one (when the signal allows) and the
             * deepest, in both extensions */
            static const int lvs[] = {-1, 3, BWR_DWT_DEEP};
            for (size_t li = 0; li < 6; li++) {
                int lv = lvs[li % 3];
                bwr_ext_t mode = li < 3 ? BWR_EXT_PERIODIZATION : BWR_EXT_SYMMETRIC;
                if (bwr_dwt_plan_ext(&p, &bwr_filters[i], n, lv, mode) != 0) {
                    assert_true(lv == 3 && mode == BWR_EXT_PERIODIZATION);
                    continue;
                }
                if (mode == BWR_EXT_PERIODIZATION)
                    assert_true(p.ncoef >= n && p.ncoef <= n + p.levels);
                else
                    assert_true(p.ncoef >= n);
                rt_fill(x, n, -2.0, 5.0);
                assert_int_equal(bwr_dwt_forward(&p, &bwr_type_real, x, c), 0);
                assert_int_equal(bwr_dwt_inverse(&p, &bwr_type_real, c, y), 0);
                assert_true(rt_max_abs_diff(x, y, n) < 5e-12 * 5.0);
                if (mode == BWR_EXT_PERIODIZATION && n % ((size_t)1 << p.levels) == 0)
                    assert_int_equal(p.ncoef, n);
                /* Parseval for the orthogonal bases when every level is even */
                if (bwr_filters[i].orthogonal && p.ncoef == n) {
                    double ex = 0.0, ec = 0.0;
                    for (size_t k = 0; k < n; k++) {
                        ex += x[k] * x[k];
                        ec += c[k] * c[k];
                    }
                    assert_true(fabs(ex - ec) < 1e-11 * ex);
                }
            }
        }
    }
    free(x);
    free(y);
    free(c);
}

static void max_level_is_pywavelets_rule(void **state)
{
    (void)state;
    /* floor(log2(n / (F - 1))) */
    assert_int_equal(bwr_dwt_max_level(81, 4), 4);   /* 81/3 = 27 */
    assert_int_equal(bwr_dwt_max_level(2151, 30), 6); /* 2151/29 = 74.2 */
    assert_int_equal(bwr_dwt_max_level(1024, 2), 10);
    assert_int_equal(bwr_dwt_max_level(5, 8), 0);
    assert_int_equal(bwr_dwt_max_level(7, 8), 0);
    assert_int_equal(bwr_dwt_max_level(14, 8), 1);
    assert_int_equal(bwr_dwt_max_level(13, 8), 0);
}

static void vectors_transform_component_by_component(void **state)
{
    (void)state;
    const size_t n = 50, B = 3;
    const bwr_filter_t *f = bwr_filter_find("sym5");
    assert_non_null(f);
    bwr_dwt_plan_t p;
    assert_int_equal(bwr_dwt_plan(&p, f, n, -1), 0);
    bwr_type_t vt = bwr_type_vector(B);
    double *x = malloc(n * B * sizeof *x), *c = malloc(p.ncoef * B * sizeof *c);
    double xb[50], cb[64];
    rt_seed(11);
    rt_fill(x, n * B, 0.0, 1.0);
    assert_int_equal(bwr_dwt_forward(&p, &vt, x, c), 0);
    for (size_t b = 0; b < B; b++) {
        for (size_t k = 0; k < n; k++)
            xb[k] = x[k * B + b];
        bwr_dwt_forward(&p, &bwr_type_real, xb, cb);
        for (size_t k = 0; k < p.ncoef; k++)
            assert_true(fabs(cb[k] - c[k * B + b]) < 1e-14);
    }
    free(x);
    free(c);
}

static void best_basis_prefers_the_basis_that_fits(void **state)
{
    (void)state;
    /* piecewise constant on dyadic blocks of 16: Haar represents it with the
     * 1/16 of the coefficients exactly, smoother bases cannot */
    const size_t n = 256;
    double x[256];
    rt_seed(12);
    for (size_t b = 0; b < n / 16; b++) {
        double v = 0.5 + rt_uniform();
        for (size_t k = 0; k < 16; k++)
            x[16 * b + k] = v;
    }
    const bwr_filter_t *cand[4] = {bwr_filter_find("db4"), bwr_filter_find("haar"),
                                   bwr_filter_find("coif2"), bwr_filter_find("bior2.2")};
    bwr_shape_t sh = bwr_shape_spectra(1, n, cand[0]);
    sh.spec_levels = 4;
    bwr_thresholds_t th = {.keep = n / 16};
    size_t best = 99;
    double err[4];
    assert_int_equal(bwr_best_basis(&sh, x, &th, cand, 4, &best, err), 0);
    assert_int_equal(best, 1);
    assert_true(err[1] < 1e-12);
    for (size_t k = 0; k < 4; k++)
        if (k != 1)
            assert_true(err[k] > 0.1);
    /* a smooth signal: the Haar error is the largest of the four */
    for (size_t k = 0; k < n; k++)
        x[k] = 1.0 + 0.5 * sin(6.283185307179586 * (double)k / (double)n) +
               0.2 * cos(3.0 * 6.283185307179586 * (double)k / (double)n);
    assert_int_equal(bwr_best_basis(&sh, x, &th, cand, 4, &best, err), 0);
    assert_true(best != 1);
    for (size_t k = 0; k < 4; k++)
        assert_true(err[1] >= err[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(filter_identities_of_every_basis),
        cmocka_unit_test(exact_inverse_even_and_odd_lengths),
        cmocka_unit_test(max_level_is_pywavelets_rule),
        cmocka_unit_test(vectors_transform_component_by_component),
        cmocka_unit_test(best_basis_prefers_the_basis_that_fits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
