/*
 * brdfwave codec: transforms, quantisation, strip coding and the payload.
 *
 * Encoding is one pass over a caller work array:
 *   load     samples / prequant -> work           (MAX_ERROR: prequant = 2E+1)
 *   forward  spectral lifting on every spectrum, then Bio-Haar on the
 *            outgoing hemisphere, then (full BRDF) on the incoming one
 *   quantise per-space thresholds: incoming blocks, then outgoing vectors
 *            dropped by normalised norm, then a dead-zone quantiser per
 *            element, with a step per subband scaled to equal sample-domain
 *            error
 *   code     the coefficients in coarse-to-fine order as strips of 32:
 *            a presence flag, the 32-bit valid index, the valid values
 * The byte-budget mode repeats the pass while it searches the step.
 * See docs/FORMAT.md for the payload.
 */
#include <string.h>

#include "bw_internal.h"
#include "bw_strip_coder.h"

#include "bw_biohaar.h"
#include "bw_coder.h"
#include "bw_crc32.h"
#include "bw_fixed.h"
#include "bw_geodesic.h"
#include "bw_le.h"
#include "bw_rc.h"
#include "bw_rice.h"
#include "bw_spectral.h"

#define STEP_FRAC 32u        /* budget search: 32 steps per octave          */
#define STEP_T_MAX (24u * STEP_FRAC)
#define STEP_REFINE 16384u   /* then bisection on the step to 1/16384 of it */
#define ROUND_MAX_Q8 32u     /* then the rounding offset, up to 1/8 of a step */
#define ROUND_WIDE_Q8 128u   /* or 1/2, where 1/8 leaves the budget unfilled  */
#define ROUND_FILL 128u      /* when the payload is more than 1/128 under */
#define VEC_THRESH_MAX_LOG2 16u /* a budget may raise it up to 2^16 steps     */

/* ---- the transform plan -------------------------------------------------- */

