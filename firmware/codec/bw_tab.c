/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The static-table coder (flags RICE and MS, docs/FORMAT.md, Body with TAB):
 * the coefficients in coding order, each one symbol of the table of its
 * class and neighbourhood (its bit length and whether its sign is the one
 * its neighbours predict), then the bits below its leading one plain, with
 * the range coder of bw_rc.h. The encoder counts the symbols of part of the
 * body first and sends the tables ahead of the code: no model adapts while
 * it codes, which is what a small core saves.
 */
#include <string.h>

#include "bw_strip_coder.h"

#if BW_CFG_CODER_TAB

#define TAB_UNLIKELY(c) __builtin_expect(!!(c), 0)
#define TAB_BITS 12u
#define TAB_ONE (1u << TAB_BITS)
#define NE 13u           /* a table's entries: bit lengths 0..NE-2, then the escape */
#define E_ESC (NE - 1u)  /* bit lengths from E_ESC on: escape, e - E_ESC in ESC_BITS */
#define ESC_BITS 5u
#define ROW (BW_TAB_SYMS + 1u) /* a table's cumulative frequencies */
#define Q_BITS 6u              /* the first entry; the others as differences */
#define Q_MAX ((1u << Q_BITS) - 1u)
#define HI_BITS 4u  /* a table's last entry */
#define SPLIT_BITS 5u /* a table's split, in 1/32 */
#define SAMPLE 4u   /* pass 1 counts every SAMPLE-th vector of bodies of ... */
#define SAMPLE_MIN 16u /* ... at least SAMPLE_MIN vectors, else every one; */
#define SAMPLE_WIDE 256u /* subbands of this many bands or more in every 2 SAMPLE-th */
#define TAB_MIN_COUNT 32u /* a table for a context counted this often (weighted) or more */

/* The bin of a neighbourhood s = left + above + 2 parent of bit lengths
 * (without a parent the left and the one above twice; without a vector
 * above, the left for it): one bin each for 0 to 3, then wider ones. */
static const uint8_t bin_of[129] = {
    0,  1,  2,  3,  3,  4,  4,  5,  5,  5,  6,  6,  6,  6,  7,  7,  7,  7,  7,  8,  8,  8,
    8,  8,  8,  9,  9,  9,  9,  9,  9,  9,  10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10,
    10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10,
    10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10,
    10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10,
    10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};

/* The same as offsets of the rows of a class's tables (bin_of[s] * ROW). */
static const uint16_t row_of[129] = {
    0, 27, 54, 81, 81, 108, 108, 135, 135, 135, 162, 162, 162, 162, 189, 189, 189, 189, 189, 216,
    216, 216, 216, 216, 216, 243, 243, 243, 243, 243, 243, 243, 270, 270, 270, 270, 270, 270, 270,
    270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270,
    270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270,
    270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270,
    270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270,
    270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270, 270,
};

/* The leading zeros of a, 32 for 0 (the core's instruction where it has
 * one). */
static BW_ALWAYS_INLINE unsigned clz_of(uint32_t a)
{
#if defined(__GNUC__) && defined(__ARM_ARCH) && (__ARM_ARCH >= 6) && !defined(__ARM_ARCH_6M__)
    unsigned c;
    __asm__("clz %0, %1" : "=r"(c) : "r"(a));
    return c;
#else
    return a ? (unsigned)__builtin_clz(a) : 32u;
#endif
}

/* The bit length of |y| without a branch (|y| < 2^31). */
static BW_ALWAYS_INLINE unsigned len_of(int32_t y)
{
    uint32_t s = (uint32_t)(y >> 31), a = ((uint32_t)y ^ s) - s;
    return 31u - (unsigned)__builtin_clz(a << 1 | 1u);
}

/* The weight of table entry q (1..63): 4 to 7 times a power of two, a
 * quarter octave a step; 0 for none. */
static inline uint32_t q_weight(unsigned q)
{
    return q ? (4u + ((q - 1u) & 3u)) << ((q - 1u) >> 2) : 0u;
}

/* The entry of a count c >= 1: the weight nearest 4 c. */
static unsigned q_of(uint32_t c)
{
    uint32_t t = 4u * c;
    unsigned e = bw_bitlen(t) - 3u, q = 4u * e + (t >> e) - 3u;
    if (q >= Q_MAX)
        return Q_MAX;
    if (q_weight(q + 1u) - t < t - q_weight(q))
        q++;
    return q;
}

