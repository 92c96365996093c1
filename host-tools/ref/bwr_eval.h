/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Evaluation of a sampled (or decoded) BRDF at any incoming and outgoing
 * direction and wavelength (sec. 4.5): the interpolants of bwr_interp.h on
 * each axis of the generic model.
 *
 *   outgoing   sphere interpolation over the outgoing triangle centres
 *   incoming   full BRDF: sphere interpolation over the incoming centres of
 *              the values interpolated at the outgoing direction; isotropic
 *              BRDF (N incoming directions in the plane phi = 0): both
 *              directions are turned about the normal until phi_i = 0 (the
 *              azimuthal rotation of sec. 5.2), then linear in theta_i
 *              between the two nearest incoming directions (clamped at the
 *              ends); reflectance: no incoming dependence
 *   spectral   cubic B-spline over the bands, on a uniform wavelength grid
 *              from lambda_first to lambda_last
 */
#ifndef BWR_EVAL_H
#define BWR_EVAL_H

#include <stddef.h>

#include "bwr_interp.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { BWR_EVAL_REFLECTANCE = 1, BWR_EVAL_ISO = 2, BWR_EVAL_FULL = 3 };

typedef struct {
    int shape;               /* BWR_EVAL_* (the codec's shape numbers) */
    unsigned level_out, level_in;
    size_t n_in, n_out, bands;
    double lambda_first, lambda_last; /* wavelengths of the first and last band */
    int smooth;              /* 1: the C1 sphere scheme, 0: barycentric */
    double *theta_in;        /* ISO: the incoming zenith angles, radians, ascending */
    double *planes;          /* [n_in][bands][n_out] */
    bwr_sinterp_t s_out, s_in;
    double *tmp_in;          /* n_in */
    double *tmp_band;        /* bands */
} bwr_brdf_t;

/*
 * values: [n_in][n_out][bands] in the codec's layout and grid order.
 * theta_in_deg (ISO only, may be NULL): the incoming zenith angles in
 * degrees, ascending; NULL means (k + 0.5) * 90 / N, as brdfwave synth.
 * Returns 0, or -1 on bad arguments or memory.
 */
int bwr_brdf_init(bwr_brdf_t *b, int shape, unsigned level_out, unsigned level_in, size_t n_in,
                  size_t bands, const float *values, const double *theta_in_deg,
                  double lambda_first, double lambda_last, int smooth);
void bwr_brdf_free(bwr_brdf_t *b);

/* f(wi, wo, lambda); wi and wo unit vectors pointing away from the surface
 * (z >= 0); NAN below the horizon. */
double bwr_brdf_eval(bwr_brdf_t *b, const double wi[3], const double wo[3], double lambda);

#ifdef __cplusplus
}
#endif

#endif
