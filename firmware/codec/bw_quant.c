/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The quantiser (docs/FORMAT.md, Quantisation): thresholds per space, then a
 * dead-zone quantiser per element with a step per subband, scaled so that a
 * step gives about the same squared error in the sample domain whatever the
 * subband; the reconstruction at 3/8 of the interval.
 *
 * Formats (bw_fixed.h):
 *
 *   value                          type       format     range
 *   step_q8, the plan's base step  uq24_8_t   Q24.8      256 (1.0) .. 2^32 - 1
 *   g_in, g_out, the Bio-Haar      uq16_t     Q16.16     at most 75674 (1.155)
 *     inverse gains of a subband
 *   g_spec, the spectral one       uq16_t     Q16.16     at most 92682 (1.414)
 *   st_q8, an element's step       uq56_8_t   Q56.8      below 2^33
 *   round_q8, the rounding offset  uint32_t   Q8 of a    0 .. 128
 *                                             step
 *   off_q8 = st_q8 round_q8 / 256  uq56_8_t   Q56.8      below st_q8 / 2
 *   coefficients c, indices q      int32_t    integers
 *   vec_thresh_q8                  uint32_t   Q8 steps   default 256 (one step)
 *
 * Scaling and overflow: st_q8 is step_q8 times the three gains, each product
 * truncated after the multiplication (>> 16): below 2^33 x 2^17 = 2^50
 * before a shift and below 2^32 x 1.155^2 x 1.414 < 2^33 after the last, so
 * the products are formed in 64 bits. The quantiser forms 256 |c| + off_q8
 * (below 2^39 + 2^32) and divides by st_q8 > 256: |q| < 2^31. Every
 * coefficient of valid input and every step of 2^24 or less leave both
 * operands below 2^32, one 32-bit division (div_q8_off). The
 * reconstruction (8 |q| + 3) st_q8 / 2^11 of what an encoder writes stays
 * below 8 x 256 |c| + 3 st_q8 < 2^43 and saturates to INT32_MAX; a payload
 * no encoder writes may wrap the 64-bit product (unsigned, so defined): it
 * decodes to wrong values, never to undefined behaviour. The energy of a
 * vector sums squares of indices saturated to 2^24 and itself saturates at
 * 2^62.
 */
#include <string.h>

#include "bw_internal.h"

/* Step of one element, Q56.8, from the base step and the inverse gains of
 * its three spaces (each Q16). */
static uq56_8_t elem_step(uq24_8_t step_q8, uq16_t g_in_q16, uq16_t g_out_q16, uq16_t g_spec_q16)
{
    uq56_8_t s = ((uint64_t)step_q8 * g_in_q16) >> 16;
    s = (s * g_out_q16) >> 16;
    s = (s * g_spec_q16) >> 16;
    return s;
}

/* floor((256 a + off_q8) / st_q8): a 32-bit division (one instruction on
 * Cortex-M4) when the operands fit, which they do for every coefficient of
 * valid input. */
BW_NOINLINE_SMALL static uint64_t div_q8_off(uint32_t a, uq56_8_t st_q8, uq56_8_t off_q8)
{
    uint64_t num = ((uint64_t)a << 8) + off_q8;
    if (num <= UINT32_MAX && st_q8 <= UINT32_MAX)
        return (uint32_t)num / (uint32_t)st_q8;
    /* a coefficient beyond 2^24 or a step beyond 2^24: long division
     * (rare, and it keeps the 64-bit division helper out of the image) */
    uint64_t q = 0, r = 0;
    for (int bit = 40; bit >= 0; bit--) {
        r = (r << 1) | ((num >> bit) & 1u);
        if (r >= st_q8) {
            r -= st_q8;
            q |= (uint64_t)1 << bit;
        }
    }
    return q;
}

/* floor(256 a / st_q8) */
static inline uint64_t div_q8(uint32_t a, uq56_8_t st_q8) { return div_q8_off(a, st_q8, 0u); }

void bw_spec_bands(const bw_plan_t *pl, spec_bands_t *sb)
{
    uint32_t len[BW_SPEC_MAX_LEVELS + 1u];
    unsigned L = pl->spec_levels;
    len[0] = pl->dims.bands;
    for (unsigned l = 1; l <= L; l++)
        len[l] = (len[l - 1u] + 1u) / 2u;
    sb->count = L + 1u;
    sb->lo[0] = 0;
    for (unsigned i = 0; i <= L; i++) {
        sb->lo[i + 1u] = len[L - i];
        sb->gain_q16[i] = (uq16_t)pl->spec_gain[len[L - i] - 1u];
    }
}

/* The threshold on a vector's energy in steps (vec_energy): the square of
 * vec_thresh_q8 / 256, at least 1. */
