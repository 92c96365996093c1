/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The shape of a measurement from the options every tool takes
 * (--level L, --incoming N, --level-in Li, --bands B): `brdfwave encode`,
 * `synth`, `import-rgl` (also under bwref) and the Python package's encode
 * all turn them into dimensions here.
 *
 *   no level            a set of spectra [spectrum][band]
 *   level L             a spectral reflectance [outgoing][band]
 *   level L, incoming N an isotropic BRDF: N incoming directions in the plane
 *                       phi = 0 at theta_k = (k + 1/2) 90 / N degrees
 *   level L, level-in Li  a full BRDF: the incoming directions are the
 *                       triangle centres of level Li
 */
#ifndef BWH_SHAPE_H
#define BWH_SHAPE_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int level;         /* outgoing geodesic level 0..6; -1: none (a set of spectra) */
    int level_in;      /* incoming level 0..6 (a full BRDF); -1: none */
    uint32_t incoming; /* incoming directions, 1..BW_MAX_N_IN (an isotropic BRDF); 0: none */
    uint32_t bands;    /* bands per spectrum, 1..BW_MAX_BANDS */
} bwh_shape_t;

/* none of the options given (bands still to be set) */
#define BWH_SHAPE_INIT {-1, -1, 0, 0}

/* The options agree with each other and lie in range (the bands may still
 * be 0: known only from the input). 0, or -1 (bwh_last_error()). */
int bwh_shape_check(const bwh_shape_t *s);

/* The dimensions of the shape for an input of `count` samples (0: not known
 * yet; a set of spectra then needs it): a set of spectra has count / bands
 * of them, every other shape must need exactly count samples. 0, or -1. */
int bwh_shape_dims(const bwh_shape_t *s, size_t count, bw_dims_t *d);

/* The zenith angle (radians) of incoming direction k of n in an isotropic
 * set: (k + 1/2) 90 / n degrees. */
double bwh_shape_theta_in(size_t k, size_t n);

/* The d->n_in incoming directions of a BRDF's dimensions, unit vectors in
 * wi[n_in] (a reflectance: the normal). 0, or -1 (out of memory). */
int bwh_shape_incoming(const bw_dims_t *d, double (*wi)[3]);

#ifdef __cplusplus
}
#endif

#endif
