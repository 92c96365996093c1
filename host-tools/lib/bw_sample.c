/* SPDX-License-Identifier: BSD-2-Clause */
/* Importance sampling of a BRDF from the triangle hierarchy (bw_sample.h). */
#include "bw_sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "geodesic.h"

#define S_PI 3.14159265358979323846

/* the nodes of level l, padded to a multiple of 16 (64 bytes of ends) */
static size_t level_padded(unsigned l)
{
    return (bwh_grid_count(l) + 15) / 16 * 16;
}

/* first node of level l: 4 (4^l - 1) / 3 */
static size_t level_offset(unsigned l)
{
    return (((size_t)1 << (2u * l)) - 1u) / 3u * 4u;
}

double bwh_projected_solid_angle(const double a[3], const double b[3], const double c[3])
{
    const double *v[3] = {a, b, c};
    double sum = 0.0;
    for (int k = 0; k < 3; k++) {
        const double *p = v[k], *q = v[(k + 1) % 3];
        double n[3];
        bwg_cross3(p, q, n);
        double sn = sqrt(bwg_dot3(n, n));
        if (sn == 0.0)
            continue;
        double gamma = atan2(sn, bwg_dot3(p, q));
        sum += gamma * n[2] / sn;
    }
    return 0.5 * fabs(sum);
}

void bwh_leaf_init(bwh_leaf_t *t, const double a[3], const double b[3], const double c[3])
{
    memcpy(t->a, a, sizeof t->a);
    memcpy(t->b, b, sizeof t->b);
    double e[3], bxe[3], amb[3], ac = bwg_dot3(a, c);
    for (int k = 0; k < 3; k++) {
        e[k] = c[k] - ac * a[k];
        amb[k] = a[k] - b[k];
    }
    bwg_normalize3(e);
    memcpy(t->e, e, sizeof t->e);
    t->opc = 1.0 + bwg_dot3(a, b);
    t->omc = 0.5 * bwg_dot3(amb, amb);
    bwg_cross3(b, e, bxe);
    t->k1 = fabs(bwg_dot3(a, bxe));
    t->k2 = bwg_dot3(b, e);
    t->area = bwh_solid_angle(a, b, c);
    t->inv_area = 1.0 / t->area;
    t->proj = bwh_projected_solid_angle(a, b, c);
}

/* Arvo, "Stratified sampling of spherical triangles" (SIGGRAPH 1995): u1
 * picks the sub-triangle (a, b, c') of area u1 * area, u2 a point on the
 * arc from b to c'. Both steps are solved in closed form with two
 * divisions and one square root side by side:
 *
 * c' = cos(phi) a + sin(phi) e. By Van Oosterom and Strackee's formula the
 * sub-triangle's area s has tan(s / 2) = k1 sin(phi) / ((1 + a.b)(1 +
 * cos(phi)) + k2 sin(phi)), that is T = k1 t / ((1 + a.b) + k2 t) with
 * t = tan(phi / 2): so t = N / D with N = T (1 + a.b), D = k1 - T k2, and
 * (cos(phi), sin(phi)) = (D^2 - N^2, 2 N D) / L, L = D^2 + N^2.
 *
 * On the arc from b to c' the point is at z = cos(angle from b) with
 * 1 - z = u2 w, w = 1 - b.c' = Q / L, Q = (1 - a.b) L + 2 N (N a.b - D k2)
 * (no cancellation of 1 - cos); it is z b + g (c' - (1 - w) b) with
 * g = sqrt((1 - z^2) / (1 - (b.c')^2)) = sqrt(u2 (2 L - u2 Q) / (2 L - Q)). */
