/*
 * Adaptive Rice strip coder: see bw_rice.h for the bit stream.
 *
 * The encoder looks at a strip once to sum its zigzag values and count its
 * zeros, picks the Rice parameter from the mean (rice_k), and only for strips with many zeros
 * computes the exact sizes of the sparse and dense codes to choose between
 * them.
 */
#include "bw_rice.h"

#include "bw_fixed.h"

#define QMAX 16u       /* quotients from here on are escaped */
#define MODE_ESC 15u   /* mode deltas from here on are sent whole */
#define MODE_BITS 6u
#define MODE_ZERO 0u
#define MODE_SPARSE 1u
#define MODE_DENSE 2u  /* + k */
#define MODE_MAX (MODE_DENSE + 31u)
#define KM_MAX 3u      /* sparse magnitude parameter: 2 bits */
#define KG_MAX 7u      /* sparse gap parameter: 3 bits */

/* ---- bit writer ---------------------------------------------------------- */

static inline void emit32(bw_bitw_t *w, uint32_t word)
{
    if (w->out) {
        if (w->pos + 4u <= w->cap) {
            uint8_t *o = w->out + w->pos;
            o[0] = (uint8_t)(word >> 24);
            o[1] = (uint8_t)(word >> 16);
            o[2] = (uint8_t)(word >> 8);
            o[3] = (uint8_t)word;
        } else {
            w->overflow = true;
        }
    }
    w->pos += 4u;
}

/* Appends the len low bits of code (1 <= len <= 31, code < 2^len). */
static inline void put(bw_bitw_t *w, uint32_t code, unsigned len)
{
    if (len < w->left) {
        w->buf = (w->buf << len) | code;
        w->left -= len;
        return;
    }
    unsigned spill = len - w->left; /* left <= 31 here */
    emit32(w, (w->buf << w->left) | (code >> spill));
    w->left = 32u - spill;
    w->buf = code; /* the bits above the low `spill` ones are shifted out later */
}

static inline void put_long(bw_bitw_t *w, uint32_t v, unsigned n) /* n <= 32 */
{
    if (n > 16u) {
        put(w, v >> 16, n - 16u);
        n = 16u;
    }
    if (n)
        put(w, v & ((1u << n) - 1u), n);
}

static inline uint32_t low_mask(unsigned k) { return k ? 0xFFFFFFFFu >> (32u - k) : 0u; }

/* q zeros, a one, then the k low bits: the number 2^k + (u mod 2^k) in
 * q + 1 + k bits */
static inline void put_rice(bw_bitw_t *w, uint32_t u, unsigned k)
{
    uint32_t q = u >> k;
    if (q >= QMAX) {
        put(w, 0, QMAX);
        put_long(w, u, 32u);
        return;
    }
    if (k < 16u) {
        put(w, (u & low_mask(k)) | (1u << k), q + 1u + k);
        return;
    }
    put(w, 1u, q + 1u);
    put_long(w, u & low_mask(k), k);
}

/* Rice size of u with parameter k, escapes included. */
static inline uint32_t rice_bits(uint32_t u, unsigned k)
{
    uint32_t q = u >> k;
    return q >= QMAX ? QMAX + 32u : q + 1u + k;
}

static inline uint32_t zigzag(int32_t v) { return ((uint32_t)v << 1) ^ (uint32_t)(v >> 31); }
static inline int32_t unzigzag(uint32_t u) { return (int32_t)((u >> 1) ^ (0u - (u & 1u))); }

/* Smallest k (<= kmax) with 1.75 n 2^k >= sum: for a geometric source with
 * mean sum / n the best Rice parameter is near log2(mean ln 2), one below
 * LOCO-I's rule n 2^k >= sum in most strips. The answer is at most the bit
 * length of the mean, and at least two below it. */
static inline unsigned rice_k(uint64_t sum, uint32_t n, unsigned kmax)
{
    uint32_t mean = sum >> 32 ? 0xFFFFFFFFu : (uint32_t)sum / n;
    unsigned k = bw_bitlen(mean);
    k = k > 2u ? k - 2u : 0u;
    if (k > kmax)
        return kmax;
    while (k < kmax && ((uint64_t)n << k) * 7u / 4u < sum)
        k++;
    return k;
}

