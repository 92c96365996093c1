/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Geodesic hemisphere grid in double precision (host side).
 *
 * Same numbering as firmware/codec/bw_geodesic.h: four base triangles of the
 * upper octahedron, child 0 the centre child, quadtree index so that every
 * subtree is a contiguous range, direction = normalize(a + b + c).
 */
#ifndef BWH_GEODESIC_H
#define BWH_GEODESIC_H

#include <math.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Small 3-vector helpers shared by the grid and the sampler. */
static inline double bwg_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void bwg_cross3(const double a[3], const double b[3], double out[3])
{
    double r0 = a[1] * b[2] - a[2] * b[1];
    double r1 = a[2] * b[0] - a[0] * b[2];
    double r2 = a[0] * b[1] - a[1] * b[0];
    out[0] = r0;
    out[1] = r1;
    out[2] = r2;
}

/* Scales v to unit length; leaves a zero vector alone. */
static inline void bwg_normalize3(double v[3])
{
    double n = sqrt(bwg_dot3(v, v));
    if (n > 0.0) {
        v[0] /= n;
        v[1] /= n;
        v[2] /= n;
    }
}

#define BWH_GRID_MAX_LEVEL 6u

/* Vertices (a, b, c) as unit vectors, counter-clockwise seen from outside. */
typedef struct {
    double v[3][3];
} bwh_tri_t;

/* 4 * 4^level triangles, or 0 if level > BWH_GRID_MAX_LEVEL. */
size_t bwh_grid_count(unsigned level);

/* Fills out[0 .. bwh_grid_count(level)-1] in index order. 0, or -1 on a bad
 * level or NULL out. */
int bwh_grid_triangles(unsigned level, bwh_tri_t *out);

/* Child m (0..3) of t, per the numbering convention. */
void bwh_tri_child(const bwh_tri_t *t, unsigned m, bwh_tri_t *child);

/* normalize(a + b + c). */
void bwh_tri_centre(const bwh_tri_t *t, double out[3]);

/* Solid angle of the spherical triangle with unit vertices a, b, c
 * (Van Oosterom-Strackee). */
double bwh_solid_angle(const double a[3], const double b[3], const double c[3]);

/* Centre and solid angle of every triangle in index order; solid_angle may
 * be NULL. 0, or -1 on a bad level or NULL xyz. */
int bwh_grid_centres(unsigned level, double (*xyz)[3], double *solid_angle);

/* The base triangle (0..3) holding dir by the half-open quadrants of (x, y);
 * the zenith (x = y = 0) goes to 0. */
unsigned bwh_grid_base(const double dir[3]);

/* The normals of the great circles through the edge midpoints of t that cut
 * off its corner children 1, 2 and 3: dir lies in child m (1..3) when the
 * first positive dot(dir, n[k]) is k = m - 1, in child 0 when none is
 * (bwh_cut_child). bwh_grid_locate descends with them. */
void bwh_tri_cut_normals(const bwh_tri_t *t, double n[3][3]);

/* The child (0..3) of the triangle with cutting normals n that holds dir. */
static inline unsigned bwh_cut_child(const double n[3][3], const double dir[3])
{
    /* 1 if past the first cut, else 2 if past the second, else 3 if past
     * the third, else 0; without branches (the child is data) */
    unsigned b0 = bwg_dot3(dir, n[0]) > 0.0, b1 = bwg_dot3(dir, n[1]) > 0.0,
             b2 = bwg_dot3(dir, n[2]) > 0.0;
    unsigned later = 2u * b1 + (1u - b1) * 3u * b2;
    return b0 + (1u - b0) * later;
}

/* Index at `level` of the triangle containing the unit direction dir
 * (z >= 0); -1 if z < 0, dir is not finite, or the level is bad. Points on a
 * shared edge go to a fixed side: bases by half-open quadrants of (x, y),
 * children to the centre child. */
long bwh_grid_locate(unsigned level, const double dir[3]);

#ifdef __cplusplus
}
#endif

#endif