void bwh_leaf_sample(const bwh_leaf_t *t, double u1, double u2, double out[3])
{
    double h = (0.5 * u1) * t->area, T;
    if (t->area <= 0.008) {
        /* tan to h^7: the first term left out is below 2e-21 of h */
        double h2 = h * h;
        T = h + h * h2 * (1.0 / 3.0 + h2 * (2.0 / 15.0 + h2 * (17.0 / 315.0)));
    } else if (t->area <= 0.1) {
        /* tan to h^11: the first term left out is below 1e-18 of h; the
         * powers paired to keep the chain short */
        double h2 = h * h, h4 = h2 * h2, h8 = h4 * h4;
        T = h + h * h2 *
                    ((1.0 / 3.0 + h2 * (2.0 / 15.0)) + h4 * (17.0 / 315.0 + h2 * (62.0 / 2835.0)) +
                     h8 * (1382.0 / 155925.0));
    } else {
        T = tan(h);
    }
    double N = T * t->opc, D = t->k1 - T * t->k2;
    double N2 = N * N, D2 = D * D, L = D2 + N2;
    double Q = t->omc * L + 2.0 * N * ((t->opc - 1.0) * N - t->k2 * D);
    double iL = 1.0 / L, iP = 1.0 / (2.0 * L - Q);
    double g = sqrt(u2 * (2.0 * L - u2 * Q) * iP);
    double cphi = (D2 - N2) * iL, sphi = 2.0 * N * D * iL, w = Q * iL;
    double kb = (1.0 - u2 * w) - g * (1.0 - w);
    for (int k = 0; k < 3; k++)
        out[k] = g * (cphi * t->a[k] + sphi * t->e[k]) + kb * t->b[k];
}

void bwh_sample_cosine(double u1, double u2, double out[3])
{
    double r = sqrt(u1), phi = 2.0 * S_PI * u2;
    out[0] = r * cos(phi);
    out[1] = r * sin(phi);
    out[2] = sqrt(fmax(0.0, 1.0 - u1));
}

void bwh_sampler_free(bwh_sampler_t *s)
{
    free(s->theta);
    free(s->trig);
    free(s->node_end);
    free(s->end);
    free(s->leaf);
    free(s->cut);
    free(s->zmap);
    memset(s, 0, sizeof *s);
}

/* the one clamp, of the tables and of sample's value: negative or not
 * finite values of f count as 0 */
static double clamp_f(double v)
{
    return v > 0.0 && isfinite(v) ? v : 0.0;
}

#define CDF_ONE 0x80000000u /* a table's whole probability: 2^31 */

/* Where each leaf's part of [0, 2^31) ends, for leaf values v (>= 0, not
 * all 0): the running sum rounded, a leaf of positive value at least 1 unit
 * wide, a leaf of value 0 empty, the last end 2^31. */
static void leaf_ends(const double *v, size_t n, uint32_t *end)
{
    double total = 0.0, run = 0.0;
    for (size_t k = 0; k < n; k++)
        total += v[k];
    uint64_t prev = 0;
    for (size_t k = 0; k < n; k++) {
        run += v[k];
        double x = (double)CDF_ONE * (run / total);
        uint64_t e = x < (double)CDF_ONE ? (uint64_t)llround(x) : CDF_ONE;
        if (v[k] > 0.0 && e <= prev)
            e = prev + 1;
        end[k] = (uint32_t)(e < prev ? prev : e); /* may pass 2^31: capped below */
        prev = end[k];
    }
    /* room for every positive leaf after k: the caps ascend, so the ends
     * stay ascending and a positive leaf keeps its unit */
    size_t after = 0;
    for (size_t k = n; k-- > 0;) {
        uint64_t cap = (uint64_t)CDF_ONE - after;
        if (end[k] > cap || k + 1 == n)
            end[k] = (uint32_t)cap;
        after += v[k] > 0.0;
    }
}

/* sub-triangle centres and projected solid angles of every leaf */
typedef struct {
    double (*dir)[3];
    double *proj;
    size_t per_leaf;
} subgrid_t;

