/* SPDX-License-Identifier: BSD-2-Clause */
/* Interpolation of decoded samples (bwh_interp.h). */
#include "bwh_interp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "geodesic.h"

/* ---- cubic B-spline ------------------------------------------------------ */

static const double POLE = -0.26794919243112270; /* sqrt(3) - 2 */

void bwh_bspline_coefficients(const double *f, size_t n, double *c)
{
    if (c != f)
        memmove(c, f, n * sizeof *c);
    if (n < 2)
        return;
    const double z = POLE, gain = (1.0 - z) * (1.0 - 1.0 / z); /* 6 */
    for (size_t k = 0; k < n; k++)
        c[k] *= gain;
    /* causal initialisation over the whole signal (mirror boundary) */
    double zn = z, iz = 1.0 / z, z2n = pow(z, (double)(n - 1));
    double sum = c[0] + z2n * c[n - 1];
    z2n *= z2n * iz;
    for (size_t k = 1; k + 1 < n; k++) {
        sum += (zn + z2n) * c[k];
        zn *= z;
        z2n *= iz;
    }
    c[0] = sum / (1.0 - zn * zn);
    for (size_t k = 1; k < n; k++)
        c[k] += z * c[k - 1];
    /* anti-causal initialisation and recursion */
    c[n - 1] = (z / (z * z - 1.0)) * (z * c[n - 2] + c[n - 1]);
    for (size_t k = n - 1; k-- > 0;)
        c[k] = z * (c[k + 1] - c[k]);
}

/* index k of the whole-sample mirror extension of n samples */
static size_t mirrored(long k, size_t n)
{
    if (n == 1)
        return 0;
    long period = 2 * ((long)n - 1);
    long r = k % period;
    if (r < 0)
        r += period;
    return (size_t)(r < (long)n ? r : period - r);
}

double bwh_bspline_eval(const double *c, size_t n, double x)
{
    if (n == 0)
        return NAN;
    if (n == 1)
        return c[0];
    double fl = floor(x), t = x - fl;
    long i = (long)fl;
    /* the cubic B-spline's weights of c[i-1], c[i], c[i+1], c[i+2] */
    double w0 = (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0;
    double w1 = (4.0 - 6.0 * t * t + 3.0 * t * t * t) / 6.0;
    double w2 = (1.0 + 3.0 * t + 3.0 * t * t - 3.0 * t * t * t) / 6.0;
    double w3 = t * t * t / 6.0;
    return w0 * c[mirrored(i - 1, n)] + w1 * c[mirrored(i, n)] + w2 * c[mirrored(i + 1, n)] +
           w3 * c[mirrored(i + 2, n)];
}

/* ---- sphere -------------------------------------------------------------- */

static double det3(const double a[3], const double b[3], const double c[3])
{
    double bc[3];
    bwg_cross3(b, c, bc);
    return bwg_dot3(a, bc);
}

void bwh_sphere_interp_free(bwh_sphere_interp_t *s)
{
    free(s->centre);
    free(s->vert);
    free(s->tv);
    free(s->vt_start);
    free(s->vt);
    free(s->area);
    memset(s, 0, sizeof *s);
}

/* a corner of a triangle, to be sorted by position: neighbouring triangles
 * compute a shared vertex from the same two endpoints in the same way, so
 * its copies are equal to the bit */
typedef struct {
    double p[3];
    uint32_t tri, k;
} corner_t;

static int corner_cmp(const void *pa, const void *pb)
{
    const corner_t *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->p[i] != b->p[i])
            return a->p[i] < b->p[i] ? -1 : 1;
    return a->tri < b->tri ? -1 : a->tri > b->tri;
}

static int same_point(const double a[3], const double b[3])
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