void bw_rice_enc_init(bw_rice_enc_t *e, uint8_t *out, size_t cap)
{
    e->w.buf = 0;
    e->w.left = 32u;
    e->w.out = out;
    e->w.cap = cap;
    e->w.pos = 0;
    e->w.overflow = false;
    e->mode = MODE_ZERO;
}

static void put_mode(bw_rice_enc_t *e, unsigned mode)
{
    uint32_t zz = zigzag((int32_t)mode - (int32_t)e->mode);
    if (zz < MODE_ESC) {
        put(&e->w, 1u, zz + 1u);
    } else {
        put(&e->w, 0, MODE_ESC);
        put(&e->w, mode, MODE_BITS);
    }
    e->mode = mode;
}

/* Sparse code of a strip: parameters and size. */
typedef struct {
    unsigned km, kg;
    uint32_t bits;
} sparse_t;

static sparse_t sparse_plan(const int32_t *v, unsigned cnt, unsigned nz)
{
    sparse_t sp;
    uint32_t n = cnt - nz; /* non-zero values, >= 1 */
    uint64_t msum = 0;
    for (unsigned b = 0; b < cnt; b++)
        if (v[b])
            msum += bw_abs32(v[b]) - 1u;
    sp.km = rice_k(msum, n, KM_MAX);
    sp.kg = rice_k(nz, n + 1u, KG_MAX);
    uint32_t bits = 5u, gap = 0;
    for (unsigned b = 0; b < cnt; b++) {
        if (!v[b]) {
            gap++;
            continue;
        }
        bits += rice_bits(gap, sp.kg) + rice_bits(bw_abs32(v[b]) - 1u, sp.km) + 1u;
        gap = 0;
    }
    if (gap)
        bits += rice_bits(gap, sp.kg);
    sp.bits = bits;
    return sp;
}

void bw_rice_enc_strip(bw_rice_enc_t *e, const int32_t *v, unsigned cnt)
{
    uint64_t sum = 0;
    unsigned nz = 0;
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t u = zigzag(v[b]);
        sum += u;
        nz += u == 0u;
    }
    if (sum == 0u) {
        put_mode(e, MODE_ZERO);
        return;
    }
    unsigned k = rice_k(sum, cnt, 31u);
    if (nz >= cnt / 4u) {
        uint32_t dense = 0;
        for (unsigned b = 0; b < cnt; b++)
            dense += rice_bits(zigzag(v[b]), k);
        sparse_t sp = sparse_plan(v, cnt, nz);
        if (sp.bits < dense) {
            put_mode(e, MODE_SPARSE);
            put(&e->w, sp.km | (sp.kg << 2), 5u);
            uint32_t gap = 0;
            for (unsigned b = 0; b < cnt; b++) {
                if (!v[b]) {
                    gap++;
                    continue;
                }
                put_rice(&e->w, gap, sp.kg);
                put_rice(&e->w, bw_abs32(v[b]) - 1u, sp.km);
                put(&e->w, v[b] < 0, 1u);
                gap = 0;
            }
            if (gap)
                put_rice(&e->w, gap, sp.kg);
            return;
        }
    }
    put_mode(e, MODE_DENSE + k);
    if (k >= 16u) {
        for (unsigned b = 0; b < cnt; b++)
            put_rice(&e->w, zigzag(v[b]), k);
        return;
    }
    /* the common case, with the writer in registers: every code is at most
     * 15 + 1 + 15 bits */
    bw_bitw_t *w = &e->w;
    uint32_t buf = w->buf, bitk = 1u << k, mask = bitk - 1u;
    unsigned left = w->left;
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t u = zigzag(v[b]), q = u >> k;
        if (q >= QMAX) {
            w->buf = buf;
            w->left = left;
            put_rice(w, u, k);
            buf = w->buf;
            left = w->left;
            continue;
        }
        uint32_t code = (u & mask) | bitk;
        unsigned len = q + 1u + k;
        if (len < left) {
            buf = (buf << len) | code;
            left -= len;
        } else {
            unsigned spill = len - left;
            emit32(w, (buf << left) | (code >> spill));
            left = 32u - spill;
            buf = code;
        }
    }
    w->buf = buf;
    w->left = left;
}

