/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Adaptive Rice strip coder: see bw_rice.h for the bit stream.
 *
 * The encoder looks at a strip once: it forms the zigzag codes, their sum,
 * OR, zeros and negative values, and picks the Rice parameter from the mean
 * (rice_k). For a strip with many zeros it chooses between the sparse and
 * dense codes from bounds on both sizes that those counts give
 * (choose_sparse), without another pass. The codes are then written with
 * the bit writer held in locals.
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

/* Without BW_CFG_FAST_RICE the same bits are written with the plain writer,
 * and both codes of a strip are always sized: smaller and slower. */
#define RICE_SMALL (!BW_CFG_FAST_RICE)

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
 * LOCO-I's rule n 2^k >= sum in most strips. n is 1..33. */
static inline unsigned rice_k(uint64_t sum, uint32_t n, unsigned kmax)
{
    unsigned k;
    if (!RICE_SMALL && sum < (1u << 29)) {
        /* 2^k >= t = ceil(4 sum / 7 n): k = bitlen(t - 1), or 0 for t <= 1 */
        uint32_t t = ((uint32_t)sum * 4u + 7u * n - 1u) / (7u * n);
        k = t > 1u ? bw_bitlen(t - 1u) : 0u;
    } else {
        /* the answer is at most the bit length of the mean, and at least
         * two below it */
        uint32_t mean = sum >> 32 ? 0xFFFFFFFFu : (uint32_t)sum / n;
        k = bw_bitlen(mean);
        k = k > 2u ? k - 2u : 0u;
        /* 1.75 m < sum as 7 m < 4 sum; sum < 2^38, m < 2^39: no overflow */
        uint64_t m = (uint64_t)n << k;
        while (k < kmax && m * 7u < sum * 4u) {
            k++;
            m <<= 1;
        }
    }
    return k < kmax ? k : kmax;
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

static inline void put_mode(bw_rice_enc_t *e, unsigned mode)
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

/* Parameters of the sparse code of a strip. */
typedef struct {
    unsigned km, kg;
} sparse_t;

/* The parameters from the strip's counts: n non-zero values (>= 1) whose
 * magnitudes less one sum to msum, nz zeros. */
static sparse_t sparse_params(uint64_t msum, unsigned n, unsigned nz)
{
    sparse_t sp;
    sp.km = rice_k(msum, n, KM_MAX);
    sp.kg = rice_k(nz, n + 1u, KG_MAX);
    return sp;
}

/* The exact sizes: whether the sparse code with the parameters of sp is
 * smaller than the dense code with parameter k (strips where a code may
 * escape, which the estimate below does not cover). */
static bool sparse_smaller(const uint32_t *u, unsigned cnt, unsigned k, const sparse_t *sp)
{
    uint32_t dense = 0, sparse = 5u, gap = 0;
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t x = u[b];
        dense += rice_bits(x, k);
        if (!x) {
            gap++;
            continue;
        }
        sparse += rice_bits(gap, sp->kg) + rice_bits((x - 1u) >> 1, sp->km) + 1u;
        gap = 0;
    }
    if (gap)
        sparse += rice_bits(gap, sp->kg);
    return sparse < dense;
}

/* The sum over m values x of floor(x / 2^k) lies within
 * [floor((s - m (2^k - 1)) / 2^k), floor(s / 2^k)] for their sum s: the sum
 * of the two bounds. */
static uint32_t quot_bounds2(uint32_t s, uint32_t m, unsigned k)
{
    uint32_t r = m * low_mask(k);
    return (s > r ? (s - r) >> k : 0u) + (s >> k);
}

/*
 * Sparse or dense. Without escapes the size of either code lies within
 * bounds that the strip's counts give (quot_bounds2); the choice is sparse
 * when the sum of its two bounds is below the dense code's. That needs no
 * second pass over the strip, and where the bounds do not overlap it is the
 * choice the exact sizes would make. When a code may escape (or a sum may
 * wrap) the exact sizes decide.
 */
static bool choose_sparse(const uint32_t *u, uint32_t sum, uint32_t any, unsigned cnt,
                          unsigned nz, unsigned k, uint64_t msum, bool wide, const sparse_t *sp)
{
    unsigned n = cnt - nz, km = sp->km, kg = sp->kg;
    if (wide || (any >> k) >= QMAX || ((any >> 1) >> km) >= QMAX || (nz >> kg) >= QMAX)
        return sparse_smaller(u, cnt, k, sp);
    /* dense: cnt (k + 1) + quotients; sparse: 5 + n (3 + km + kg) +
     * quotients, and at most 1 + kg for a final gap */
    uint32_t dense2 = 2u * cnt * (k + 1u) + quot_bounds2(sum, cnt, k);
    uint32_t sparse2 = 2u * (5u + n * (3u + km + kg)) + 1u + kg +
                       quot_bounds2((uint32_t)msum, n, km) + quot_bounds2(nz, n + 1u, kg);
    return sparse2 < dense2;
}

