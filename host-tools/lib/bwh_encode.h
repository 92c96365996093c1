/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Measurements to payloads: the codec core on the host (or on a device),
 * with float input mapped to integer samples (value = scale * sample, scale
 * and the mode's guarantee checked in float against the input).
 */
#ifndef BWH_ENCODE_H
#define BWH_ENCODE_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

struct bwh_device_job;

/* Encoder options' flags beside the header's: without BW_FLAG_MIRROR,
 * BW_FLAG_RECIPROCAL or this, a host encode of directional data also tries
 * BW_FLAG_MIRROR (and for a full BRDF on one grid level BW_FLAG_RECIPROCAL
 * and both) and keeps the smallest payload (for a byte budget: the one that
 * decodes closest); with this it uses the symmetry flags given, if any. */
#define BWH_NO_MIRROR 0x100u

typedef struct {
    bw_mode_t mode;     /* LOSSLESS, MAX_ERROR or BYTES */
    double max_error;   /* MAX_ERROR, in value units */
    size_t byte_budget; /* BYTES */
    unsigned basis;     /* bw_basis_t or BW_BASIS_AUTO */
    double scale;       /* > 0: force the integer step of float input */
    unsigned flags;     /* header flags (BW_FLAG_DECIMAL_SCALE, BW_FLAG_MIRROR and
                         * BW_FLAG_RECIPROCAL: always), and BWH_NO_MIRROR */
    /* NULL: encode on the host. Otherwise the encode runs on a device (the
     * command line's `encode --device`; bwh_device.h, not part of the
     * installed interface) and the host decodes and checks its payload. */
    const struct bwh_device_job *device;
    /* float input: R > 0 bounds every value relatively, |x' - x| <= max(R |x|, F)
     * with F = rel_floor (0: none); with mode MAX_ERROR as well the tighter
     * of the two, |x' - x| <= min(E, max(R |x|, F)) (bwh_guarantee.h) */
    double max_rel_error;
    double rel_floor;
    /* extension records for the payload (bw_params_t.ext: the metadata
     * record of bwh_meta_encode), ext_len bytes; none when 0 */
    const uint8_t *ext;
    size_t ext_len;
    /* bw_effort_t: BW_EFFORT_BEST (0) or BW_EFFORT_FAST (bw_codec.h) */
    unsigned effort;
    /* bw_coder_choice_t: BW_CODER_BY_FLAGS (0, the coder `flags` names) or
     * BW_CODER_AUTO (the encoder chooses; `flags` then names none) */
    unsigned coder;
    /* 0 or 1: the body in one piece; n > 1: about n segments, each decodable
     * alone (bw_params_t.segment_vectors: ceil(vectors / n) vectors each) */
    uint32_t segments;
    /* nonzero: embedded segments (bw_params_t.progressive): a prefix decodes
     * to an approximation; with a byte budget the exact coding is cut at
     * the budget */
    uint32_t progressive;
    /* nonzero: a set of spectra coded for band access (bw_params_t.band_access) */
    uint32_t band_access;
} bwh_encode_opts_t;

/* Encodes float samples. *out is allocated. The mapping to integers is
 * chosen from the mode:
 *   LOSSLESS   every value bit for bit (bwh_exact.h: a binary or decimal
 *              scale, or the float bit planes; NaN and infinities kept
 *              too); with a given `scale`, every value must be an integer
 *              multiple of it
 *   MAX_ERROR  scale = E / 3.5: integer bound 3 plus half a step of rounding
 *   BYTES      scale = max|x| / 2^23, fine enough to vanish under the budget
 *   max_rel_error > 0: the relative bound's log map (bwh_logmap.h), alone
 *              or with MAX_ERROR's bound
 * The lossy modes refuse NaN and infinities. The result is checked in float
 * against the input, and a lossless or bounded payload records its
 * guarantee (record 0x82, bwh_guarantee.h). */
int bwh_encode_f32(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o, uint8_t **out,
                   size_t *out_len);

/* Encodes integer samples with scale 1 (or the given scale/offset bits);
 * o->max_error in sample units. */
int bwh_encode_i32(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                   float scale, float offset, uint8_t **out, size_t *out_len);

/* Encodes integer samples whose value is scale * sample (a .sed file's
 * 1e-5, or 1), o->max_error in value units: the bound becomes whole sample
 * units, keeping in hand the float32 rounding of the largest decoded value
 * (a bound below one unit: exact coding), and a scale of 10^-k is recorded
 * as exactly that (BW_FLAG_DECIMAL_SCALE). The payload records its
 * guarantee (exact, or E in value units). */
int bwh_encode_scaled(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                      float scale, uint8_t **out, size_t *out_len);

#ifdef __cplusplus
}
#endif

#endif
