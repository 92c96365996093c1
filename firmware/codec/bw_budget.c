/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The byte budget (BW_MODE_BYTES): the finest quantiser whose payload fits.
 *
 * The exact coding first (it may fit); then the step, 32 steps per octave
 * and by bisection on the step itself; then the rounding offset, which fills
 * what the step leaves; or, where even the coarsest step leaves too much,
 * the vector threshold. Every try codes the whole measurement without
 * writing it (bw_encode_pass with no output) to learn its size, and every
 * search is one bisection between a value that fits and one that does not
 * (bisect); the payload grows with the offset and shrinks with the step
 * and the threshold.
 */
#include <string.h>

#include "bw_internal.h"

#define STEP_FRAC 32u        /* 32 steps per octave                            */
#define STEP_T_MAX (24u * STEP_FRAC)
#define STEP_REFINE 16384u   /* then bisection on the step to 1/16384 of it    */
#define ROUND_MAX_Q8 32u     /* then the rounding offset, up to 1/8 of a step  */
#define ROUND_WIDE_Q8 128u   /* or 1/2, where 1/8 leaves the budget unfilled   */
#define ROUND_FILL 128u      /* when the payload is more than 1/128 under      */
#define VEC_THRESH_MAX_LOG2 16u /* a budget may raise the threshold to 2^16 steps */

/* 256 * 2^(t / 32), t = 0..768: the step of index t, Q24.8 */
static uint32_t step_of(unsigned t)
{
    uint64_t s = bw_oct32(BW_STEP_ONE_Q8, t);
    return s > UINT32_MAX ? UINT32_MAX : (uint32_t)s;
}

/* The budget of a request and an output of cap bytes. */
static size_t budget_of(const bw_params_t *pa, size_t cap)
{
    return pa->byte_budget < cap ? pa->byte_budget : cap;
}

/* BW_EFFORT_FAST's landing: a payload of at least this many bytes (within
 * 1 % under the budget) ends its encodes and its search. */
static size_t landing(size_t budget) { return budget - budget / 100u; }

/* What one encode with one basis needs to try a setting. */
typedef struct {
    bw_plan_t *pl;
    const bw_params_t *pa;
    const int32_t *samples;
    int32_t *work;
    bw_ctx_t *ctx;
    size_t budget;
    size_t near; /* > 0: a search may stop at a payload that fits in near or more bytes */
#if BW_CFG_FAST_BUDGET
    uint8_t *out; /* with near: each try written here (budget bytes), else counted */
    size_t last;  /* the size of the last try */
#endif
} budget_t;

/* The size of the BYTES payload at the plan's current settings; with b->out
 * also written there where it fits the budget (a size above it: not). */
static bw_status_t count_bytes(budget_t *b, size_t *sz)
{
#if BW_CFG_FAST_BUDGET
    *sz = SIZE_MAX; /* (an output too small for the header: too much) */
    bw_status_t st = bw_encode_pass(b->pl, b->pa, BW_MODE_BYTES, b->samples, b->work, b->ctx,
                                    b->out, b->out ? b->budget : 0u, sz);
    b->last = *sz;
    return st == BW_ERR_OUTPUT_FULL && b->out && *sz > b->budget ? BW_OK : st;
#else
    return bw_encode_pass(b->pl, b->pa, BW_MODE_BYTES, b->samples, b->work, b->ctx, NULL, 0, sz);
#endif
}

/* The try before landed: within the budget, near or more bytes. */
static bool landed(const budget_t *b, size_t sz)
{
    return BW_CFG_FAST_BUDGET && b->near && sz <= b->budget && sz >= b->near;
}

/* The settings a search moves: value t of each. */
enum { SET_VEC, SET_STEP_T, SET_STEP, SET_ROUND_T, SET_ROUND, SET_CUT };

/* aux: SET_VEC the threshold t shifts (2^t of it), SET_ROUND_T the number of
 * samples n (t = round n + cut) */
static void set(bw_plan_t *pl, unsigned what, uint32_t t, uint32_t aux)
{
    switch (what) {
    case SET_VEC:
        pl->vec_thresh_q8 = aux > (UINT32_MAX >> t) ? UINT32_MAX : aux << t;
        break;
    case SET_STEP_T:
        pl->step_q8 = step_of(t);
        break;
    case SET_STEP:
        pl->step_q8 = t;
        break;
    case SET_ROUND_T:
        pl->round_q8 = t / aux;
        pl->round_cut = t % aux;
        break;
    case SET_ROUND:
        pl->round_q8 = t;
        break;
    default: /* SET_CUT */
        pl->round_cut = t;
        break;
    }
}