/* A table's cumulative frequencies (of TAB_ONE) from its entries q[0..hi]
 * (0 above hi) and its split: every symbol 1, then each entry's weight's
 * share of the rest, that of a bit length from 1 on split between its two
 * symbols by pm / 32 (bit length 0 has one, symbol 0), and what is left to
 * the symbol with the largest frequency (the first). q NULL: the table of
 * a context the body does not send, every entry alike, split in halves.
 * false: no weight. */
static bool tab_build(uint16_t *cum, const uint8_t *q, unsigned hi, unsigned pm)
{
    uint32_t f[BW_TAB_SYMS], t = 0, sh[NE];
    for (unsigned e = 0; e < NE; e++) {
        sh[e] = !q ? 1u : e <= hi ? q_weight(q[e]) : 0u;
        t += sh[e];
    }
    if (!t)
        return false;
    if (!q)
        pm = 1u << (SPLIT_BITS - 1u);
    uint32_t sum = 0;
    unsigned big = 0;
    for (unsigned e = 0; e < NE; e++) {
        uint32_t s = sh[e] * (TAB_ONE - BW_TAB_SYMS) / t, a = e ? (s * pm) >> SPLIT_BITS : 0u;
        f[2u * e] = 1u + s - a;
        f[2u * e + 1u] = 1u + a;
        sum += 2u + s;
    }
    for (unsigned j = 1; j < BW_TAB_SYMS; j++)
        if (f[j] > f[big])
            big = j;
    f[big] += TAB_ONE - sum;
    cum[0] = 0;
    for (unsigned j = 0; j < BW_TAB_SYMS; j++)
        cum[j + 1u] = (uint16_t)(cum[j] + f[j]);
    return true;
}

/* ---- encoder --------------------------------------------------------------- */

/* The encoder's state: the range coder's low and range (low in 32 bits, as
 * the multi-symbol coder's encoder keeps it: a carry goes into the bytes
 * written at once), its output (bytes past cap counted, not written; cap 0
 * when it only counts), the left neighbour's bit length and sign (1:
 * negative). The loops hold a copy in locals. */
typedef struct {
    uint8_t *out;
    size_t pos, cap;
    uint32_t low, range;
    unsigned el, ln;
    unsigned w; /* pass 1: what a count weighs (the vectors it stands for) */
} tab_state_t;

/* A carry out of low: one more in the bytes written, through the 0xFF
 * bytes before it (the code value stays below 1: it never passes the
 * first). */
static BW_NOINLINE void tab_carry(uint8_t *out, size_t pos, size_t cap)
{
    for (size_t i = pos < cap ? pos : cap; i-- > 0;)
        if (++out[i] != 0u)
            return;
}

#define T_RENORM(g)                                                                              \
    while ((g).range < BW_RC_TOP) {                                                              \
        if ((g).pos < (g).cap)                                                                   \
            (g).out[(g).pos] = (uint8_t)((g).low >> 24);                                         \
        (g).pos++;                                                                               \
        (g).low <<= 8;                                                                           \
        (g).range <<= 8;                                                                         \
    }
#define T_ADD(g, x)                                                                              \
    do {                                                                                         \
        uint32_t t_ = (g).low + (x);                                                             \
        if (t_ < (g).low)                                                                        \
            tab_carry((g).out, (g).pos, (g).cap);                                                \
        (g).low = t_;                                                                            \
    } while (0)
/* n <= 16 plain bits (the decoder reads them in the same groups) */
#define T_BITS(g, v, n)                                                                          \
    do {                                                                                         \
        (g).range >>= (n);                                                                       \
        T_ADD(g, (g).range * (v));                                                               \
        T_RENORM(g);                                                                             \
    } while (0)

/* A non-zero bit length's first symbol: 2 min(e, E_ESC). */
static const uint8_t sym_of[32] = {0,  2,  4,  6,  8,  10, 12, 14, 16, 18, 20,
                                   22, 24, 24, 24, 24, 24, 24, 24, 24, 24, 24,
                                   24, 24, 24, 24, 24, 24, 24, 24, 24, 24};

/* The cumulative frequencies p[0] and p[1], in one load where the core
 * allows it (little-endian, unaligned loads). */
static BW_ALWAYS_INLINE void pair_at(const uint16_t *p, uint32_t *lo, uint32_t *hi)
{
#if defined(__GNUC__) && defined(__ARM_FEATURE_UNALIGNED) && defined(__BYTE_ORDER__) &&        \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint32_t w;
    __builtin_memcpy(&w, p, sizeof w);
    *lo = w & 0xFFFFu;
    *hi = w >> 16;
#else
    *lo = p[0];
    *hi = p[1];
#endif
}

