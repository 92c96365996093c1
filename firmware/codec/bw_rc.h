/*
 * Adaptive binary range coder (carry-less 32-bit range, LZMA style).
 *
 * Probabilities are 11-bit (bw_prob_t, probability of a 0 in units of
 * 1/2048) and adapt by 1/32 of the error after every bit. Bypass bits cost
 * exactly one bit. The encoder writes into a caller buffer and only records
 * an overflow (the caller then reports BW_ERR_OUTPUT_FULL), so it can also
 * run with a NULL buffer to count bytes. The decoder treats bytes past the
 * end of its input as an error (flag `overrun`) and never reads them.
 */
#ifndef BW_RC_H
#define BW_RC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef uint16_t bw_prob_t;

#define BW_PROB_BITS 11u
#define BW_PROB_INIT ((bw_prob_t)(1u << (BW_PROB_BITS - 1u)))
#define BW_PROB_SHIFT 5u
#define BW_RC_TOP (1u << 24)

typedef struct {
    uint64_t low;
    uint32_t range;
    uint8_t cache;
    uint64_t cache_size;
    uint8_t *out; /* NULL: count only */
    size_t cap;
    size_t pos;
    bool overflow;
} bw_rc_enc_t;

typedef struct {
    uint32_t range;
    uint32_t code;
    const uint8_t *in;
    size_t len;
    size_t pos;
    bool overrun;
} bw_rc_dec_t;

void bw_rc_enc_init(bw_rc_enc_t *e, uint8_t *out, size_t cap);
void bw_rc_enc_shift_low(bw_rc_enc_t *e);
/* Flushes the coder; returns the number of bytes produced. */
size_t bw_rc_enc_finish(bw_rc_enc_t *e);

void bw_rc_dec_init(bw_rc_dec_t *d, const uint8_t *in, size_t len);

static inline void bw_rc_enc_bit(bw_rc_enc_t *e, bw_prob_t *p, unsigned bit)
{
    uint32_t bound = (e->range >> BW_PROB_BITS) * *p;
    if (!bit) {
        e->range = bound;
        *p = (bw_prob_t)(*p + (((1u << BW_PROB_BITS) - *p) >> BW_PROB_SHIFT));
    } else {
        e->low += bound;
        e->range -= bound;
        *p = (bw_prob_t)(*p - (*p >> BW_PROB_SHIFT));
    }
    while (e->range < BW_RC_TOP) {
        e->range <<= 8;
        bw_rc_enc_shift_low(e);
    }
}

static inline void bw_rc_enc_direct(bw_rc_enc_t *e, uint32_t value, unsigned nbits)
{
    while (nbits--) {
        e->range >>= 1;
        if ((value >> nbits) & 1u)
            e->low += e->range;
        while (e->range < BW_RC_TOP) {
            e->range <<= 8;
            bw_rc_enc_shift_low(e);
        }
    }
}

static inline uint8_t bw_rc_dec_byte(bw_rc_dec_t *d)
{
    if (d->pos < d->len)
        return d->in[d->pos++];
    d->overrun = true;
    return 0;
}

static inline unsigned bw_rc_dec_bit(bw_rc_dec_t *d, bw_prob_t *p)
{
    uint32_t bound = (d->range >> BW_PROB_BITS) * *p;
    unsigned bit;
    if (d->code < bound) {
        d->range = bound;
        *p = (bw_prob_t)(*p + (((1u << BW_PROB_BITS) - *p) >> BW_PROB_SHIFT));
        bit = 0;
    } else {
        d->code -= bound;
        d->range -= bound;
        *p = (bw_prob_t)(*p - (*p >> BW_PROB_SHIFT));
        bit = 1;
    }
    while (d->range < BW_RC_TOP) {
        d->range <<= 8;
        d->code = (d->code << 8) | bw_rc_dec_byte(d);
    }
    return bit;
}

static inline uint32_t bw_rc_dec_direct(bw_rc_dec_t *d, unsigned nbits)
{
    uint32_t v = 0;
    while (nbits--) {
        d->range >>= 1;
        uint32_t t = (d->code >= d->range);
        if (t)
            d->code -= d->range;
        v = (v << 1) | t;
        while (d->range < BW_RC_TOP) {
            d->range <<= 8;
            d->code = (d->code << 8) | bw_rc_dec_byte(d);
        }
    }
    return v;
}

#endif
