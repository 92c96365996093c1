/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The fixed inputs whose payload checksums are recorded in
 * tests/golden/payload_crc.txt. Shared by the host unit test and the target
 * test, so the emulated Cortex-M4 must produce byte-identical payloads.
 */
#ifndef BW_GOLDEN_CASES_H
#define BW_GOLDEN_CASES_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bw_codec.h"

typedef struct {
    const char *name;
    uint8_t shape, level_out, level_in;
    uint32_t n_in, bands;
    uint8_t mode, basis;
    uint32_t param; /* max_error, byte_budget or step_q8 by mode */
    uint8_t flags;  /* BW_FLAG_STREAM_ORDER: the streaming encoder must match too;
                     * BW_FLAG_RICE, BW_FLAG_MS (both: the static tables),
                     * BW_FLAG_MIRROR, BW_FLAG_RECIPROCAL;
                     * GOLDEN_EMBED: embedded segments (bw_params_t.progressive) */
} golden_case_t;

/* BW_FLAG_EXT is the header's (no caller gives it): here it marks a case
 * with embedded segments */
#define GOLDEN_EMBED BW_FLAG_EXT

static const golden_case_t golden_cases[] = {
    {"refl3x81_lossless_haar", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_HAAR, 0, 0},
    {"refl3x81_lossless_53", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_53, 0, 0},
    {"refl3x81_lossless_97", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_97, 0, 0},
    {"refl3x81_maxerr4_haar", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_HAAR, 4, 0},
    {"refl3x81_maxerr4_53", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_53, 4, 0},
    {"refl3x81_maxerr4_97", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_97, 4, 0},
    {"refl3x81_bytes2000_haar", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_BYTES, BW_BASIS_HAAR, 2000, 0},
    {"refl3x81_bytes2000_53", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_BYTES, BW_BASIS_53, 2000, 0},
    {"refl3x81_bytes2000_97", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_BYTES, BW_BASIS_97, 2000, 0},
    {"refl3x81_step2560_97", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_STEP, BW_BASIS_97, 2560, 0},
    {"refl3x1_lossless_haar", BW_SHAPE_REFLECTANCE, 3, 0, 1, 1, BW_MODE_LOSSLESS, BW_BASIS_HAAR, 0, 0},
    {"spectra5x2151_lossless_auto", BW_SHAPE_SPECTRA, 0, 0, 5, 2151, BW_MODE_LOSSLESS, BW_BASIS_AUTO, 0, 0},
    {"iso4x2x17_maxerr1_53", BW_SHAPE_BRDF_ISO, 2, 0, 4, 17, BW_MODE_MAX_ERROR, BW_BASIS_53, 1, 0},
    {"full1x1x9_bytes600_97", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_BYTES, BW_BASIS_97, 600, 0},
    {"refl4x81_stream_lossless_53", BW_SHAPE_REFLECTANCE, 4, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_53,
     0, BW_FLAG_STREAM_ORDER},
    {"refl4x81_stream_maxerr2_97", BW_SHAPE_REFLECTANCE, 4, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_97,
     2, BW_FLAG_STREAM_ORDER},
    {"iso16x4x1_stream_step4000_haar", BW_SHAPE_BRDF_ISO, 4, 0, 16, 1, BW_MODE_STEP, BW_BASIS_HAAR,
     4000, BW_FLAG_STREAM_ORDER},
    {"spectra8x1024_stream_lossless_97", BW_SHAPE_SPECTRA, 0, 0, 8, 1024, BW_MODE_LOSSLESS,
     BW_BASIS_97, 0, BW_FLAG_STREAM_ORDER},
    {"refl3x81_lossless_53_rice", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_53,
     0, BW_FLAG_RICE},
    {"refl3x81_maxerr4_haar_rice", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR,
     BW_BASIS_HAAR, 4, BW_FLAG_RICE},
    {"refl3x81_step2560_97_rice", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_STEP, BW_BASIS_97, 2560,
     BW_FLAG_RICE},
    {"full1x1x9_bytes600_97_rice", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_BYTES, BW_BASIS_97, 600,
     BW_FLAG_RICE},
    {"refl4x81_stream_lossless_53_rice", BW_SHAPE_REFLECTANCE, 4, 0, 1, 81, BW_MODE_LOSSLESS,
     BW_BASIS_53, 0, BW_FLAG_STREAM_ORDER | BW_FLAG_RICE},
    {"spectra8x1024_stream_maxerr2_53_rice", BW_SHAPE_SPECTRA, 0, 0, 8, 1024, BW_MODE_MAX_ERROR,
     BW_BASIS_53, 2, BW_FLAG_STREAM_ORDER | BW_FLAG_RICE},
    {"iso4x2x17_maxerr1_53_mirror", BW_SHAPE_BRDF_ISO, 2, 0, 4, 17, BW_MODE_MAX_ERROR, BW_BASIS_53,
     1, BW_FLAG_MIRROR},
    {"full1x1x9_bytes600_97_mirror", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_BYTES, BW_BASIS_97,
     600, BW_FLAG_MIRROR},
    {"refl3x81_lossless_53_mirror_rice", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS,
     BW_BASIS_53, 0, BW_FLAG_MIRROR | BW_FLAG_RICE},
    {"full1x1x9_lossless_haar_reciprocal", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_LOSSLESS,
     BW_BASIS_HAAR, 0, BW_FLAG_RECIPROCAL},
    {"full1x1x9_maxerr2_53_mirror_reciprocal", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_MAX_ERROR,
     BW_BASIS_53, 2, BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL},
    {"spectra4x64_lossless_haar", BW_SHAPE_SPECTRA, 0, 0, 4, 64, BW_MODE_LOSSLESS, BW_BASIS_HAAR, 0,
     0},
    {"spectra4x64_maxerr3_haar_rice", BW_SHAPE_SPECTRA, 0, 0, 4, 64, BW_MODE_MAX_ERROR,
     BW_BASIS_HAAR, 3, BW_FLAG_RICE},
    {"spectra4x66_maxerr5_haar", BW_SHAPE_SPECTRA, 0, 0, 4, 66, BW_MODE_MAX_ERROR, BW_BASIS_HAAR, 5,
     0},
    {"spectra5x2151_lossless_pred", BW_SHAPE_SPECTRA, 0, 0, 5, 2151, BW_MODE_LOSSLESS,
     BW_BASIS_PRED, 0, 0},
    {"spectra6x300_maxerr7_pred", BW_SHAPE_SPECTRA, 0, 0, 6, 300, BW_MODE_MAX_ERROR, BW_BASIS_PRED,
     7, 0},
    {"spectra6x300_maxerr2_pred_rice", BW_SHAPE_SPECTRA, 0, 0, 6, 300, BW_MODE_MAX_ERROR,
     BW_BASIS_PRED, 2, BW_FLAG_RICE},
    {"refl3x81_lossless_53_ms", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_LOSSLESS, BW_BASIS_53, 0,
     BW_FLAG_MS},
    {"refl3x81_maxerr4_97_ms", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_97, 4,
     BW_FLAG_MS},
    {"iso16x4x1_stream_step4000_haar_ms", BW_SHAPE_BRDF_ISO, 4, 0, 16, 1, BW_MODE_STEP,
     BW_BASIS_HAAR, 4000, BW_FLAG_STREAM_ORDER | BW_FLAG_MS},
    {"full1x1x9_bytes600_97_mirror_ms", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_BYTES, BW_BASIS_97,
     600, BW_FLAG_MIRROR | BW_FLAG_MS},
    {"spectra8x1024_stream_maxerr2_53_ms", BW_SHAPE_SPECTRA, 0, 0, 8, 1024, BW_MODE_MAX_ERROR,
     BW_BASIS_53, 2, BW_FLAG_STREAM_ORDER | BW_FLAG_MS},
    {"spectra6x300_maxerr2_pred_ms", BW_SHAPE_SPECTRA, 0, 0, 6, 300, BW_MODE_MAX_ERROR,
     BW_BASIS_PRED, 2, BW_FLAG_MS},
    {"refl3x81_maxerr4_53_embedded", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR,
     BW_BASIS_53, 4, GOLDEN_EMBED},
    {"full1x1x9_bytes600_97_embedded", BW_SHAPE_BRDF_FULL, 1, 1, 0, 9, BW_MODE_BYTES, BW_BASIS_97,
     600, GOLDEN_EMBED},
    {"iso8x3x1_bytes1500_haar_embedded", BW_SHAPE_BRDF_ISO, 3, 0, 8, 1, BW_MODE_BYTES, BW_BASIS_HAAR,
     1500, GOLDEN_EMBED},
    {"spectra8x1024_lossless_97_tab", BW_SHAPE_SPECTRA, 0, 0, 8, 1024, BW_MODE_LOSSLESS, BW_BASIS_97,
     0, BW_FLAG_RICE | BW_FLAG_MS},
    {"spectra6x300_maxerr7_haar_tab", BW_SHAPE_SPECTRA, 0, 0, 6, 300, BW_MODE_MAX_ERROR,
     BW_BASIS_HAAR, 7, BW_FLAG_RICE | BW_FLAG_MS},
    {"refl3x81_maxerr4_53_tab", BW_SHAPE_REFLECTANCE, 3, 0, 1, 81, BW_MODE_MAX_ERROR, BW_BASIS_53, 4,
     BW_FLAG_RICE | BW_FLAG_MS},
};

