/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The objects of sec. 4.2 (Spectrum sets, Reflectance, Spectral Reflectance,
 * BRDF full and isotropic, Spectral BRDF): exact round trips, the structure
 * of the coefficients, compression with thresholds per space and by count,
 * and the error metrics of eq. 7-8.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_compress.h"
#include "bwr_model.h"
#include "ref_test_util.h"

static void round_trip(const bwr_shape_t *sh, double tol)
{
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, sh), 0);
    double *x = malloc(m.n_samples * sizeof *x), *y = malloc(m.n_samples * sizeof *y);
    double *c = malloc(m.n_coefs * sizeof *c);
    assert_non_null(x);
    assert_non_null(c);
    rt_fill(x, m.n_samples, 0.01, 2.0);
    assert_int_equal(bwr_model_forward(&m, x, c), 0);
    assert_int_equal(bwr_model_inverse(&m, c, y), 0);
    assert_true(rt_max_abs_diff(x, y, m.n_samples) < tol);
    free(x);
    free(y);
    free(c);
    bwr_model_free(&m);
}

static void every_object_round_trips_within_1e_12(void **state)
{
    (void)state;
    rt_seed(20);
    const bwr_filter_t *db4 = bwr_filter_find("db4"), *b22 = bwr_filter_find("bior2.2");
    bwr_shape_t s[] = {
        bwr_shape_spectra(7, 81, db4),
        bwr_shape_spectra(3, 1024, b22),
        bwr_shape_reflectance(0),
        bwr_shape_reflectance(6),
        bwr_shape_spectral_reflectance(3, 33, bwr_filter_find("coif2")),
        bwr_shape_brdf(2, 3),
        bwr_shape_brdf_isotropic(16, 4),
        bwr_shape_spectral_brdf(-1, 5, 2, 40, bwr_filter_find("sym6")),
        bwr_shape_spectral_brdf(1, 0, 2, 9, b22),
    };
    for (size_t i = 0; i < sizeof s / sizeof s[0]; i++)
        round_trip(&s[i], 2e-12);
    /* a 1-D transform across the set (odd count: 71 incidence angles) */
    bwr_shape_t a = bwr_shape_spectra(71, 40, db4);
    a.in_basis = bwr_filter_find("sym4");
    round_trip(&a, 2e-12);
    a = bwr_shape_spectral_brdf(-1, 9, 1, 1, NULL);
    a.bands = 1;
    a.in_basis = b22;
    round_trip(&a, 2e-12);
}

/* the 1-D transform across the set is the same generic code on Spectrum
 * elements: the coefficients of an angle-independent set have no details
 * across the set */
static void transform_across_a_set(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_spectra(32, 16, bwr_filter_find("haar"));
    s.in_basis = bwr_filter_find("db2");
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    assert_int_equal(m.nci, 32);
    double x[32 * 16], c[32 * 16];
    rt_seed(24);
    rt_fill(x, 16, 0.0, 1.0);
    for (size_t i = 1; i < 32; i++)
        memcpy(x + 16 * i, x, 16 * sizeof *x);
    assert_int_equal(bwr_model_forward(&m, x, c), 0);
    size_t na = m.dwt_in.len[m.dwt_in.levels];
    for (size_t q = na * 16; q < 32 * 16; q++)
        assert_true(fabs(c[q]) < 1e-13);
    bwr_model_free(&m);
}

static void bad_shapes_are_rejected(void **state)
{
    (void)state;
    bwr_model_t m;
    bwr_shape_t s = bwr_shape_reflectance(7);
    assert_int_equal(bwr_model_init(&m, &s), -1);
    s = bwr_shape_spectra(3, 10, NULL); /* bands > 1 need a basis */
    assert_int_equal(bwr_model_init(&m, &s), -1);
    s = bwr_shape_brdf(1, 1);
    s.n_in = 15; /* not 4 * 4^level_in */
    assert_int_equal(bwr_model_init(&m, &s), -1);
    s = bwr_shape_spectra(0, 10, bwr_filter_find("haar"));
    assert_int_equal(bwr_model_init(&m, &s), -1);
}

/* The BRDF is a Bio-Haar over incoming directions of Reflectance objects:
 * its coefficients equal those of the outgoing transform applied to the
 * incoming transform's coefficients, computed by hand here. */