/* Bisection on a setting between *lo and *hi, of which one fits the budget:
 * *lo when `up` (the payload grows with t), else *hi. Narrows them to
 * neighbours, or with `fine` only to within 1/STEP_REFINE of *hi. The
 * setting is left at the last value tried. */
static bw_status_t bisect(budget_t *b, unsigned what, uint32_t aux, bool up, bool fine,
                          uint32_t *lo, uint32_t *hi)
{
    while (*hi - *lo > 1u && (!fine || (uint64_t)(*hi - *lo) * STEP_REFINE > *hi)) {
        uint32_t mid = *lo + (*hi - *lo) / 2u;
        size_t sz;
        set(b->pl, what, mid, aux);
        bw_status_t st = count_bytes(b, &sz);
        if (st != BW_OK)
            return st;
        if ((sz <= b->budget) == up)
            *lo = mid;
        else
            *hi = mid;
        if (landed(b, sz))
            return BW_OK; /* near enough: the fitting end is mid */
    }
    return BW_OK;
}

/* The exact coding, if it fits, else the two neighbouring steps of 32 per
 * octave around the budget (*lo_s leaves too much, *hi_s fits); or, where
 * even the coarsest step leaves too much, the vector threshold. *done: the
 * payload is written. */
static BW_ALWAYS_INLINE bw_status_t coarse(budget_t *b, uint8_t *out, size_t *len,
                                           bool *done, uint32_t *lo_s, uint32_t *hi_s)
{
    bw_plan_t *pl = b->pl;
    size_t sz;
    *done = true;
    /* the exact coding first: if it fits, nothing is lost, and the payload
     * is the lossless one */
    pl->step_q8 = BW_STEP_ONE_Q8;
    bw_status_t st = bw_encode_pass(pl, b->pa, BW_MODE_LOSSLESS, b->samples, b->work, b->ctx,
                                    NULL, 0, &sz);
    if (st != BW_OK)
        return st;
    if (sz <= b->budget)
        return bw_encode_pass(pl, b->pa, BW_MODE_LOSSLESS, b->samples, b->work, b->ctx, out,
                              b->budget, len);
    uint32_t lo = 0, hi = STEP_T_MAX;
    pl->step_q8 = step_of(hi);
    st = count_bytes(b, &sz);
    if (st != BW_OK)
        return st;
    if (sz > b->budget) {
        /* even the coarsest step leaves too much: then, at that step, the
         * smallest vector threshold (2, 4, .. 65536 steps) that fits; the
         * largest drops every vector with more than one band */
        uint32_t vt0 = pl->vec_thresh_q8, lo_i = 0, hi_i = VEC_THRESH_MAX_LOG2 + 1u;
        st = bisect(b, SET_VEC, vt0, false, false, &lo_i, &hi_i); /* hi_i fits, if any does */
        if (st != BW_OK)
            return st;
        if (hi_i > VEC_THRESH_MAX_LOG2)
            return BW_ERR_BUDGET;
        set(pl, SET_VEC, hi_i, vt0);
        return bw_encode_pass(pl, b->pa, BW_MODE_BYTES, b->samples, b->work, b->ctx, out,
                              b->budget, len);
    }
    st = bisect(b, SET_STEP_T, 0, false, false, &lo, &hi);
    *lo_s = step_of(lo);
    *hi_s = step_of(hi);
    *done = false;
    return st;
}

/* The search; from the steps bracket[0] (too much; BW_STEP_ONE_Q8: not
 * known) and bracket[1] (fits; UINT32_MAX: not known) when bracket is
 * given, stopping at the first payload within 1 % under the budget
 * (BW_EFFORT_FAST after its encodes). */
