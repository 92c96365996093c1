/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Loads: the caller's samples into the work array, range-checked and
 * prequantised (MAX_ERROR: q = 2E + 1), and for the Haar basis the first
 * spectral levels on the way (BW_CFG_FAST_LOADS).
 */
#include "bw_internal.h"

/* The range check: the OR over the samples of x ^ (x >> 31) (x for x >= 0,
 * |x| - 1 below) is below 2^24 exactly when every sample lies in
 * [-2^24, 2^24 - 1], two instructions a sample. Of those only -2^24 is
 * outside +-BW_SAMPLE_MAX; it sets all 24 low bits of the OR, so only an OR
 * of 2^24 - 1 makes range_status look for it. */
#define RANGE_BITS 24u
_Static_assert(BW_SAMPLE_MAX == (1 << RANGE_BITS) - 1, "the range check needs 2^24 - 1");

static inline uint32_t range_mag(int32_t x) { return (uint32_t)(x ^ bw_asr32(x, 31)); }

static bw_status_t range_status(uint32_t acc, const int32_t *in, size_t n)
{
    if (acc >> RANGE_BITS)
        return BW_ERR_RANGE;
    if (acc == (1u << RANGE_BITS) - 1u)
        for (size_t i = 0; i < n; i++)
            if (in[i] == -BW_SAMPLE_MAX - 1)
                return BW_ERR_RANGE;
    return BW_OK;
}

/* The max-error prequantiser q = 2E + 1 (1: none) of valid samples,
 * floor((x + E) / q), the nearest multiple of q, error <= E: as
 * (x + bias) / q - k in unsigned arithmetic (x + bias >= 0 for every
 * valid x; |x| <= 2^24 and q <= 2^25 + 1: x + bias fits 32 bits). */
static inline bw_prequant_t prequant_of(uint32_t q)
{
    bw_prequant_t pq;
    pq.q = q;
    pq.k = (uint32_t)BW_SAMPLE_MAX / q + 1u;
    pq.bias = (q - 1u) / 2u + pq.k * q;
    return pq;
}

/* (x + bias) / q: the prequantised sample plus k */
static inline uint32_t prequant_k(int32_t x, const bw_prequant_t *pq)
{
    return ((uint32_t)x + pq->bias) / pq->q;
}

/* A sample as the loads take it: prequantised plus k, or (pre false, no
 * prequantiser) itself; the loads subtract koff(pq, pre) where k stays. */
static BW_ALWAYS_INLINE uint32_t load_k(int32_t x, const bw_prequant_t *pq, bool pre)
{
    return pre ? prequant_k(x, pq) : (uint32_t)x;
}
static BW_ALWAYS_INLINE uint32_t koff(const bw_prequant_t *pq, bool pre) { return pre ? pq->k : 0u; }

/* The loops below are written once and called with pre constant: with the
 * prequantiser, and without it (q = 1: no division). Each returns the OR of
 * the range check (range_status). */
static BW_ALWAYS_INLINE uint32_t load_pass(int32_t *out, const int32_t *in, size_t n,
                                           const bw_prequant_t *pq, bool pre)
{
    uint32_t acc = 0;
    BW_UNROLL8
    for (size_t i = 0; i < n; i++) {
        int32_t x = in[i];
        acc |= range_mag(x);
        out[i] = (int32_t)(load_k(x, pq, pre) - koff(pq, pre));
    }
    return acc;
}

/* The load and the first level of the Haar lifting (bw_spectral.c,
 * fwd_haar) in one pass: from the caller's samples the approximation and
 * the details go straight to their places in out, with no scratch. Same
 * values (the k of the prequantiser cancels in the details). */
static BW_ALWAYS_INLINE uint32_t haar1_pass(const bw_plan_t *pl, int32_t *o, const int32_t *x,
                                            const bw_prequant_t *pq, bool pre)
{
    size_t vectors = (size_t)pl->dims.n_in * pl->dims.n_out;
    uint32_t b = pl->dims.bands, ns = (b + 1u) / 2u, nd = b / 2u, acc = 0;
    for (size_t v = 0; v < vectors; v++, x += b, o += b) {
        BW_UNROLL8
        for (uint32_t k = 0; k < nd; k++) {
            int32_t e0 = x[2u * k], o0 = x[2u * k + 1u];
            acc |= range_mag(e0) | range_mag(o0);
            uint32_t e = load_k(e0, pq, pre);
            int32_t d = (int32_t)(load_k(o0, pq, pre) - e);
            o[k] = (int32_t)(e - koff(pq, pre) + (uint32_t)bw_asr32(d, 1));
            o[ns + k] = d;
        }
        if (ns > nd) {
            acc |= range_mag(x[2u * nd]);
            o[nd] = (int32_t)(load_k(x[2u * nd], pq, pre) - koff(pq, pre));
        }
    }
    return acc;
}

/* haar1_pass and the second Haar level in one pass, for bands divisible by
 * 4: each 4 samples give two level-1 details, one level-2 detail and one
 * approximation, written to their places in out. Same values (k cancels in
 * every detail). */
