/* Importance sampling of a BRDF from the triangle hierarchy (bw_sample.h). */
#include "bw_sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwhost.h"
#include "geodesic.h"

#define S_PI 3.14159265358979323846

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
    double tb[3], tc[3], ab = bwg_dot3(a, b), ac = bwg_dot3(a, c);
    for (int k = 0; k < 3; k++) {
        tb[k] = b[k] - ab * a[k];
        tc[k] = c[k] - ac * a[k];
    }
    bwg_normalize3(tb);
    bwg_normalize3(tc);
    double ca = bwg_dot3(tb, tc);
    ca = ca > 1.0 ? 1.0 : ca < -1.0 ? -1.0 : ca;
    t->alpha = acos(ca);
    t->cos_alpha = ca;
    t->sin_alpha = sin(t->alpha);
    t->cos_c = ab;
    memcpy(t->e, tc, sizeof t->e);
    t->area = bwh_solid_angle(a, b, c);
    t->inv_area = 1.0 / t->area;
    t->proj = bwh_projected_solid_angle(a, b, c);
}

/* Arvo, "Stratified sampling of spherical triangles" (SIGGRAPH 1995): u1
 * picks the sub-triangle (a, b, c') of area u1 * area, u2 a point on the
 * arc from b to c'. */
void bwh_leaf_sample(const bwh_leaf_t *t, double u1, double u2, double out[3])
{
    double ahat = u1 * t->area, s, c;
    if (t->area <= 0.1) {
        /* sin, cos of ahat - alpha by the sum formulas, with the Taylor
         * series of the small angle ahat to x^9 and x^8: the first term
         * left out is below 3e-17; the powers paired so that the chain of
         * dependent products stays short */
        double x2 = ahat * ahat, x4 = x2 * x2;
        double sa = ahat + ahat * x2 *
                               ((-1.0 / 6.0 + x2 * (1.0 / 120.0)) +
                                x4 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0)));
        double ca = 1.0 + x2 * ((-1.0 / 2.0 + x2 * (1.0 / 24.0)) +
                                x4 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0)));
        s = sa * t->cos_alpha - ca * t->sin_alpha;
        c = ca * t->cos_alpha + sa * t->sin_alpha;
    } else {
        s = sin(ahat - t->alpha);
        c = cos(ahat - t->alpha);
    }
    double uu = c - t->cos_alpha;
    double vv = s + t->sin_alpha * t->cos_c;
    /* q = cos of the arc from a to c' = num / den, and sqrt(1 - q^2) as
     * sqrt(den^2 - num^2) / |den|: the square root and the reciprocal run
     * side by side */
    double num = (vv * c - uu * s) * t->cos_alpha - vv;
    double den = (vv * s + uu * c) * t->sin_alpha;
    double r2 = (den - num) * (den + num);
    double rden = 1.0 / den, root = sqrt(r2 > 0.0 ? r2 : 0.0);
    double q = num * rden;
    q = q > 1.0 ? 1.0 : q < -1.0 ? -1.0 : q;
    double sq = root * fabs(rden), cp[3];
    sq = sq < 1.0 ? sq : 1.0;
    for (int k = 0; k < 3; k++)
        cp[k] = q * t->a[k] + sq * t->e[k];
    /* on the arc from b to c': z = cos of the angle from b, with
     * w = 1 - cos(b, c') = |c' - b|^2 / 2 (no cancellation), 1 - z = u2 w;
     * along the arc f = c' - (1 - w) b, of length sqrt(w (2 - w)) */
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = cp[k] - t->b[k];
    double w = 0.5 * bwg_dot3(d, d), uw = u2 * w, z = 1.0 - uw;
    /* g |f| = sqrt(1 - z^2) = sqrt(uw (2 - uw)) */
    double g = sqrt(u2 * (2.0 - uw) / (2.0 - w));
    for (int k = 0; k < 3; k++)
        out[k] = z * t->b[k] + g * (d[k] + w * t->b[k]);
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
    free(s->cdf);
    free(s->end);
    free(s->leaf);
    free(s->cut);
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
    s->n_groups = level_offset(level) / 4; /* groups of 4 siblings above the leaves */
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
    s->cdf = malloc((s->n_groups ? n_tables * s->n_groups : 1) * sizeof *s->cdf);
    s->end = malloc(n_tables * s->n_leaves * sizeof *s->end);
    g.dir = malloc(s->n_leaves * g.per_leaf * sizeof *g.dir);
    g.proj = malloc(s->n_leaves * g.per_leaf * sizeof *g.proj);
    if (kind == BWH_SAMPLER_ISO) {
        s->theta = malloc(n_tables * sizeof *s->theta);
        s->trig = malloc(2 * n_tables * sizeof *s->trig);
    }
    if (!tri || !in_dir || !s->leaf || !s->cut || !lv || !s->cdf || !s->end ||
        !g.dir || !g.proj || (kind == BWH_SAMPLER_ISO && (!s->theta || !s->trig))) {
        free(tri);
        free(lv);
        free(in_dir);
        free(g.dir);
        free(g.proj);
        bwh_sampler_free(s);
        return bwh_fail("sampler: out of memory");
    }
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
    if (kind == BWH_SAMPLER_ISO) {
        for (size_t i = 0; i < n_tables; i++) {
            s->theta[i] = theta[i];
            s->trig[2 * i] = cos(theta[i]);
            s->trig[2 * i + 1] = sin(theta[i]);
            in_dir[i][0] = s->trig[2 * i + 1];
            in_dir[i][1] = 0.0;
            in_dir[i][2] = s->trig[2 * i];
        }
    } else {
        bwh_grid_centres(level_in, in_dir, NULL);
    }

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
        }
        /* the leaves' ends, and above them each group's first 3 ends */
        uint32_t *end = s->end + i * s->n_leaves;
        leaf_ends(lv, s->n_leaves, end);
        bwh_cdf_group_t *grp = s->cdf + i * s->n_groups;
        for (unsigned l = 0; l < level; l++) {
            size_t span = (size_t)1 << (2u * (level - l)); /* leaves under a node */
            size_t n_grp = (size_t)1 << (2u * l);
            for (size_t q = 0; q < n_grp; q++)
                for (unsigned m = 0; m < 3; m++)
                    grp[level_offset(l) / 4 + q].end[m] = end[(4 * q + m + 1) * span - 1];
        }
    }
    free(lv);
    free(in_dir);
    free(g.dir);
    free(g.proj);
    return 0;
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
 * phi = 0 (ISO). Returns the number of tables (1 or 2), 0 for a bad wi. */