static void subdivide(const bwh_tri_t *t, unsigned depth, double (*dir)[3], double *proj,
                      size_t *k)
{
    if (depth == 0) {
        bwh_tri_centre(t, dir[*k]);
        proj[*k] = bwh_projected_solid_angle(t->v[0], t->v[1], t->v[2]);
        (*k)++;
        return;
    }
    for (unsigned m = 0; m < 4; m++) {
        bwh_tri_t c;
        bwh_tri_child(t, m, &c);
        subdivide(&c, depth - 1, dir, proj, k);
    }
}

/* The bucket map of the table search (ISO): buckets narrower than the
 * smallest gap between the tables' cosines, so each holds at most one; none
 * (a search) when that would take more than 2^16 buckets. */
static int build_zmap(bwh_sampler_t *s)
{
    size_t n = s->n_tables;
    double gap = 1.0;
    for (size_t i = 0; i + 1 < n; i++) {
        double g = s->trig[2 * i] - s->trig[2 * (i + 1)];
        gap = g < gap ? g : gap;
    }
    size_t m = 64;
    while (m <= 65536 && !(1.0 / (double)m < gap))
        m *= 2;
    if (n < 2 || m > 65536 || n > 65535)
        return 0;
    s->zmap = malloc(m * sizeof *s->zmap);
    if (!s->zmap)
        return -1;
    s->n_zmap = m;
    size_t cnt = n;
    for (size_t j = 0; j < m; j++) {
        double top = (double)(j + 1) / (double)m;
        while (cnt > 0 && s->trig[2 * (cnt - 1)] < top)
            cnt--;
        s->zmap[j] = (uint16_t)cnt;
    }
    return 0;
}

