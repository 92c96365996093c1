/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Integer spectral lifting: S-transform (Haar), LeGall 5/3 and CDF 9/7.
 *
 * Scaling and overflow: samples are |x| <= 2^24. Haar and 5/3 details grow by
 * at most 1 bit a level, approximations stay within the input range; the
 * unnormalised 9/7 grows by at most 3 bits a level in the detail band
 * (1 + 2|alpha| < 4.2) and stays within a factor 1.2 in the approximation.
 * Lifting sums are formed modulo 2^32 and the 9/7 products in 64 bits: for
 * |x| <= 2^24 no sum exceeds 2^31 (the largest, a sum of two 9/7 details
 * after 12 levels, stays below 2^30.4), and beyond the documented range the
 * coefficients wrap, which keeps the transform reversible (bw_fixed.h).
 *
 *   basis  predict (d += ...)               update (s += ...)
 *   Haar   -s[k]                             floor(d[k] / 2)
 *   5/3    -floor((s[k] + s[k+1]) / 2)       floor((d[k-1] + d[k] + 2) / 4)
 *   9/7    round(A (s[k] + s[k+1]))          round(B (d[k-1] + d[k]))
 *          round(C (s[k] + s[k+1]))          round(D (d[k-1] + d[k]))
 * with A..D the CDF 9/7 lifting constants in Q16; the final scaling by K is
 * left out (it is not reversible on integers) and accounted for in the
 * quantiser's gain table instead.
 */
#include "bw_spectral.h"

#include <stdbool.h>
#include <string.h>

#include "bw_codec.h"
#include "bw_fixed.h"

#define Q16_A (-103949) /* -1.586134342 */
#define Q16_B (-3472)   /* -0.052980118 */
#define Q16_C (57863)   /*  0.882911075, rounded so that a constant signal leaves no detail */
#define Q16_D (29066)   /*  0.443506852 */

unsigned bw_spec_levels(uint32_t bands)
{
    unsigned levels = 0;
    while (bands > 4u && levels < BW_SPEC_MAX_LEVELS) {
        bands = (bands + 1u) / 2u;
        levels++;
    }
    return levels;
}

uint32_t bw_spec_approx_len(uint32_t n, unsigned levels)
{
    while (levels--)
        n = (n + 1u) / 2u;
    return n;
}

unsigned bw_spec_subband(uint32_t n, unsigned levels, uint32_t k)
{
    /* len[l] = approximation length after l levels; band l occupies
     * [len[l], len[l-1]). */
    uint32_t len = n;
    for (unsigned l = 1; l <= levels; l++) {
        uint32_t next = (len + 1u) / 2u;
        if (k >= next)
            return l;
        len = next;
    }
    return 0;
}

/* bw_mul_q16_round(c, v) for a constant c = hi 2^16 + lo (|lo| < 2^15):
 * hi v + floor((lo v + 2^15) / 2^16), the same integer, whose second term
 * is the rounded high word of (lo 2^16) v, one SMMULR where the core has
 * it. */
#define Q16_HI(c) (((c) + 32768) >> 16)
#define Q16_LO(c) ((c) - Q16_HI(c) * 65536)
static inline int32_t mul_q16_split(int32_t hi, int32_t lo16, int32_t v)
{
#if defined(__ARM_FEATURE_DSP) && defined(__GNUC__)
    int32_t r;
    __asm__("smmulr %0, %1, %2" : "=r"(r) : "r"(lo16), "r"(v));
#else
    int32_t r = (int32_t)bw_asr64((int64_t)lo16 * v + 0x80000000LL, 32);
#endif
    return bw_wadd((int32_t)((uint32_t)hi * (uint32_t)v), r);
}

_Static_assert(Q16_LO(Q16_A) >= -32768 && Q16_LO(Q16_A) < 32768 && Q16_LO(Q16_B) >= -32768 &&
                   Q16_LO(Q16_B) < 32768 && Q16_LO(Q16_C) >= -32768 && Q16_LO(Q16_C) < 32768 &&
                   Q16_LO(Q16_D) >= -32768 && Q16_LO(Q16_D) < 32768,
               "9/7 constants split into hi 2^16 + lo with |lo| < 2^15");