static uint64_t vec_thr(const bw_plan_t *pl)
{
    uint64_t t = ((uint64_t)pl->vec_thresh_q8 * pl->vec_thresh_q8) >> 16;
    return t ? t : 1u;
}

/* Per subband, the step of a vector whose incoming x outgoing gain is gio. */
static void vec_steps(const bw_plan_t *pl, const spec_bands_t *sb, uq16_t gio_q16,
                      uq56_8_t *st_q8)
{
    for (unsigned i = 0; i < sb->count; i++)
        st_q8[i] = elem_step(pl->step_q8, gio_q16, 65536u, sb->gain_q16[i]);
}

/* Energy of a vector in steps: the sum of floor(|c| / step)^2 (the squares
 * of the indices the dead-zone quantiser gives), saturating; it stops once
 * the sum reaches limit (the callers only compare it with a threshold), so
 * for most vectors after a few elements. */
static uint64_t vec_energy(const spec_bands_t *sb, const uq56_8_t *st_q8, const int32_t *x,
                           uint64_t limit)
{
    uint64_t e = 0;
    if (limit == 0u)
        return 0;
    for (unsigned i = 0; i < sb->count; i++) {
        uq56_8_t st = st_q8[i] ? st_q8[i] : 1u;
        /* |c| < zero (256 |c| < step): an index of 0, nothing to add */
        uint32_t zero = !BW_CFG_FAST_QUANT        ? 0u
                        : st >= ((uint64_t)1 << 32) ? 1u << 24
                                                    : (uint32_t)((st + 255u) >> 8);
        /* |c| < zero, as one unsigned comparison: c + zero - 1 < 2 zero - 1 */
        uint32_t bias = zero - 1u, lim = 2u * zero - 1u;
        for (uint32_t k = sb->lo[i], end = sb->lo[i + 1u]; k < end; k++) {
            if (BW_CFG_FAST_QUANT) {
                while ((uint32_t)x[k] + bias < lim)
                    if (++k == end)
                        break;
                if (k == end)
                    break;
            }
            uint32_t a = bw_abs32(x[k]);
            uint64_t r = div_q8(a, st);
            if (r > (1u << 24))
                r = 1u << 24;
            e += r * r;
            if (e > ((uint64_t)1 << 62))
                return (uint64_t)1 << 62;
            if (e >= limit)
                return e;
        }
    }
    return e;
}

/* floor(|c| / step + round / 256) with the sign of c; off_q8 = st_q8 *
 * round / 256 (0: the dead-zone quantiser, floor(|c| / step)). */
static inline int32_t quant(int32_t c, uq56_8_t st_q8, uq56_8_t off_q8)
{
    if (st_q8 <= BW_STEP_ONE_Q8)
        return c;
    uint32_t q = (uint32_t)div_q8_off(bw_abs32(c), st_q8, off_q8);
    return c < 0 ? -(int32_t)q : (int32_t)q;
}

/* Reconstruction at 3/8 of the interval: the centroid of a Laplacian-like
 * band is below the midpoint. */
static inline int32_t dequant(int32_t q, uq56_8_t st_q8)
{
    if (st_q8 <= BW_STEP_ONE_Q8 || q == 0)
        return q;
    uint64_t m = (((uint64_t)bw_abs32(q) * 8u + 3u) * st_q8) >> 11;
    if (m > INT32_MAX)
        m = INT32_MAX;
    return q < 0 ? -(int32_t)m : (int32_t)m;
}

/* Quantises (forward, rounding offset round_q8, and round_q8 + 1 for the
 * coefficients below kc) or reconstructs one vector with its subband steps. */
static void vec_quant(const spec_bands_t *sb, const uq56_8_t *st_q8, int32_t *v, bool forward,
                      uint32_t round_q8, uint32_t kc)
{
    for (unsigned i = 0; i < sb->count; i++) {
        uq56_8_t st = st_q8[i];
        if (st <= BW_STEP_ONE_Q8)
            continue;
        uint32_t k = sb->lo[i], end = sb->lo[i + 1u];
        if (forward) {
#if !BW_CFG_FAST_QUANT
            /* the offset of each coefficient computed in place: less code */
            for (; k < end; k++)
                v[k] = quant(v[k], st, (st * (round_q8 + (k < kc))) >> 8);
#else
            /* the coefficients below kc, then the rest: no choice per element */
            uint32_t cut = kc < k ? k : kc < end ? kc : end;
            uq56_8_t off1_q8 = (st * (round_q8 + 1u)) >> 8, off_q8 = (st * round_q8) >> 8;
            for (; k < cut; k++)
                v[k] = quant(v[k], st, off1_q8);
            for (; k < end; k++)
                v[k] = quant(v[k], st, off_q8);
#endif
        } else {
            for (; k < end; k++)
                v[k] = dequant(v[k], st);
        }
    }
}