static bw_status_t search(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                          int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len,
                          const uint32_t *bracket)
{
    size_t sz, budget = budget_of(pa, cap);
    bw_status_t st;
    bracket = BW_CFG_FAST_BUDGET ? bracket : NULL;
    budget_t b = {.pl = pl, .pa = pa, .samples = samples, .work = work, .ctx = ctx,
                  .budget = budget, .near = bracket ? landing(budget) : 0u};
#if BW_CFG_FAST_BUDGET
    /* after BW_EFFORT_FAST's encodes each try is written: the first that
     * lands is the payload */
    b.out = bracket ? out : NULL;
    b.last = SIZE_MAX;
#endif
    uint32_t lo_s = bracket ? bracket[0] : 0u, hi_s = bracket ? bracket[1] : 0u;
    /* one side of the bracket only: widen it by an eighth of the step at a
     * time (up to 8 encodes) */
    for (unsigned k = 0; bracket && k < 8u && (lo_s <= BW_STEP_ONE_Q8 || hi_s == UINT32_MAX);
         k++) {
        bool up = hi_s == UINT32_MAX;
        uint32_t t = up ? lo_s + lo_s / 8u : hi_s - hi_s / 8u;
        if ((up && t < lo_s) || t <= BW_STEP_ONE_Q8)
            break;
        pl->step_q8 = t;
        st = count_bytes(&b, &sz);
        if (st != BW_OK || landed(&b, sz)) {
            *len = sz;
            return st;
        }
        if (sz <= b.budget)
            hi_s = t;
        else
            lo_s = t;
    }
    if (!bracket || lo_s <= BW_STEP_ONE_Q8 || hi_s == UINT32_MAX) {
        bool done;
        b.near = 0u; /* the whole search, as BW_EFFORT_BEST's */
#if BW_CFG_FAST_BUDGET
        b.out = NULL;
#endif
        st = coarse(&b, out, len, &done, &lo_s, &hi_s);
        if (st != BW_OK || done)
            return st;
    }
    /* then on the step itself, down to 1/16384 of it: at 32 steps per
     * octave the payload still jumps by about 2 % from step to step, and
     * small payloads (a few hundred bytes) move by a few bytes at a time */
#if BW_CFG_FAST_BUDGET
    b.last = SIZE_MAX;
#endif
    st = bisect(&b, SET_STEP, 0, false, true, &lo_s, &hi_s);
    if (st != BW_OK)
        return st;
#if BW_CFG_FAST_BUDGET
    if (landed(&b, b.last)) { /* the last try's payload is written */
        *len = b.last;
        return st;
    }
#endif
    pl->step_q8 = hi_s;
    /* then the quantiser's rounding offset, 0 .. 1/8 of a step: the size
     * jumps at some steps (similar coefficients cross a power of two
     * together), and rounding up more of them fills the budget by smaller
     * amounts. Within 1/8 of a step every coefficient it rounds up ends
     * nearer its reconstruction (at 3/8 of the interval above) than before. */
    st = count_bytes(&b, &sz);
    if (st != BW_OK)
        return st;
    if (landed(&b, sz)) {
        *len = sz;
        return BW_OK;
    }
    if (sz < b.budget - b.budget / ROUND_FILL) {
        /* t = r n + c: the offset r / 256 for every coefficient, and
         * (r + 1) / 256 for the first c of them, band by band (coarse to
         * fine), each band in the quantiser's order of vectors: so that the
         * last few bytes fill by single coefficients where a whole step of
         * r would add too many (many coefficients just below a step) */
        uint32_t n = (uint32_t)pl->n, lo_t = 0; /* n <= BW_MAX_SAMPLES; lo_t fits */
        uint32_t max_t = n > UINT32_MAX / ROUND_MAX_Q8 ? UINT32_MAX : ROUND_MAX_Q8 * n;
        uint32_t hi_t = max_t;
        st = bisect(&b, SET_ROUND_T, n, true, false, &lo_t, &hi_t);
        if (st != BW_OK)
            return st;
        set(pl, SET_ROUND_T, lo_t, n);
#if BW_CFG_BUDGET_FILL_HALF
        /* all of that fits and the payload is still short: the step jumped
         * where integer coefficients of a few units (data coded nearly
         * exactly, at a step just above 1) fell a level together, and no
         * step between the exact coding and that one exists. An offset up
         * to 1/2 of a step takes them back, most to their exact value (the
         * reconstruction is an integer): the error falls as the budget
         * grows (tests/unit/test_codec.c). */
        if (lo_t + 1u == max_t) {
            uint32_t r = pl->round_q8, r_hi = ROUND_WIDE_Q8 + 1u, c = 0, c_hi = n;
            pl->round_cut = 0;
            st = bisect(&b, SET_ROUND, 0, true, false, &r, &r_hi);
            pl->round_q8 = r;
            if (st == BW_OK && r < ROUND_WIDE_Q8)
                st = bisect(&b, SET_CUT, 0, true, false, &c, &c_hi);
            if (st != BW_OK)
                return st;
            pl->round_cut = c;
        }
#endif
    }
    return bw_encode_pass(pl, pa, BW_MODE_BYTES, samples, work, ctx, out, b.budget, len);
}

bw_status_t bw_budget_encode(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                             int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len)
{
    return search(pl, pa, samples, work, ctx, out, cap, len, NULL);
}

