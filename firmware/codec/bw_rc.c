/* SPDX-License-Identifier: BSD-2-Clause */
#include "bw_rc.h"

void bw_rc_enc_init(bw_rc_enc_t *e, uint8_t *out, size_t cap)
{
    e->low = 0;
    e->range = 0xFFFFFFFFu;
    e->cache = 0xFF; /* no byte yet: see bw_rc_enc_shift_low */
    e->cache_size = 0;
    e->out = out;
    e->cap = cap;
    e->pos = 0;
    e->overflow = false;
}

static inline void put(bw_rc_enc_t *e, uint8_t b)
{
    if (e->out) {
        if (e->pos < e->cap)
            e->out[e->pos] = b;
        else
            e->overflow = true;
    }
    e->pos++;
}

/* Emits the top byte of low once no carry can reach it any more; a run of
 * 0xFF bytes is held back (cache_size) until the carry is known. The code
 * value stays below 1 (no carry out of the first byte), so the first byte
 * is not preceded by one: cache_size starts at 0, and a first byte of 0xFF
 * held back is the initial cache. */
void bw_rc_enc_shift_low(bw_rc_enc_t *e)
{
    if ((uint32_t)e->low < 0xFF000000u || (e->low >> 32) != 0) {
        uint8_t carry = (uint8_t)(e->low >> 32);
        uint8_t temp = e->cache;
        for (; e->cache_size != 0; e->cache_size--) {
            put(e, (uint8_t)(temp + carry));
            temp = 0xFF;
        }
        e->cache = (uint8_t)(e->low >> 24);
    }
    e->cache_size++;
    e->low = (e->low & 0x00FFFFFFu) << 8;
}

/* Ends the code at the value in [low, low + range) with the most zero bits
 * (range >= 2^24: a multiple of 2^24), which leaves one byte to write
 * after those held back, none when it and they are a single 0 (the decoder
 * reads zeros past its input). */
size_t bw_rc_enc_finish(bw_rc_enc_t *e)
{
    e->low = (e->low + 0xFFFFFFu) & ~(uint64_t)0xFFFFFFu;
    bw_rc_enc_shift_low(e);
    if (e->cache != 0u || e->cache_size > 1u)
        bw_rc_enc_shift_low(e);
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
