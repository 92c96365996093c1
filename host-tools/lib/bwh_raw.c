/* SPDX-License-Identifier: BSD-2-Clause */
/* Raw sample files (bwh_raw.h). */
#include "bwh_raw.h"

#include <stdlib.h>
#include <string.h>

#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_values.h"

int bwh_format_from_name(const char *name)
{
    static const char *const names[] = {"f32", "u16", "i32"};
    for (int k = 0; name && k < 3; k++)
        if (!strcmp(name, names[k]))
            return k;
    return -1;
}

size_t bwh_format_size(bwh_format_t f) { return f == BWH_FMT_U16 ? 2 : 4; }

int bwh_raw_read(const char *path, bwh_format_t f, float **floats, int32_t **ints, size_t *n)
{
    if (floats)
        *floats = NULL;
    if (ints)
        *ints = NULL;
    *n = 0;
    if (!floats && f == BWH_FMT_F32)
        return bwh_fail("%s: float32 samples read as integers", path);
    uint8_t *raw;
    size_t len;
    if (bwh_read_file(path, &raw, &len) != 0)
        return -1;
    size_t es = bwh_format_size(f), count = len / es;
    if (len % es) {
        free(raw);
        return bwh_fail("%s: %zu bytes is not a whole number of %zu-byte samples", path, len, es);
    }
    float *v = NULL;
    int32_t *q = NULL;
    if (floats)
        v = malloc((count ? count : 1) * sizeof *v);
    else
        q = malloc((count ? count : 1) * sizeof *q);
    if (!v && !q) {
        free(raw);
        return bwh_fail("%s: out of memory", path);
    }
    for (size_t i = 0; i < count; i++) {
        int32_t x = f == BWH_FMT_U16 ? (int32_t)bw_get_u16(raw + 2 * i)
                                     : (int32_t)bw_get_u32(raw + 4 * i);
        if (q)
            q[i] = x;
        else
            v[i] = f == BWH_FMT_F32 ? bwh_bits_to_float(bw_get_u32(raw + 4 * i)) : (float)x;
    }
    free(raw);
    if (floats)
        *floats = v;
    else
        *ints = q;
    *n = count;
    return 0;
}

int bwh_raw_write(const char *path, void *samples, size_t n, int as_int)
{
    uint8_t *raw = samples;
    for (size_t i = 0; i < n; i++)
        bw_put_u32(raw + 4 * i, as_int ? (uint32_t)((const int32_t *)samples)[i]
                                       : bwh_float_to_bits(((const float *)samples)[i]));
    return bwh_write_file(path, raw, 4 * n);
}
