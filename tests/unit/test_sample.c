/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Importance sampling from the triangle hierarchy (host-tools/lib/bw_sample.c)
 * tested as renderers test their BSDF samplers:
 *
 *  - chi-square goodness of fit of sample() against the sampler's own
 *    density, 1M samples per incoming direction, bins = the leaf triangles:
 *    the density is constant on a leaf apart from the cosine lobe, whose
 *    integral over a spherical triangle is exact (Lambert's edge formula), so
 *    every expected count is exact; cells expected below 5 are pooled; level
 *    0.01 with a Sidak correction over the incoming directions of a BRDF;
 *    for Phong, Ward and a measured RGL BRDF encoded and decoded by the codec;
 *  - the same test rejects samples of a different BRDF (it has power);
 *  - a sampler of one channel of a decoded BRDF follows that channel;
 *  - Arvo's method is uniform inside a triangle (chi-square on 64 parts);
 *  - pdf() agrees with the pdf sample() returns (to the bit, away from leaf
 *    edges), integrates to 1, and its integral over each leaf is that
 *    leaf's mass;
 *  - the albedo estimator f cos / pdf is unbiased (within 4 standard errors
 *    plus the error of the reference quadrature);
 *  - sample's value is f at (wi, wo), clamped as the tables are;
 *  - negative values are clamped the same way for sample and pdf; a region
 *    where f is faint but positive keeps a positive pdf and is drawn as often
 *    as it says; the tree and the linear scan pick the same leaves; bad input
 *    is refused.
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

#include "brdf_eval.h"
#include "brdf_models.h"
#include "bw_config.h"
#include "bw_sample.h"
#include "bwhost.h"
#include "bwr_rgl.h"
#include "geodesic.h"
#include "test_rng.h"

#define PI BWH_BRDF_PI
/* samples per incoming direction: 1M, or 100k with BW_TEST_QUICK=1 (the
 * sanitizer build) */
static long N_SAMPLES = 1000000L;

/* ---- random numbers ---------------------------------------------------- */

static uint64_t rng_state = 0x853c49e6748fea9bull;

static double rnd(void) { return test_uniform(&rng_state); }

/* ---- chi-square ----------------------------------------------------------- */

/* regularised upper incomplete gamma Q(a, x) (series / continued fraction) */
static double gamma_q(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    double gln = lgamma(a);
    if (x < a + 1.0) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int n = 0; n < 100000; n++) {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if (fabs(del) < fabs(sum) * 1e-15)
                break;
        }
        return 1.0 - sum * exp(-x + a * log(x) - gln);
    }
    double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < 1e-300)
            d = 1e-300;
        c = b + an / c;
        if (fabs(c) < 1e-300)
            c = 1e-300;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < 1e-15)
            break;
    }
    return exp(-x + a * log(x) - gln) * h;
}

/* p-value of observed counts against expected counts (cells below 5
 * pooled into one) */
static double chi2_pvalue(const long *obs, const double *expct, size_t n, double *chi2_out,
                          size_t *dof_out)
{
    double chi2 = 0.0, pool_e = 0.0;
    long pool_o = 0;
    size_t cells = 0;
    for (size_t i = 0; i < n; i++) {
        if (expct[i] < 5.0) {
            pool_e += expct[i];
            pool_o += obs[i];
            continue;
        }
        double d = obs[i] - expct[i];
        chi2 += d * d / expct[i];
        cells++;
    }
    if (pool_e > 0.0) {
        double d = pool_o - pool_e;
        if (pool_e >= 5.0) {
            chi2 += d * d / pool_e;
            cells++;
        } else if (pool_o > 5.0 + 10.0 * pool_e) {
            chi2 = INFINITY; /* too many samples where almost none belong */
        }
    }
    size_t dof = cells > 1 ? cells - 1 : 1;
    if (chi2_out)
        *chi2_out = chi2;
    if (dof_out)
        *dof_out = dof;
    return isinf(chi2) ? 0.0 : gamma_q(0.5 * (double)dof, 0.5 * chi2);
}

/* ---- test BRDFs ------------------------------------------------------------- */

static const bwh_brdf_params_t phong = {.kd = 0.2, .ks = 0.7, .n = 40.0};
static const bwh_brdf_params_t ward = {.kd = 0.3, .ks = 0.6, .ax = 0.25, .ay = 0.08};

static double phong_cb(void *ctx, const double wi[3], const double wo[3])
{
    return bwh_brdf_phong(ctx, wi, wo);
}

static double ward_cb(void *ctx, const double wi[3], const double wo[3])
{
    return bwh_brdf_ward(ctx, wi, wo);
}

static void dir(double theta_deg, double phi_deg, double out[3])
{
    double t = theta_deg * PI / 180.0, p = phi_deg * PI / 180.0;
    out[0] = sin(t) * cos(p);
    out[1] = sin(t) * sin(p);
    out[2] = cos(t);
}

static int build_phong(bwh_sampler_t *s, const bwh_brdf_params_t *p, unsigned level, double mix)
{
    double th[32];
    for (int k = 0; k < 32; k++)
        th[k] = (k + 0.5) * 0.5 * PI / 32.0;
    return bwh_sampler_build(s, BWH_SAMPLER_ISO, level, 32, th, 0, phong_cb, (void *)p, 1, mix);
}

/* Ward: one table per incoming triangle of level 2, leaves of level 4 */
static int build_ward(bwh_sampler_t *s, double mix)
{
    return bwh_sampler_build(s, BWH_SAMPLER_FULL, 4, 64, NULL, 2, ward_cb, (void *)&ward, 1, mix);
}

/* An isotropic BRDF of `bands` channels tabulated in the codec's layout
 * [n_in][n_out][bands]: fn(ctx, wi, wo, out) at the incidences
 * (i + 1/2) 90 / n_in degrees (phi = 0) and the centres of the triangles of
 * `level`. NULL when out of memory. */
typedef void (*rgb_fn)(void *ctx, const double wi[3], const double wo[3], double *out);

