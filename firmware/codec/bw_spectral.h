/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Integer 1-D lifting on the spectral axis, any length.
 *
 * One level splits x[0..n) into its even samples s (ceil(n/2)) and odd
 * samples d (floor(n/2)) and stores them as [s | d]; further levels recurse on
 * s (Mallat order: approximation first, then details from coarse to fine).
 * Boundaries use whole-sample symmetric extension, which for lifting means
 * clamping the neighbour index into its subband. n = 1 is the identity.
 */
#ifndef BW_SPECTRAL_H
#define BW_SPECTRAL_H

#include <stddef.h>
#include <stdint.h>

#define BW_SPEC_MAX_LEVELS 12u

/* Decomposition depth used by the codec for a given number of bands: halve
 * while the approximation is longer than 4 samples, at most 12 times. */
unsigned bw_spec_levels(uint32_t bands);

/* Length of the approximation after `levels` levels. */
uint32_t bw_spec_approx_len(uint32_t n, unsigned levels);

/* One level, forward / inverse; tmp holds n elements. */
void bw_spec_fwd1(int32_t *x, uint32_t n, unsigned basis, int32_t *tmp);
void bw_spec_inv1(int32_t *x, uint32_t n, unsigned basis, int32_t *tmp);

/* `levels` levels, forward / inverse; tmp holds n elements. */
void bw_spec_fwd(int32_t *x, uint32_t n, unsigned basis, unsigned levels, int32_t *tmp);
void bw_spec_inv(int32_t *x, uint32_t n, unsigned basis, unsigned levels, int32_t *tmp);

/* A sample as the encoder's load takes it (bw_load.c): with q > 1 the
 * max-error prequantiser, (x + bias) / q - k in unsigned arithmetic, else
 * the sample itself. */
typedef struct {
    uint32_t q, k, bias;
} bw_prequant_t;

/* The load (pq) and the first level of each of `vectors` spectra of n
 * samples in one pass, from in into out (apart): the values bw_spec_fwd1
 * gives the loaded samples, for the 5/3 basis (n >= 3) or the 9/7 (n >= 4).
 * Returns the OR over the samples x of x ^ (x >> 31), the load's range
 * check (BW_CFG_FAST_LOADS). */
uint32_t bw_spec_fwd1_load(int32_t *out, const int32_t *in, size_t vectors, uint32_t n,
                           unsigned basis, const bw_prequant_t *pq);

/* Subband of coefficient k in Mallat order: 0 = approximation, l = 1..levels
 * the detail band of level l (1 = finest). */
unsigned bw_spec_subband(uint32_t n, unsigned levels, uint32_t k);

/* 1/sqrt(synthesis gain) of a subband as unsigned Q16: the factor that makes
 * a quantiser step give the same squared error in the sample domain whatever
 * the band. */
uint32_t bw_spec_inv_gain_q16(unsigned basis, unsigned levels, unsigned subband);

#endif