/* The writer in locals, so that the loops below keep it in registers. */
#define W_LOAD(w) uint32_t buf = (w)->buf; unsigned left = (w)->left
#define W_STORE(w) ((w)->buf = buf, (w)->left = left)
#define W_RELOAD(w) (buf = (w)->buf, left = (w)->left)
/* appends code (len bits, 1 <= len <= 31) */
#define W_PUT(w, code, len)                                         \
    do {                                                            \
        uint32_t c_ = (code);                                       \
        unsigned l_ = (len);                                        \
        if (l_ < left) {                                            \
            buf = (buf << l_) | c_;                                 \
            left -= l_;                                             \
        } else {                                                    \
            unsigned s_ = l_ - left;                                \
            emit32((w), (buf << left) | (c_ >> s_));                \
            left = 32u - s_;                                        \
            buf = c_;                                               \
        }                                                           \
    } while (0)

/* u: the zigzag codes; a value v != 0 has |v| - 1 = (u - 1) / 2 and its
 * sign in the low bit of u */
static void code_sparse(bw_bitw_t *w, const uint32_t *u, unsigned cnt, const sparse_t *sp)
{
    unsigned km = sp->km, kg = sp->kg;
    put(w, km | (kg << 2), 5u);
    if (RICE_SMALL) {
        uint32_t gap = 0;
        for (unsigned b = 0; b < cnt; b++) {
            if (!u[b]) {
                gap++;
                continue;
            }
            put_rice(w, gap, kg);
            put_rice(w, (u[b] - 1u) >> 1, km);
            put(w, u[b] & 1u, 1u);
            gap = 0;
        }
        if (gap)
            put_rice(w, gap, kg);
        return;
    }
    W_LOAD(w);
    uint32_t gap = 0, gbit = 1u << kg, gmask = gbit - 1u, mbit = 1u << km, mmask = mbit - 1u;
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t x = u[b];
        if (!x) {
            gap++;
            continue;
        }
        uint32_t a = (x - 1u) >> 1, qg = gap >> kg, qm = a >> km;
        if (qg >= QMAX || qm >= QMAX) { /* an escape: the general writer */
            W_STORE(w);
            put_rice(w, gap, kg);
            put_rice(w, a, km);
            put(w, x & 1u, 1u);
            W_RELOAD(w);
        } else {
            /* gap code, then magnitude code and sign: each at most 15 + 1 + 7 bits */
            W_PUT(w, (gap & gmask) | gbit, qg + 1u + kg);
            W_PUT(w, (((a & mmask) | mbit) << 1) | (x & 1u), qm + 2u + km);
        }
        gap = 0;
    }
    W_STORE(w);
    if (gap)
        put_rice(w, gap, kg);
}

/* The dense codes of a strip without escapes (k < 16, every quotient below
 * QMAX) into o, which has room for every word; returns the new end. */
static inline uint8_t *dense_words(const uint32_t *u, unsigned cnt, unsigned k, uint8_t *o,
                                   uint32_t *buf_p, unsigned *left_p)
{
    uint32_t buf = *buf_p, bitk = 1u << k, mask = bitk - 1u, k1 = k + 1u;
    unsigned left = *left_p;
    BW_UNROLL8
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t x = u[b], c = (x & mask) | bitk;
        unsigned len = (x >> k) + k1;
        if (BW_LIKELY(len < left)) {
            buf = (buf << len) | c;
            left -= len;
        } else {
            unsigned sp = len - left;
            uint32_t word = (buf << left) | (c >> sp);
            o[0] = (uint8_t)(word >> 24);
            o[1] = (uint8_t)(word >> 16);
            o[2] = (uint8_t)(word >> 8);
            o[3] = (uint8_t)word;
            o += 4;
            left = 32u - sp;
            buf = c;
        }
    }
    *buf_p = buf;
    *left_p = left;
    return o;
}

