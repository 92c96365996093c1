/* SPDX-License-Identifier: BSD-2-Clause */
/* Measurements to payloads (bwh_encode.h). */
#include "bwh_encode.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwh_device.h"
#include "bwh_encode_bound.h"
#include "bwh_error.h"
#include "bwh_ext.h"
#include "bwh_guarantee.h"
#include "bwh_values.h"

static double sse_of(const int32_t *x, const int32_t *y, size_t n)
{
    double e = 0.0;
    for (size_t i = 0; i < n; i++)
        e += ((double)y[i] - x[i]) * ((double)y[i] - x[i]);
    return e;
}

#define SYM_FLAGS (BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL)

/* The same encode with the symmetry flags sym instead of *p0's; keeps
 * whichever payload is smaller (a byte budget: whichever decodes closer,
 * then the smaller), and sets the flags in *p0 when it keeps the new one.
 * *buf holds the payload of status st0 and *e0 the squared error of its
 * decoded samples; ver is scratch. */
static int try_symmetry(const bw_dims_t *dims, bw_params_t *p0, unsigned sym, const int32_t *x,
                        size_t n, int32_t *work, int32_t *ver, uint8_t **buf, size_t cap,
                        size_t *len, int st0, double *e0)
{
    bw_params_t p = *p0;
    p.flags = (uint8_t)((p.flags & ~SYM_FLAGS) | sym);
    uint8_t *alt = malloc(cap);
    size_t alen = 0;
    if (!alt)
        return st0;
    int st = bw_encode(dims, &p, x, work, ver, alt, cap, &alen);
    int take = 0;
    double e = st == BW_OK ? sse_of(x, ver, n) : 0.0;
    if (st == BW_OK) {
        if (st0 != BW_OK)
            take = 1;
        else if (p.mode == BW_MODE_BYTES)
            take = e < *e0 || (e == *e0 && alen < *len);
        else
            take = alen < *len;
    }
    if (take) {
        free(*buf);
        *buf = alt;
        *len = alen;
        *e0 = e;
        p0->flags = p.flags;
        return BW_OK;
    }
    free(alt);
    return st0;
}

