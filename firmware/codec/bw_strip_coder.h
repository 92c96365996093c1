/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The strip coder: the coefficients, in coding order, as strips of 32
 * (docs/FORMAT.md, Body), with the context-adaptive range coder (a presence
 * flag, valid bits, magnitudes and signs with contexts from the neighbours)
 * or with Rice strips (BW_FLAG_RICE, bw_rice.h). Encoder and decoder are
 * side by side in bw_strip_coder.c; the state's types are in bw_coder.h, so
 * that callers can own it.
 *
 * The encoder is fed a vector at a time (bw_strip_put_vector) and codes a
 * strip when its 32nd coefficient arrives; bw_code_body and bw_decode_body
 * walk a plan's coefficients in coding order (bw_order.c).
 */
#ifndef BW_STRIP_CODER_H
#define BW_STRIP_CODER_H

#include "bw_coder.h"
#include "bw_internal.h"

void bw_models_init(bw_models_t *m, unsigned coder);

/* out NULL: only counts; coder: BW_CODER_RANGE, _RICE or _MS. */
void bw_strip_enc_init(bw_strip_enc_t *se, uint8_t *out, size_t cap, unsigned coder);
/* The coder a payload's or a request's flags name. */
static inline unsigned bw_coder_of(unsigned flags)
{
    if (BW_CFG_CODER_TAB && (flags & (BW_FLAG_RICE | BW_FLAG_MS)) == (BW_FLAG_RICE | BW_FLAG_MS))
        return BW_CODER_TAB; /* (a core without it refuses both flags first) */
    return flags & BW_FLAG_RICE ? BW_CODER_RICE : flags & BW_FLAG_MS ? BW_CODER_MS : BW_CODER_RANGE;
}
/* The static-table coder (bw_tab.c): n coefficients from *it (left past
 * them) into out[cap] (NULL: counts only), tables first; returns the bytes,
 * *over when they passed cap; with min_q8 not 0, SIZE_MAX (nothing coded)
 * where the counts put the code below min_q8 / 256 bits a coefficient.
 * Decoding: n coefficients from in[len] into the iterator's array;
 * BW_ERR_CORRUPT for a malformed body. */
size_t bw_tab_encode(bw_iter_t *it, size_t n, bw_tab_models_t *m, uint8_t *out, size_t cap,
                     unsigned min_q8, bool *over);
bw_status_t bw_tab_decode(bw_iter_t *it, size_t n, const uint8_t *in, size_t len,
                          bw_tab_models_t *m);
/* Codes the strip of the se->cnt coefficients put since the last one. */
void bw_strip_enc_code(bw_strip_enc_t *se);
/* Codes what is left; returns the body size. */
size_t bw_strip_enc_finish(bw_strip_enc_t *se);
/* Whether the body ran past the output's capacity. */
bool bw_strip_enc_overflow(const bw_strip_enc_t *se);

/* The coefficients of one vector v of b bands in order: their classes
 * from spec_cls (the plan's) and the vector's direction class cls_dir,
 * their parents from the parent vector par (NULL: the spectral parents in
 * v), the vector above them prev (NULL: none). */
void bw_strip_put_vector(bw_strip_enc_t *se, const int32_t *v, uint32_t b,
                         const int32_t *spec_cls, unsigned cls_dir, const int32_t *par,
                         const int32_t *prev);

/* Codes the plan's coefficients x in coding order into se. */
void bw_code_body(const bw_plan_t *pl, int32_t *x, bw_strip_enc_t *se);
/* Codes the next nvec vectors of the iterator into se (a segment). */
void bw_code_vectors(bw_iter_t *it, bw_strip_enc_t *se, size_t nvec);
/* Decodes the next n coefficients of the iterator from a body of its own
 * (a segment): Rice strips, or the range coder with the models m
 * (initialised here). */
bw_status_t bw_decode_coefs(bw_iter_t *it, size_t n, const uint8_t *body, size_t len,
                            unsigned coder, bw_models_t *m);
/* Decodes a body into the plan's coefficients x: Rice strips, or the range
 * coder with the models m (initialised here). */
bw_status_t bw_decode_body(const bw_plan_t *pl, int32_t *x, const uint8_t *body, size_t len,
                           unsigned coder, bw_models_t *m);

#endif