static void brdf_is_a_transform_of_reflectances(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_brdf(1, 2);
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    size_t ni = m.n_in, no = m.n_out;
    double *x = malloc(ni * no * sizeof *x), *c = malloc(ni * no * sizeof *c);
    double *t = malloc(ni * no * sizeof *t), *u = malloc(ni * no * sizeof *u);
    rt_seed(21);
    rt_fill(x, ni * no, 0.0, 1.0);
    assert_int_equal(bwr_model_forward(&m, x, c), 0);
    bwr_type_t refl = bwr_type_vector(no);
    bwr_biohaar_forward(&m.sph_in, &refl, x, t);
    for (size_t i = 0; i < ni; i++)
        bwr_biohaar_forward(&m.sph_out, &bwr_type_real, t + i * no, u + i * no);
    assert_true(rt_max_abs_diff(c, u, ni * no) < 1e-14);
    /* a BRDF that does not depend on the incoming direction has zero
     * incoming details */
    for (size_t i = 0; i < ni; i++)
        memcpy(x + i * no, x, no * sizeof *x);
    bwr_model_forward(&m, x, c);
    for (size_t q = 4 * no; q < ni * no; q++)
        assert_true(fabs(c[q]) < 1e-14);
    free(x);
    free(c);
    free(t);
    free(u);
    bwr_model_free(&m);
}

static size_t nonzero(const double *c, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += c[i] != 0.0;
    return k;
}

static void keep_count_is_exact_and_error_shrinks(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_brdf_isotropic(4, 4);
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    double *x = malloc(m.n_samples * sizeof *x), *c = malloc(m.n_coefs * sizeof *c);
    double *k = malloc(m.n_coefs * sizeof *k), *y = malloc(m.n_samples * sizeof *y);
    rt_seed(22);
    for (size_t i = 0; i < m.n_samples; i++) /* smooth plus noise */
        x[i] = 1.0 + 0.5 * sin(0.01 * (double)i) + 0.05 * rt_uniform();
    bwr_model_forward(&m, x, c);
    double prev = INFINITY;
    size_t counts[] = {16, 64, 256, 1024, 4096};
    for (size_t q = 0; q < 5; q++) {
        bwr_thresholds_t th = {.keep = counts[q]};
        bwr_compress_info_t inf;
        assert_int_equal(bwr_compress(&m, c, &th, k, &inf), 0);
        assert_int_equal(inf.kept, counts[q]);
        assert_int_equal(nonzero(k, m.n_coefs), counts[q]);
        bwr_model_inverse(&m, k, y);
        bwr_error_t e;
        bwr_error(x, y, m.n_samples, &e);
        assert_true(e.rmse < prev);
        prev = e.rmse;
        /* the kept ones are the largest normalised magnitudes */
        double minkept = INFINITY, maxdropped = 0.0;
        for (size_t i = 0; i < m.n_coefs; i++) {
            double g = fabs(c[i]) * sqrt(bwr_model_norm2(&m, i / m.n_out, i % m.n_out, 0));
            if (k[i] != 0.0)
                minkept = fmin(minkept, g);
            else
                maxdropped = fmax(maxdropped, g);
        }
        assert_true(minkept >= maxdropped);
    }
    /* keeping everything is exact */
    bwr_thresholds_t all = {.keep = m.n_coefs};
    bwr_compress(&m, c, &all, k, NULL);
    bwr_model_inverse(&m, k, y);
    assert_true(rt_max_abs_diff(x, y, m.n_samples) < 1e-12);
    free(x);
    free(c);
    free(k);
    free(y);
    bwr_model_free(&m);
}