/* One coefficient x with the table row (class and bin) found and pn, the
 * sign its neighbours predict: counted (pass 1, code false: its symbol in
 * row, counts halved where one reaches 2^16 - 1) or coded (pass 2). */
static BW_ALWAYS_INLINE void tab_coef(tab_state_t *g, uint16_t *row, int32_t x, unsigned pn,
                                      bool code)
{
    uint32_t sx = (uint32_t)(x >> 31), a = ((uint32_t)x ^ sx) - sx;
    unsigned c = clz_of(a), e = 32u - c;
    unsigned j = e ? sym_of[e] + ((sx & 1u) ^ pn) : 0u;
    g->el = e;
    g->ln = sx & 1u;
    if (!code) {
        uint32_t t = row[j] + g->w;
        if (TAB_UNLIKELY(t > 0xFFFFu)) {
            for (unsigned i = 0; i < BW_TAB_SYMS; i++)
                row[i] = (uint16_t)((row[i] + 1u) >> 1);
            t = row[j] + g->w;
        }
        row[j] = (uint16_t)t;
        return;
    }
    uint32_t r = g->range >> TAB_BITS, lo, hi;
    pair_at(row + j, &lo, &hi);
    g->range = r * (hi - lo);
    T_ADD(*g, r * lo);
    T_RENORM(*g);
    if (e - 2u < E_ESC - 2u) { /* 2 <= e < E_ESC */
        T_BITS(*g, a & ~(0x80000000u >> c), e - 1u); /* the leading one, bit 31 - c, off */
    } else if (TAB_UNLIKELY(e >= E_ESC)) {
        unsigned nb = e - 1u;
        T_BITS(*g, e - E_ESC, ESC_BITS);
        if (nb > 16u) { /* the bits below the leading one, the top first */
            nb -= 16u;
            T_BITS(*g, (a >> 16) & ((1u << nb) - 1u), nb);
            nb = 16u;
        }
        T_BITS(*g, a & ((1u << nb) - 1u), nb);
    }
}

/* The sign predicted (1: negative): that of the value above ya, else that
 * of the left neighbour, else positive. */
static BW_ALWAYS_INLINE unsigned pred_of(int32_t ya, unsigned ln)
{
    return ya ? (uint32_t)ya >> 31 : ln;
}

/* The context (table) of band k of vector v, element by element: its
 * class from sc (spec_cls[k]) and cd, the bin of e_left el, of the value
 * above ya (if has_prev, else el again) and of its parent (in par if
 * has_par, else its spectral parent in v, if any). Encoder and decoder. */
static BW_ALWAYS_INLINE unsigned elem_ctx(const int32_t *v, uint32_t k, int32_t sc, unsigned el,
                                          unsigned cd, const int32_t *par, int32_t ya,
                                          bool has_par, bool has_prev)
{
    unsigned s = el + (has_prev ? len_of(ya) : el);
    if (has_par || BW_SPEC_PAR(sc) >= 0)
        s += 2u * len_of(has_par ? par[k] : v[BW_SPEC_PAR(sc)]);
    else
        s *= 2u;
    return (BW_SPEC_CLS(sc) * 3u + cd) * BW_TAB_BINS + bin_of[s];
}

/* Bands k0..k1-1 of vector v, element by element: their classes and
 * spectral parents from spec_cls, the parent vector par (if has_par), the
 * vector above prv (if has_prev). The callers pass constants for the flags,
 * so each gets its own copy. */
static BW_ALWAYS_INLINE void tab_elems(bw_tab_models_t *m, tab_state_t *st, const int32_t *v,
                                       uint32_t k0, uint32_t k1, const int32_t *spec_cls,
                                       unsigned cd, const int32_t *par, const int32_t *prv,
                                       bool code, bool has_par, bool has_prev)
{
    tab_state_t g = *st;
    for (uint32_t k = k0; k < k1; k++) {
        int32_t ya = has_prev ? prv[k] : 0;
        uint16_t *row = m->cum[elem_ctx(v, k, spec_cls[k], g.el, cd, par, ya, has_par, has_prev)];
        tab_coef(&g, row, v[k], pred_of(ya, g.ln), code);
    }
    *st = g;
}

/* A whole vector without a parent vector, subband by subband (the
 * elements' order): each subband's class once, each spectral parent read
 * for its two children (the same contexts as tab_elems). */