size_t bw_rice_enc_finish(bw_rice_enc_t *e)
{
    bw_bitw_t *w = &e->w;
    unsigned pending = 32u - w->left;
    uint32_t word = pending ? w->buf << w->left : 0u; /* MSB aligned, zero padded */
    for (; pending; pending = pending > 8u ? pending - 8u : 0u, word <<= 8) {
        if (w->out) {
            if (w->pos < w->cap)
                w->out[w->pos] = (uint8_t)(word >> 24);
            else
                w->overflow = true;
        }
        w->pos++;
    }
    w->buf = 0;
    w->left = 32u;
    return w->pos;
}

/* ---- bit reader ---------------------------------------------------------- */

static inline void refill(bw_bitr_t *r)
{
    while (r->nb <= 56u) {
        uint64_t byte = 0;
        if (r->pos < r->len)
            byte = r->in[r->pos];
        r->pos++; /* past the end: zero bytes, caught by past_end() */
        r->acc |= byte << (56u - r->nb);
        r->nb += 8u;
    }
}

/* 1 <= n <= 32; the caller has refilled enough bits */
static inline uint32_t take(bw_bitr_t *r, unsigned n)
{
    uint32_t v = (uint32_t)(r->acc >> (64u - n));
    r->acc <<= n;
    r->nb -= n;
    return v;
}

static inline uint32_t get_rice(bw_bitr_t *r, unsigned k)
{
    refill(r);
    uint32_t top16 = (uint32_t)(r->acc >> 48);
    if (!top16) { /* 16 zeros: the escape */
        take(r, QMAX);
        return take(r, 32u);
    }
    unsigned q = (unsigned)__builtin_clz(top16) - 16u;
    take(r, q + 1u);
    return (q << k) | (k ? take(r, k) : 0u);
}

void bw_rice_dec_init(bw_rice_dec_t *d, const uint8_t *in, size_t len)
{
    d->r.acc = 0;
    d->r.nb = 0;
    d->r.in = in;
    d->r.len = len;
    d->r.pos = 0;
    d->r.overrun = false;
    d->mode = MODE_ZERO;
}

/* Bits consumed past the end of the input? */
static bool past_end(const bw_bitr_t *r)
{
    /* consumed = 8 * pos - nb */
    return (uint64_t)r->pos * 8u - r->nb > (uint64_t)r->len * 8u;
}

bool bw_rice_dec_strip(bw_rice_dec_t *d, int32_t *v, unsigned cnt)
{
    bw_bitr_t *r = &d->r;
    refill(r);
    unsigned mode;
    uint32_t top = (uint32_t)(r->acc >> (64u - MODE_ESC));
    if (!top) {
        take(r, MODE_ESC);
        mode = take(r, MODE_BITS);
    } else {
        unsigned zz = (unsigned)__builtin_clz(top) - (32u - MODE_ESC);
        take(r, zz + 1u);
        mode = (unsigned)((int32_t)d->mode + unzigzag(zz));
    }
    if (mode > MODE_MAX)
        return false;
    d->mode = mode;
    if (mode == MODE_ZERO) {
        for (unsigned b = 0; b < cnt; b++)
            v[b] = 0;
    } else if (mode == MODE_SPARSE) {
        unsigned par = take(r, 5u), km = par & 3u, kg = par >> 2;
        unsigned pos = 0;
        while (pos < cnt) {
            uint32_t g = get_rice(r, kg);
            if (g > cnt - pos)
                return false;
            for (; g; g--)
                v[pos++] = 0;
            if (pos == cnt)
                break;
            uint32_t a = get_rice(r, km) + 1u;
            if (a == 0u)
                return false;
            refill(r);
            v[pos++] = (int32_t)(take(r, 1u) ? 0u - a : a);
            if (r->pos > r->len + 64u)
                return false;
        }
    } else {
        unsigned k = mode - MODE_DENSE;
        for (unsigned b = 0; b < cnt; b++)
            v[b] = unzigzag(get_rice(r, k));
    }
    return !past_end(r);
}
