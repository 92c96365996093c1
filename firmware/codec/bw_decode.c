/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The decoder: header and CRC, the body, then the quantiser, the transforms
 * and the symmetry steps backwards, or prediction. Every payload the format
 * allows decodes in every build, whatever its encoder leaves out
 * (bw_config.h).
 */
#include <string.h>

#include "bw_internal.h"
#include "bw_strip_coder.h"

static bw_status_t decode_checked(bw_ctx_t *ctx, const uint8_t *p, const bw_header_t *h,
                                  int32_t *samples, size_t samples_cap, int32_t *work,
                                  size_t work_cap)
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
    bw_status_t st = bw_decode_body(&pl, work, p + h->header_len, h->body_len,
                                    bw_coder_of(h->flags), &ctx->models);
    if (st != BW_OK)
        return st;
    if (pl.basis == BW_BASIS_PRED) {
        bw_predict(&pl, work, NULL, false); /* decoded samples: no prequantiser left */
        memcpy(samples, work, n * sizeof *samples);
        return BW_OK;
    }
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

bw_status_t bw_decode_ctx(bw_ctx_t *ctx, const uint8_t *payload, size_t len, int32_t *samples,
                          size_t samples_cap, int32_t *work, size_t work_cap, bw_header_t *hdr_out)
{
    bw_header_t h;
    if (!ctx || !payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_read(payload, len, &h);
    if (hdr_out)
        *hdr_out = h;
    if (st != BW_OK)
        return st;
    return decode_checked(ctx, payload, &h, samples, samples_cap, work, work_cap);
}

bw_status_t bw_decode(const uint8_t *payload, size_t len, int32_t *samples, size_t samples_cap,
                      int32_t *work, size_t work_cap, bw_header_t *hdr_out)
{
    bw_ctx_t ctx;
    return bw_decode_ctx(&ctx, payload, len, samples, samples_cap, work, work_cap, hdr_out);
}

bw_status_t bw_decode_unchecked(const uint8_t *payload, size_t len, int32_t *samples,
                                size_t samples_cap, int32_t *work, size_t work_cap)
{
    bw_header_t h;
    bw_ctx_t ctx;
    if (!payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_parse_fields(payload, len, &h); /* every field but crc */
    if (st != BW_OK)
        return st;
    return decode_checked(&ctx, payload, &h, samples, samples_cap, work, work_cap);
}
