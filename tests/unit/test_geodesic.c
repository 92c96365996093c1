/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Geodesic grid (host-tools/lib/geodesic.c) and the firmware weight table
 * (firmware/codec/bw_geodesic_tables.c).
 *
 *   cc -std=c11 -I firmware/codec -I host-tools/lib tests/unit/test_geodesic.c \
 *      host-tools/lib/geodesic.c firmware/codec/bw_geodesic_tables.c -lcmocka -lm
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "bw_geodesic.h"
#include "geodesic.h"

#define PI 3.14159265358979323846

/* grids[l] = all triangles of level l, built once for the whole group. */
static bwh_tri_t *grids[BWH_GRID_MAX_LEVEL + 1];

static int setup_grids(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        grids[l] = malloc(bwh_grid_count(l) * sizeof *grids[l]);
        if (grids[l] == NULL || bwh_grid_triangles(l, grids[l]) != 0)
            return -1;
    }
    return 0;
}

static int teardown_grids(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        free(grids[l]);
        grids[l] = NULL;
    }
    return 0;
}

static double area(const bwh_tri_t *t)
{
    return bwh_solid_angle(t->v[0], t->v[1], t->v[2]);
}

static void grid_counts_are_four_times_four_to_the_level_and_bad_levels_are_rejected(
    void **state)
{
    (void)state;
    for (unsigned l = 0; l <= 6; l++)
        assert_int_equal(bwh_grid_count(l), (size_t)4 << (2 * l));
    assert_int_equal(bwh_grid_count(7), 0);
    bwh_tri_t t[4];
    double xyz[4][3];
    double up[3] = {0.0, 0.0, 1.0};
    assert_int_equal(bwh_grid_triangles(7, t), -1);
    assert_int_equal(bwh_grid_triangles(0, NULL), -1);
    assert_int_equal(bwh_grid_centres(7, xyz, NULL), -1);
    assert_int_equal(bwh_grid_locate(7, up), -1);
}

static void base_triangles_are_the_upper_octahedron_faces_in_quadrant_order(void **state)
{
    (void)state;
    static const double want[4][3][3] = {
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
        {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}},
        {{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}},
        {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}},
    };
    for (unsigned b = 0; b < 4; b++)
        for (unsigned v = 0; v < 3; v++)
            for (unsigned k = 0; k < 3; k++)
                assert_true(grids[0][b].v[v][k] == want[b][v][k]);
    /* Child 1 holds vertex a (the zenith), children 2 and 3 hold b and c. */
    const bwh_tri_t *g1 = grids[1];
    for (unsigned b = 0; b < 4; b++)
        for (unsigned k = 0; k < 3; k++) {
            assert_true(g1[4 * b + 1].v[0][k] == want[b][0][k]);
            assert_true(g1[4 * b + 2].v[1][k] == want[b][1][k]);
            assert_true(g1[4 * b + 3].v[2][k] == want[b][2][k]);
        }
}

static void solid_angles_sum_to_two_pi_at_every_level_and_children_sum_to_their_parent(
    void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        double sum = 0.0;
        for (size_t i = 0; i < n; i++) {
            double a = area(&grids[l][i]);
            assert_true(a > 0.0);
            sum += a;
            if (l < BWH_GRID_MAX_LEVEL) {
                const bwh_tri_t *kid = &grids[l + 1][4 * i];
                double ks = area(&kid[0]) + area(&kid[1]) + area(&kid[2]) + area(&kid[3]);
                assert_true(fabs(ks - a) <= 1e-12 * a);
            }
        }
        assert_true(fabs(sum - 2.0 * PI) < 1e-9);
    }
}

static void solid_angle_of_the_octant_is_a_quarter_of_the_hemisphere(void **state)
{
    (void)state;
    double x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
    assert_true(fabs(bwh_solid_angle(z, x, y) - PI / 2.0) < 1e-15);
    assert_true(fabs(bwh_solid_angle(z, y, x) - PI / 2.0) < 1e-15);
}

static void grid_centres_match_the_normalized_vertex_sums_and_solid_angles(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        double(*xyz)[3] = malloc(n * sizeof *xyz);
        double *sa = malloc(n * sizeof *sa);
        assert_non_null(xyz);
        assert_non_null(sa);
        assert_int_equal(bwh_grid_centres(l, xyz, sa), 0);
        for (size_t i = 0; i < n; i++) {
            double c[3];
            bwh_tri_centre(&grids[l][i], c);
            for (int k = 0; k < 3; k++)
                assert_true(xyz[i][k] == c[k]);
            assert_true(fabs(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - 1.0) < 1e-15);
            assert_true(c[2] > 0.0);
            assert_true(sa[i] == area(&grids[l][i]));
        }
        assert_int_equal(bwh_grid_centres(l, xyz, NULL), 0);
        free(xyz);
        free(sa);
    }
}

