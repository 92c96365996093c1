/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Measurements at scattered directions onto the geodesic grid: the
 * reference model's projection (host-tools/ref/bwr_project.h: each
 * triangle takes the value at its centre by a local modified Shepard
 * interpolation over the 8 nearest measured directions), on the grid the
 * codec's directions share. For the goniometer, CSV and RGL readers.
 */
#ifndef BWH_PROJECT_H
#define BWH_PROJECT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* dir[n] unit directions (z >= 0), values[n][bands]; out[4*4^level][bands]
 * in grid order. 0, or -1 (bwh_last_error()). */
int bwh_project(const double (*dir)[3], const double *values, size_t n, size_t bands,
                unsigned level, double *out);

#ifdef __cplusplus
}
#endif

#endif