int bwh_sampler_build(bwh_sampler_t *s, int kind, unsigned level, size_t n_tables,
                      const double *theta, unsigned level_in, bwh_brdf_fn f, void *ctx,
                      unsigned supersample, double mix)
{
    memset(s, 0, sizeof *s);
    if (level > BWH_SAMPLER_MAX_LEVEL)
        return bwh_fail("sampler: level %u above %u", level, BWH_SAMPLER_MAX_LEVEL);
    if (supersample > BWH_SAMPLER_MAX_SUPERSAMPLE)
        return bwh_fail("sampler: supersample %u above %u", supersample,
                        BWH_SAMPLER_MAX_SUPERSAMPLE);
    if (!(mix >= 0.0 && mix <= 1.0))
        return bwh_fail("sampler: cosine weight must be in [0, 1]");
    if (f == NULL || n_tables == 0)
        return bwh_fail("sampler: no BRDF or no incoming directions");
    if (kind == BWH_SAMPLER_ISO) {
        if (theta == NULL)
            return bwh_fail("sampler: isotropic tables need their zenith angles");
        for (size_t i = 0; i < n_tables; i++)
            if (!(theta[i] >= 0.0 && theta[i] <= 0.5 * S_PI) || (i && !(theta[i] > theta[i - 1])))
                return bwh_fail("sampler: zenith angles must ascend within [0, pi/2]");
    } else if (kind == BWH_SAMPLER_FULL) {
        if (level_in > BWH_GRID_MAX_LEVEL || n_tables != bwh_grid_count(level_in))
            return bwh_fail("sampler: a full BRDF needs 4*4^level_in tables");
    } else {
        return bwh_fail("sampler: unknown kind %d", kind);
    }

    s->kind = kind;
    s->level = level;
    s->level_in = level_in;
    s->n_tables = n_tables;
    s->n_leaves = bwh_grid_count(level);
    s->node_stride = 0;
    for (unsigned l = (level + 1) % 2; l + 1 <= level; l += 2)
        s->node_stride += level_padded(l);
    s->mix = mix;
    s->f = f;
    s->ctx = ctx;

    /* cutting circles down to the leaves, and to the incoming triangles */
    unsigned cut_levels = kind == BWH_SAMPLER_FULL && level_in > level ? level_in : level;
    subgrid_t g = {NULL, NULL, (size_t)1 << (2u * supersample)};
    bwh_tri_t *tri = malloc(bwh_grid_count(cut_levels) * sizeof *tri);
    double(*in_dir)[3] = malloc(n_tables * sizeof *in_dir);
    s->leaf = aligned_alloc(64, s->n_leaves * sizeof *s->leaf); /* 2 cache lines each */
    s->cut = malloc((cut_levels ? level_offset(cut_levels) : 1) * sizeof *s->cut);
    double *lv = malloc(s->n_leaves * sizeof *lv); /* one table's leaf integrals */
    s->node_end = aligned_alloc(64, (s->node_stride ? n_tables * s->node_stride : 16) *
                                        sizeof *s->node_end);
    s->end = aligned_alloc(64, (n_tables * s->n_leaves + 15) / 16 * 16 * sizeof *s->end);
    g.dir = malloc(s->n_leaves * g.per_leaf * sizeof *g.dir);
    g.proj = malloc(s->n_leaves * g.per_leaf * sizeof *g.proj);
    if (kind == BWH_SAMPLER_ISO) {
        s->theta = malloc(n_tables * sizeof *s->theta);
        s->trig = malloc(2 * n_tables * sizeof *s->trig);
    }
    if (!tri || !in_dir || !s->leaf || !s->cut || !lv || !s->node_end || !s->end ||
        !g.dir || !g.proj || (kind == BWH_SAMPLER_ISO && (!s->theta || !s->trig)))
        goto out_of_memory;
    for (unsigned l = 0; l < cut_levels; l++) {
        bwh_grid_triangles(l, tri);
        for (size_t k = 0; k < bwh_grid_count(l); k++)
            bwh_tri_cut_normals(&tri[k], s->cut[level_offset(l) + k]);
    }
    bwh_grid_triangles(level, tri);
    for (size_t k = 0; k < s->n_leaves; k++) {
        bwh_leaf_init(&s->leaf[k], tri[k].v[0], tri[k].v[1], tri[k].v[2]);
        size_t j = k * g.per_leaf;
        subdivide(&tri[k], supersample, g.dir, g.proj, &j);
    }
    free(tri);
    tri = NULL;
    if (kind == BWH_SAMPLER_ISO) {
        for (size_t i = 0; i < n_tables; i++) {
            s->theta[i] = theta[i];
            s->trig[2 * i] = cos(theta[i]);
            s->trig[2 * i + 1] = sin(theta[i]);
            in_dir[i][0] = s->trig[2 * i + 1];
            in_dir[i][1] = 0.0;
            in_dir[i][2] = s->trig[2 * i];
        }
        if (build_zmap(s) != 0)
            goto out_of_memory;
    } else {
        bwh_grid_centres(level_in, in_dir, NULL);
    }

    double proj_total = 0.0; /* pi, as the leaves add up */
    for (size_t k = 0; k < s->n_leaves; k++)
        proj_total += s->leaf[k].proj;
    for (size_t i = 0; i < n_tables; i++) {
        double total = 0.0;
        for (size_t k = 0; k < s->n_leaves; k++) {
            double sum = 0.0;
            for (size_t j = 0; j < g.per_leaf; j++) {
                size_t q = k * g.per_leaf + j;
                sum += clamp_f(f(ctx, in_dir[i], g.dir[q])) * g.proj[q];
            }
            lv[k] = sum;
            total += sum;
        }
        if (!(total > 0.0) || !isfinite(total)) {
            /* nothing to follow: the projected solid angle (the cosine lobe) */
            for (size_t k = 0; k < s->n_leaves; k++)
                lv[k] = s->leaf[k].proj;
        } else if (mix > 0.0) {
            /* each leaf's share of the cosine lobe mixed in */
            for (size_t k = 0; k < s->n_leaves; k++)
                lv[k] = (1.0 - mix) * (lv[k] / total) + mix * (s->leaf[k].proj / proj_total);
        }
        /* the leaves' ends, and above them the kept levels' node ends (a
         * node's part ends where its last leaf's does) */
        uint32_t *end = s->end + i * s->n_leaves;
        leaf_ends(lv, s->n_leaves, end);
        uint32_t *ne = s->node_end + i * s->node_stride;
        for (unsigned l = (level + 1) % 2; l + 1 <= level; l += 2) {
            size_t span = (size_t)1 << (2u * (level - l)); /* leaves under a node */
            size_t n_node = bwh_grid_count(l), q = 0;
            for (; q < n_node; q++)
                ne[q] = end[(q + 1) * span - 1];
            for (; q < level_padded(l); q++)
                ne[q] = UINT32_MAX;
            ne += level_padded(l);
        }
    }
    free(lv);
    free(in_dir);
    free(g.dir);
    free(g.proj);
    return 0;

out_of_memory:
    free(tri);
    free(lv);
    free(in_dir);
    free(g.dir);
    free(g.proj);
    bwh_sampler_free(s);
    return bwh_fail("sampler: out of memory");
}

