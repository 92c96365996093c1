/*
 * The strip coder: the coefficients, in coding order, as strips of 32
 * (docs/FORMAT.md, Body), with the context-adaptive range coder (a presence
 * flag, valid bits, magnitudes and signs with contexts from the neighbours)
 * or with Rice strips (BW_FLAG_RICE, bw_rice.h). Encoder and decoder are
 * side by side in bw_strip_coder.c; the state's types are in bw_coder.h, so
 * that callers can own it.
 *
 * The encoder is fed one coefficient at a time (bw_strip_put) and codes a
 * strip when its 32nd arrives; bw_code_body and bw_decode_body walk a plan's
 * coefficients in coding order (bw_order.c).
 */
#ifndef BW_STRIP_CODER_H
#define BW_STRIP_CODER_H

#include "bw_coder.h"
#include "bw_internal.h"

void bw_models_init(bw_models_t *m);

/* out NULL: only counts; rice: Rice strips instead of the range coder. */
void bw_strip_enc_init(bw_strip_enc_t *se, uint8_t *out, size_t cap, bool rice);
/* Codes the strip of the se->cnt coefficients put since the last one. */
void bw_strip_enc_code(bw_strip_enc_t *se);
/* Codes what is left; returns the body size. */
size_t bw_strip_enc_finish(bw_strip_enc_t *se);
/* Whether the body ran past the output's capacity. */
bool bw_strip_enc_overflow(const bw_strip_enc_t *se);

/* Contexts of a coefficient from the bit lengths of its neighbours
 * (BW_NO_CTX: no such neighbour). */
#define BW_NO_CTX 0xFFu

static inline unsigned bw_ctx_len(const int32_t *p)
{
    return p ? bw_bitlen(bw_abs32(*p)) : BW_NO_CTX;
}
/* sign context of a value: 0 none or zero, 1 positive, 2 negative */
static inline unsigned bw_sign_ctx(const int32_t *p) { return p && *p ? 1u + (*p < 0) : 0u; }
/* the sign model of a value is left + this, left the sign context of the
 * previous value of the strip (0 for the first) */
static inline unsigned bw_sign_ctx_up(const int32_t *par, const int32_t *prv)
{
    return 3u * (bw_sign_ctx(par) + 3u * bw_sign_ctx(prv));
}

/* One coefficient v of class cls; par, prv: its parent and the same band in
 * the previous vector (NULL: none), whose bit lengths and signs are its
 * contexts. */
static inline void bw_strip_put(bw_strip_enc_t *se, int32_t v, unsigned cls, const int32_t *par,
                                const int32_t *prv)
{
    se->v[se->cnt] = v;
    se->cls[se->cnt] = (uint8_t)cls;
    se->pe[se->cnt] = (uint8_t)bw_ctx_len(par);
    se->ps[se->cnt] = (uint8_t)bw_sign_ctx_up(par, prv);
    se->pv[se->cnt] = (uint8_t)bw_ctx_len(prv);
    if (++se->cnt == BW_STRIP)
        bw_strip_enc_code(se);
}

/* Codes the plan's coefficients x in coding order into se. */
void bw_code_body(const bw_plan_t *pl, int32_t *x, bw_strip_enc_t *se);
/* Decodes a body into the plan's coefficients x: Rice strips, or the range
 * coder with the models m (initialised here). */
bw_status_t bw_decode_body(const bw_plan_t *pl, int32_t *x, const uint8_t *body, size_t len,
                           bool rice, bw_models_t *m);

#endif
