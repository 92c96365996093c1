/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Measured RGL BRDFs (host-tools/ref/bwr_rgl.c): the 2-D warp and its
 * inverse on synthetic tables, then the three files of tests/data/rgl:
 * structure, physical plausibility (a near-Lambertian paper, albedo,
 * reciprocity), the cosine convention, and rejection of damaged files.
 */
#define _DEFAULT_SOURCE /* mkstemp */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bwr_rgl.h"
#include "bwr_geodesic.h"
#include "ref_test_util.h"

#define DATA "tests/data/rgl/"
#define PI 3.14159265358979323846

static void warp_round_trip_and_density(void **state)
{
    (void)state;
    /* 5 columns x 4 rows, two parameter slices */
    float d[2 * 20];
    rt_seed(50);
    for (int i = 0; i < 40; i++)
        d[i] = (float)(0.1 + rt_uniform());
    d[7] = 0.0f; /* a zero corner */
    const double pv[2] = {0.0, 1.0};
    const double *pvp[1] = {pv};
    uint32_t pr[1] = {2};
    bwr_warp_t w;
    assert_int_equal(bwr_warp_init(&w, 5, 4, d, 1, pr, pvp, 1), 0);
    for (int k = 0; k < 500; k++) {
        double u[2] = {rt_uniform(), rt_uniform()}, par = rt_uniform(), s[2], v[2], p1, p2;
        bwr_warp_sample(&w, u, &par, s, &p1);
        assert_true(s[0] >= 0.0 && s[0] <= 1.0 && s[1] >= 0.0 && s[1] <= 1.0);
        bwr_warp_invert(&w, s, &par, v, &p2);
        assert_true(fabs(v[0] - u[0]) < 1e-12 && fabs(v[1] - u[1]) < 1e-12);
        assert_true(fabs(p1 - p2) < 1e-12 * p1);
        assert_true(fabs(bwr_warp_eval(&w, s, &par) - p1) < 1e-12 * p1);
    }
    /* corners map to corners; the density integrates to 1 in each slice */
    for (int sl = 0; sl < 2; sl++) {
        double par = sl, o[2], z[2] = {0.0, 0.0}, one[2] = {1.0, 1.0}, sum = 0.0;
        bwr_warp_invert(&w, z, &par, o, NULL);
        assert_true(fabs(o[0]) < 1e-15 && fabs(o[1]) < 1e-15);
        bwr_warp_invert(&w, one, &par, o, NULL);
        assert_true(fabs(o[0] - 1.0) < 1e-12 && fabs(o[1] - 1.0) < 1e-12);
        const int N = 400;
        for (int i = 0; i < N; i++)
            for (int j = 0; j < N; j++) {
                double q[2] = {(i + 0.5) / N, (j + 0.5) / N};
                sum += bwr_warp_eval(&w, q, &par) / (N * N);
            }
        assert_true(fabs(sum - 1.0) < 1e-4);
    }
    bwr_warp_free(&w);
    /* without CDFs, eval is the bilinear interpolation of the data, linear
     * in the parameter */
    assert_int_equal(bwr_warp_init(&w, 5, 4, d, 1, pr, pvp, 0), 0);
    double node[2] = {0.25, 1.0 / 3.0}, p0 = 0.0, p1 = 1.0, ph = 0.25;
    assert_true(fabs(bwr_warp_eval(&w, node, &p0) - d[1 * 5 + 1]) < 1e-7);
    assert_true(fabs(bwr_warp_eval(&w, node, &p1) - d[20 + 1 * 5 + 1]) < 1e-7);
    assert_true(fabs(bwr_warp_eval(&w, node, &ph) - (0.75 * d[6] + 0.25 * d[26])) < 1e-7);
    double mid[2] = {0.125, 1.0 / 6.0};
    assert_true(fabs(bwr_warp_eval(&w, mid, &p0) - 0.25 * (d[0] + d[1] + d[5] + d[6])) < 1e-7);
    bwr_warp_free(&w);
}

static const char *files[3] = {DATA "paper_white_rgb.bsdf", DATA "cc_ibiza_sunset_rgb.bsdf",
                               DATA "satin_rosaline_rgb.bsdf"};