static BW_ALWAYS_INLINE void tab_subbands(bw_tab_models_t *m, tab_state_t *st, const int32_t *v,
                                          const spec_bands_t *sb, const int32_t *spec_cls,
                                          unsigned cd, const int32_t *prv, unsigned w, bool all,
                                          bool code, bool has_prev)
{
    tab_state_t g = *st;
    for (unsigned b = 0; b < sb->count; b++) {
        uint32_t lo = sb->lo[b], n = sb->lo[b + 1u] - lo;
        if (!code && !all && n >= SAMPLE_WIDE)
            continue; /* counted in half the vectors counted */
        g.w = w * (n >= SAMPLE_WIDE ? 2u : 1u);
        uint16_t(*rows)[ROW] = m->cum + (BW_SPEC_CLS(spec_cls[lo]) * 3u + cd) * BW_TAB_BINS;
        const int32_t *x = v + lo, *y = has_prev ? prv + lo : NULL;
        if (b < 2u) { /* the approximation and the coarsest details: no parent */
            for (uint32_t i = 0; i < n; i++) {
                int32_t ya = has_prev ? y[i] : 0;
                unsigned s = 2u * (g.el + (has_prev ? len_of(ya) : g.el));
                tab_coef(&g, rows[bin_of[s]], x[i], pred_of(ya, g.ln), code);
            }
            continue;
        }
        const int32_t *p = v + sb->lo[b - 1u];
        uint32_t pl = lo - sb->lo[b - 1u];
        for (uint32_t i = 0; i < n; i++) {
            uint32_t pi = i >> 1;
            int32_t ya = has_prev ? y[i] : 0;
            unsigned s =
                g.el + (has_prev ? len_of(ya) : g.el) + 2u * len_of(p[pi < pl ? pi : pl - 1u]);
            tab_coef(&g, rows[bin_of[s]], x[i], pred_of(ya, g.ln), code);
        }
    }
    *st = g;
}

/* tab_subbands coding a whole vector (the same code in fewer instructions)
 * with the vector above's bit lengths and signs in pb (tab_coef's bytes;
 * NULL: no vector above), the vector's own into cb, where its spectral
 * parents' are read (each for its two children), the left neighbour's as
 * the same byte lb, and the output unchecked: the caller leaves room for
 * TAB_VEC_MAX(bands) bytes. Returns the output's end. */
