/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Adaptive binary range coder (carry-less 32-bit range, LZMA style).
 *
 * A model (bw_prob_t) holds an 11-bit probability of a 0 in units of 1/2048
 * (bits 0-10) and a count of the bits it has seen, saturating at 31 (bits
 * 11-15). It adapts by 2^-s of the error after every bit, s growing with the
 * count: 3 for the first 4 bits, 4 up to 16, 5 up to 31, then 6 - fast
 * while it learns, steady once it has. Bypass bits cost
 * exactly one bit. The encoder writes into a caller buffer and only records
 * an overflow (the caller then reports BW_ERR_OUTPUT_FULL), so it can also
 * run with a NULL buffer to count bytes. The code leaves out the encoder's
 * always-zero first byte and a last byte of 0; the decoder reads zeros past
 * the end of its input (docs/FORMAT.md, Range coder).
 */
#ifndef BW_RC_H
#define BW_RC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef uint16_t bw_prob_t;

#define BW_PROB_BITS 11u
#define BW_PROB_INIT ((bw_prob_t)(1u << (BW_PROB_BITS - 1u)))
#define BW_PROB_MASK 0x7FFu
#define BW_PROB_COUNT_MAX 31u
#define BW_RC_TOP (1u << 24)

static inline uint32_t bw_prob_p0(const bw_prob_t *p) { return *p & BW_PROB_MASK; }

/* probability stays within [7, 2041]: never 0, never the whole range */
static inline void bw_prob_update(bw_prob_t *p, unsigned bit)
{
    uint32_t pr = *p & BW_PROB_MASK, cnt = (uint32_t)*p >> BW_PROB_BITS;
    unsigned sh = cnt < 4u ? 3u : cnt < BW_PROB_COUNT_MAX ? 4u : 5u;
    if (!bit)
        pr += ((1u << BW_PROB_BITS) - pr) >> sh;
    else
        pr -= pr >> sh;
    if (cnt < BW_PROB_COUNT_MAX)
        cnt++;
    *p = (bw_prob_t)(pr | (cnt << BW_PROB_BITS));
}

typedef struct {
    uint64_t low; /* bit 32: a carry not yet added to the bytes written */
    uint32_t range;
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
    size_t pos; /* bytes read, those past the end included */
} bw_rc_dec_t;

void bw_rc_enc_init(bw_rc_enc_t *e, uint8_t *out, size_t cap);
void bw_rc_enc_shift_low(bw_rc_enc_t *e);
/* For an encoder that holds low in 32 bits (and range) in its own
 * variables: the carry out of such a low added to the bytes written, and
 * its top byte written (bw_rc_enc_shift_low in two). */
void bw_rc_enc_carry(bw_rc_enc_t *e);
static inline void bw_rc_enc_put(bw_rc_enc_t *e, uint8_t b)
{
    if (e->out) {
        if (e->pos < e->cap)
            e->out[e->pos] = b;
        else
            e->overflow = true;
    }
    e->pos++;
}

/* Flushes the coder; returns the number of bytes produced. */
size_t bw_rc_enc_finish(bw_rc_enc_t *e);

void bw_rc_dec_init(bw_rc_dec_t *d, const uint8_t *in, size_t len);

static inline void bw_rc_enc_renorm(bw_rc_enc_t *e)
{
    while (e->range < BW_RC_TOP) {
        e->range <<= 8;
        bw_rc_enc_shift_low(e);
    }
}

/* One bit whose probability of a 0 is p0 (BW_PROB_BITS bits), before the
 * renormalisation: the coding step of every binary model, whatever its
 * adaptation (its model is updated before the renormalisation, whose call
 * to bw_rc_enc_shift_low need not keep the model live). */
static inline void bw_rc_enc_p0(bw_rc_enc_t *e, uint32_t p0, unsigned bit)
{
    uint32_t bound = (e->range >> BW_PROB_BITS) * p0;
    if (!bit) {
        e->range = bound;
    } else {
        e->low += bound;
        e->range -= bound;
    }
}

static inline void bw_rc_enc_bit(bw_rc_enc_t *e, bw_prob_t *p, unsigned bit)
{
    bw_rc_enc_p0(e, bw_prob_p0(p), bit);
    bw_prob_update(p, bit);
    bw_rc_enc_renorm(e);
}

static inline void bw_rc_enc_direct(bw_rc_enc_t *e, uint32_t value, unsigned nbits)
{
    while (nbits--) {
        e->range >>= 1;
        if ((value >> nbits) & 1u)
            e->low += e->range;
        bw_rc_enc_renorm(e);
    }
}

/* Bytes past the end of the input read as 0 (never from memory); pos still
 * counts them: a whole code leaves it 3 or 4 past the end. */
static inline uint8_t bw_rc_dec_byte(bw_rc_dec_t *d)
{
    uint8_t b = d->pos < d->len ? d->in[d->pos] : 0u;
    d->pos++;
    return b;
}

static inline void bw_rc_dec_renorm(bw_rc_dec_t *d)
{
    while (d->range < BW_RC_TOP) {
        d->range <<= 8;
        d->code = (d->code << 8) | bw_rc_dec_byte(d);
    }
}

