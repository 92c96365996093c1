/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Continuous reconstruction (sec. 4.5): the wavelet model gives the discrete
 * samples back; these interpolants turn them into functions.
 *
 * Spectral axis: cubic B-spline interpolation (Unser, Aldroubi and Eden 1991;
 * Thevenaz, Blu and Unser 2000): the samples f_k on a uniform grid are
 * turned into B-spline coefficients c_k (recursive prefilter, pole
 * sqrt(3) - 2, whole-sample mirror boundaries) so that
 * s(x) = sum_k c_k beta3(x - k) passes through every sample; s is C2.
 *
 * Sphere (values at the triangle centres of one geodesic level):
 *  - bwr_sinterp_linear: barycentric over neighbouring triangle centres.
 *    Each grid vertex gets the solid-angle-weighted mean of the centre values
 *    of the triangles around it; a triangle is split into three by its centre,
 *    and a direction in the part (centre, v_a, v_b) is interpolated
 *    barycentrically (coordinates of the gnomonic projection) between the
 *    centre value and the two vertex values. Exact at the centres, continuous
 *    (C0) everywhere: on an edge only its two vertices count. First-order
 *    accurate (the vertex value is a mean of its neighbours, one-sided at the
 *    horizon).
 *  - bwr_sinterp_smooth: C1, local modified Shepard (Franke and Little):
 *    f(d) = sum w_i f_i / sum w_i, w_i = ((R - r_i)_+ / (R r_i))^2 with r_i the
 *    geodesic angle from d to centre i and R twice the largest distance from
 *    a point to its triangle's centre; exact at the centres, C1 everywhere,
 *    constants reproduced exactly.
 */
#ifndef BWR_INTERP_H
#define BWR_INTERP_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* B-spline coefficients of n samples (in place allowed). */
void bwr_bspline_coefficients(const double *f, size_t n, double *c);
/* s(x) at x in sample units (0 = first sample, n - 1 = last; outside, the
 * mirror extension). */
double bwr_bspline_eval(const double *c, size_t n, double x);

typedef struct {
    unsigned level;
    size_t n;              /* triangles */
    size_t nv;             /* grid vertices */
    double (*centre)[3];   /* n */
    double (*vert)[3];     /* nv */
    size_t (*tv)[3];       /* vertex indices of every triangle */
    size_t *vt_start;      /* CSR: triangles around vertex v: vt[vt_start[v] .. vt_start[v+1]) */
    size_t *vt;
    double *area;          /* n solid angles */
    double radius;         /* R of the smooth scheme (radians) */
} bwr_sinterp_t;

/* 0, or -1 (level > 6, out of memory). */
int bwr_sinterp_init(bwr_sinterp_t *s, unsigned level);
void bwr_sinterp_free(bwr_sinterp_t *s);

/* Interpolated value at the unit direction d (z >= 0) of the n values
 * (grid order); NAN when d is not on the hemisphere. */
double bwr_sinterp_linear(const bwr_sinterp_t *s, const double *values, const double d[3]);
double bwr_sinterp_smooth(const bwr_sinterp_t *s, const double *values, const double d[3]);

#ifdef __cplusplus
}
#endif

#endif
