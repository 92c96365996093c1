/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Dimensions and worst-case sizes: which shapes and sizes a measurement may
 * have (bw_dims_check), making them (bw_dims_make) and the buffer bounds of
 * bw_codec.h.
 */
#include <string.h>

#include "bw_internal.h"

size_t bw_payload_bound(size_t n) { return BW_PAYLOAD_BOUND(n); }
size_t bw_work_bound(size_t n, size_t bands) { return BW_WORK_BOUND(n, bands); }
size_t bw_stream_mem_bound(unsigned level, size_t bands)
{
    return BW_STREAM_MEM_BOUND(level, bands);
}

size_t bw_dims_samples(const bw_dims_t *d) { return (size_t)d->n_in * d->n_out * d->bands; }

bw_status_t bw_dims_check(const bw_dims_t *d)
{
    if (!d || d->bands < 1u || d->bands > BW_MAX_BANDS || d->n_in < 1u || d->n_in > BW_MAX_N_IN)
        return BW_ERR_SHAPE;
    switch (d->shape) {
    case BW_SHAPE_SPECTRA:
        if (d->n_out != 1u || d->level_out != 0u || d->level_in != 0u)
            return BW_ERR_SHAPE;
        break;
    case BW_SHAPE_REFLECTANCE:
    case BW_SHAPE_BRDF_ISO:
        if (d->level_out > BW_MAX_LEVEL || d->n_out != bw_tri_count(d->level_out) ||
            d->level_in != 0u)
            return BW_ERR_SHAPE;
        if (d->shape == BW_SHAPE_REFLECTANCE && d->n_in != 1u)
            return BW_ERR_SHAPE;
        break;
    case BW_SHAPE_BRDF_FULL:
        if (d->level_out > BW_MAX_LEVEL || d->level_in > BW_MAX_LEVEL ||
            d->n_out != bw_tri_count(d->level_out) || d->n_in != bw_tri_count(d->level_in))
            return BW_ERR_SHAPE;
        break;
    default:
        return BW_ERR_SHAPE;
    }
    /* n_in * n_out * bands <= BW_MAX_SAMPLES without overflow */
    uint64_t n = (uint64_t)d->n_in * d->n_out * d->bands;
    return n <= BW_MAX_SAMPLES ? BW_OK : BW_ERR_SHAPE;
}

bw_status_t bw_dims_make(bw_dims_t *d, bw_shape_t shape, unsigned level_out, unsigned level_in,
                         uint32_t n_in, uint32_t bands)
{
    if (!d)
        return BW_ERR_ARG;
    memset(d, 0, sizeof *d);
    d->shape = (uint8_t)shape;
    d->bands = bands;
    switch (shape) {
    case BW_SHAPE_SPECTRA:
        d->n_in = n_in;
        d->n_out = 1u;
        break;
    case BW_SHAPE_REFLECTANCE:
    case BW_SHAPE_BRDF_ISO:
        if (level_out > BW_MAX_LEVEL)
            return BW_ERR_SHAPE;
        d->level_out = (uint8_t)level_out;
        d->n_in = shape == BW_SHAPE_REFLECTANCE ? 1u : n_in;
        d->n_out = bw_tri_count(level_out);
        break;
    case BW_SHAPE_BRDF_FULL:
        if (level_out > BW_MAX_LEVEL || level_in > BW_MAX_LEVEL)
            return BW_ERR_SHAPE;
        d->level_out = (uint8_t)level_out;
        d->level_in = (uint8_t)level_in;
        d->n_in = bw_tri_count(level_in);
        d->n_out = bw_tri_count(level_out);
        break;
    default:
        return BW_ERR_SHAPE;
    }
    return bw_dims_check(d);
}