static void thresholds_per_space(void **state)
{
    (void)state;
    /* spectral reflectance: vectors by norm, then elements */
    bwr_shape_t s = bwr_shape_spectral_reflectance(2, 32, bwr_filter_find("haar"));
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    double *x = malloc(m.n_samples * sizeof *x), *c = malloc(m.n_coefs * sizeof *c);
    double *k = malloc(m.n_coefs * sizeof *k);
    rt_seed(23);
    rt_fill(x, m.n_samples, 0.0, 1.0);
    bwr_model_forward(&m, x, c);
    /* vector norms */
    double *vn = calloc(m.n_out, sizeof *vn);
    for (size_t o = 0; o < m.n_out; o++) {
        double e = 0.0;
        for (size_t q = 0; q < m.ncoef_spec; q++)
            e += c[o * m.ncoef_spec + q] * c[o * m.ncoef_spec + q] * m.spec_norm2[q];
        vn[o] = sqrt(e * m.out_psi2[o]);
    }
    double eps_vec = 0.5 * (vn[10] + vn[20]);
    size_t below = 0;
    for (size_t o = 0; o < m.n_out; o++)
        below += vn[o] < eps_vec;
    bwr_thresholds_t th = {.eps_vec = eps_vec};
    bwr_compress_info_t inf;
    bwr_compress(&m, c, &th, k, &inf);
    assert_int_equal(inf.vec_dropped, below);
    for (size_t o = 0; o < m.n_out; o++)
        for (size_t q = 0; q < m.ncoef_spec; q++) {
            double v = k[o * m.ncoef_spec + q];
            if (vn[o] < eps_vec)
                assert_true(v == 0.0);
            else
                assert_true(v == c[o * m.ncoef_spec + q]);
        }
    /* then elements: every survivor above eps_elem */
    th.eps_elem = 0.05;
    bwr_compress(&m, c, &th, k, &inf);
    for (size_t i = 0; i < m.n_coefs; i++) {
        double g = fabs(c[i]) *
                   sqrt(m.out_psi2[i / m.ncoef_spec] * m.spec_norm2[i % m.ncoef_spec]);
        int keep = vn[i / m.ncoef_spec] >= eps_vec && g >= 0.05;
        assert_true(keep ? k[i] == c[i] : k[i] == 0.0);
    }
    free(vn);
    bwr_model_free(&m);

    /* full BRDF: incoming Reflectance objects by norm */
    s = bwr_shape_brdf(1, 1);
    assert_int_equal(bwr_model_init(&m, &s), 0);
    free(x);
    free(c);
    free(k);
    x = malloc(m.n_samples * sizeof *x);
    c = malloc(m.n_coefs * sizeof *c);
    k = malloc(m.n_coefs * sizeof *k);
    rt_fill(x, m.n_samples, 0.0, 1.0);
    bwr_model_forward(&m, x, c);
    th = (bwr_thresholds_t){.eps_in = 1e9};
    bwr_compress(&m, c, &th, k, &inf);
    assert_int_equal(inf.in_dropped, m.n_in);
    assert_int_equal(inf.kept, 0);
    free(x);
    free(c);
    free(k);
    bwr_model_free(&m);
}

/* raw: ranking by |c|; keep_coarse: the base scaling coefficients stay */
static void raw_magnitudes_and_coarse_coefficients(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_brdf_isotropic(3, 2);
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    double *x = malloc(m.n_samples * sizeof *x), *c = malloc(m.n_coefs * sizeof *c);
    double *k = malloc(m.n_coefs * sizeof *k);
    rt_seed(25);
    rt_fill(x, m.n_samples, 0.0, 1.0);
    bwr_model_forward(&m, x, c);
    bwr_thresholds_t th = {.keep = 20, .raw = 1};
    bwr_compress_info_t inf;
    bwr_compress(&m, c, &th, k, &inf);
    assert_int_equal(inf.kept, 20);
    double minkept = INFINITY, maxdropped = 0.0;
    for (size_t q = 0; q < m.n_coefs; q++) {
        if (k[q] != 0.0)
            minkept = fmin(minkept, fabs(c[q]));
        else
            maxdropped = fmax(maxdropped, fabs(c[q]));
    }
    assert_true(minkept >= maxdropped);
    /* keep 14 with the coarse ones forced: the 12 base scaling coefficients
     * (4 per incoming direction) and the 2 largest others */
    th.keep = 14;
    th.keep_coarse = 1;
    for (size_t i = 0; i < 3; i++)
        c[i * m.n_out + 1] *= 1e-9; /* make some scaling coefficients tiny */
    bwr_compress(&m, c, &th, k, &inf);
    assert_int_equal(inf.kept, 14);
    for (size_t i = 0; i < 3; i++)
        for (size_t o = 0; o < 4; o++)
            assert_true(k[i * m.n_out + o] == c[i * m.n_out + o]);
    /* keep fewer than the coarse ones: only coarse ones remain */
    th.keep = 5;
    bwr_compress(&m, c, &th, k, &inf);
    assert_int_equal(inf.kept, 5);
    for (size_t q = 0; q < m.n_coefs; q++)
        if (k[q] != 0.0)
            assert_true(q % m.n_out < 4);
    free(x);
    free(c);
    free(k);
    bwr_model_free(&m);
}