/* ---- BW_EFFORT_FAST ---------------------------------------------------------
 *
 * The bits at a base step 2^(t / 4) are estimated from the histogram of the
 * coefficients against their steps (bw_quant_hist), taken once: each
 * coefficient at or above its step costs about A0 + A1 log2(|c| / step)
 * bits, and the zeros A2 times the binary entropy of the share of non-zero
 * ones (constants fitted on measured sizes of the benchmark's sets; the
 * coder's contexts make the real size differ from that by a few percent,
 * more or less by data set). Each encode then aims at 99.5 % of the budget
 * with the estimate scaled by what the encodes before it measured (from the
 * third on, the secant through the two before), writing the payload as it
 * goes: the first that lands within 1 % under the budget is the payload;
 * after FAST_PASSES, the search from the steps they tried (the largest that
 * left too much, the smallest that fit; widened by an eighth at a time where
 * they all left too much or all too little) to the first payload within 1 %
 * under, and only where that falls short, the whole search. Against the
 * search above, one to four encodes instead of fifteen to twenty where they
 * land, for a payload up to 1 % smaller and no rounding fill. */

#define EST_A0_Q6 186u /* 2.90 bits per non-zero coefficient, 1/64 bit  */
#define EST_A1_Q6 16u  /* 0.99 bit per octave of |c| / step, per quarter */
#define EST_A2_Q8 65u  /* 0.254 of the entropy of the non-zero share     */
#define EST_T_LOSSLESS (-15) /* every bin but the zeros */
#define FAST_PASSES 4u
#define EST_PRIOR_Q12 4342u /* the real sizes run about 6 % above the estimate */

/* binary entropy h(i / 64), 1/64 bit, i = 0..64 */
static const uint8_t h64[65] = {
    0,  8,  13, 17, 21, 24, 27, 30, 33, 35, 38, 40, 42, 44, 46, 47, 49, 50, 52, 53, 54, 55,
    57, 58, 59, 60, 60, 61, 62, 62, 63, 63, 64, 63, 63, 62, 62, 61, 60, 60, 59, 58, 57, 55,
    54, 53, 52, 50, 49, 47, 46, 44, 42, 40, 38, 35, 33, 30, 27, 24, 21, 17, 13, 8,  0};

/* The estimated bits at the base step 2^(t / 4), t >= EST_T_LOSSLESS. */
static uint64_t est_bits(const uint32_t *hist, int t)
{
    uint64_t n = hist[0], nz = 0, mag = 0;
    for (unsigned bin = 1; bin < BW_HIST_BINS; bin++) {
        n += hist[bin];
        int x = (int)bin - (int)BW_HIST_ZERO_BIN - t;
        if (x >= 0) {
            nz += hist[bin];
            mag += (uint64_t)hist[bin] * (unsigned)x;
        }
    }
    uint64_t share = n ? nz * 64u / n : 0u;
    return (nz * EST_A0_Q6 + mag * EST_A1_Q6 + (n * h64[share] * EST_A2_Q8 >> 8)) / 64u;
}

/* The same at step index t (32 per octave, step_of), interpolated between
 * quarter octaves, times ratio_q12 / 4096. */
static uint64_t est_at(const uint32_t *hist, unsigned t, uint64_t ratio_q12)
{
    unsigned q = t / 8u, f = t % 8u;
    uint64_t a = est_bits(hist, (int)q), b = est_bits(hist, (int)q + 1);
    uint64_t e = a - (a > b ? (a - b) * f / 8u : 0u);
    return e * ratio_q12 / 4096u;
}

/* The step (Q8) whose estimate meets bits: the step indices t - 1 and t
 * around it (the estimate falls as t grows), then linearly between their
 * steps; 0 if even the coarsest step leaves more. */
static uint32_t est_step(const uint32_t *hist, uint64_t ratio_q12, uint64_t bits)
{
    unsigned lo = 0, hi = STEP_T_MAX;
    if (est_at(hist, hi, ratio_q12) > bits)
        return 0;
    while (lo < hi) {
        unsigned mid = (lo + hi) / 2u;
        if (est_at(hist, mid, ratio_q12) <= bits)
            hi = mid;
        else
            lo = mid + 1u;
    }
    if (lo == 0u)
        return step_of(0) + 1u;
    uint64_t a = est_at(hist, lo - 1u, ratio_q12), b = est_at(hist, lo, ratio_q12);
    uint32_t s0 = step_of(lo - 1u), s1 = step_of(lo);
    uint64_t f = a > b ? (a - bits) * 256u / (a - b) : 256u;
    return s0 + (uint32_t)((uint64_t)(s1 - s0) * f / 256u);
}