static float *tabulate(unsigned level, size_t n_in, size_t bands, rgb_fn fn, void *ctx)
{
    size_t n_out = bwh_grid_count(level);
    double(*c)[3] = malloc(n_out * sizeof *c), v[8];
    float *x = malloc(n_in * n_out * bands * sizeof *x);
    if (!c || !x || bands > 8) {
        free(c);
        free(x);
        return NULL;
    }
    bwh_grid_centres(level, c, NULL);
    for (size_t i = 0; i < n_in; i++) {
        double wi[3];
        dir((i + 0.5) * 90.0 / (double)n_in, 0.0, wi);
        for (size_t o = 0; o < n_out; o++) {
            fn(ctx, wi, c[o], v);
            for (size_t k = 0; k < bands; k++)
                x[(i * n_out + o) * bands + k] = (float)v[k];
        }
    }
    free(c);
    return x;
}

static void rgl_rgb(void *ctx, const double wi[3], const double wo[3], double *out)
{
    bwr_rgl_eval(ctx, wi, wo, out);
}

/* measured: satin_rosaline (RGL) at level 4, 16 incidences, 3 bands, through
 * the codec at 20:1, as brdfwave import-rgl + encode --ratio 20 + decode */
static bwh_brdf_data_t measured;
static int have_measured;

static int load_measured(void)
{
    bwr_rgl_t rgl;
    char err[256];
    if (bwr_rgl_load(&rgl, "tests/data/rgl/satin_rosaline_rgb.bsdf", err, sizeof err) != 0) {
        fprintf(stderr, "rgl: %s\n", err);
        return -1;
    }
    const unsigned level = 4;
    const size_t n_in = 16, n_out = bwh_grid_count(level), bands = 3;
    float *x = tabulate(level, n_in, bands, rgl_rgb, &rgl);
    bwr_rgl_free(&rgl);
    if (!x)
        return -1;
    bw_dims_t dims = {.shape = BW_SHAPE_BRDF_ISO, .level_out = level, .n_in = (uint32_t)n_in,
                      .n_out = (uint32_t)n_out, .bands = (uint32_t)bands};
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_BYTES;
    o.basis = BW_BASIS_AUTO;
    o.byte_budget = 4 * n_in * n_out * bands / 20;
    uint8_t *payload;
    size_t len;
    int rc = bwh_encode_f32(&dims, x, &o, &payload, &len);
    free(x);
    if (rc != 0) {
        fprintf(stderr, "encode: %s\n", bwh_last_error());
        return -1;
    }
    bw_header_t h;
    int32_t *samples;
    float *values;
    rc = bwh_decode(payload, len, &h, &samples, &values);
    free(payload);
    if (rc != 0)
        return -1;
    free(samples);
    rc = bwh_brdf_data_init(&measured, &h.dims, values, NULL, 0.0, 0.0);
    free(values);
    return rc;
}

static int build_measured(bwh_sampler_t *s, unsigned level, double mix)
{
    return bwh_sampler_build(s, BWH_SAMPLER_ISO, level, measured.n_in, measured.theta_in, 0,
                             bwh_brdf_data_mean_cb, &measured, 1, mix);
}

static double measured_cb(void *ctx, const double wi[3], const double wo[3])
{
    return bwh_brdf_data_mean(ctx, wi, wo);
}

/* f straight from a payload (bwh_payload_eval, bwh_brdf_data_from_payload
 * decoding only the rows the directions read) is f of the whole decode
 * (bwh_brdf_data_from_payload of every row) at every direction pair, to
 * the bit: a full BRDF in segments (the rows alone), the same with the
 * reciprocity step (decoded whole), and the satin BRDF of 16 incidences
 * (two rows about each wi); a band past the last and a corrupt payload are
 * refused; an incoming direction whose rows were not decoded gives NAN. */
static void eval_against_whole(const uint8_t *p, size_t len, size_t bands, bool rows_alone,
                               const char *what)
{
    enum { N = 200 };
    static double wi[N][3], wo[N][3], lam[N], got[N], want[N];
    uint64_t r = 0x243F6A8885A308D3ull;
    for (int j = 0; j < N; j++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        dir((double)(r >> 40) / (double)(1u << 24) * 89.0, (double)(r & 0xFFFF) / 65536.0 * 360.0,
            wi[j]);
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        dir((double)(r >> 40) / (double)(1u << 24) * 89.0, (double)(r & 0xFFFF) / 65536.0 * 360.0,
            wo[j]);
        lam[j] = (double)(r % 1000u) / 999.0 * (double)(bands - 1u);
    }
    bwh_brdf_data_t all;
    assert_int_equal(bwh_brdf_data_from_payload(&all, p, len, NULL, 0), 0);
    double *work = malloc(bands * sizeof *work);
    assert_non_null(work);
    /* 6 pairs read a few rows (decoded alone); 200, most (decoded whole) */
    for (int mode = 0; mode < 6; mode++) {
        long band = mode % 3 == 1 ? (long)bands - 1 : -1;
        int cnt = mode < 3 ? 6 : N;
        if (bwh_payload_eval(p, len, (size_t)cnt, &wi[0][0], &wo[0][0], mode % 3 == 2 ? lam : NULL,
                             band, got) != 0)
            fail_msg("%s: %s", what, bwh_last_error());
        for (int j = 0; j < cnt; j++) {
            want[j] = mode % 3 == 2   ? bwh_brdf_data_eval(&all, wi[j], wo[j], lam[j], work)
                      : mode % 3 == 1 ? bwh_brdf_data_band(&all, wi[j], wo[j], (size_t)band)
                                      : bwh_brdf_data_mean(&all, wi[j], wo[j]);
            if (isnan(want[j]) || memcmp(&got[j], &want[j], sizeof got[j]))
                fail_msg("%s: mode %d, pair %d: %.17g, the whole decode's %.17g", what, mode, j,
                         got[j], want[j]);
        }
    }
    assert_int_equal(bwh_payload_eval(p, len, N, &wi[0][0], &wo[0][0], NULL, (long)bands, got), -1);
    /* f at a wavelength (every band located once) is the B-spline through
     * the bands' values, each located on its own */
    double *spl = malloc(bands * sizeof *spl);
    assert_non_null(spl);
    for (int j = 0; j < N; j++) {
        for (size_t k = 0; k < bands; k++)
            spl[k] = bwh_brdf_data_band(&all, wi[j], wo[j], k);
        double x = all.lambda_last != all.lambda_first
                       ? (lam[j] - all.lambda_first) / (all.lambda_last - all.lambda_first) *
                             (double)(bands - 1)
                       : 0.0;
        if (bands > 1)
            bwh_bspline_coefficients(spl, bands, spl);
        double f = bands > 1 ? bwh_bspline_eval(spl, bands, x) : spl[0];
        double g = bwh_brdf_data_eval(&all, wi[j], wo[j], lam[j], work);
        if (isnan(f) || memcmp(&f, &g, sizeof f))
            fail_msg("%s: pair %d at %g: %.17g, the bands' B-spline %.17g", what, j, lam[j], g, f);
    }
    free(spl);
    /* rows decoded for one incoming direction only: another far off is NAN */
    bwh_brdf_data_t one;
    assert_int_equal(bwh_brdf_data_from_payload(&one, p, len, (const double(*)[3])wi, 1), 0);
    assert_true(bwh_brdf_data_mean(&one, wi[0], wo[0]) == bwh_brdf_data_mean(&all, wi[0], wo[0]));
    double far[3];
    dir(wi[0][2] > 0.5 ? 80.0 : 5.0, 180.0, far);
    assert_true((one.row_of != NULL) == rows_alone);
    if (rows_alone)
        assert_true(isnan(bwh_brdf_data_mean(&one, far, wo[0])));
    bwh_brdf_data_free(&one);
    bwh_brdf_data_free(&all);
    free(work);
}

