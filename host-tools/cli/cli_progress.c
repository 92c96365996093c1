/* SPDX-License-Identifier: BSD-2-Clause */
/* The progress line on a terminal (cli_progress.h). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, pthread_cond_timedwait */
#include "cli_progress.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_errors.h"

#define REDRAW_NS 200000000L /* at most 5 lines a second */

static struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    pthread_t thread;
    int running, stop;
    char text[160];
    double done, total;
    struct timespec t0;
    double delay;
    size_t shown; /* characters of the line on the terminal, 0: none */
} P = {.lock = PTHREAD_MUTEX_INITIALIZER, .wake = PTHREAD_COND_INITIALIZER};

static double since(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

int cli_progress_enabled(void) { return isatty(STDERR_FILENO); }

/* the line over the one before it; called with the lock held */
static void draw(double elapsed)
{
    char line[256];
    int n;
    if (P.total > 0)
        n = snprintf(line, sizeof line, "%s %s: %s %3.0f%% %5.1f s", cli_prog(), cli_cmd(), P.text,
                     100.0 * P.done / P.total, elapsed);
    else
        n = snprintf(line, sizeof line, "%s %s: %s %5.1f s", cli_prog(), cli_cmd(), P.text,
                     elapsed);
    if (n < 0)
        return;
    size_t len = strlen(line);
    fprintf(stderr, "\r%s", line);
    for (size_t k = len; k < P.shown; k++) /* what a longer line left */
        fputc(' ', stderr);
    fflush(stderr);
    P.shown = len > P.shown ? len : P.shown;
}

static void *ticker(void *arg)
{
    (void)arg;
    pthread_mutex_lock(&P.lock);
    while (!P.stop) {
        /* the first line once the delay has passed, then a redraw every
         * REDRAW_NS */
        double t = since(&P.t0);
        long wait_ns = t < P.delay && P.delay - t < REDRAW_NS * 1e-9
                           ? (long)((P.delay - t) * 1e9) + 1L
                           : REDRAW_NS;
        struct timespec until;
        clock_gettime(CLOCK_MONOTONIC, &until);
        until.tv_nsec += wait_ns;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&P.wake, &P.lock, &until);
        t = since(&P.t0);
        if (!P.stop && t >= P.delay)
            draw(t);
    }
    pthread_mutex_unlock(&P.lock);
    return NULL;
}

static void set_text(const char *fmt, va_list ap)
{
    vsnprintf(P.text, sizeof P.text, fmt, ap);
}

void cli_progress_start(const char *fmt, ...)
{
    cli_progress_end();
    if (!cli_progress_enabled())
        return;
    pthread_mutex_lock(&P.lock);
    va_list ap;
    va_start(ap, fmt);
    set_text(fmt, ap);
    va_end(ap);
    P.done = P.total = 0;
    P.shown = 0;
    P.stop = 0;
    const char *d = getenv("BRDFWAVE_PROGRESS_DELAY");
    P.delay = d && *d ? atof(d) : 1.0;
    clock_gettime(CLOCK_MONOTONIC, &P.t0);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_destroy(&P.wake);
    pthread_cond_init(&P.wake, &ca);
    pthread_condattr_destroy(&ca);
    P.running = pthread_create(&P.thread, NULL, ticker, NULL) == 0;
    pthread_mutex_unlock(&P.lock);
}

void cli_progress_text(const char *fmt, ...)
{
    if (!P.running)
        return;
    pthread_mutex_lock(&P.lock);
    va_list ap;
    va_start(ap, fmt);
    set_text(fmt, ap);
    va_end(ap);
    P.done = P.total = 0;
    pthread_mutex_unlock(&P.lock);
}

void cli_progress_set(double done, double total)
{
    if (!P.running)
        return;
    pthread_mutex_lock(&P.lock);
    P.done = done;
    P.total = total;
    pthread_mutex_unlock(&P.lock);
}

void cli_progress_end(void)
{
    if (!P.running)
        return;
    pthread_mutex_lock(&P.lock);
    P.stop = 1;
    pthread_cond_signal(&P.wake);
    pthread_mutex_unlock(&P.lock);
    pthread_join(P.thread, NULL);
    P.running = 0;
    if (P.shown) { /* the line's characters overwritten, the cursor back at its start */
        fputc('\r', stderr);
        for (size_t k = 0; k < P.shown; k++)
            fputc(' ', stderr);
        fputc('\r', stderr);
        fflush(stderr);
        P.shown = 0;
    }
}