/* The triangle of `level` holding d (z >= 0, finite): bwh_grid_locate's
 * descent with the cutting normals stored, so it gives the same triangle
 * without forming midpoints. */
static size_t locate(const bwh_sampler_t *s, unsigned level, const double d[3])
{
    size_t idx = bwh_grid_base(d);
    for (unsigned l = 0; l < level; l++)
        idx = 4 * idx + bwh_cut_child((const double(*)[3])s->cut[level_offset(l) + idx], d);
    return idx;
}

/* The tables for wi and their weights, and the rotation taking wi to
 * phi = 0 (ISO). Table t[0] has weight b / (a + b), t[1] (when n = 2)
 * a / (a + b); w[] are these weights. Returns the number of tables (1 or
 * 2), 0 for a bad wi. */
typedef struct {
    size_t t[2];
    double w[2];
    double a, b; /* the weights before normalising (1 table: a = 0, b = 1) */
    int n;
    double c, s; /* cos, sin of phi_i (ISO); 1, 0 otherwise */
} select_t;

static int one_table(select_t *sel, size_t t)
{
    sel->t[0] = sel->t[1] = t;
    sel->w[0] = 1.0;
    sel->w[1] = 0.0;
    sel->a = 0.0;
    sel->b = 1.0;
    return sel->n = 1;
}

static int select_tables(const bwh_sampler_t *s, const double wi[3], select_t *sel)
{
    if (!(wi[2] > 0.0) || !isfinite(wi[0]) || !isfinite(wi[1]) || !isfinite(wi[2]))
        return 0;
    sel->c = 1.0;
    sel->s = 0.0;
    if (s->kind == BWH_SAMPLER_FULL)
        return one_table(sel, locate(s, s->level_in, wi));
    double r2 = wi[0] * wi[0] + wi[1] * wi[1], l2 = r2 + wi[2] * wi[2];
    double len_xy = sqrt(r2), r = len_xy, z = wi[2];
    if (fabs(l2 - 1.0) > 0x1p-40) { /* not a unit vector */
        double inv_len = 1.0 / sqrt(l2);
        z *= inv_len;
        r *= inv_len;
    }
    /* the azimuth: off the path to the table search */
    if (len_xy > 1e-300) {
        double inv = 1.0 / len_xy;
        sel->c = wi[0] * inv;
        sel->s = wi[1] * inv;
    }
    /* the tables around theta_i, by their cosines (no arc tangent) */
    size_t n = s->n_tables;
    const double *tr = s->trig;
    if (n == 1 || z >= tr[0])
        return one_table(sel, 0);
    if (z <= tr[2 * (n - 1)])
        return one_table(sel, n - 1);
    /* the last table with cos(theta) >= z: theta[lo] <= theta_i < theta[lo + 1] */
    size_t lo;
    if (s->zmap) {
        /* zmap[j] tables have cos(theta) >= (j + 1) / n_zmap, the top of
         * z's bucket; at most one more lies in the bucket */
        size_t j = (size_t)(z * (double)s->n_zmap), cnt;
        cnt = s->zmap[j < s->n_zmap ? j : s->n_zmap - 1];
        lo = cnt - 1 + (size_t)(tr[2 * cnt] >= z);
    } else {
        /* a search without branches: its steps do not depend on z */
        lo = 0;
        for (size_t len = n - 1; len > 1;) { /* candidates lo .. lo + len - 1 */
            size_t half = len / 2;
            lo = tr[2 * (lo + half)] >= z ? lo + half : lo;
            len -= half;
        }
    }
    size_t hi = lo + 1;
    /* weights sin(theta_i - theta[lo]), sin(theta[hi] - theta_i) */
    double a = r * tr[2 * lo] - z * tr[2 * lo + 1];
    double b = z * tr[2 * hi + 1] - r * tr[2 * hi];
    a = a > 0.0 ? a : 0.0;
    b = b > 0.0 ? b : 0.0;
    if (!(a + b > 0.0)) {
        a = 0.0;
        b = 1.0;
    }
    double inv = 1.0 / (a + b);
    sel->t[0] = lo;
    sel->t[1] = hi;
    sel->a = a;
    sel->b = b;
    sel->w[0] = b * inv;
    sel->w[1] = a * inv;
    return sel->n = 2;
}