/* Lifting steps with whole-sample symmetric extension: a neighbour index
 * outside its subband is clamped into it. The interior runs without the
 * clamp; only the first and last positions need it.
 *
 * predict: d[k] +/-= f(s[k] + s[k+1])      k = 0 .. nd-1, s[ns] -> s[ns-1]
 * update:  s[k] +/-= f(d[k-1] + d[k])      k = 0 .. ns-1, d[-1] -> d[0],
 *                                                          d[nd] -> d[nd-1]
 * f is round(c x / 2^16) for the 9/7 constants, floor(x / 2) for the 5/3
 * predict and floor((x + 2) / 4) for its update. */
enum { F_Q16, F_HALF, F_QUARTER };

static inline int32_t lift_f(int kind, q16_t c, int32_t sum)
{
    if (kind == F_HALF)
        return bw_asr32(sum, 1);
    if (kind == F_QUARTER)
        return bw_asr32(bw_wadd(sum, 2), 2);
#if BW_CFG_FAST_SPECTRAL
    return mul_q16_split(Q16_HI(c), Q16_LO(c) * 65536, sum); /* c folded: constants */
#else
    return bw_mul_q16_round(c, sum);
#endif
}

/* The lifting, one copy per basis and direction with the steps' constants
 * folded in (BW_CFG_FAST_SPECTRAL), else one copy run through the steps. */
#if BW_CFG_FAST_SPECTRAL
#define STEP_INLINE BW_ALWAYS_INLINE
#define LIFT_INLINE BW_ALWAYS_INLINE
#define LIFT_UNROLL _Pragma("GCC unroll 4")
#else
#define STEP_INLINE inline
#define LIFT_INLINE
#define LIFT_UNROLL
#endif

static STEP_INLINE void predict(int32_t *d, uint32_t nd, const int32_t *s, uint32_t ns, int kind,
                                q16_t c, int sign)
{
    uint32_t inner = nd < ns ? nd : ns - 1u; /* k + 1 < ns */
    uint32_t k = 0;
    for (; k < inner; k++) {
        int32_t t = lift_f(kind, c, bw_wadd(s[k], s[k + 1]));
        d[k] = sign > 0 ? bw_wadd(d[k], t) : bw_wsub(d[k], t);
    }
    for (; k < nd; k++) {
        int32_t t = lift_f(kind, c, bw_wadd(s[k], s[ns - 1u]));
        d[k] = sign > 0 ? bw_wadd(d[k], t) : bw_wsub(d[k], t);
    }
}

static STEP_INLINE void update(int32_t *s, uint32_t ns, const int32_t *d, uint32_t nd, int kind,
                               q16_t c, int sign)
{
    /* k = 0 uses d[0] twice; k >= nd uses d[nd-1] for the missing d[k] */
    uint32_t inner = nd < ns ? nd : ns;
    int32_t t = lift_f(kind, c, bw_wadd(d[0], d[0]));
    s[0] = sign > 0 ? bw_wadd(s[0], t) : bw_wsub(s[0], t);
    uint32_t k = 1;
    for (; k < inner; k++) {
        t = lift_f(kind, c, bw_wadd(d[k - 1u], d[k]));
        s[k] = sign > 0 ? bw_wadd(s[k], t) : bw_wsub(s[k], t);
    }
    for (; k < ns; k++) {
        t = lift_f(kind, c, bw_wadd(d[k - 1u], d[nd - 1u]));
        s[k] = sign > 0 ? bw_wadd(s[k], t) : bw_wsub(s[k], t);
    }
}

/* The lifting steps of one level on s[ns], d[nd], in forward order: a
 * predict (d from s) or an update (s from d), its f and constant, and the
 * sign of the forward step; the inverse runs them backwards with the other
 * sign. The Haar steps, d -= s[k] and s += floor(d[k] / 2), use one sample,
 * not two, and are written out. */
typedef struct {
    uint8_t update, kind;
    int8_t sign;
    q16_t c;
} lift_step_t;

static const lift_step_t lift_53[2] = {{0, F_HALF, -1, 0}, {1, F_QUARTER, +1, 0}};
static const lift_step_t lift_97[4] = {
    {0, F_Q16, +1, Q16_A}, {1, F_Q16, +1, Q16_B}, {0, F_Q16, +1, Q16_C}, {1, F_Q16, +1, Q16_D}};

