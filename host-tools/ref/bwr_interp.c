/* SPDX-License-Identifier: BSD-2-Clause */
/* Cubic B-spline interpolation and interpolation on the geodesic sphere. */
#include "bwr_interp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_geodesic.h"

/* ---- cubic B-spline ------------------------------------------------------ */

static const double Z1 = -0.26794919243112270; /* sqrt(3) - 2 */

void bwr_bspline_coefficients(const double *f, size_t n, double *c)
{
    if (c != f)
        memmove(c, f, n * sizeof *c);
    if (n < 2)
        return;
    const double z = Z1, lambda = (1.0 - z) * (1.0 - 1.0 / z); /* 6 */
    for (size_t k = 0; k < n; k++)
        c[k] *= lambda;
    /* causal initialisation, mirror boundary, exact over the whole signal */
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

static size_t mirror(long k, size_t n)
{
    if (n == 1)
        return 0;
    long period = 2 * ((long)n - 1);
    long r = k % period;
    if (r < 0)
        r += period;
    return (size_t)(r < (long)n ? r : period - r);
}

double bwr_bspline_eval(const double *c, size_t n, double x)
{
    if (n == 0)
        return NAN;
    if (n == 1)
        return c[0];
    double fl = floor(x), t = x - fl;
    long i = (long)fl;
    /* weights of c[i-1], c[i], c[i+1], c[i+2] */
    double w0 = (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0;
    double w1 = (4.0 - 6.0 * t * t + 3.0 * t * t * t) / 6.0;
    double w2 = (1.0 + 3.0 * t + 3.0 * t * t - 3.0 * t * t * t) / 6.0;
    double w3 = t * t * t / 6.0;
    return w0 * c[mirror(i - 1, n)] + w1 * c[mirror(i, n)] + w2 * c[mirror(i + 1, n)] +
           w3 * c[mirror(i + 2, n)];
}

/* ---- sphere -------------------------------------------------------------- */

static double det3(const double a[3], const double b[3], const double c[3])
{
    double bc[3];
    bwr_cross3(b, c, bc);
    return bwr_dot3(a, bc);
}

void bwr_sinterp_free(bwr_sinterp_t *s)
{
    free(s->centre);
    free(s->vert);
    free(s->tv);
    free(s->vt_start);
    free(s->vt);
    free(s->area);
    memset(s, 0, sizeof *s);
}

/* vertex index of p, added when new (vertices are shared exactly by the
 * construction up to rounding; compare with a tolerance) */
static size_t vertex_id(bwr_sinterp_t *s, const double p[3])
{
    for (size_t v = s->nv; v-- > 0;)
        if (fabs(s->vert[v][0] - p[0]) < 1e-12 && fabs(s->vert[v][1] - p[1]) < 1e-12 &&
            fabs(s->vert[v][2] - p[2]) < 1e-12)
            return v;
    memcpy(s->vert[s->nv], p, sizeof s->vert[0]);
    return s->nv++;
}

int bwr_sinterp_init(bwr_sinterp_t *s, unsigned level)
{
    memset(s, 0, sizeof *s);
    if (level > BWR_GRID_MAX_LEVEL)
        return -1;
    s->level = level;
    s->n = bwr_grid_count(level);
    bwr_tri_t *tri = malloc(s->n * sizeof *tri);
    s->centre = malloc(s->n * sizeof *s->centre);
    s->vert = malloc(3 * s->n * sizeof *s->vert);
    s->tv = malloc(s->n * sizeof *s->tv);
    s->area = malloc(s->n * sizeof *s->area);
    if (tri == NULL || s->centre == NULL || s->vert == NULL || s->tv == NULL || s->area == NULL) {
        free(tri);
        bwr_sinterp_free(s);
        return -1;
    }
    bwr_grid_triangles(level, tri);
    double rmax = 0.0;
    for (size_t t = 0; t < s->n; t++) {
        bwr_tri_direction(&tri[t], s->centre[t]);
        s->area[t] = bwr_tri_area(tri[t].v[0], tri[t].v[1], tri[t].v[2]);
        for (int k = 0; k < 3; k++) {
            s->tv[t][k] = vertex_id(s, tri[t].v[k]);
            double c = bwr_dot3(s->centre[t], tri[t].v[k]);
            double a = acos(c > 1.0 ? 1.0 : c);
            if (a > rmax)
                rmax = a;
        }
    }
    free(tri);
    s->radius = 2.0 * rmax;
    s->vt_start = calloc(s->nv + 1, sizeof *s->vt_start);
    s->vt = malloc(3 * s->n * sizeof *s->vt);
    if (s->vt_start == NULL || s->vt == NULL) {
        bwr_sinterp_free(s);
        return -1;
    }
    for (size_t t = 0; t < s->n; t++)
        for (int k = 0; k < 3; k++)
            s->vt_start[s->tv[t][k] + 1]++;
    for (size_t v = 0; v < s->nv; v++)
        s->vt_start[v + 1] += s->vt_start[v];
    size_t *fill = calloc(s->nv, sizeof *fill);
    if (fill == NULL) {
        bwr_sinterp_free(s);
        return -1;
    }
    for (size_t t = 0; t < s->n; t++)
        for (int k = 0; k < 3; k++) {
            size_t v = s->tv[t][k];
            s->vt[s->vt_start[v] + fill[v]++] = t;
        }
    free(fill);
    return 0;
}

static double vertex_value(const bwr_sinterp_t *s, const double *values, size_t v)
{
    double num = 0.0, den = 0.0;
    for (size_t q = s->vt_start[v]; q < s->vt_start[v + 1]; q++) {
        size_t t = s->vt[q];
        num += s->area[t] * values[t];
        den += s->area[t];
    }
    return num / den;
}

double bwr_sinterp_linear(const bwr_sinterp_t *s, const double *values, const double d[3])
{
    long t = bwr_grid_locate(s->level, d);
    if (t < 0)
        return NAN;
    const double *c = s->centre[t];
    /* the part (c, v_k, v_k+1) that contains d: both sides non-negative */
    int best = 0;
    double bestmin = -INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *va = s->vert[s->tv[t][k]], *vb = s->vert[s->tv[t][(k + 1) % 3]];
        double s1 = det3(c, va, d), s2 = det3(c, d, vb);
        /* orientation: (c, va, vb) has the sign of det3(c, va, vb) */
        double o = det3(c, va, vb) > 0.0 ? 1.0 : -1.0;
        double m = fmin(o * s1, o * s2);
        if (m > bestmin) {
            bestmin = m;
            best = k;
        }
    }
    size_t ia = s->tv[t][best], ib = s->tv[t][(best + 1) % 3];
    const double *va = s->vert[ia], *vb = s->vert[ib];
    /* d = a c + b va + g vb; barycentric = (a, b, g) / (a + b + g) */
    double D = det3(c, va, vb);
    double a = det3(d, va, vb) / D, b = det3(c, d, vb) / D, g = det3(c, va, d) / D;
    double sum = a + b + g;
    a /= sum;
    b /= sum;
    g /= sum;
    return a * values[t] + b * vertex_value(s, values, ia) + g * vertex_value(s, values, ib);
}

double bwr_sinterp_smooth(const bwr_sinterp_t *s, const double *values, const double d[3])
{
    if (!(d[2] >= 0.0) || !isfinite(d[0]) || !isfinite(d[1]))
        return NAN;
    double R = s->radius, num = 0.0, den = 0.0;
    double cr = cos(R);
    for (size_t t = 0; t < s->n; t++) {
        double cd = bwr_dot3(d, s->centre[t]);
        if (cd <= cr)
            continue;
        double r = acos(cd > 1.0 ? 1.0 : cd);
        if (r < 1e-15)
            return values[t];
        double w = (R - r) / (R * r);
        w *= w;
        num += w * values[t];
        den += w;
    }
    return den > 0.0 ? num / den : NAN;
}
