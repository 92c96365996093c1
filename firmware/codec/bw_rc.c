/* SPDX-License-Identifier: BSD-2-Clause */
#include "bw_rc.h"

#include "bw_config.h"

void bw_rc_enc_init(bw_rc_enc_t *e, uint8_t *out, size_t cap)
{
    e->low = 0;
    e->range = 0xFFFFFFFFu;
    e->out = out;
    e->cap = cap;
    e->pos = 0;
    e->overflow = false;
}

/* A carry out of low: one more in the bytes already written, through the
 * 0xFF bytes before it. The code value stays below 1, so the carry never
 * passes the first byte. */
void bw_rc_enc_carry(bw_rc_enc_t *e)
{
    if (!e->out)
        return;
    for (size_t i = e->pos; i-- > 0;) {
        if (i < e->cap && ++e->out[i] != 0u)
            return;
    }
}

static void carry(bw_rc_enc_t *e)
{
    e->low &= 0xFFFFFFFFu;
    bw_rc_enc_carry(e);
}


/* Writes the top byte of low (a carry first goes into the bytes before). */
void bw_rc_enc_shift_low(bw_rc_enc_t *e)
{
    if (e->low >> 32)
        carry(e);
    bw_rc_enc_put(e, (uint8_t)(e->low >> 24));
    e->low = (e->low & 0x00FFFFFFu) << 8;
}

/* Ends the code at the value in [low, low + range) with the most zero bits
 * (range >= 2^24: a multiple of 2^24); its top byte is the last one, left
 * out when it is 0 (the decoder reads zeros past its input). */
size_t bw_rc_enc_finish(bw_rc_enc_t *e)
{
    e->low = (e->low + 0xFFFFFFu) & ~(uint64_t)0xFFFFFFu;
    if (e->low >> 32)
        carry(e);
    if ((uint8_t)(e->low >> 24) != 0u)
        bw_rc_enc_put(e, (uint8_t)(e->low >> 24));
    return e->pos;
}

void bw_rc_dec_init(bw_rc_dec_t *d, const uint8_t *in, size_t len)
{
    d->range = 0xFFFFFFFFu;
    d->code = 0;
    d->in = in;
    d->len = len;
    d->pos = 0;
    for (int i = 0; i < 4; i++)
        d->code = (d->code << 8) | bw_rc_dec_byte(d);
}

void bw_ms_model_init(bw_ms_model_t *m)
{
    /* a start that expects small bit lengths */
    for (unsigned i = 0; i < BW_MS_SYMS; i++)
        m->f[i] = (uint16_t)(i < 4u ? 8u >> i : 1u);
    m->seen = 0;
    m->cum[BW_MS_SYMS] = 0; /* no total yet: nothing to halve */
    bw_ms_model_refresh(m);
}

#if BW_CFG_FAST_STRIPS
#define BW_UNROLL_MS _Pragma("GCC unroll 16")
#else
#define BW_UNROLL_MS
#endif

void bw_ms_model_refresh(bw_ms_model_t *m)
{
    /* the total the counts reach (each symbol since the last refresh added
     * BW_MS_INC): past BW_MS_TOTAL, halve them on the way */
    unsigned t = 0, since = m->seen ? (unsigned)(m->seen <= BW_MS_WARM1 ? 1u
                                                 : m->seen <= BW_MS_WARM1 + BW_MS_WARM2 ? 4u
                                                                                      : BW_MS_REFRESH)
                                    : 0u;
    if (m->cum[BW_MS_SYMS] + since * BW_MS_INC > BW_MS_TOTAL) {
        BW_UNROLL_MS
        for (unsigned i = 0; i < BW_MS_SYMS; i++) {
            unsigned f = (m->f[i] + 1u) >> 1;
            m->f[i] = (uint16_t)f;
            m->cum[i] = (uint16_t)t;
            t += f;
        }
    } else { /* most refreshes: the counts as they are */
        BW_UNROLL_MS
        for (unsigned i = 0; i < BW_MS_SYMS; i++) {
            m->cum[i] = (uint16_t)t;
            t += m->f[i];
        }
    }
    m->cum[BW_MS_SYMS] = (uint16_t)t;
    /* after every symbol while the model learns, then less often */
    m->left = m->seen < BW_MS_WARM1 ? 1u : m->seen < BW_MS_WARM1 + BW_MS_WARM2 ? 4u : BW_MS_REFRESH;
    if (m->seen < 255u)
        m->seen++;
}