#if BW_RATE
/* ---- one encode that meets the budget as it codes ----------------------------
 *
 * The quantiser runs ahead of the coder a chunk of vectors at a time
 * (struct bw_rate), each chunk at a step of its own that the payload
 * records (BW_EXT_CHUNK_STEPS): the header's step (the estimate's for the
 * budget) changed by d/32 of an octave. The estimate gives each chunk's
 * bits at the header's step (bw_quant_est: the coefficients at or above
 * the step alone; a term for the zeros' share, as the histogram's
 * estimate has, follows the coder's bits from chunk to chunk less closely)
 * and how the bits follow the step (gamma, octaves of bits per octave of
 * step, from the histogram's estimate an octave apart). Before each chunk,
 * the bits coded so far and the ratio of coded to estimated bits of the
 * chunks before (each estimate at its chunk's step; the estimate's own
 * ratio weighing a quarter of the whole at first; the first chunk left
 * out, as it also pays for the models' learning) say what the chunks left
 * will cost, and the chunk takes the d that brings the whole to the bits
 * aimed at (the middle of the landing), within RATE_D_SLEW of the chunk
 * before: a step that varies costs quality. Where the payload does not
 * land, the encodes below take over. */

#define RATE_D_MAX 96         /* chunk steps within 3 octaves of the header's     */
#define RATE_D_SLEW 8         /* and within 1/4 octave of the chunk before        */
#define RATE_GAMMA_MIN 26     /* gamma, Q8: 0.1 to 2.5 octaves of bits per octave */
#define RATE_GAMMA_MAX 640    /* gamma RATE_D_MAX / 256 within 256: at_step       */
#define RATE_PRIOR_SHIFT 2    /* the estimate's ratio weighs 1/4 of its bits      */
#define RATE_CHUNK_BYTES 256u /* a chunk (a byte of the record) per 256 bytes of  */
#define RATE_CHUNKS_MIN 8u    /* budget, 8 to BW_RATE_CHUNKS chunks               */
#define RATE_BUDGET_MIN 512u  /* bytes                                            */

/* The quarter octave nearest step s (Q8), 2^(t4 / 4) */
static int quarter_of(uint32_t s)
{
    int t4 = 0;
    while (t4 < (int)(STEP_T_MAX / 8u) && step_of(8u * (unsigned)(t4 + 1)) <= s)
        t4++;
    if (t4 < (int)(STEP_T_MAX / 8u) &&
        step_of(8u * (unsigned)(t4 + 1)) - s < s - step_of(8u * (unsigned)t4))
        t4++;
    return t4;
}

/* bits scaled as a step change of d 1/32 octaves moves them: 2^(-gamma d / 32) */
static uint64_t at_step(uint64_t bits, int32_t gamma_q8, int d)
{
    /* gamma_q8 <= RATE_GAMMA_MAX, |d| <= RATE_D_MAX: the exponent within +-256 */
    unsigned t = (unsigned)(256 - gamma_q8 * d / 256); /* 2^(t / 32) / 2^8 */
    return bits * bw_oct32(1u << 12, t) >> 20;
}

void bw_rate_chunk(struct bw_rate *r, uint64_t bits, uint32_t v)
{
    bw_plan_t *pl = r->pl;
    while (r->ahead < v && r->chunk < r->chunks) {
        uint32_t g = r->chunk;
        int d0 = g ? r->d[g - 1u] : 0, d = d0;
        if (g > 0u) {
            /* the ratio of the chunks before (the first left out) */
            if (g > 1u) {
                r->b_sum += bits - r->bits_seen;
                r->e_sum += r->est_done - r->est_seen;
            }
            r->bits_seen = bits;
            r->est_seen = r->est_done;
            /* the chunks left at that ratio, and the d that makes them
             * aim - bits: 2^(-gamma d / 32) = (aim - bits) / need */
            uint64_t rho_q16 = (r->b_sum << 16) / (r->e_sum ? r->e_sum : 1u);
            uint64_t need = rho_q16 * r->est_left >> 16; /* (bits below 2^35: in 64 bits) */
            if (bits >= r->aim) {
                d = RATE_D_MAX;
            } else if (need > 0u) {
                uint32_t left = (uint32_t)(r->aim - bits > UINT32_MAX ? UINT32_MAX : r->aim - bits);
                uint32_t nd = (uint32_t)(need > UINT32_MAX ? UINT32_MAX : need);
                int64_t l_q16 = (int64_t)bw_log2_q16(nd) - (int64_t)bw_log2_q16(left);
                d = (int)((l_q16 * 32 * 256 / r->gamma_q8 + (l_q16 < 0 ? -32768 : 32768)) / 65536);
            }
            d = d > d0 + RATE_D_SLEW ? d0 + RATE_D_SLEW : d < d0 - RATE_D_SLEW ? d0 - RATE_D_SLEW : d;
            d = d > RATE_D_MAX ? RATE_D_MAX : d < -RATE_D_MAX ? -RATE_D_MAX : d;
        }
        r->d[g] = (int8_t)d;
        pl->step_q8 = bw_chunk_step(r->step_q8, d);
        bw_quant_ahead(pl, &r->qw, r->x, pl->chunk_vec);
        pl->step_q8 = r->step_q8;
        r->ahead += pl->chunk_vec;
        r->est_left -= r->est[g] < r->est_left ? r->est[g] : r->est_left;
        r->est_done += at_step(r->est[g], r->gamma_q8, d);
        r->chunk++;
    }
    if (r->ahead < v)
        r->ahead = v; /* past the last chunk: nothing is left to quantise */
}

