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
/* the largest |e| |ds| whose e ds PRED_MU is within 32 bits */
#define PRED_FAST_EDS (INT32_MAX / PRED_MU)
/* D^2 below this: the weights' steps in 32 bits (D <= 2^15) */
#define PRED_FAST_DD ((int64_t)1 << 30)

static inline int64_t sat64(int64_t v, int64_t m) { return v > m ? m : v < -m ? -m : v; }

static inline int32_t sat_d(int32_t d)
{
    return d > PRED_SAT ? PRED_SAT : d < -PRED_SAT ? -PRED_SAT : d;
}

/* w within +-PRED_W_MAX, |w| <= 2^30 + 2^18 (one unsigned comparison
 * finds both ends) */
static inline int32_t pred_clamp(int32_t w)
{
    if ((uint32_t)w + (uint32_t)PRED_W_MAX > 2u * (uint32_t)PRED_W_MAX)
        w = w < 0 ? -PRED_W_MAX : PRED_W_MAX;
    return w;
}

/* One weight's step: w + floor(e ds PRED_MU / 2^sh), kept within
 * +-PRED_W_MAX; |e|, |ds| <= 2^20. */
static inline int32_t pred_step(int32_t w, int32_t e, int32_t ds, unsigned sh)
{
    return (int32_t)sat64(w + bw_asr64((int64_t)e * ds * PRED_MU, sh), PRED_W_MAX);
}

/* floor(log2(nrm)), nrm >= 1 */
static inline unsigned log2_64(int64_t nrm)
{
    uint32_t hi = (uint32_t)((uint64_t)nrm >> 32);
    return hi ? 31u + bw_bitlen(hi) : bw_bitlen((uint32_t)nrm) - 1u;
}

typedef struct {
    int32_t w[PRED_TAPS];
} pred_w_t;

/* The weights learn from the decoded error err (the general form: every
 * bound of the header comment). */
static BW_NOINLINE void pred_learn(pred_w_t *pw, int64_t err, int64_t dd, int32_t d0, int32_t d1,
                                   int32_t d2, int32_t d3)
{
    int32_t e = (int32_t)sat64(err, PRED_SAT);
    int32_t ds[PRED_TAPS] = {sat_d(d0), sat_d(d1), sat_d(d2), sat_d(d3)};
    int64_t nrm = dd;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        nrm += (int64_t)ds[i] * ds[i];
    unsigned sh = log2_64(nrm);
    for (unsigned i = 0; i < PRED_TAPS; i++)
        pw->w[i] = pred_step(pw->w[i], e, ds[i], sh);
}

/* pred_learn on weights the caller holds in registers. */
static BW_ALWAYS_INLINE void pred_learn_regs(int32_t *w0, int32_t *w1, int32_t *w2, int32_t *w3,
                                             int64_t err, int64_t dd, int32_t d0, int32_t d1,
                                             int32_t d2, int32_t d3)
{
    pred_w_t pw = {{*w0, *w1, *w2, *w3}};
    pred_learn(&pw, err, dd, d0, d1, d2, d3);
    *w0 = pw.w[0];
    *w1 = pw.w[1];
    *w2 = pw.w[2];
    *w3 = pw.w[3];
}

/* The weights' step in 32 bits from the decoded error err (k >= 1) where
 * D^2 = dd < 2^30 and err fits 32 bits, given m = |d_0| | |d_1| | |d_2| |
 * |d_3|: where the error and the differences are small (the bounds below),
 * else pred_learn. Inline, the weights stay in the caller's registers. */
static BW_ALWAYS_INLINE void pred_weights32(int32_t *w0, int32_t *w1, int32_t *w2, int32_t *w3,
                                            int32_t err, uint32_t m, uint32_t dd, int32_t d0,
                                            int32_t d1, int32_t d2, int32_t d3)
{
    uint32_t ae = bw_abs32(err);
    if (BW_LIKELY(((m >> 14) | (ae >> 17)) == 0u && (ae | 1u) * (m | 1u) <= PRED_FAST_EDS)) {
        /* |d_i| < 2^14 and D^2 < 2^30: nrm < 2^31, and sh < 31 */
        uint32_t nrm = dd + (uint32_t)(d0 * d0) + (uint32_t)(d1 * d1) + (uint32_t)(d2 * d2) +
                       (uint32_t)(d3 * d3);
        unsigned sh = bw_bitlen(nrm) - 1u;
        int32_t em = err * PRED_MU;
        int32_t u0 = *w0 + ((em * d0) >> sh), u1 = *w1 + ((em * d1) >> sh);
        int32_t u2 = *w2 + ((em * d2) >> sh), u3 = *w3 + ((em * d3) >> sh);
        const uint32_t B = (uint32_t)PRED_W_MAX;
        /* all four within +-PRED_W_MAX: each of w + B below 2 B (B a power
         * of two: their OR too), else each kept within */
        if (BW_LIKELY((((uint32_t)u0 + B) | ((uint32_t)u1 + B) | ((uint32_t)u2 + B) |
                       ((uint32_t)u3 + B)) < 2u * B)) {
            *w0 = u0;
            *w1 = u1;
            *w2 = u2;
            *w3 = u3;
        } else {
            *w0 = pred_clamp(u0);
            *w1 = pred_clamp(u1);
            *w2 = pred_clamp(u2);
            *w3 = pred_clamp(u3);
        }
    } else {
        pred_learn_regs(w0, w1, w2, w3, err, dd, d0, d1, d2, d3);
    }
}