static void f_straight_from_a_payload_is_f_of_the_whole_decode(void **state)
{
    (void)state;
    const unsigned L = 3;
    size_t n = bwh_grid_count(L);
    float *x = malloc(n * n * sizeof *x);
    double(*c)[3] = malloc(n * sizeof *c);
    assert_non_null(x);
    assert_non_null(c);
    bwh_grid_centres(L, c, NULL);
    for (size_t i = 0; i < n; i++)
        for (size_t o = 0; o < n; o++)
            x[i * n + o] = (float)bwh_brdf_ward(&ward, c[i], c[o]);
    bw_dims_t dims = {.shape = BW_SHAPE_BRDF_FULL, .level_out = L, .level_in = L,
                      .n_in = (uint32_t)n, .n_out = (uint32_t)n, .bands = 1};
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_MAX_ERROR;
    o.basis = BW_BASIS_AUTO;
    o.max_error = 1000;
    o.segments = BW_CFG_SEGMENTS ? (uint32_t)n : 0u; /* (a core without them: one body) */
    for (int recip = 0; recip < 2; recip++) {
        o.flags = recip ? BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL : BW_FLAG_MIRROR;
        uint8_t *p;
        size_t len;
        if (bwh_encode_f32(&dims, x, &o, &p, &len) != 0)
            fail_msg("encode: %s", bwh_last_error());
        eval_against_whole(p, len, 1, !recip, recip ? "ward, reciprocity" : "ward, in segments");
        p[len / 2] ^= 1u;
        double wi[3] = {0, 0, 1}, out;
        assert_int_equal(bwh_payload_eval(p, len, 1, wi, wi, NULL, -1, &out), -1);
        free(p);
    }
    free(x);
    free(c);
    /* the satin BRDF of 16 incidences, 3 bands */
    bwr_rgl_t rgl;
    char err[256];
    assert_int_equal(bwr_rgl_load(&rgl, "tests/data/rgl/satin_rosaline_rgb.bsdf", err, sizeof err),
                     0);
    float *y = tabulate(3, 16, 3, rgl_rgb, &rgl);
    bwr_rgl_free(&rgl);
    assert_non_null(y);
    bw_dims_t d2 = {.shape = BW_SHAPE_BRDF_ISO, .level_out = 3, .n_in = 16,
                    .n_out = (uint32_t)bwh_grid_count(3), .bands = 3};
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_BYTES;
    o.basis = BW_BASIS_AUTO;
    o.byte_budget = 4000;
    o.segments = BW_CFG_SEGMENTS ? 16u : 0u;
    uint8_t *p;
    size_t len;
    if (bwh_encode_f32(&d2, y, &o, &p, &len) != 0)
        fail_msg("encode: %s", bwh_last_error());
    eval_against_whole(p, len, 3, true, "satin, 16 incidences");
    free(p);
    free(y);
}

static int setup(void **state)
{
    (void)state;
    const char *q = getenv("BW_TEST_QUICK");
    if (q && *q && strcmp(q, "0") != 0)
        N_SAMPLES = 100000L;
    have_measured = load_measured() == 0;
    return have_measured ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    bwh_brdf_data_free(&measured);
    return 0;
}

/* the leaf a sample falls in, in the sampler's frame (ISO: turned so that
 * phi_i = 0) */
static long leaf_of(const bwh_sampler_t *s, const double wi[3], const double wo[3])
{
    double l[3] = {wo[0], wo[1], wo[2]};
    if (s->kind == BWH_SAMPLER_ISO) {
        double r = hypot(wi[0], wi[1]), c = 1.0, sn = 0.0;
        if (r > 0.0) {
            c = wi[0] / r;
            sn = wi[1] / r;
        }
        l[0] = c * wo[0] + sn * wo[1];
        l[1] = -sn * wo[0] + c * wo[1];
    }
    if (l[2] < 0.0)
        l[2] = 0.0;
    return bwh_grid_locate(s->level, l);
}

/* chi-square of `drawn`'s samples against `model`'s leaf masses at wi;
 * also counts pdf disagreements between sample() and pdf(). */
