/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Compression of the dense model (sec. 4.1, 4.3) and the error metrics of
 * sec. 5 (eq. 7, 8).
 *
 * Thresholds per space, coarse space first: a coefficient's magnitude is
 * normalised by the norm of its synthesis function (bwr_model_norm2), so that
 * magnitudes on different spheres, levels and subbands compare as L2 energy.
 *   1. incoming sphere (full BRDF): a coefficient is a whole (spectral)
 *      Reflectance object; dropped when its normalised norm is below eps_in;
 *   2. outgoing sphere (when there is a spectral axis): a coefficient is a
 *      Spectrum vector; dropped when its normalised norm is below eps_vec;
 *   3. elements: a real coefficient is dropped when its normalised magnitude
 *      is below eps_elem, or, with keep > 0, all but the `keep` largest
 *      survivors are dropped (ties broken by index).
 * With raw = 1 the magnitudes are compared as they are (the plain threshold
 * on coefficient values).
 */
#ifndef BWR_COMPRESS_H
#define BWR_COMPRESS_H

#include <stddef.h>

#include "bwr_model.h"
#include "bwr_sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double eps_in;
    double eps_vec;
    double eps_elem;
    size_t keep; /* > 0: number of real coefficients to keep */
    int raw;     /* 1: compare raw |c| (no normalisation by the basis norms) */
    int keep_coarse; /* 1: the coefficients that are scaling coefficients in every
                      * transformed space are never dropped by step 3 */
    int per_in;      /* 1: keep is shared equally among the incoming objects (each
                      * of the nci blocks keeps keep / nci): objects compressed
                      * one by one, e.g. a set of unrelated spectra */
} bwr_thresholds_t;

typedef struct {
    size_t kept;          /* non-zero coefficients left */
    size_t in_dropped;    /* incoming objects dropped by eps_in */
    size_t vec_dropped;   /* vectors dropped by eps_vec */
    double eps_elem;      /* the element threshold applied */
} bwr_compress_info_t;

/* out = compressed copy of coef (n_coefs each; may be the same array).
 * info may be NULL. 0, or -1 (out of memory). */
int bwr_compress(const bwr_model_t *m, const double *coef, const bwr_thresholds_t *th, double *out,
                 bwr_compress_info_t *info);

typedef struct {
    size_t n;
    size_t zero_ref;   /* reference samples equal to 0, left out of rel_l1, rel_l2 */
    double rel_l1;     /* percent, eq. 7 */
    double rel_l2;     /* percent, eq. 8 */
    double rmse;
    double max_abs;
} bwr_error_t;

void bwr_error(const double *ref, const double *test, size_t n, bwr_error_t *e);

/* Best spectral basis by relative L2 error (eq. 8) after compression with th:
 * the model of `shape` is built with every candidate basis in turn. *best is
 * an index into cand; err (optional, ncand entries) receives the errors in
 * percent. 0, or -1 (bad shape, out of memory). */
int bwr_best_basis(const bwr_shape_t *shape, const double *samples, const bwr_thresholds_t *th,
                   const bwr_filter_t *const *cand, size_t ncand, size_t *best, double *err);

/* Memory of a coefficient set stored as sparse strip arrays (bwr_sparse.h),
 * value_bytes per value:
 *   flat    one sparse array over all n_coefs coefficients in storage order;
 *   nested  the paper's objects: a sparse array over the incoming directions
 *           (when n_in > 1) of sparse spheres over the outgoing directions
 *           (when there is a sphere) of sparse spectra; an element of an
 *           outer array is valid when its inner object is not empty, and the
 *           strips of all arrays are added up. */
void bwr_coef_memory(const bwr_model_t *m, const double *coef, size_t value_bytes,
                     bwr_memory_t *flat, bwr_memory_t *nested);

/* The same for the uncompressed samples (every sample a valid value). */
void bwr_sample_memory(const bwr_model_t *m, size_t value_bytes, bwr_memory_t *flat,
                       bwr_memory_t *nested);


#ifdef __cplusplus
}
#endif

#endif
