/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Interpolation of decoded samples (sec. 4.5), for evaluating a decoded BRDF
 * at any directions and wavelength (brdf_eval.h).
 *
 * Spectral axis: cubic B-spline interpolation (Unser, Aldroubi and Eden 1991;
 * Thevenaz, Blu and Unser 2000): the samples f_k on a uniform grid become
 * B-spline coefficients c_k (recursive prefilter, pole sqrt(3) - 2,
 * whole-sample mirror boundaries) so that s(x) = sum_k c_k beta3(x - k)
 * passes through every sample; s is C2.
 *
 * Sphere (values at the triangle centres of one geodesic level): every grid
 * vertex takes the solid-angle-weighted mean of the centre values of the
 * triangles around it; a triangle is split into three by its centre, and a
 * direction in the part (centre, v_a, v_b) is interpolated barycentrically
 * (coordinates of the gnomonic projection) between the centre value and the
 * two vertex values. Exact at the centres, continuous (C0) everywhere.
 *
 * The reference model has its own implementation (bwr_interp.h, on its own
 * grid); tests/ref/test_interp_vs_ref.c holds the two together.
 */
#ifndef BWH_INTERP_H
#define BWH_INTERP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* B-spline coefficients of n samples (in place allowed). */
void bwh_bspline_coefficients(const double *f, size_t n, double *c);
/* s(x) at x in sample units (0 = first sample, n - 1 = last; outside, the
 * mirror extension). */
double bwh_bspline_eval(const double *c, size_t n, double x);

typedef struct {
    unsigned level;
    size_t n;            /* triangles */
    size_t nv;           /* grid vertices */
    double (*centre)[3]; /* n */
    double (*vert)[3];   /* nv */
    uint32_t (*tv)[3];   /* vertex indices of every triangle */
    uint32_t *vt_start;  /* triangles around vertex v: vt[vt_start[v] .. vt_start[v + 1]),
                          * ascending */
    uint32_t *vt;
    double *area;        /* n solid angles */
} bwh_sphere_interp_t;

/* 0, or -1 (level > 6, out of memory; bwh_last_error()). */
int bwh_sphere_interp_init(bwh_sphere_interp_t *s, unsigned level);
void bwh_sphere_interp_free(bwh_sphere_interp_t *s);

/* The interpolated value at the unit direction d (z >= 0) of the n values
 * (grid order); NAN when d is not on the hemisphere. Read-only: any number
 * of threads may call it. */
double bwh_sphere_interp(const bwh_sphere_interp_t *s, const double *values, const double d[3]);
/* Where d falls: its triangle, the two grid vertices of the part of it
 * that holds d, and the barycentric weights of the centre and those two. */
typedef struct {
    uint32_t t, ia, ib;
    double w[3];
} bwh_sphere_at_t;
/* 0, or -1 when d is not on the hemisphere. */
int bwh_sphere_locate(const bwh_sphere_interp_t *s, const double d[3], bwh_sphere_at_t *at);
/* The interpolated value there of values (grid order), or of float values
 * with triangle t's at values[t * stride] (the decoder's [n_out][bands]
 * layout: stride = bands): bwh_sphere_interp's of the same values as
 * doubles, to the bit, located once for any number of value tables (the
 * bands of a spectrum). */
double bwh_sphere_value(const bwh_sphere_interp_t *s, const bwh_sphere_at_t *at,
                        const double *values);
double bwh_sphere_value_f32(const bwh_sphere_interp_t *s, const bwh_sphere_at_t *at,
                            const float *values, size_t stride);

#ifdef __cplusplus
}
#endif

#endif