static double chi2_test(const bwh_sampler_t *drawn, const bwh_sampler_t *model,
                        const double wi[3], long n, long *pdf_mismatch)
{
    size_t nl = model->n_leaves;
    long *obs = calloc(nl, sizeof *obs);
    double *ex = malloc(nl * sizeof *ex);
    assert_non_null(obs);
    assert_non_null(ex);
    long mism = 0;
    for (long i = 0; i < n; i++) {
        double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf;
        assert_int_equal(bwh_sampler_sample(drawn, wi, u, wo, &pdf, NULL), 0);
        long k = leaf_of(model, wi, wo);
        assert_true(k >= 0);
        obs[k]++;
        double p2 = bwh_sampler_pdf(drawn, wi, wo);
        if (p2 != pdf) /* the same product: equal to the bit */
            mism++;
    }
    double total = 0.0;
    for (size_t k = 0; k < nl; k++) {
        ex[k] = (double)n * bwh_sampler_leaf_mass(model, wi, k);
        total += ex[k];
    }
    assert_true(fabs(total - (double)n) < 1e-6 * (double)n);
    double chi2;
    size_t dof;
    double p = chi2_pvalue(obs, ex, nl, &chi2, &dof);
    printf("    wi (%.3f %.3f %.3f): chi2 %.1f, dof %zu, p %.4f\n", wi[0], wi[1], wi[2], chi2, dof,
           p);
    free(obs);
    free(ex);
    if (pdf_mismatch)
        *pdf_mismatch = mism;
    return p;
}

/* 1M samples at each of the incoming directions; Sidak over them */
static void chi2_brdf(const bwh_sampler_t *s, const double (*wi)[3], int n_wi)
{
    double alpha = 1.0 - pow(1.0 - 0.01, 1.0 / n_wi);
    for (int i = 0; i < n_wi; i++) {
        long mism;
        double p = chi2_test(s, s, wi[i], N_SAMPLES, &mism);
        if (p < alpha)
            fail_msg("chi-square rejects the sampler: p = %g < %g", p, alpha);
        /* a sample on a leaf edge may be located in the neighbour by rounding */
        assert_true(mism <= N_SAMPLES / 100000);
    }
}

static void sampler_phong_passes_chi_square(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_phong(&s, &phong, 4, 0.05), 0);
    double wi[3][3];
    dir(0.0, 0.0, wi[0]);
    dir(37.0, 0.0, wi[1]);
    dir(71.0, 123.0, wi[2]); /* between two tables, turned about the normal */
    chi2_brdf(&s, (const double(*)[3])wi, 3);
    bwh_sampler_free(&s);
}

static void sampler_ward_passes_chi_square(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_ward(&s, 0.05), 0);
    double wi[3][3];
    dir(10.0, 20.0, wi[0]);
    dir(45.0, 200.0, wi[1]);
    dir(75.0, 300.0, wi[2]);
    chi2_brdf(&s, (const double(*)[3])wi, 3);
    bwh_sampler_free(&s);
}

static void sampler_decoded_measured_passes_chi_square(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_measured(&s, 4, 0.05), 0);
    double wi[3][3];
    dir(5.0, 0.0, wi[0]);
    dir(40.0, 70.0, wi[1]);
    dir(80.0, 250.0, wi[2]);
    chi2_brdf(&s, (const double(*)[3])wi, 3);
    bwh_sampler_free(&s);
}

/* the centres (normalize(a + b + c)) of a sampler's leaves */
static double (*leaf_centres(const bwh_sampler_t *s))[3]
{
    double(*c)[3] = malloc(s->n_leaves * sizeof *c);
    assert_non_null(c);
    assert_int_equal(bwh_grid_centres(s->level, c, NULL), 0);
    return c;
}

/* Total variation distance between the sampler's leaf masses for wi and
 * max(0, f(wi_frame, centre)) times the leaf's projected solid angle,
 * normalised and mixed with the cosine lobe as the sampler is (wi_frame:
 * wi in the sampler's frame, turned to phi = 0 for ISO). */
static double leaf_mass_distance(const bwh_sampler_t *s, bwh_brdf_fn f, void *ctx,
                                 const double wi[3], const double wi_frame[3])
{
    double *m = malloc(s->n_leaves * sizeof *m), sum = 0.0, tv = 0.0;
    double(*c)[3] = leaf_centres(s);
    assert_non_null(m);
    for (size_t k = 0; k < s->n_leaves; k++) {
        double v = f(ctx, wi_frame, c[k]);
        m[k] = (v > 0.0 ? v : 0.0) * s->leaf[k].proj;
        sum += m[k];
    }
    for (size_t k = 0; k < s->n_leaves; k++) {
        double want = (1.0 - s->mix) * m[k] / sum + s->mix * s->leaf[k].proj / PI;
        tv += fabs(bwh_sampler_leaf_mass(s, wi, k) - want);
    }
    free(m);
    free(c);
    return 0.5 * tv;
}

/* The tables a sampler draws from belong to wi: at the incoming directions
 * it tabulates (FULL: the centres of the level_in triangles; ISO: the
 * tabulated zenith angles, at any azimuth) its leaf masses are those of the
 * BRDF there, up to the leaf quadrature; half way between two ISO tables,
 * up to the mixing of the two. */
static void sampler_draws_from_the_tables_of_wi(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_ward(&s, 0.05), 0);
    double cen[64][3];
    bwh_grid_centres(2, cen, NULL);
    static const size_t in[] = {0, 9, 21, 38, 50, 63};
    for (size_t i = 0; i < sizeof in / sizeof *in; i++) {
        double d = leaf_mass_distance(&s, ward_cb, (void *)&ward, cen[in[i]], cen[in[i]]);
        printf("    ward, incoming triangle %zu: distance %.4f\n", in[i], d);
        assert_true(d < 0.1); /* a neighbour's table: above 0.3 */
    }
    bwh_sampler_free(&s);

    assert_int_equal(build_phong(&s, &phong, 4, 0.05), 0);
    /* at a table, and half way to the next (where the two are mixed) */
    static const struct {
        size_t table;
        double phi;
    } at[] = {{0, 0.0}, {5, 40.0}, {17, 200.0}, {28, 310.0}};
    for (size_t i = 0; i < sizeof at / sizeof *at; i++) {
        for (int half = 0; half < 2; half++) {
            size_t k = at[i].table;
            double th = (half ? 0.5 * (s.theta[k] + s.theta[k + 1]) : s.theta[k]) * 180.0 / PI;
            double wi[3], frame[3];
            dir(th, at[i].phi, wi);
            dir(th, 0.0, frame);
            double d = leaf_mass_distance(&s, phong_cb, (void *)&phong, wi, frame);
            printf("    phong, %.2f deg at phi %.0f: distance %.4f\n", th, at[i].phi, d);
            assert_true(d < 0.02); /* the next table in place of one: above 0.03 */
        }
    }
    bwh_sampler_free(&s);
}