/* Whether the body of this plan is coded by bw_code_body's loops, which
 * ask for each vector before they read it (coarse-to-fine order, one body,
 * not Rice strips), in at least RATE_CHUNKS_MIN chunks, for a budget of at
 * least RATE_BUDGET_MIN bytes (below, the record's bytes and the few
 * chunks leave too little to steer by). */
static bool rate_applies(const bw_plan_t *pl, const bw_params_t *pa, size_t budget)
{
    return BW_CFG_FAST_STRIPS && !pl->stream && !pl->seg_vec && !(pa->flags & BW_FLAG_RICE) &&
           pl->basis != BW_BASIS_PRED && budget >= RATE_BUDGET_MIN &&
           (uint64_t)pl->dims.n_in * pl->dims.n_out >= RATE_CHUNKS_MIN;
}

/* The encode at step s with the rate r (in the context) into a
 * payload of at most budget bytes, from the coefficients in work
 * (transformed, not quantised) and their histogram hist (which r
 * overwrites). BW_ERR_BUDGET: the body did not ask for every vector. */
static bw_status_t rate_encode(bw_plan_t *pl, const bw_params_t *pa, int32_t *work, bw_ctx_t *ctx,
                               uint8_t *out, size_t budget, size_t *len, struct bw_rate *r,
                               const uint32_t *hist, uint32_t s, uint32_t *s_eff)
{
    const bw_dims_t *dm = &pl->dims;
    int t4 = quarter_of(s);
    /* gamma: the estimate's bits at the step and an octave above */
    uint64_t e0 = est_bits(hist, t4), e1 = est_bits(hist, t4 + 4);
    int32_t gamma_q8 = e1 && e0 > e1
                           ? (int32_t)((bw_log2_q16(e0 > UINT32_MAX ? UINT32_MAX : (uint32_t)e0) -
                                        bw_log2_q16(e1 > UINT32_MAX ? UINT32_MAX : (uint32_t)e1)) >>
                                       8)
                           : 256;
    r->gamma_q8 = gamma_q8 < RATE_GAMMA_MIN   ? RATE_GAMMA_MIN
                  : gamma_q8 > RATE_GAMMA_MAX ? RATE_GAMMA_MAX
                                              : gamma_q8;
    /* chunks: one per RATE_CHUNK_BYTES of the budget, whole incoming blocks
     * of one band (their steps then one per block) */
    uint32_t vecs = dm->n_in * dm->n_out, cmax = (uint32_t)(budget / RATE_CHUNK_BYTES), K;
    cmax = cmax < RATE_CHUNKS_MIN ? RATE_CHUNKS_MIN : cmax > BW_RATE_CHUNKS ? BW_RATE_CHUNKS : cmax;
    if (dm->bands == 1u && dm->n_in >= cmax)
        K = dm->n_out * ((dm->n_in - 1u) / cmax + 1u);
    else
        K = (vecs - 1u) / cmax + 1u;
    r->chunks = (vecs - 1u) / K + 1u;
    memset(r->d, 0, sizeof r->d);
    pl->chunk_vec = K;
    pl->chunk_d = r->d;
    pl->step_q8 = s;
    size_t over = bw_header_write(NULL, pl, pa, BW_MODE_BYTES) + BW_TRAILER_SIZE;
    if (budget <= over + 8u)
        return BW_ERR_BUDGET;
    r->aim = (uint64_t)(budget - budget / 200u - over) * 8u;
    r->pl = pl;
    r->x = work;
    r->step_q8 = s;
    bw_qwalk_init(&r->qw);
    r->ahead = 0;
    r->chunk = 0;
    memset(r->est, 0, sizeof r->est);
    bw_quant_est(pl, work, K, t4, EST_A0_Q6, EST_A1_Q6, r->est);
    r->est_left = 0;
    for (unsigned g = 0; g < r->chunks; g++)
        r->est_left += r->est[g];
    r->est_done = 0;
    r->bits_seen = 0;
    r->est_seen = 0;
    /* the estimate's own ratio (the header's step was its choice), as if
     * of chunks of a quarter of its bits */
    r->e_sum = (r->est_left >> RATE_PRIOR_SHIFT) + 1u;
    r->b_sum = r->aim >> RATE_PRIOR_SHIFT;
    pl->rate = r;
    bw_status_t st = bw_encode_code(pl, pa, BW_MODE_BYTES, work, ctx, out, budget, len);
    pl->rate = NULL;
    /* the chunks' steps' mean, each weighing its estimate */
    uint64_t ew = 0;
    int64_t dw = 0;
    for (unsigned g = 0; g < r->chunks; g++) {
        ew += r->est[g];
        dw += (int64_t)r->est[g] * r->d[g];
    }
    *s_eff = bw_chunk_step(s, ew ? (int)(dw / (int64_t)ew) : 0);
    /* every vector quantised before it was coded, or the body is not one */
    if (st == BW_OK && r->qw.i < dm->n_in)
        return BW_ERR_BUDGET;
    return st;
}
#endif