/* world -> local (phi_i = 0) and back */
static void to_local(const select_t *sel, const double w[3], double out[3])
{
    double x = sel->c * w[0] + sel->s * w[1];
    double y = -sel->s * w[0] + sel->c * w[1];
    out[0] = x;
    out[1] = y;
    out[2] = w[2];
}

static void to_world(const select_t *sel, const double w[3], double out[3])
{
    double x = sel->c * w[0] - sel->s * w[1];
    double y = sel->s * w[0] + sel->c * w[1];
    out[0] = x;
    out[1] = y;
    out[2] = w[2];
}

/* probability of leaf k in table t: its part's width */
static inline double leaf_prob(const bwh_sampler_t *s, size_t t, size_t k)
{
    const uint32_t *end = s->end + t * s->n_leaves;
    return 0x1p-31 * (double)(end[k] - (k ? end[k - 1] : 0u));
}

/* tree pdf of leaf k (local frame) */
static double tree_pdf(const bwh_sampler_t *s, const select_t *sel, size_t k)
{
    double p = 0.0;
    for (int i = 0; i < sel->n; i++)
        p += sel->w[i] * leaf_prob(s, sel->t[i], k);
    return p * s->leaf[k].inv_area;
}

/* the leaf holding wo (world frame, z >= 0, finite) */
static size_t leaf_of(const bwh_sampler_t *s, const select_t *sel, const double wo[3])
{
    double local[3];
    to_local(sel, wo, local);
    return locate(s, s->level, local);
}

/* how many of the n ends e[] lie at or below x: the node among those that
 * holds x (a node of probability 0 has an empty part and is never picked) */
static inline unsigned count_below(const uint32_t *e, unsigned n, uint32_t x)
{
    unsigned c = 0;
    for (unsigned j = 0; j < n; j++)
        c += x >= e[j];
    return c;
}

/* The leaf whose part of [0, 2^31) holds x in table t. The 4-way choice of
 * the hierarchy, two levels at a time down to the leaves' parents: from a
 * node, the one of its 16 grandchildren (side by side in the next kept
 * level, 64 bytes) whose part holds x; the same node as one level at a
 * time, in half the dependent reads. The top step chooses among the 4 base
 * triangles (odd level) or their 16 children (even level). Then the 4
 * candidate leaves' triangles (8 cache lines) are fetched while their ends
 * are compared. */