/* The incoming x outgoing inverse gain (Q16) of a subband. */
static inline uq16_t gain_io(uq16_t gi_q16, uq16_t g_out_q16)
{
    return (uq16_t)(((uint64_t)gi_q16 * g_out_q16) >> 16);
}

/* One band: the step, at base step step_q8, of the coefficients of outgoing
 * level k (0: scaling, j + 1 for a detail of level j) of a block of
 * incoming gain gi_q16. */
static inline uq56_8_t band_step(const bw_dims_t *d, const spec_bands_t *sb, uq16_t gi_q16,
                                 uint32_t step_q8, unsigned k)
{
    uq16_t g_out_q16 =
        bw_has_out(d) ? (uq16_t)bw_biohaar_inv_gain_q16(d->level_out, (int)k - 1) : 65536u;
    return elem_step(step_q8, gain_io(gi_q16, g_out_q16), 65536u, sb->gain_q16[0]);
}

/* The next outgoing vector in the coder's walk: its position, and *gio_q16
 * the incoming x outgoing inverse gain of its subband. */
static uint32_t walk_vector(const bw_dims_t *d, bw_walk_t *w, uq16_t gi_q16, uq16_t *gio_q16)
{
    uint32_t pos = 0;
    uq16_t g_out_q16 = 65536u;
    if (bw_has_out(d)) {
        int j;
        pos = bw_walk_next(w, d->level_out, &j);
        g_out_q16 = bw_biohaar_inv_gain_q16(d->level_out, j);
    }
    *gio_q16 = gain_io(gi_q16, g_out_q16);
    return pos;
}

/* k = level + 1 of the coefficient at in-place position t of a level-L
 * hemisphere (mask 4^L - 1): 0 for the scaling coefficients, else L less
 * the index of the lowest non-zero base-4 digit (bw_walk_next) */
static inline unsigned level_at(uint32_t t, uint32_t mask, unsigned L)
{
    uint32_t low = t & mask;
    return low ? L - (bw_bitlen(low & (0u - low)) - 1u) / 2u : 0u;
}

/* The in-place position in its block of the coefficient of coding-order
 * index o of a one-band hemisphere of level L (bw_biohaar_pos), and its
 * level k (0: scaling, j + 1 for a detail of level j). */
static inline uint32_t band_pos(uint32_t o, unsigned L, unsigned *k)
{
    if (o < 4u) {
        *k = 0;
        return o << (2u * L);
    }
    unsigned j = (bw_bitlen(o) - 1u) / 2u - 1u; /* 4^(j+1) <= o < 4^(j+2) */
    uint32_t r = o - (1u << (2u * (j + 1u))), p = r / 3u;
    *k = j + 1u;
    return (4u * p + (r - 3u * p) + 1u) << (2u * (L - j - 1u));
}

#if BW_CFG_FAST_QUANT
/* quant, out of the loop that calls it for the rare large value */
static BW_NOINLINE int32_t quant_far(int32_t c, uq56_8_t st_q8, uq56_8_t off_q8)
{
    return quant(c, st_q8, off_q8);
}

/* One band: every vector is one coefficient whose step depends only on its
 * level, so the block is taken in memory order, the level of position t
 * that of its lowest non-zero base-4 digit (bw_walk_next); without a
 * rounding cut, the order does not matter. Forward, where a level's step
 * and offset fit 32 bits, each coefficient below 2^23 takes one 32-bit
 * division (div_q8_off's result). */