#define TAB_VEC_MAX(bands) (7u * (size_t)(bands) + 8u) /* 12 + 5 + 30 bits a band, at most */
static BW_NOINLINE uint8_t *tab_code_fast(uint8_t *o, uint32_t *low_, uint32_t *range_,
                                         unsigned *lb_, const bw_tab_models_t *m,
                                         const int32_t *v, const spec_bands_t *sb,
                                         const int32_t *spec_cls, unsigned cd, const uint8_t *pb,
                                         uint8_t *cb)
{
    uint32_t low = *low_, range = *range_;
    unsigned lb = *lb_;
#define F_RENORM()                                                                               \
    while (range < BW_RC_TOP) {                                                                  \
        *o++ = (uint8_t)(low >> 24);                                                             \
        low <<= 8;                                                                               \
        range <<= 8;                                                                             \
    }
#define F_ADD(x)                                                                                 \
    do {                                                                                         \
        uint32_t t_ = low + (x);                                                                 \
        if (t_ < low) { /* the carry: never past the first byte */                               \
            uint8_t *q_ = o;                                                                     \
            while (++*--q_ == 0u)                                                                \
                ;                                                                                \
        }                                                                                        \
        low = t_;                                                                                \
    } while (0)
#define F_BITS(v, n)                                                                             \
    do {                                                                                         \
        range >>= (n);                                                                           \
        F_ADD(range * (v));                                                                      \
        F_RENORM();                                                                              \
    } while (0)
    /* one coefficient x[i]: yb_ the byte above (lb without a vector
     * above), s_ its neighbourhood */
#define F_ONE(i, s_, yb_)                                                                        \
    do {                                                                                         \
        int32_t x_ = x[i];                                                                       \
        const uint16_t *row_ = row0 + row_of[s_];                                                \
        unsigned pn_ = ((yb_) ? (yb_) : lb) >> 5;                                                \
        uint32_t sx_ = (uint32_t)(x_ >> 31), a_ = ((uint32_t)x_ ^ sx_) - sx_;                    \
        unsigned c_ = clz_of(a_), e_ = 32u - c_;                                                 \
        unsigned j_ = e_ ? sym_of[e_] + ((sx_ ^ pn_) & 1u) : 0u;                                 \
        uint32_t lo_, hi_, r_ = range >> TAB_BITS;                                               \
        pair_at(row_ + j_, &lo_, &hi_);                                                          \
        range = r_ * (hi_ - lo_);                                                                \
        F_ADD(r_ * lo_);                                                                         \
        F_RENORM();                                                                              \
        if (e_ - 2u < E_ESC - 2u) {                                                              \
            F_BITS(a_ & ~(0x80000000u >> c_), e_ - 1u);                                          \
        } else if (TAB_UNLIKELY(e_ >= E_ESC)) {                                                  \
            unsigned nb_ = e_ - 1u;                                                              \
            F_BITS(e_ - E_ESC, ESC_BITS);                                                        \
            if (nb_ > 16u) {                                                                     \
                nb_ -= 16u;                                                                      \
                F_BITS((a_ >> 16) & ((1u << nb_) - 1u), nb_);                                    \
                nb_ = 16u;                                                                       \
            }                                                                                    \
            F_BITS(a_ & ((1u << nb_) - 1u), nb_);                                                \
        }                                                                                        \
        lb = e_ | (sx_ & 32u);                                                                   \
        c[i] = (uint8_t)lb;                                                                      \
    } while (0)
    for (unsigned b = 0; b < sb->count; b++) {
        uint32_t lo = sb->lo[b], n = sb->lo[b + 1u] - lo, i = 0;
        const uint16_t *row0 = m->cum[(BW_SPEC_CLS(spec_cls[lo]) * 3u + cd) * BW_TAB_BINS];
        const int32_t *x = v + lo;
        const uint8_t *y = pb ? pb + lo : NULL;
        uint8_t *c = cb + lo;
        if (b < 2u) { /* the approximation and the coarsest details: no parent */
            for (; i < n; i++) {
                unsigned yb = y ? y[i] : lb;
                F_ONE(i, 2u * ((lb & 31u) + (yb & 31u)), yb);
            }
            continue;
        }
        const uint8_t *p = cb + sb->lo[b - 1u];
        uint32_t pl = lo - sb->lo[b - 1u], pairs = n / 2u < pl ? n / 2u : pl;
        if (y) {
            for (uint32_t q = 0; q < pairs; q++, i += 2u) { /* two children a parent */
                unsigned pe2 = 2u * (p[q] & 31u), yb = y[i];
                F_ONE(i, pe2 + (lb & 31u) + (yb & 31u), yb);
                yb = y[i + 1u];
                F_ONE(i + 1u, pe2 + (lb & 31u) + (yb & 31u), yb);
            }
        } else {
            for (uint32_t q = 0; q < pairs; q++, i += 2u) {
                unsigned pe2 = 2u * (p[q] & 31u);
                F_ONE(i, pe2 + 2u * (lb & 31u), lb);
                F_ONE(i + 1u, pe2 + 2u * (lb & 31u), lb);
            }
        }
        for (; i < n; i++) { /* a last child, or those of the last parent */
            uint32_t pi = i >> 1;
            unsigned yb = y ? y[i] : lb;
            F_ONE(i, 2u * (p[pi < pl ? pi : pl - 1u] & 31u) + (lb & 31u) + (yb & 31u), yb);
        }
    }
#undef F_ONE
#undef F_BITS
#undef F_ADD
#undef F_RENORM
    *low_ = low;
    *range_ = range;
    *lb_ = lb;
    return o;
}

/* The vectors from it holding n coefficients (left past them), counted
 * (every one, or every SAMPLE-th of a body of SAMPLE_MIN or more, each
 * count weighted by the vectors it stands for) or coded: whole vectors
 * without a parent vector subband by subband (coded with tab_code_fast
 * where the work array has room for the bytes of two vectors and the
 * output for one vector), the others element by element. */