/* done: the first spectral levels already applied (load_haar1, load_haar2) */
static void transform_fwd(const bw_plan_t *pl, int32_t *x, unsigned done)
{
    const bw_dims_t *d = &pl->dims;
    size_t vectors = (size_t)d->n_in * d->n_out;
    uint32_t n = d->bands;
    for (unsigned l = 0; l < done; l++)
        n = (n + 1u) / 2u;
    unsigned levels = pl->spec_levels - done;
    if (levels)
        for (size_t v = 0; v < vectors; v++)
            bw_spec_fwd(x + v * d->bands, n, pl->basis, levels, pl->tmp);
    if (bw_has_out(d))
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_fwd(x + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
    if (bw_has_in(d))
        bw_biohaar_fwd(x, d->level_in, (size_t)d->n_out * d->bands);
}

static void transform_inv(const bw_plan_t *pl, int32_t *x)
{
    const bw_dims_t *d = &pl->dims;
    size_t vectors = (size_t)d->n_in * d->n_out;
    if (bw_has_in(d))
        bw_biohaar_inv(x, d->level_in, (size_t)d->n_out * d->bands);
    if (bw_has_out(d))
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_inv(x + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
    if (pl->spec_levels)
        for (size_t v = 0; v < vectors; v++)
            bw_spec_inv(x + v * d->bands, d->bands, pl->basis, pl->spec_levels, pl->tmp);
}

/* ---- mirror symmetry ----------------------------------------------------- */

/* The direction index of the mirror image (x, -y, z) of direction o at a
 * level: base triangle b goes to 3 - b, and in every child digit the
 * corners 2 and 3 trade places (0, 1, 2, 3 -> 0, 1, 3, 2). */
BW_NOINLINE_SMALL static uint32_t mirror_index(uint32_t o, unsigned level)
{
    unsigned sh = 2u * level;
    uint32_t r = o & ((1u << sh) - 1u);
    return (3u - (o >> sh)) << sh | (r ^ ((r >> 1) & 0x55555555u));
}

#if BW_CFG_ENCODE_PRED
/* ---- prediction (BW_BASIS_PRED) ------------------------------------------
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
 * All of it is integer: encoder and decoder predict alike. */
#define PRED_TAPS 4u
#define PRED_MU 6554 /* the LMS step, 0.1 in Q16 */
#define PRED_SAT (1 << 20)
#define PRED_W_MAX (1 << 18)

static inline int64_t sat64(int64_t v, int64_t m) { return v > m ? m : v < -m ? -m : v; }

typedef struct {
    int32_t w[PRED_TAPS];
    int64_t d[PRED_TAPS];
} pred_t;

/* The prediction of band k of spectrum cur (bands before k decoded), prev
 * the decoded previous spectrum (NULL for the first); sets pr->d. */
static int32_t pred_value(pred_t *pr, const int32_t *cur, const int32_t *prev, uint32_t k,
                          uint32_t bands)
{
    pr->d[0] = k >= 2u ? (int64_t)cur[k - 1] - cur[k - 2] : 0;
    pr->d[1] = prev && k + 1u < bands ? (int64_t)prev[k + 1] - prev[k] : 0;
    pr->d[2] = prev && k ? (int64_t)prev[k] - prev[k - 1] : 0;
    pr->d[3] = k >= 3u ? (int64_t)cur[k - 2] - cur[k - 3] : 0;
    int64_t acc = 0, a1 = k ? cur[k - 1] : prev ? prev[0] : 0;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        acc += pr->w[i] * pr->d[i];
    return (int32_t)sat64(a1 + ((acc + 32768) >> 16), BW_SAMPLE_MAX);
}

static void pred_learn(pred_t *pr, int64_t err, uint32_t D)
{
    int64_t e = sat64(err, PRED_SAT), d[PRED_TAPS], nrm = (int64_t)D * D;
    for (unsigned i = 0; i < PRED_TAPS; i++) {
        d[i] = sat64(pr->d[i], PRED_SAT);
        nrm += d[i] * d[i];
    }
    /* divided by 2^floor(log2(nrm)) instead of nrm: no division */
    uint32_t hi = (uint32_t)((uint64_t)nrm >> 32);
    unsigned sh = hi ? 31u + bw_bitlen(hi) : bw_bitlen((uint32_t)nrm) - 1u;
    for (unsigned i = 0; i < PRED_TAPS; i++)
        pr->w[i] = (int32_t)sat64(pr->w[i] + bw_asr64(e * d[i] * PRED_MU, sh), PRED_W_MAX);
}

/* Encoder (fwd) on range-checked samples x -> coded errors, in place, the
 * decoded spectra in two rows of `bands` (rows); decoder: coded errors ->
 * decoded samples, in place. */
static BW_NOINLINE void predict(const bw_plan_t *pl, int32_t *x, int32_t *rows, bool fwd)
{
    uint32_t bands = pl->dims.bands, D = pl->prequant, E = D / 2u;
    const int32_t *prev = NULL;
    for (size_t s = 0; s < pl->dims.n_in; s++) {
        int32_t *v = x + s * bands, *cur = fwd ? rows + (s & 1u) * bands : v;
        pred_t pr = {{0}, {0}};
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
#endif

/* The symmetry steps, on whole vectors of samples; a vector whose partner
 * comes first in [incoming][outgoing] order is coded as its difference
 * from the partner:
 *   BW_FLAG_MIRROR      the mirrored half, each vector against its mirror
 *                       image: (i, m(o)), or for a full BRDF (m(i), m(o))
 *                       for the incoming half i >= n_in / 2;
 *   BW_FLAG_RECIPROCAL  then, in the rows MIRROR leaves (all, or i < n / 2),
 *                       (i, o) against (o, i), or with MIRROR and o in the
 *                       mirrored half against (m(o), m(i)).
 * Forward runs the steps in that order and each backwards (every partner
 * still holds its samples); inverse the other way round. In 32-bit wrapping
 * arithmetic: a corrupt body decodes to wrong samples, never to undefined
 * behaviour; forward, BW_ERR_RANGE if a difference leaves +-BW_SAMPLE_MAX. */
static bw_status_t symmetry(const bw_plan_t *pl, int32_t *x, bool forward)
{
    const bw_dims_t *d = &pl->dims;
    unsigned lo = d->level_out, li = d->level_in, sh = 2u * lo + 2u;
    uint32_t ni = d->n_in, no = d->n_out, rows = pl->mirror ? ni / 2u : ni;
    bool full = bw_has_in(d);
    size_t b = d->bands, total = (size_t)ni << sh;
    uint32_t neg = forward ? ~0u : 0u, bad = 0; /* p ^ neg - neg: -p or p */
    for (unsigned step = 0; step < 2u; step++) {
        bool rec = (step == 0u) != forward;
        if (rec ? !pl->recip : !pl->mirror)
            continue;
        for (size_t t = 0; t < total; t++) {
            size_t s = forward ? total - 1u - t : t;
            uint32_t i = (uint32_t)(s >> sh), o = (uint32_t)s & (no - 1u), a = i, c = o;
            if (rec) {
                if (i < rows) {
                    a = o;
                    c = i;
                    if (o >= rows) {
                        a = mirror_index(o, lo);
                        c = mirror_index(i, lo);
                    }
                }
            } else if (full ? i >= ni / 2u : o >= no / 2u) {
                if (full)
                    a = mirror_index(i, li);
                c = mirror_index(o, lo);
            }
            size_t ps = ((size_t)a << sh) + c;
            if (ps >= s)
                continue;
            uint32_t *v = (uint32_t *)x + s * b;
            const uint32_t *p = (const uint32_t *)x + ps * b;
            for (size_t k = 0; k < b; k++) {
                uint32_t r = v[k] + ((p[k] ^ neg) - neg);
                bad |= r + BW_SAMPLE_MAX > 2u * BW_SAMPLE_MAX;
                v[k] = r;
            }
        }
    }
    return bad & neg ? BW_ERR_RANGE : BW_OK;
}

/* ---- quantisation -------------------------------------------------------- */

/* Step of one element, Q24.8, from the base step and the inverse gains of
 * its three spaces (each Q16). */
static uint64_t elem_step(uint32_t step_q8, uint32_t g_in, uint32_t g_out, uint32_t g_spec)
{
    uint64_t s = ((uint64_t)step_q8 * g_in) >> 16;
    s = (s * g_out) >> 16;
    s = (s * g_spec) >> 16;
    return s;
}

/* floor((256 a + off) / st): a 32-bit division (one instruction on
 * Cortex-M4) when the operands fit, which they do for every coefficient of
 * valid input. */
BW_NOINLINE_SMALL static uint64_t div_q8_off(uint32_t a, uint64_t st, uint64_t off)
{
    uint64_t num = ((uint64_t)a << 8) + off;
    if (num <= UINT32_MAX && st <= UINT32_MAX)
        return (uint32_t)num / (uint32_t)st;
    /* a coefficient beyond 2^24 or a step beyond 2^24: long division
     * (rare, and it keeps the 64-bit division helper out of the image) */
    uint64_t q = 0, r = 0;
    for (int bit = 40; bit >= 0; bit--) {
        r = (r << 1) | ((num >> bit) & 1u);
        if (r >= st) {
            r -= st;
            q |= (uint64_t)1 << bit;
        }
    }
    return q;
}

/* floor(256 a / st) */
static inline uint64_t div_q8(uint32_t a, uint64_t st) { return div_q8_off(a, st, 0u); }

/* The spectral subbands of a vector, Mallat order: subband 0 the
 * approximation, then the details from coarse to fine; band i holds the
 * elements [lo[i], lo[i + 1]). */
typedef struct {
    unsigned count;
    uint32_t lo[BW_SPEC_MAX_LEVELS + 2u];
    uint32_t gain[BW_SPEC_MAX_LEVELS + 1u]; /* inverse gain, Q16 */
} spec_bands_t;

static void spec_bands(const bw_plan_t *pl, spec_bands_t *sb)
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
        sb->gain[i] = (uint32_t)pl->spec_gain[len[L - i] - 1u];
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
static void vec_steps(const bw_plan_t *pl, const spec_bands_t *sb, uint32_t gio, uint64_t *st)
{
    for (unsigned i = 0; i < sb->count; i++)
        st[i] = elem_step(pl->step_q8, gio, 65536u, sb->gain[i]);
}

/* Energy of a vector in steps: the sum of floor(|c| / step)^2 (the squares
 * of the indices the dead-zone quantiser gives), saturating; it stops once
 * the sum reaches limit (the callers only compare it with a threshold), so
 * for most vectors after a few elements. */
static uint64_t vec_energy(const spec_bands_t *sb, const uint64_t *steps, const int32_t *x,
                           uint64_t limit)
{
    uint64_t e = 0;
    if (limit == 0u)
        return 0;
    for (unsigned i = 0; i < sb->count; i++) {
        uint64_t st = steps[i] ? steps[i] : 1u;
        for (uint32_t k = sb->lo[i]; k < sb->lo[i + 1u]; k++) {
            uint64_t r = div_q8(bw_abs32(x[k]), st);
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

/* floor(|c| / step + round / 256) with the sign of c; off = step_q8 *
 * round / 256 (0: the dead-zone quantiser, floor(|c| / step)). */
static inline int32_t quant(int32_t c, uint64_t st, uint64_t off)
{
    if (st <= BW_STEP_ONE_Q8)
        return c;
    uint32_t q = (uint32_t)div_q8_off(bw_abs32(c), st, off);
    return c < 0 ? -(int32_t)q : (int32_t)q;
}

/* Reconstruction at 3/8 of the interval: the centroid of a Laplacian-like
 * band is below the midpoint. */
static inline int32_t dequant(int32_t q, uint64_t st)
{
    if (st <= BW_STEP_ONE_Q8 || q == 0)
        return q;
    uint64_t m = (((uint64_t)bw_abs32(q) * 8u + 3u) * st) >> 11;
    if (m > INT32_MAX)
        m = INT32_MAX;
    return q < 0 ? -(int32_t)m : (int32_t)m;
}

/* Quantises (forward, rounding offset round_q8, and round_q8 + 1 for the
 * coefficients below kc) or reconstructs one vector with its subband steps. */
static void vec_quant(const spec_bands_t *sb, const uint64_t *steps, int32_t *v, bool forward,
                      uint32_t round_q8, uint32_t kc)
{
    for (unsigned i = 0; i < sb->count; i++) {
        uint64_t st = steps[i];
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
            uint64_t off1 = (st * (round_q8 + 1u)) >> 8, off = (st * round_q8) >> 8;
            for (; k < cut; k++)
                v[k] = quant(v[k], st, off1);
            for (; k < end; k++)
                v[k] = quant(v[k], st, off);
#endif
        } else {
            for (; k < end; k++)
                v[k] = dequant(v[k], st);
        }
    }
}

/* The step of every vector, walking the outgoing hemisphere as the coder
 * does; the subband steps are recomputed only when the vector's gain
 * changes (once per level). */
static void quantise(const bw_plan_t *pl, int32_t *x, bool forward)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    unsigned L = d->level_out;
    uint64_t thr = vec_thr(pl);
    spec_bands_t sb;
    uint64_t steps[BW_SPEC_MAX_LEVELS + 1u];
    uint32_t steps_gio = 0; /* no vector has gain 0: the first one computes */
    size_t vecs = (size_t)d->n_in * d->n_out;
    spec_bands(pl, &sb);
    for (uint32_t i = 0; i < d->n_in; i++) {
        uint32_t gi = bw_in_gain_q16(pl, i);
        int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
        for (int pass = forward && bw_has_in(d) ? 0 : 1; pass < 2; pass++) {
            /* pass 0: the incoming space, drop a whole [outgoing][band] block
             * whose energy stays below the threshold; pass 1: every vector */
            uint64_t e = 0;
            bw_walk_t w;
            bw_walk_init(&w);
            for (uint32_t o = 0; o < d->n_out && (pass || e < thr); o++) {
                uint32_t pos = 0, g_out = 65536u;
                if (bw_has_out(d)) {
                    int j;
                    pos = bw_walk_next(&w, L, &j);
                    g_out = bw_biohaar_inv_gain_q16(L, j);
                }
                uint32_t gio = (uint32_t)(((uint64_t)gi * g_out) >> 16);
                if (gio != steps_gio) {
                    vec_steps(pl, &sb, gio, steps);
                    steps_gio = gio;
                }
                int32_t *v = blk + (size_t)pos * b;
                if (!pass) {
                    e += vec_energy(&sb, steps, v, thr - e);
                } else if (forward && b > 1u && vec_energy(&sb, steps, v, thr) < thr) {
                    /* outgoing space: drop the spectral vector */
                    memset(v, 0, (size_t)b * sizeof *v);
                } else {
                    /* the bands k with k vecs + vi < round_cut (< b vecs) */
                    size_t vi = (size_t)i * d->n_out + o;
                    vec_quant(&sb, steps, v, forward, pl->round_q8,
                              (uint32_t)((pl->round_cut + vecs - 1u - vi) / vecs));
                }
            }
            if (!pass && e < thr) {
                memset(blk, 0, (size_t)d->n_out * b * sizeof *blk);
                break;
            }
        }
    }
}

/* ---- encoder ------------------------------------------------------------- */

/* The range check of the loads: the OR over the samples of
 * x ^ (x >> 31) (x for x >= 0, |x| - 1 below) is below 2^24 exactly when
 * every sample lies in [-2^24, 2^24 - 1], two instructions a sample. Of
 * those only -2^24 is outside +-BW_SAMPLE_MAX; it sets all 24 low bits of
 * the OR, so only an OR of 2^24 - 1 makes range_status look for it. */
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
typedef struct {
    uint32_t q, k, bias;
} prequant_t;

static inline prequant_t prequant_of(uint32_t q)
{
    prequant_t pq;
    pq.q = q;
    pq.k = (uint32_t)BW_SAMPLE_MAX / q + 1u;
    pq.bias = (q - 1u) / 2u + pq.k * q;
    return pq;
}

/* (x + bias) / q: the prequantised sample plus k */
static inline uint32_t prequant_k(int32_t x, const prequant_t *pq)
{
    return ((uint32_t)x + pq->bias) / pq->q;
}

/* A sample as the loads take it: prequantised plus k, or (pre false, no
 * prequantiser) itself; the loads subtract koff(pq, pre) where k stays. */
static BW_ALWAYS_INLINE uint32_t load_k(int32_t x, const prequant_t *pq, bool pre)
{
    return pre ? prequant_k(x, pq) : (uint32_t)x;
}
static BW_ALWAYS_INLINE uint32_t koff(const prequant_t *pq, bool pre) { return pre ? pq->k : 0u; }

/* The loops below are written once and called with pre constant: with the
 * prequantiser, and without it (q = 1: no division). Each returns the OR of
 * the range check (range_status). */
static BW_ALWAYS_INLINE uint32_t load_pass(int32_t *out, const int32_t *in, size_t n,
                                           const prequant_t *pq, bool pre)
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

/* Loads n samples into out, prequantised; BW_ERR_RANGE, after loading all,
 * when a sample is out of range. */
static bw_status_t load_samples(int32_t *out, const int32_t *in, size_t n, uint32_t q)
{
    prequant_t pq = prequant_of(q);
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

/* load_samples and the first level of the Haar lifting (fwd_haar) in one
 * pass: from the caller's samples the approximation and the details go
 * straight to their places in out, with no scratch. Same values (the k of
 * the prequantiser cancels in the details). */
static BW_ALWAYS_INLINE uint32_t haar1_pass(const bw_plan_t *pl, int32_t *o, const int32_t *x,
                                            const prequant_t *pq, bool pre)
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

static bw_status_t load_haar1(const bw_plan_t *pl, int32_t *out, const int32_t *in)
{
    prequant_t pq = prequant_of(pl->prequant);
    uint32_t acc = pq.q == 1u ? haar1_pass(pl, out, in, &pq, false)
                              : haar1_pass(pl, out, in, &pq, true);
    return range_status(acc, in, bw_dims_samples(&pl->dims));
}

/* load_haar1 and the second Haar level in one pass, for bands divisible by
 * 4: each 4 samples give two level-1 details, one level-2 detail and one
 * approximation, written to their places in out. Same values (k cancels in
 * every detail). */
static BW_ALWAYS_INLINE uint32_t haar2_pass(const bw_plan_t *pl, int32_t *o, const int32_t *x,
                                            const prequant_t *pq, bool pre)
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

static bw_status_t load_haar2(const bw_plan_t *pl, int32_t *out, const int32_t *in)
{
    prequant_t pq = prequant_of(pl->prequant);
    uint32_t acc = pq.q == 1u ? haar2_pass(pl, out, in, &pq, false)
                              : haar2_pass(pl, out, in, &pq, true);
    return range_status(acc, in, bw_dims_samples(&pl->dims));
}

/* Prediction in place of the prequantiser and the transform (out of line, so
 * that the transforms' encode is built as without it). */
#if !BW_CFG_ENCODE_PRED
#define PREQUANT_OF(pl) ((pl)->prequant)
#define TRANSFORM_FWD(pl, x, done) transform_fwd(pl, x, done)
#else
#define PREQUANT_OF(pl) ((pl)->basis == BW_BASIS_PRED ? 1u : (pl)->prequant)
#define TRANSFORM_FWD(pl, x, done) transform_or_predict(pl, x, done)
static BW_NOINLINE void transform_or_predict(const bw_plan_t *pl, int32_t *x, unsigned done)
{
    if (pl->basis == BW_BASIS_PRED)
        predict(pl, x, x + pl->n, true);
    else
        transform_fwd(pl, x, done);
}
#endif

/* One encode at fixed plan: load, transform, quantise, code. out may be NULL
 * (count only). */
static bw_status_t encode_pass(bw_plan_t *pl, const bw_params_t *pa, uint32_t mode,
                               const int32_t *samples, int32_t *work, uint8_t *out,
                               size_t cap, size_t *len)
{
    /* Haar spectra without a symmetry step: load and the first levels at once */
    unsigned fused = 0;
    if (BW_CFG_FAST_LOADS && pl->basis == BW_BASIS_HAAR && pl->spec_levels > 0u && !pl->mirror &&
        !pl->recip)
        fused = pl->spec_levels > 1u && pl->dims.bands % 4u == 0u ? 2u : 1u;
    bw_status_t st = fused == 2u   ? load_haar2(pl, work, samples)
                     : fused == 1u ? load_haar1(pl, work, samples)
                                   : load_samples(work, samples, pl->n, PREQUANT_OF(pl));
    if (st == BW_OK && (pl->mirror || pl->recip))
        st = symmetry(pl, work, true);
    if (st != BW_OK)
        return st;
    TRANSFORM_FWD(pl, work, fused);
    bw_plan_tables(pl);
    if (pl->step_q8 > BW_STEP_ONE_Q8)
        quantise(pl, work, true);

    bw_strip_enc_t se;
    bool counting = out == NULL;
    size_t body_cap = 0, hl = bw_header_write(NULL, pl, pa, mode);
    if (!counting) {
        if (cap < hl + BW_TRAILER_SIZE)
            return BW_ERR_OUTPUT_FULL;
        body_cap = cap - hl - BW_TRAILER_SIZE;
    }
    bw_strip_enc_init(&se, counting ? NULL : out + hl, body_cap, (pa->flags & BW_FLAG_RICE) != 0u);
    bw_code_body(pl, work, &se);
    size_t body = bw_strip_enc_finish(&se);
    *len = hl + body + BW_TRAILER_SIZE;
    if (counting)
        return BW_OK;
    if (bw_strip_enc_overflow(&se) || *len > UINT32_MAX)
        return BW_ERR_OUTPUT_FULL;
    bw_header_write(out, pl, pa, mode);
    bw_put_u32(out + hl + body, bw_crc32(out, hl + body));
    return BW_OK;
}

static uint32_t step_of(unsigned t)
{
    /* 256 * 2^(t / 32), t = 0..768 */
    static const uint16_t frac_q15[STEP_FRAC] = {
        32768, 33486, 34219, 34968, 35734, 36516, 37316, 38133, 38968, 39821, 40693,
        41584, 42495, 43425, 44376, 45348, 46341, 47356, 48393, 49452, 50535, 51642,
        52773, 53928, 55109, 56316, 57549, 58809, 60097, 61413, 62757, 64132,
    };
    uint64_t s = ((uint64_t)BW_STEP_ONE_Q8 << (t / STEP_FRAC)) * frac_q15[t % STEP_FRAC] >> 15;
    return s > UINT32_MAX ? UINT32_MAX : (uint32_t)s;
}

static bw_status_t verify_payload(const bw_plan_t *pl, const bw_params_t *pa, uint32_t mode,
                                  const int32_t *samples, const uint8_t *out, size_t len,
                                  int32_t *verify, uint64_t *sse)
{
    size_t wb = bw_work_bound(pl->n, pl->dims.bands);
    bw_status_t st = bw_decode(out, len, verify, wb, verify, wb, NULL);
    if (st != BW_OK)
        return BW_ERR_VERIFY;
    uint64_t acc = 0;
    for (size_t i = 0; i < pl->n; i++) {
        int64_t diff = (int64_t)verify[i] - samples[i];
        uint64_t ad = (uint64_t)(diff < 0 ? -diff : diff);
        if (mode == BW_MODE_LOSSLESS && ad != 0)
            return BW_ERR_VERIFY;
        if (mode == BW_MODE_MAX_ERROR && ad > pa->max_error)
            return BW_ERR_VERIFY;
        acc += ad * ad;
    }
    if (sse)
        *sse = acc;
    return BW_OK;
}

/* The parameter of the mode: E, the step, or (BYTES, whose search sets the
 * step) a step of 1. */
static uint32_t mode_param(const bw_params_t *pa)
{
    return pa->mode == BW_MODE_MAX_ERROR ? pa->max_error
           : pa->mode == BW_MODE_STEP    ? pa->step_q8
                                         : BW_STEP_ONE_Q8;
}

/* The plan of one encode with one basis; the work array holds the
 * coefficients, then the spectral tables (which share their room with the
 * lifting scratch). */
static void plan_for(bw_plan_t *pl, const bw_dims_t *dims, unsigned basis, const bw_params_t *pa,
                     int32_t *work)
{
    int32_t *tables = work + bw_dims_samples(dims);
    bw_plan_make(pl, dims, basis, pa->mode, mode_param(pa), pa->flags, pa->vec_thresh_q8, tables,
                 tables);
}

/* Encodes with one basis; for BYTES searches the step. */
/* The size of the BYTES payload at the plan's current settings. */
static bw_status_t count_bytes(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                               int32_t *work, size_t *sz)
{
    return encode_pass(pl, pa, BW_MODE_BYTES, samples, work, NULL, 0, sz);
}

#if BW_CFG_BUDGET_FILL_HALF
/* The largest value of *field in [*lo, hi] whose payload fits the budget
 * (*lo fits; the size grows with it), into *lo. */
static bw_status_t fill_search(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                               int32_t *work, size_t budget, uint32_t *field, uint32_t hi,
                               uint32_t *lo)
{
    uint32_t l = *lo, h = hi + 1u; /* l fits, h does not (or lies past hi) */
    while (h - l > 1u) {
        size_t sz;
        uint32_t mid = l + (h - l) / 2u;
        *field = mid;
        bw_status_t st = count_bytes(pl, pa, samples, work, &sz);
        if (st != BW_OK)
            return st;
        if (sz <= budget)
            l = mid;
        else
            h = mid;
    }
    *lo = l;
    return BW_OK;
}
#endif

static bw_status_t encode_basis(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                                int32_t *work, uint8_t *out, size_t cap, size_t *len)
{
    size_t sz;
    bw_status_t st;
    if (pa->mode != BW_MODE_BYTES)
        return encode_pass(pl, pa, pa->mode, samples, work, out, cap, len);

    size_t budget = pa->byte_budget < cap ? pa->byte_budget : cap;
    /* the exact coding first: if it fits, nothing is lost, and the payload
     * is the lossless one */
    pl->step_q8 = BW_STEP_ONE_Q8;
    st = encode_pass(pl, pa, BW_MODE_LOSSLESS, samples, work, NULL, 0, &sz);
    if (st != BW_OK)
        return st;
    if (sz <= budget)
        return encode_pass(pl, pa, BW_MODE_LOSSLESS, samples, work, out, budget, len);
    unsigned lo = 0, hi = STEP_T_MAX;
    pl->step_q8 = step_of(hi);
    st = count_bytes(pl, pa, samples, work, &sz);
    if (st != BW_OK)
        return st;
    if (sz > budget) {
        /* even the coarsest step leaves too much: then, at that step, the
         * smallest vector threshold (2, 4, .. 65536 steps) that fits; the
         * largest drops every vector with more than one band */
        uint32_t vt0 = pl->vec_thresh_q8;
        unsigned lo_i = 0, hi_i = VEC_THRESH_MAX_LOG2 + 1u; /* hi_i fits (if any does) */
        while (hi_i - lo_i > 1u) {
            unsigned mid = (lo_i + hi_i) / 2u;
            pl->vec_thresh_q8 = vt0 > (UINT32_MAX >> mid) ? UINT32_MAX : vt0 << mid;
            st = count_bytes(pl, pa, samples, work, &sz);
            if (st != BW_OK)
                return st;
            if (sz <= budget)
                hi_i = mid;
            else
                lo_i = mid;
        }
        if (hi_i > VEC_THRESH_MAX_LOG2)
            return BW_ERR_BUDGET;
        pl->vec_thresh_q8 = vt0 > (UINT32_MAX >> hi_i) ? UINT32_MAX : vt0 << hi_i;
        return encode_pass(pl, pa, BW_MODE_BYTES, samples, work, out, budget, len);
    }
    while (hi - lo > 1u) {
        unsigned mid = (lo + hi) / 2u;
        pl->step_q8 = step_of(mid);
        st = count_bytes(pl, pa, samples, work, &sz);
        if (st != BW_OK)
            return st;
        if (sz <= budget)
            hi = mid;
        else
            lo = mid;
    }
    /* then on the step itself, down to 1/16384 of it: at 32 steps per
     * octave the payload still jumps by about 2 % from step to step, and
     * small payloads (a few hundred bytes) move by a few bytes at a time */
    uint32_t lo_s = step_of(lo), hi_s = step_of(hi);
    while (hi_s - lo_s > 1u && (uint64_t)(hi_s - lo_s) * STEP_REFINE > hi_s) {
        uint32_t mid = lo_s + (hi_s - lo_s) / 2u;
        pl->step_q8 = mid;
        st = count_bytes(pl, pa, samples, work, &sz);
        if (st != BW_OK)
            return st;
        if (sz <= budget)
            hi_s = mid;
        else
            lo_s = mid;
    }
    pl->step_q8 = hi_s;
    /* then the quantiser's rounding offset, 0 .. 1/8 of a step: the size
     * jumps at some steps (similar coefficients cross a power of two
     * together), and rounding up more of them fills the budget by smaller
     * amounts. Within 1/8 of a step every coefficient it rounds up ends
     * nearer its reconstruction (at 3/8 of the interval above) than before. */
    st = count_bytes(pl, pa, samples, work, &sz);
    if (st != BW_OK)
        return st;
    if (sz < budget - budget / ROUND_FILL) {
        /* t = r n + c: the offset r / 256 for every coefficient, and
         * (r + 1) / 256 for the first c of them, band by band (coarse to
         * fine), each band in the quantiser's order of vectors: so that the
         * last few bytes fill by single coefficients where a whole step of
         * r would add too many (many coefficients just below a step) */
        uint32_t n = (uint32_t)pl->n, lo_t = 0; /* n <= BW_MAX_SAMPLES; lo_t fits */
        uint32_t max_t = n > UINT32_MAX / ROUND_MAX_Q8 ? UINT32_MAX : ROUND_MAX_Q8 * n;
        uint32_t hi_t = max_t;
        while (hi_t - lo_t > 1u) {
            uint32_t mid = lo_t + (hi_t - lo_t) / 2u;
            pl->round_q8 = mid / n;
            pl->round_cut = mid % n;
            st = count_bytes(pl, pa, samples, work, &sz);
            if (st != BW_OK)
                return st;
            if (sz <= budget)
                lo_t = mid;
            else
                hi_t = mid;
        }
        pl->round_q8 = lo_t / n;
        pl->round_cut = lo_t % n;
#if BW_CFG_BUDGET_FILL_HALF
        /* all of that fits and the payload is still short: the step jumped
         * where integer coefficients of a few units (data coded nearly
         * exactly, at a step just above 1) fell a level together, and no
         * step between the exact coding and that one exists. An offset up
         * to 1/2 of a step takes them back, most to their exact value (the
         * reconstruction is an integer): the error falls as the budget
         * grows (tests/unit/test_codec.c). */
        if (lo_t + 1u == max_t) {
            uint32_t r = pl->round_q8, c = 0;
            pl->round_cut = 0;
            st = fill_search(pl, pa, samples, work, budget, &pl->round_q8, ROUND_WIDE_Q8, &r);
            pl->round_q8 = r;
            if (st == BW_OK && r < ROUND_WIDE_Q8)
                st = fill_search(pl, pa, samples, work, budget, &pl->round_cut, n - 1u, &c);
            if (st != BW_OK)
                return st;
            pl->round_cut = c;
        }
#endif
    }
    return encode_pass(pl, pa, BW_MODE_BYTES, samples, work, out, budget, len);
}

bw_status_t bw_encode(const bw_dims_t *dims, const bw_params_t *pa, const int32_t *samples,
                      int32_t *work, int32_t *verify, uint8_t *out, size_t out_cap,
                      size_t *out_len)
{
    if (!dims || !pa || !samples || !work || !out || !out_len)
        return BW_ERR_ARG;
    *out_len = 0;
    bw_status_t st = bw_params_check(dims, pa->mode, pa->basis, pa->flags, mode_param(pa),
                                     BW_FOR_ENCODE);
    if (st != BW_OK)
        return st;
    bool pred = BW_CFG_ENCODE_PRED && bw_pred_applies(dims, pa->mode, pa->flags);

    bw_plan_t pl;
    bw_status_t fit = BW_OK;
    unsigned first = pa->basis, last = pa->basis;
    if (pa->basis == BW_BASIS_AUTO) {
        first = 0;
        last = pred ? BW_BASIS_PRED : BW_BASIS_COUNT - 1u;
    }
    /* no spectral transform: every transform basis codes alike */
    bool one_transform = bw_spec_levels(dims->bands) == 0u;
    if (one_transform && (!BW_CFG_ENCODE_PRED || last < BW_BASIS_COUNT))
        last = first;
    unsigned best = first;
    if (first != last) {
        /* keep the smallest payload, or for BYTES the smallest error (the
         * smallest step when there is no room to decode) */
        uint64_t best_score = UINT64_MAX;
        size_t best_sz = 0;
        for (unsigned b = first; b <= last; b++) {
            size_t sz;
            if (BW_CFG_ENCODE_PRED && one_transform && b != first && b < BW_BASIS_COUNT)
                continue;
            plan_for(&pl, dims, b, pa, work);
            st = encode_basis(&pl, pa, samples, work, pa->mode == BW_MODE_BYTES ? out : NULL,
                              out_cap, &sz);
            if (st == BW_ERR_BUDGET) { /* another basis may still fit */
                fit = st;
                continue;
            }
            if (st != BW_OK)
                return st;
            uint64_t score = sz;
            if (pa->mode == BW_MODE_BYTES) {
                score = pl.step_q8;
                if (verify && verify_payload(&pl, pa, BW_MODE_BYTES, samples, out, sz, verify,
                                             &score) != BW_OK)
                    return BW_ERR_VERIFY;
            }
            /* a byte budget: the smallest error, then the smallest payload
             * (several bases may code the data exactly) */
            if (score < best_score || (score == best_score && sz < best_sz)) {
                best_score = score;
                best_sz = sz;
                best = b;
            }
        }
        if (best_score == UINT64_MAX)
            return fit; /* no basis fits the budget */
    }
    plan_for(&pl, dims, best, pa, work);
    st = encode_basis(&pl, pa, samples, work, out, out_cap, out_len);
    if (st != BW_OK)
        return st;
    if (verify)
        return verify_payload(&pl, pa, pa->mode, samples, out, *out_len, verify, NULL);
    return BW_OK;
}

/* ---- decoder ------------------------------------------------------------- */

static bw_status_t decode_checked(const uint8_t *p, const bw_header_t *h, int32_t *samples,
                                  size_t samples_cap, int32_t *work, size_t work_cap)
{
    const bw_dims_t *d = &h->dims;
    size_t n = bw_dims_samples(d);
    if (samples_cap < n || work_cap < bw_work_bound(n, d->bands))
        return BW_ERR_WORK;
    bw_plan_t pl;
    bw_plan_make(&pl, d, h->basis, h->mode,
                 h->mode == BW_MODE_MAX_ERROR ? h->max_error : h->step_q8, h->flags, 0u,
                 work + n, work + n);
    bw_plan_tables(&pl);

    bw_models_t m;
    bw_status_t st = bw_decode_body(&pl, work, p + h->header_len, h->body_len,
                                    (h->flags & BW_FLAG_RICE) != 0u, &m);
    if (st != BW_OK)
        return st;
#if BW_CFG_ENCODE_PRED
    if (pl.basis == BW_BASIS_PRED) {
        predict(&pl, work, NULL, false); /* decoded samples: no prequantiser left */
        memcpy(samples, work, n * sizeof *samples);
        return BW_OK;
    }
#endif
    if (pl.step_q8 > BW_STEP_ONE_Q8)
        quantise(&pl, work, false);
    transform_inv(&pl, work);
    if (pl.mirror || pl.recip)
        symmetry(&pl, work, false);
    for (size_t i = 0; i < n; i++) {
        int64_t v = (int64_t)work[i] * pl.prequant;
        samples[i] = v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
    }
    return BW_OK;
}

bw_status_t bw_decode(const uint8_t *payload, size_t len, int32_t *samples, size_t samples_cap,
                      int32_t *work, size_t work_cap, bw_header_t *hdr_out)
{
    bw_header_t h;
    if (!payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_read(payload, len, &h);
    if (hdr_out)
        *hdr_out = h;
    if (st != BW_OK)
        return st;
    return decode_checked(payload, &h, samples, samples_cap, work, work_cap);
}

bw_status_t bw_decode_unchecked(const uint8_t *payload, size_t len, int32_t *samples,
                                size_t samples_cap, int32_t *work, size_t work_cap)
{
    bw_header_t h;
    if (!payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_parse_fields(payload, len, &h); /* every field but crc */
    if (st != BW_OK)
        return st;
    return decode_checked(payload, &h, samples, samples_cap, work, work_cap);
}

/* ---- streaming encoder --------------------------------------------------- */

static void stream_plan(const bw_stream_t *s, bw_plan_t *pl)
{
    bw_plan_make(pl, &s->dims, s->basis, s->params.mode, mode_param(&s->params),
                 s->params.flags, s->params.vec_thresh_q8, s->cls, s->tmp);
}

bw_status_t bw_stream_init(bw_stream_t *s, const bw_dims_t *dims, const bw_params_t *pa,
                           int32_t *mem, size_t mem_len, uint8_t *out, size_t cap)
{
    if (!s || !dims || !pa || !mem || !out)
        return BW_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->err = BW_ERR_ARG;
    bw_status_t st = bw_params_check(dims, pa->mode, pa->basis, pa->flags, mode_param(pa),
                                     BW_FOR_STREAM);
    if (st != BW_OK)
        return st;
    if (mem_len < bw_stream_mem_bound(dims->level_out, dims->bands))
        return BW_ERR_WORK;
    s->dims = *dims;
    s->params = *pa;
    s->params.flags |= BW_FLAG_STREAM_ORDER;
    s->basis = pa->basis;
    s->spec_levels = (uint8_t)bw_spec_levels(dims->bands);
    s->prequant = pa->mode == BW_MODE_MAX_ERROR ? 2u * pa->max_error + 1u : 1u;
    s->step_q8 = pa->mode == BW_MODE_STEP ? pa->step_q8 : BW_STEP_ONE_Q8;
    size_t b = dims->bands;
    s->cls = mem;
    s->gain = mem + b;
    s->tmp = mem + 2u * b;
    s->pend = mem + 3u * b;
    bw_plan_t pl;
    stream_plan(s, &pl);
    bw_plan_tables(&pl);
    size_t hl = bw_header_write(NULL, &pl, &s->params, s->params.mode);
    if (cap < hl + BW_TRAILER_SIZE)
        return BW_ERR_OUTPUT_FULL;
    s->out = out;
    s->cap = cap;
    bw_strip_enc_init(&s->se, out + hl, cap - hl - BW_TRAILER_SIZE, (pa->flags & BW_FLAG_RICE) != 0u);
    s->err = BW_OK;
    return BW_OK;
}

static int32_t *pend_slot(bw_stream_t *s, unsigned level, unsigned slot)
{
    return s->pend + ((size_t)level * 4u + slot) * s->dims.bands;
}

/* Quantises (as quantise() does) and codes one completed vector whose
 * parent level is j (-1: scaling). */
static void stream_emit(bw_stream_t *s, const bw_plan_t *pl, int32_t *v, int j)
{
    uint32_t b = s->dims.bands;
    uint32_t gio = bw_has_out(&s->dims) ? bw_biohaar_inv_gain_q16(s->dims.level_out, j) : 65536u;
    unsigned cd = bw_level_cls(pl, j);
    if (s->step_q8 > BW_STEP_ONE_Q8) {
        uint64_t thr = vec_thr(pl);
        spec_bands_t sb;
        uint64_t steps[BW_SPEC_MAX_LEVELS + 1u];
        spec_bands(pl, &sb);
        vec_steps(pl, &sb, gio, steps);
        if (b > 1u && vec_energy(&sb, steps, v, thr) < thr)
            memset(v, 0, (size_t)b * sizeof *v);
        else
            vec_quant(&sb, steps, v, true, 0u, 0u);
    }
    /* stream order: no directional parent, no previous vector */
    for (uint32_t k = 0; k < b; k++)
        bw_strip_put(&s->se, v[k], BW_SPEC_CLS(s->cls[k]) * 3u + cd,
                     bw_parent_of(NULL, v, s->cls[k], k), NULL);
}

bw_status_t bw_stream_push(bw_stream_t *s, const int32_t *spectrum)
{
    if (!s || !spectrum)
        return BW_ERR_ARG;
    if (s->err != BW_OK)
        return s->err;
    const bw_dims_t *d = &s->dims;
    if (s->pushed >= (size_t)d->n_in * d->n_out)
        return s->err = BW_ERR_ARG; /* more spectra than the shape holds */
    uint32_t b = d->bands;
    unsigned L = d->level_out;
    bw_plan_t pl;
    stream_plan(s, &pl);
    unsigned lv = bw_has_out(d) ? L : 0u;
    int32_t *v = pend_slot(s, lv, s->pend_n[lv]);
    bw_status_t st = load_samples(v, spectrum, b, s->prequant);
    if (st != BW_OK)
        return s->err = st;
    if (s->spec_levels)
        bw_spec_fwd(v, b, s->basis, s->spec_levels, s->tmp);
    s->pushed++;
    if (!bw_has_out(d)) {
        stream_emit(s, &pl, v, -1);
        return BW_OK;
    }
    /* up the tree while four siblings are complete */
    s->pend_n[L]++;
    uint32_t t = s->leaf;
    for (unsigned j = L; j > 0u && s->pend_n[j] == 4u; j--) {
        unsigned k = L - j + 1u; /* the parent is t >> 2k at level j - 1 */
        uint32_t p = t >> (2u * k);
        uint32_t per_base = 1u << (2u * (j - 1u));
        uint16_t w[3];
        bw_geo_weights(j - 1u, p & (per_base - 1u), w);
        bw_biohaar_lift4(pend_slot(s, j, 0), pend_slot(s, j, 1), pend_slot(s, j, 2),
                         pend_slot(s, j, 3), w, b);
        for (unsigned m = 1; m <= 3u; m++)
            stream_emit(s, &pl, pend_slot(s, j, m), (int)j - 1);
        /* the parent's scaling vector moves up a level */
        memcpy(pend_slot(s, j - 1u, s->pend_n[j - 1u]), pend_slot(s, j, 0), (size_t)b * sizeof *v);
        s->pend_n[j - 1u]++;
        s->pend_n[j] = 0;
    }
    if (s->pend_n[0] == 1u) { /* a base triangle is complete */
        stream_emit(s, &pl, pend_slot(s, 0, 0), -1);
        s->pend_n[0] = 0;
    }
    if (++s->leaf == d->n_out) {
        s->leaf = 0;
        s->in++;
    }
    return BW_OK;
}

bw_status_t bw_stream_finish(bw_stream_t *s, size_t *len)
{
    if (!s || !len)
        return BW_ERR_ARG;
    *len = 0;
    if (s->err != BW_OK)
        return s->err;
    if (s->pushed != (size_t)s->dims.n_in * s->dims.n_out)
        return s->err = BW_ERR_ARG; /* fewer spectra than the shape holds */
    size_t body = bw_strip_enc_finish(&s->se);
    bw_plan_t pl;
    stream_plan(s, &pl);
    /* the header's room was kept at init */
    size_t hl = bw_header_write(s->out, &pl, &s->params, s->params.mode);
    if (bw_strip_enc_overflow(&s->se) || hl + body + BW_TRAILER_SIZE > UINT32_MAX)
        return s->err = BW_ERR_OUTPUT_FULL;
    bw_put_u32(s->out + hl + body, bw_crc32(s->out, hl + body));
    *len = hl + body + BW_TRAILER_SIZE;
    s->err = BW_ERR_ARG; /* finished: no more pushes */
    return BW_OK;
}