static void quant_one_band(const bw_plan_t *pl, const spec_bands_t *sb, int32_t *blk,
                           uq16_t gi_q16, bool forward)
{
    const bw_dims_t *d = &pl->dims;
    unsigned L = bw_has_out(d) ? d->level_out : 0u;
    uq56_8_t st[BW_MAX_LEVEL + 1u], off[BW_MAX_LEVEL + 1u];
    uint32_t st32[BW_MAX_LEVEL + 1u], off32[BW_MAX_LEVEL + 1u];
    for (unsigned k = 0; k <= L; k++) {
        st[k] = band_step(d, sb, gi_q16, pl->step_q8, k);
        off[k] = (st[k] * pl->round_q8) >> 8;
        /* 0: no 32-bit division at this level (exact, or too large) */
        bool fits = st[k] > BW_STEP_ONE_Q8 && st[k] <= UINT32_MAX && off[k] < (1u << 31);
        st32[k] = fits ? (uint32_t)st[k] : 0u;
        off32[k] = fits ? (uint32_t)off[k] : 0u;
    }
    /* level k >= 1 holds the positions m 4^(L - k) with m not a multiple
     * of 4 (the lowest non-zero base-4 digit, level_at), level 0 the
     * multiples of 4^L: each level's positions in strides, its step and
     * offset in registers */
    for (unsigned k = 0; k <= L; k++) {
        if (st[k] <= BW_STEP_ONE_Q8)
            continue;
        uint32_t stride = (uint32_t)1 << (2u * (L - k)), s32 = st32[k], o32 = off32[k];
        uint32_t first = k ? stride : 0u, skip = k ? stride * 4u : stride;
        unsigned runs = k ? 3u : 1u; /* m = 4 i + 1, 4 i + 2, 4 i + 3 */
        if (forward && s32) { /* one 32-bit division a value below 2^23 */
            for (uint32_t base = first; base < d->n_out; base += skip) {
                int32_t *c = blk + base;
                for (unsigned r = 0; r < runs; r++, c += stride) {
                    uint32_t a = bw_abs32(*c);
                    if (BW_LIKELY(a < (1u << 23))) {
                        uint32_t q = ((a << 8) + o32) / s32;
                        *c = *c < 0 ? -(int32_t)q : (int32_t)q;
                    } else {
                        *c = quant_far(*c, st[k], off[k]);
                    }
                }
            }
            continue;
        }
        for (uint32_t base = first; base < d->n_out; base += skip)
            for (uint32_t t = base, r = 0; r < runs; r++, t += stride)
                blk[t] = forward ? quant(blk[t], st[k], off[k]) : dequant(blk[t], st[k]);
    }
}
#endif

#if BW_CFG_FAST_QUANT && BW_RATE
/* One band, forward, the coefficients of coding-order indices o .. o + n - 1
 * of one block (what vec_quant gives each at its vector's step, without a
 * rounding offset), in coding order, each one's level from its index; out
 * of line, so that its tables do not deepen bw_quant_ahead's frame on the
 * way to quant_block's. */
static BW_NOINLINE void quant_band_range(const bw_plan_t *pl, const spec_bands_t *sb,
                                         int32_t *blk, uq16_t gi_q16, uint32_t o, uint32_t n)
{
    const bw_dims_t *d = &pl->dims;
    unsigned L = bw_has_out(d) ? d->level_out : 0u;
    uq56_8_t st[BW_MAX_LEVEL + 1u];
    uint32_t st32[BW_MAX_LEVEL + 1u];
    for (unsigned k = 0; k <= L; k++) {
        st[k] = band_step(d, sb, gi_q16, pl->step_q8, k);
        st32[k] = st[k] > BW_STEP_ONE_Q8 && st[k] <= UINT32_MAX ? (uint32_t)st[k] : 0u;
    }
    for (uint32_t end = o + n; o < end; o++) {
        unsigned k = 0;
        uint32_t t = bw_has_out(d) ? band_pos(o, L, &k) : o;
        int32_t c = blk[t];
        uint32_t a = bw_abs32(c);
        if (st32[k] && a < (1u << 23)) {
            uint32_t q = (a << 8) / st32[k];
            blk[t] = c < 0 ? -(int32_t)q : (int32_t)q;
        } else if (st[k] > BW_STEP_ONE_Q8) {
            blk[t] = quant_far(c, st[k], 0u);
        }
    }
}
#endif

/* The step of every vector, walking the outgoing hemisphere as the coder
 * does; the subband steps are recomputed only when the vector's gain
 * changes (once per level). */
/* The quantiser's cached steps of one gain (vec_steps), across vectors. */
typedef struct {
    spec_bands_t sb;
    uq56_8_t steps_q8[BW_SPEC_MAX_LEVELS + 1u];
    uq16_t gio_q16; /* no vector has gain 0: the first one computes */
} quant_cache_t;

/* The incoming space: whether the [outgoing][band] block blk of incoming
 * gain gi_q16 has an energy below the threshold, and then zeroes it. */
static bool block_below(const bw_plan_t *pl, quant_cache_t *qc, int32_t *blk, uq16_t gi_q16,
                        uint64_t thr)
{
    const bw_dims_t *d = &pl->dims;
    uint64_t e = 0;
    bw_walk_t w;
    bw_walk_init(&w);
    for (uint32_t o = 0; o < d->n_out && e < thr; o++) {
        uq16_t gio_q16;
        uint32_t pos = walk_vector(d, &w, gi_q16, &gio_q16);
        if (gio_q16 != qc->gio_q16) {
            vec_steps(pl, &qc->sb, gio_q16, qc->steps_q8);
            qc->gio_q16 = gio_q16;
        }
        e += vec_energy(&qc->sb, qc->steps_q8, blk + (size_t)pos * d->bands, thr - e);
    }
    if (e >= thr)
        return false;
    memset(blk, 0, (size_t)d->n_out * d->bands * sizeof *blk);
    return true;
}