/* The weights' step from the decoded error err (k >= 1), given m = |d_0| |
 * |d_1| | |d_2| | |d_3|: pred_weights32 where D^2 and err allow it
 * (BW_CFG_FAST_PREDICT), else pred_learn. */
static BW_ALWAYS_INLINE void pred_weights(int32_t *w0, int32_t *w1, int32_t *w2, int32_t *w3,
                                          int64_t err, uint32_t m, int64_t dd, int32_t d0,
                                          int32_t d1, int32_t d2, int32_t d3)
{
    if (BW_CFG_FAST_PREDICT && BW_LIKELY(dd < PRED_FAST_DD && err == (int32_t)err))
        pred_weights32(w0, w1, w2, w3, (int32_t)err, m, (uint32_t)dd, d0, d1, d2, d3);
    else
        pred_learn_regs(w0, w1, w2, w3, err, dd, d0, d1, d2, d3);
}

/* One spectrum, either way (fwd a constant where it is inlined): v the
 * samples (encoder: replaced by the coded errors) or the coded errors
 * (decoder: replaced by the decoded samples), cur where the decoded
 * samples go (the decoder: v), prev the previous spectrum's (NULL: none).
 * Where the error and the differences are small (|d_i| < 2^14, |err| <
 * 2^17, |err| |d_i| <= PRED_FAST_EDS, D^2 < 2^30: so every d_i and err
 * within +-PRED_SAT) the step is taken in 32 bits: nrm < 2^31, e d_i
 * PRED_MU fits, and so does the weight plus its step (sh 0: every d_i 0). */
#if BW_CFG_FAST_PREDICT
#define PRED_SPECTRUM_INLINE BW_ALWAYS_INLINE
#else
#define PRED_SPECTRUM_INLINE BW_NOINLINE
#endif
static PRED_SPECTRUM_INLINE void pred_spectrum(int32_t *v, int32_t *cur, const int32_t *prev,
                                           uint32_t bands, uint32_t D, int64_t dd, bool fwd)
{
    int32_t w0 = 0, w1 = 0, w2 = 0, w3 = 0; /* in registers: pred_learn gets a copy */
    int32_t d0 = 0, d1 = 0;
    int32_t a1 = prev ? prev[0] : 0; /* r[k-1] */
    for (uint32_t k = 0; k < bands; k++) {
        int32_t d3 = d0, d2 = d1;
        d0 = k >= 2u ? bw_wsub(a1, cur[k - 2]) : 0;
        d1 = prev && k + 1u < bands ? bw_wsub(prev[k + 1], prev[k]) : 0;
        int64_t acc = (int64_t)w0 * d0 + (int64_t)w1 * d1 + (int64_t)w2 * d2 + (int64_t)w3 * d3;
        int32_t p = (int32_t)sat64(a1 + ((acc + 32768) >> 16), BW_SAMPLE_MAX);
        int32_t q = v[k];
        if (fwd) { /* |x - p| < 2^25, E < 2^24: 32-bit division */
            int32_t e = q - p;
            uint32_t m = (bw_abs32(e) + D / 2u) / D;
            q = e < 0 ? -(int32_t)m : (int32_t)m;
            v[k] = q;
        }
        int64_t err = (int64_t)q * (int32_t)D; /* D < 2^25 */
        a1 = cur[k] = bw_wadd(p, (int32_t)err);
        if (!k)
            continue;
        uint32_t m = bw_abs32(d0) | bw_abs32(d1) | bw_abs32(d2) | bw_abs32(d3);
        pred_weights(&w0, &w1, &w2, &w3, err, m, dd, d0, d1, d2, d3);
    }
}

#if BW_CFG_FAST_PREDICT
/* The encoder's state between samples: the weights, the last two new
 * differences d_0 and d_1, and r[k-1]. */
typedef struct {
    int32_t w0, w1, w2, w3, d0, d1, a1;
    uint32_t m; /* |d_0| | |d_1| */
} pred_enc_t;

/* pred_spectrum's step for one sample of the encoder, the new differences
 * given (d0, d1): the same values. The encoder's decoded samples are within
 * E < 2^24 of samples within +-2^24, so r[k-1] + round(acc / 2^16)
 * (|acc| <= 2^46) and the error e' = q D (|e'| <= |x - p| + D / 2) fit 32
 * bits. lossless: D = 1, q = x - p. learn: k >= 1. */