static BW_ALWAYS_INLINE void tab_pass(bw_tab_models_t *m, tab_state_t *st, bw_iter_t *it,
                                      size_t n, bool code)
{
    const bw_plan_t *pl = it->pl;
    uint32_t b = pl->dims.bands, every = code || n / b < SAMPLE_MIN ? 1u : SAMPLE, i = 0;
    const int32_t *sc = pl->spec_cls;
    spec_bands_t sb;
    bw_spec_bands(pl, &sb);
    /* the bytes of two vectors (tab_code_fast) after the plan's tables, in
     * the n / 16 + 24 words that BW_WORK_BOUND leaves there */
    uint8_t *pb = (uint8_t *)(pl->spec_cls + 2u * b), *cb = pb + b;
    bool room = code && pl->basis != BW_BASIS_PRED && 2u * (size_t)b <= 4u * (pl->n / 16u + 24u);
    const int32_t *pb_of = NULL; /* the vector whose bytes pb holds */
    while (n) {
        uint32_t k0 = it->k, k1 = n < b - k0 ? k0 + (uint32_t)n : b;
        const int32_t *v = it->vec, *par = it->par, *prv = it->prev;
        unsigned cd = it->cls_dir;
        bool whole = !par && k0 == 0u && k1 == b;
        if (room && whole && (!prv || prv == pb_of) && st->pos <= st->cap &&
            st->cap - st->pos >= TAB_VEC_MAX(b)) {
            unsigned lb = st->el | (st->ln << 5);
            uint8_t *o = tab_code_fast(st->out + st->pos, &st->low, &st->range, &lb, m, v, &sb, sc,
                                       cd, prv ? pb : NULL, cb);
            st->pos = (size_t)(o - st->out);
            st->el = lb & 31u;
            st->ln = lb >> 5;
            uint8_t *t = pb;
            pb = cb;
            cb = t;
            pb_of = v;
        } else if (!code && i++ % every != 0u) {
            /* not counted */
        } else if (whole) {
            bool all = code || (i - 1u) % (2u * every) == 0u;
            pb_of = NULL;
            if (prv)
                tab_subbands(m, st, v, &sb, sc, cd, prv, every, all, code, true);
            else
                tab_subbands(m, st, v, &sb, sc, cd, prv, every, all, code, false);
        } else {
            pb_of = NULL;
            st->w = every;
            if (par && prv)
                tab_elems(m, st, v, k0, k1, sc, cd, par, prv, code, true, true);
            else if (par)
                tab_elems(m, st, v, k0, k1, sc, cd, par, prv, code, true, false);
            else if (prv)
                tab_elems(m, st, v, k0, k1, sc, cd, par, prv, code, false, true);
            else
                tab_elems(m, st, v, k0, k1, sc, cd, par, prv, code, false, false);
        }
        n -= k1 - k0;
        if (k1 == b)
            bw_iter_next_vec(it);
        else
            it->k = k1;
    }
}

/* tab_pass, each way in a copy of its own */
static BW_NOINLINE void tab_count(bw_tab_models_t *m, tab_state_t *st, bw_iter_t *it, size_t n)
{
    tab_pass(m, st, it, n, false);
}

static BW_NOINLINE void tab_code(bw_tab_models_t *m, tab_state_t *st, bw_iter_t *it, size_t n)
{
    tab_pass(m, st, it, n, true);
}

/* A split of a pair of counts (a the second's) in 1/32, rounded. */
static unsigned split_of(uint32_t a, uint32_t t)
{
    uint32_t p = t ? (a * (1u << SPLIT_BITS) + t / 2u) / t : 0u;
    return p > (1u << SPLIT_BITS) - 1u ? (1u << SPLIT_BITS) - 1u : p;
}

/* The bits (Q16) of the symbols counted in cnt[] coded with the table cum,
 * with the bits below their leading ones (escapes as 16 of them); *counted
 * adds their number. */
static uint64_t code_bits(const uint16_t *cnt, const uint16_t *cum, uint64_t *counted)
{
    uint64_t bits = 0;
    for (unsigned j = 0; j < BW_TAB_SYMS; j++) {
        unsigned e = j >> 1, raw = e < 2u ? 0u : e < E_ESC ? e - 1u : 16u + ESC_BITS;
        bits += (uint64_t)cnt[j] * (((TAB_BITS + raw) << 16) - bw_log2_q16(cum[j + 1u] - cum[j]));
        *counted += cnt[j];
    }
    return bits;
}