/* The block of coarse-to-fine incoming index i, forward or back. */
static BW_ALWAYS_INLINE void quant_block(const bw_plan_t *pl, quant_cache_t *qc, int32_t *x,
                                         uint32_t i, bool forward, uint64_t thr)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    size_t vecs = (size_t)d->n_in * d->n_out;
    uq16_t gi_q16 = bw_in_gain_q16(pl, i);
    int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
    /* the incoming space first: drop a whole block whose energy stays
     * below the threshold */
    if (forward && bw_has_in(d) && block_below(pl, qc, blk, gi_q16, thr))
        return;
#if BW_CFG_FAST_QUANT
    if (b == 1u && pl->round_cut == 0u) {
        quant_one_band(pl, &qc->sb, blk, gi_q16, forward);
        return;
    }
#endif
    /* then every vector */
    bw_walk_t w;
    bw_walk_init(&w);
    for (uint32_t o = 0; o < d->n_out; o++) {
        uq16_t gio_q16;
        uint32_t pos = walk_vector(d, &w, gi_q16, &gio_q16);
        if (gio_q16 != qc->gio_q16) {
            vec_steps(pl, &qc->sb, gio_q16, qc->steps_q8);
            qc->gio_q16 = gio_q16;
        }
        int32_t *v = blk + (size_t)pos * b;
        if (forward && b > 1u && vec_energy(&qc->sb, qc->steps_q8, v, thr) < thr) {
            /* outgoing space: drop the spectral vector */
            memset(v, 0, (size_t)b * sizeof *v);
        } else {
            /* the bands k with k vecs + vi < round_cut (< b vecs) */
            size_t vi = (size_t)i * d->n_out + o;
            vec_quant(&qc->sb, qc->steps_q8, v, forward, pl->round_q8,
                      (uint32_t)((pl->round_cut + vecs - 1u - vi) / vecs));
        }
    }
}

#if BW_CFG_CHUNK_STEPS
uint32_t bw_chunk_step(uint32_t step_q8, int d)
{
    /* 2^(d / 32) = 2^((d + 128) / 32) / 16: floor(floor(x) / 16) = floor(x / 16) */
    uint64_t s = d >= 0 ? bw_oct32(step_q8, (unsigned)d) : bw_oct32(step_q8, (unsigned)(d + 128)) >> 4;
    return s > UINT32_MAX ? UINT32_MAX : s <= BW_STEP_ONE_Q8 ? BW_STEP_ONE_Q8 + 1u : (uint32_t)s;
}

/* Block i back with the steps of its vectors' chunks (BW_EXT_CHUNK_STEPS):
 * each run of its vectors in one chunk with that chunk's step. */
static void dequant_chunks(const bw_plan_t *pl, quant_cache_t *qc, int32_t *x, uint32_t i)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t K = pl->chunk_vec, b = d->bands;
    size_t v0 = (size_t)i * d->n_out;
    size_t g = v0 / K, left = K - v0 % K; /* its first vector's chunk, and its vectors left */
    bw_plan_t cp = *pl;
    uq16_t gi_q16 = (uq16_t)bw_in_gain_q16(pl, i);
    int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
    cp.step_q8 = bw_chunk_step(pl->step_q8, pl->chunk_d[g]);
    qc->gio_q16 = 0;
#if BW_CFG_FAST_QUANT
    if (b == 1u && left >= d->n_out) { /* the block in one chunk */
        quant_one_band(&cp, &qc->sb, blk, gi_q16, false);
        return;
    }
#endif
    bw_walk_t w;
    bw_walk_init(&w);
    for (uint32_t o = 0; o < d->n_out; o++, left--) {
        if (left == 0u) { /* the next chunk */
            cp.step_q8 = bw_chunk_step(pl->step_q8, pl->chunk_d[++g]);
            qc->gio_q16 = 0;
            left = K;
        }
        uq16_t gio_q16;
        uint32_t pos = walk_vector(d, &w, gi_q16, &gio_q16);
        if (gio_q16 != qc->gio_q16) {
            vec_steps(&cp, &qc->sb, gio_q16, qc->steps_q8);
            qc->gio_q16 = gio_q16;
        }
        vec_quant(&qc->sb, qc->steps_q8, blk + (size_t)pos * b, false, 0u, 0u);
    }
    qc->gio_q16 = 0; /* the cache is of a chunk's step */
}
#endif

void bw_quantise(const bw_plan_t *pl, int32_t *x, bool forward)
{
    uint64_t thr = vec_thr(pl);
    quant_cache_t qc;
    qc.gio_q16 = 0;
    bw_spec_bands(pl, &qc.sb);
    for (uint32_t i = 0; i < pl->dims.n_in; i++) {
#if BW_CFG_CHUNK_STEPS
        if (!forward && pl->chunk_vec) {
            dequant_chunks(pl, &qc, x, i);
            continue;
        }
#endif
        quant_block(pl, &qc, x, i, forward, thr);
    }
}