/* bw_rc_enc_p0's twin: the bit, before the renormalisation */
static inline unsigned bw_rc_dec_p0(bw_rc_dec_t *d, uint32_t p0)
{
    uint32_t bound = (d->range >> BW_PROB_BITS) * p0;
    if (d->code < bound) {
        d->range = bound;
        return 0;
    }
    d->code -= bound;
    d->range -= bound;
    return 1;
}

static inline unsigned bw_rc_dec_bit(bw_rc_dec_t *d, bw_prob_t *p)
{
    unsigned bit = bw_rc_dec_p0(d, bw_prob_p0(p));
    bw_prob_update(p, bit);
    bw_rc_dec_renorm(d);
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
        bw_rc_dec_renorm(d);
    }
    return v;
}


/* The multi-symbol coder's binary models adapt at one fixed rate: 2^-5 of
 * the error after every bit (no count to keep). */
#ifndef BW_MS_SHIFT
#define BW_MS_SHIFT 5u
#endif
static inline void bw_ms_prob_update(bw_prob_t *p, unsigned bit)
{
    uint32_t pr = *p;
    if (!bit)
        pr += ((1u << BW_PROB_BITS) - pr) >> BW_MS_SHIFT;
    else
        pr -= pr >> BW_MS_SHIFT;
    *p = (bw_prob_t)pr;
}

static inline void bw_rc_enc_msbit(bw_rc_enc_t *e, bw_prob_t *p, unsigned bit)
{
    bw_rc_enc_p0(e, *p, bit);
    bw_ms_prob_update(p, bit);
    bw_rc_enc_renorm(e);
}

static inline unsigned bw_rc_dec_msbit(bw_rc_dec_t *d, bw_prob_t *p)
{
    unsigned bit = bw_rc_dec_p0(d, *p);
    bw_ms_prob_update(p, bit);
    bw_rc_dec_renorm(d);
    return bit;
}

/* ---- multi-symbol coding (BW_FLAG_MS) -------------------------------------
 * A model codes one of BW_MS_SYMS symbols with the cumulative frequencies
 * cum[] (cum[0] = 0, cum[BW_MS_SYMS] the total): symbol s takes
 * range / total times cum[s + 1] - cum[s], one division, two reads and one
 * multiplication. The model counts the symbols it codes (f[], BW_MS_INC
 * each) and sets cum[] from the counts after every BW_MS_REFRESH symbols,
 * halving them first when their total would pass BW_MS_TOTAL (rounding
 * up: none reaches 0). */
#define BW_MS_SYMS 16u
#ifndef BW_MS_INC
#define BW_MS_INC 24u
#endif
#ifndef BW_MS_TOTAL
#define BW_MS_TOTAL 8192u
#endif
#ifndef BW_MS_REFRESH
#define BW_MS_REFRESH 16u
#endif
#ifndef BW_MS_WARM1
#define BW_MS_WARM1 32u
#endif
#ifndef BW_MS_WARM2
#define BW_MS_WARM2 32u
#endif

typedef struct {
    uint16_t cum[BW_MS_SYMS + 1u];
    uint16_t f[BW_MS_SYMS];
    uint8_t left; /* symbols until the next refresh */
    uint8_t seen; /* refreshes so far, saturating */
} bw_ms_model_t;

void bw_ms_model_init(bw_ms_model_t *m);
void bw_ms_model_refresh(bw_ms_model_t *m);

static inline void bw_ms_update(bw_ms_model_t *m, unsigned s)
{
    m->f[s] = (uint16_t)(m->f[s] + BW_MS_INC);
    if (--m->left == 0u)
        bw_ms_model_refresh(m);
}

static inline void bw_rc_enc_sym(bw_rc_enc_t *e, bw_ms_model_t *m, unsigned s)
{
    uint32_t r = e->range / m->cum[BW_MS_SYMS];
    e->low += (uint64_t)r * m->cum[s];
    e->range = r * (uint32_t)(m->cum[s + 1u] - m->cum[s]);
    bw_ms_update(m, s);
    bw_rc_enc_renorm(e);
}

static inline unsigned bw_rc_dec_sym(bw_rc_dec_t *d, bw_ms_model_t *m)
{
    uint32_t r = d->range / m->cum[BW_MS_SYMS], v = d->code / r;
    unsigned s = 0;
    while (s < BW_MS_SYMS - 1u && m->cum[s + 1u] <= v)
        s++;
    d->code -= r * m->cum[s];
    d->range = r * (uint32_t)(m->cum[s + 1u] - m->cum[s]);
    bw_ms_update(m, s);
    bw_rc_dec_renorm(d);
    return s;
}

/* n <= 16 bits at once, each of probability 1/2 */
static inline void bw_rc_enc_bits(bw_rc_enc_t *e, uint32_t value, unsigned n)
{
    e->range >>= n;
    e->low += (uint64_t)e->range * (value & ((1u << n) - 1u));
    bw_rc_enc_renorm(e);
}

static inline uint32_t bw_rc_dec_bits(bw_rc_dec_t *d, unsigned n)
{
    d->range >>= n;
    uint32_t v = d->code / d->range;
    if (v >> n)
        v = (1u << n) - 1u; /* only a corrupt code gets here */
    d->code -= v * d->range;
    bw_rc_dec_renorm(d);
    return v;
}

#endif
