/* SPDX-License-Identifier: BSD-2-Clause */
/* The path tracer (render_tracer.h). */
#include "render_tracer.h"

#include <math.h>

const char *const render_strategy_names[4] = {"uniform", "cosine", "analytic", "wavelet"};

/* the strategy used at a hit on m: the diffuse walls, and payloads under
 * --sampling analytic, sample the cosine */
static enum strategy strategy_for(const render_job_t *j, const material_t *m)
{
    enum strategy st = j->strat;
    if (m->kind == MAT_DIFFUSE || (st == S_ANALYTIC && m->kind == MAT_DATA))
        st = S_COSINE;
    if (st == S_WAVELET && !m->has_sampler)
        st = S_COSINE;
    return st;
}

/* the density sample_dir draws wo with (local frame) */
static double strategy_pdf(const render_job_t *j, const material_t *m, const double wi[3],
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
static int sample_dir(const render_job_t *j, const material_t *m, const double wi[3], rng_t *r,
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
static double light_pdf(const render_scene_t *s, double d2, double cl)
{
    return d2 / (s->light_area * cl);
}

/* the origin of a ray leaving a surface at p on the side of its normal n */
static v3 leave(v3 p, v3 n) { return add(p, mul(n, 1e-5)); }

/* --direct mis: the light reflected at a hit p (shading frame n, t, b; wi
 * local) from one point drawn uniformly on the panel's area, if nothing is in
 * the way, weighted against the chance that the material's strategy draws
 * the same direction */
static v3 light_sample(const render_job_t *j, const material_t *m, v3 p, v3 n, v3 t, v3 b,
                       const double wi[3], rng_t *r)
{
    const render_scene_t *s = j->scene;
    const quad_t *lq = s->light;
    double su = rnd(r), sv = rnd(r);
    v3 to = sub(add(lq->o, add(mul(lq->u, su), mul(lq->v, sv))), p);
    double d2 = dot(to, to);
    v3 dl = mul(to, 1.0 / sqrt(d2));
    double cl = -dot(dl, lq->n), wl[3] = {dot(dl, t), dot(dl, b), dot(dl, n)};
    if (!(cl > 0.0 && wl[2] > 0.0))
        return vec(0, 0, 0);
    v3 f = render_material_eval(m, wi, wl);
    if (!(f.x + f.y + f.z > 0.0))
        return vec(0, 0, 0);
    render_hit_t hs;
    if (!render_intersect(s, leave(p, n), dl, &hs) || hs.mat != MAT_LIGHT_ID)
        return vec(0, 0, 0);
    double pl = light_pdf(s, d2, cl);
    double w = power_heuristic(pl, strategy_pdf(j, m, wi, wl)) * wl[2] / pl;
    return mul(mulv(f, s->mat[MAT_LIGHT_ID].albedo), w);
}

static v3 trace(const render_job_t *j, v3 o, v3 d, rng_t *r, unsigned long long *n_samples)
{
    const render_scene_t *s = j->scene;
    v3 L = vec(0, 0, 0), beta = vec(1, 1, 1);
    double prev_pdf = 0.0; /* density of d from the last hit; 0: a camera ray */
    for (int bounce = 0; bounce <= j->depth; bounce++) {
        render_hit_t h;
        if (!render_intersect(s, o, d, &h))
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
        v3 f = render_material_eval(m, wi, wo);
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
    render_job_t *j = arg;
    const render_scene_t *s = j->scene;
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

void render_pass(render_job_t *j, long pass, unsigned threads, pthread_t *tid)
{
    j->pass = pass;
    j->next_row = 0;
    unsigned started = 0;
    for (unsigned t = 0; t < threads; t++) {
        if (pthread_create(&tid[t], NULL, worker, j) != 0)
            break;
        started++;
    }
    if (started == 0)
        worker(j);
    for (unsigned t = 0; t < started; t++)
        pthread_join(tid[t], NULL);
}