/* The steps of a table from first to last, or (inverse) from last to first
 * with the other sign. */
#define LIFT_STEPS(st, n, s, ns, d, nd, inverse)                                 \
    do {                                                                         \
        LIFT_UNROLL                                                              \
        for (unsigned i_ = 0; i_ < (n); i_++) {                                  \
            const lift_step_t *p_ = &(st)[(inverse) ? (n) - 1u - i_ : i_];       \
            int sign_ = (inverse) ? -p_->sign : p_->sign;                        \
            if (p_->update)                                                      \
                update(s, ns, d, nd, p_->kind, p_->c, sign_);                    \
            else                                                                 \
                predict(d, nd, s, ns, p_->kind, p_->c, sign_);                   \
        }                                                                        \
    } while (0)

static LIFT_INLINE void lift(int32_t *s, uint32_t ns, int32_t *d, uint32_t nd, unsigned basis,
                             bool inverse)
{
    if (basis == BW_BASIS_HAAR) {
        for (uint32_t k = 0; k < nd; k++) {
            if (inverse) {
                s[k] = bw_wsub(s[k], bw_asr32(d[k], 1));
                d[k] = bw_wadd(d[k], s[k]);
            } else {
                d[k] = bw_wsub(d[k], s[k]);
                s[k] = bw_wadd(s[k], bw_asr32(d[k], 1));
            }
        }
        return;
    }
#if BW_CFG_FAST_SPECTRAL
    /* a constant table each: its steps fold into the code */
    if (basis == BW_BASIS_53)
        LIFT_STEPS(lift_53, 2u, s, ns, d, nd, inverse);
    else
        LIFT_STEPS(lift_97, 4u, s, ns, d, nd, inverse);
#else
    const lift_step_t *st = basis == BW_BASIS_53 ? lift_53 : lift_97;
    unsigned n = basis == BW_BASIS_53 ? 2u : 4u;
    LIFT_STEPS(st, n, s, ns, d, nd, inverse);
#endif
}

/* Haar and 5/3 in one pass over the interleaved samples (the same values
 * as lift_fwd / lift_inv on the split halves): the approximation is written
 * in place at x[k] (every sample it overwrites has been read), the details
 * go through tmp. */
static void fwd_haar(int32_t *x, uint32_t ns, uint32_t nd, int32_t *tmp)
{
    for (uint32_t k = 0; k < nd; k++) {
        int32_t e = x[2u * k], d = bw_wsub(x[2u * k + 1u], e);
        x[k] = bw_wadd(e, bw_asr32(d, 1));
        tmp[k] = d;
    }
    if (ns > nd)
        x[nd] = x[2u * nd];
    memcpy(x + ns, tmp, (size_t)nd * sizeof *x);
}

static void inv_haar(int32_t *x, uint32_t ns, uint32_t nd, int32_t *tmp)
{
    memcpy(tmp, x + ns, (size_t)nd * sizeof *x);
    if (ns > nd)
        x[2u * nd] = x[nd];
    for (uint32_t k = nd; k-- > 0;) {
        int32_t d = tmp[k], e = bw_wsub(x[k], bw_asr32(d, 1));
        x[2u * k + 1u] = bw_wadd(d, e);
        x[2u * k] = e;
    }
}

static inline int32_t p53(int32_t a, int32_t b) { return bw_asr32(bw_wadd(a, b), 1); }
static inline int32_t u53(int32_t a, int32_t b) { return bw_asr32(bw_wadd(bw_wadd(a, b), 2), 2); }

/* Where a forward pass (fwd_53, fwd_97) reads its samples: in place
 * (FROM_SELF), or apart from the caller's samples as the load takes them
 * (bw_prequant_t), each once, without (FROM_IN) or with the prequantiser
 * (FROM_IN_Q), the range check's OR gathered in *acc. */
enum { FROM_SELF, FROM_IN, FROM_IN_Q };

