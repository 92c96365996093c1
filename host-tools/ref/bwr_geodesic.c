/* SPDX-License-Identifier: BSD-2-Clause */
/* The reference model's geodesic hemisphere (bwr_geodesic.h). */
#include "bwr_geodesic.h"

#include <math.h>
#include <stdlib.h>

/* (p + q [+ r]) / |...|, the sums in the order given */
static void unit_sum(const double *p, const double *q, const double *r, double o[3])
{
    for (int k = 0; k < 3; k++)
        o[k] = r ? p[k] + q[k] + r[k] : p[k] + q[k];
    double n = sqrt(bwr_dot3(o, o));
    for (int k = 0; k < 3; k++)
        o[k] /= n;
}

static void copy3(double o[3], const double *p)
{
    o[0] = p[0];
    o[1] = p[1];
    o[2] = p[2];
}

static void make_tri(bwr_tri_t *t, const double *a, const double *b, const double *c)
{
    copy3(t->v[0], a);
    copy3(t->v[1], b);
    copy3(t->v[2], c);
}

size_t bwr_grid_count(unsigned level)
{
    return level > BWR_GRID_MAX_LEVEL ? 0 : (size_t)1 << (2u * level + 2u);
}

/* base b: the zenith, then the unit vectors at azimuths b 90 and b 90 + 90
 * degrees, written out (no rotation is computed) */
static void base(unsigned b, bwr_tri_t *t)
{
    static const double ring[5][3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}};
    static const double zenith[3] = {0, 0, 1};
    make_tri(t, zenith, ring[b], ring[b + 1]);
}

static void child(const bwr_tri_t *t, unsigned m, bwr_tri_t *c)
{
    const double *a = t->v[0], *b = t->v[1], *v = t->v[2];
    double ab[3], bc[3], ca[3];
    unit_sum(a, b, NULL, ab);
    unit_sum(b, v, NULL, bc);
    unit_sum(v, a, NULL, ca);
    switch (m) {
    case 0: make_tri(c, bc, ca, ab); break;
    case 1: make_tri(c, a, ab, ca); break;
    case 2: make_tri(c, ab, b, bc); break;
    default: make_tri(c, ca, bc, v); break;
    }
}

/* the subtree of t down to `depth` more levels, written at out[first ..] */
static void descend(const bwr_tri_t *t, unsigned depth, bwr_tri_t *out, size_t first)
{
    if (depth == 0) {
        out[first] = *t;
        return;
    }
    size_t span = (size_t)1 << (2u * (depth - 1u));
    for (unsigned m = 0; m < 4; m++) {
        bwr_tri_t c;
        child(t, m, &c);
        descend(&c, depth - 1u, out, first + m * span);
    }
}

int bwr_grid_triangles(unsigned level, bwr_tri_t *out)
{
    if (level > BWR_GRID_MAX_LEVEL || out == NULL)
        return -1;
    size_t per_base = (size_t)1 << (2u * level);
    for (unsigned b = 0; b < 4; b++) {
        bwr_tri_t t;
        base(b, &t);
        descend(&t, level, out, b * per_base);
    }
    return 0;
}

void bwr_tri_direction(const bwr_tri_t *t, double out[3])
{
    unit_sum(t->v[0], t->v[1], t->v[2], out);
}

/* the angle between unit vectors, accurate for small and large angles */
static double arc(const double p[3], const double q[3])
{
    double n[3];
    bwr_cross3(p, q, n);
    return atan2(sqrt(bwr_dot3(n, n)), bwr_dot3(p, q));
}

double bwr_tri_area(const double a[3], const double b[3], const double c[3])
{
    double la = arc(b, c), lb = arc(c, a), lc = arc(a, b);
    double s = 0.5 * (la + lb + lc);
    double p = tan(0.5 * s) * tan(0.5 * (s - la)) * tan(0.5 * (s - lb)) * tan(0.5 * (s - lc));
    return 4.0 * atan(sqrt(p > 0.0 ? p : 0.0));
}

int bwr_grid_centres(unsigned level, double (*xyz)[3], double *area)
{
    if (level > BWR_GRID_MAX_LEVEL || xyz == NULL)
        return -1;
    size_t n = bwr_grid_count(level);
    bwr_tri_t *t = malloc(n * sizeof *t);
    if (t == NULL)
        return -1;
    bwr_grid_triangles(level, t);
    for (size_t i = 0; i < n; i++) {
        bwr_tri_direction(&t[i], xyz[i]);
        if (area != NULL)
            area[i] = bwr_tri_area(t[i].v[0], t[i].v[1], t[i].v[2]);
    }
    free(t);
    return 0;
}

/* how far d is inside t: the smallest of the three side determinants
 * (all >= 0: inside or on a side) */
static double inside(const bwr_tri_t *t, const double d[3])
{
    double m = INFINITY;
    for (int k = 0; k < 3; k++) {
        double n[3];
        bwr_cross3(t->v[k], t->v[(k + 1) % 3], n);
        double s = bwr_dot3(n, d);
        if (s < m)
            m = s;
    }
    return m;
}

/* the first of the n triangles that holds d, else the least outside */
static unsigned pick(const bwr_tri_t *t, unsigned n, const double d[3])
{
    unsigned best = 0;
    double best_m = -INFINITY;
    for (unsigned i = 0; i < n; i++) {
        double m = inside(&t[i], d);
        if (m >= 0.0)
            return i;
        if (m > best_m) {
            best_m = m;
            best = i;
        }
    }
    return best;
}

long bwr_grid_locate(unsigned level, const double d[3])
{
    if (level > BWR_GRID_MAX_LEVEL || d == NULL || !isfinite(d[0]) || !isfinite(d[1]) ||
        !isfinite(d[2]) || d[2] < 0.0)
        return -1;
    bwr_tri_t four[4];
    for (unsigned b = 0; b < 4; b++)
        base(b, &four[b]);
    unsigned b = pick(four, 4, d);
    bwr_tri_t t = four[b];
    long idx = (long)b;
    for (unsigned l = 0; l < level; l++) {
        for (unsigned m = 0; m < 4; m++)
            child(&t, m, &four[m]);
        unsigned m = pick(four, 4, d);
        t = four[m];
        idx = 4 * idx + (long)m;
    }
    return idx;
}
