/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * A sampled or decoded BRDF as a function (libbrdfwave): f(wi, wo, lambda)
 * at any directions and wavelength, with the interpolants of sec. 4.5
 * (bwh_interp.h):
 *
 *   outgoing   barycentric interpolation over the outgoing triangle centres
 *   incoming   isotropic (N directions in the plane phi = 0): both directions
 *              turned about the normal until phi_i = 0 (sec. 5.2), then
 *              linear in theta_i between the two nearest tables (clamped at
 *              the ends); full BRDF: the incoming triangle that contains wi
 *              (nearest, no interpolation across incoming triangles);
 *              reflectance: no incoming dependence
 *   spectral   cubic B-spline over the bands on a uniform wavelength grid
 *
 * It keeps no scratch memory in the object: a loaded BRDF is read-only and
 * can be evaluated from any number of threads.
 */
#ifndef BW_BRDF_EVAL_H
#define BW_BRDF_EVAL_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"
#include "bwh_interp.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int shape;                 /* BW_SHAPE_REFLECTANCE, _BRDF_ISO or _BRDF_FULL */
    unsigned level_out, level_in;
    size_t n_in, n_out, bands;
    double lambda_first, lambda_last;
    double *theta_in;          /* ISO: radians, ascending */
    double *planes;            /* [rows][bands][n_out] */
    double *mean;              /* [rows][n_out]: the mean over the bands (one band:
                                * planes itself) */
    bwh_sphere_interp_t s_out;
    uint32_t *row_of;          /* NULL: rows = n_in; else [n_in], the row of planes
                                * that holds incoming direction i (UINT32_MAX: not
                                * decoded: f is NAN there) */
} bwh_brdf_data_t;

/* values: [n_in][n_out][bands], the codec's layout. theta_in_deg (ISO, may be
 * NULL: (k + 1/2) 90 / N as brdfwave synth and import-rgl --incoming N).
 * 0, or -1 (bwh_last_error()). */
int bwh_brdf_data_init(bwh_brdf_data_t *d, const bw_dims_t *dims, const float *values,
                       const double *theta_in_deg, double lambda_first, double lambda_last);
/* Decodes a payload file and initialises d from it, with the incidence
 * angles and the wavelength range its metadata carries (docs/FORMAT.md,
 * Metadata; the measured angles of an RGL file, for one), else the
 * defaults above. */
int bwh_brdf_data_load(bwh_brdf_data_t *d, const char *path);
/* The same from a payload in memory, decoding only the incoming directions
 * that f at the incoming directions wi[n] reads (wi NULL: all): a full
 * BRDF's triangle holding each, an isotropic BRDF's two incidences about
 * each (bwh_decode_rows: with segments, only the segments that hold them);
 * a payload whose rows depend on each other (the reciprocity step, a float
 * tail), or more than half of whose rows are read, is decoded whole. f at
 * another incoming direction is NAN where its rows were not decoded. */
int bwh_brdf_data_from_payload(bwh_brdf_data_t *d, const uint8_t *p, size_t len,
                               const double (*wi)[3], size_t n);
/* f at n direction pairs (unit vectors wi[3 n], wo[3 n]): at lambda[j]
 * (bwh_brdf_data_eval), of band `band` >= 0, or the mean over the bands
 * with neither: out[n]. 0, or -1 (a band past the last). */
int bwh_brdf_data_eval_many(const bwh_brdf_data_t *d, size_t n, const double *wi,
                            const double *wo, const double *lambda, long band, double *out);
/* f at n direction pairs (unit vectors wi[3 n], wo[3 n]) straight from a
 * payload: the rows bwh_brdf_data_from_payload decodes for the wi, then
 * the values of bwh_brdf_data_eval_many, to the bit, read from the decoded
 * float values themselves (no tables of doubles but the band mean's with
 * more than one band). 0, or -1. */
int bwh_payload_eval(const uint8_t *p, size_t len, size_t n, const double *wi, const double *wo,
                     const double *lambda, long band, double *out);
void bwh_brdf_data_free(bwh_brdf_data_t *d);

/* Band k at (wi, wo), interpolated over the directions. NAN below the
 * horizon. */
double bwh_brdf_data_band(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                          size_t k);
/* The mean over the bands (the BRDF integrated over wavelength, divided by
 * the range) at (wi, wo). */
double bwh_brdf_data_mean(const bwh_brdf_data_t *d, const double wi[3], const double wo[3]);
/* f at wavelength lambda: the B-spline through the bands; work holds
 * `bands` doubles. */
double bwh_brdf_data_eval(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                          double lambda, double *work);

/* For bwh_sampler_build: ctx is a bwh_brdf_data_t, f its band mean. */
double bwh_brdf_data_mean_cb(void *ctx, const double wi[3], const double wo[3]);

/* For bwh_sampler_build, one channel: ctx is a bwh_brdf_band_t, f band
 * `band` of `data` (NAN, which the sampler counts as 0, for a band out of
 * range). */
typedef struct {
    const bwh_brdf_data_t *data;
    size_t band;
} bwh_brdf_band_t;
double bwh_brdf_data_band_cb(void *ctx, const double wi[3], const double wo[3]);

#ifdef __cplusplus
}
#endif

#endif