static void every_subtree_is_a_contiguous_index_range_inside_its_parent(void **state)
{
    (void)state;
    for (unsigned l = 0; l < BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        for (size_t i = 0; i < n; i++) {
            for (unsigned m = 0; m < 4; m++) {
                /* Children of i are exactly 4i..4i+3 one level down. */
                bwh_tri_t want;
                bwh_tri_child(&grids[l][i], m, &want);
                for (unsigned v = 0; v < 3; v++)
                    for (unsigned k = 0; k < 3; k++)
                        assert_true(grids[l + 1][4 * i + m].v[v][k] == want.v[v][k]);
                /* ... and lie inside their parent. */
                double c[3];
                bwh_tri_centre(&grids[l + 1][4 * i + m], c);
                assert_int_equal(bwh_grid_locate(l, c), (long)i);
            }
        }
    }
    /* Consequently the descendants of i at level l + d are i*4^d .. (i+1)*4^d - 1. */
    for (unsigned l = 0; l < BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        for (unsigned d = 1; l + d <= BWH_GRID_MAX_LEVEL; d++) {
            size_t span = (size_t)1 << (2 * d);
            for (size_t i = 0; i < n; i++) {
                for (size_t j = i * span; j < (i + 1) * span; j += span / 4 + 1) {
                    double c[3];
                    bwh_tri_centre(&grids[l + d][j], c);
                    assert_int_equal(bwh_grid_locate(l, c), (long)i);
                }
            }
        }
    }
}

static void locating_each_triangle_centre_returns_its_own_index(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        size_t n = bwh_grid_count(l);
        for (size_t i = 0; i < n; i++) {
            double c[3];
            bwh_tri_centre(&grids[l][i], c);
            assert_int_equal(bwh_grid_locate(l, c), (long)i);
        }
    }
}

static void locate_rejects_the_lower_hemisphere_and_handles_edges_deterministically(
    void **state)
{
    (void)state;
    double below[3] = {0.6, 0.0, -0.8};
    double nan_dir[3] = {NAN, 0.0, 1.0};
    assert_int_equal(bwh_grid_locate(3, below), -1);
    assert_int_equal(bwh_grid_locate(3, nan_dir), -1);

    /* Vertices and edge points give a valid index and the same one on every
     * call, and a coarser level's answer is always the prefix. */
    static const double pts[][3] = {
        {0, 0, 1},  {1, 0, 0},  {0, 1, 0},  {-1, 0, 0}, {0, -1, 0},
        {0.70710678118654752, 0.70710678118654752, 0},
        {0.70710678118654752, 0, 0.70710678118654752},
        {0, -0.70710678118654752, 0.70710678118654752},
    };
    for (size_t p = 0; p < sizeof pts / sizeof pts[0]; p++) {
        long prev = -1;
        for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
            long idx = bwh_grid_locate(l, pts[p]);
            assert_true(idx >= 0 && (size_t)idx < bwh_grid_count(l));
            assert_int_equal(bwh_grid_locate(l, pts[p]), idx);
            if (l > 0)
                assert_int_equal(idx / 4, prev);
            prev = idx;
        }
    }
    /* The zenith belongs to base 0, and the quadrant axes to the base that
     * starts there going counter-clockwise. */
    assert_int_equal(bwh_grid_locate(0, pts[0]), 0);
    assert_int_equal(bwh_grid_locate(0, pts[1]), 0);
    assert_int_equal(bwh_grid_locate(0, pts[2]), 1);
    assert_int_equal(bwh_grid_locate(0, pts[3]), 2);
    assert_int_equal(bwh_grid_locate(0, pts[4]), 3);
}

/* The triangle found by descending from the base, forming each level's
 * cutting normals (what bwh_grid_locate's stored normals stand for). */
static long descend(unsigned level, const double d[3])
{
    long idx = (long)bwh_grid_base(d);
    bwh_tri_t t = grids[0][idx];
    for (unsigned l = 0; l < level; l++) {
        double n[3][3];
        bwh_tri_cut_normals(&t, n);
        unsigned m = bwh_cut_child((const double(*)[3])n, d);
        bwh_tri_child(&t, m, &t);
        idx = idx * 4 + (long)m;
    }
    return idx;
}

static void locate_finds_the_triangle_of_the_descent_on_edges_and_anywhere(void **state)
{
    (void)state;
    /* random directions, and the vertices and edge midpoints of level-5
     * triangles (on the cutting circles of every level above) */
    uint64_t r = 0x9E3779B97F4A7C15u;
    for (unsigned k = 0; k < 20000; k++) {
        double d[3];
        for (int i = 0; i < 3; i++) {
            r = r * 6364136223846793005u + 1442695040888963407u;
            d[i] = (double)(r >> 11) / 9007199254740992.0 * 2.0 - 1.0;
        }
        d[2] = fabs(d[2]);
        bwg_normalize3(d);
        for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++)
            assert_int_equal(bwh_grid_locate(l, d), descend(l, d));
    }
    for (size_t i = 0; i < bwh_grid_count(5); i++) {
        const bwh_tri_t *t = &grids[5][i];
        for (unsigned v = 0; v < 3; v++) {
            double m[3];
            for (int c = 0; c < 3; c++)
                m[c] = t->v[v][c] + t->v[(v + 1) % 3][c];
            bwg_normalize3(m);
            for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
                assert_int_equal(bwh_grid_locate(l, t->v[v]), descend(l, t->v[v]));
                assert_int_equal(bwh_grid_locate(l, m), descend(l, m));
            }
        }
    }
}

