/*
 * brdfwave render: a small multithreaded path tracer for the paper's
 * comparison of sampling strategies (sec. 6.2, Tables 5 and 6).
 *
 * Scenes are closed rooms with diffuse walls and an emitting panel in the
 * ceiling; the objects carry the materials given with --material (analytic
 * Phong or Ward, or a decoded payload). At every hit on such an object the
 * next direction comes from the chosen strategy (uniform hemisphere, cosine,
 * the analytic lobe, or the wavelet hierarchy); the diffuse walls always
 * sample the cosine. Paths end on the light or after --depth bounces; the
 * value carried is f cos / pdf with the BRDF's own values (the sampling
 * structure only picks directions). With --direct mis every hit also takes
 * one sample of the light panel, and the two ways of reaching the light are
 * weighted by the power heuristic (Veach 1997) with the strategy's pdf.
 *
 * Output: a PNG (sRGB-encoded) and key: value lines, among them the image
 * variance of sec. 6.2: for every interior pixel the variance of the
 * displayed intensity (mean of R, G, B clamped to [0, 1]) over the 3 x 3
 * block of the pixel and its 8 neighbours, averaged over the image.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "brdf_eval.h"
#include "brdf_models.h"
#include "bw_mesh.h"
#include "bw_sample.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "commands.h"
#include "geodesic.h"
#include "render_png.h"

#define R_PI 3.14159265358979323846
#define R_EPS 1e-6
#define MAX_MATERIALS 8
#define MAX_SPP 1000000L

/* ---- vectors ------------------------------------------------------------ */

typedef struct {
    double x, y, z;
} v3;

