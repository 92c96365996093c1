/* SPDX-License-Identifier: BSD-2-Clause */
/* Geodesic hemisphere grid in double precision (host side). */
#include "geodesic.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static void midpoint(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] + b[0];
    out[1] = a[1] + b[1];
    out[2] = a[2] + b[2];
    bwg_normalize3(out);
}

static void set3(double dst[3], const double src[3])
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
}

/* Base b = (Z, R_b X, R_b Y), R_b the rotation by b * 90 degrees about z.
 * Rotating by 90 degrees maps (x, y, z) to (-y, x, z), which is exact. */
static void base_triangle(unsigned b, bwh_tri_t *t)
{
    static const double z[3] = {0.0, 0.0, 1.0};
    double x[3] = {1.0, 0.0, 0.0};
    double y[3] = {0.0, 1.0, 0.0};
    for (unsigned k = 0; k < b; k++) {
        double tx = x[0], ty = y[0];
        x[0] = -x[1];
        x[1] = tx;
        y[0] = -y[1];
        y[1] = ty;
    }
    set3(t->v[0], z);
    set3(t->v[1], x);
    set3(t->v[2], y);
}

size_t bwh_grid_count(unsigned level)
{
    if (level > BWH_GRID_MAX_LEVEL)
        return 0;
    return (size_t)4 << (2u * level);
}

void bwh_tri_child(const bwh_tri_t *t, unsigned m, bwh_tri_t *child)
{
    double mab[3], mbc[3], mca[3];
    const double *a = t->v[0], *b = t->v[1], *c = t->v[2];
    midpoint(a, b, mab);
    midpoint(b, c, mbc);
    midpoint(c, a, mca);
    /* Copy first so that child may alias t. */
    double va[3], vb[3], vc[3];
    set3(va, a);
    set3(vb, b);
    set3(vc, c);
    switch (m & 3u) {
    case 0:
        set3(child->v[0], mbc);
        set3(child->v[1], mca);
        set3(child->v[2], mab);
        break;
    case 1:
        set3(child->v[0], va);
        set3(child->v[1], mab);
        set3(child->v[2], mca);
        break;
    case 2:
        set3(child->v[0], mab);
        set3(child->v[1], vb);
        set3(child->v[2], mbc);
        break;
    default:
        set3(child->v[0], mca);
        set3(child->v[1], mbc);
        set3(child->v[2], vc);
        break;
    }
}

int bwh_grid_triangles(unsigned level, bwh_tri_t *out)
{
    if (level > BWH_GRID_MAX_LEVEL || out == NULL)
        return -1;
    for (unsigned b = 0; b < 4; b++)
        base_triangle(b, &out[b]);
    /* Refine in place from the back: children of i go to 4i..4i+3, which
     * only overwrites parents that have already been refined. */
    size_t n = 4;
    for (unsigned l = 0; l < level; l++) {
        for (size_t i = n; i-- > 0;) {
            bwh_tri_t parent = out[i];
            for (unsigned m = 0; m < 4; m++)
                bwh_tri_child(&parent, m, &out[4 * i + m]);
        }
        n *= 4;
    }
    return 0;
}

void bwh_tri_centre(const bwh_tri_t *t, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = t->v[0][k] + t->v[1][k] + t->v[2][k];
    bwg_normalize3(out);
}

double bwh_solid_angle(const double a[3], const double b[3], const double c[3])
{
    double bc[3];
    bwg_cross3(b, c, bc);
    double num = fabs(bwg_dot3(a, bc));
    double den = 1.0 + bwg_dot3(a, b) + bwg_dot3(b, c) + bwg_dot3(c, a);
    return 2.0 * atan2(num, den);
}

int bwh_grid_centres(unsigned level, double (*xyz)[3], double *solid_angle)
{
    if (level > BWH_GRID_MAX_LEVEL || xyz == NULL)
        return -1;
    size_t n = bwh_grid_count(level);
    bwh_tri_t *t = malloc(n * sizeof *t);
    if (t == NULL)
        return -1;
    bwh_grid_triangles(level, t);
    for (size_t i = 0; i < n; i++) {
        bwh_tri_centre(&t[i], xyz[i]);
        if (solid_angle != NULL)
            solid_angle[i] = bwh_solid_angle(t[i].v[0], t[i].v[1], t[i].v[2]);
    }
    free(t);
    return 0;
}

