/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Sampling throughput of the triangle hierarchy (bwh_sampler_sample: a
 * descent of O(level) steps) against a linear scan of the same leaves
 * (bwh_sampler_sample_linear: the O(n) running sum), same sampler, same
 * random numbers, one thread, CPU time; and, for scale, the analytic Phong
 * lobe sampler with its pdf (bwh_phong_sample + bwh_phong_pdf, what the
 * renderer calls per direction). Then, for a few incoming directions, the
 * relative variance of the path weight f cos / pdf that each sampler gives
 * (0 for a sampler exactly proportional to f cos). Used by
 * `make bench-render`.
 *
 *   bench_sampling LEVEL     prints key: value lines
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "brdf_models.h"
#include "bw_sample.h"
#include "test_rng.h"

static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static uint64_t st = 0x9e3779b97f4a7c15ull;
static double rnd(void) { return test_uniform(&st); }

static double phong(void *ctx, const double wi[3], const double wo[3])
{
    return bwh_brdf_phong(ctx, wi, wo);
}

enum method { TREE, SCAN, LOBE };

/* one direction for wi: 0 with wo and its pdf, or -1 */
static int draw(const bwh_sampler_t *s, const bwh_brdf_params_t *p, enum method how,
                const double wi[3], const double u[3], double wo[3], double *pdf)
{
    if (how == LOBE) {
        bwh_phong_sample(p, wi, u, wo);
        *pdf = bwh_phong_pdf(p, wi, wo);
        return *pdf > 0.0 ? 0 : -1;
    }
    return how == SCAN ? bwh_sampler_sample_linear(s, wi, u, wo, pdf, NULL)
                       : bwh_sampler_sample(s, wi, u, wo, pdf, NULL);
}

/* samples per CPU second over at least `min_seconds`: the hierarchy s by
 * its tree or its linear scan, or the analytic lobe of p */
static double rate(const bwh_sampler_t *s, const bwh_brdf_params_t *p, enum method how,
                   double min_seconds, double *check)
{
    long n = 0, batch = 1000;
    double t0 = cpu(), t, acc = 0.0;
    do {
        for (long i = 0; i < batch; i++) {
            double th = 1.4 * rnd(), ph = 6.283185307179586 * rnd();
            double wi[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
            double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf;
            if (draw(s, p, how, wi, u, wo, &pdf) == 0)
                acc += wo[2] / pdf;
        }
        n += batch;
        t = cpu() - t0;
    } while (t < min_seconds);
    *check = acc / (double)n;
    return (double)n / t;
}

/* relative variance Var(w) / E(w)^2 of the path weight w = f cos / pdf of
 * n draws for the incoming zenith angle th (0 for a sampler exactly
 * proportional to f cos), by the hierarchy s or the analytic lobe of p */
static double weight_relvar(const bwh_sampler_t *s, const bwh_brdf_params_t *p, enum method how,
                            double th, long n)
{
    double wi[3] = {sin(th), 0.0, cos(th)}, m = 0.0, m2 = 0.0;
    for (long i = 0; i < n; i++) {
        double u[3] = {rnd(), rnd(), rnd()}, wo[3], pdf = 0.0, w = 0.0;
        if (draw(s, p, how, wi, u, wo, &pdf) == 0 && wo[2] > 0.0 && pdf > 0.0)
            w = bwh_brdf_phong(p, wi, wo) * wo[2] / pdf;
        m += w;
        m2 += w * w;
    }
    m /= (double)n;
    return (m2 / (double)n - m * m) / (m * m);
}

int main(int argc, char **argv)
{
    unsigned level = argc > 1 ? (unsigned)atoi(argv[1]) : 6;
    bwh_brdf_params_t p = {.kd = 0.05, .ks = 0.9, .n = 60.0};
    double th[32];
    for (int k = 0; k < 32; k++)
        th[k] = k * 0.5 * 3.141592653589793 / 32.0;
    bwh_sampler_t s;
    if (bwh_sampler_build(&s, BWH_SAMPLER_ISO, level, 32, th, 0, phong, &p, 1, 0.05) != 0) {
        fprintf(stderr, "bench_sampling: cannot build the sampler at level %u\n", level);
        return 1;
    }
    double c1, c2, c3;
    double tree = rate(&s, &p, TREE, 1.0, &c1);
    double scan = rate(&s, &p, SCAN, 1.0, &c2);
    double lobe = rate(&s, &p, LOBE, 1.0, &c3);
    printf("level: %u\nleaves: %zu\ntree_samples_per_second: %.0f\n"
           "linear_samples_per_second: %.0f\nratio: %.2f\nanalytic_samples_per_second: %.0f\n",
           level, s.n_leaves, tree, scan, tree / scan, lobe);
    static const int deg[] = {0, 30, 60, 80};
    for (size_t i = 0; i < sizeof deg / sizeof *deg; i++) {
        double zen = deg[i] * 3.141592653589793 / 180.0;
        printf("weight_relvar_tree_%d: %.6g\nweight_relvar_analytic_%d: %.6g\n", deg[i],
               weight_relvar(&s, &p, TREE, zen, 400000), deg[i],
               weight_relvar(&s, &p, LOBE, zen, 400000));
    }
    bwh_sampler_free(&s);
    return 0;
}