/* Three bands of different shapes: a lobe about the mirror direction, a
 * constant, a lobe about the incoming direction (back-scatter). */
static void three_lobes(void *ctx, const double wi[3], const double wo[3], double *out)
{
    (void)ctx;
    double cm = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2];
    double cb = wi[0] * wo[0] + wi[1] * wo[1] + wi[2] * wo[2];
    out[0] = cm > 0.0 ? pow(cm, 30.0) : 0.0;
    out[1] = 0.3;
    out[2] = cb > 0.0 ? pow(cb, 30.0) : 0.0;
}

static int synth_bands(bwh_brdf_data_t *d)
{
    const unsigned level = 4;
    const size_t n_in = 8, n_out = bwh_grid_count(level), bands = 3;
    float *x = tabulate(level, n_in, bands, three_lobes, NULL);
    if (!x)
        return -1;
    bw_dims_t dims = {.shape = BW_SHAPE_BRDF_ISO, .level_out = level, .n_in = (uint32_t)n_in,
                      .n_out = (uint32_t)n_out, .bands = (uint32_t)bands};
    int rc = bwh_brdf_data_init(d, &dims, x, NULL, 0.0, 0.0);
    free(x);
    return rc;
}

/* Sampling one channel on request (bwh_brdf_data_band_cb): the sampler of a
 * band follows that band, not the mean nor another band, and passes the
 * chi-square test. */
static void a_sampler_per_channel_follows_its_band(void **state)
{
    (void)state;
    bwh_brdf_data_t d;
    assert_int_equal(synth_bands(&d), 0);
    bwh_brdf_band_t band[2] = {{&d, 0}, {&d, 2}};
    double th = d.theta_in[3] * 180.0 / PI, wi[3], frame[3];
    dir(th, 70.0, wi);
    dir(th, 0.0, frame);
    for (int b = 0; b < 2; b++) {
        bwh_sampler_t s;
        assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 4, d.n_in, d.theta_in, 0,
                                           bwh_brdf_data_band_cb, &band[b], 1, 0.05),
                         0);
        double own = leaf_mass_distance(&s, bwh_brdf_data_band_cb, &band[b], wi, frame);
        double other = leaf_mass_distance(&s, bwh_brdf_data_band_cb, &band[1 - b], wi, frame);
        double mean = leaf_mass_distance(&s, bwh_brdf_data_mean_cb, &d, wi, frame);
        printf("    band %zu: distance to its band %.4f, to band %zu %.4f, to the mean %.4f\n",
               band[b].band, own, band[1 - b].band, other, mean);
        assert_true(own < 0.05); /* the leaf quadrature of a cos^30 lobe at level 4 */
        assert_true(other > 0.5 && mean > 0.2);
        long mism;
        double p = chi2_test(&s, &s, wi, N_SAMPLES, &mism);
        assert_true(p >= 1.0 - sqrt(1.0 - 0.01)); /* 0.01, Sidak over the 2 bands */
        assert_true(mism <= N_SAMPLES / 100000);
        bwh_sampler_free(&s);
    }
    bwh_brdf_data_free(&d);
}

static void chi_square_rejects_a_different_brdf(void **state)
{
    (void)state;
    bwh_sampler_t s20, s25;
    bwh_brdf_params_t p2 = phong;
    p2.n = 50.0; /* a lobe 10 % narrower in exponent */
    assert_int_equal(build_phong(&s20, &phong, 4, 0.05), 0);
    assert_int_equal(build_phong(&s25, &p2, 4, 0.05), 0);
    double wi[3];
    dir(30.0, 0.0, wi);
    double p = chi2_test(&s20, &s25, wi, N_SAMPLES / 4, NULL);
    assert_true(p < 1e-6);
    bwh_sampler_free(&s20);
    bwh_sampler_free(&s25);
}

/* Arvo's samples in grid triangle `index` of `level` fall in its 64
 * descendants three levels down in proportion to their solid angles. */
static void arvo_uniform_in(unsigned level, size_t index)
{
    bwh_tri_t t[256], sub[64];
    bwh_grid_triangles(level, t);
    bwh_leaf_t leaf;
    const bwh_tri_t *T = &t[index];
    bwh_leaf_init(&leaf, T->v[0], T->v[1], T->v[2]);
    sub[0] = *T;
    size_t n = 1;
    for (int l = 0; l < 3; l++) {
        bwh_tri_t tmp[64];
        for (size_t i = 0; i < n; i++)
            for (unsigned m = 0; m < 4; m++)
                bwh_tri_child(&sub[i], m, &tmp[4 * i + m]);
        n *= 4;
        memcpy(sub, tmp, n * sizeof *sub);
    }
    long obs[64] = {0};
    double ex[64];
    const long N = 400000;
    long first = (long)index * 64;
    for (long i = 0; i < N; i++) {
        double d[3];
        bwh_leaf_sample(&leaf, rnd(), rnd(), d);
        assert_true(fabs(bwg_dot3(d, d) - 1.0) < 1e-14);
        long k = bwh_grid_locate(level + 3, d);
        assert_true(k >= first && k < first + 64); /* inside the triangle */
        obs[k - first]++;
    }
    for (int i = 0; i < 64; i++)
        ex[i] = N * bwh_solid_angle(sub[i].v[0], sub[i].v[1], sub[i].v[2]) / leaf.area;
    double p = chi2_pvalue(obs, ex, 64, NULL, NULL);
    assert_true(p > 0.01);
}

static void arvo_samples_are_uniform_in_a_triangle(void **state)
{
    (void)state;
    arvo_uniform_in(1, 6);   /* a corner child of base 1: tan from libm */
    arvo_uniform_in(3, 150); /* solid angle below 0.1: its series */
}