static v3 vec(double x, double y, double z) { return (v3){x, y, z}; }
static v3 add(v3 a, v3 b) { return vec(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 sub(v3 a, v3 b) { return vec(a.x - b.x, a.y - b.y, a.z - b.z); }
static v3 mul(v3 a, double s) { return vec(a.x * s, a.y * s, a.z * s); }
static v3 mulv(v3 a, v3 b) { return vec(a.x * b.x, a.y * b.y, a.z * b.z); } /* per channel */
static double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 cross(v3 a, v3 b)
{
    return vec(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static v3 norm(v3 a) { return mul(a, 1.0 / sqrt(dot(a, a))); }

/* ---- random numbers: splitmix64 seeding, xorshift64* stream ------------- */

typedef struct {
    uint64_t s;
} rng_t;

static uint64_t splitmix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

static double rnd(rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (double)((r->s * 0x2545f4914f6cdd1dull) >> 11) * 0x1.0p-53;
}

/* ---- materials ------------------------------------------------------------ */

enum mat_kind { MAT_DIFFUSE, MAT_PHONG, MAT_WARD, MAT_DATA, MAT_LIGHT };
enum strategy { S_UNIFORM, S_COSINE, S_ANALYTIC, S_WAVELET };
static const char *const strategy_names[] = {"uniform", "cosine", "analytic", "wavelet"};

typedef struct {
    enum mat_kind kind;
    v3 albedo;            /* diffuse: reflectance; light: emitted radiance */
    bwh_brdf_params_t p;  /* phong, ward */
    bwh_brdf_data_t data; /* decoded payload */
    bwh_sampler_t sampler;
    int has_sampler;
    char spec[256];
} material_t;

static double analytic_f(void *ctx, const double wi[3], const double wo[3])
{
    const material_t *m = ctx;
    return m->kind == MAT_PHONG ? bwh_brdf_phong(&m->p, wi, wo) : bwh_brdf_ward(&m->p, wi, wo);
}

/* f(wi, wo) per channel, directions in the local frame (z = normal) */
static v3 mat_eval(const material_t *m, const double wi[3], const double wo[3])
{
    switch (m->kind) {
    case MAT_DIFFUSE:
        return mul(m->albedo, 1.0 / R_PI);
    case MAT_PHONG: {
        double f = bwh_brdf_phong(&m->p, wi, wo);
        return vec(f, f, f);
    }
    case MAT_WARD: {
        double f = bwh_brdf_ward(&m->p, wi, wo);
        return vec(f, f, f);
    }
    case MAT_DATA: {
        double c[3];
        for (size_t k = 0; k < 3; k++) {
            double v = bwh_brdf_data_band(&m->data, wi, wo, m->data.bands == 3 ? k : 0);
            c[k] = v > 0.0 ? v : 0.0; /* values below 0 left by compression */
        }
        return vec(c[0], c[1], c[2]);
    }
    default:
        return vec(0, 0, 0);
    }
}

/* ---- scene ------------------------------------------------------------------ */

typedef struct {
    v3 c;
    double r;
    int mat;
} sphere_t;

typedef struct {
    v3 o, u, v, n; /* parallelogram o + s u + t v, s, t in [0, 1] */
    int mat;
} quad_t;

/* sphereflake node: a sphere with 9 children of a third of its radius */
typedef struct flake {
    v3 c;
    double r, bound;
    int mat;
    int n_child;
    struct flake *child;
} flake_t;

typedef struct {
    quad_t *quad;
    size_t n_quad;
    sphere_t *sph;
    size_t n_sph;
    flake_t *flake; /* NULL or the root */
    bwh_mesh_t mesh; /* triangles, all of material mesh_mat */
    int mesh_mat;
    v3 eye, look, up;
    double fov_deg;
    material_t mat[MAX_MATERIALS + 3];
    int n_mat;
    const quad_t *light; /* the emitting panel */
    double light_area;
} scene_t;

enum { MAT_WALL = 0, MAT_WALL_RED, MAT_LIGHT_ID, MAT_SLOT0 };

static void add_quad(scene_t *s, v3 o, v3 u, v3 v, int mat)
{
    quad_t *q = &s->quad[s->n_quad++];
    q->o = o;
    q->u = u;
    q->v = v;
    q->n = norm(cross(u, v));
    q->mat = mat;
}

/* box [x0,x1] x [y0,y1] x [z0,z1], normals outwards */
static void add_box(scene_t *s, v3 lo, v3 hi, int mat)
{
    double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
    add_quad(s, lo, vec(0, dy, 0), vec(dx, 0, 0), mat);             /* bottom, -z */
    add_quad(s, vec(lo.x, lo.y, hi.z), vec(dx, 0, 0), vec(0, dy, 0), mat); /* top */
    add_quad(s, lo, vec(dx, 0, 0), vec(0, 0, dz), mat);             /* -y */
    add_quad(s, vec(lo.x, hi.y, lo.z), vec(0, 0, dz), vec(dx, 0, 0), mat); /* +y */
    add_quad(s, lo, vec(0, 0, dz), vec(0, dy, 0), mat);             /* -x */
    add_quad(s, vec(hi.x, lo.y, lo.z), vec(0, dy, 0), vec(0, 0, dz), mat); /* +x */
}

/* the room: x in [-1, 1] (left/right), y in [-1, 1] (back at +1), z in
 * [0, 2] (up); normals point inwards; a light panel under the ceiling */
static void add_room(scene_t *s)
{
    add_quad(s, vec(-1, -1, 0), vec(2, 0, 0), vec(0, 2, 0), MAT_WALL);     /* floor */
    add_quad(s, vec(-1, -1, 2), vec(0, 2, 0), vec(2, 0, 0), MAT_WALL);     /* ceiling */
    add_quad(s, vec(-1, 1, 0), vec(2, 0, 0), vec(0, 0, 2), MAT_WALL);      /* back */
    add_quad(s, vec(-1, -1, 0), vec(0, 0, 2), vec(2, 0, 0), MAT_WALL);     /* front */
    add_quad(s, vec(-1, -1, 0), vec(0, 2, 0), vec(0, 0, 2), MAT_WALL_RED); /* left */
    add_quad(s, vec(1, -1, 0), vec(0, 0, 2), vec(0, 2, 0), MAT_WALL);      /* right */
    add_quad(s, vec(-0.8, -0.8, 1.999), vec(0, 1.6, 0), vec(1.6, 0, 0), MAT_LIGHT_ID);
    s->light = &s->quad[s->n_quad - 1];
    v3 c = cross(s->light->u, s->light->v);
    s->light_area = sqrt(dot(c, c));
}

static void flake_build(flake_t *f, v3 c, double r, v3 up, int depth, int mat)
{
    f->c = c;
    f->r = r;
    f->mat = mat;
    f->bound = 2.0 * r; /* r (1 + 2/3 + 2/9 + ...) < 2 r */
    f->n_child = 0;
    f->child = NULL;
    if (depth == 0)
        return;
    f->child = calloc(9, sizeof *f->child);
    if (!f->child)
        return;
    v3 t = fabs(up.z) < 0.9 ? norm(cross(vec(0, 0, 1), up)) : norm(cross(vec(1, 0, 0), up));
    v3 b = cross(up, t);
    for (int k = 0; k < 9; k++) {
        double el = k < 6 ? 0.0 : R_PI / 3.0;
        double az = k < 6 ? k * R_PI / 3.0 : (k - 6) * 2.0 * R_PI / 3.0 + R_PI / 6.0;
        v3 d = add(add(mul(t, cos(el) * cos(az)), mul(b, cos(el) * sin(az))), mul(up, sin(el)));
        flake_build(&f->child[k], add(c, mul(d, r * (1.0 + 1.0 / 3.0))), r / 3.0, d, depth - 1,
                    mat);
    }
    f->n_child = 9;
}

static void flake_free(flake_t *f)
{
    for (int k = 0; k < f->n_child; k++)
        flake_free(&f->child[k]);
    free(f->child);
}

typedef struct {
    double t;
    v3 p, n;
    int mat;
} hit_t;

static int hit_sphere(v3 c, double r, v3 o, v3 d, double tmax, double *t)
{
    v3 oc = sub(o, c);
    double b = dot(oc, d), cc = dot(oc, oc) - r * r, disc = b * b - cc;
    if (disc < 0.0)
        return 0;
    double sq = sqrt(disc), t0 = -b - sq;
    if (t0 > R_EPS && t0 < tmax) {
        *t = t0;
        return 1;
    }
    t0 = -b + sq;
    if (t0 > R_EPS && t0 < tmax) {
        *t = t0;
        return 1;
    }
    return 0;
}

static void flake_hit(const flake_t *f, v3 o, v3 d, hit_t *h)
{
    double t;
    if (!hit_sphere(f->c, f->bound, o, d, INFINITY, &t) && dot(sub(o, f->c), sub(o, f->c)) >
                                                              f->bound * f->bound)
        return;
    if (hit_sphere(f->c, f->r, o, d, h->t, &t)) {
        h->t = t;
        h->p = add(o, mul(d, t));
        h->n = norm(sub(h->p, f->c));
        h->mat = f->mat;
    }
    for (int k = 0; k < f->n_child; k++)
        flake_hit(&f->child[k], o, d, h);
}

static int intersect(const scene_t *s, v3 o, v3 d, hit_t *h)
{
    h->t = INFINITY;
    h->mat = -1;
    for (size_t i = 0; i < s->n_quad; i++) {
        const quad_t *q = &s->quad[i];
        double dn = dot(d, q->n);
        if (fabs(dn) < 1e-12)
            continue;
        double t = dot(sub(q->o, o), q->n) / dn;
        if (!(t > R_EPS && t < h->t))
            continue;
        v3 p = sub(add(o, mul(d, t)), q->o);
        /* coordinates in (u, v) */
        double uu = dot(q->u, q->u), uv = dot(q->u, q->v), vv = dot(q->v, q->v);
        double pu = dot(p, q->u), pv = dot(p, q->v), det = uu * vv - uv * uv;
        double a = (pu * vv - pv * uv) / det, b = (pv * uu - pu * uv) / det;
        if (a < 0.0 || a > 1.0 || b < 0.0 || b > 1.0)
            continue;
        h->t = t;
        h->p = add(o, mul(d, t));
        h->n = q->n;
        h->mat = q->mat;
    }
    for (size_t i = 0; i < s->n_sph; i++) {
        double t;
        if (hit_sphere(s->sph[i].c, s->sph[i].r, o, d, h->t, &t)) {
            h->t = t;
            h->p = add(o, mul(d, t));
            h->n = norm(sub(h->p, s->sph[i].c));
            h->mat = s->sph[i].mat;
        }
    }
    if (s->flake)
        flake_hit(s->flake, o, d, h);
    if (s->mesh.n_tri) {
        long k = bwh_mesh_hit(&s->mesh, (const double[3]){o.x, o.y, o.z},
                              (const double[3]){d.x, d.y, d.z}, R_EPS, &h->t);
        if (k >= 0) {
            const double *n = s->mesh.tri[k].n;
            h->p = add(o, mul(d, h->t));
            h->n = vec(n[0], n[1], n[2]);
            h->mat = s->mesh_mat;
        }
    }
    return h->mat >= 0;
}

/* ---- the path tracer --------------------------------------------------------- */

typedef struct {
    const scene_t *scene;
    enum strategy strat;
    int depth;
    int direct; /* sample the light at every hit, weighted by the power heuristic */
    unsigned w, h;
    uint64_t seed;
    double *sum; /* w * h * 3 */
    long pass;
    unsigned next_row;
    pthread_mutex_t lock;
    unsigned long long samples; /* strategy samples drawn (all threads) */
} job_t;

/* the strategy used at a hit on m: the diffuse walls, and payloads under
 * --sampling analytic, sample the cosine */
static enum strategy strategy_for(const job_t *j, const material_t *m)
{
    enum strategy st = j->strat;
    if (m->kind == MAT_DIFFUSE || (st == S_ANALYTIC && m->kind == MAT_DATA))
        st = S_COSINE;
    if (st == S_WAVELET && !m->has_sampler)
        st = S_COSINE;
    return st;
}

/* the density sample_dir draws wo with (local frame) */
static double strategy_pdf(const job_t *j, const material_t *m, const double wi[3],
                           const double wo[3])
{
    if (!(wo[2] > 0.0))
        return 0.0;
    switch (strategy_for(j, m)) {
    case S_UNIFORM:
        return 1.0 / (2.0 * R_PI);
    case S_COSINE:
        return wo[2] / R_PI;
    case S_ANALYTIC:
        return m->kind == MAT_PHONG ? bwh_phong_pdf(&m->p, wi, wo) : bwh_ward_pdf(&m->p, wi, wo);
    case S_WAVELET:
        return bwh_sampler_pdf(&m->sampler, wi, wo);
    }
    return 0.0;
}

/* one direction for the material at a hit; wo and pdf in the local frame.
 * 0: no direction (the path ends). */
static int sample_dir(const job_t *j, const material_t *m, const double wi[3], rng_t *r,
                      double wo[3], double *pdf)
{
    double u[3] = {rnd(r), rnd(r), rnd(r)};
    switch (strategy_for(j, m)) {
    case S_UNIFORM: {
        double z = u[0], rr = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * R_PI * u[1];
        wo[0] = rr * cos(phi);
        wo[1] = rr * sin(phi);
        wo[2] = z;
        *pdf = 1.0 / (2.0 * R_PI);
        return 1;
    }
    case S_COSINE:
        bwh_sample_cosine(u[0], u[1], wo);
        *pdf = wo[2] / R_PI;
        return wo[2] > 0.0;
    case S_ANALYTIC:
        if (m->kind == MAT_PHONG)
            bwh_phong_sample(&m->p, wi, u, wo);
        else
            bwh_ward_sample(&m->p, wi, u, wo);
        *pdf = strategy_pdf(j, m, wi, wo);
        return wo[2] > 0.0 && *pdf > 0.0;
    case S_WAVELET:
        if (bwh_sampler_sample(&m->sampler, wi, u, wo, pdf, NULL) != 0)
            return 0;
        return wo[2] > 0.0 && *pdf > 0.0;
    }
    return 0;
}

/* Veach's power heuristic (exponent 2): the weight of a strategy of density
 * p where another of density q could have drawn the same direction */
static double power_heuristic(double p, double q)
{
    return p * p / (p * p + q * q);
}

/* the density per solid angle with which a point drawn uniformly on the
 * light panel's area is seen from distance^2 d2 at cosine cl on the panel */
static double light_pdf(const scene_t *s, double d2, double cl)
{
    return d2 / (s->light_area * cl);
}

/* the origin of a ray leaving a surface at p on the side of its normal n */
static v3 leave(v3 p, v3 n) { return add(p, mul(n, 1e-5)); }

/* --direct mis: the light reflected at a hit p (shading frame n, t, b; wi
 * local) from one point drawn uniformly on the panel's area, if nothing is in
 * the way, weighted against the chance that the material's strategy draws
 * the same direction */
static v3 light_sample(const job_t *j, const material_t *m, v3 p, v3 n, v3 t, v3 b,
                       const double wi[3], rng_t *r)
{
    const scene_t *s = j->scene;
    const quad_t *lq = s->light;
    double su = rnd(r), sv = rnd(r);
    v3 to = sub(add(lq->o, add(mul(lq->u, su), mul(lq->v, sv))), p);
    double d2 = dot(to, to);
    v3 dl = mul(to, 1.0 / sqrt(d2));
    double cl = -dot(dl, lq->n), wl[3] = {dot(dl, t), dot(dl, b), dot(dl, n)};
    if (!(cl > 0.0 && wl[2] > 0.0))
        return vec(0, 0, 0);
    v3 f = mat_eval(m, wi, wl);
    if (!(f.x + f.y + f.z > 0.0))
        return vec(0, 0, 0);
    hit_t hs;
    if (!intersect(s, leave(p, n), dl, &hs) || hs.mat != MAT_LIGHT_ID)
        return vec(0, 0, 0);
    double pl = light_pdf(s, d2, cl);
    double w = power_heuristic(pl, strategy_pdf(j, m, wi, wl)) * wl[2] / pl;
    return mul(mulv(f, s->mat[MAT_LIGHT_ID].albedo), w);
}

static v3 trace(const job_t *j, v3 o, v3 d, rng_t *r, unsigned long long *n_samples)
{
    const scene_t *s = j->scene;
    v3 L = vec(0, 0, 0), beta = vec(1, 1, 1);
    double prev_pdf = 0.0; /* density of d from the last hit; 0: a camera ray */
    for (int bounce = 0; bounce <= j->depth; bounce++) {
        hit_t h;
        if (!intersect(s, o, d, &h))
            break;
        const material_t *m = &s->mat[h.mat];
        if (m->kind == MAT_LIGHT) {
            double cl = -dot(d, h.n); /* the panel emits on its front face only */
            if (cl > 0.0) {
                /* a direction drawn by the last hit's strategy: with --direct
                 * mis the light sample covers it too, so it takes its weight */
                double wgt = j->direct && prev_pdf > 0.0
                                 ? power_heuristic(prev_pdf, light_pdf(s, h.t * h.t, cl))
                                 : 1.0;
                L = add(L, mul(mulv(beta, m->albedo), wgt));
            }
            break;
        }
        if (bounce == j->depth)
            break;
        v3 n = dot(h.n, d) < 0.0 ? h.n : mul(h.n, -1.0);
        v3 t = fabs(n.z) < 0.9 ? norm(cross(vec(0, 0, 1), n)) : norm(cross(vec(1, 0, 0), n));
        v3 b = cross(n, t);
        v3 vdir = mul(d, -1.0);
        double wi[3] = {dot(vdir, t), dot(vdir, b), dot(vdir, n)}, wo[3], pdf;
        if (!(wi[2] > 0.0))
            break;
        if (j->direct)
            L = add(L, mulv(beta, light_sample(j, m, h.p, n, t, b, wi, r)));
        (*n_samples)++;
        if (!sample_dir(j, m, wi, r, wo, &pdf))
            break;
        prev_pdf = pdf;
        v3 f = mat_eval(m, wi, wo);
        double w = wo[2] / pdf;
        beta = mul(mulv(beta, f), w);
        if (!(beta.x + beta.y + beta.z > 0.0))
            break;
        d = norm(add(add(mul(t, wo[0]), mul(b, wo[1])), mul(n, wo[2])));
        o = leave(h.p, n);
    }
    return L;
}

static void *worker(void *arg)
{
    job_t *j = arg;
    const scene_t *s = j->scene;
    v3 fwd = norm(sub(s->look, s->eye)), right = norm(cross(fwd, s->up)), up = cross(right, fwd);
    double th = tan(0.5 * s->fov_deg * R_PI / 180.0), aspect = (double)j->w / j->h;
    unsigned long long n_samples = 0;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        unsigned y = j->next_row++;
        pthread_mutex_unlock(&j->lock);
        if (y >= j->h)
            break;
        for (unsigned x = 0; x < j->w; x++) {
            size_t px = (size_t)y * j->w + x;
            rng_t r = {splitmix(j->seed ^ splitmix(px * 0x100000001b3ull + (uint64_t)j->pass))};
            if (r.s == 0)
                r.s = 1;
            double sx = (2.0 * (x + rnd(&r)) / j->w - 1.0) * th * aspect;
            double sy = (1.0 - 2.0 * (y + rnd(&r)) / j->h) * th;
            v3 d = norm(add(fwd, add(mul(right, sx), mul(up, sy))));
            v3 L = trace(j, s->eye, d, &r, &n_samples);
            j->sum[3 * px] += L.x;
            j->sum[3 * px + 1] += L.y;
            j->sum[3 * px + 2] += L.z;
        }
    }
    pthread_mutex_lock(&j->lock);
    j->samples += n_samples;
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* ---- image ------------------------------------------------------------------ */

static double displayed(const double *rgb, double exposure)
{
    double v = exposure * (rgb[0] + rgb[1] + rgb[2]) / 3.0;
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

/* sec. 6.2: the mean over interior pixels of the variance over the 3 x 3
 * block (the pixel and its 8 neighbours) */
static double image_variance(const double *img, unsigned w, unsigned h, double exposure)
{
    double total = 0.0;
    size_t n = 0;
    for (unsigned y = 1; y + 1 < h; y++)
        for (unsigned x = 1; x + 1 < w; x++) {
            double s = 0.0, s2 = 0.0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    double v = displayed(img + 3 * ((size_t)(y + dy) * w + (x + dx)), exposure);
                    s += v;
                    s2 += v * v;
                }
            double mean = s / 9.0;
            total += s2 / 9.0 - mean * mean;
            n++;
        }
    return n ? total / (double)n : 0.0;
}

static uint8_t srgb8(double v)
{
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (uint8_t)lround(v * 255.0);
}

/* ---- options ------------------------------------------------------------------ */

static const char render_help[] =
    "usage: brdfwave render [--scene sphereflake|room] [--material SPEC]...\n"
    "                       [--sampling uniform|cosine|analytic|wavelet] [--level J]\n"
    "                       [--spp N | --time SECONDS] [--size WxH] [--threads T]\n"
    "                       [--depth D] [--direct off|mis] [--seed S] [--exposure E]\n"
    "                       -o OUT.png\n"
    "\n"
    "Path-traces a closed room with diffuse walls and a light panel under the\n"
    "ceiling, and writes a PNG. Objects take the --material options in order\n"
    "(repeated when fewer are given):\n"
    "  sphereflake  one sphereflake (91 spheres) on the floor\n"
    "  room         a table (box), a sphere, a torus (6,144 triangles) on the\n"
    "               table, a sphereflake\n"
    "\n"
    "  --material SPEC    phong:KD,KS,N       modified Phong (default phong:0.05,0.9,60)\n"
    "                     ward:KD,KS,AX,AY    Ward anisotropic\n"
    "                     payload:FILE.bwv    a decoded BRDF payload (isotropic or full,\n"
    "                                         1 band or 3 bands read as R, G, B), e.g.\n"
    "                                         from brdfwave import-rgl + encode\n"
    "  --sampling S[,S]   next direction at the material's hits: uniform hemisphere,\n"
    "                     cosine, the analytic lobe (Phong, Ward; cosine for\n"
    "                     payloads) or the wavelet hierarchy (default wavelet); a\n"
    "                     comma list renders each in turn, side by side in one PNG\n"
    "  --level J          level of accuracy of the hierarchy, 0..6 (default 4)\n"
    "  --tables N         incoming tables for analytic models: isotropic, every 90/N\n"
    "                     degrees from the normal (default 32); anisotropic Ward,\n"
    "                     one per incoming triangle, at least N (default: the grid\n"
    "                     level whose triangles are no wider than the lobe, up to\n"
    "                     1024 triangles)\n"
    "  --supersample S    leaf integrals from 4^S points per leaf, 0..3 (default 1)\n"
    "  --mix M            weight of the cosine lobe in the hierarchy's pdf (default 0.05)\n"
    "  --spp N            paths per pixel (default 16)\n"
    "  --time SECONDS     instead: passes of one path per pixel until the process has\n"
    "                     spent SECONDS of CPU time rendering (equal-time runs)\n"
    "  --size WxH         image size (default 160x120)\n"
    "  --threads T        worker threads (default: the online CPUs)\n"
    "  --depth D          bounces (default 5)\n"
    "  --direct off|mis   off (default): paths reach the light only along the\n"
    "                     strategies' directions, as in sec. 6.2; mis: at every hit\n"
    "                     also one point drawn on the light panel, both weighted by\n"
    "                     the power heuristic with the strategy's pdf (multiple\n"
    "                     importance sampling: the same mean, less noise)\n"
    "  --seed S           random seed (default 1); images do not depend on --threads\n"
    "  --exposure E       scale before display (default 1)\n"
    "  -o, --output FILE  the PNG\n"
    "\n"
    "Prints key: value lines: material (with tables, the incoming tables of its\n"
    "hierarchy), build_seconds (the sampling structures), then per\n"
    "strategy: sampling, spp, cpu_seconds, wall_seconds, samples (directions drawn),\n"
    "samples_per_second (per CPU second), radiance (mean over the image and the\n"
    "channels, unclamped: the same for every strategy up to noise), mean (displayed\n"
    "intensity), and\n"
    "variance: the image variance of sec. 6.2 (per pixel the variance over its\n"
    "3 x 3 block of displayed intensities, mean of R, G, B clamped to [0, 1];\n"
    "averaged over the interior pixels). A progress line goes to a terminal.\n";

/* comma-separated numbers in [0, 1e6]; exactly n of them */
static int number_list(const char *s, double *v, size_t n)
{
    size_t k;
    return cli_real_list(s, 0.0, 1e6, v, n, &k) != 0 || k != n ? -1 : 0;
}

typedef struct {
    uint32_t level, supersample;
    unsigned long tables;
    double mix;
} sampler_opts_t;

static int material_parse(material_t *m, const char *spec, const sampler_opts_t *so,
                          int want_sampler)
{
    memset(m, 0, sizeof *m);
    snprintf(m->spec, sizeof m->spec, "%s", spec);
    double v[4];
    if (!strncmp(spec, "phong:", 6)) {
        if (number_list(spec + 6, v, 3) != 0 || v[2] < 0.0)
            return cli_usage("--material phong:KD,KS,N needs three numbers >= 0");
        m->kind = MAT_PHONG;
        m->p.kd = v[0];
        m->p.ks = v[1];
        m->p.n = v[2];
    } else if (!strncmp(spec, "ward:", 5)) {
        if (number_list(spec + 5, v, 4) != 0 || !(v[2] > 0.0) || !(v[3] > 0.0))
            return cli_usage("--material ward:KD,KS,AX,AY needs four numbers, AX, AY > 0");
        m->kind = MAT_WARD;
        m->p.kd = v[0];
        m->p.ks = v[1];
        m->p.ax = v[2];
        m->p.ay = v[3];
    } else if (!strncmp(spec, "payload:", 8)) {
        if (bwh_brdf_data_load(&m->data, spec + 8) != 0)
            return cli_fail("%s", bwh_last_error());
        m->kind = MAT_DATA;
        if (m->data.shape == BW_SHAPE_REFLECTANCE) {
            bwh_brdf_data_free(&m->data);
            return cli_fail("%s: a reflectance, not a BRDF (needs --incoming or --level-in)",
                         spec + 8);
        }
        if (m->data.bands != 1 && m->data.bands != 3) {
            bwh_brdf_data_free(&m->data);
            return cli_fail("%s: %zu bands; render reads 1 band or 3 (R, G, B)", spec + 8,
                         m->data.bands);
        }
    } else {
        return cli_usage("unknown material '%s' (phong:..., ward:..., payload:FILE)", spec);
    }
    if (!want_sampler)
        return 0;
    int rc;
    if (m->kind == MAT_DATA) {
        const bwh_brdf_data_t *d = &m->data;
        rc = d->shape == BW_SHAPE_BRDF_ISO
                 ? bwh_sampler_build(&m->sampler, BWH_SAMPLER_ISO, so->level, d->n_in,
                                     d->theta_in, 0, bwh_brdf_data_mean_cb, &m->data,
                                     so->supersample, so->mix)
                 : bwh_sampler_build(&m->sampler, BWH_SAMPLER_FULL, so->level, d->n_in, NULL,
                                     d->level_in, bwh_brdf_data_mean_cb, &m->data,
                                     so->supersample, so->mix);
    } else if (m->kind == MAT_PHONG || m->p.ax == m->p.ay) {
        /* isotropic (Phong, Ward with AX = AY): tables over theta_i only,
         * turned to the hit's azimuth (sec. 5.2) */
        unsigned long n = so->tables ? so->tables : 32;
        double *th = malloc(n * sizeof *th);
        if (!th)
            return cli_fail("out of memory");
        for (unsigned long k = 0; k < n; k++)
            th[k] = k * 0.5 * R_PI / (double)n; /* from normal incidence */
        rc = bwh_sampler_build(&m->sampler, BWH_SAMPLER_ISO, so->level, n, th, 0, analytic_f,
                               m, so->supersample, so->mix);
        free(th);
    } else {
        /* anisotropic: one table per incoming triangle, at least --tables of
         * them; by default the level whose triangles (their width taken as
         * the square root of their solid angle, 2 pi / count) are at most
         * 1.6 x the narrower roughness, so that the lobe moves by less than
         * its width within one triangle */
        unsigned li = 0;
        double a = fmin(m->p.ax, m->p.ay);
        while (li < 4 && (so->tables ? bwh_grid_count(li) < so->tables
                                     : sqrt(2.0 * R_PI / (double)bwh_grid_count(li)) > 1.6 * a))
            li++;
        rc = bwh_sampler_build(&m->sampler, BWH_SAMPLER_FULL, so->level, bwh_grid_count(li), NULL,
                               li, analytic_f, m, so->supersample, so->mix);
    }
    if (rc != 0)
        return cli_fail("%s", bwh_last_error());
    m->has_sampler = 1;
    return 0;
}

static void material_free(material_t *m)
{
    if (m->kind == MAT_DATA)
        bwh_brdf_data_free(&m->data);
    if (m->has_sampler)
        bwh_sampler_free(&m->sampler);
}

/* --sampling S[,S...]: up to 4 strategies */
typedef struct {
    enum strategy s[4];
    int n;
} strategy_list_t;

static int parse_strategies(const char *v, void *dest)
{
    strategy_list_t *l = dest;
    char buf[128];
    if (strlen(v) >= sizeof buf)
        return -1;
    strcpy(buf, v);
    l->n = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k;
        for (k = 0; k < 4 && strcmp(tok, strategy_names[k]); k++)
            ;
        if (k == 4 || l->n == 4)
            return -1;
        l->s[l->n++] = (enum strategy)k;
    }
    return l->n ? 0 : -1;
}

/* --size WxH */
static int parse_size(const char *v, void *dest)
{
    uint32_t *wh = dest;
    return cli_size2(v, 3, 8192, &wh[0], &wh[1]);
}

int bw_cmd_render(int argc, char **argv)
{
    static const char *const scenes[] = {"sphereflake", "room", NULL};
    static const char *const direct_modes[] = {"off", "mis", NULL};
    const char *out = NULL, *mat_spec[MAX_MATERIALS];
    cli_list_t mats = {mat_spec, 0, MAX_MATERIALS};
    strategy_list_t sl = {{S_WAVELET}, 1};
    sampler_opts_t so = {4, 1, 0, 0.05}; /* tables 0: by the material */
    uint32_t spp = 16, size[2] = {160, 120}, depth = 5, threads = 0, seed32 = 1, tables = 0;
    double time_budget = 0.0, exposure = 1.0;
    int scene = 0, direct = 0;
    const cli_opt_t opts[] = {
        {"scene", 0, CLI_CHOICE, .dest = &scene, .choices = scenes},
        {"material", 0, CLI_LIST, .dest = &mats},
        {"sampling", 0, CLI_CALL, .dest = &sl, .parse = parse_strategies,
         .what = "--sampling needs uniform, cosine, analytic or wavelet (or up to 4 of them, "
                 "comma-separated)"},
        {"level", 0, CLI_U32, .dest = &so.level, .lo = 0, .hi = BWH_SAMPLER_MAX_LEVEL},
        {"tables", 0, CLI_U32, .dest = &tables, .lo = 1, .hi = 1024},
        {"supersample", 0, CLI_U32, .dest = &so.supersample, .lo = 0, .hi = BWH_SAMPLER_MAX_SUPERSAMPLE},
        {"mix", 0, CLI_REAL, .dest = &so.mix, .lo = 0, .hi = 1},
        {"spp", 0, CLI_U32, .dest = &spp, .lo = 1, .hi = MAX_SPP},
        {"time", 0, CLI_REAL, .dest = &time_budget, .lo = 1e-3, .hi = 1e6},
        {"size", 0, CLI_CALL, .dest = size, .parse = parse_size, .what = "--size needs WxH, 3..8192 each"},
        {"threads", 0, CLI_U32, .dest = &threads, .lo = 1, .hi = 256},
        {"depth", 0, CLI_U32, .dest = &depth, .lo = 1, .hi = 64},
        {"direct", 0, CLI_CHOICE, .dest = &direct, .choices = direct_modes},
        {"seed", 0, CLI_U32, .dest = &seed32, .lo = 0, .hi = UINT32_MAX},
        {"exposure", 0, CLI_REAL, .dest = &exposure, .lo = 1e-6, .hi = 1e6},
        {"output", 'o', CLI_STRING, .dest = &out},
        {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, render_help, &first, &st))
        return st;
    if (first < argc)
        return cli_usage("unexpected argument '%s'", argv[first]);
    so.tables = tables;
    const char *scene_name = scenes[scene];
    int n_spec = mats.n, n_strat = sl.n;
    enum strategy *strats = sl.s;
    unsigned w = size[0], h = size[1];
    uint64_t seed = seed32;
    if (!threads)
        threads = (uint32_t)sysconf(_SC_NPROCESSORS_ONLN);
    if (!out)
        return cli_usage("no output (-o OUT.png)");
    if (threads < 1)
        threads = 1;
    if (n_spec == 0)
        mat_spec[n_spec++] = "phong:0.05,0.9,60";

    scene_t sc;
    memset(&sc, 0, sizeof sc);
    sc.mat[MAT_WALL] = (material_t){.kind = MAT_DIFFUSE, .albedo = {0.7, 0.7, 0.7}};
    sc.mat[MAT_WALL_RED] = (material_t){.kind = MAT_DIFFUSE, .albedo = {0.7, 0.25, 0.2}};
    sc.mat[MAT_LIGHT_ID] = (material_t){.kind = MAT_LIGHT, .albedo = {1.5, 1.5, 1.5}};
    double t_build = wall_seconds();
    int want = 0;
    for (int k = 0; k < n_strat; k++)
        want |= strats[k] == S_WAVELET;
    for (int k = 0; k < n_spec; k++) {
        int rc = material_parse(&sc.mat[MAT_SLOT0 + k], mat_spec[k], &so, want);
        if (rc != 0) {
            for (int q = 0; q < k; q++)
                material_free(&sc.mat[MAT_SLOT0 + q]);
            return rc;
        }
    }
    t_build = wall_seconds() - t_build;
    sc.n_mat = MAT_SLOT0 + n_spec;
    size_t npx = (size_t)w * h, W = (size_t)w * n_strat;
    double *sum = calloc(npx * 3, sizeof *sum);
    uint8_t *rgb = malloc(npx * 3 * n_strat);
    pthread_t *tid = malloc((size_t)threads * sizeof *tid);
    int rc = 0;
    quad_t quads[7 + 6];
    sphere_t sph[1];
    flake_t root;
    sc.quad = quads;
    sc.sph = sph;
    add_room(&sc);
    sc.up = vec(0, 0, 1);
    sc.fov_deg = 55.0;
    if (!strcmp(scene_name, "sphereflake")) {
        flake_build(&root, vec(0, 0.2, 0.32), 0.32, vec(0, 0, 1), 2, MAT_SLOT0);
        sc.flake = &root;
        sc.eye = vec(0, -0.95, 1.1);
        sc.look = vec(0, 0.2, 0.4);
    } else {
        int m0 = MAT_SLOT0, m1 = MAT_SLOT0 + 1 % n_spec, m2 = MAT_SLOT0 + 2 % n_spec,
            m3 = MAT_SLOT0 + 3 % n_spec;
        add_box(&sc, vec(-0.85, 0.1, 0.0), vec(0.05, 0.85, 0.5), m0); /* table */
        sph[0] = (sphere_t){vec(0.5, 0.45, 0.38), 0.38, m1};
        sc.n_sph = 1;
        /* a torus of 6,144 triangles lying on the table */
        if (bwh_mesh_torus(&sc.mesh, (const double[3]){-0.38, 0.45, 0.56}, 0.17, 0.06, 96, 32) !=
            0) {
            rc = cli_fail("%s", bwh_last_error());
            goto done;
        }
        sc.mesh_mat = m2;
        flake_build(&root, vec(0.45, -0.25, 0.16), 0.16, vec(0, 0, 1), 2, m3);
        sc.flake = &root;
        sc.eye = vec(0, -0.97, 1.2);
        sc.look = vec(0, 0.3, 0.45);
    }

    if (!sum || !rgb || !tid) {
        rc = cli_fail("out of memory");
        goto done;
    }
    printf("scene: %s\n", scene_name);
    for (int k = 0; k < n_spec; k++) {
        const material_t *m = &sc.mat[MAT_SLOT0 + k];
        printf("material: %s\n", m->spec);
        if (m->has_sampler)
            printf("tables: %zu\n", m->sampler.n_tables);
    }
    printf("size: %ux%u\ndirect: %s\nbuild_seconds: %.3f\n", w, h, direct ? "mis" : "off",
           t_build);
    int tty = isatty(2);
    for (int si = 0; si < n_strat; si++) {
        enum strategy strat = strats[si];
        memset(sum, 0, npx * 3 * sizeof *sum);
        job_t job = {.scene = &sc, .strat = strat, .depth = (int)depth, .direct = direct,
                     .w = w, .h = h, .seed = splitmix(seed), .sum = sum};
        pthread_mutex_init(&job.lock, NULL);
        double c0 = cpu_seconds(), w0 = wall_seconds();
        long pass = 0;
        for (;;) {
            if (time_budget > 0.0 ? (pass > 0 && cpu_seconds() - c0 >= time_budget)
                                  : pass >= (long)spp)
                break;
            job.pass = pass;
            job.next_row = 0;
            long started = 0;
            for (long t = 0; t < threads; t++) {
                if (pthread_create(&tid[t], NULL, worker, &job) != 0)
                    break;
                started++;
            }
            if (started == 0)
                worker(&job);
            for (long t = 0; t < started; t++)
                pthread_join(tid[t], NULL);
            pass++;
            if (tty) {
                if (time_budget > 0.0)
                    fprintf(stderr, "\rrender %s: %ld spp, %.1f / %.1f s CPU ",
                            strategy_names[strat], pass, cpu_seconds() - c0, time_budget);
                else
                    fprintf(stderr, "\rrender %s: %ld / %u spp (%3.0f%%) ",
                            strategy_names[strat], pass, spp, 100.0 * pass / spp);
            }
        }
        if (tty)
            fputc('\n', stderr);
        double cpu = cpu_seconds() - c0, wall = wall_seconds() - w0;
        pthread_mutex_destroy(&job.lock);
        double mean = 0.0, radiance = 0.0;
        for (size_t i = 0; i < npx * 3; i++) {
            sum[i] /= (double)pass;
            radiance += sum[i];
        }
        for (size_t i = 0; i < npx; i++) {
            size_t y = i / w, x = i % w, o = 3 * (y * W + (size_t)si * w + x);
            for (int c = 0; c < 3; c++)
                rgb[o + c] = srgb8(exposure * sum[3 * i + c]);
            mean += displayed(sum + 3 * i, exposure);
        }
        /* one block of lines per strategy */
        printf("sampling: %s\n", strategy_names[strat]);
        if (strat == S_WAVELET)
            printf("level: %u\n", so.level);
        printf("spp: %ld\ncpu_seconds: %.3f\nwall_seconds: %.3f\nsamples: %llu\n"
               "samples_per_second: %.0f\nradiance: %.6f\nmean: %.6f\nvariance: %.6g\n",
               pass, cpu, wall, job.samples, cpu > 0 ? job.samples / cpu : 0.0,
               radiance / (3.0 * (double)npx), mean / (double)npx, image_variance(sum, w, h, exposure));
    }
    if (bw_png_write(out, rgb, (unsigned)W, h) != 0)
        rc = cli_fail("%s", bwh_last_error());
done:
    if (sc.flake)
        flake_free(sc.flake);
    bwh_mesh_free(&sc.mesh);
    for (int k = 0; k < n_spec; k++)
        material_free(&sc.mat[MAT_SLOT0 + k]);
    free(sum);
    free(rgb);
    free(tid);
    return rc;
}
