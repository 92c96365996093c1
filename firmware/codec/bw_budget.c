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
    static const uint16_t frac_q15[STEP_FRAC] = {
        32768, 33486, 34219, 34968, 35734, 36516, 37316, 38133, 38968, 39821, 40693,
        41584, 42495, 43425, 44376, 45348, 46341, 47356, 48393, 49452, 50535, 51642,
        52773, 53928, 55109, 56316, 57549, 58809, 60097, 61413, 62757, 64132,
    };
    uint64_t s = ((uint64_t)BW_STEP_ONE_Q8 << (t / STEP_FRAC)) * frac_q15[t % STEP_FRAC] >> 15;
    return s > UINT32_MAX ? UINT32_MAX : (uint32_t)s;
}

/* What one encode with one basis needs to try a setting. */
typedef struct {
    bw_plan_t *pl;
    const bw_params_t *pa;
    const int32_t *samples;
    int32_t *work;
    bw_ctx_t *ctx;
    size_t budget;
} budget_t;

/* The size of the BYTES payload at the plan's current settings. */
static bw_status_t count_bytes(const budget_t *b, size_t *sz)
{
    return bw_encode_pass(b->pl, b->pa, BW_MODE_BYTES, b->samples, b->work, b->ctx, NULL, 0, sz);
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
static bw_status_t bisect(const budget_t *b, unsigned what, uint32_t aux, bool up, bool fine,
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
    }
    return BW_OK;
}

bw_status_t bw_budget_encode(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                             int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len)
{
    size_t sz;
    bw_status_t st;
    budget_t b = {pl, pa, samples, work, ctx, pa->byte_budget < cap ? pa->byte_budget : cap};
    /* the exact coding first: if it fits, nothing is lost, and the payload
     * is the lossless one */
    pl->step_q8 = BW_STEP_ONE_Q8;
    st = bw_encode_pass(pl, pa, BW_MODE_LOSSLESS, samples, work, ctx, NULL, 0, &sz);
    if (st != BW_OK)
        return st;
    if (sz <= b.budget)
        return bw_encode_pass(pl, pa, BW_MODE_LOSSLESS, samples, work, ctx, out, b.budget, len);
    uint32_t lo = 0, hi = STEP_T_MAX;
    pl->step_q8 = step_of(hi);
    st = count_bytes(&b, &sz);
    if (st != BW_OK)
        return st;
    if (sz > b.budget) {
        /* even the coarsest step leaves too much: then, at that step, the
         * smallest vector threshold (2, 4, .. 65536 steps) that fits; the
         * largest drops every vector with more than one band */
        uint32_t vt0 = pl->vec_thresh_q8, lo_i = 0, hi_i = VEC_THRESH_MAX_LOG2 + 1u;
        st = bisect(&b, SET_VEC, vt0, false, false, &lo_i, &hi_i); /* hi_i fits, if any does */
        if (st != BW_OK)
            return st;
        if (hi_i > VEC_THRESH_MAX_LOG2)
            return BW_ERR_BUDGET;
        set(pl, SET_VEC, hi_i, vt0);
        return bw_encode_pass(pl, pa, BW_MODE_BYTES, samples, work, ctx, out, b.budget, len);
    }
    st = bisect(&b, SET_STEP_T, 0, false, false, &lo, &hi);
    if (st != BW_OK)
        return st;
    /* then on the step itself, down to 1/16384 of it: at 32 steps per
     * octave the payload still jumps by about 2 % from step to step, and
     * small payloads (a few hundred bytes) move by a few bytes at a time */
    uint32_t lo_s = step_of(lo), hi_s = step_of(hi);
    st = bisect(&b, SET_STEP, 0, false, true, &lo_s, &hi_s);
    if (st != BW_OK)
        return st;
    pl->step_q8 = hi_s;
    /* then the quantiser's rounding offset, 0 .. 1/8 of a step: the size
     * jumps at some steps (similar coefficients cross a power of two
     * together), and rounding up more of them fills the budget by smaller
     * amounts. Within 1/8 of a step every coefficient it rounds up ends
     * nearer its reconstruction (at 3/8 of the interval above) than before. */
    st = count_bytes(&b, &sz);
    if (st != BW_OK)
        return st;
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
