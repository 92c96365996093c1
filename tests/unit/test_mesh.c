/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Triangle meshes of `brdfwave render` (host-tools/render/render_mesh.c):
 *
 *  - a ray hits a triangle inside it, on either face, within (tmin, tmax),
 *    and misses it outside, parallel or out of range;
 *  - the hierarchy finds the same nearest hit as a test of every triangle;
 *  - the torus is closed (every ray from inside its tube leaves through it,
 *    by a face that looks outwards) and its area is the torus's;
 *  - bad meshes are refused with a message; triangles of no area are left out.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render_mesh.h"
#include "bwhost.h"
#include "test_rng.h"

#define PI 3.14159265358979323846

static uint64_t rng = 0x2545f4914f6cdd1dull;

static double uniform(void) { return test_uniform(&rng); }

static void random_dir(double d[3])
{
    double z = 2.0 * uniform() - 1.0, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * PI * uniform();
    d[0] = r * cos(phi);
    d[1] = r * sin(phi);
    d[2] = z;
}

/* render_tri_hit for the ray (x, y, z) + t (dx, dy, dz) */
static int shoot(const render_mesh_tri_t *t, double x, double y, double z, double dx, double dy,
                 double dz, double tmin, double tmax, double *th)
{
    return render_tri_hit(t, (const double[3]){x, y, z}, (const double[3]){dx, dy, dz}, tmin, tmax,
                       th);
}

