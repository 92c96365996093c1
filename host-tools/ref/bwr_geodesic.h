/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The reference model's geodesic hemisphere, in double precision, computed
 * on its own: the model shares with the codec only the numbering convention
 * of the triangles, so that comparing the two checks the geometry as well.
 *
 * Convention (firmware/codec/bw_geodesic.h): four base triangles, base b =
 * (Z, R_b X, R_b Y) with R_b the rotation by b * 90 degrees about z; the
 * children of (a, b, c) with edge midpoints m_ab, m_bc, m_ca (normalised
 * a + b, ...) are 0 = (m_bc, m_ca, m_ab), 1 = (a, m_ab, m_ca),
 * 2 = (m_ab, b, m_bc), 3 = (m_ca, m_bc, c); index = 4 * parent + child, so
 * every subtree is a contiguous range; a triangle's direction is the
 * normalised sum of its vertices (in that order).
 *
 * Solid angles come from the arc lengths of the sides by L'Huilier's theorem,
 *   tan(E / 4) = sqrt(tan(s / 2) tan((s - a) / 2) tan((s - b) / 2) tan((s - c) / 2)),
 * s the half perimeter, where the codec's host grid (host-tools/lib/geodesic.c)
 * uses Van Oosterom and Strackee's formula of the vertex vectors: the two
 * agree to about 1e-13 of the area, and tests/ref/test_grid_vs_ref.c holds
 * them (and the codec's Q16 tables) to that.
 */
#ifndef BWR_GEODESIC_H
#define BWR_GEODESIC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_GRID_MAX_LEVEL 6u

/* the 3-vector products the reference model's geometry is written with */
static inline double bwr_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void bwr_cross3(const double a[3], const double b[3], double o[3])
{
    double r0 = a[1] * b[2] - a[2] * b[1], r1 = a[2] * b[0] - a[0] * b[2],
           r2 = a[0] * b[1] - a[1] * b[0];
    o[0] = r0;
    o[1] = r1;
    o[2] = r2;
}

/* Vertices (a, b, c) as unit vectors. */
typedef struct {
    double v[3][3];
} bwr_tri_t;

/* 4 * 4^level triangles, or 0 above BWR_GRID_MAX_LEVEL. */
size_t bwr_grid_count(unsigned level);

/* The triangles of one level in index order; 0, or -1 (bad level, NULL). */
int bwr_grid_triangles(unsigned level, bwr_tri_t *out);

/* The normalised sum of the vertices. */
void bwr_tri_direction(const bwr_tri_t *t, double out[3]);

/* Solid angle of the spherical triangle with unit vertices a, b, c
 * (L'Huilier). */
double bwr_tri_area(const double a[3], const double b[3], const double c[3]);

/* Direction and solid angle (may be NULL) of every triangle of one level in
 * index order; 0, or -1 (bad level, NULL xyz, out of memory). */
int bwr_grid_centres(unsigned level, double (*xyz)[3], double *area);

/* Index at `level` of a triangle that contains the unit direction d (z >= 0):
 * descending from the bases, the first child (in the order 0, 1, 2, 3) whose
 * three sides leave d inside; a point that rounding puts outside every child
 * goes to the one it is least outside of. -1 below the horizon, for a
 * direction that is not finite, or a bad level. */
long bwr_grid_locate(unsigned level, const double d[3]);

#ifdef __cplusplus
}
#endif

#endif