#if BW_RATE
/* The estimate (its factor 1) at the step index nearest step s */
static uint64_t est_near(const uint32_t *hist, uint32_t s)
{
    unsigned t = 0;
    while (t < STEP_T_MAX && step_of(t + 1u) <= s)
        t++;
    return est_at(hist, t, 4096u);
}
#endif

/* What bw_ctx_t.budget holds: the histogram, then the rate. */
typedef union {
    uint32_t hist[BW_HIST_BINS];
#if BW_RATE
    struct bw_rate rate;
#endif
} budget_mem_t;
_Static_assert(sizeof(budget_mem_t) <= sizeof(((bw_ctx_t *)0)->budget), "bw_ctx_t.budget");

/* The encodes of BW_EFFORT_FAST: BW_OK with the payload in out, or
 * BW_ERR_BUDGET where none landed (the search's turn), or an error. */
static bw_status_t fast_passes(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                               int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t budget,
                               size_t *len, uint32_t bracket[2])
{
    bracket[0] = BW_STEP_ONE_Q8; /* the largest step that left too much */
    bracket[1] = UINT32_MAX;     /* the smallest that fit */
    /* the histogram, and the one encode's rate in its place, in the
     * context (off the stack, which the rate's quantiser deepens) */
    budget_mem_t *u = (budget_mem_t *)(void *)ctx->budget;
    uint32_t *hist = u->hist;
    pl->step_q8 = step_of(STEP_T_MAX / 2u);
    size_t over = bw_header_write(NULL, pl, pa, BW_MODE_BYTES) + BW_TRAILER_SIZE;
    if (budget <= over + 8u)
        return BW_ERR_BUDGET;
    uint64_t aim = (uint64_t)(budget - over) * 8u * 199u / 200u, ratio = EST_PRIOR_Q12;
    bw_status_t st = bw_encode_prepare(pl, samples, work);
    if (st != BW_OK)
        return st;
    bw_quant_hist(pl, work, hist);
    /* the exact coding first, where it may fit (the estimate of the exact
     * coding is the roughest); later, where the encodes ask for the finest
     * step */
    bool exact_tried = est_bits(hist, EST_T_LOSSLESS) * EST_PRIOR_Q12 / 4096u <= aim * 5u / 4u;
#if BW_RATE
    /* with the rate, only where the step it would take is within a quarter
     * of the exact coding's (else later, where the encodes ask for it) */
    uint32_t s_rate = rate_applies(pl, pa, budget) ? est_step(hist, ratio, aim) : 0u;
    if (s_rate > BW_STEP_ONE_Q8 + BW_STEP_ONE_Q8 / 4u)
        exact_tried = false;
#endif
    if (exact_tried) {
        pl->step_q8 = BW_STEP_ONE_Q8;
        st = bw_encode_code(pl, pa, BW_MODE_LOSSLESS, work, ctx, out, budget, len);
        if (st != BW_ERR_OUTPUT_FULL)
            return st;
    }
    /* the last two encodes: step and body bits */
    int64_t s1 = 0, l1 = 0, s2 = 0, l2 = 0;
#if BW_RATE
    if (s_rate > BW_STEP_ONE_Q8 + 1u) {
        /* one encode that steers its chunks' steps as it codes */
        uint32_t s_eff;
        st = rate_encode(pl, pa, work, ctx, out, budget, len, &u->rate, hist, s_rate, &s_eff);
        pl->chunk_vec = 0; /* the payload, if any, is written */
        pl->chunk_d = NULL;
        if (st == BW_OK && *len >= landing(budget))
            return BW_OK;
        if (st != BW_OK && st != BW_ERR_OUTPUT_FULL && st != BW_ERR_BUDGET)
            return st;
        /* short of it or over: the encodes below, from the start, the
         * estimate scaled by what this one measured at its chunks' mean
         * step */
        bool measured = st != BW_ERR_BUDGET && *len > over;
        st = bw_encode_prepare(pl, samples, work);
        if (st != BW_OK)
            return st;
        bw_quant_hist(pl, work, hist);
        if (measured) {
            uint64_t body = (*len - over) * 8u, e = est_near(hist, s_eff);
            if (e) {
                ratio = body * 4096u / e;
                ratio = ratio ? ratio : 1u;
            }
        }
    }
#endif
    for (unsigned pass = 0; pass < FAST_PASSES; pass++) {
        uint32_t s = est_step(hist, ratio, aim);
        if (s == 0u)
            break; /* the coarsest step leaves too much: the search's threshold */
        if (pass >= 2u && l1 != l2 && s1 != s2) {
            /* the secant through the two encodes before, where the
             * estimate's own slope would limit the ratio's correction
             * (its slope in Q16, within +-16: no overflow) */
            int64_t k_q16 = ((int64_t)aim - l2) * 65536 / (l2 - l1);
            k_q16 = k_q16 > (16 << 16) ? (16 << 16) : k_q16 < -(16 << 16) ? -(16 << 16) : k_q16;
            int64_t t = s2 + (s2 - s1) * k_q16 / 65536;
            if (t > (int64_t)BW_STEP_ONE_Q8 && t <= (int64_t)step_of(STEP_T_MAX))
                s = (uint32_t)t;
        }
        if (s <= BW_STEP_ONE_Q8 + 1u)
            s = BW_STEP_ONE_Q8 + 1u;
        if (pass) {
            st = bw_encode_prepare(pl, samples, work);
            if (st != BW_OK)
                return st;
        }
        if (s == BW_STEP_ONE_Q8 + 1u && !exact_tried) {
            exact_tried = true;
            pl->step_q8 = BW_STEP_ONE_Q8;
            st = bw_encode_code(pl, pa, BW_MODE_LOSSLESS, work, ctx, out, budget, len);
            if (st != BW_ERR_OUTPUT_FULL)
                return st;
        }
        pl->step_q8 = s;
        bw_quantise(pl, work, true);
        st = bw_encode_code(pl, pa, BW_MODE_BYTES, work, ctx, out, budget, len);
        if (st == BW_OK && *len >= landing(budget))
            return BW_OK;
        if (st != BW_OK && st != BW_ERR_OUTPUT_FULL)
            return st;
        if (st == BW_OK && s < bracket[1])
            bracket[1] = s;
        else if (st != BW_OK && s > bracket[0])
            bracket[0] = s;
        /* the estimate was off by what this encode measured */
        uint64_t body = (*len > over ? *len - over : 1u) * 8u;
        s1 = s2;
        l1 = l2;
        s2 = s;
        l2 = (int64_t)body;
        ratio = ratio * body / aim;
        if (ratio == 0u)
            ratio = 1u;
    }
    return BW_ERR_BUDGET;
}

