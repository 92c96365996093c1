/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The encoder: one pass at fixed settings (load, symmetry, transform or
 * prediction, quantise, code, header and CRC), the choice of the basis, and
 * the self-check of the mode's guarantee.
 */
#include "bw_crc32.h"
#include "bw_internal.h"
#include "bw_le.h"
#include "bw_strip_coder.h"

bw_status_t bw_encode_pass(bw_plan_t *pl, const bw_params_t *pa, unsigned mode,
                           const int32_t *samples, int32_t *work, bw_ctx_t *ctx, uint8_t *out,
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

    bw_strip_enc_t *se = &ctx->enc;
    bool counting = out == NULL;
    size_t body_cap = 0, hl = bw_header_write(NULL, pl, pa, mode);
    if (!counting) {
        if (cap < hl + BW_TRAILER_SIZE)
            return BW_ERR_OUTPUT_FULL;
        body_cap = cap - hl - BW_TRAILER_SIZE;
    }
    bw_strip_enc_init(se, counting ? NULL : out + hl, body_cap, bw_coder_of(pa->flags));
    bw_code_body(pl, work, se);
    size_t body = bw_strip_enc_finish(se);
    *len = hl + body + BW_TRAILER_SIZE;
    if (counting)
        return BW_OK;
    if (bw_strip_enc_overflow(se) || *len > UINT32_MAX)
        return BW_ERR_OUTPUT_FULL;
    bw_header_write(out, pl, pa, mode);
    bw_put_u32(out + hl + body, bw_crc32(out, hl + body));
    return BW_OK;
}

/* Decodes the payload into verify and checks the mode's guarantee; *sse
 * (may be NULL): the squared error. */
static bw_status_t verify_payload(bw_ctx_t *ctx, const bw_plan_t *pl, const bw_params_t *pa,
                                  uint32_t mode, const int32_t *samples, const uint8_t *out,
                                  size_t len, int32_t *verify, uint64_t *sse)
{
    size_t wb = bw_work_bound(pl->n, pl->dims.bands);
    bw_status_t st = bw_decode_ctx(ctx, out, len, verify, wb, verify, wb, NULL);
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

/* The parameter of the mode for bw_plan_make: E, the step, or (BYTES, whose
 * search sets the step) a step of 1. */
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
static bw_status_t encode_basis(bw_ctx_t *ctx, bw_plan_t *pl, const bw_params_t *pa,
                                const int32_t *samples, int32_t *work, uint8_t *out, size_t cap,
                                size_t *len)
{
    if (pa->mode != BW_MODE_BYTES)
        return bw_encode_pass(pl, pa, pa->mode, samples, work, ctx, out, cap, len);
    return bw_budget_encode(pl, pa, samples, work, ctx, out, cap, len);
}

bw_status_t bw_encode_ctx(bw_ctx_t *ctx, const bw_dims_t *dims, const bw_params_t *pa,
                          const int32_t *samples, int32_t *work, int32_t *verify, uint8_t *out,
                          size_t out_cap, size_t *out_len)
{
    if (!ctx || !dims || !pa || !samples || !work || !out || !out_len)
        return BW_ERR_ARG;
    *out_len = 0;
    bw_status_t st = bw_params_check(dims, pa->mode, pa->basis, pa->flags, mode_param(pa),
                                     BW_FOR_ENCODE);
    if (st != BW_OK)
        return st;
    if (!bw_ext_valid(pa->ext, pa->ext_len))
        return BW_ERR_ARG;
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
    if (one_transform && last < BW_BASIS_COUNT)
        last = first;
    unsigned best = first;
    if (first != last) {
        /* keep the smallest payload, or for BYTES the smallest error (the
         * smallest step when there is no room to decode) */
        uint64_t best_score = UINT64_MAX;
        size_t best_sz = 0;
        for (unsigned b = first; b <= last; b++) {
            size_t sz;
            if (one_transform && b != first && b < BW_BASIS_COUNT)
                continue;
            plan_for(&pl, dims, b, pa, work);
            st = encode_basis(ctx, &pl, pa, samples, work, pa->mode == BW_MODE_BYTES ? out : NULL,
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
                if (verify && verify_payload(ctx, &pl, pa, BW_MODE_BYTES, samples, out, sz, verify,
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
    st = encode_basis(ctx, &pl, pa, samples, work, out, out_cap, out_len);
    if (st != BW_OK)
        return st;
    if (verify)
        return verify_payload(ctx, &pl, pa, pa->mode, samples, out, *out_len, verify, NULL);
    return BW_OK;
}

bw_status_t bw_encode(const bw_dims_t *dims, const bw_params_t *pa, const int32_t *samples,
                      int32_t *work, int32_t *verify, uint8_t *out, size_t out_cap,
                      size_t *out_len)
{
    bw_ctx_t ctx;
    return bw_encode_ctx(&ctx, dims, pa, samples, work, verify, out, out_cap, out_len);
}