void bw_dequant_block(const bw_plan_t *pl, int32_t *x, uint32_t i)
{
    quant_cache_t qc;
    qc.gio_q16 = 0;
    bw_spec_bands(pl, &qc.sb);
#if BW_CFG_CHUNK_STEPS
    if (pl->chunk_vec) {
        dequant_chunks(pl, &qc, x, i);
        return;
    }
#endif
    quant_block(pl, &qc, x, i, false, 0u);
}

void bw_quant_vector(const bw_plan_t *pl, int32_t *v, int j)
{
    if (pl->step_q8 <= BW_STEP_ONE_Q8)
        return;
    uint32_t b = pl->dims.bands;
    uq16_t gio_q16 = bw_has_out(&pl->dims) ? bw_biohaar_inv_gain_q16(pl->dims.level_out, j)
                                           : 65536u;
    uint64_t thr = vec_thr(pl);
    spec_bands_t sb;
    uq56_8_t steps_q8[BW_SPEC_MAX_LEVELS + 1u];
    bw_spec_bands(pl, &sb);
    vec_steps(pl, &sb, gio_q16, steps_q8);
    if (b > 1u && vec_energy(&sb, steps_q8, v, thr) < thr)
        memset(v, 0, (size_t)b * sizeof *v);
    else
        vec_quant(&sb, steps_q8, v, true, 0u, 0u);
}

/* 4 log2(v), rounded down to a quarter octave (v >= 1): the leading one's
 * position and the two bits below it (quarters at 1, 1.25, 1.5, 1.75) */
static inline unsigned log4(uint64_t v)
{
    unsigned e = 0;
    if (v >> 32) {
        v >>= 32;
        e = 32;
    }
    e += bw_bitlen((uint32_t)v) - 1u;
    uint32_t top = e >= 2u ? (uint32_t)(v >> ((e & 31u) - 2u)) : (uint32_t)(v << (2u - e));
    return 4u * e + (top & 3u);
}

/* The quarter octave (log4) of each subband's step at a base step of 1,
 * l4[s] for s < sb->count, of a vector of incoming x outgoing gain gio_q16. */
static BW_NOINLINE void sub_log4(const spec_bands_t *sb, uq16_t gio_q16, unsigned *l4)
{
    for (unsigned s = 0; s < sb->count; s++) {
        uq56_8_t st = elem_step(BW_STEP_ONE_Q8, gio_q16, 65536u, sb->gain_q16[s]);
        l4[s] = log4(st ? st : 1u);
    }
}

#if BW_CFG_FAST_QUANT || BW_RATE
/* The same for a block of one band of incoming gain gi_q16, per outgoing
 * level: l4[k] for k = level + 1 (0: scaling), k = 0..L (as quant_one_band
 * and level_at); returns L. */
static BW_NOINLINE unsigned level_log4(const bw_dims_t *d, const spec_bands_t *sb, uq16_t gi_q16,
                                  unsigned *l4)
{
    unsigned L = bw_has_out(d) ? d->level_out : 0u;
    for (unsigned k = 0; k <= L; k++) {
        uq56_8_t st = band_step(d, sb, gi_q16, BW_STEP_ONE_Q8, k);
        l4[k] = log4(st ? st : 1u);
    }
    return L;
}
#endif

void bw_quant_hist(const bw_plan_t *pl, const int32_t *x, uint32_t *hist)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    spec_bands_t sb;
    unsigned lst[BW_SPEC_MAX_LEVELS + 1u];
    uq16_t lst_gio_q16 = 0;
    memset(hist, 0, BW_HIST_BINS * sizeof *hist);
    bw_spec_bands(pl, &sb);
    for (uint32_t i = 0; i < d->n_in; i++) {
        uq16_t gi_q16 = bw_in_gain_q16(pl, i);
        const int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
#if BW_CFG_FAST_QUANT
        if (b == 1u) {
            /* one band: the block in memory order, each coefficient's level
             * from its position (as quant_one_band) */
            unsigned off[BW_MAX_LEVEL + 1u], L = level_log4(d, &sb, gi_q16, off);
            for (unsigned k = 0; k <= L; k++)
                off[k] = BW_HIST_ZERO_BIN + 32u - off[k];
            uint32_t mask = (1u << (2u * L)) - 1u;
            for (uint32_t t = 0; t < d->n_out; t++) {
                uint32_t a = bw_abs32(blk[t]);
                unsigned bin = a ? log4(a) + off[level_at(t, mask, L)] : 0u;
                hist[bin < BW_HIST_BINS ? bin : BW_HIST_BINS - 1u]++;
            }
            continue;
        }
#endif
        bw_walk_t w;
        bw_walk_init(&w);
        for (uint32_t o = 0; o < d->n_out; o++) {
            uq16_t gio_q16;
            uint32_t pos = walk_vector(d, &w, gi_q16, &gio_q16);
            if (gio_q16 != lst_gio_q16) {
                sub_log4(&sb, gio_q16, lst);
                lst_gio_q16 = gio_q16;
            }
            const int32_t *v = blk + (size_t)pos * b;
            for (unsigned s = 0; s < sb.count; s++) {
                /* bin 4 log2(256 |c| / st) + BW_HIST_ZERO_BIN - 32: below
                 * BW_HIST_ZERO_BIN the step 1 codes c as 0 */
                unsigned off = BW_HIST_ZERO_BIN + 32u - lst[s];
                for (uint32_t k = sb.lo[s]; k < sb.lo[s + 1u]; k++) {
                    uint32_t a = bw_abs32(v[k]);
                    unsigned bin = a ? log4(a) + off : 0u;
                    hist[bin < BW_HIST_BINS ? bin : BW_HIST_BINS - 1u]++;
                }
            }
        }
    }
}

