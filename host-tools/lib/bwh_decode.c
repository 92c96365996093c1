/* SPDX-License-Identifier: BSD-2-Clause */
/* Payloads to samples (bwh_decode.h). */
#include "bwh_decode.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "bwh_error.h"
#include "bwh_exact.h"
#include "bwh_ext.h"
#include "bwh_logmap.h"
#include "bwh_values.h"

/* The header of p[len], checked, and its sample count against the limit. */
static int header_within(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h)
{
    int st = bw_header_read(p, len, h);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(&h->dims);
    if (!max_samples)
        max_samples = BWH_MAX_SAMPLES_DEFAULT;
    if (n > max_samples)
        return bwh_fail("the payload decodes to %zu samples (%.1f MiB as float32), more than the "
                        "limit of %zu (raise it with --max-samples)",
                        n, (double)n * 4 / 1048576.0, max_samples);
    return 0;
}

/* The integer samples of p[len] in *w (allocated, the decoder's work
 * bound: the samples first), its header in *h. */
static int decode_ints(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                       int32_t **w)
{
    *w = NULL;
    if (header_within(p, len, max_samples, h) != 0)
        return -1;
    size_t wb = bw_work_bound(bw_dims_samples(&h->dims), h->dims.bands);
    int32_t *b = malloc(wb * sizeof *b);
    if (!b)
        return bwh_fail("out of memory");
    int st = bw_decode(p, len, b, wb, b, wb, h);
    if (st != BW_OK) {
        free(b);
        return bwh_fail("%s", bw_strerror(st));
    }
    *w = b;
    return 0;
}

int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h)
{
    int32_t *w;
    if (decode_ints(p, len, max_samples, h, &w) != 0)
        return -1;
    free(w);
    return 0;
}

int bwh_decode_limit(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                     int32_t **samples, float **values)
{
    if (samples)
        *samples = NULL;
    if (values)
        *values = NULL;
    int32_t *w;
    if (decode_ints(p, len, max_samples, h, &w) != 0)
        return -1;
    size_t n = bw_dims_samples(&h->dims);
    if (values) {
        float scale = bwh_bits_to_float(h->scale_bits), off = bwh_bits_to_float(h->offset_bits);
        if (!isfinite(scale) || !isfinite(off) || scale == 0) {
            free(w);
            return bwh_fail("payload header has a zero or non-finite scale or offset");
        }
        /* without the integers the values take their place */
        float *v = samples ? malloc((n ? n : 1) * sizeof *v) : (float *)(void *)w;
        if (!v) {
            free(w);
            return bwh_fail("out of memory");
        }
        bwh_value_map_t vm = bwh_value_map(scale, off, h->flags);
        /* the critical records 0x01 (float bits, exceptions) and 0x02 (the
         * log map) take the place of the header's scale, or follow it */
        const uint8_t *xd = NULL, *ld = NULL, *tail;
        uint32_t xl = 0, ll = 0;
        bwh_logmap_t lm;
        int fx = bwh_ext_find(p, h, BW_EXT_FLOAT_EXACT, &xd, &xl);
        int fl = bwh_ext_find(p, h, BW_EXT_LOG_MAP, &ld, &ll);
        int planes = fx == 1 && bwh_exact_map_of(xd, xl) == BWH_EXACT_PLANES;
        bool plain = scale == 1.0f && bwh_float_to_bits(off) == 0 &&
                     !(h->flags & (BW_FLAG_DECIMAL_SCALE | BW_FLAG_LOG_VALUE));
        if (fx < 0 || fl < 0 || (fx == 1 && bwh_exact_map_of(xd, xl) < 0) ||
            (fl == 1 && bwh_logmap_parse(ld, ll, &lm) != 0) || ((planes || fl == 1) && !plain) ||
            (planes && fl == 1)) {
            if (v != (float *)(void *)w)
                free(v);
            free(w);
            return bwh_fail("the payload's value records are malformed or conflict");
        }
        for (size_t i = 0; i < n && !planes; i++) {
            int32_t q = w[i];
            float x = fl == 1 ? bwh_logmap_value(&lm, q) : bwh_value_of(&vm, q);
            if (!isfinite(x)) {
                bwh_fail("sample %zu (%d) decodes to %g, beyond float32 (scale %g, offset %g%s)",
                         i, q, (double)x, (double)scale, (double)off,
                         h->flags & BW_FLAG_LOG_VALUE ? ", logarithmic" : "");
                if (v != (float *)(void *)w)
                    free(v);
                free(w);
                return -1;
            }
            v[i] = x;
        }
        int map;
        size_t tl = bwh_ext_tail(p, h, &tail);
        if (fx == 1 && bwh_exact_apply(xd, xl, tail, tl, w, v, n, &map) != 0) {
            if (v != (float *)(void *)w)
                free(v);
            free(w);
            return -1;
        }
        *values = v;
    }
    if (samples)
        *samples = w;
    else if (!values)
        free(w);
    return 0;
}

int bwh_decode(const uint8_t *p, size_t len, bw_header_t *h, int32_t **samples, float **values)
{
    return bwh_decode_limit(p, len, 0, h, samples, values);
}