int bwh_encode_i32(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                   float scale, float offset, uint8_t **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(dims);
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = (uint8_t)o->mode;
    p.basis = (uint8_t)o->basis;
    p.effort = (uint8_t)o->effort;
    p.coder = (uint8_t)o->coder;
    p.progressive = o->progressive != 0u;
    p.band_access = o->band_access != 0u;
    if (o->segments > 1u) {
        uint32_t nv = dims->n_in * dims->n_out;
        p.segment_vectors = (nv - 1u) / o->segments + 1u;
    }
    p.scale_bits = bwh_float_to_bits(scale);
    p.offset_bits = bwh_float_to_bits(offset);
    p.flags = (uint8_t)(o->flags & BW_FLAGS_KNOWN);
    if (o->ext_len > BW_EXT_MAX)
        return bwh_fail("extension records of %zu bytes, more than %u", o->ext_len, BW_EXT_MAX);
    p.ext = o->ext;
    p.ext_len = (uint32_t)o->ext_len;
    if (o->mode == BW_MODE_MAX_ERROR) {
        if (!(o->max_error >= 1.0) || o->max_error > BW_SAMPLE_MAX)
            return bwh_fail("max error must be at least 1 sample unit (and below %d)", BW_SAMPLE_MAX);
        p.max_error = (uint32_t)floor(o->max_error);
    }
    if (o->mode == BW_MODE_BYTES) {
        if (o->byte_budget > UINT32_MAX)
            p.byte_budget = UINT32_MAX;
        else
            p.byte_budget = (uint32_t)o->byte_budget;
    }
    for (size_t i = 0; i < n; i++)
        if (x[i] > BW_SAMPLE_MAX || x[i] < -BW_SAMPLE_MAX)
            return bwh_fail("sample %zu = %d is outside the codec's range +-%d", i, x[i], BW_SAMPLE_MAX);
    /* a device is asked first what it takes: a job it cannot take is
     * refused before the host spends any work on it */
    bwh_device_t dv;
    if (o->device && (bwh_device_open(&dv, o->device->device, o->device->firmware) != 0))
        return -1;
    if (o->device && bwh_device_admit(&dv, dims, &p) != 0) {
        bwh_device_close(&dv);
        return -1;
    }
    size_t wb = bw_work_bound(n, dims->bands), cap = bw_payload_bound(n);
    if (o->ext_len)
        cap += o->ext_len + BW_EXT_OVERHEAD;
    if (p.band_access)
        cap += BW_BANDS_OVERHEAD;
    if (p.segment_vectors)
        cap += BW_SEGMENT_OVERHEAD((dims->n_in * dims->n_out - 1u) / p.segment_vectors + 1u);
    int32_t *work = malloc(wb * sizeof *work), *ver = malloc(wb * sizeof *ver);
    uint8_t *buf = malloc(cap);
    if (!work || !ver || !buf) {
        free(work);
        free(ver);
        free(buf);
        if (o->device)
            bwh_device_close(&dv);
        return bwh_fail("out of memory");
    }
    size_t len = 0;
    bool auto_sym = !(o->flags & (SYM_FLAGS | BWH_NO_MIRROR)) &&
                    dims->shape != BW_SHAPE_SPECTRA && !(o->flags & BW_FLAG_STREAM_ORDER);
    if (!o->device || auto_sym) {
        /* the host's encode (with auto, every symmetry that applies); before
         * a device encode it only makes the choice, so that the device's
         * payload is the host's */
        st = bw_encode(dims, &p, x, work, ver, buf, cap, &len);
        double e0 = st == BW_OK ? sse_of(x, ver, n) : 0.0;
        bool recip = dims->shape == BW_SHAPE_BRDF_FULL && dims->level_in == dims->level_out;
        static const unsigned syms[3] = {BW_FLAG_MIRROR, BW_FLAG_RECIPROCAL,
                                         BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL};
        for (unsigned k = 0; auto_sym && k < (recip ? 3u : 1u); k++)
            if (st == BW_OK || st == BW_ERR_BUDGET)
                st = try_symmetry(dims, &p, syms[k], x, n, work, ver, &buf, cap, &len, st, &e0);
    }
    if (o->device) {
        /* the emulated co-processor encodes; the host checks what came back */
        bwh_rx_opts_t ro = {o->device->timeout > 0 ? o->device->timeout : 120.0,
                            o->device->drop_chunk, 0, SIZE_MAX, 0, NULL};
        bwh_received_t r;
        int drc = bwh_device_run(&dv, dims, &p, x, &ro, &r);
        bwh_device_close(&dv);
        if (drc != 0) {
            free(work);
            free(ver);
            free(buf);
            return -1;
        }
        free(buf);
        buf = r.payload;
        len = r.len;
        if (o->device->instructions)
            *o->device->instructions = r.instructions;
        st = bw_decode(buf, len, ver, wb, ver, wb, NULL);
        for (size_t i = 0; st == BW_OK && i < n; i++) {
            int64_t e = (int64_t)ver[i] - x[i];
            if ((o->mode == BW_MODE_LOSSLESS && e != 0) ||
                (o->mode == BW_MODE_MAX_ERROR && (e > p.max_error || -e > p.max_error)))
                st = BW_ERR_VERIFY;
        }
        if (st == BW_OK && o->mode == BW_MODE_BYTES && len > o->byte_budget)
            st = BW_ERR_VERIFY;
    }
    free(work);
    free(ver);
    if (st != BW_OK) {
        free(buf);
        if (st == BW_ERR_BUDGET)
            return bwh_fail("byte budget %zu is too small for this measurement", o->byte_budget);
        return bwh_fail("%s", bw_strerror(st));
    }
    *out = buf;
    *out_len = len;
    return 0;
}

/* BW_FLAG_LOG_VALUE: the samples are round((log x - offset) / scale) on 2^20
 * levels each side of the mid-range offset, so the byte-budget search spends
 * its bits on relative rather than absolute error. */
