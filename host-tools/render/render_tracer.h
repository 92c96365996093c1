/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The path tracer of `brdfwave render` (sec. 6.2, Tables 5 and 6). At every
 * hit on an object the next direction comes from the chosen strategy
 * (uniform hemisphere, cosine, the analytic lobe, or the wavelet hierarchy);
 * the diffuse walls always sample the cosine. Paths end on the light or
 * after `depth` bounces; the value carried is f cos / pdf with the BRDF's own
 * values (the sampling structure only picks directions). With `direct`
 * every hit also takes one sample of the light panel, and the two ways of
 * reaching the light are weighted by the power heuristic (Veach 1997) with
 * the strategy's pdf.
 */
#ifndef RENDER_TRACER_H
#define RENDER_TRACER_H

#include <pthread.h>
#include <stdint.h>

#include "render_scene.h"

enum strategy { S_UNIFORM, S_COSINE, S_ANALYTIC, S_WAVELET };
extern const char *const render_strategy_names[4];

typedef struct {
    const render_scene_t *scene;
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
} render_job_t;

/* One pass: a path through every pixel (its random numbers from the seed,
 * the pixel and the pass, so the image does not depend on the threads),
 * added to j->sum; rows are handed to `threads` threads (tid: room for
 * them), or done here if none starts. j->lock must be initialised. */
void render_pass(render_job_t *j, long pass, unsigned threads, pthread_t *tid);

#endif
