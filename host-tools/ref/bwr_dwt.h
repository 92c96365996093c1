/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Generic 1-D discrete wavelet transform (the Spectrum transform of sec. 4.2),
 * written once over an element type (bwr_type.h).
 *
 * Extension (PyWavelets' modes, coefficient for coefficient):
 *
 * BWR_EXT_PERIODIZATION, mode 'periodization' (non-redundant):
 * a level on m samples gives ceil(m/2) approximation and ceil(m/2) detail
 * coefficients, an odd m being first extended by a copy of its last sample;
 *   a[i] = sum_k dec_lo[k] x[(2i + F/2 - k) mod m'],  d[i] likewise with dec_hi.
 * The inverse is the dual (transposed) filter bank with rec_lo / rec_hi and
 * drops the extension sample, so it returns exactly the m input samples.
 * For even lengths the coefficient count equals the sample count; every odd
 * length on the way adds one coefficient.
 *
 * BWR_EXT_SYMMETRIC, mode 'symmetric' (half-sample symmetric extension
 * x[-1-k] = x[k], x[m+k] = x[m-1-k]; redundant, no boundary jump): a level
 * on m samples gives floor((m + F - 1)/2) coefficients in each band,
 *   a[i] = sum_k dec_lo[k] x_ext[2i + 1 - k];
 * the inverse y[n] = sum_i rec_lo[n + F - 2 - 2i] a[i] + rec_hi[...] d[i]
 * returns the first m samples, which are exact.
 *
 * Coefficients are stored in PyWavelets' wavedec order:
 *   [cA_J, cD_J, cD_{J-1}, ..., cD_1].
 */
#ifndef BWR_DWT_H
#define BWR_DWT_H

#include <stddef.h>

#include "bwr_filters.h"
#include "bwr_type.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_DWT_MAX_LEVELS 24

typedef enum { BWR_EXT_PERIODIZATION = 0, BWR_EXT_SYMMETRIC = 1 } bwr_ext_t;

typedef struct {
    const bwr_filter_t *f;
    bwr_ext_t mode;
    size_t maxlen;                        /* longest of len[] */
    size_t n;                             /* samples */
    unsigned levels;                      /* J */
    size_t len[BWR_DWT_MAX_LEVELS + 1];   /* len[0] = n, len[j]: the next subband length */
    size_t ncoef;                         /* len[J] + sum_{j=1..J} len[j] */
    size_t off[BWR_DWT_MAX_LEVELS + 1];   /* off[j]: start of cD_j; off[0]: cA_J (= 0) */
    double dec_hi[BWR_MAX_FILTER_LEN], rec_hi[BWR_MAX_FILTER_LEN];
} bwr_dwt_plan_t;

/* PyWavelets' dwt_max_level: floor(log2(n / (F - 1))), 0 if n < F - 1. */
unsigned bwr_dwt_max_level(size_t n, size_t filter_len);

/* levels = -1: PyWavelets' maximum level (bwr_dwt_max_level); BWR_DWT_DEEP:
 * as many levels as shorten the signal, down to 2 coefficients (periodization
 * stays exactly invertible when the filter is longer than the signal: the
 * filter then wraps around; symmetric stops when a level would not shorten).
 * 0, or -1 (bad filter or mode, n = 0, too many levels). */
#define BWR_DWT_DEEP (-2)
int bwr_dwt_plan_ext(bwr_dwt_plan_t *p, const bwr_filter_t *f, size_t n, int levels,
                     bwr_ext_t mode);
/* bwr_dwt_plan_ext with periodization. */
int bwr_dwt_plan(bwr_dwt_plan_t *p, const bwr_filter_t *f, size_t n, int levels);

/* in: p->n elements; out: p->ncoef elements (valid, distinct from in).
 * 0, or -1 when scratch memory runs out. */
int bwr_dwt_forward(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *in, void *out);
/* in: p->ncoef coefficients; out: p->n elements. */
int bwr_dwt_inverse(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *in, void *out);

/* One level on m elements: a and d receive the next length (p->len of the
 * following level) each. tmp: one valid scratch element. */
void bwr_dwt_step(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *x, size_t m, void *a,
                  void *d, void *tmp);
/* Inverse of one level: a, d of h elements each -> y of m elements (the
 * length before the level). ext: scratch of 2h valid elements. */
void bwr_idwt_step(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *a, const void *d,
                   size_t h, void *y, size_t m, void *ext, void *tmp);

/* Squared l2 norms of the synthesis functions, out[c] = |inverse(e_c)|^2,
 * one value per subband (that of its middle coefficient; exact for even
 * lengths, where every coefficient of a subband has the same norm; 1 for the
 * orthogonal bases). */
int bwr_dwt_synthesis_norms2(const bwr_dwt_plan_t *p, double *out);

#ifdef __cplusplus
}
#endif

#endif