unsigned bwh_grid_base(const double dir[3])
{
    double x = dir[0], y = dir[1];
    if (x > 0.0 && y >= 0.0)
        return 0;
    if (x <= 0.0 && y > 0.0)
        return 1;
    if (x < 0.0 && y <= 0.0)
        return 2;
    if (x >= 0.0 && y < 0.0)
        return 3;
    return 0; /* x = y = 0: the zenith, a vertex of every base */
}

/* Each corner child is cut off from the centre child by one great circle
 * through two edge midpoints; its other two sides lie on the parent's
 * boundary. */
void bwh_tri_cut_normals(const bwh_tri_t *t, double n[3][3])
{
    double mab[3], mbc[3], mca[3];
    midpoint(t->v[0], t->v[1], mab);
    midpoint(t->v[1], t->v[2], mbc);
    midpoint(t->v[2], t->v[0], mca);
    bwg_cross3(mab, mca, n[0]);
    bwg_cross3(mbc, mab, n[1]);
    bwg_cross3(mca, mbc, n[2]);
}

/* The cutting normals of every triangle of levels 0 .. BWH_GRID_MAX_LEVEL
 * - 1, the descent's, each level's built once on its first use (from any
 * thread) and kept: the same normals the descent forms, so the same
 * triangles. NULL where memory ran out: the descent forms them then. */
static double (*cut_tab[BWH_GRID_MAX_LEVEL])[3][3];
static pthread_once_t cut_once[BWH_GRID_MAX_LEVEL] = {
    PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT,
    PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT};

static void cut_build(unsigned level)
{
    size_t n = bwh_grid_count(level);
    bwh_tri_t *t = malloc(n * sizeof *t);
    double(*c)[3][3] = malloc(n * sizeof *c);
    if (t && c && bwh_grid_triangles(level, t) == 0) {
        for (size_t i = 0; i < n; i++)
            bwh_tri_cut_normals(&t[i], c[i]);
        cut_tab[level] = c;
    } else {
        free(c);
    }
    free(t);
}

#define CUT_BUILDER(l) \
    static void cut_build_##l(void) { cut_build(l); }
CUT_BUILDER(0)
CUT_BUILDER(1)
CUT_BUILDER(2)
CUT_BUILDER(3)
CUT_BUILDER(4)
CUT_BUILDER(5)
_Static_assert(BWH_GRID_MAX_LEVEL == 6u, "one builder per level below the finest");
static void (*const cut_builders[BWH_GRID_MAX_LEVEL])(void) = {
    cut_build_0, cut_build_1, cut_build_2, cut_build_3, cut_build_4, cut_build_5};

static const double (*cut_level(unsigned level))[3][3]
{
    pthread_once(&cut_once[level], cut_builders[level]);
    return (const double(*)[3][3])cut_tab[level];
}

long bwh_grid_locate(unsigned level, const double dir[3])
{
    if (level > BWH_GRID_MAX_LEVEL || dir == NULL)
        return -1;
    if (!isfinite(dir[0]) || !isfinite(dir[1]) || !isfinite(dir[2]))
        return -1;
    if (dir[2] < 0.0)
        return -1;

    unsigned b = bwh_grid_base(dir);
    long idx = (long)b;
    unsigned l = 0;
    for (; l < level; l++) {
        const double(*c)[3][3] = cut_level(l);
        if (!c)
            break;
        idx = idx * 4 + (long)bwh_cut_child(c[idx], dir);
    }
    if (l == level)
        return idx;
    /* no table: the descent from the base, forming the normals */
    bwh_tri_t t;
    base_triangle(b, &t);
    idx = (long)b;
    for (l = 0; l < level; l++) {
        double n[3][3];
        bwh_tri_cut_normals(&t, n);
        unsigned m = bwh_cut_child((const double(*)[3])n, dir);
        bwh_tri_child(&t, m, &t);
        idx = idx * 4 + (long)m;
    }
    return idx;
}