#if BW_RATE
void bw_qwalk_init(bw_qwalk_t *qw)
{
    qw->i = 0;
    qw->o = 0;
    qw->dropped = false;
    bw_walk_init(&qw->w);
}

/* The next vector of the walk (qw->i < n_in): its place in x, its gain in
 * *gio_q16; *start: it is the first of its block. */
static int32_t *qwalk_next(const bw_plan_t *pl, bw_qwalk_t *qw, int32_t *x, uq16_t *gi_q16,
                           uq16_t *gio_q16, bool *start)
{
    const bw_dims_t *d = &pl->dims;
    int32_t *blk = x + (size_t)bw_in_pos(pl, qw->i) * d->n_out * d->bands;
    *gi_q16 = (uq16_t)bw_in_gain_q16(pl, qw->i);
    *start = qw->o == 0u;
    if (*start)
        bw_walk_init(&qw->w);
    uint32_t pos = walk_vector(d, &qw->w, *gi_q16, gio_q16);
    if (++qw->o == d->n_out) {
        qw->o = 0;
        qw->i++;
    }
    return blk + (size_t)pos * d->bands;
}

void bw_quant_ahead(const bw_plan_t *pl, bw_qwalk_t *qw, int32_t *x, uint32_t nvec)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    uint64_t thr = vec_thr(pl);
    quant_cache_t qc;
    qc.gio_q16 = 0;
    bw_spec_bands(pl, &qc.sb);
#if BW_CFG_FAST_QUANT
    if (b == 1u) { /* one band: runs of a block's coefficients (its walk not kept) */
        while (nvec && qw->i < d->n_in) {
            if (qw->o == 0u && nvec >= d->n_out) {
                quant_block(pl, &qc, x, qw->i++, true, thr);
                nvec -= d->n_out;
                continue;
            }
            int32_t *blk = x + (size_t)bw_in_pos(pl, qw->i) * d->n_out;
            uq16_t gi_q16 = (uq16_t)bw_in_gain_q16(pl, qw->i);
            if (qw->o == 0u)
                qw->dropped = bw_has_in(d) && block_below(pl, &qc, blk, gi_q16, thr);
            uint32_t n = d->n_out - qw->o < nvec ? d->n_out - qw->o : nvec;
            if (!qw->dropped)
                quant_band_range(pl, &qc.sb, blk, gi_q16, qw->o, n);
            nvec -= n;
            if ((qw->o += n) == d->n_out) {
                qw->o = 0;
                qw->i++;
            }
        }
        return;
    }
#endif
    for (; nvec && qw->i < d->n_in; nvec--) {
        if (qw->o == 0u && nvec >= d->n_out) {
            /* a whole block, as bw_quantise does */
            quant_block(pl, &qc, x, qw->i++, true, thr);
            nvec -= d->n_out - 1u;
            continue;
        }
        uq16_t gi_q16, gio_q16;
        bool start;
        int32_t *blk = x + (size_t)bw_in_pos(pl, qw->i) * d->n_out * b;
        int32_t *v = qwalk_next(pl, qw, x, &gi_q16, &gio_q16, &start);
        if (start)
            qw->dropped = bw_has_in(d) && block_below(pl, &qc, blk, gi_q16, thr);
        if (qw->dropped)
            continue;
        if (gio_q16 != qc.gio_q16) {
            vec_steps(pl, &qc.sb, gio_q16, qc.steps_q8);
            qc.gio_q16 = gio_q16;
        }
        if (b > 1u && vec_energy(&qc.sb, qc.steps_q8, v, thr) < thr)
            memset(v, 0, (size_t)b * sizeof *v);
        else
            vec_quant(&qc.sb, qc.steps_q8, v, true, 0u, 0u);
    }
}