size_t bw_tab_encode(bw_iter_t *it, size_t n, bw_tab_models_t *m, uint8_t *out, size_t cap,
                     unsigned min_q8, bool *over)
{
    tab_state_t st = {out, 0u, out ? cap : 0u, 0u, 0xFFFFFFFFu, 0u, 0u, 1u};
    uint64_t est = 0, counted = 0; /* the code's bits (Q16) of the symbols counted, their number */
    bw_iter_t first = *it;
    memset(m, 0, sizeof *m);
    tab_count(m, &st, &first, n);
    /* the classes with a table, then each table of those (a flag, what it
     * holds), each built from what it sent; the others alike */
    uint32_t classes = 0;
    for (unsigned c = 0; c < BW_TAB_CTX; c++)
        for (unsigned j = 0; j < BW_TAB_SYMS; j++)
            if (m->cum[c][j])
                classes |= 1u << (c / BW_TAB_BINS);
    T_BITS(st, classes, BW_CODER_CLASSES);
    uint16_t none[ROW];
    tab_build(none, NULL, 0u, 0u);
    for (unsigned c = 0; c < BW_TAB_CTX; c++) {
        uint16_t *h = m->cum[c];
        uint32_t w[NE], a1 = 0, t1 = 0, all = 0;
        unsigned hi = 0;
        for (unsigned e = 0; e < NE; e++) {
            w[e] = (uint32_t)h[2u * e] + h[2u * e + 1u];
            all += w[e];
            if (w[e])
                hi = e + 1u;
            if (e) {
                a1 += h[2u * e + 1u];
                t1 += w[e];
            }
        }
        if (all < TAB_MIN_COUNT) /* too few to pay for a table */
            hi = 0;
        if (classes >> (c / BW_TAB_BINS) & 1u)
            T_BITS(st, hi != 0u, 1u);
        if (!hi) { /* the table of the bin before in its class, or one alike */
            const uint16_t *from = c % BW_TAB_BINS ? m->cum[c - 1u] : none;
            if (min_q8 && all)
                est += code_bits(h, from, &counted);
            memcpy(h, from, sizeof none);
            continue;
        }
        hi--;
        uint8_t q[NE];
        T_BITS(st, hi, HI_BITS);
        for (unsigned e = 0; e <= hi; e++) {
            q[e] = (uint8_t)(w[e] ? q_of(w[e]) : 0u);
            if (!e) {
                T_BITS(st, q[e], Q_BITS);
                continue;
            }
            /* the difference from the entry before, zigzag, Exp-Golomb of
             * order 1: nb zeros and a one, a bit at a time (as the decoder
             * reads them), then the nb + 1 low bits */
            int dq = (int)q[e] - (int)q[e - 1u];
            uint32_t z = dq < 0 ? 2u * (uint32_t)(-dq) - 1u : 2u * (uint32_t)dq, zz = z + 2u;
            unsigned nb = bw_bitlen(zz) - 2u;
            for (unsigned z0 = 0; z0 < nb; z0++)
                T_BITS(st, 0u, 1u);
            T_BITS(st, 1u, 1u);
            T_BITS(st, zz & ((1u << (nb + 1u)) - 1u), nb + 1u);
        }
        unsigned pm = split_of(a1, t1);
        if (hi)
            T_BITS(st, pm, SPLIT_BITS);
        uint16_t cum[ROW];
        tab_build(cum, q, hi, pm);
        if (min_q8)
            est += code_bits(h, cum, &counted);
        memcpy(h, cum, sizeof cum);
    }
    /* fewer than min_q8 / 256 bits a coefficient as the counts estimate
     * them, tables included: declined */
    if (min_q8 && counted &&
        ((est >> 16) * 256u + (uint64_t)st.pos * 8u * 256u * counted / (n ? n : 1u)) <
            (uint64_t)min_q8 * counted)
        return SIZE_MAX;
    /* pass 2: the code */
    st.el = st.ln = 0;
    tab_code(m, &st, it, n);
    /* the range coder's end (bw_rc_enc_finish) */
    bw_rc_enc_t rc;
    bw_rc_enc_init(&rc, out, cap);
    rc.pos = st.pos;
    rc.overflow = out && st.pos > cap;
    rc.low = st.low;
    rc.range = st.range;
    size_t len = bw_rc_enc_finish(&rc);
    *over = rc.overflow;
    return len;
}

/* ---- decoder --------------------------------------------------------------- */

/* Bands k0..k1-1 of vector v decoded, element by element (the contexts of
 * tab_elems). false: a corrupt code. */