static size_t descend(const bwh_sampler_t *s, size_t t, uint32_t x)
{
    const uint32_t *leaf_end = s->end + t * s->n_leaves;
    size_t idx = 0;
    if (s->level > 0) {
        const uint32_t *ne = s->node_end + t * s->node_stride;
        unsigned l = (s->level + 1) % 2;
        idx = count_below(ne, l ? 16u : 4u, x);
        for (; l + 3 <= s->level; l += 2) {
            ne += level_padded(l);
            idx = 16 * idx + count_below(ne + 16 * idx, 16u, x);
        }
        for (int j = 0; j < 8; j++)
            __builtin_prefetch((const char *)&s->leaf[4 * idx] + 64 * j);
    }
    return 4 * idx + count_below(leaf_end + 4 * idx, 4u, x);
}

/* the same leaf by walking the leaves' ends (their running sum) in order,
 * O(n): the first that lies above x */
static size_t scan(const bwh_sampler_t *s, size_t t, uint32_t x)
{
    const uint32_t *end = s->end + t * s->n_leaves;
    size_t k = 0;
    while (k + 1 < s->n_leaves && x >= end[k])
        k++;
    return k;
}

/* u clamped into [0, 1) (NaN to 0) */
static inline double unit_interval(double u)
{
    u = u > 0.0 ? u : 0.0;
    return u < 0x1.fffffffffffffp-1 ? u : 0x1.fffffffffffffp-1;
}

static int sample_with(const bwh_sampler_t *s, const double wi[3], const double u[3],
                       double wo[3], double *pdf, double *value, int linear)
{
    select_t sel;
    if (!select_tables(s, wi, &sel))
        return -1;
    /* u0, scaled to [0, 2^31), is the point of the descent */
    uint32_t x = (uint32_t)(unit_interval(u[0]) * (double)CDF_ONE);
    /* u2 picks the table, table 1 below a / (a + b), and is rescaled to
     * [0, 1) inside the chosen one's share: the division waits for Arvo's
     * second step, not the descent */
    double u1 = unit_interval(u[1]), u2 = unit_interval(u[2]), v = u2 * (sel.a + sel.b);
    size_t t = sel.t[0];
    if (v < sel.a) {
        t = sel.t[1];
        u2 = v / sel.a;
    } else {
        u2 = (v - sel.a) / sel.b;
    }
    u2 = unit_interval(u2); /* the rescaling may round up to 1 */
    size_t k = linear ? scan(s, t, x) : descend(s, t, x);
    double local[3];
    bwh_leaf_sample(&s->leaf[k], u1, u2, local);
    to_world(&sel, local, wo);
    *pdf = tree_pdf(s, &sel, k);
    if (value)
        *value = clamp_f(s->f(s->ctx, wi, wo));
    return 0;
}

int bwh_sampler_sample(const bwh_sampler_t *s, const double wi[3], const double u[3],
                       double wo[3], double *pdf, double *value)
{
    return sample_with(s, wi, u, wo, pdf, value, 0);
}

int bwh_sampler_sample_linear(const bwh_sampler_t *s, const double wi[3], const double u[3],
                              double wo[3], double *pdf, double *value)
{
    return sample_with(s, wi, u, wo, pdf, value, 1);
}

double bwh_sampler_pdf(const bwh_sampler_t *s, const double wi[3], const double wo[3])
{
    select_t sel;
    if (!select_tables(s, wi, &sel) || !(wo[2] >= 0.0) || !isfinite(wo[0]) ||
        !isfinite(wo[1]) || !isfinite(wo[2]))
        return 0.0;
    return tree_pdf(s, &sel, leaf_of(s, &sel, wo));
}

double bwh_sampler_leaf_mass(const bwh_sampler_t *s, const double wi[3], size_t leaf)
{
    select_t sel;
    if (leaf >= s->n_leaves || !select_tables(s, wi, &sel))
        return 0.0;
    return tree_pdf(s, &sel, leaf) * s->leaf[leaf].area;
}

/* ---- analytic lobes --------------------------------------------------- */

