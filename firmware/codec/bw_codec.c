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

/* ---- encoder ------------------------------------------------------------- */

/* One encode at fixed plan: load, transform, quantise, code. out may be NULL
 * (count only). */
static bw_status_t encode_pass(bw_plan_t *pl, const bw_params_t *pa, uint32_t mode,
                               const int32_t *samples, int32_t *work, uint8_t *out,
                               size_t cap, size_t *len)
{
    unsigned done;
    bw_status_t st = bw_load(pl, work, samples, &done);
    if (st == BW_OK && (pl->mirror || pl->recip))
        st = bw_symmetry(pl, work, true);
    if (st != BW_OK)
        return st;
    if (BW_CFG_ENCODE_PRED && pl->basis == BW_BASIS_PRED)
        bw_predict(pl, work, work + pl->n, true);
    else
        bw_transform_fwd(pl, work, done);
    bw_plan_tables(pl);
    if (pl->step_q8 > BW_STEP_ONE_Q8)
        bw_quantise(pl, work, true);

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
        bw_predict(&pl, work, NULL, false); /* decoded samples: no prequantiser left */
        memcpy(samples, work, n * sizeof *samples);
        return BW_OK;
    }
#endif
    if (pl.step_q8 > BW_STEP_ONE_Q8)
        bw_quantise(&pl, work, false);
    bw_transform_inv(&pl, work);
    if (pl.mirror || pl.recip)
        bw_symmetry(&pl, work, false);
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
    unsigned cd = bw_level_cls(pl, j);
    bw_quant_vector(pl, v, j);
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
    bw_status_t st = bw_load_samples(v, spectrum, b, s->prequant);
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