static BW_ALWAYS_INLINE void pred_enc_step(pred_enc_t *st, int32_t *vk, int32_t *ck, int32_t d0,
                                           int32_t d1, uint32_t D, int64_t dd, bool lossless,
                                           bool small, bool learn)
{
    int32_t d3 = st->d0, d2 = st->d1;
    uint32_t m23 = st->m; /* |d_2| | |d_3|, found for the sample before */
    st->d0 = d0;
    st->d1 = d1;
    st->m = bw_abs32(d0) | bw_abs32(d1);
    int64_t acc = (int64_t)st->w0 * d0 + (int64_t)st->w1 * d1 + (int64_t)st->w2 * d2 +
                  (int64_t)st->w3 * d3;
    int32_t p = st->a1 + (int32_t)((acc + 32768) >> 16);
    if (!BW_LIKELY((uint32_t)p + (uint32_t)BW_SAMPLE_MAX <= 2u * (uint32_t)BW_SAMPLE_MAX))
        p = p < 0 ? -BW_SAMPLE_MAX : BW_SAMPLE_MAX;
    int32_t e = *vk - p, err;
    if (lossless) {
        err = e;
    } else {
        uint32_t m = (bw_abs32(e) + D / 2u) / D;
        int32_t q = e < 0 ? -(int32_t)m : (int32_t)m;
        err = q * (int32_t)D;
        e = q;
    }
    *vk = e;
    st->a1 = *ck = p + err;
    if (!learn)
        return;
    if (small)
        pred_weights32(&st->w0, &st->w1, &st->w2, &st->w3, err, st->m | m23, (uint32_t)dd, d0,
                       d1, d2, d3);
    else
        pred_weights(&st->w0, &st->w1, &st->w2, &st->w3, err, st->m | m23, dd, d0, d1, d2, d3);
}

/* pred_spectrum forward, the first two samples and the last apart (their
 * differences need samples outside the spectrum), one copy for each of
 * has_prev (prev not NULL), lossless (D = 1) and small (D^2 < 2^30: the
 * weights' step in 32 bits where the values allow it). */
static BW_ALWAYS_INLINE void pred_encode(int32_t *v, int32_t *cur, const int32_t *prev,
                                         uint32_t bands, uint32_t D, int64_t dd, bool has_prev,
                                         bool lossless, bool small)
{
    pred_enc_t st = {0, 0, 0, 0, 0, 0, has_prev ? prev[0] : 0, 0};
    for (uint32_t k = 0; k < bands && k < 2u; k++)
        pred_enc_step(&st, v + k, cur + k, k >= 2u ? bw_wsub(st.a1, cur[k - 2]) : 0,
                      has_prev && k + 1u < bands ? bw_wsub(prev[k + 1], prev[k]) : 0, D, dd,
                      lossless, small, k != 0u);
    uint32_t k = 2;
    for (; k + 1u < bands; k++)
        pred_enc_step(&st, v + k, cur + k, bw_wsub(st.a1, cur[k - 2]),
                      has_prev ? bw_wsub(prev[k + 1], prev[k]) : 0, D, dd, lossless, small, true);
    if (k < bands) /* the last sample: no k + 1 */
        pred_enc_step(&st, v + k, cur + k, bw_wsub(st.a1, cur[k - 2]), 0, D, dd, lossless, small,
                      true);
}
#endif

/* Encoder (forward) on range-checked samples x -> coded errors, in place,
 * the decoded spectra in two rows of `bands` (rows); decoder: coded errors
 * -> decoded samples, in place. The decoded samples of a valid payload lie
 * within +-2^25, their differences within +-2^26: 32 bits (which wrap,
 * defined, on a corrupt payload). */
BW_NOINLINE void bw_predict(const bw_plan_t *pl, int32_t *x, int32_t *rows, bool fwd)
{
    uint32_t bands = pl->dims.bands, D = pl->prequant;
    int64_t dd = (int64_t)D * D;
    const int32_t *prev = NULL;
    for (size_t s = 0; s < pl->dims.n_in; s++) {
        int32_t *v = x + s * bands, *cur = fwd ? rows + (s & 1u) * bands : v;
#if BW_CFG_FAST_PREDICT
        if (fwd && prev && D == 1u)
            pred_encode(v, cur, prev, bands, D, dd, true, true, true);
        else if (fwd && prev && dd < PRED_FAST_DD)
            pred_encode(v, cur, prev, bands, D, dd, true, false, true);
        else if (fwd && prev)
            pred_encode(v, cur, prev, bands, D, dd, true, false, false);
        else if (fwd)
            pred_encode(v, cur, prev, bands, D, dd, false, D == 1u, dd < PRED_FAST_DD);
        else
            pred_spectrum(v, cur, prev, bands, D, dd, false);
#else
        pred_spectrum(v, cur, prev, bands, D, dd, fwd);
#endif
        /* a segment's first spectrum has none before it */
        prev = BW_CFG_SEGMENTS && pl->seg_vec && (s + 1u) % pl->seg_vec == 0u ? NULL : cur;
    }
}