/* esc: some code may escape (or k >= 16) */
static void code_dense(bw_bitw_t *w, const uint32_t *u, unsigned cnt, unsigned k, bool esc)
{
    if (RICE_SMALL || k >= 16u) {
        for (unsigned b = 0; b < cnt; b++)
            put_rice(w, u[b], k);
        return;
    }
    /* every code is at most 15 + 1 + 15 bits */
    W_LOAD(w);
    uint32_t bitk = 1u << k, mask = bitk - 1u, k1 = k + 1u;
    if (!esc && w->out && w->pos <= w->cap && w->cap - w->pos >= 4u * cnt) {
        /* no escape, at most 31 bits a value: room for every word, so the
         * words go out through a local pointer without checks */
        uint8_t *o = w->out + w->pos;
        if (cnt == BW_RICE_STRIP_MAX)
            o = dense_words(u, BW_RICE_STRIP_MAX, k, o, &buf, &left); /* a fixed count */
        else
            o = dense_words(u, cnt, k, o, &buf, &left);
        w->pos = (size_t)(o - w->out);
        W_STORE(w);
        return;
    }
    if (!esc) {
        BW_UNROLL8
        for (unsigned b = 0; b < cnt; b++) {
            uint32_t x = u[b];
            W_PUT(w, (x & mask) | bitk, (x >> k) + k1);
        }
        W_STORE(w);
        return;
    }
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t x = u[b], q = x >> k;
        if (q >= QMAX) {
            W_STORE(w);
            put_rice(w, x, k);
            W_RELOAD(w);
            continue;
        }
        W_PUT(w, (x & mask) | bitk, q + k1);
    }
    W_STORE(w);
}

/* The zigzag codes of a strip and their sum, OR and zeros. A zero is
 * counted as (u - 1) >> 31, right for u <= 2^31 (a wider strip is counted
 * again by the caller). */
typedef struct {
    uint32_t sum, any, nz;
} strip_stats_t;

static inline void strip_stats(const int32_t *v, uint32_t *u, unsigned cnt, strip_stats_t *st)
{
    uint32_t sum = 0, any = 0, nz = 0;
    BW_UNROLL8
    for (unsigned b = 0; b < cnt; b++) {
        uint32_t z = zigzag(v[b]);
        u[b] = z;
        sum += z;
        any |= z;
        nz += (z - 1u) >> 31;
    }
    st->sum = sum;
    st->any = any;
    st->nz = nz;
}

/* the number of odd codes: the negative values */
static inline uint32_t odd_count(const uint32_t *u, unsigned cnt)
{
    uint32_t neg = 0;
    BW_UNROLL8
    for (unsigned b = 0; b < cnt; b++)
        neg += u[b] & 1u;
    return neg;
}

void bw_rice_enc_strip(bw_rice_enc_t *e, const int32_t *v, unsigned cnt)
{
    uint32_t u[BW_RICE_STRIP_MAX];
    strip_stats_t st;
    if (cnt > BW_RICE_STRIP_MAX)
        cnt = BW_RICE_STRIP_MAX;
    if (!RICE_SMALL && cnt == BW_RICE_STRIP_MAX)
        strip_stats(v, u, BW_RICE_STRIP_MAX, &st); /* a whole strip: a fixed count */
    else
        strip_stats(v, u, cnt, &st);
    uint32_t sum32 = st.sum, any = st.any;
    unsigned nz = st.nz;
    if (any == 0u) {
        put_mode(e, MODE_ZERO);
        return;
    }
    uint64_t sum = sum32;
    bool wide = (any >> 26) != 0u;
    if (wide) { /* the sum may have wrapped: again in 64 bits */
        sum = 0;
        nz = 0;
        for (unsigned b = 0; b < cnt; b++) {
            sum += u[b];
            nz += u[b] == 0u;
        }
    }
    unsigned k = rice_k(sum, cnt, 31u);
    if (nz >= cnt / 4u) {
        unsigned n = cnt - nz;
        /* sum of |v| is (sum + negatives) / 2: a negative v has an odd code */
        uint32_t neg = !RICE_SMALL && cnt == BW_RICE_STRIP_MAX ? odd_count(u, BW_RICE_STRIP_MAX)
                                                              : odd_count(u, cnt);
        uint64_t msum = (sum + neg) / 2u - n;
        sparse_t sp = sparse_params(msum, n, nz);
        if (choose_sparse(u, sum32, any, cnt, nz, k, msum, wide, &sp)) {
            put_mode(e, MODE_SPARSE);
            code_sparse(&e->w, u, cnt, &sp);
            return;
        }
    }
    put_mode(e, MODE_DENSE + k);
    code_dense(&e->w, u, cnt, k, wide || (any >> k) >= QMAX);
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
