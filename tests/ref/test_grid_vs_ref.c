/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Two geodesic grids computed apart: the codec's host grid
 * (host-tools/lib/geodesic.c, solid angles by Van Oosterom and Strackee),
 * with the core's Q16 weight and Q31 area tables generated from it, against
 * the reference model's (host-tools/ref/bwr_geodesic.c, L'Huilier's theorem).
 * They share only the numbering convention, so a wrong direction, a wrong
 * area formula in either, or stale tables in the core make this test fail.
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

#include "bw_geodesic.h"
#include "bwr_geodesic.h"
#include "geodesic.h"
#include "ref_test_util.h"

#define PI 3.14159265358979323846

/* the same directions, bit for bit, and the same vertices */
static void directions_and_vertices_are_the_same_at_every_level(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWR_GRID_MAX_LEVEL; l++) {
        size_t n = bwr_grid_count(l);
        assert_int_equal(n, bwh_grid_count(l));
        bwr_tri_t *r = malloc(n * sizeof *r);
        bwh_tri_t *h = malloc(n * sizeof *h);
        double(*dr)[3] = malloc(n * sizeof *dr), (*dh)[3] = malloc(n * sizeof *dh);
        assert_non_null(r);
        assert_non_null(h);
        assert_non_null(dr);
        assert_non_null(dh);
        assert_int_equal(bwr_grid_triangles(l, r), 0);
        assert_int_equal(bwh_grid_triangles(l, h), 0);
        assert_int_equal(bwr_grid_centres(l, dr, NULL), 0);
        assert_int_equal(bwh_grid_centres(l, dh, NULL), 0);
        for (size_t i = 0; i < n; i++) {
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++)
                    assert_true(r[i].v[v][k] == h[i].v[v][k]);
            assert_memory_equal(dr[i], dh[i], sizeof dr[i]);
        }
        free(r);
        free(h);
        free(dr);
        free(dh);
    }
}

/* the two area formulas agree within 1e-12 of each triangle's area */
static void the_two_area_formulas_agree(void **state)
{
    (void)state;
    double worst = 0.0;
    for (unsigned l = 0; l <= BWR_GRID_MAX_LEVEL; l++) {
        size_t n = bwr_grid_count(l);
        double(*xyz)[3] = malloc(n * sizeof *xyz), *ar = malloc(n * sizeof *ar),
               *ah = malloc(n * sizeof *ah);
        assert_non_null(xyz);
        assert_non_null(ar);
        assert_non_null(ah);
        assert_int_equal(bwr_grid_centres(l, xyz, ar), 0);
        assert_int_equal(bwh_grid_centres(l, xyz, ah), 0);
        double sum = 0.0;
        for (size_t i = 0; i < n; i++) {
            worst = fmax(worst, fabs(ar[i] - ah[i]) / ah[i]);
            sum += ar[i];
        }
        assert_true(fabs(sum - 2.0 * PI) < 1e-11);
        free(xyz);
        free(ar);
        free(ah);
    }
    printf("largest relative difference of the solid angles: %.3g\n", worst);
    assert_true(worst < 1e-12);
}

/* the core's tables (generated from the host grid) within rounding of what
 * the reference's solid angles give */
static void the_core_tables_match_the_reference_solid_angles(void **state)
{
    (void)state;
    double(*c)[3] = malloc(bwr_grid_count(BWR_GRID_MAX_LEVEL) * sizeof *c);
    double *a[BWR_GRID_MAX_LEVEL + 1];
    assert_non_null(c);
    for (unsigned l = 0; l <= BWR_GRID_MAX_LEVEL; l++) {
        a[l] = malloc(bwr_grid_count(l) * sizeof *a[l]);
        assert_non_null(a[l]);
        assert_int_equal(bwr_grid_centres(l, c, a[l]), 0);
    }
    double worst_w = 0.0, worst_a = 0.0;
    for (unsigned j = 0; j < BW_GEO_TABLE_LEVELS; j++)
        for (uint32_t p = 0; p < (1u << (2u * j)); p++) {
            uint16_t w[3];
            bw_geo_weights(j, p, w);
            double ap = a[j][p];
            for (unsigned m = 1; m <= 3; m++) {
                double exact = 65536.0 * a[j + 1][4 * p + m] / ap;
                worst_w = fmax(worst_w, fabs((double)w[m - 1] - exact));
            }
        }
    for (unsigned j = 0; j < BW_GEO_AREA_LEVELS; j++)
        for (uint32_t i = 0; i < bwr_grid_count(j); i++)
            worst_a = fmax(worst_a, fabs((double)bw_geo_area(j, i) -
                                         2147483648.0 * a[j][i] / (PI / 2.0)));
    printf("largest table error: weights %.4f LSB (Q16), areas %.4f LSB (Q31)\n", worst_w,
           worst_a);
    /* rounding to the nearest step, and the two formulas' 1e-12 */
    assert_true(worst_w <= 0.5 + 1e-6);
    assert_true(worst_a <= 0.5 + 1e-2);
    for (unsigned l = 0; l <= BWR_GRID_MAX_LEVEL; l++)
        free(a[l]);
    free(c);
}

/* both grids find the same triangle for directions off the edges */
static void both_grids_locate_the_same_triangle(void **state)
{
    (void)state;
    rt_seed(11);
    for (unsigned l = 0; l <= BWR_GRID_MAX_LEVEL; l++)
        for (int k = 0; k < 4000; k++) {
            double z = rt_uniform(), phi = 2.0 * PI * rt_uniform(), r = sqrt(1.0 - z * z);
            double d[3] = {r * cos(phi), r * sin(phi), z};
            assert_int_equal(bwr_grid_locate(l, d), bwh_grid_locate(l, d));
        }
    double below[3] = {0.0, 0.6, -0.8};
    assert_int_equal(bwr_grid_locate(3, below), -1);
    assert_int_equal(bwr_grid_locate(7, (double[3]){0, 0, 1}), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(directions_and_vertices_are_the_same_at_every_level),
        cmocka_unit_test(the_two_area_formulas_agree),
        cmocka_unit_test(the_core_tables_match_the_reference_solid_angles),
        cmocka_unit_test(both_grids_locate_the_same_triangle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
