/* SPDX-License-Identifier: BSD-2-Clause */
/* `brdfwave render` from its options to the PNG and the report (render.h). */
#define _POSIX_C_SOURCE 200809L
#include "render.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bwh_error.h"
#include "render_image.h"
#include "render_png.h"

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

/* the objects' materials in s, with their hierarchies when a strategy needs
 * them */
static int make_materials(render_scene_t *s, const render_opts_t *o)
{
    int want = 0;
    for (int k = 0; k < o->n_strategies; k++)
        want |= o->strategies[k] == S_WAVELET;
    for (int k = 0; k < o->n_materials; k++)
        if (render_material_init(&s->mat[MAT_SLOT0 + k], &o->materials[k], &o->sampler, want) !=
            0) {
            for (int q = 0; q < k; q++)
                render_material_free(&s->mat[MAT_SLOT0 + q]);
            return -1;
        }
    return 0;
}

int render_run(const render_opts_t *o, FILE *report)
{
    render_scene_t sc;
    render_scene_init(&sc);
    double t_build = wall_seconds();
    if (make_materials(&sc, o) != 0)
        return -1;
    t_build = wall_seconds() - t_build;
    unsigned w = o->width, h = o->height, threads = o->threads ? o->threads : 1;
    int n_strat = o->n_strategies;
    size_t npx = (size_t)w * h, W = (size_t)w * n_strat;
    double *sum = calloc(npx * 3, sizeof *sum);
    uint8_t *rgb = malloc(npx * 3 * n_strat);
    pthread_t *tid = malloc((size_t)threads * sizeof *tid);
    int rc = 0;
    if (render_scene_build(&sc, o->scene, o->n_materials) != 0) {
        rc = -1;
        goto done;
    }
    if (!sum || !rgb || !tid) {
        rc = bwh_fail("out of memory");
        goto done;
    }
    fprintf(report, "scene: %s\n", o->scene == RENDER_ROOM ? "room" : "sphereflake");
    for (int k = 0; k < o->n_materials; k++) {
        const material_t *m = &sc.mat[MAT_SLOT0 + k];
        fprintf(report, "material: %s\n", m->spec);
        if (m->has_sampler)
            fprintf(report, "tables: %zu\n", m->sampler.n_tables);
    }
    fprintf(report, "size: %ux%u\ndirect: %s\nbuild_seconds: %.3f\n", w, h,
            o->direct ? "mis" : "off", t_build);
    for (int si = 0; si < n_strat; si++) {
        enum strategy strat = o->strategies[si];
        memset(sum, 0, npx * 3 * sizeof *sum);
        render_job_t job = {.scene = &sc, .strat = strat, .depth = (int)o->depth,
                            .direct = o->direct, .w = w, .h = h, .seed = splitmix(o->seed),
                            .sum = sum};
        pthread_mutex_init(&job.lock, NULL);
        double c0 = cpu_seconds(), w0 = wall_seconds();
        long pass = 0;
        for (;;) {
            if (o->time_budget > 0.0 ? (pass > 0 && cpu_seconds() - c0 >= o->time_budget)
                                     : pass >= (long)o->spp)
                break;
            render_pass(&job, pass, threads, tid);
            pass++;
            if (o->progress) {
                char what[64];
                snprintf(what, sizeof what, "%s (%d of %d), %ld spp", render_strategy_names[strat],
                         si + 1, n_strat, pass);
                if (o->time_budget > 0.0)
                    o->progress(o->progress_ctx, what, cpu_seconds() - c0, o->time_budget);
                else
                    o->progress(o->progress_ctx, what, (double)pass, (double)o->spp);
            }
        }
        double cpu = cpu_seconds() - c0, wall = wall_seconds() - w0;
        pthread_mutex_destroy(&job.lock);
        double mean = 0.0, radiance = 0.0;
        for (size_t i = 0; i < npx * 3; i++) {
            sum[i] /= (double)pass;
            radiance += sum[i];
        }
        for (size_t i = 0; i < npx; i++) {
            size_t y = i / w, x = i % w, off = 3 * (y * W + (size_t)si * w + x);
            for (int c = 0; c < 3; c++)
                rgb[off + c] = render_srgb8(o->exposure * sum[3 * i + c]);
            mean += render_displayed(sum + 3 * i, o->exposure);
        }
        /* one block of lines per strategy */
        fprintf(report, "sampling: %s\n", render_strategy_names[strat]);
        if (strat == S_WAVELET)
            fprintf(report, "level: %u\n", o->sampler.level);
        fprintf(report,
                "spp: %ld\ncpu_seconds: %.3f\nwall_seconds: %.3f\nsamples: %llu\n"
                "samples_per_second: %.0f\nradiance: %.6f\nmean: %.6f\nvariance: %.6g\n",
                pass, cpu, wall, job.samples, cpu > 0 ? job.samples / cpu : 0.0,
                radiance / (3.0 * (double)npx), mean / (double)npx,
                render_image_variance(sum, w, h, o->exposure));
    }
    if (render_png_write(o->output, rgb, (unsigned)W, h) != 0)
        rc = -1;
done:
    render_scene_free(&sc);
    for (int k = 0; k < o->n_materials; k++)
        render_material_free(&sc.mat[MAT_SLOT0 + k]);
    free(sum);
    free(rgb);
    free(tid);
    return rc;
}