int bwh_sphere_interp_init(bwh_sphere_interp_t *s, unsigned level)
{
    memset(s, 0, sizeof *s);
    if (level > BWH_GRID_MAX_LEVEL)
        return bwh_fail("interpolation: level %u above %u", level, BWH_GRID_MAX_LEVEL);
    s->level = level;
    s->n = bwh_grid_count(level);
    size_t nc = 3 * s->n;
    bwh_tri_t *tri = malloc(s->n * sizeof *tri);
    corner_t *cn = malloc(nc * sizeof *cn);
    s->centre = malloc(s->n * sizeof *s->centre);
    s->tv = malloc(s->n * sizeof *s->tv);
    s->area = malloc(s->n * sizeof *s->area);
    s->vert = malloc(nc * sizeof *s->vert);
    s->vt_start = malloc((nc + 1) * sizeof *s->vt_start);
    s->vt = malloc(nc * sizeof *s->vt);
    if (!tri || !cn || !s->centre || !s->tv || !s->area || !s->vert || !s->vt_start || !s->vt) {
        free(tri);
        free(cn);
        bwh_sphere_interp_free(s);
        return bwh_fail("interpolation: out of memory");
    }
    bwh_grid_triangles(level, tri);
    for (size_t t = 0; t < s->n; t++) {
        bwh_tri_centre(&tri[t], s->centre[t]);
        s->area[t] = bwh_solid_angle(tri[t].v[0], tri[t].v[1], tri[t].v[2]);
        for (uint32_t k = 0; k < 3; k++) {
            corner_t *c = &cn[3 * t + k];
            memcpy(c->p, tri[t].v[k], sizeof c->p);
            c->tri = (uint32_t)t;
            c->k = k;
        }
    }
    free(tri);
    /* equal positions next to each other, each group's triangles ascending */
    qsort(cn, nc, sizeof *cn, corner_cmp);
    for (size_t i = 0; i < nc; i++) {
        if (i == 0 || !same_point(cn[i].p, cn[i - 1].p)) {
            memcpy(s->vert[s->nv], cn[i].p, sizeof s->vert[0]);
            s->vt_start[s->nv++] = (uint32_t)i;
        }
        s->vt[i] = cn[i].tri;
        s->tv[cn[i].tri][cn[i].k] = (uint32_t)(s->nv - 1);
    }
    s->vt_start[s->nv] = (uint32_t)nc;
    free(cn);
    return 0;
}

/* The value of triangle t: values[t] or fvalues[t * stride]. */
static inline double value_at(const double *values, const float *fvalues, size_t stride,
                              uint32_t t)
{
    return values ? values[t] : (double)fvalues[(size_t)t * stride];
}

/* the solid-angle-weighted mean of the centre values around vertex v */
static double vertex_value(const bwh_sphere_interp_t *s, const double *values,
                           const float *fvalues, size_t stride, size_t v)
{
    double num = 0.0, den = 0.0;
    for (uint32_t q = s->vt_start[v]; q < s->vt_start[v + 1]; q++) {
        uint32_t t = s->vt[q];
        num += s->area[t] * value_at(values, fvalues, stride, t);
        den += s->area[t];
    }
    return num / den;
}

int bwh_sphere_locate(const bwh_sphere_interp_t *s, const double d[3], bwh_sphere_at_t *at)
{
    long t = bwh_grid_locate(s->level, d);
    if (t < 0)
        return -1;
    const double *c = s->centre[t];
    /* the part (c, v_k, v_k+1) that holds d: both of its sides through c
     * leave d on the inner side (the best of the three, against rounding) */
    int best = 0;
    double bestmin = -INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *va = s->vert[s->tv[t][k]], *vb = s->vert[s->tv[t][(k + 1) % 3]];
        double o = det3(c, va, vb) > 0.0 ? 1.0 : -1.0;
        double m = fmin(o * det3(c, va, d), o * det3(c, d, vb));
        if (m > bestmin) {
            bestmin = m;
            best = k;
        }
    }
    uint32_t ia = s->tv[t][best], ib = s->tv[t][(best + 1) % 3];
    const double *va = s->vert[ia], *vb = s->vert[ib];
    /* d = a c + b va + g vb; barycentric = (a, b, g) / (a + b + g) */
    double D = det3(c, va, vb);
    double a = det3(d, va, vb) / D, b = det3(c, d, vb) / D, g = det3(c, va, d) / D;
    double sum = a + b + g;
    at->t = (uint32_t)t;
    at->ia = ia;
    at->ib = ib;
    at->w[0] = a / sum;
    at->w[1] = b / sum;
    at->w[2] = g / sum;
    return 0;
}

/* the value at `at` of values, or (values NULL) of fvalues[t * stride] */
static double value_of_at(const bwh_sphere_interp_t *s, const bwh_sphere_at_t *at,
                          const double *values, const float *fvalues, size_t stride)
{
    return at->w[0] * value_at(values, fvalues, stride, at->t) +
           at->w[1] * vertex_value(s, values, fvalues, stride, at->ia) +
           at->w[2] * vertex_value(s, values, fvalues, stride, at->ib);
}

double bwh_sphere_value(const bwh_sphere_interp_t *s, const bwh_sphere_at_t *at,
                        const double *values)
{
    return value_of_at(s, at, values, NULL, 1);
}

double bwh_sphere_value_f32(const bwh_sphere_interp_t *s, const bwh_sphere_at_t *at,
                            const float *values, size_t stride)
{
    return value_of_at(s, at, NULL, values, stride);
}

double bwh_sphere_interp(const bwh_sphere_interp_t *s, const double *values, const double d[3])
{
    bwh_sphere_at_t at;
    return bwh_sphere_locate(s, d, &at) != 0 ? NAN : bwh_sphere_value(s, &at, values);
}