static BW_ALWAYS_INLINE int32_t rd_at(const int32_t *src, uint32_t i, int how,
                                     const bw_prequant_t *pq, uint32_t *acc)
{
    int32_t v = src[i];
    if (how == FROM_SELF)
        return v;
    *acc |= (uint32_t)(v ^ bw_asr32(v, 31));
    return how == FROM_IN ? v : (int32_t)(((uint32_t)v + pq->bias) / pq->q - pq->k);
}

/* n >= 3, so ns >= 2 and nd >= 1: from src into [s | d] at dst, in place
 * (src is dst, the details through tmp) or apart (how, pq, acc: rd_at),
 * each sample read once. */
static BW_ALWAYS_INLINE void fwd_53(int32_t *dst, const int32_t *src, uint32_t ns, uint32_t nd,
                                    int32_t *tmp, int how, const bw_prequant_t *pq,
                                    uint32_t *acc)
{
    int32_t *det = how == FROM_SELF ? tmp : dst + ns;
    uint32_t inner = nd < ns - 1u ? nd : ns - 1u; /* k with k + 1 < ns and k < nd */
    int32_t e = rd_at(src, 0, how, pq, acc), o = rd_at(src, 1, how, pq, acc);
    int32_t enext = rd_at(src, 2, how, pq, acc); /* x[2 k + 2] below */
    int32_t dprev = bw_wsub(o, p53(e, enext));
    dst[0] = bw_wadd(e, u53(dprev, dprev));
    det[0] = dprev;
    uint32_t k = 1;
    for (; k < inner; k++) {
        e = enext;
        o = rd_at(src, 2u * k + 1u, how, pq, acc);
        enext = rd_at(src, 2u * k + 2u, how, pq, acc);
        int32_t d = bw_wsub(o, p53(e, enext));
        dst[k] = bw_wadd(e, u53(dprev, d));
        det[k] = d;
        dprev = d;
    }
    if (k < nd) { /* n even: the last detail's right neighbour is itself */
        e = enext;
        int32_t d = bw_wsub(rd_at(src, 2u * k + 1u, how, pq, acc), p53(e, e));
        dst[k] = bw_wadd(e, u53(dprev, d));
        det[k] = d;
        dprev = d;
        k++;
    }
    if (k < ns) /* n odd: the last approximation sample, d[nd] -> d[nd - 1] */
        dst[k] = bw_wadd(enext, u53(dprev, dprev));
    if (how == FROM_SELF)
        memcpy(dst + ns, tmp, (size_t)nd * sizeof *dst);
}

static void inv_53(int32_t *x, uint32_t ns, uint32_t nd, int32_t *tmp)
{
    memcpy(tmp, x + ns, (size_t)nd * sizeof *x);
    int32_t snext;
    uint32_t k = ns - 1u;
    if (ns > nd) { /* n odd */
        snext = bw_wsub(x[k], u53(tmp[nd - 1u], tmp[nd - 1u]));
        x[2u * k] = snext;
    } else {
        int32_t d = tmp[k];
        snext = bw_wsub(x[k], u53(k ? tmp[k - 1u] : d, d));
        x[2u * k + 1u] = bw_wadd(d, p53(snext, snext));
        x[2u * k] = snext;
    }
    while (k-- > 1u) {
        int32_t d = tmp[k];
        int32_t e = bw_wsub(x[k], u53(tmp[k - 1u], d));
        x[2u * k + 1u] = bw_wadd(d, p53(e, snext));
        x[2u * k] = e;
        snext = e;
    }
    int32_t d = tmp[0];
    int32_t e = bw_wsub(x[0], u53(d, d));
    x[1] = bw_wadd(d, p53(e, snext));
    x[0] = e;
}

/* 9/7 in one pass over the interleaved samples (the same values as the four
 * lifting steps one after the other): at sample pair j the first predict
 * and update give d1[j] and s1[j], the second pair d2[j - 1] and s2[j - 1],
 * each from neighbours the pass has just formed; the neighbours outside
 * the signal are clamped as lift() clamps them. In place, the
 * approximation goes to x[j - 1] (every sample it overwrites has been read),
 * the details through tmp; apart, each straight to its place. n >= 4, so
 * ns >= 2 and nd >= 2. */
#define lift97(base, c, a, b)                                                                     \
    bw_wadd((base), mul_q16_split(Q16_HI(c), Q16_LO(c) * 65536, bw_wadd((a), (b))))

