#include "bw_rc.h"

void bw_rc_enc_init(bw_rc_enc_t *e, uint8_t *out, size_t cap)
{
    e->low = 0;
    e->range = 0xFFFFFFFFu;
    e->cache = 0;
    e->cache_size = 1;
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
 * 0xFF bytes is held back (cache_size) until the carry is known. */
void bw_rc_enc_shift_low(bw_rc_enc_t *e)
{
    if ((uint32_t)e->low < 0xFF000000u || (e->low >> 32) != 0) {
        uint8_t carry = (uint8_t)(e->low >> 32);
        uint8_t temp = e->cache;
        do {
            put(e, (uint8_t)(temp + carry));
            temp = 0xFF;
        } while (--e->cache_size != 0);
        e->cache = (uint8_t)(e->low >> 24);
    }
    e->cache_size++;
    e->low = (e->low & 0x00FFFFFFu) << 8;
}

size_t bw_rc_enc_finish(bw_rc_enc_t *e)
{
    for (int i = 0; i < 5; i++)
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
    d->overrun = false;
    for (int i = 0; i < 5; i++)
        d->code = (d->code << 8) | bw_rc_dec_byte(d);
}
