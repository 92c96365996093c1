/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Projection of scattered measured directions onto the geodesic grid
 * (sec. 5: the goniometer's 474 measured directions are projected on the
 * 1024 triangles of level 4; a triangle's value is the value at its centre).
 *
 * Scheme: each triangle takes the value interpolated at its centre c by the
 * local modified Shepard method (Franke and Little 1980; Renka 1988) over
 * the k measured directions nearest to c by geodesic angle r_i:
 *     v(c) = sum_i w_i v_i / sum_i w_i,   w_i = ((R - r_i)_+ / (R r_i))^2,
 * with R the angle to the (k+1)-th nearest measurement (so a measurement's
 * weight falls continuously to 0 as it leaves the neighbourhood), or twice
 * the largest angle when there are at most k measurements. Properties:
 *  - a measurement at the centre itself (r < 1e-12 rad) is taken as is
 *    (the mean of coincident ones);
 *  - the result is a convex combination of the neighbours' values, so it
 *    stays within their range, and a constant field is reproduced exactly
 *    (computed as v_1 + sum w_i (v_i - v_1) / sum w_i, v_1 the nearest);
 *  - if every neighbour is exactly R away (ties) they count equally.
 * The weights depend on the directions only: a measurement may carry a
 * vector of `bands` values (a spectrum), all projected with the same weights.
 */
#ifndef BWR_PROJECT_H
#define BWR_PROJECT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_PROJECT_K_DEFAULT 8u
#define BWR_PROJECT_K_MAX 64u

/* dir: n unit directions (z >= 0; normalised here, so any positive length
 * will do); values: n * bands, row-major [direction][band]; out:
 * bwr_grid_count(level) * bands, [triangle][band] in grid order. k: number
 * of neighbours, 1..BWR_PROJECT_K_MAX (0: BWR_PROJECT_K_DEFAULT).
 * 0, or -1 (n = 0, bands = 0, level > 6, k too large, a direction not finite,
 * of zero length or below the horizon (z < -1e-9), a value not finite, out
 * of memory). */
int bwr_project(const double (*dir)[3], const double *values, size_t n, size_t bands,
                unsigned level, unsigned k, double *out);

/* Unit direction of spherical angles in degrees (theta from the normal z,
 * phi from x towards y). */
void bwr_dir_from_degrees(double theta_deg, double phi_deg, double d[3]);

#ifdef __cplusplus
}
#endif

#endif