/* With u2 = 1 Arvo's point is the vertex c' that cuts off the triangle
 * (a, b, c') of solid angle u1 times the leaf's. */
static void arvo_cuts_the_area_in_proportion_to_u1(void **state)
{
    (void)state;
    static const struct {
        unsigned level;
        size_t index;
    } leaf_of[] = {{0, 1}, {1, 6}, {3, 150}, {6, 9000}};
    for (size_t i = 0; i < sizeof leaf_of / sizeof *leaf_of; i++) {
        static bwh_tri_t t[16384];
        bwh_grid_triangles(leaf_of[i].level, t);
        const bwh_tri_t *T = &t[leaf_of[i].index];
        bwh_leaf_t leaf;
        bwh_leaf_init(&leaf, T->v[0], T->v[1], T->v[2]);
        for (int k = 1; k < 100; k++) {
            double u1 = k / 100.0, cp[3];
            bwh_leaf_sample(&leaf, u1, 1.0, cp);
            double part = bwh_solid_angle(leaf.a, leaf.b, cp) / leaf.area;
            /* the solid angles carry rounding of about 1e-15 */
            assert_true(fabs(part - u1) * leaf.area < 4e-14);
        }
    }
}

static void projected_solid_angles_add_up_to_pi(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_phong(&s, &phong, 5, 0.0), 0);
    double proj = 0.0, area = 0.0;
    for (size_t k = 0; k < s.n_leaves; k++) {
        proj += s.leaf[k].proj;
        area += s.leaf[k].area;
    }
    assert_true(fabs(proj - PI) < 1e-12);
    assert_true(fabs(area - 2.0 * PI) < 1e-12);
    bwh_sampler_free(&s);
}

/* integral of pdf over the hemisphere and over each leaf: midpoint sums
 * over the sub-triangles two levels below the leaves (the tree part is
 * constant there; only the cosine part carries quadrature error) */
static void pdf_integrates_to_one(void **state)
{
    (void)state;
    bwh_sampler_t s[3];
    assert_int_equal(build_phong(&s[0], &phong, 4, 0.1), 0);
    assert_int_equal(build_ward(&s[1], 0.1), 0);
    assert_int_equal(build_measured(&s[2], 4, 0.1), 0);
    size_t n6 = bwh_grid_count(6);
    double(*c)[3] = malloc(n6 * sizeof *c), *a = malloc(n6 * sizeof *a);
    assert_non_null(c);
    assert_non_null(a);
    bwh_grid_centres(6, c, a);
    double wis[2][3];
    dir(20.0, 0.0, wis[0]);
    dir(63.0, 140.0, wis[1]);
    for (int b = 0; b < 3; b++)
        for (int w = 0; w < 2; w++) {
            const double *wi = wis[w];
            double total = 0.0, mass_total = 0.0, worst = 0.0;
            /* ISO samplers are binned in the turned frame: integrate there */
            double r = hypot(wi[0], wi[1]), cs = wi[0] / r, sn = wi[1] / r;
            if (s[b].kind != BWH_SAMPLER_ISO) {
                cs = 1.0;
                sn = 0.0;
            }
            for (size_t leaf = 0; leaf < s[b].n_leaves; leaf++) {
                double in_leaf = 0.0;
                for (size_t q = 16 * leaf; q < 16 * leaf + 16; q++) {
                    double wo[3] = {cs * c[q][0] - sn * c[q][1], sn * c[q][0] + cs * c[q][1],
                                    c[q][2]};
                    in_leaf += bwh_sampler_pdf(&s[b], wi, wo) * a[q];
                }
                double m = bwh_sampler_leaf_mass(&s[b], wi, leaf);
                worst = fmax(worst, fabs(in_leaf - m) / m);
                total += in_leaf;
                mass_total += m;
            }
            printf("    brdf %d: int pdf = %.8f, sum of leaf masses = %.15f, worst leaf %.2e\n",
                   b, total, mass_total, worst);
            assert_true(fabs(total - 1.0) < 2e-4);
            assert_true(fabs(mass_total - 1.0) < 1e-12);
            assert_true(worst < 2e-3);
        }
    free(c);
    free(a);
    for (int b = 0; b < 3; b++)
        bwh_sampler_free(&s[b]);
}

/* reference albedo: midpoint sum at level 6, 4^2 points per triangle; its
 * error estimated against the level-5 sum (second order: difference / 3) */
static double albedo_ref(bwh_brdf_fn f, void *ctx, const double wi[3], double *err)
{
    double q[2];
    for (int pass = 0; pass < 2; pass++) {
        unsigned level = pass ? 6 : 5;
        size_t n = bwh_grid_count(level);
        bwh_tri_t *t = malloc(n * sizeof *t);
        assert_non_null(t);
        bwh_grid_triangles(level, t);
        double sum = 0.0;
        for (size_t k = 0; k < n; k++)
            for (unsigned m = 0; m < 4; m++) {
                bwh_tri_t c1;
                bwh_tri_child(&t[k], m, &c1);
                for (unsigned m2 = 0; m2 < 4; m2++) {
                    bwh_tri_t c2;
                    bwh_tri_child(&c1, m2, &c2);
                    double d[3];
                    bwh_tri_centre(&c2, d);
                    sum += f(ctx, wi, d) *
                           bwh_projected_solid_angle(c2.v[0], c2.v[1], c2.v[2]);
                }
            }
        q[pass] = sum;
        free(t);
    }
    *err = fabs(q[1] - q[0]) / 3.0;
    return q[1];
}

