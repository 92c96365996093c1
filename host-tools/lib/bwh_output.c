/* SPDX-License-Identifier: BSD-2-Clause */
/* Decoded measurements out (bwh_output.h). */
#define _POSIX_C_SOURCE 200809L
#include "bwh_output.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_values.h"

static const char *const out_names[BWH_OUT_COUNT] = {"f32", "i32", "u16", "raw",
                                                      "npy", "csv", "envi"};

const char *bwh_output_format_name(int f)
{
    return f >= 0 && f < BWH_OUT_COUNT ? out_names[f] : "?";
}

int bwh_output_format_from_name(const char *name)
{
    for (int f = 0; name && f < BWH_OUT_COUNT; f++)
        if (!strcmp(name, out_names[f]))
            return f;
    return -1;
}

int bwh_output_type(int f, const bwh_decoded_t *d)
{
    if (f == BWH_OUT_F32)
        return BWH_ST_F32;
    if (f == BWH_OUT_I32)
        return BWH_ST_I32;
    if (f == BWH_OUT_U16)
        return BWH_ST_U16;
    int t = d->meta && (d->meta->present & BWH_M_SAMPLE_TYPE) ? d->meta->sample_type : BWH_ST_F32;
    if (t != BWH_ST_F32 && t != BWH_ST_F64 && !d->ints_are_values)
        t = BWH_ST_F32; /* the values are not the integers: they stay floats */
    return t;
}

void bwh_put_sample(uint8_t *dst, int t, float v, int32_t q)
{
    switch (t) {
    case BWH_ST_U8:
        dst[0] = (uint8_t)q;
        break;
    case BWH_ST_I16:
    case BWH_ST_U16:
        bw_put_u16(dst, (uint16_t)q);
        break;
    case BWH_ST_I32:
        bw_put_u32(dst, (uint32_t)q);
        break;
    case BWH_ST_F64: {
        double x = v;
        uint64_t u;
        memcpy(&u, &x, 8);
        bw_put_u32(dst, (uint32_t)u);
        bw_put_u32(dst + 4, (uint32_t)(u >> 32));
        break;
    }
    default:
        bw_put_u32(dst, bwh_float_to_bits(v));
    }
}

/* the integer samples fit type t */
static int fits(const bwh_decoded_t *d, int t, size_t n)
{
    long lo = t == BWH_ST_U8 ? 0 : t == BWH_ST_I16 ? -32768 : t == BWH_ST_U16 ? 0 : INT32_MIN;
    long hi = t == BWH_ST_U8 ? 255 : t == BWH_ST_I16 ? 32767 : t == BWH_ST_U16 ? 65535 : INT32_MAX;
    for (size_t i = 0; i < n; i++)
        if (d->ints[i] < lo || d->ints[i] > hi)
            return bwh_fail("sample %zu = %d does not fit %s (%ld..%ld)", i, d->ints[i],
                            bwh_sample_type_name(t), lo, hi);
    return 0;
}

/* the samples as little-endian bytes of type t, allocated */
static uint8_t *samples_as(const bwh_decoded_t *d, int t, size_t *len)
{
    size_t n = bw_dims_samples(&d->dims), es = bwh_sample_type_size(t);
    int integer = t != BWH_ST_F32 && t != BWH_ST_F64;
    if (integer && (!d->ints || fits(d, t, n) != 0)) {
        if (!d->ints)
            bwh_fail("no integer samples to write as %s", bwh_sample_type_name(t));
        return NULL;
    }
    uint8_t *b = malloc(n * es + 1);
    if (!b) {
        bwh_fail("out of memory");
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        bwh_put_sample(b + i * es, t, d->values ? d->values[i] : 0.0f, d->ints ? d->ints[i] : 0);
    *len = n * es;
    return b;
}

int bwh_sidecar_write(const char *path, const bwh_meta_t *m, int shape)
{
    if (!strcmp(path, "-"))
        return 0;
    char side[4096];
    if (snprintf(side, sizeof side, "%s.json", path) >= (int)sizeof side)
        return bwh_fail("%s: name too long for its sidecar", path);
    if (!m || bwh_meta_empty(m)) {
        if (unlink(side) != 0 && errno != ENOENT)
            return bwh_fail("%s: %s", side, strerror(errno));
        return 0;
    }
    char *j;
    if (bwh_meta_to_json_layout(m, shape, &j) != 0)
        return -1;
    size_t n = strlen(j);
    j[n] = '\n'; /* the terminating NUL becomes the line end */
    int rc = bwh_write_file(side, j, n + 1);
    free(j);
    return rc;
}

int bwh_output_write(const char *path, int f, const bwh_decoded_t *d)
{
    int t = bwh_output_type(f, d);
    switch (f) {
    case BWH_OUT_F32:
    case BWH_OUT_I32:
    case BWH_OUT_U16:
    case BWH_OUT_RAW: {
        size_t len;
        uint8_t *b = samples_as(d, t, &len);
        if (!b)
            return -1;
        int rc = bwh_write_file(path, b, len);
        free(b);
        if (rc)
            return -1;
        return bwh_sidecar_write(path, d->meta, d->dims.shape);
    }
    case BWH_OUT_NPY:
        if (bwh_npy_write(path, d, t) != 0)
            return -1;
        return bwh_sidecar_write(path, d->meta, d->dims.shape);
    case BWH_OUT_CSV:
        return bwh_csv_write(path, d);
    case BWH_OUT_ENVI:
        return bwh_envi_write(path, d, t);
    default:
        return bwh_fail("unknown output format %d", f);
    }
}

uint8_t *bwh_output_samples(const bwh_decoded_t *d, int t, size_t *len)
{
    return samples_as(d, t, len);
}