/* The pass's state after pair j - 1: s0[j], d1[j - 1], s1[j - 1], d2[j - 2]. */
typedef struct {
    int32_t s0j, d1p, s1p, d2p;
} fwd97_t;

/* Pair j (j >= 1): d1[j] (has_d: j < nd; else d1[nd - 1] stands in), s1[j],
 * then d2[j - 1] and s2[j - 1] (first: j = 1, whose d2[-1] is d2[0]) into
 * dst[j - 1] and det[j - 1]; s0next is s0[j + 1], clamped. */
static BW_ALWAYS_INLINE void fwd97_pair(const int32_t *src, int32_t *dst, int32_t *det,
                                        uint32_t j, fwd97_t *f, int32_t s0next, bool has_d,
                                        bool first, int how, const bw_prequant_t *pq,
                                        uint32_t *acc)
{
    int32_t d1j = has_d ? lift97(rd_at(src, 2u * j + 1u, how, pq, acc), Q16_A, f->s0j, s0next)
                        : f->d1p;
    int32_t s1j = lift97(f->s0j, Q16_B, f->d1p, d1j);
    int32_t d2 = lift97(f->d1p, Q16_C, f->s1p, s1j);
    dst[j - 1u] = lift97(f->s1p, Q16_D, first ? d2 : f->d2p, d2);
    det[j - 1u] = d2;
    f->d2p = d2;
    f->d1p = d1j;
    f->s1p = s1j;
    f->s0j = s0next;
}

/* n = ns + nd >= 4 samples from src into [s | d] at dst: in place (src is
 * dst, the details through tmp), or apart (how, pq, acc: rd_at). */
static BW_ALWAYS_INLINE void fwd_97(int32_t *dst, const int32_t *src, uint32_t ns, uint32_t nd,
                                    int32_t *tmp, int how, const bw_prequant_t *pq,
                                    uint32_t *acc)
{
    int32_t *det = how == FROM_SELF ? tmp : dst + ns;
    int32_t s0 = rd_at(src, 0, how, pq, acc), x1 = rd_at(src, 1, how, pq, acc);
    int32_t x2 = rd_at(src, 2, how, pq, acc), d1 = lift97(x1, Q16_A, s0, x2); /* d1[0] */
    fwd97_t f = {x2, d1, lift97(s0, Q16_B, d1, d1), 0};
    /* j with j < nd and j + 1 < ns: every neighbour inside */
    uint32_t inner = nd < ns - 1u ? nd : ns - 1u, j = 1;
    if (j < inner)
        fwd97_pair(src, dst, det, j++, &f, rd_at(src, 4, how, pq, acc), true, true, how, pq, acc);
    for (; j < inner; j++)
        fwd97_pair(src, dst, det, j, &f, rd_at(src, 2u * j + 2u, how, pq, acc), true, false, how,
                   pq, acc);
    for (; j < ns; j++) /* the last one or two: ns == nd (s0 clamped), or j == nd */
        fwd97_pair(src, dst, det, j, &f, f.s0j, j < nd, j == 1u, how, pq, acc);
    int32_t s1p = f.s1p, d1p = f.d1p, d2p = f.d2p;
    if (ns == nd) { /* the last detail: s1[ns] -> s1[ns - 1] */
        int32_t d2 = lift97(d1p, Q16_C, s1p, s1p);
        dst[ns - 1u] = lift97(s1p, Q16_D, d2p, d2);
        det[ns - 1u] = d2;
    } else { /* the last approximation: d2[nd] -> d2[nd - 1] */
        dst[ns - 1u] = lift97(s1p, Q16_D, d2p, d2p);
    }
    if (how == FROM_SELF)
        memcpy(dst + ns, tmp, (size_t)nd * sizeof *dst);
}

#if BW_CFG_FAST_LOADS
/* each of them in a function of its own (how constant), over every vector */
#define LOAD_LIFT(name, fwd, how)                                                                \
    static BW_NOINLINE uint32_t name(int32_t *out, const int32_t *in, size_t vectors,           \
                                     uint32_t n, const bw_prequant_t *pq)                        \
    {                                                                                            \
        uint32_t acc = 0;                                                                        \
        for (size_t v = 0; v < vectors; v++)                                                     \
            fwd(out + v * n, in + v * n, (n + 1u) / 2u, n / 2u, NULL, how, pq, &acc);           \
        return acc;                                                                              \
    }
