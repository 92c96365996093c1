/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Prediction (BW_BASIS_PRED, docs/FORMAT.md, Prediction): for sets of
 * spectra coded exactly or within a bound, in place of the prequantiser and
 * the transforms.
 *
 * Spectrum by spectrum, band by band, over the decoded samples r: sample k
 * of spectrum s is predicted as
 *   p = r[s][k-1] + round(sum_i w_i d_i / 2^16),
 *   d_0 = r[s][k-1] - r[s][k-2],    d_1 = r[s-1][k+1] - r[s-1][k],
 *   d_2 = r[s-1][k] - r[s-1][k-1],  d_3 = r[s][k-2] - r[s][k-3]
 * (a difference that needs a sample outside the spectra is 0; r[s][-1] is
 * r[s-1][0], and 0 for the very first sample), clamped to +-BW_SAMPLE_MAX.
 * The error x - p is quantised with the prequantiser D = 2E+1 (1: lossless),
 * q = sign(e) floor((|e| + E) / D), r = p + q D, so |r - x| <= E; q is
 * coded. The weights w (Q16, 0 at the start of every spectrum) then learn
 * from the decoded error for k >= 1 (a normalised LMS step):
 *   w_i += floor(PRED_MU e' d'_i / 2^floor(log2(D^2 + sum_j d'_j^2))),  e' = q D,
 * with e' and d' saturated to +-2^20, and w_i kept within +-2^18.
 *
 * Scaling and overflow: samples and predictions are within +-2^24 and the
 * decoded samples within E < 2^24 of the samples, so below 2^25; the
 * differences d_i are within +-2^26 (32 bits) and sum w_i d_i within
 * 4 * 2^18 * 2^26 = 2^46, formed in 64 bits; the update's product
 * e' d'_i PRED_MU is below 2^20 * 2^20 * 2^13 = 2^53. A corrupt payload may
 * decode to samples beyond that: the differences wrap (defined), and it
 * decodes to wrong samples. All of it is integer: encoder and decoder
 * predict alike.
 */
#include "bw_internal.h"

#define PRED_TAPS 4u
#define PRED_MU 6554 /* the LMS step, 0.1 in Q16 */
#define PRED_SAT (1 << 20)
#define PRED_W_MAX (1 << 18)

static inline int64_t sat64(int64_t v, int64_t m) { return v > m ? m : v < -m ? -m : v; }

typedef struct {
    int32_t w_q16[PRED_TAPS];
    int32_t d[PRED_TAPS];  /* the differences of the current sample */
    int32_t ds[PRED_TAPS]; /* the same saturated to +-PRED_SAT */
} pred_t;

static inline int32_t sat_d(int32_t d)
{
    return d > PRED_SAT ? PRED_SAT : d < -PRED_SAT ? -PRED_SAT : d;
}

/* The prediction of band k of spectrum cur (bands before k decoded), prev
 * the decoded previous spectrum (NULL for the first); sets pr->d and pr->ds.
 * d_3 and d_2 are the previous band's d_0 and d_1 (0 before band 1). The
 * decoded samples of a valid payload lie within +-2^25, their differences
 * within +-2^26: 32 bits (which wrap, defined, on a corrupt payload). */
static int32_t pred_value(pred_t *pr, const int32_t *cur, const int32_t *prev, uint32_t k,
                          uint32_t bands)
{
    pr->d[3] = pr->d[0];
    pr->d[2] = pr->d[1];
    pr->ds[3] = pr->ds[0];
    pr->ds[2] = pr->ds[1];
    pr->d[0] = k >= 2u ? bw_wsub(cur[k - 1], cur[k - 2]) : 0;
    pr->d[1] = prev && k + 1u < bands ? bw_wsub(prev[k + 1], prev[k]) : 0;
    pr->ds[0] = sat_d(pr->d[0]);
    pr->ds[1] = sat_d(pr->d[1]);
    int64_t acc = 0, a1 = k ? cur[k - 1] : prev ? prev[0] : 0;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        acc += (int64_t)pr->w_q16[i] * pr->d[i];
    return (int32_t)sat64(a1 + ((acc + 32768) >> 16), BW_SAMPLE_MAX);
}

/* The weights learn from the decoded error err of the current sample. */
static void pred_learn(pred_t *pr, int64_t err, uint32_t D)
{
    int32_t e = (int32_t)sat64(err, PRED_SAT);
    int64_t nrm = (int64_t)D * D;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        nrm += (int64_t)pr->ds[i] * pr->ds[i];
    /* divided by 2^floor(log2(nrm)) instead of nrm: no division */
    uint32_t hi = (uint32_t)((uint64_t)nrm >> 32);
    unsigned sh = hi ? 31u + bw_bitlen(hi) : bw_bitlen((uint32_t)nrm) - 1u;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        pr->w_q16[i] = (int32_t)sat64(
            pr->w_q16[i] + bw_asr64((int64_t)e * pr->ds[i] * PRED_MU, sh), PRED_W_MAX);
}

/* Encoder (forward) on range-checked samples x -> coded errors, in place,
 * the decoded spectra in two rows of `bands` (rows); decoder: coded errors
 * -> decoded samples, in place. */
BW_NOINLINE void bw_predict(const bw_plan_t *pl, int32_t *x, int32_t *rows, bool fwd)
{
    uint32_t bands = pl->dims.bands, D = pl->prequant, E = D / 2u;
    const int32_t *prev = NULL;
    for (size_t s = 0; s < pl->dims.n_in; s++) {
        int32_t *v = x + s * bands, *cur = fwd ? rows + (s & 1u) * bands : v;
        pred_t pr = {{0}, {0}, {0}};
        for (uint32_t k = 0; k < bands; k++) {
            int32_t p = pred_value(&pr, cur, prev, k, bands);
            int64_t q = v[k];
            if (fwd) { /* |x - p| < 2^25, E < 2^24: 32-bit division */
                int64_t e = q - p;
                uint32_t m = ((uint32_t)(e < 0 ? -e : e) + E) / D;
                q = e < 0 ? -(int64_t)m : (int64_t)m;
                v[k] = (int32_t)q;
            }
            cur[k] = (int32_t)(p + q * D);
            if (k)
                pred_learn(&pr, q * D, D);
        }
        prev = cur;
    }
}
