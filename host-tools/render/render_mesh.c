/* SPDX-License-Identifier: BSD-2-Clause */
/* Triangle meshes and their bounding volume hierarchy (bw_mesh.h). */
#include "render_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "geodesic.h"

#define M_TWO_PI 6.28318530717958647692
#define MAX_DEPTH 64u /* the median split halves: far below this */

typedef struct {
    double key;
    uint32_t i;
} keyed_t;

/* reorders a[0 .. n) so that a[k] holds the k-th smallest key, smaller ones
 * before it and larger ones after (quickselect, middle pivot) */
static void select_kth(keyed_t *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = a[lo + (hi - lo) / 2].key;
        size_t i = lo, j = hi;
        while (i <= j) {
            while (a[i].key < pivot)
                i++;
            while (a[j].key > pivot)
                j--;
            if (i <= j) {
                keyed_t t = a[i];
                a[i] = a[j];
                a[j] = t;
                i++;
                if (j == 0)
                    break;
                j--;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return;
    }
}

typedef struct {
    const render_mesh_tri_t *tri;
    const double (*centroid)[3];
    keyed_t *order;
    render_mesh_node_t *node;
    size_t n_node;
} builder_t;

/* the node for order[first .. first + count), children after it;
 * returns its index */
static uint32_t build(builder_t *b, size_t first, size_t count, unsigned depth)
{
    uint32_t k = (uint32_t)b->n_node++;
    render_mesh_node_t *nd = &b->node[k];
    double clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (unsigned a = 0; a < 3; a++) {
        nd->lo[a] = INFINITY;
        nd->hi[a] = -INFINITY;
    }
    for (size_t q = first; q < first + count; q++) {
        const render_mesh_tri_t *t = &b->tri[b->order[q].i];
        const double *c = b->centroid[b->order[q].i];
        for (unsigned a = 0; a < 3; a++) {
            double p[3] = {t->v0[a], t->v0[a] + t->e1[a], t->v0[a] + t->e2[a]};
            for (unsigned v = 0; v < 3; v++) {
                nd->lo[a] = fmin(nd->lo[a], p[v]);
                nd->hi[a] = fmax(nd->hi[a], p[v]);
            }
            clo[a] = fmin(clo[a], c[a]);
            chi[a] = fmax(chi[a], c[a]);
        }
    }
    /* a margin, so that rounding in the box test never loses a hit the
     * triangle test finds */
    for (unsigned a = 0; a < 3; a++) {
        double pad = 1e-9 * (1.0 + fabs(nd->lo[a]) + fabs(nd->hi[a]));
        nd->lo[a] -= pad;
        nd->hi[a] += pad;
    }
    if (count <= RENDER_MESH_LEAF || depth + 1u >= MAX_DEPTH) {
        nd->first = (uint32_t)first;
        nd->count = (uint32_t)count;
        return k;
    }
    /* the median of the centroids along their longest extent */
    unsigned axis = 0;
    for (unsigned a = 1; a < 3; a++)
        axis = chi[a] - clo[a] > chi[axis] - clo[axis] ? a : axis;
    for (size_t q = first; q < first + count; q++)
        b->order[q].key = b->centroid[b->order[q].i][axis];
    size_t half = count / 2;
    select_kth(b->order + first, count, half);
    nd->count = 0;
    build(b, first, half, depth + 1u);
    uint32_t second = build(b, first + half, count - half, depth + 1u);
    nd->first = second;
    return k;
}

int render_mesh_build(render_mesh_t *m, const double (*vert)[3], size_t n_vert,
                   const uint32_t (*idx)[3], size_t n_idx)
{
    memset(m, 0, sizeof *m);
    if (n_idx > RENDER_MESH_MAX_TRI)
        return bwh_fail("mesh: %zu triangles, at most %u", n_idx, RENDER_MESH_MAX_TRI);
    for (size_t i = 0; i < n_idx; i++)
        for (unsigned c = 0; c < 3; c++) {
            if (idx[i][c] >= n_vert)
                return bwh_fail("mesh: triangle %zu: vertex %u of %zu", i, idx[i][c], n_vert);
            const double *v = vert[idx[i][c]];
            if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
                return bwh_fail("mesh: vertex %u is not finite", idx[i][c]);
        }
    if (n_idx == 0)
        return 0;
    render_mesh_tri_t *tri = malloc(n_idx * sizeof *tri);
    double(*centroid)[3] = malloc(n_idx * sizeof *centroid);
    keyed_t *order = malloc(n_idx * sizeof *order);
    m->node = malloc((2 * n_idx - 1) * sizeof *m->node);
    m->tri = malloc(n_idx * sizeof *m->tri);
    if (!tri || !centroid || !order || !m->node || !m->tri) {
        free(tri);
        free(centroid);
        free(order);
        render_mesh_free(m);
        return bwh_fail("mesh: out of memory");
    }
    size_t n = 0;
    for (size_t i = 0; i < n_idx; i++) {
        render_mesh_tri_t *t = &tri[n];
        const double *a = vert[idx[i][0]], *b = vert[idx[i][1]], *c = vert[idx[i][2]];
        for (unsigned k = 0; k < 3; k++) {
            t->v0[k] = a[k];
            t->e1[k] = b[k] - a[k];
            t->e2[k] = c[k] - a[k];
            centroid[n][k] = (a[k] + b[k] + c[k]) / 3.0;
        }
        bwg_cross3(t->e1, t->e2, t->n);
        double len = sqrt(bwg_dot3(t->n, t->n));
        if (!(len > 0.0) || !isfinite(len))
            continue; /* no area: nothing to hit */
        for (unsigned k = 0; k < 3; k++)
            t->n[k] /= len;
        order[n].i = (uint32_t)n;
        n++;
    }
    if (n > 0) {
        builder_t b = {tri, (const double(*)[3])centroid, order, m->node, 0};
        build(&b, 0, n, 0);
        m->n_node = b.n_node;
        for (size_t q = 0; q < n; q++)
            m->tri[q] = tri[order[q].i];
    }
    m->n_tri = n;
    free(tri);
    free(centroid);
    free(order);
    if (n == 0) {
        free(m->node);
        m->node = NULL;
    }
    return 0;
}

int render_mesh_torus(render_mesh_t *m, const double centre[3], double major, double minor,
                   unsigned n_around, unsigned n_tube)
{
    memset(m, 0, sizeof *m);
    if (!(minor > 0.0 && minor < major) || !isfinite(major) || !isfinite(centre[0]) ||
        !isfinite(centre[1]) || !isfinite(centre[2]))
        return bwh_fail("torus: needs 0 < tube radius < ring radius, finite");
    if (n_around < 3 || n_around > 4096 || n_tube < 3 || n_tube > 4096 ||
        2u * n_around * n_tube > RENDER_MESH_MAX_TRI)
        return bwh_fail("torus: %u x %u quads: each 3..4096, %u triangles at most", n_around,
                        n_tube, RENDER_MESH_MAX_TRI);
    size_t nv = (size_t)n_around * n_tube;
    double(*v)[3] = malloc(nv * sizeof *v);
    uint32_t(*idx)[3] = malloc(2 * nv * sizeof *idx);
    if (!v || !idx) {
        free(v);
        free(idx);
        return bwh_fail("torus: out of memory");
    }
    for (unsigned i = 0; i < n_around; i++) {
        double u = M_TWO_PI * i / n_around;
        for (unsigned j = 0; j < n_tube; j++) {
            double w = M_TWO_PI * j / n_tube, ring = major + minor * cos(w);
            double *p = v[(size_t)i * n_tube + j];
            p[0] = centre[0] + ring * cos(u);
            p[1] = centre[1] + ring * sin(u);
            p[2] = centre[2] + minor * sin(w);
        }
    }
    /* each quad (i, j) .. (i + 1, j + 1) as two triangles, normals outwards */
    size_t q = 0;
    for (unsigned i = 0; i < n_around; i++) {
        unsigned i1 = (i + 1) % n_around;
        for (unsigned j = 0; j < n_tube; j++) {
            unsigned j1 = (j + 1) % n_tube;
            uint32_t a = i * n_tube + j, b = i1 * n_tube + j, c = i1 * n_tube + j1,
                     d = i * n_tube + j1;
            idx[q][0] = a, idx[q][1] = b, idx[q][2] = c, q++;
            idx[q][0] = a, idx[q][1] = c, idx[q][2] = d, q++;
        }
    }
    int rc = render_mesh_build(m, (const double(*)[3])v, nv, (const uint32_t(*)[3])idx, q);
    free(v);
    free(idx);
    return rc;
}

void render_mesh_free(render_mesh_t *m)
{
    free(m->tri);
    free(m->node);
    memset(m, 0, sizeof *m);
}

int render_tri_hit(const render_mesh_tri_t *tri, const double o[3], const double d[3], double tmin,
                double tmax, double *t)
{
    double p[3], s[3], q[3];
    bwg_cross3(d, tri->e2, p);
    double det = bwg_dot3(tri->e1, p);
    if (!(fabs(det) > 0.0))
        return 0; /* parallel to the plane */
    double inv = 1.0 / det;
    for (unsigned k = 0; k < 3; k++)
        s[k] = o[k] - tri->v0[k];
    double u = bwg_dot3(s, p) * inv;
    if (!(u >= 0.0 && u <= 1.0))
        return 0;
    bwg_cross3(s, tri->e1, q);
    double v = bwg_dot3(d, q) * inv;
    if (!(v >= 0.0 && u + v <= 1.0))
        return 0;
    double th = bwg_dot3(tri->e2, q) * inv;
    if (!(th > tmin && th < tmax))
        return 0;
    *t = th;
    return 1;
}

/* the ray (inverse direction inv) crosses the node's box within (tmin, tmax) */
static int box_hit(const render_mesh_node_t *nd, const double o[3], const double inv[3],
                   double tmin, double tmax)
{
    for (unsigned a = 0; a < 3; a++) {
        double t0 = (nd->lo[a] - o[a]) * inv[a], t1 = (nd->hi[a] - o[a]) * inv[a];
        if (t0 > t1) {
            double x = t0;
            t0 = t1;
            t1 = x;
        }
        tmin = t0 > tmin ? t0 : tmin;
        tmax = t1 < tmax ? t1 : tmax;
        if (!(tmin <= tmax))
            return 0;
    }
    return 1;
}

long render_mesh_hit(const render_mesh_t *m, const double o[3], const double d[3], double tmin,
                  double *t)
{
    if (m->n_node == 0)
        return -1;
    /* a zero component as a tiny one: no 0 x infinity in the box test */
    double inv[3];
    for (unsigned a = 0; a < 3; a++)
        inv[a] = 1.0 / (d[a] != 0.0 ? d[a] : 1e-300);
    uint32_t stack[MAX_DEPTH];
    unsigned sp = 0;
    uint32_t k = 0;
    long best = -1;
    for (;;) {
        const render_mesh_node_t *nd = &m->node[k];
        if (box_hit(nd, o, inv, tmin, *t)) {
            if (nd->count == 0) {
                stack[sp++] = nd->first;
                k++;
                continue;
            }
            for (uint32_t i = nd->first; i < nd->first + nd->count; i++)
                if (render_tri_hit(&m->tri[i], o, d, tmin, *t, t))
                    best = (long)i;
        }
        if (sp == 0)
            return best;
        k = stack[--sp];
    }
}