/* The estimate's sums of one block of one band in memory order (its
 * outgoing level from the position, as quant_one_band): lst[k] for level
 * k + 1 (0: scaling) as bw_quant_est's. */
static void est_one_band(const bw_dims_t *d, const int32_t *blk, const int *lst, uint32_t a0_q6,
                         uint32_t a1_q6, uint64_t *acc)
{
    unsigned L = bw_has_out(d) ? d->level_out : 0u;
    uint32_t mask = (1u << (2u * L)) - 1u;
    for (uint32_t t = 0; t < d->n_out; t++) {
        uint32_t a = bw_abs32(blk[t]);
        if (!a)
            continue;
        int xq = (int)log4(a) - lst[level_at(t, mask, L)];
        if (xq >= 0)
            *acc += a0_q6 + a1_q6 * (uint32_t)xq;
    }
}

void bw_quant_est(const bw_plan_t *pl, const int32_t *x, uint32_t chunk_vec, int t4,
                  uint32_t a0_q6, uint32_t a1_q6, uint32_t *est)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands, left = chunk_vec, *e = est;
    spec_bands_t sb;
    unsigned l4[BW_SPEC_MAX_LEVELS + BW_MAX_LEVEL + 2u];
    int lst[BW_SPEC_MAX_LEVELS + BW_MAX_LEVEL + 2u];
    uq16_t lst_gio_q16 = 0;
    uint64_t acc = 0;
    bw_qwalk_t qw;
    bw_spec_bands(pl, &sb);
    bw_qwalk_init(&qw);
    /* one band in chunks of whole blocks: a block at a time in memory order */
    bool blocks = b == 1u && chunk_vec % d->n_out == 0u;
#if BW_CFG_FAST_QUANT
    if (b == 1u && !blocks) { /* one band: each block in coding order */
        for (uint32_t i = 0; i < d->n_in; i++) {
            uq16_t gi_q16 = (uq16_t)bw_in_gain_q16(pl, i);
            unsigned L = level_log4(d, &sb, gi_q16, l4);
            for (unsigned k = 0; k <= L; k++)
                lst[k] = (int)l4[k] - 32 + t4;
            const int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out;
            for (uint32_t o = 0; o < d->n_out; o++) {
                unsigned k = 0;
                uint32_t a = bw_abs32(blk[bw_has_out(d) ? band_pos(o, L, &k) : o]);
                int xq = a ? (int)log4(a) - lst[k] : -1;
                if (xq >= 0)
                    acc += a0_q6 + a1_q6 * (uint32_t)xq;
                if (--left == 0u || (i + 1u == d->n_in && o + 1u == d->n_out)) {
                    *e++ = (uint32_t)(acc >> 6);
                    acc = 0;
                    left = chunk_vec;
                }
            }
        }
        return;
    }
#endif
    while (qw.i < d->n_in) {
        uq16_t gi_q16, gio_q16;
        uint32_t nv = 1;
        if (blocks) {
            gi_q16 = (uq16_t)bw_in_gain_q16(pl, qw.i);
            unsigned L = level_log4(d, &sb, gi_q16, l4);
            for (unsigned k = 0; k <= L; k++)
                lst[k] = (int)l4[k] - 32 + t4;
            est_one_band(d, x + (size_t)bw_in_pos(pl, qw.i) * d->n_out, lst, a0_q6, a1_q6, &acc);
            nv = d->n_out;
            qw.i++;
        } else {
            bool start;
            const int32_t *v =
                qwalk_next(pl, &qw, (int32_t *)(uintptr_t)x, &gi_q16, &gio_q16, &start);
            if (gio_q16 != lst_gio_q16) {
                /* each subband's quarter octave at step 1, less 32 + t4 */
                sub_log4(&sb, gio_q16, l4);
                for (unsigned s = 0; s < sb.count; s++)
                    lst[s] = (int)l4[s] - 32 + t4;
                lst_gio_q16 = gio_q16;
            }
            for (unsigned s = 0; s < sb.count; s++) {
                int l = lst[s];
                for (uint32_t k = sb.lo[s]; k < sb.lo[s + 1u]; k++) {
                    uint32_t a = bw_abs32(v[k]);
                    int xq = a ? (int)log4(a) - l : -1;
                    if (xq >= 0)
                        acc += a0_q6 + a1_q6 * (uint32_t)xq;
                }
            }
        }
        left -= nv;
        if (left == 0u || qw.i == d->n_in) {
            *e++ = (uint32_t)(acc >> 6);
            acc = 0;
            left = chunk_vec;
        }
    }
}
#endif