static int encode_log(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                      uint8_t **out, size_t *out_len)
{
    size_t n = bw_dims_samples(dims);
    if (o->mode != BW_MODE_BYTES)
        return bwh_fail("--relative needs --bytes or --ratio");
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !(x[i] > 0))
            return bwh_fail("--relative needs positive finite values (sample %zu = %g)", i,
                        (double)x[i]);
        double l = log((double)x[i]);
        lo = fmin(lo, l);
        hi = fmax(hi, l);
    }
    float offset = (float)(0.5 * (lo + hi));
    double half = fmax(fabs(hi - (double)offset), fabs(lo - (double)offset));
    float scale = (float)(half > 0 ? half / 1048576.0 : 1.0);
    if (!(scale > 0) || !isfinite(scale) || !isfinite(offset))
        return bwh_fail("--relative: the value range cannot be represented");
    int32_t *q = malloc((n ? n : 1) * sizeof *q);
    if (!q)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < n; i++)
        q[i] = (int32_t)nearbyint((log((double)x[i]) - (double)offset) / (double)scale);
    int rc = bwh_encode_i32(dims, q, o, scale, offset, out, out_len);
    free(q);
    return rc;
}

int bwh_encode_f32(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o, uint8_t **out,
                   size_t *out_len)
{
    /* a relative bound (with or without an absolute one), and lossless
     * without a given scale: bwh_encode_bound.c */
    if (o->max_rel_error > 0 || o->rel_floor > 0)
        return bwh_encode_relative(dims, x, o, out, out_len);
    if (o->mode == BW_MODE_LOSSLESS && !(o->scale > 0) && !(o->flags & BW_FLAG_LOG_VALUE))
        return bwh_encode_exact(dims, x, o, NULL, out, out_len);
    if (o->flags & BW_FLAG_LOG_VALUE)
        return encode_log(dims, x, o, out, out_len);
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(dims);
    double maxabs = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            return bwh_fail("sample %zu is %s (--lossless keeps NaN and infinities bit for bit)", i,
                            isnan(x[i]) ? "NaN" : "infinite");
        double a = fabs((double)x[i]);
        if (a > maxabs)
            maxabs = a;
    }
    double scale = o->scale;
    bwh_encode_opts_t io = *o;
    /* MAX_ERROR: the decoded value is rounded to float32, so one ulp of the
     * largest value is kept in hand; the rest is split into 3 integer steps
     * of coding error plus half a step of rounding to the integer grid. */
    double budget = 0;
    if (o->mode == BW_MODE_MAX_ERROR) {
        if (!(o->max_error > 0))
            return bwh_fail("max error must be positive");
        float top = (float)(maxabs + o->max_error);
        budget = o->max_error - ((double)nextafterf(top, INFINITY) - (double)top);
        if (!(budget > 0))
            return bwh_fail("max error %g is below the float32 resolution of the data (max |x| = %g)",
                        o->max_error, maxabs);
        io.max_error = 3;
    }
    if (!(scale > 0)) {
        switch (o->mode) {
        case BW_MODE_LOSSLESS:
            scale = 1.0;
            break;
        case BW_MODE_MAX_ERROR:
            scale = budget / 3.5;
            break;
        default:
            /* 2^23 levels: fine enough that the quantiser, not the grid,
             * sets the size between the exact coding and step 1 */
            scale = maxabs > 0 ? maxabs / 8388608.0 : 1.0;
            break;
        }
    }
    /* the header carries the scale as float32: use exactly that value */
    float scale_f = (float)scale;
    if (o->mode == BW_MODE_MAX_ERROR && !(o->scale > 0))
        while (scale_f > 0 && 3.5 * (double)scale_f > budget)
            scale_f = nextafterf(scale_f, 0);
    if (!(scale_f > 0) || !isfinite(scale_f))
        return bwh_fail("scale %g is not representable", scale);
    scale = scale_f;
    if (maxabs / scale > BW_SAMPLE_MAX)
        return bwh_fail("the data range (max |x| = %g) needs a coarser step than %g: %s", maxabs, scale,
                    o->mode == BW_MODE_MAX_ERROR ? "raise --max-error" : "give a larger --scale");
    if (o->mode == BW_MODE_MAX_ERROR && o->scale > 0) {
        io.max_error = floor((budget - 0.5 * scale) / scale);
        if (io.max_error < 1)
            return bwh_fail("max error %g is below 1.5 steps of the given scale %g", o->max_error, scale);
    }
    unsigned flags = o->scale > 0 && bwh_decimal_exponent(scale_f) ? BW_FLAG_DECIMAL_SCALE : 0u;
    bwh_value_map_t vm = bwh_value_map(scale_f, 0.0f, flags);
    int32_t *q = malloc(n * sizeof *q);
    if (!q)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < n; i++) {
        double v = (double)x[i] / scale;
        double r = nearbyint(v);
        /* lossless: the value must come back as the very same float, bits
         * and all (-0.0 is not 0.0) */
        if (o->mode == BW_MODE_LOSSLESS &&
            bwh_float_to_bits(bwh_value_of(&vm, (int32_t)r)) != bwh_float_to_bits(x[i])) {
            free(q);
            return bwh_fail("lossless needs values that are whole multiples of the scale %g "
                        "(sample %zu = %.9g); use --max-error, --bytes or --scale",
                        scale, i, (double)x[i]);
        }
        q[i] = (int32_t)r;
    }
    io.flags = o->flags | flags;
    int rc = bwh_encode_i32(dims, q, &io, scale_f, 0.0f, out, out_len);
    free(q);
    if (rc != 0)
        return rc;
    if (o->mode == BW_MODE_LOSSLESS || o->mode == BW_MODE_MAX_ERROR) {
        /* check the guarantee where the user sees it, in float32, and
         * record it */
        bwh_guarantee_t g = {.kind = o->mode == BW_MODE_LOSSLESS ? BWH_GUARANTEE_EXACT
                                                                  : BWH_GUARANTEE_ABSOLUTE,
                             .max_error = o->mode == BW_MODE_LOSSLESS ? 0.0 : o->max_error};
        return bwh_encode_seal(out, out_len, x, n, &g, NULL, 0, NULL, 0, 0);
    }
    return 0;
}