static void albedo_estimator_is_unbiased(void **state)
{
    (void)state;
    struct {
        bwh_brdf_fn f;
        void *ctx;
        double theta, phi;
    } cases[] = {
        {phong_cb, (void *)&phong, 0.0, 0.0},
        {phong_cb, (void *)&phong, 55.0, 30.0},
        {ward_cb, (void *)&ward, 35.0, 60.0},
        {measured_cb, &measured, 50.0, 200.0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        bwh_sampler_t s;
        if (c < 2)
            assert_int_equal(build_phong(&s, &phong, 4, 0.05), 0);
        else if (c == 2)
            assert_int_equal(build_ward(&s, 0.05), 0);
        else
            assert_int_equal(build_measured(&s, 4, 0.05), 0);
        double wi[3];
        dir(cases[c].theta, cases[c].phi, wi);
        double qerr, ref = albedo_ref(cases[c].f, cases[c].ctx, wi, &qerr);
        if (c == 0)
            ref = phong.kd + phong.ks, qerr = 0.0; /* exact at normal incidence */
        double sum = 0.0, sum2 = 0.0;
        for (long i = 0; i < N_SAMPLES; i++) {
            double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf, value;
            assert_int_equal(bwh_sampler_sample(&s, wi, u, wo, &pdf, &value), 0);
            double v = cases[c].f(cases[c].ctx, wi, wo);
            assert_true(value == (v > 0.0 ? v : 0.0)); /* sample's value: f, clamped */
            double est = wo[2] > 0.0 && pdf > 0.0 ? v * wo[2] / pdf : 0.0;
            sum += est;
            sum2 += est * est;
        }
        double mean = sum / N_SAMPLES, var = sum2 / N_SAMPLES - mean * mean;
        double se = sqrt(var / N_SAMPLES);
        printf("    case %zu: estimate %.6f, reference %.6f (+- %.1e), standard error %.1e\n", c,
               mean, ref, qerr, se);
        assert_true(fabs(mean - ref) <= 4.0 * se + qerr);
        bwh_sampler_free(&s);
    }
}

static double with_negative(void *ctx, const double wi[3], const double wo[3])
{
    (void)ctx;
    (void)wi;
    /* half the hemisphere negative, across leaves (not along a base edge) */
    return wo[0] > 0.25 * wo[1] ? 1.0 : -0.5;
}

static void negative_values_are_clamped_alike_in_sample_and_pdf(void **state)
{
    (void)state;
    bwh_sampler_t s;
    double th[1] = {0.0};
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 3, 1, th, 0, with_negative, NULL, 0,
                                       0.0),
                     0);
    double wi[3] = {0.0, 0.0, 1.0};
    double(*c)[3] = leaf_centres(&s);
    size_t zero = 0;
    long neg = 0;
    for (size_t k = 0; k < s.n_leaves; k++) {
        /* supersample 0: f at the centre only */
        if (with_negative(NULL, wi, c[k]) < 0.0) {
            assert_true(bwh_sampler_leaf_mass(&s, wi, k) == 0.0);
            assert_true(bwh_sampler_pdf(&s, wi, c[k]) == 0.0);
            zero++;
        }
    }
    free(c);
    assert_true(zero > s.n_leaves / 3);
    for (int i = 0; i < 100000; i++) {
        double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf, value;
        assert_int_equal(bwh_sampler_sample(&s, wi, u, wo, &pdf, &value), 0);
        long k = bwh_grid_locate(3, wo);
        assert_true(bwh_sampler_leaf_mass(&s, wi, (size_t)k) > 0.0);
        assert_true(pdf > 0.0);
        /* a leaf across the edge of the negative half: its value there is 0 */
        assert_true(value == (with_negative(NULL, wi, wo) > 0.0 ? 1.0 : 0.0));
        neg += value == 0.0;
    }
    printf("    %ld of 100000 draws where f < 0 (value 0)\n", neg);
    assert_true(neg > 0);
    bwh_sampler_free(&s);
}

static double faint_half(void *ctx, const double wi[3], const double wo[3])
{
    (void)ctx;
    (void)wi;
    return wo[0] > 0.0 ? 1.0 : 1e-12; /* half the hemisphere nearly 0, not 0 */
}

/* The leaves' parts are rounded to 2^-31 of the table, but a leaf whose
 * integral is positive keeps at least one unit: the tree alone (no cosine lobe) still
 * reaches every direction where f > 0, as often as its pdf says. */
static void a_faint_region_keeps_a_positive_pdf(void **state)
{
    (void)state;
    bwh_sampler_t s;
    double th[1] = {0.0};
    assert_int_equal(
        bwh_sampler_build(&s, BWH_SAMPLER_ISO, 3, 1, th, 0, faint_half, NULL, 0, 0.0), 0);
    double wi[3] = {0.0, 0.0, 1.0}, (*c)[3] = leaf_centres(&s), faint = 0.0;
    for (size_t k = 0; k < s.n_leaves; k++) {
        double m = bwh_sampler_leaf_mass(&s, wi, k);
        assert_true(m > 0.0);
        if (c[k][0] <= 0.0) {
            assert_true(fabs(m * 0x1p31 - 1.0) < 1e-12); /* its integral rounds to 0: one unit */
            faint += m;
        }
    }
    free(c);
    long hits = 0;
    for (long i = 0; i < N_SAMPLES; i++) {
        double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf;
        assert_int_equal(bwh_sampler_sample(&s, wi, u, wo, &pdf, NULL), 0);
        assert_true(pdf > 0.0);
        hits += wo[0] <= 0.0;
    }
    double want = faint * N_SAMPLES;
    printf("    faint half: mass %.3g, %ld draws of %ld (expected %.1f)\n", faint, hits,
           (long)N_SAMPLES, want);
    assert_true(faint > 0.0 && faint < 1e-3);
    assert_true(fabs((double)hits - want) <= 5.0 * sqrt(want) + 1.0);
    bwh_sampler_free(&s);
}

/* The descent (two levels a step, from the top kept level down) and the
 * linear scan find the same leaf at every level, odd and even. */
static void tree_and_linear_scan_pick_the_same_leaf(void **state)
{
    (void)state;
    for (unsigned level = 0; level <= BWH_SAMPLER_MAX_LEVEL; level++) {
        bwh_sampler_t s;
        assert_int_equal(build_phong(&s, &phong, level, 0.0), 0);
        double wi[3];
        dir(33.0, 10.0, wi);
        int same = 0;
        for (int i = 0; i < 20000; i++) {
            double u[3] = {rnd(), rnd(), rnd()}, a[3], b[3], pa, pb;
            assert_int_equal(bwh_sampler_sample(&s, wi, u, a, &pa, NULL), 0);
            assert_int_equal(bwh_sampler_sample_linear(&s, wi, u, b, &pb, NULL), 0);
            same += a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && pa == pb;
        }
        printf("    level %u: %d of 20000 the same\n", level, same);
        assert_int_equal(same, 20000);
        bwh_sampler_free(&s);
    }
}

