/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The last error of the library: every failing bwh_* call leaves one line
 * of text here (per thread) and returns -1; the tools print it.
 */
#ifndef BWH_ERROR_H
#define BWH_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

/* Error text of the last failing bwh_* call (thread-local). */
const char *bwh_last_error(void);

/* Sets bwh_last_error() (printf format; the message may quote the last
 * one); returns -1. */
__attribute__((format(printf, 1, 2))) int bwh_fail(const char *fmt, ...);

#ifdef __cplusplus
}
#endif

#endif