/* an orthonormal frame (t, b, n) about the unit vector n */
static void frame(const double n[3], double t[3], double b[3])
{
    if (fabs(n[2]) < 0.9) {
        double z[3] = {0.0, 0.0, 1.0};
        bwg_cross3(z, n, t);
    } else {
        double x[3] = {1.0, 0.0, 0.0};
        bwg_cross3(x, n, t);
    }
    bwg_normalize3(t);
    bwg_cross3(n, t, b);
}

static double diffuse_prob(const bwh_brdf_params_t *p)
{
    double s = p->kd + p->ks;
    return s > 0.0 ? p->kd / s : 1.0;
}

void bwh_phong_sample(const bwh_brdf_params_t *p, const double wi[3], const double u[3],
                      double wo[3])
{
    double pd = diffuse_prob(p);
    if (u[0] < pd) {
        bwh_sample_cosine(u[1], u[2], wo);
        return;
    }
    double r[3] = {-wi[0], -wi[1], wi[2]}, t[3], b[3];
    frame(r, t, b);
    double ca = pow(u[1], 1.0 / (p->n + 1.0)), sa = sqrt(fmax(0.0, 1.0 - ca * ca));
    double phi = 2.0 * S_PI * u[2], x = sa * cos(phi), y = sa * sin(phi);
    for (int k = 0; k < 3; k++)
        wo[k] = x * t[k] + y * b[k] + ca * r[k];
}

double bwh_phong_pdf(const bwh_brdf_params_t *p, const double wi[3], const double wo[3])
{
    if (!(wo[2] > 0.0))
        return 0.0;
    double pd = diffuse_prob(p);
    double c = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2];
    double lobe = c > 0.0 ? (p->n + 1.0) / (2.0 * S_PI) * pow(c, p->n) : 0.0;
    return pd * wo[2] / S_PI + (1.0 - pd) * lobe;
}

void bwh_ward_sample(const bwh_brdf_params_t *p, const double wi[3], const double u[3],
                     double wo[3])
{
    double pd = diffuse_prob(p);
    if (u[0] < pd) {
        bwh_sample_cosine(u[1], u[2], wo);
        return;
    }
    /* phi_h = atan(ay/ax tan(2 pi u2)) in the quadrant of 2 pi u2 */
    double a = 2.0 * S_PI * u[2];
    double phi = atan2(p->ay * sin(a), p->ax * cos(a));
    double cp = cos(phi), sp = sin(phi);
    double q = cp * cp / (p->ax * p->ax) + sp * sp / (p->ay * p->ay);
    double u1 = u[1] > 0.0 ? u[1] : 1e-300;
    double th = atan(sqrt(-log(u1) / q));
    double st = sin(th), h[3] = {st * cp, st * sp, cos(th)};
    double d = bwg_dot3(wi, h);
    for (int k = 0; k < 3; k++)
        wo[k] = 2.0 * d * h[k] - wi[k];
}

double bwh_ward_pdf(const bwh_brdf_params_t *p, const double wi[3], const double wo[3])
{
    if (!(wo[2] > 0.0))
        return 0.0;
    double pd = diffuse_prob(p);
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    bwg_normalize3(h);
    double spec = 0.0;
    if (h[2] > 0.0) {
        double c2 = h[2] * h[2], t2 = (1.0 - c2) / c2;
        double r2 = h[0] * h[0] + h[1] * h[1];
        double q = r2 > 0.0 ? (h[0] * h[0] / (p->ax * p->ax) + h[1] * h[1] / (p->ay * p->ay)) / r2
                            : 0.0;
        double ph = exp(-t2 * q) / (S_PI * p->ax * p->ay * c2 * h[2]);
        double oh = bwg_dot3(wo, h);
        spec = oh > 0.0 ? ph / (4.0 * oh) : 0.0;
    }
    return pd * wo[2] / S_PI + (1.0 - pd) * spec;
}