LOAD_LIFT(load_53, fwd_53, FROM_IN)
LOAD_LIFT(load_53_q, fwd_53, FROM_IN_Q)
LOAD_LIFT(load_97, fwd_97, FROM_IN)
LOAD_LIFT(load_97_q, fwd_97, FROM_IN_Q)

uint32_t bw_spec_fwd1_load(int32_t *out, const int32_t *in, size_t vectors, uint32_t n,
                           unsigned basis, const bw_prequant_t *pq)
{
    if (basis == BW_BASIS_53)
        return (pq->q == 1u ? load_53 : load_53_q)(out, in, vectors, n, pq);
    return (pq->q == 1u ? load_97 : load_97_q)(out, in, vectors, n, pq);
}
#endif

/* 9/7 inverse in two passes, each two lifting steps pipelined: an update
 * undone on S[k] (from D[k-1], D[k]), then a predict undone on D[k-1] (from
 * S[k-1], S[k]) as soon as S[k] is known; neighbours clamped as lift()
 * clamps them. The second pass writes the samples interleaved into out. */
#define UNLIFT97(c, a, b) mul_q16_split(Q16_HI(c), Q16_LO(c) * 65536, bw_wadd((a), (b)))
/* S[k] from D[k - 1] and dr (D[k], or its clamped stand-in), then D[k - 1]
 * from S[k - 1] (sp) and S[k]; returns S[k]. */
static BW_ALWAYS_INLINE int32_t inv97_at(int32_t *S, int32_t *D, uint32_t k, int32_t dr,
                                         int32_t sp, q16_t cu, q16_t cp, int32_t *out)
{
    int32_t sk = bw_wsub(S[k], UNLIFT97(cu, D[k - 1u], dr));
    int32_t dk = bw_wsub(D[k - 1u], UNLIFT97(cp, sp, sk));
    S[k] = sk;
    D[k - 1u] = dk;
    if (out) {
        out[2u * k] = sk;
        out[2u * k - 1u] = dk;
    }
    return sk;
}

static BW_ALWAYS_INLINE void inv97_pass(int32_t *S, uint32_t ns, int32_t *D, uint32_t nd,
                                        q16_t cu, q16_t cp, int32_t *out)
{
    int32_t sp = bw_wsub(S[0], UNLIFT97(cu, D[0], D[0]));
    S[0] = sp;
    if (out)
        out[0] = sp;
    uint32_t inner = nd < ns ? nd : ns, k = 1;
    for (; k < inner; k++) /* D[k - 1] and D[k] both there */
        sp = inv97_at(S, D, k, D[k], sp, cu, cp, out);
    for (; k < ns; k++) /* n odd: the last S[k], D[nd] -> D[nd - 1] */
        sp = inv97_at(S, D, k, D[nd - 1u], sp, cu, cp, out);
    if (ns == nd) { /* n even: the last D, S[ns] -> S[ns - 1] */
        int32_t dk = bw_wsub(D[ns - 1u], UNLIFT97(cp, sp, sp));
        D[ns - 1u] = dk;
        if (out)
            out[2u * ns - 1u] = dk;
    }
}

/* n >= 4: the coefficients through tmp, the samples back into x */
static void inv_97(int32_t *x, uint32_t ns, uint32_t nd, int32_t *tmp)
{
    memcpy(tmp, x, (size_t)(ns + nd) * sizeof *x);
    inv97_pass(tmp, ns, tmp + ns, nd, Q16_D, Q16_C, NULL);
    inv97_pass(tmp, ns, tmp + ns, nd, Q16_B, Q16_A, x);
}