#define GOLDEN_CASES (sizeof golden_cases / sizeof *golden_cases)

/* A fixed integer formula of (vector, band): no PRNG, no floating point. */
static inline void golden_input(const bw_dims_t *d, int32_t *x)
{
    size_t vectors = (size_t)d->n_in * d->n_out;
    for (size_t v = 0; v < vectors; v++)
        for (uint32_t k = 0; k < d->bands; k++) {
            int32_t kk = (int32_t)(k % 97u);
            x[v * d->bands + k] = 30000 + 250 * kk - 3 * kk * kk +
                                  (int32_t)((v * 7919u) % 613u) * 11 +
                                  (int32_t)((v * 31u + k * 17u) % 23u);
        }
}

static inline bw_params_t golden_params(const golden_case_t *g)
{
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = g->mode;
    p.basis = g->basis;
    p.scale_bits = 0x3727C5ACu; /* 1e-5f */
    p.max_error = g->mode == BW_MODE_MAX_ERROR ? g->param : 0u;
    p.byte_budget = g->mode == BW_MODE_BYTES ? g->param : 0u;
    p.step_q8 = g->mode == BW_MODE_STEP ? g->param : 0u;
    p.flags = g->flags & (uint8_t)~GOLDEN_EMBED;
    p.progressive = (g->flags & GOLDEN_EMBED) != 0u;
    return p;
}

#endif