static BW_ALWAYS_INLINE bool tab_vector_dec(const bw_tab_models_t *m, bw_rc_dec_t *d,
                                            unsigned *el_, unsigned *ln_, int32_t *v,
                                            uint32_t k0, uint32_t k1, const int32_t *spec_cls,
                                            unsigned cd, const int32_t *par, const int32_t *prv,
                                            bool has_par, bool has_prev)
{
    unsigned el = *el_, ln = *ln_;
    for (uint32_t k = k0; k < k1; k++) {
        int32_t ya = has_prev ? prv[k] : 0;
        const uint16_t *cum =
            m->cum[elem_ctx(v, k, spec_cls[k], el, cd, par, ya, has_par, has_prev)];
        uint32_t r = d->range >> TAB_BITS, c = d->code / r;
        if (c >= TAB_ONE)
            return false; /* past the total */
        unsigned j = 0;
        while (cum[j + 1u] <= c)
            j++;
        d->code -= r * cum[j];
        d->range = r * (uint32_t)(cum[j + 1u] - cum[j]);
        bw_rc_dec_renorm(d);
        unsigned e = j >> 1, neg = (ya ? (uint32_t)ya >> 31 : ln) ^ (j & 1u);
        if (!e) { /* (symbol 1 is never coded) */
            v[k] = 0;
            el = ln = 0;
            continue;
        }
        if (e == E_ESC) {
            e += bw_rc_dec_bits(d, ESC_BITS);
            if (e > 31u)
                return false;
        }
        uint32_t a = 1;
        unsigned nb = e - 1u;
        if (nb > 16u) {
            a = (a << (nb - 16u)) | bw_rc_dec_bits(d, nb - 16u);
            nb = 16u;
        }
        if (nb)
            a = (a << nb) | bw_rc_dec_bits(d, nb);
        v[k] = neg ? (int32_t)(0u - a) : (int32_t)a;
        el = e;
        ln = neg;
    }
    *el_ = el;
    *ln_ = ln;
    return true;
}

bw_status_t bw_tab_decode(bw_iter_t *it, size_t n, const uint8_t *in, size_t len,
                          bw_tab_models_t *m)
{
    bw_rc_dec_t d;
    bw_rc_dec_init(&d, in, len);
    uint32_t classes = bw_rc_dec_bits(&d, BW_CODER_CLASSES);
    uint16_t none[ROW];
    tab_build(none, NULL, 0u, 0u);
    for (unsigned c = 0; c < BW_TAB_CTX; c++) {
        uint16_t *cum = m->cum[c];
        if (!(classes >> (c / BW_TAB_BINS) & 1u) || !bw_rc_dec_bits(&d, 1u)) {
            memcpy(cum, c % BW_TAB_BINS ? m->cum[c - 1u] : none, sizeof none);
            continue;
        }
        unsigned hi = bw_rc_dec_bits(&d, HI_BITS), pm = 0;
        uint8_t q[NE];
        if (hi >= NE)
            return BW_ERR_CORRUPT;
        q[0] = (uint8_t)bw_rc_dec_bits(&d, Q_BITS);
        for (unsigned e = 1; e <= hi; e++) {
            unsigned nb = 0;
            while (!bw_rc_dec_bits(&d, 1u))
                if (++nb > 6u)
                    return BW_ERR_CORRUPT;
            uint32_t zz = (1u << (nb + 1u)) | bw_rc_dec_bits(&d, nb + 1u), z = zz - 2u;
            int dq = z & 1u ? -(int)((z + 1u) >> 1) : (int)(z >> 1), qe = (int)q[e - 1u] + dq;
            if (qe < 0 || qe > (int)Q_MAX)
                return BW_ERR_CORRUPT;
            q[e] = (uint8_t)qe;
        }
        if (hi)
            pm = bw_rc_dec_bits(&d, SPLIT_BITS);
        if (!tab_build(cum, q, hi, pm))
            return BW_ERR_CORRUPT;
    }
    const bw_plan_t *pl = it->pl;
    uint32_t b = pl->dims.bands;
    const int32_t *sc = pl->spec_cls;
    unsigned el = 0, ln = 0;
    while (n) {
        uint32_t k0 = it->k, k1 = n < b - k0 ? k0 + (uint32_t)n : b;
        int32_t *v = it->vec;
        const int32_t *par = it->par, *prv = it->prev;
        unsigned cd = it->cls_dir;
        bool ok =
            par && prv ? tab_vector_dec(m, &d, &el, &ln, v, k0, k1, sc, cd, par, prv, true, true)
            : par      ? tab_vector_dec(m, &d, &el, &ln, v, k0, k1, sc, cd, par, prv, true, false)
            : prv      ? tab_vector_dec(m, &d, &el, &ln, v, k0, k1, sc, cd, par, prv, false, true)
                       : tab_vector_dec(m, &d, &el, &ln, v, k0, k1, sc, cd, par, prv, false, false);
        if (!ok)
            return BW_ERR_CORRUPT;
        n -= k1 - k0;
        if (k1 == b)
            bw_iter_next_vec(it);
        else
            it->k = k1;
    }
    /* a whole code is read to 3 or 4 bytes past its end: more, a cut body */
    return d.pos > d.len + 4u ? BW_ERR_CORRUPT : BW_OK;
}

#endif