static void files_load_with_their_structure(void **state)
{
    (void)state;
    static const char *desc[3] = {"White A4 paper", "Ibiza Sunset", "Rosaline Satin"};
    for (int k = 0; k < 3; k++) {
        bwr_rgl_t b;
        char err[256];
        assert_int_equal(bwr_rgl_load(&b, files[k], err, sizeof err), 0);
        assert_non_null(strstr(b.description, desc[k]));
        assert_int_equal(b.n_theta, 8);
        assert_int_equal(b.n_phi, 1);
        assert_true(b.isotropic && b.jacobian);
        assert_true(fabs(b.theta_i[0]) < 1e-6 && fabs(b.theta_i[7] - PI / 2) < 1e-5);
        assert_int_equal(b.vndf.size[0], 128);
        assert_int_equal(b.rgb.size[0], 32);
        /* below the horizon: nothing; f cos = eval_cos */
        double wi[3] = {0.5, 0.0, sqrt(0.75)}, wo[3] = {0.0, 0.6, 0.8}, dn[3] = {0.0, 0.6, -0.8};
        double f[3], fc[3];
        bwr_rgl_eval(&b, wi, dn, f);
        assert_true(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
        bwr_rgl_eval(&b, wi, wo, f);
        bwr_rgl_eval_cos(&b, wi, wo, fc);
        for (int c = 0; c < 3; c++)
            assert_true(fabs(f[c] * wo[2] - fc[c]) < 1e-12);
        bwr_rgl_free(&b);
    }
}

/* white paper: nearly Lambertian f ~ albedo / pi, which fixes the cosine
 * convention (f cos would fall like cos(theta_o)); albedo below 1 */
static void paper_is_nearly_lambertian(void **state)
{
    (void)state;
    bwr_rgl_t b;
    char err[256];
    assert_int_equal(bwr_rgl_load(&b, files[0], err, sizeof err), 0);
    double wi[3] = {sin(0.5), 0.0, cos(0.5)}, f0[3];
    double up[3] = {0.0, 0.0, 1.0};
    bwr_rgl_eval(&b, wi, up, f0);
    assert_true(f0[1] > 0.2 && f0[1] < 0.35);
    for (int t = 10; t <= 60; t += 10) {
        double th = t * PI / 180.0, wo[3] = {0.0, sin(th), cos(th)}, f[3];
        bwr_rgl_eval(&b, wi, wo, f);
        assert_true(fabs(f[1] / f0[1] - 1.0) < 0.1);
    }
    /* directional albedo by quadrature on the geodesic grid */
    size_t n = bwr_grid_count(5);
    double(*xyz)[3] = malloc(n * sizeof *xyz), *a = malloc(n * sizeof *a);
    bwr_grid_centres(5, xyz, a);
    for (int ti = 0; ti <= 60; ti += 30) {
        double th = ti * PI / 180.0, w[3] = {sin(th), 0.0, cos(th)}, s = 0.0;
        for (size_t k = 0; k < n; k++) {
            double f[3];
            bwr_rgl_eval_cos(&b, w, xyz[k], f);
            s += f[1] * a[k];
        }
        assert_true(s > 0.7 && s < 1.0);
    }
    /* reciprocity, through the interpolation between measured incidences */
    double diffs[400];
    rt_seed(51);
    for (int k = 0; k < 400; k++) {
        double t1 = acos(1.0 - 0.9 * rt_uniform()), t2 = acos(1.0 - 0.9 * rt_uniform());
        double p = 2.0 * PI * rt_uniform();
        double w1[3] = {sin(t1), 0.0, cos(t1)};
        double w2[3] = {sin(t2) * cos(p), sin(t2) * sin(p), cos(t2)}, fa[3], fb[3];
        bwr_rgl_eval(&b, w1, w2, fa);
        bwr_rgl_eval(&b, w2, w1, fb);
        diffs[k] = fabs(fa[1] - fb[1]) / (0.5 * (fa[1] + fb[1]));
    }
    int small = 0;
    for (int k = 0; k < 400; k++)
        small += diffs[k] < 0.05;
    assert_true(small > 300);
    free(xyz);
    free(a);
    bwr_rgl_free(&b);
}

static int write_bytes(const char *path, const unsigned char *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return -1;
    size_t w = fwrite(p, 1, n, f);
    fclose(f);
    return w == n ? 0 : -1;
}

static void damaged_files_are_rejected(void **state)
{
    (void)state;
    bwr_rgl_t b;
    char err[256];
    assert_int_equal(bwr_rgl_load(&b, DATA "none.bsdf", err, sizeof err), -1);
    assert_non_null(strstr(err, "cannot open"));
    FILE *f = fopen(files[0], "rb");
    assert_non_null(f);
    unsigned char *buf = malloc(700000);
    size_t n = fread(buf, 1, 700000, f);
    fclose(f);
    char tmp[] = "/tmp/bwr_rgl_XXXXXX";
    int fd = mkstemp(tmp);
    assert_true(fd >= 0);
    close(fd);
    /* truncated in the field table, truncated in the data, bad magic,
     * bad version, a renamed field */
    size_t cuts[2] = {40, n / 2};
    for (int k = 0; k < 2; k++) {
        assert_int_equal(write_bytes(tmp, buf, cuts[k]), 0);
        err[0] = '\0';
        assert_int_equal(bwr_rgl_load(&b, tmp, err, sizeof err), -1);
        assert_true(err[0] != '\0');
    }
    buf[0] = 'x';
    write_bytes(tmp, buf, n);
    assert_int_equal(bwr_rgl_load(&b, tmp, err, sizeof err), -1);
    buf[0] = 't';
    buf[12] = 2;
    write_bytes(tmp, buf, n);
    assert_int_equal(bwr_rgl_load(&b, tmp, err, sizeof err), -1);
    buf[12] = 1;
    unsigned char *p = NULL;
    for (size_t i = 0; i + 4 < 400 && p == NULL; i++)
        if (memcmp(buf + i, "vndf", 4) == 0)
            p = buf + i;
    assert_non_null(p);
    p[0] = 'w';
    write_bytes(tmp, buf, n);
    assert_int_equal(bwr_rgl_load(&b, tmp, err, sizeof err), -1);
    assert_non_null(strstr(err, "not an RGB RGL file"));
    p[0] = 'v';
    write_bytes(tmp, buf, n);
    assert_int_equal(bwr_rgl_load(&b, tmp, err, sizeof err), 0);
    bwr_rgl_free(&b);
    remove(tmp);
    free(buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(warp_round_trip_and_density),
        cmocka_unit_test(files_load_with_their_structure),
        cmocka_unit_test(paper_is_nearly_lambertian),
        cmocka_unit_test(damaged_files_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