int bwh_encode_scaled(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                      float scale, uint8_t **out, size_t *out_len)
{
    bwh_encode_opts_t io = *o;
    if (o->mode == BW_MODE_MAX_ERROR) {
        /* value units -> sample units. Values scaled by a non-unit step
         * are rounded to float32 when decoded: keep one ulp of the
         * largest value in hand for that rounding. */
        double margin = 0;
        if (scale != 1.0f) {
            double maxabs = 0;
            size_t n = bw_dims_samples(dims);
            for (size_t i = 0; i < n; i++)
                maxabs = fmax(maxabs, fabs((double)x[i] * scale));
            float top = (float)(maxabs + o->max_error);
            margin = (double)nextafterf(top, INFINITY) - (double)top;
        }
        io.max_error = floor((o->max_error - margin) / scale);
        /* a bound finer than the integer grid: only exact coding meets it */
        if (io.max_error < 1 && o->max_error > 0)
            io.mode = BW_MODE_LOSSLESS;
    }
    if (bwh_decimal_exponent(scale))
        io.flags |= BW_FLAG_DECIMAL_SCALE;
    int rc = bwh_encode_i32(dims, x, &io, scale, 0.0f, out, out_len);
    /* The header states the guarantee itself where it is exact in value
     * units: lossless mode, and a bound in whole samples of scale 1 (the
     * integers and their float32 values are the same). Otherwise the bound
     * the user gave is recorded: the core checked the samples, and the bound
     * in samples keeps the values' float32 rounding in hand. */
    if (rc != 0 || io.mode != BW_MODE_MAX_ERROR ||
        (scale == 1.0f && !(io.flags & BW_FLAG_DECIMAL_SCALE)))
        return rc;
    bwh_guarantee_t g = {.kind = BWH_GUARANTEE_ABSOLUTE, .max_error = o->max_error};
    uint8_t rec[32];
    size_t rl = bwh_guarantee_record(&g, rec);
    if (bwh_ext_add(out, out_len, rec, rl, NULL, 0) != 0) {
        free(*out);
        *out = NULL;
        *out_len = 0;
        return -1;
    }
    return 0;
}