typedef struct {
    size_t t[2];
    double w[2];
    int n;
    double c, s; /* cos, sin of phi_i (ISO); 1, 0 otherwise */
} select_t;

static int select_tables(const bwh_sampler_t *s, const double wi[3], select_t *sel)
{
    if (!(wi[2] > 0.0) || !isfinite(wi[0]) || !isfinite(wi[1]) || !isfinite(wi[2]))
        return 0;
    sel->c = 1.0;
    sel->s = 0.0;
    if (s->kind == BWH_SAMPLER_FULL) {
        sel->t[0] = locate(s, s->level_in, wi);
        sel->w[0] = 1.0;
        return sel->n = 1;
    }
    double r2 = wi[0] * wi[0] + wi[1] * wi[1], r = sqrt(r2);
    if (r > 1e-300) {
        double inv = 1.0 / r;
        sel->c = wi[0] * inv;
        sel->s = wi[1] * inv;
    }
    double inv_len = 1.0 / sqrt(r2 + wi[2] * wi[2]), z = wi[2] * inv_len;
    r *= inv_len;
    /* the tables around theta_i, by their cosines (no arc tangent) */
    size_t n = s->n_tables;
    const double *tr = s->trig;
    if (n == 1 || z >= tr[0]) {
        sel->t[0] = 0;
        sel->w[0] = 1.0;
        return sel->n = 1;
    }
    if (z <= tr[2 * (n - 1)]) {
        sel->t[0] = n - 1;
        sel->w[0] = 1.0;
        return sel->n = 1;
    }
    /* the last table with cos(theta) >= z: theta[lo] <= theta_i < theta[lo + 1]
     * (a search without branches: its steps do not depend on z) */
    size_t lo = 0;
    for (size_t len = n - 1; len > 1;) { /* candidates lo .. lo + len - 1 */
        size_t half = len / 2;
        lo = tr[2 * (lo + half)] >= z ? lo + half : lo;
        len -= half;
    }
    size_t hi = lo + 1;
    /* weights sin(theta_i - theta[lo]), sin(theta[hi] - theta_i), normalised */
    double a = r * tr[2 * lo] - z * tr[2 * lo + 1];
    double b = z * tr[2 * hi + 1] - r * tr[2 * hi];
    a = a > 0.0 ? a : 0.0;
    b = b > 0.0 ? b : 0.0;
    double t = a + b > 0.0 ? a / (a + b) : 0.0;
    sel->t[0] = lo;
    sel->w[0] = 1.0 - t;
    sel->t[1] = hi;
    sel->w[1] = t;
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

/* the mixture's pdf at a direction in leaf k with cos(theta_o) = cos_o */
static double mixture_pdf(const bwh_sampler_t *s, const select_t *sel, size_t k, double cos_o)
{
    return s->mix * cos_o / S_PI + (1.0 - s->mix) * tree_pdf(s, sel, k);
}

/* the leaf holding wo (world frame, z >= 0, finite) */
static size_t leaf_of(const bwh_sampler_t *s, const select_t *sel, const double wo[3])
{
    double local[3];
    to_local(sel, wo, local);
    return locate(s, s->level, local);
}

/* The leaf whose part of [0, 2^31) holds x in table t: at each level the
 * child is the number of its siblings' ends at or below x (a child of
 * probability 0 has an empty part and is never picked); the leaves' own
 * ends give the last step. The reads depend on each other; while one level
 * is read, the next level's 4 candidates (side by side) are fetched, and
 * before the last step the 4 candidate leaves' triangles (8 cache lines). */
static size_t descend(const bwh_sampler_t *s, size_t t, uint32_t x)
{
    const bwh_cdf_group_t *g = s->cdf + t * s->n_groups;
    const uint32_t *leaf_end = s->end + t * s->n_leaves;
    size_t idx = 0;
    for (unsigned l = 0; l < s->level; l++) {
        const bwh_cdf_group_t *next = g + ((size_t)1 << (2u * l)); /* level l + 1's */
        if (l + 1 < s->level)
            __builtin_prefetch(next + 4 * idx);
        else
            __builtin_prefetch(leaf_end + 16 * idx);
        const uint32_t *e = g[idx].end;
        idx = 4 * idx + (unsigned)(x >= e[0]) + (unsigned)(x >= e[1]) + (unsigned)(x >= e[2]);
        g = next;
    }
    for (int j = 0; j < 8; j++)
        __builtin_prefetch((const char *)&s->leaf[4 * idx] + 64 * j);
    const uint32_t *e = leaf_end + 4 * idx;
    return 4 * idx + (unsigned)(x >= e[0]) + (unsigned)(x >= e[1]) + (unsigned)(x >= e[2]);
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

static int sample_with(const bwh_sampler_t *s, const double wi[3], const double u[3],
                       double wo[3], double *pdf, double *value, int linear)
{
    select_t sel;
    if (!select_tables(s, wi, &sel))
        return -1;
    double u0 = u[0];
    size_t k;
    if (u0 < s->mix) {
        bwh_sample_cosine(u[1], u[2], wo);
        k = leaf_of(s, &sel, wo);
    } else {
        if (s->mix > 0.0)
            u0 = (u0 - s->mix) / (1.0 - s->mix);
        int chosen = 0; /* the table drawn from */
        if (sel.n == 2) {
            if (u0 < sel.w[1]) {
                chosen = 1;
                u0 /= sel.w[1];
            } else {
                u0 = (u0 - sel.w[1]) / sel.w[0];
            }
        }
        if (u0 >= 1.0)
            u0 = nextafter(1.0, 0.0);
        size_t t = sel.t[chosen];
        uint32_t x = (uint32_t)(u0 * (double)CDF_ONE);
        k = linear ? scan(s, t, x) : descend(s, t, x);
        double local[3];
        bwh_leaf_sample(&s->leaf[k], u[1], u[2], local);
        to_world(&sel, local, wo);
    }
    *pdf = mixture_pdf(s, &sel, k, wo[2] > 0.0 ? wo[2] : 0.0);
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
    return mixture_pdf(s, &sel, leaf_of(s, &sel, wo), wo[2]);
}

double bwh_sampler_leaf_mass(const bwh_sampler_t *s, const double wi[3], size_t leaf)
{
    select_t sel;
    if (leaf >= s->n_leaves || !select_tables(s, wi, &sel))
        return 0.0;
    return s->mix * s->leaf[leaf].proj / S_PI +
           (1.0 - s->mix) * tree_pdf(s, &sel, leaf) * s->leaf[leaf].area;
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
