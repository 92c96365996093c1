/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The objects of sec. 4.2 as one dense model: a Signal with up to three
 * atomic transforms, applied as in the paper (analysis: incoming sphere,
 * outgoing sphere, spectral axis; synthesis in the reverse order), each
 * through the generic transforms of bwr_biohaar.h and bwr_dwt.h:
 *
 *   Spectrum               R -> R          1-D transform            (set of n_in)
 *   Reflectance            sphere -> R     Bio-Haar on reals
 *   Spectral Reflectance   sphere -> Spectrum   Bio-Haar on Spectrum vectors,
 *                                          then the 1-D transform of each vector
 *   BRDF                   sphere -> Reflectance  Bio-Haar on Reflectance
 *                                          objects, then on each of them
 *   Spectral BRDF          sphere -> Spectral Reflectance
 *
 * An isotropic BRDF keeps its N incoming directions (the plane phi = 0)
 * untransformed: only the outgoing hemisphere is transformed (sec. 5.2).
 * Optionally a 1-D transform runs across the n_in objects instead (its
 * elements are then whole Reflectance or Spectrum objects), for sets sampled
 * along one angle.
 *
 * Samples are laid out [incoming][outgoing][band] (grid order on each
 * sphere); coefficients [incoming][outgoing][spectral], coarse to fine on
 * each sphere and in wavedec order on the spectral axis.
 */
#ifndef BWR_MODEL_H
#define BWR_MODEL_H

#include <stddef.h>

#include "bwr_biohaar.h"
#include "bwr_dwt.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BWR_SPECTRUM = 0,             /* n_in spectra */
    BWR_REFLECTANCE,              /* one sphere, 1 band */
    BWR_SPECTRAL_REFLECTANCE,     /* one sphere, bands */
    BWR_BRDF,                     /* incoming x sphere, 1 band */
    BWR_SPECTRAL_BRDF             /* incoming x sphere, bands */
} bwr_kind_t;

typedef struct {
    bwr_kind_t kind;
    size_t n_in;          /* spectra: their number; reflectance: 1; BRDF: incoming directions */
    int level_in;         /* BRDF: incoming level (transformed), or -1: n_in directions kept */
    int level_out;        /* -1 for spectra */
    size_t bands;
    const bwr_filter_t *basis; /* spectral basis when bands > 1 */
    int spec_levels;      /* -1: the maximum (PyWavelets' dwt_max_level) */
    bwr_ext_t spec_ext;   /* extension of the 1-D transforms (spectral and across) */
    /* optional 1-D transform across the n_in objects when level_in < 0
     * (e.g. incidence angles of a multi-angle set); NULL: none */
    const bwr_filter_t *in_basis;
    int in_levels;        /* -1: the maximum */
} bwr_shape_t;

/* The objects of sec. 4.2. */
bwr_shape_t bwr_shape_spectra(size_t count, size_t bands, const bwr_filter_t *basis);
bwr_shape_t bwr_shape_reflectance(unsigned level);
bwr_shape_t bwr_shape_spectral_reflectance(unsigned level, size_t bands, const bwr_filter_t *basis);
bwr_shape_t bwr_shape_brdf(unsigned level_in, unsigned level_out);
bwr_shape_t bwr_shape_brdf_isotropic(size_t n_in, unsigned level_out);
bwr_shape_t bwr_shape_spectral_brdf(int level_in, size_t n_in, unsigned level_out, size_t bands,
                                    const bwr_filter_t *basis);

const char *bwr_kind_name(bwr_kind_t k);

typedef struct {
    bwr_shape_t shape;
    size_t n_in, n_out, bands;
    size_t ncoef_spec;   /* coefficients per spectrum (>= bands, see bwr_dwt.h) */
    size_t n_samples;    /* n_in * n_out * bands */
    size_t nci;          /* incoming coefficients: n_in, or the 1-D transform's count */
    size_t n_coefs;      /* nci * n_out * ncoef_spec */
    int have_in, have_in1d, have_out, have_spec;
    bwr_sphere_t sph_in, sph_out;
    bwr_dwt_plan_t dwt, dwt_in;
    double *in_psi2;     /* nci squared norms of the incoming basis functions (1 if none) */
    double *out_psi2;    /* n_out (1 if none) */
    double *spec_norm2;  /* ncoef_spec (1 if none) */
} bwr_model_t;

/* 0, or -1 on a bad shape or out of memory. */
int bwr_model_init(bwr_model_t *m, const bwr_shape_t *shape);
void bwr_model_free(bwr_model_t *m);

/* Coefficient (i, o, k) is coef[(i * n_out + o) * ncoef_spec + k], i < nci.
 * samples (n_samples) -> coef (n_coefs). 0, or -1 (out of memory). */
int bwr_model_forward(const bwr_model_t *m, const double *samples, double *coef);
/* coef (n_coefs) -> samples (n_samples). */
int bwr_model_inverse(const bwr_model_t *m, const double *coef, double *samples);

/* Squared norm of the synthesis function of coefficient (i, o, k). */
static inline double bwr_model_norm2(const bwr_model_t *m, size_t i, size_t o, size_t k)
{
    return m->in_psi2[i] * m->out_psi2[o] * m->spec_norm2[k];
}

#ifdef __cplusplus
}
#endif

#endif