static void the_four_base_triangles_are_congruent(void **state)
{
    (void)state;
    for (unsigned l = 0; l <= BWH_GRID_MAX_LEVEL; l++) {
        size_t per_base = (size_t)1 << (2 * l);
        for (size_t k = 0; k < per_base; k++) {
            double a0 = area(&grids[l][k]);
            for (unsigned b = 1; b < 4; b++) {
                const bwh_tri_t *t = &grids[l][b * per_base + k];
                assert_true(fabs(area(t) - a0) <= 1e-14 * a0);
                /* Triangle b*4^l + k is triangle k rotated by b * 90 degrees. */
                const bwh_tri_t *u = &grids[l][k];
                for (unsigned v = 0; v < 3; v++) {
                    double x = u->v[v][0], y = u->v[v][1];
                    for (unsigned r = 0; r < b; r++) {
                        double tx = x;
                        x = -y;
                        y = tx;
                    }
                    assert_true(fabs(t->v[v][0] - x) < 1e-15);
                    assert_true(fabs(t->v[v][1] - y) < 1e-15);
                    assert_true(fabs(t->v[v][2] - u->v[v][2]) < 1e-15);
                }
            }
        }
    }
}

static void the_firmware_weight_table_equals_what_the_generator_computes(void **state)
{
    (void)state;
    unsigned checked = 0;
    for (unsigned j = 0; j < BW_GEO_TABLE_LEVELS; j++) {
        uint32_t n = 1u << (2u * j);
        for (uint32_t p = 0; p < n; p++) {
            uint16_t w[3];
            bw_geo_weights(j, p, w);
            double ap = area(&grids[j][p]);
            uint32_t sum = 0;
            for (unsigned m = 1; m <= 3; m++) {
                double x = 65536.0 * area(&grids[j + 1][4 * p + m]) / ap;
                uint32_t want = (uint32_t)floor(x + 0.5);
                assert_int_equal(w[m - 1], want);
                sum += w[m - 1];
            }
            assert_true(sum < 65536u);
            uint32_t l0 = 65536u - sum;
            assert_true(l0 > 0);
            assert_true(l0 > w[0]);
            assert_true(l0 > w[1]);
            assert_true(l0 > w[2]);
            checked++;
        }
    }
    assert_int_equal(checked, BW_GEO_PARENTS);
}

static void the_firmware_area_table_equals_the_solid_angles(void **state)
{
    (void)state;
    for (unsigned j = 0; j < BW_GEO_AREA_LEVELS; j++) {
        size_t n = bwh_grid_count(j);
        bwh_tri_t *t = malloc(n * sizeof *t);
        assert_non_null(t);
        assert_int_equal(bwh_grid_triangles(j, t), 0);
        for (uint32_t i = 0; i < n; i++) {
            double a = bwh_solid_angle(t[i].v[0], t[i].v[1], t[i].v[2]);
            double want = floor(2147483648.0 * a / (3.14159265358979323846 / 2) + 0.5);
            /* every base reads base 0's entry: exact for the congruent bases */
            assert_true((double)bw_geo_area(j, i) == want);
            if (j > 0) {
                uint64_t parent = bw_geo_area(j - 1, i / 4), sum = 0;
                for (unsigned m = 0; m < 4; m++)
                    sum += bw_geo_area(j, (i & ~3u) + m);
                assert_true(sum + 2 >= parent && sum <= parent + 2); /* rounding only */
            }
        }
        free(t);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(
            grid_counts_are_four_times_four_to_the_level_and_bad_levels_are_rejected),
        cmocka_unit_test(base_triangles_are_the_upper_octahedron_faces_in_quadrant_order),
        cmocka_unit_test(
            solid_angles_sum_to_two_pi_at_every_level_and_children_sum_to_their_parent),
        cmocka_unit_test(solid_angle_of_the_octant_is_a_quarter_of_the_hemisphere),
        cmocka_unit_test(grid_centres_match_the_normalized_vertex_sums_and_solid_angles),
        cmocka_unit_test(every_subtree_is_a_contiguous_index_range_inside_its_parent),
        cmocka_unit_test(locating_each_triangle_centre_returns_its_own_index),
        cmocka_unit_test(locate_finds_the_triangle_of_the_descent_on_edges_and_anywhere),
        cmocka_unit_test(
            locate_rejects_the_lower_hemisphere_and_handles_edges_deterministically),
        cmocka_unit_test(the_four_base_triangles_are_congruent),
        cmocka_unit_test(the_firmware_weight_table_equals_what_the_generator_computes),
        cmocka_unit_test(the_firmware_area_table_equals_the_solid_angles),
    };
    return cmocka_run_group_tests(tests, setup_grids, teardown_grids);
}