static BW_ALWAYS_INLINE uint32_t haar2_pass(const bw_plan_t *pl, int32_t *o, const int32_t *x,
                                            const bw_prequant_t *pq, bool pre)
{
    size_t vectors = (size_t)pl->dims.n_in * pl->dims.n_out;
    uint32_t b = pl->dims.bands, n1 = b / 2u, n2 = b / 4u, acc = 0;
    for (size_t v = 0; v < vectors; v++, x += b, o += b) {
        BW_UNROLL8
        for (uint32_t j = 0; j < n2; j++) {
            int32_t e0 = x[4u * j], o0 = x[4u * j + 1u];
            int32_t e1 = x[4u * j + 2u], o1 = x[4u * j + 3u];
            acc |= range_mag(e0) | range_mag(o0) | range_mag(e1) | range_mag(o1);
            uint32_t qe0 = load_k(e0, pq, pre), qe1 = load_k(e1, pq, pre);
            int32_t d0 = (int32_t)(load_k(o0, pq, pre) - qe0);
            int32_t d1 = (int32_t)(load_k(o1, pq, pre) - qe1);
            uint32_t s0 = qe0 + (uint32_t)bw_asr32(d0, 1);
            int32_t dd = (int32_t)(qe1 + (uint32_t)bw_asr32(d1, 1) - s0);
            o[j] = (int32_t)(s0 - koff(pq, pre) + (uint32_t)bw_asr32(dd, 1));
            o[n2 + j] = dd;
            o[n1 + 2u * j] = d0;
            o[n1 + 2u * j + 1u] = d1;
        }
    }
    return acc;
}

bw_status_t bw_load_samples(int32_t *out, const int32_t *in, size_t n, uint32_t q)
{
    bw_prequant_t pq = prequant_of(q);
#if !BW_CFG_FAST_LOADS
    /* each sample checked exactly: the same result, less code */
    uint32_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        int32_t x = in[i];
        bad |= (uint32_t)x + BW_SAMPLE_MAX > 2u * BW_SAMPLE_MAX;
        out[i] = (int32_t)(prequant_k(x, &pq) - pq.k);
    }
    return bad ? BW_ERR_RANGE : BW_OK;
#else
    uint32_t acc = q == 1u ? load_pass(out, in, n, &pq, false) : load_pass(out, in, n, &pq, true);
    return range_status(acc, in, n);
#endif
}

/* Spectra with a spectral level and no symmetry step: the load may run the
 * first levels as it goes */
static bool load_levels(const bw_plan_t *pl)
{
    return BW_CFG_FAST_LOADS && pl->spec_levels > 0u && !pl->mirror && !pl->recip;
}

/* 5/3 and 9/7 spectra of 4 bands or more: the load and the first spectral
 * level at once (bw_spec_fwd1_load) */
static bool load_lift(const bw_plan_t *pl)
{
    return load_levels(pl) && BW_CFG_FAST_SPECTRAL &&
           (pl->basis == BW_BASIS_53 || pl->basis == BW_BASIS_97) && pl->dims.bands >= 4u;
}

bw_status_t bw_load_spectrum(const bw_plan_t *pl, int32_t *out, const int32_t *in,
                             unsigned *done)
{
    *done = 0;
    if (!load_lift(pl))
        return bw_load_samples(out, in, pl->dims.bands, pl->prequant);
    bw_prequant_t pq = prequant_of(pl->prequant);
    *done = 1;
    return range_status(bw_spec_fwd1_load(out, in, 1, pl->dims.bands, pl->basis, &pq), in,
                        pl->dims.bands);
}

bw_status_t bw_load(const bw_plan_t *pl, int32_t *out, const int32_t *in, unsigned *done)
{
    /* prediction quantises its errors in the loop: no prequantiser here */
    uint32_t q = pl->basis == BW_BASIS_PRED ? 1u : pl->prequant;
    unsigned levels = 0;
    /* Haar spectra without a symmetry step: the load and the first levels at once */
    if (pl->basis == BW_BASIS_HAAR && load_levels(pl))
        levels = pl->spec_levels > 1u && pl->dims.bands % 4u == 0u ? 2u : 1u;
    /* 5/3 and 9/7 spectra likewise, one level */
    bool l1 = load_lift(pl);
    if (l1)
        levels = 1u;
    *done = levels;
    if (levels == 0u)
        return bw_load_samples(out, in, pl->n, q);
    bw_prequant_t pq = prequant_of(q);
    uint32_t acc = 0;
    if (l1)
        acc = bw_spec_fwd1_load(out, in, pl->n / pl->dims.bands, pl->dims.bands, pl->basis, &pq);
    else if (levels == 2u)
        acc = q == 1u ? haar2_pass(pl, out, in, &pq, false) : haar2_pass(pl, out, in, &pq, true);
    else
        acc = q == 1u ? haar1_pass(pl, out, in, &pq, false) : haar1_pass(pl, out, in, &pq, true);
    return range_status(acc, in, pl->n);
}