static void memory_accounting_flat_and_nested(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_brdf_isotropic(2, 1); /* 2 x 16 */
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    double c[32] = {0};
    c[0] = 1.0;
    c[17] = -2.0;
    bwr_memory_t fl, ne;
    bwr_coef_memory(&m, c, 8, &fl, &ne);
    assert_int_equal(fl.values, 2);
    assert_int_equal(fl.strips, 1);             /* indices 0..31: one strip */
    assert_int_equal(ne.strips, 3);             /* incoming array + 2 spheres */
    assert_int_equal(fl.total_bytes, 2 * 8 + 1 * 8);
    assert_int_equal(ne.total_bytes, 2 * 8 + 3 * 8);
    c[17] = 0.0;
    bwr_coef_memory(&m, c, 4, &fl, &ne);
    assert_int_equal(ne.strips, 2);             /* the empty sphere has no strip */
    assert_int_equal(fl.data_bytes, 4);
    bwr_sample_memory(&m, 8, &fl, &ne);
    assert_int_equal(fl.values, 32);
    assert_int_equal(fl.strips, 1);
    assert_int_equal(ne.strips, 3);
    bwr_model_free(&m);
    /* a spectral set: 3 spectra of 40 bands, nested = set + 3 x 2 strips */
    s = bwr_shape_spectra(3, 40, bwr_filter_find("haar"));
    assert_int_equal(bwr_model_init(&m, &s), 0);
    bwr_sample_memory(&m, 8, &fl, &ne);
    assert_int_equal(fl.strips, 4); /* 120 samples */
    assert_int_equal(ne.strips, 1 + 3 * 2);
    bwr_model_free(&m);
}

static void keep_per_object(void **state)
{
    (void)state;
    bwr_shape_t s = bwr_shape_spectra(4, 32, bwr_filter_find("db2"));
    bwr_model_t m;
    assert_int_equal(bwr_model_init(&m, &s), 0);
    double x[128], c[128], k[128];
    rt_seed(26);
    for (size_t i = 0; i < 128; i++) /* very different magnitudes per spectrum */
        x[i] = (1.0 + rt_uniform()) * pow(10.0, (double)(i / 32));
    bwr_model_forward(&m, x, c);
    bwr_thresholds_t th = {.keep = 9, .per_in = 1};
    bwr_compress_info_t inf;
    assert_int_equal(bwr_compress(&m, c, &th, k, &inf), 0);
    assert_int_equal(inf.kept, 9);
    for (size_t i = 0; i < 4; i++)
        assert_int_equal(nonzero(k + 32 * i, 32), i == 0 ? 3 : 2);
    /* one global ranking gives the bright spectrum nearly everything */
    th.per_in = 0;
    bwr_compress(&m, c, &th, k, &inf);
    assert_true(nonzero(k + 96, 32) >= 6);
    bwr_model_free(&m);
}

static void error_metrics_are_eq_7_and_8(void **state)
{
    (void)state;
    double ref[4] = {1.0, 2.0, 0.0, 4.0}, t[4] = {1.1, 1.8, 0.3, 4.0};
    bwr_error_t e;
    bwr_error(ref, t, 4, &e);
    /* the zero reference is left out: n = 3 */
    assert_int_equal(e.zero_ref, 1);
    assert_true(fabs(e.rel_l1 - 100.0 * (0.1 + 0.1 + 0.0) / 3.0) < 1e-12);
    assert_true(fabs(e.rel_l2 - 100.0 * sqrt((0.01 + 0.01) / 3.0)) < 1e-12);
    assert_true(fabs(e.max_abs - 0.3) < 1e-15);
    assert_true(fabs(e.rmse - sqrt((0.01 + 0.04 + 0.09) / 4.0)) < 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_object_round_trips_within_1e_12),
        cmocka_unit_test(bad_shapes_are_rejected),
        cmocka_unit_test(transform_across_a_set),
        cmocka_unit_test(raw_magnitudes_and_coarse_coefficients),
        cmocka_unit_test(brdf_is_a_transform_of_reflectances),
        cmocka_unit_test(keep_count_is_exact_and_error_shrinks),
        cmocka_unit_test(thresholds_per_space),
        cmocka_unit_test(memory_accounting_flat_and_nested),
        cmocka_unit_test(keep_per_object),
        cmocka_unit_test(error_metrics_are_eq_7_and_8),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
