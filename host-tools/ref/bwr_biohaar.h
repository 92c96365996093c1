/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Spherical Bio-Haar wavelets on the geodesic hemisphere, in double precision
 * (Schroeder and Sweldens 1995, as used in sec. 3.1 and 4 of the paper),
 * written once over an element type (bwr_type.h).
 *
 * Grid and numbering: bwr_geodesic.h (4 base triangles of the
 * upper octahedron, children 0 = centre, 1..3 = corners, index = base * 4^L
 * + child digits). A signal at level L is one element per triangle, in that
 * order.
 *
 * For a parent P with children i = 0..3 of solid angles a_i,
 * L_i = a_i / a_P (a_P = sum a_i, the children tile the parent):
 *   analysis   d_m = s_m - s_0  (m = 1..3, relative to the centre child),
 *              s_P = sum_i L_i s_i = s_0 + sum_m L_m d_m;
 *   synthesis  s_0 = s_P - sum_m L_m d_m,  s_m = s_0 + d_m.
 * The scaling functions are the indicator functions of the triangles (s is
 * the area-weighted mean) and the wavelet of d_m is
 *   psi_m = 1_{T_m} - L_m 1_{T_P},  |psi_m|^2 = a_m (1 - L_m)  (in sr),
 * which has zero integral: wavelets of different parents are orthogonal in
 * L2(H^2, d omega); the three of one parent are not (<psi_m, psi_k> =
 * -a_m a_k / a_P). This is the Bio-Haar basis of Schroeder and Sweldens up to
 * a factor 2 in the detail coefficients (their dual wavelet is
 * (phi_m - phi_0) / 2).
 *
 * Coefficients are stored coarse to fine: [0, 4) the base scaling
 * coefficients, then for each level j = 0..L-1 the 12 * 4^j details at
 * [4 * 4^j, 16 * 4^j): detail m of parent p at 4 * 4^j + 3p + m - 1.
 */
#ifndef BWR_BIOHAAR_H
#define BWR_BIOHAAR_H

#include <stddef.h>

#include "bwr_type.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_SPHERE_MAX_LEVEL 6u

typedef struct {
    unsigned level;
    size_t n;          /* 4 * 4^level triangles = coefficients */
    double *weight;    /* L_i of parent p at level j: weight[4 * (parents before level j + p) + i] */
    double *area;      /* solid angle of triangle t at level j: area[4 * (4^j - 1) / 3 + t] */
    double *psi2;      /* squared norm of the basis function of every coefficient, coarse to fine */
    int *coef_level;   /* -1 for the scaling coefficients, else the level j of the parent */
} bwr_sphere_t;

/* 0, or -1 (level > 6 or out of memory). */
int bwr_sphere_init(bwr_sphere_t *s, unsigned level);
void bwr_sphere_free(bwr_sphere_t *s);

/* Solid angle of triangle t at level j (j <= s->level). */
double bwr_sphere_area(const bwr_sphere_t *s, unsigned j, size_t t);

/* in: s->n elements in grid order; out: s->n coefficients, coarse to fine.
 * in and out must not overlap. 0, or -1 when scratch memory runs out. */
int bwr_biohaar_forward(const bwr_sphere_t *s, const bwr_type_t *t, const void *in, void *out);
int bwr_biohaar_inverse(const bwr_sphere_t *s, const bwr_type_t *t, const void *in, void *out);

/* Number of coefficients (and first index) of the details of level j. */
static inline size_t bwr_sphere_level_start(unsigned j)
{
    return (size_t)4 << (2u * j);
}

#ifdef __cplusplus
}
#endif

#endif