void bw_spec_fwd1(int32_t *x, uint32_t n, unsigned basis, int32_t *tmp)
{
    if (n < 2u)
        return;
    uint32_t ns = (n + 1u) / 2u, nd = n / 2u;
    /* without BW_CFG_FAST_SPECTRAL every basis is split and lifted alike */
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_HAAR) {
        fwd_haar(x, ns, nd, tmp);
        return;
    }
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_53 && n >= 3u) {
        fwd_53(x, x, ns, nd, tmp, FROM_SELF, NULL, NULL);
        return;
    }
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_97 && n >= 4u) {
        fwd_97(x, x, ns, nd, tmp, FROM_SELF, NULL, NULL);
        return;
    }
    for (uint32_t k = 0; k < ns; k++)
        tmp[k] = x[2u * k];
    for (uint32_t k = 0; k < nd; k++)
        tmp[ns + k] = x[2u * k + 1u];
    lift(tmp, ns, tmp + ns, nd, basis, false);
    memcpy(x, tmp, (size_t)n * sizeof *x);
}

void bw_spec_inv1(int32_t *x, uint32_t n, unsigned basis, int32_t *tmp)
{
    if (n < 2u)
        return;
    uint32_t ns = (n + 1u) / 2u, nd = n / 2u;
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_HAAR) {
        inv_haar(x, ns, nd, tmp);
        return;
    }
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_53 && n >= 3u) {
        inv_53(x, ns, nd, tmp);
        return;
    }
    if (BW_CFG_FAST_SPECTRAL && basis == BW_BASIS_97 && n >= 4u) {
        inv_97(x, ns, nd, tmp);
        return;
    }
    lift(x, ns, x + ns, nd, basis, true);
    for (uint32_t k = 0; k < ns; k++)
        tmp[2u * k] = x[k];
    for (uint32_t k = 0; k < nd; k++)
        tmp[2u * k + 1u] = x[ns + k];
    memcpy(x, tmp, (size_t)n * sizeof *x);
}

void bw_spec_fwd(int32_t *x, uint32_t n, unsigned basis, unsigned levels, int32_t *tmp)
{
    for (unsigned l = 0; l < levels && n >= 2u; l++) {
        bw_spec_fwd1(x, n, basis, tmp);
        n = (n + 1u) / 2u;
    }
}

void bw_spec_inv(int32_t *x, uint32_t n, unsigned basis, unsigned levels, int32_t *tmp)
{
    uint32_t len[BW_SPEC_MAX_LEVELS + 1u];
    if (levels > BW_SPEC_MAX_LEVELS)
        levels = BW_SPEC_MAX_LEVELS;
    len[0] = n;
    for (unsigned l = 1; l <= levels; l++)
        len[l] = (len[l - 1] + 1u) / 2u;
    for (unsigned l = levels; l-- > 0;)
        bw_spec_inv1(x, len[l], basis, tmp);
}

/* 65536 / sqrt(energy of the synthesis function) of each band of the
 * unnormalised liftings above, measured on long signals: detail bands by
 * level (1 = finest), approximation by depth. */
static const uint32_t inv_gain_det[BW_BASIS_COUNT][BW_SPEC_MAX_LEVELS] = {
    {92682, 65536, 46341, 32768, 23170, 16384, 11585, 8192, 5793, 4096, 2896, 2048},
    {77302, 68256, 52040, 37569, 26707, 18910, 13376, 9459, 6689, 4730, 3345, 2365},
    {73862, 66637, 55910, 47825, 41395, 35961, 31271, 27199, 23659, 20580, 17900, 15570},
};
static const uint32_t inv_gain_app[BW_BASIS_COUNT][BW_SPEC_MAX_LEVELS + 1] = {
    {65536, 46341, 32768, 23170, 16384, 11585, 8192, 5793, 4096, 2896, 2048, 1448, 1024},
    {65536, 53510, 39520, 28268, 20047, 14185, 10032, 7094, 5017, 3547, 2508, 1774, 1254},
    {65536, 57500, 48847, 42054, 36471, 31700, 27569, 23980, 20859, 18144, 15783, 13730, 11940},
};

uint32_t bw_spec_inv_gain_q16(unsigned basis, unsigned levels, unsigned subband)
{
    if (basis >= BW_BASIS_COUNT || levels > BW_SPEC_MAX_LEVELS || subband > levels)
        return 65536u;
    if (subband == 0)
        return inv_gain_app[basis][levels];
    return inv_gain_det[basis][subband - 1u];
}