bw_status_t bw_budget_encode_fast(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                                  int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap,
                                  size_t *len)
{
    size_t budget = budget_of(pa, cap);
    uint32_t bracket[2], round_q8 = pl->round_q8, vec_thresh_q8 = pl->vec_thresh_q8;
    bw_status_t st = fast_passes(pl, pa, samples, work, ctx, out, budget, len, bracket);
    if (st != BW_ERR_BUDGET)
        return st;
    pl->step_q8 = BW_STEP_ONE_Q8;
    /* the search from the steps the encodes tried, to the first payload
     * within 1 % under (widening the bracket where they all left too much,
     * or all too little); else the whole search */
    bool tried = (bracket[0] > BW_STEP_ONE_Q8 || bracket[1] != UINT32_MAX) &&
                 bracket[0] < bracket[1];
    if (tried) {
        st = search(pl, pa, samples, work, ctx, out, cap, len, bracket);
        if (st != BW_OK || *len >= landing(budget))
            return st;
        /* short of it (a payload of a few hundred bytes, where single
         * coefficients move it by more than 1 %): the whole search */
        pl->step_q8 = BW_STEP_ONE_Q8;
        pl->round_q8 = round_q8;
        pl->round_cut = 0;
        pl->vec_thresh_q8 = vec_thresh_q8;
    }
    return search(pl, pa, samples, work, ctx, out, cap, len, NULL);
}