static void a_ray_hits_a_triangle_inside_it_on_either_face(void **state)
{
    (void)state;
    const double v[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const uint32_t idx[1][3] = {{0, 1, 2}};
    render_mesh_t m;
    assert_int_equal(render_mesh_build(&m, v, 3, idx, 1), 0);
    assert_int_equal(m.n_tri, 1);
    const render_mesh_tri_t *t = &m.tri[0];
    assert_true(fabs(t->n[2] - 1.0) < 1e-15); /* (1,0,0) x (0,1,0) */
    double th = -1.0;
    assert_int_equal(shoot(t, 0.25, 0.25, 1, 0, 0, -1, 0, 10, &th), 1);
    assert_true(th == 1.0);
    assert_int_equal(shoot(t, 0.25, 0.25, -2, 0, 0, 1, 0, 10, &th), 1);
    assert_true(th == 2.0); /* the back face too */
    /* outside the edge u + v = 1, outside u = 0, parallel, out of range */
    assert_int_equal(shoot(t, 0.6, 0.6, 1, 0, 0, -1, 0, 10, &th), 0);
    assert_int_equal(shoot(t, -0.01, 0.5, 1, 0, 0, -1, 0, 10, &th), 0);
    assert_int_equal(shoot(t, 0.2, 0.2, 0, 1, 0, 0, -10, 10, &th), 0);
    assert_int_equal(shoot(t, 0.25, 0.25, 1, 0, 0, -1, 0, 0.99, &th), 0);
    assert_int_equal(shoot(t, 0.25, 0.25, 1, 0, 0, -1, 1.01, 10, &th), 0);
    assert_true(th == 2.0); /* a miss leaves *t alone */
    /* through the mesh: the same */
    const double down[3] = {0, 0, -1};
    th = 10.0;
    assert_int_equal(render_mesh_hit(&m, (const double[3]){0.1, 0.7, 3}, down, 1e-9, &th), 0);
    assert_true(th == 3.0);
    th = 10.0;
    assert_int_equal(render_mesh_hit(&m, (const double[3]){0.7, 0.7, 3}, down, 1e-9, &th), -1);
    assert_true(th == 10.0);
    render_mesh_free(&m);
}

/* the nearest hit by testing every triangle in turn */
static long brute_hit(const render_mesh_t *m, const double o[3], const double d[3], double tmin,
                      double *t)
{
    long best = -1;
    for (size_t i = 0; i < m->n_tri; i++)
        if (render_tri_hit(&m->tri[i], o, d, tmin, *t, t))
            best = (long)i;
    return best;
}

static void the_hierarchy_finds_the_nearest_hit_of_every_triangle(void **state)
{
    (void)state;
    render_mesh_t m;
    const double c[3] = {0.1, -0.2, 0.3};
    assert_int_equal(render_mesh_torus(&m, c, 0.5, 0.2, 96, 32), 0);
    assert_int_equal(m.n_tri, 2 * 96 * 32);
    assert_true(m.n_node < 2 * m.n_tri);
    unsigned n = 20000, hits = 0, axis_rays = 0;
    for (unsigned r = 0; r < n; r++) {
        double o[3], d[3];
        for (unsigned k = 0; k < 3; k++)
            o[k] = c[k] + 1.6 * (2.0 * uniform() - 1.0);
        if (r % 2) { /* towards a point of the torus's box */
            const double half[3] = {0.7, 0.7, 0.2};
            double len = 0.0;
            for (unsigned k = 0; k < 3; k++) {
                d[k] = c[k] + half[k] * (2.0 * uniform() - 1.0) - o[k];
                len += d[k] * d[k];
            }
            for (unsigned k = 0; k < 3; k++)
                d[k] /= sqrt(len);
        } else {
            random_dir(d);
        }
        if (r % 10 == 0) { /* along an axis: zero components */
            d[0] = d[1] = 0.0;
            d[2] = r % 20 ? 1.0 : -1.0;
            axis_rays++;
        }
        double tb = INFINITY, tt = INFINITY;
        long kb = render_mesh_hit(&m, o, d, 1e-9, &tb), kt = brute_hit(&m, o, d, 1e-9, &tt);
        assert_true(tb == tt);
        /* the same triangle, or one at the very same distance (a shared edge) */
        if (kb != kt) {
            assert_true(kb >= 0 && kt >= 0);
        }
        hits += kb >= 0;
    }
    printf("mesh: %zu triangles, %zu nodes; %u of %u rays hit (%u along the z axis)\n", m.n_tri,
           m.n_node, hits, n, axis_rays);
    assert_true(hits > n / 10 && hits < n - n / 10); /* both kinds of rays tested */
    render_mesh_free(&m);
}

static void the_torus_is_closed_and_has_the_torus_area(void **state)
{
    (void)state;
    render_mesh_t m;
    const double c[3] = {0.0, 0.0, 0.5}, R = 0.4, r = 0.1;
    assert_int_equal(render_mesh_torus(&m, c, R, r, 96, 32), 0);
    double area = 0.0;
    for (size_t i = 0; i < m.n_tri; i++) {
        const render_mesh_tri_t *t = &m.tri[i];
        double x[3] = {t->e1[1] * t->e2[2] - t->e1[2] * t->e2[1],
                       t->e1[2] * t->e2[0] - t->e1[0] * t->e2[2],
                       t->e1[0] * t->e2[1] - t->e1[1] * t->e2[0]};
        area += 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
    double exact = 4.0 * PI * PI * R * r;
    printf("torus: area %.6f, exact %.6f (%.3f %% below)\n", area, exact,
           100.0 * (1.0 - area / exact));
    assert_true(fabs(area / exact - 1.0) < 0.01);
    /* from points inside the tube every ray leaves through a face whose
     * normal points the way the ray goes (outwards) */
    for (unsigned q = 0; q < 20000; q++) {
        double u = 2.0 * PI * uniform(), w = 2.0 * PI * uniform(), s = 0.8 * r * uniform();
        double o[3] = {c[0] + (R + s * cos(w)) * cos(u), c[1] + (R + s * cos(w)) * sin(u),
                       c[2] + s * sin(w)};
        double d[3], t = INFINITY;
        random_dir(d);
        long k = render_mesh_hit(&m, o, d, 0.0, &t);
        assert_true(k >= 0);
        assert_true(t < 2.0 * (R + r)); /* within the torus's ball */
        const double *n = m.tri[k].n;
        assert_true(n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0.0);
    }
    render_mesh_free(&m);
}

static void bad_meshes_are_refused(void **state)
{
    (void)state;
    render_mesh_t m;
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, NAN, 0}};
    const uint32_t out_of_range[1][3] = {{0, 1, 4}}, not_finite[1][3] = {{0, 1, 3}},
                   no_area[2][3] = {{0, 1, 2}, {1, 1, 0}};
    assert_int_equal(render_mesh_build(&m, v, 4, out_of_range, 1), -1);
    printf("%s\n", bwh_last_error());
    assert_int_equal(render_mesh_build(&m, v, 4, not_finite, 1), -1);
    printf("%s\n", bwh_last_error());
    /* collinear corners and a repeated corner: left out, an empty mesh */
    assert_int_equal(render_mesh_build(&m, v, 4, no_area, 2), 0);
    assert_int_equal(m.n_tri, 0);
    double t = INFINITY;
    assert_int_equal(render_mesh_hit(&m, (double[3]){0.5, 0, 1}, (double[3]){0, 0, -1}, 0, &t), -1);
    render_mesh_free(&m);
    const double c[3] = {0, 0, 0};
    assert_int_equal(render_mesh_torus(&m, c, 0.1, 0.2, 16, 16), -1);
    assert_int_equal(render_mesh_torus(&m, c, 0.2, 0.0, 16, 16), -1);
    assert_int_equal(render_mesh_torus(&m, c, NAN, 0.1, 16, 16), -1);
    assert_int_equal(render_mesh_torus(&m, (double[3]){0, INFINITY, 0}, 0.2, 0.1, 16, 16), -1);
    assert_int_equal(render_mesh_torus(&m, c, 0.2, 0.1, 2, 16), -1);
    assert_int_equal(render_mesh_torus(&m, c, 0.2, 0.1, 16, 5000), -1);
    printf("%s\n", bwh_last_error());
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_ray_hits_a_triangle_inside_it_on_either_face),
        cmocka_unit_test(the_hierarchy_finds_the_nearest_hit_of_every_triangle),
        cmocka_unit_test(the_torus_is_closed_and_has_the_torus_area),
        cmocka_unit_test(bad_meshes_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
