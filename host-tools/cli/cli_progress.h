/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * A progress line on standard error while a command works, only when
 * standard error is a terminal (never in a pipe or a file): it appears once
 * the work has taken a second ($BRDFWAVE_PROGRESS_DELAY seconds), is
 * redrawn at most 5 times a second by a thread of its own, so that work the
 * command cannot look into (one call into the codec) still shows the time
 * it takes, and is cleared when the work ends, leaving the terminal as it
 * was for the command's own lines.
 *
 *   cli_progress_start("encode: %zu samples", n);
 *   for (k = 0; k < n_steps; k++) { ...; cli_progress_set(k + 1, n_steps); }
 *   cli_progress_end();
 *
 * The line reads "brdfwave encode: 16777216 samples  45%  3.2 s" (the
 * fraction only when one was set).
 */
#ifndef CLI_PROGRESS_H
#define CLI_PROGRESS_H

#ifdef __cplusplus
extern "C" {
#endif

/* Starts the line with what the command does (printf format); a line
 * already running is ended first. */
__attribute__((format(printf, 1, 2))) void cli_progress_start(const char *fmt, ...);

/* What the command does now (a new stage of the same work). */
__attribute__((format(printf, 1, 2))) void cli_progress_text(const char *fmt, ...);

/* done of total (total 0: the fraction is not known). */
void cli_progress_set(double done, double total);

/* Clears the line (if it was shown) and stops its thread. Safe to call
 * when none is running. */
void cli_progress_end(void);

/* Whether a line would be shown: standard error is a terminal. */
int cli_progress_enabled(void);

#ifdef __cplusplus
}
#endif

#endif
