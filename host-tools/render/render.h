/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * `brdfwave render`: a small multithreaded path tracer comparing sampling
 * strategies (sec. 6.2). render_run builds the materials (render_material.h)
 * and the scene (render_scene.h), renders one image per strategy
 * (render_tracer.h), side by side in one PNG (render_png.h), and reports,
 * per strategy, the CPU time, samples per second and image variance
 * (render_image.h) as key: value lines.
 */
#ifndef RENDER_H
#define RENDER_H

#include <stdint.h>
#include <stdio.h>

#include "render_material.h"
#include "render_scene.h"
#include "render_tracer.h"

typedef struct {
    int scene;                                /* RENDER_SPHEREFLAKE or RENDER_ROOM */
    const render_material_spec_t *materials;  /* the objects', in turn */
    int n_materials;                          /* 1 .. RENDER_MAX_MATERIALS */
    enum strategy strategies[4];              /* rendered in turn, side by side */
    int n_strategies;
    render_sampler_opts_t sampler;            /* the wavelet hierarchy's */
    unsigned long spp;                        /* passes of one path per pixel, or */
    double time_budget;                       /* > 0: passes until this much CPU time */
    unsigned width, height, depth, threads;
    int direct;                               /* light samples, weighted (MIS) */
    uint64_t seed;
    double exposure;
    const char *output;                       /* the PNG */
    /* after every pass (may be NULL): what is rendered, and done of total
     * (passes, or CPU seconds of a time budget) */
    void (*progress)(void *ctx, const char *what, double done, double total);
    void *progress_ctx;
} render_opts_t;

/* Renders and writes the PNG, the key: value lines to `report`, and
 * tells o->progress how far it is. 0, or -1
 * (bwh_last_error(): a material that does not load, out of memory, the PNG
 * not written). */
int render_run(const render_opts_t *o, FILE *report);

#endif