/* The table search by buckets of cos(theta_i) finds the tables the binary
 * search does (the same sampler with its bucket map taken away draws the
 * same directions with the same pdf); tables closer than the finest bucket
 * make the build fall back to the search, which passes chi-square. */
static void the_table_buckets_agree_with_the_search(void **state)
{
    (void)state;
    bwh_sampler_t s;
    assert_int_equal(build_phong(&s, &phong, 3, 0.05), 0);
    assert_non_null(s.zmap);
    bwh_sampler_t plain = s;
    plain.zmap = NULL;
    for (int i = 0; i < 200000; i++) {
        double wi[3], u[3] = {rnd(), rnd(), rnd()}, a[3], b[3], pa, pb;
        dir(90.0 * rnd(), 360.0 * rnd(), wi);
        if (i % 1000 == 0) /* exactly at a table */
            dir((i / 1000 % 32 + 0.5) * 90.0 / 32.0, 45.0, wi);
        int ra = bwh_sampler_sample(&s, wi, u, a, &pa, NULL);
        int rb = bwh_sampler_sample(&plain, wi, u, b, &pb, NULL);
        assert_int_equal(ra, rb);
        if (ra == 0)
            assert_true(a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && pa == pb);
    }
    bwh_sampler_free(&s);

    const double th[6] = {0.0, 0.002, 0.4, 0.8, 1.2, 1.5}; /* cosines 2e-6 apart */
    assert_int_equal(
        bwh_sampler_build(&s, BWH_SAMPLER_ISO, 4, 6, th, 0, phong_cb, (void *)&phong, 1, 0.05),
        0);
    assert_null(s.zmap);
    double wi[3][3];
    dir(0.06, 0.0, wi[0]); /* between the two close tables */
    dir(30.0, 80.0, wi[1]);
    dir(75.0, 200.0, wi[2]);
    chi2_brdf(&s, (const double(*)[3])wi, 3);
    bwh_sampler_free(&s);
}

static void bad_input_is_refused(void **state)
{
    (void)state;
    bwh_sampler_t s;
    double th[2] = {0.5, 0.2};
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 7, 1, th, 0, phong_cb,
                                       (void *)&phong, 0, 0.0),
                     -1);
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 3, 2, th, 0, phong_cb,
                                       (void *)&phong, 0, 0.0),
                     -1); /* not ascending */
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_FULL, 3, 5, NULL, 1, phong_cb,
                                       (void *)&phong, 0, 0.0),
                     -1);
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 3, 1, th, 0, phong_cb,
                                       (void *)&phong, 0, 1.5),
                     -1);
    assert_int_equal(bwh_sampler_build(&s, BWH_SAMPLER_ISO, 3, 1, th, 0, phong_cb,
                                       (void *)&phong, 4, 0.0),
                     -1);
    assert_int_equal(build_phong(&s, &phong, 3, 0.1), 0);
    double below[3] = {0.6, 0.0, -0.8}, nan[3] = {NAN, 0.0, 1.0}, up[3] = {0.0, 0.0, 1.0};
    double u[3] = {0.3, 0.3, 0.3}, wo[3] = {9, 9, 9}, pdf = -1.0;
    assert_int_equal(bwh_sampler_sample(&s, below, u, wo, &pdf, NULL), -1);
    assert_int_equal(bwh_sampler_sample(&s, nan, u, wo, &pdf, NULL), -1);
    assert_true(wo[0] == 9.0 && pdf == -1.0);
    assert_true(bwh_sampler_pdf(&s, below, up) == 0.0);
    assert_true(bwh_sampler_pdf(&s, up, below) == 0.0);
    /* random numbers outside [0, 1) are clamped: a unit wo with a positive
     * pdf (at 0 or 1 - 2^-53 it lies on its leaf's edge or vertex, where
     * pdf() may take the neighbour's) */
    const double bad_u[4][3] = {
        {-0.5, 1.5, 0.5}, {1.0, 1.0, 1.0}, {NAN, NAN, NAN}, {0.5, -1e300, 1e300}};
    double wi[3];
    dir(40.0, 30.0, wi);
    for (int i = 0; i < 4; i++) {
        assert_int_equal(bwh_sampler_sample(&s, wi, bad_u[i], wo, &pdf, NULL), 0);
        assert_true(fabs(bwg_dot3(wo, wo) - 1.0) < 1e-14 && wo[2] >= 0.0);
        assert_true(pdf > 0.0 && isfinite(pdf) && bwh_sampler_pdf(&s, wi, wo) > 0.0);
    }
    bwh_sampler_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(projected_solid_angles_add_up_to_pi),
        cmocka_unit_test(arvo_samples_are_uniform_in_a_triangle),
        cmocka_unit_test(arvo_cuts_the_area_in_proportion_to_u1),
        cmocka_unit_test(sampler_phong_passes_chi_square),
        cmocka_unit_test(sampler_ward_passes_chi_square),
        cmocka_unit_test(sampler_decoded_measured_passes_chi_square),
        cmocka_unit_test(f_straight_from_a_payload_is_f_of_the_whole_decode),
        cmocka_unit_test(sampler_draws_from_the_tables_of_wi),
        cmocka_unit_test(a_sampler_per_channel_follows_its_band),
        cmocka_unit_test(chi_square_rejects_a_different_brdf),
        cmocka_unit_test(pdf_integrates_to_one),
        cmocka_unit_test(albedo_estimator_is_unbiased),
        cmocka_unit_test(negative_values_are_clamped_alike_in_sample_and_pdf),
        cmocka_unit_test(a_faint_region_keeps_a_positive_pdf),
        cmocka_unit_test(tree_and_linear_scan_pick_the_same_leaf),
        cmocka_unit_test(the_table_buckets_agree_with_the_search),
        cmocka_unit_test(bad_input_is_refused),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
