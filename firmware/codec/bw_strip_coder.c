/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The strip coder, encoder and decoder side by side (docs/FORMAT.md, Body
 * and Body with RICE): each strip of 32 coefficients as a presence flag,
 * then per element a valid bit and, for a non-zero value, its bit length
 * (a 5-bit tree), the bit below the leading one, the rest as direct bits
 * and the sign, each with its context; or, with BW_FLAG_RICE, the strip as
 * bw_rice.c codes it.
 */
#include <string.h>

#include "bw_strip_coder.h"

#define NB_CTX BW_CODER_NB_CTX

/* Contexts of a coefficient from the bit lengths of its neighbours
 * (NO_CTX: no such neighbour): its parent pe, the previous coefficient in
 * the strip and the one above it (the same band of the previous vector
 * when there is one, else the same place in the previous strip). */
#define NO_CTX 0xFFu

static inline unsigned ctx_len(const int32_t *p) { return p ? bw_bitlen(bw_abs32(*p)) : NO_CTX; }
/* sign context of a value: 0 none or zero, 1 positive, 2 negative */
static inline unsigned sign_ctx(const int32_t *p) { return p && *p ? 1u + (*p < 0) : 0u; }
/* the sign model of a value is left + this, left the sign context of the
 * previous value of the strip (0 for the first) */
static inline unsigned sign_ctx_up(const int32_t *par, const int32_t *prv)
{
    return 3u * (sign_ctx(par) + 3u * sign_ctx(prv));
}

void bw_models_init(bw_models_t *m, unsigned coder)
{
    if (BW_CFG_CODER_MS && coder == BW_CODER_MS) {
        bw_ms_models_t *ms = &m->ms;
        bw_prob_t *p = &ms->present[0][0];
        for (size_t i = 0; i < sizeof ms->present / sizeof *p; i++)
            p[i] = BW_PROB_INIT;
        p = &ms->valid[0][0][0];
        for (size_t i = 0; i < sizeof ms->valid / sizeof *p; i++)
            p[i] = BW_PROB_INIT;
        for (size_t i = 0; i < sizeof ms->sign / sizeof *p; i++)
            ms->sign[i] = BW_PROB_INIT;
        for (unsigned c = 0; c < BW_CODER_CLASSES; c++)
            for (unsigned k = 0; k < BW_CODER_NB_CTX; k++)
                bw_ms_model_init(&ms->e[c][k]);
        return;
    }
    bw_prob_t *p = (bw_prob_t *)&m->rc;
    size_t n = sizeof m->rc / sizeof *p;
#if BW_CFG_SPEED
    /* by doubling copies: a partial decode of many segments starts as many
     * models */
    p[0] = BW_PROB_INIT;
    for (size_t k = 1; k < n; k += k < n - k ? k : n - k)
        memcpy(p + k, p, (k < n - k ? k : n - k) * sizeof *p);
#else
    for (size_t i = 0; i < n; i++)
        p[i] = BW_PROB_INIT;
#endif
}

/* A strip with no value: the next strip's contexts above and to the left
 * are none. */
static inline void strip_none(bw_strip_state_t *s)
{
    s->prev_mask = 0;
#if BW_CFG_FAST_STRIPS
    for (unsigned i = 0; i < 8u; i++) /* in line, where memset is a call */
        s->e_above_w[i] = 0;
#else
    memset(s->e_above, 0, sizeof s->e_above);
#endif
    s->e_left = 0;
}

/* significance: the bit above, and whether the parent is zero, small or not */
static inline unsigned valid_ctx(unsigned above_bit, unsigned pe)
{
    return above_bit + (pe == 0u || pe == NO_CTX ? 0u : pe <= 2u ? 2u : 4u);
}

/* magnitude: the bit lengths of the left and above neighbours, and of the
 * parent when there is one */
static inline unsigned mag_ctx(unsigned left, unsigned above, unsigned pe)
{
    unsigned c = pe == NO_CTX ? (left + above + 1u) >> 1 : (left + above + 2u * pe + 2u) >> 2;
    return c < NB_CTX ? c : NB_CTX - 1u;
}

/* ---- encoder --------------------------------------------------------------- */

void bw_strip_enc_init(bw_strip_enc_t *se, uint8_t *out, size_t cap, unsigned coder)
{
    se->coder = coder;
    if (coder == BW_CODER_RICE) {
        bw_rice_enc_init(&se->re, out, cap);
    } else {
        bw_rc_enc_init(&se->rc, out, cap);
        bw_models_init(&se->m, coder);
    }
    se->cnt = 0;
    se->mask = 0;
    memset(&se->st, 0, sizeof se->st);
}

/* The strip code both ways, once per direction (BW_CFG_FAST_STRIPS) or one
 * copy for both. */
#if BW_CFG_FAST_STRIPS
#define STRIP_INLINE BW_ALWAYS_INLINE
#else
#define STRIP_INLINE BW_NOINLINE
#endif

/* One model bit: coded (dec NULL), or decoded (enc NULL) and returned. */
static STRIP_INLINE unsigned rc_bit(bw_rc_enc_t *enc, bw_rc_dec_t *dec, bw_prob_t *p,
                                    unsigned bit)
{
    if (dec)
        return bw_rc_dec_bit(dec, p);
    bw_rc_enc_bit(enc, p, bit);
    return bit;
}

#define MS_ESC (BW_MS_SYMS - 1u)

/* One of the multi-symbol coder's binary models, either way (rc_bit's twin). */
static STRIP_INLINE unsigned ms_bit(bw_rc_enc_t *enc, bw_rc_dec_t *dec, bw_prob_t *p,
                                    unsigned bit)
{
    if (dec)
        return bw_rc_dec_msbit(dec, p);
    bw_rc_enc_msbit(enc, p, bit);
    return bit;
}

/* A binary model of either coder: the binary one's adaptive rate, or the
 * multi-symbol one's fixed rate. */
static STRIP_INLINE unsigned model_bit(bool ms, bw_rc_enc_t *enc, bw_rc_dec_t *dec, bw_prob_t *p,
                                       unsigned bit)
{
    return BW_CFG_CODER_MS && ms ? ms_bit(enc, dec, p, bit) : rc_bit(enc, dec, p, bit);
}

/* The binary coder's bit length e (1..31) of a non-zero element of class c
 * in magnitude context mc, and its bits below the leading one: coded (e
 * given, from *a), or decoded (e 0, into *a, which holds 1). Returns e; 0
 * for a corrupt length. */
static STRIP_INLINE unsigned rc_magnitude(bw_rc_models_t *m, bw_rc_enc_t *rce, bw_rc_dec_t *rcd,
                                          unsigned c, unsigned mc, uint32_t *a, unsigned e)
{
    bool dec = rcd != NULL;
    bw_prob_t *tree = m->mag[c][mc];
    unsigned node = 1, sym = e - 1u;
    for (int sh = 4; sh >= 0; sh--)
        node = node * 2u + rc_bit(rce, rcd, &tree[node], (sym >> sh) & 1u);
    if (dec) {
        e = node - 32u + 1u;
        if (e > 31u)
            return 0;
    }
    if (e >= 2u) {
        unsigned mb = rc_bit(rce, rcd, &m->mant[c][e], (*a >> (e - 2u)) & 1u);
        if (dec)
            *a = (*a << 1) | mb;
        if (e >= 3u) {
            if (dec)
                *a = (*a << (e - 2u)) | bw_rc_dec_direct(rcd, e - 2u);
            else
                bw_rc_enc_direct(rce, *a, e - 2u);
        }
    }
    return e;
}

/* The multi-symbol coder's: e as one symbol (MS_ESC and 5 bits for
 * e - 1 >= MS_ESC), the bits below the leading one plain. */
static STRIP_INLINE unsigned ms_magnitude(bw_ms_models_t *m, bw_rc_enc_t *rce, bw_rc_dec_t *rcd,
                                          unsigned c, unsigned mc, uint32_t *a, unsigned e)
{
    bw_ms_model_t *em = &m->e[c][mc];
    if (rcd) {
        e = 1u + bw_rc_dec_sym(rcd, em);
        if (e == MS_ESC + 1u)
            e += bw_rc_dec_bits(rcd, 5);
    } else if (e - 1u >= MS_ESC) {
        bw_rc_enc_sym(rce, em, MS_ESC);
        bw_rc_enc_bits(rce, e - 1u - MS_ESC, 5);
    } else {
        bw_rc_enc_sym(rce, em, e - 1u);
    }
    if (e > 31u)
        return 0;
    for (unsigned n = e - 1u; n;) { /* the bits below the leading one, plain */
        unsigned k = n > 16u ? n - 16u : n; /* the top bits first */
        n -= k;
        if (rcd)
            *a = (*a << k) | bw_rc_dec_bits(rcd, k);
        else
            bw_rc_enc_bits(rce, *a >> n, k);
    }
    return e;
}

/*
 * The range coders' side of a strip of cnt elements, both ways: the
 * encoder (rcd NULL) codes the values v with the contexts put with them
 * (pe, pv, ps); the decoder (rce NULL) decodes into v and *dst[b] and finds
 * the contexts from par[b] and prv[b] as it goes (a parent or the vector
 * above may lie earlier in the same strip). ms: the multi-symbol coder
 * (BW_FLAG_MS: its models, bit lengths as symbols), else the binary one;
 * the callers pass a constant, so each gets its own copy. cls: the
 * elements' classes; s: what the previous strip left. false: a corrupt
 * strip.
 */
static STRIP_INLINE bool range_strip(bool ms, bw_models_t *m, bw_rc_enc_t *rce, bw_rc_dec_t *rcd,
                                     bw_strip_state_t *s, unsigned cnt, int32_t *v,
                                     const uint8_t *cls, const uint8_t *pe, const uint8_t *pv,
                                     const uint8_t *ps, int32_t *const *dst,
                                     const int32_t *const *par, const int32_t *const *prv)
{
    bool dec = rcd != NULL;
    ms = BW_CFG_CODER_MS && ms;
    uint32_t mask = 0;
    if (!dec)
        for (unsigned b = 0; b < cnt; b++)
            if (v[b])
                mask |= 1u << b;
    unsigned c0 = cls[0], pm = s->prev_mask != 0;
    if (!model_bit(ms, rce, rcd, ms ? &m->ms.present[c0][pm] : &m->rc.present[c0][pm], mask != 0)) {
        if (dec)
            for (unsigned b = 0; b < cnt; b++)
                *dst[b] = 0;
        strip_none(s);
        return true;
    }
    unsigned prev_bit = 0;
    for (unsigned b = 0; b < cnt; b++) {
        unsigned pe_b = dec ? ctx_len(par[b]) : pe[b];
        unsigned vc = valid_ctx((s->prev_mask >> b) & 1u, pe_b);
        unsigned c = cls[b];
        unsigned bit = model_bit(ms, rce, rcd,
                                 ms ? &m->ms.valid[c][prev_bit][vc] : &m->rc.valid[c][prev_bit][vc],
                                 (mask >> b) & 1u);
        mask |= (uint32_t)bit << b;
        prev_bit = bit;
        if (!bit) {
            if (dec)
                *dst[b] = v[b] = 0;
            s->e_above[b] = 0;
            s->e_left = 0;
            continue;
        }
        uint32_t a = dec ? 1u : bw_abs32(v[b]);
        unsigned e = dec ? 0u : bw_bitlen(a); /* 1..32 */
        unsigned pv_b = dec ? ctx_len(prv[b]) : pv[b];
        unsigned above = pv_b != NO_CTX ? pv_b : s->e_above[b];
        unsigned mc = mag_ctx(s->e_left, above, pe_b);
        e = ms ? ms_magnitude(&m->ms, rce, rcd, c, mc, &a, e)
               : rc_magnitude(&m->rc, rce, rcd, c, mc, &a, e);
        if (!e)
            return false;
        unsigned sc = (b ? sign_ctx(&v[b - 1]) : 0u) + (dec ? sign_ctx_up(par[b], prv[b]) : ps[b]);
        unsigned neg =
            model_bit(ms, rce, rcd, ms ? &m->ms.sign[sc] : &m->rc.sign[sc], !dec && v[b] < 0);
        if (dec)
            *dst[b] = v[b] = neg ? -(int32_t)a : (int32_t)a;
        s->e_above[b] = (uint8_t)e;
        s->e_left = e;
    }
    if (dec && !mask)
        return false; /* a present strip holds at least one value */
    s->prev_mask = mask;
    return true;
}

#if BW_CFG_FAST_STRIPS
/* The multi-symbol coder's encoder alone, with the coder's range and low in
 * locals: the same code as range_strip (which the decoder runs), in fewer
 * instructions. low is held in 32 bits: a carry out of it goes into the
 * bytes written at once (bw_rc_enc_carry), where the coder's 64-bit low
 * would hold it until its next byte; the same bytes either way. */
#define MS_RENORM()                                                                              \
    while (range < BW_RC_TOP) {                                                                  \
        bw_rc_enc_put(rc, (uint8_t)(low >> 24));                                                 \
        low <<= 8;                                                                               \
        range <<= 8;                                                                             \
    }
#define MS_ADD(x)                                                                                \
    do {                                                                                         \
        uint32_t t_ = low + (x);                                                                 \
        if (t_ < low)                                                                            \
            bw_rc_enc_carry(rc);                                                                 \
        low = t_;                                                                                \
    } while (0)
#define MS_BIT(prob, bit)                                                                        \
    do {                                                                                         \
        bw_prob_t *p_ = (prob);                                                                  \
        uint32_t bound_ = (range >> BW_PROB_BITS) * *p_;                                         \
        if (!(bit)) {                                                                            \
            range = bound_;                                                                      \
        } else {                                                                                 \
            MS_ADD(bound_);                                                                      \
            range -= bound_;                                                                     \
        }                                                                                        \
        bw_ms_prob_update(p_, (bit));                                                            \
        MS_RENORM();                                                                             \
    } while (0)

/* low and range into locals (a carry the coder still holds, into the bytes
 * first), and back */
#define MS_LOAD()                                                                                \
    if (rc->low >> 32)                                                                           \
        bw_rc_enc_carry(rc);                                                                     \
    uint32_t low = (uint32_t)rc->low, range = rc->range
#define MS_STORE()                                                                               \
    do {                                                                                         \
        rc->low = low;                                                                           \
        rc->range = range;                                                                       \
    } while (0)

/* The bit length e of a non-zero element as the model's symbol (e - 1, or
 * the escape and 5 bits), then its e - 1 bits below the leading one. */
#define MS_MAGNITUDE(em, e, a)                                                                   \
    do {                                                                                         \
        bw_ms_model_t *m_ = (em);                                                                \
        unsigned n_ = (e) - 1u, sym_ = n_ < MS_ESC ? n_ : MS_ESC;                                \
        uint32_t lo_ = m_->cum[sym_], r_ = range / m_->cum[BW_MS_SYMS];                          \
        range = r_ * (uint32_t)(m_->cum[sym_ + 1u] - lo_);                                       \
        MS_ADD(r_ * lo_);                                                                        \
        bw_ms_update(m_, sym_);                                                                  \
        MS_RENORM();                                                                             \
        if (n_ >= MS_ESC) {                                                                      \
            range >>= 5;                                                                         \
            MS_ADD(range * (n_ - MS_ESC));                                                       \
            MS_RENORM();                                                                         \
            if (n_ > 16u) {                                                                      \
                range >>= n_ - 16u;                                                              \
                MS_ADD(range * (((a) >> 16) & ((1u << (n_ - 16u)) - 1u)));                      \
                MS_RENORM();                                                                     \
                n_ = 16u;                                                                        \
            }                                                                                    \
        }                                                                                        \
        if (n_) {                                                                                \
            range >>= n_;                                                                        \
            MS_ADD(range * ((a) & ((1u << n_) - 1u)));                                           \
            MS_RENORM();                                                                         \
        }                                                                                        \
    } while (0)

/* ms_strip's element b (x, class c, parent bit length pe): its valid bit;
 * for a zero, the contexts it leaves, and the loop's next element */
#define MS_VALID_OR_NEXT(c, pe, b, x)                                                            \
    {                                                                                            \
        unsigned bit_ = (x) != 0;                                                                \
        mask |= (uint32_t)bit_ << (b);                                                           \
        MS_BIT(&m->valid[c][prev_bit][valid_ctx((above_mask >> (b)) & 1u, pe)], bit_);           \
        prev_bit = bit_;                                                                         \
        if (!bit_) {                                                                             \
            ea[b] = 0;                                                                           \
            e_left = 0;                                                                          \
            left_sign = 0;                                                                       \
            continue;                                                                            \
        }                                                                                        \
    }
/* ... and of a non-zero one (a = |x|, bit length e) its bit length (above:
 * the bit length above), bits and sign (up: its sign model but for the
 * left sign) */
#define MS_NONZERO(c, pe, b, x, a, e, above, up)                                                 \
    do {                                                                                         \
        MS_MAGNITUDE(&m->e[c][mag_ctx(e_left, above, pe)], e, a);                                \
        unsigned neg_ = (x) < 0;                                                                 \
        MS_BIT(&m->sign[left_sign + (up)], neg_);                                                \
        left_sign = 1u + neg_;                                                                   \
        ea[b] = (uint8_t)(e);                                                                    \
        e_left = (e);                                                                            \
    } while (0)

/*
 * One strip: its first b0 elements put (se->v and the contexts strip_put
 * stored), then, up to len, bands k.. of vector vec coded straight from it,
 * with the contexts strip_put would store found as they are needed:
 * has_par, the parent vector par (else each band's spectral parent, if
 * any); has_prev, the vector above prev (else the previous strip); flat,
 * every band of one class and without a spectral parent (no spectral
 * transform); put, the elements put alone (b0 = len). The coder's low and
 * range in *lo and *ra. The callers pass constants, so each gets its own
 * copy.
 */
static BW_ALWAYS_INLINE void ms_strip(bw_strip_enc_t *se, uint32_t *lo, uint32_t *ra, unsigned b0,
                                      unsigned len, const int32_t *vec, uint32_t k,
                                      const int32_t *spec_cls, unsigned cls_dir,
                                      const int32_t *par, const int32_t *prev, bool has_par,
                                      bool has_prev, bool flat, bool put)
{
    bw_ms_models_t *m = &se->m.ms;
    bw_rc_enc_t *rc = &se->rc;
    bw_strip_state_t *s = &se->st;
    uint32_t low = *lo, range = *ra;
    unsigned cls0 = put ? 0u : bw_coef_cls(spec_cls[0], cls_dir);
    const int32_t *v = put ? NULL : vec + k, *sct = put ? NULL : spec_cls + k;
    uint32_t any = se->mask; /* the mask bit by bit below, as it codes */
    if (!put)
        for (unsigned i = 0; i < len - b0; i++)
            any |= (uint32_t)v[i];
    unsigned c_first = put || b0 ? se->cls[0] : flat ? cls0 : bw_coef_cls(sct[0], cls_dir);
    MS_BIT(&m->present[c_first][s->prev_mask != 0], any != 0);
    se->cnt = 0;
    se->mask = 0;
    if (!any) {
        strip_none(s);
        *lo = low;
        *ra = range;
        return;
    }
    unsigned prev_bit = 0, e_left = s->e_left, left_sign = 0;
    uint32_t above_mask = s->prev_mask, mask = 0;
    uint8_t *ea = s->e_above;
    for (unsigned b = 0; b < b0; b++) { /* the elements put */
        int32_t x = se->v[b];
        unsigned c = se->cls[b], pe = se->pe[b];
        MS_VALID_OR_NEXT(c, pe, b, x)
        uint32_t a = bw_abs32(x);
        unsigned e = bw_bitlen(a), pv_b = se->pv[b];
        MS_NONZERO(c, pe, b, x, a, e, pv_b != NO_CTX ? pv_b : ea[b], se->ps[b]);
    }
    for (unsigned b = b0, i = 0; b < len; b++, i++) { /* vec's */
        int32_t sc = flat ? 0 : sct[i];
        unsigned c = flat ? cls0 : bw_coef_cls(sc, cls_dir), pe = NO_CTX, par_sign = 0;
        int32_t sp = flat ? -1 : BW_SPEC_PAR(sc);
        if (has_par || sp >= 0) {
            int32_t pval = has_par ? par[k + i] : vec[sp];
            pe = bw_bitlen(bw_abs32(pval));
            par_sign = pval ? 1u + (pval < 0) : 0u;
        }
        int32_t x = v[i];
        MS_VALID_OR_NEXT(c, pe, b, x)
        uint32_t a = bw_abs32(x);
        unsigned e = bw_bitlen(a), above, up_sign = 0;
        if (has_prev) {
            int32_t y = prev[k + i];
            above = bw_bitlen(bw_abs32(y));
            up_sign = y ? 1u + (y < 0) : 0u;
        } else {
            above = ea[b];
        }
        MS_NONZERO(c, pe, b, x, a, e, above, 3u * (par_sign + 3u * up_sign));
    }
    s->e_left = e_left;
    s->prev_mask = mask;
    *lo = low;
    *ra = range;
}

/* A strip put (se->v and the contexts strip_put stored). */
static void ms_strip_enc(bw_strip_enc_t *se)
{
    bw_rc_enc_t *rc = &se->rc;
    MS_LOAD();
    ms_strip(se, &low, &range, se->cnt, se->cnt, NULL, 0, NULL, 0, NULL, NULL, false, false, false,
             true);
    MS_STORE();
}

/* Bands k.. of vector vec: the pending strip completed (where vec holds
 * enough bands), then whole strips straight from vec (ms_strip).
 * Returns the first band left for strip_put. */
static BW_ALWAYS_INLINE uint32_t ms_vector_strips(bw_strip_enc_t *se, const int32_t *vec,
                                                  uint32_t k, uint32_t end,
                                                  const int32_t *spec_cls, unsigned cls_dir,
                                                  const int32_t *par, const int32_t *prev,
                                                  bool has_par, bool has_prev, bool flat)
{
    bw_rc_enc_t *rc = &se->rc;
    MS_LOAD();
    unsigned b0 = se->cnt;
    if (b0 && k + BW_STRIP - b0 <= end) {
        ms_strip(se, &low, &range, b0, BW_STRIP, vec, k, spec_cls, cls_dir, par, prev, has_par,
                 has_prev, flat, false);
        k += BW_STRIP - b0;
    }
    if (!se->cnt)
        for (; k + BW_STRIP <= end; k += BW_STRIP)
            ms_strip(se, &low, &range, 0u, BW_STRIP, vec, k, spec_cls, cls_dir, par, prev,
                     has_par, has_prev, flat, false);
    MS_STORE();
    return k;
}
#endif

void bw_strip_enc_code(bw_strip_enc_t *se)
{
    unsigned cnt = se->cnt;
    if (se->coder == BW_CODER_RICE) {
        bw_rice_enc_strip(&se->re, se->v, cnt);
    } else if (BW_CFG_CODER_MS && se->coder == BW_CODER_MS) {
#if BW_CFG_FAST_STRIPS
        ms_strip_enc(se);
#else
        range_strip(true, &se->m, &se->rc, NULL, &se->st, cnt, se->v, se->cls, se->pe, se->pv,
                    se->ps, NULL, NULL, NULL);
#endif
    } else {
        range_strip(false, &se->m, &se->rc, NULL, &se->st, cnt, se->v, se->cls, se->pe, se->pv,
                    se->ps, NULL, NULL, NULL);
    }
    se->cnt = 0;
    se->mask = 0;
}

size_t bw_strip_enc_finish(bw_strip_enc_t *se)
{
    if (se->cnt)
        bw_strip_enc_code(se);
    return se->coder == BW_CODER_RICE ? bw_rice_enc_finish(&se->re) : bw_rc_enc_finish(&se->rc);
}

bool bw_strip_enc_overflow(const bw_strip_enc_t *se)
{
    return se->coder == BW_CODER_RICE ? se->re.w.overflow : se->rc.overflow;
}

/* par, prv: the parent and the same band in the previous vector (NULL:
 * none); their bit lengths and signs are the contexts */
static inline void strip_put(bw_strip_enc_t *se, int32_t v, unsigned cls, const int32_t *par,
                             const int32_t *prv)
{
    se->mask |= (uint32_t)(v != 0) << se->cnt;
    se->v[se->cnt] = v;
    se->cls[se->cnt] = (uint8_t)cls;
    se->pe[se->cnt] = (uint8_t)ctx_len(par);
    se->ps[se->cnt] = (uint8_t)sign_ctx_up(par, prv);
    se->pv[se->cnt] = (uint8_t)ctx_len(prv);
    if (++se->cnt == BW_STRIP)
        bw_strip_enc_code(se);
}

/* Band k of vector v with the contexts of put_vector's arguments. */
static inline void put_band(bw_strip_enc_t *se, const int32_t *v, uint32_t k,
                            const int32_t *spec_cls, unsigned cls_dir, const int32_t *par,
                            const int32_t *prev)
{
    int32_t sc = spec_cls[k];
    strip_put(se, v[k], bw_coef_cls(sc, cls_dir), bw_parent_of(par, v, sc, k),
              prev ? prev + k : NULL);
}

/* Rice: the values in coding order, whole strips straight from a vector. */
static void rice_vector(bw_strip_enc_t *se, const int32_t *v, uint32_t b)
{
    uint32_t k = 0;
    if (se->cnt == 0u)
        for (; k + BW_STRIP <= b; k += BW_STRIP)
            bw_rice_enc_strip(&se->re, v + k, BW_STRIP);
    for (; k < b; k++) {
        se->v[se->cnt] = v[k];
        if (++se->cnt == BW_STRIP)
            bw_strip_enc_code(se);
    }
}

static inline void rice_push(bw_strip_enc_t *se, const int32_t *v, uint32_t b)
{
    if (b == 1u) { /* one value per direction */
        se->v[se->cnt] = *v;
        if (++se->cnt == BW_STRIP)
            bw_strip_enc_code(se);
    } else {
        rice_vector(se, v, b);
    }
}

static inline void put_vector(bw_strip_enc_t *se, const int32_t *v, uint32_t b,
                              const int32_t *spec_cls, unsigned cls_dir, const int32_t *par,
                              const int32_t *prev)
{
    if (se->coder == BW_CODER_RICE) {
        rice_vector(se, v, b);
        return;
    }
    uint32_t k = 0;
#if BW_CFG_FAST_STRIPS
    if (BW_CFG_CODER_MS && se->coder == BW_CODER_MS) {
        /* whole strips straight from v, the pending one first where v
         * completes it (else v's bands are all put below); flat: one class
         * and no spectral parents (no spectral transform: the finest band's
         * class is the first's) */
        bool flat = b > 1u && spec_cls[0] == spec_cls[b - 1u] && BW_SPEC_PAR(spec_cls[0]) < 0;
        if (par && prev)
            k = ms_vector_strips(se, v, k, b, spec_cls, cls_dir, par, prev, true, true, false);
        else if (par)
            k = ms_vector_strips(se, v, k, b, spec_cls, cls_dir, par, prev, true, false, false);
        else if (prev && flat)
            k = ms_vector_strips(se, v, k, b, spec_cls, cls_dir, par, prev, false, true, true);
        else if (prev)
            k = ms_vector_strips(se, v, k, b, spec_cls, cls_dir, par, prev, false, true, false);
        else
            k = ms_vector_strips(se, v, k, b, spec_cls, cls_dir, par, prev, false, false, false);
    }
#endif
    for (; k < b; k++)
        put_band(se, v, k, spec_cls, cls_dir, par, prev);
}

void bw_strip_put_vector(bw_strip_enc_t *se, const int32_t *v, uint32_t b,
                         const int32_t *spec_cls, unsigned cls_dir, const int32_t *par,
                         const int32_t *prev)
{
    put_vector(se, v, b, spec_cls, cls_dir, par, prev);
}

#if BW_RATE
/* A quantiser ahead of the coder (pl->rate): the next v vectors in coding
 * order quantised before the coder reads them, the rate's control told the
 * bits coded so far where it quantises a chunk. */
static inline void rate_need(struct bw_rate *r, const bw_strip_enc_t *se, uint32_t v)
{
    if (r->ahead < v)
        bw_rate_chunk(r, (uint64_t)se->rc.pos * 8u, v);
    r->ahead -= v;
}
#define RATE_NEED(v)                                                                               \
    do {                                                                                           \
        if (rate)                                                                                  \
            rate_need(rate, se, (v));                                                              \
    } while (0)
#else
#define RATE_NEED(v) ((void)0)
#endif

#if BW_CFG_FAST_STRIPS && BW_CFG_CODER_MS
/* One band, one level of the coarse-to-fine order, for the multi-symbol
 * coder: the children 1..3 of np parents from c (parent p at c + 4 p step,
 * its children 1..3 steps after it), in class cls, each with its parent's
 * bit length and sign as contexts and none above (as strip_put stages them
 * and ms_strip_enc codes them): a pending strip completed and the last
 * few staged, whole strips coded straight from c. The rate (if any) is
 * asked for each parent's three vectors at its first child, before the
 * strip that holds it is coded, as when staged. */
typedef struct {
    const int32_t *ch; /* the next child */
    size_t step;
    unsigned m;        /* its number, 1..3 */
} band_walk_t;

static inline void band_next(band_walk_t *w)
{
    w->ch += w->m == 3u ? 2u * w->step : w->step; /* past the next parent */
    w->m = w->m == 3u ? 1u : w->m + 1u;
}

/* n children on */
static inline void band_skip(band_walk_t *w, uint32_t n)
{
    uint32_t i = w->m - 1u + n, p = i / 3u, m = i - 3u * p + 1u;
    w->ch += (4u * p + m - w->m) * w->step;
    w->m = m;
}

static inline const int32_t *band_parent(const band_walk_t *w)
{
    return w->ch - (size_t)w->m * w->step;
}

static BW_NOINLINE void ms_band_level(bw_strip_enc_t *se, const int32_t *c, size_t step,
                                      uint32_t np, unsigned cls, struct bw_rate *rate)
{
    band_walk_t w = {c + step, step, 1u};
    uint32_t left = 3u * np;
#if !BW_RATE
    (void)rate;
#endif
    for (int phase = 0; phase < 2; phase++) {
        /* staged: up to a strip boundary, then (second) what is left */
        for (; left && (phase || se->cnt); left--, band_next(&w)) {
            if (w.m == 1u)
                RATE_NEED(3u);
            strip_put(se, *w.ch, cls, band_parent(&w), NULL);
        }
        if (phase)
            break;
        bw_ms_models_t *m = &se->m.ms;
        bw_rc_enc_t *rc = &se->rc;
        bw_strip_state_t *s = &se->st;
        size_t step4 = 4u * step;
        bw_prob_t(*valid)[6] = m->valid[cls];
        bw_ms_model_t *em = m->e[cls];
        for (; left >= BW_STRIP; left -= BW_STRIP) {
            /* the strip's values present (the rate asked first) */
            uint32_t any = 0;
            if (BW_RATE && rate) {
                band_walk_t u = w;
                for (unsigned b = 0; b < BW_STRIP; b++, band_next(&u)) {
                    if (u.m == 1u)
                        RATE_NEED(3u);
                    any |= (uint32_t)*u.ch;
                }
            } else { /* the rest of this parent's children, then three a parent */
                const int32_t *ch = w.ch;
                unsigned b = 4u - w.m;
                for (unsigned r = b; r; r--, ch += step)
                    any |= (uint32_t)*ch;
                for (ch += step; b + 3u <= BW_STRIP; b += 3u, ch += step4)
                    any |= (uint32_t)(ch[0] | ch[step] | ch[2u * step]);
                for (; b < BW_STRIP; b++, ch += step)
                    any |= (uint32_t)*ch;
            }
            MS_LOAD();
            MS_BIT(&m->present[cls][s->prev_mask != 0], any != 0);
            if (!any) {
                MS_STORE();
                strip_none(s);
                band_skip(&w, BW_STRIP);
                continue;
            }
            unsigned prev_bit = 0, e_left = s->e_left, left_sign = 0;
            uint32_t above_mask = s->prev_mask, mask = 0;
            uint8_t *ea = s->e_above;
            /* the parent's contexts, once for its three children: valid_ctx
             * and mag_ctx of a parent bit length pe (never NO_CTX here) */
            const int32_t *ch = w.ch;
            unsigned rem = 4u - w.m; /* this parent's children left */
            const int32_t *par = ch - (size_t)w.m * step;
            unsigned pe = ctx_len(par), ps = 3u * sign_ctx(par);
            unsigned vc = valid_ctx(0u, pe), pm = 2u * pe + 2u;
            for (unsigned b = 0; b < BW_STRIP; b++) {
                int32_t x = *ch;
                unsigned bit = x != 0;
                mask |= (uint32_t)bit << b;
                MS_BIT(&valid[prev_bit][vc + ((above_mask >> b) & 1u)], bit);
                prev_bit = bit;
                if (!bit) {
                    ea[b] = 0;
                    e_left = 0;
                    left_sign = 0;
                } else {
                    uint32_t a = bw_abs32(x);
                    unsigned e = bw_bitlen(a);
                    unsigned mc = (e_left + ea[b] + pm) >> 2;
                    MS_MAGNITUDE(&em[mc < NB_CTX ? mc : NB_CTX - 1u], e, a);
                    unsigned neg = x < 0;
                    MS_BIT(&m->sign[left_sign + ps], neg);
                    left_sign = 1u + neg;
                    ea[b] = (uint8_t)e;
                    e_left = e;
                }
                ch += step;
                if (--rem == 0u) { /* past the next parent, to its first child */
                    par = ch;
                    ch += step;
                    rem = 3u;
                    if (b + 1u == BW_STRIP)
                        break; /* (which may lie past the level's end) */
                    pe = ctx_len(par);
                    ps = 3u * sign_ctx(par);
                    vc = valid_ctx(0u, pe);
                    pm = 2u * pe + 2u;
                }
            }
            w.ch = ch;
            w.m = 4u - rem;
            MS_STORE();
            s->e_left = e_left;
            s->prev_mask = mask;
        }
    }
}
#endif

void bw_code_body(const bw_plan_t *pl, int32_t *x, bw_strip_enc_t *se)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    if (BW_CFG_FAST_RICE && se->coder == BW_CODER_RICE && !pl->stream) {
        /* the coarse-to-fine order of bw_walk_next as loops (Rice strips
         * need no context class): the 4 scaling coefficients, then per
         * level j the children 1..3 of every parent */
        unsigned L = d->level_out;
        for (uint32_t i = 0; i < d->n_in; i++) {
            const int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
            if (!bw_has_out(d)) {
                for (uint32_t o = 0; o < d->n_out; o++)
                    rice_push(se, blk, b);
                continue;
            }
            for (uint32_t p = 0; p < 4u; p++)
                rice_push(se, blk + ((size_t)p << (2u * L)) * b, b);
            for (unsigned j = 0; j < L; j++) {
                unsigned sh = 2u * (L - j - 1u);
                size_t step = ((size_t)1 << sh) * b;
                const int32_t *c = blk;
                for (uint32_t p = 0; p < (4u << (2u * j)); p++, c += 4u * step) {
                    rice_push(se, c + step, b);
                    rice_push(se, c + 2u * step, b);
                    rice_push(se, c + 3u * step, b);
                }
            }
        }
        return;
    }
    if (BW_CFG_FAST_STRIPS && !pl->stream) {
        /* the coarse-to-fine order as loops: per incoming block the 4
         * scaling vectors, then per level j the children 1..3 of every
         * parent c, whose vector is their directional parent; the previous
         * vector in this order is the one above (with more than one band) */
        unsigned L = d->level_out;
        const int32_t *prev = NULL, *sc = pl->spec_cls;
        bool above = b > 1u;
#if BW_RATE
        struct bw_rate *rate = se->coder != BW_CODER_RICE ? pl->rate : NULL;
#endif
        for (uint32_t i = 0; i < d->n_in; i++) {
            const int32_t *blk = x + (size_t)bw_in_pos(pl, i) * d->n_out * b;
            if (!bw_has_out(d)) {
                for (uint32_t o = 0; o < d->n_out; o++) {
                    RATE_NEED(1u);
                    put_vector(se, blk, b, sc, 2u, NULL, above ? prev : NULL);
                    prev = blk;
                }
                continue;
            }
            unsigned cd = bw_level_cls(pl, -1);
            for (uint32_t p = 0; p < 4u; p++) {
                const int32_t *v = blk + ((size_t)p << (2u * L)) * b;
                RATE_NEED(1u);
                put_vector(se, v, b, sc, cd, NULL, above ? prev : NULL);
                prev = v;
            }
            for (unsigned j = 0; j < L; j++) {
                size_t step = ((size_t)1 << (2u * (L - j - 1u))) * b;
                const int32_t *c = blk;
                cd = bw_level_cls(pl, (int)j);
                if (b == 1u && se->coder != BW_CODER_RICE) {
                    /* one band: three values share their parent's contexts;
                     * the strip's count and mask in locals (the byte stores
                     * below would make the compiler reload them) */
                    uint8_t cls = (uint8_t)bw_coef_cls(sc[0], cd);
#if BW_CFG_CODER_MS
                    if (se->coder == BW_CODER_MS) {
#if BW_RATE
                        ms_band_level(se, c, step, 4u << (2u * j), cls, rate);
#else
                        ms_band_level(se, c, step, 4u << (2u * j), cls, NULL);
#endif
                        continue;
                    }
#endif
                    unsigned n = se->cnt;
                    uint32_t mask = se->mask;
                    int32_t *sv = se->v;
                    uint8_t *scls = se->cls, *spe = se->pe, *sps = se->ps, *spv = se->pv;
                    for (uint32_t p = 0; p < (4u << (2u * j)); p++, c += 4u * step) {
                        RATE_NEED(3u);
                        int32_t q = *c;
                        uint8_t pe = (uint8_t)bw_bitlen(bw_abs32(q));
                        uint8_t ps = (uint8_t)(q ? 3u + 3u * (q < 0) : 0u);
                        if (BW_LIKELY(n + 3u < BW_STRIP)) { /* the three, no strip full */
                            int32_t v1 = c[step], v2 = c[2u * step], v3 = c[3u * step];
                            mask |= ((uint32_t)(v1 != 0) | (uint32_t)(v2 != 0) << 1 |
                                     (uint32_t)(v3 != 0) << 2)
                                    << n;
                            sv[n] = v1;
                            sv[n + 1u] = v2;
                            sv[n + 2u] = v3;
                            for (unsigned m = 0; m < 3u; m++) {
                                scls[n + m] = cls;
                                spe[n + m] = pe;
                                sps[n + m] = ps;
                                spv[n + m] = (uint8_t)NO_CTX;
                            }
                            n += 3u;
                            continue;
                        }
                        for (unsigned m = 1; m <= 3u; m++) {
                            int32_t val = c[m * step];
                            mask |= (uint32_t)(val != 0) << n;
                            sv[n] = val;
                            scls[n] = cls;
                            spe[n] = pe;
                            sps[n] = ps;
                            spv[n] = (uint8_t)NO_CTX;
                            if (++n == BW_STRIP) {
                                se->cnt = n;
                                se->mask = mask;
                                bw_strip_enc_code(se);
                                n = 0;
                                mask = 0;
                            }
                        }
                    }
                    se->cnt = n;
                    se->mask = mask;
                    continue;
                }
                for (uint32_t p = 0; p < (4u << (2u * j)); p++, c += 4u * step) {
                    RATE_NEED(3u);
                    for (unsigned m = 1; m <= 3u; m++) {
                        const int32_t *v = c + m * step;
                        put_vector(se, v, b, sc, cd, c, above ? prev : NULL);
                        prev = v;
                    }
                }
            }
        }
        return;
    }
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    size_t vectors = (size_t)d->n_in * d->n_out;
    for (size_t n = 0; n < vectors; n++) {
        put_vector(se, it.vec, b, pl->spec_cls, it.cls_dir, it.par, it.prev);
        bw_iter_next_vec(&it);
    }
}

void bw_code_vectors(bw_iter_t *it, bw_strip_enc_t *se, size_t nvec)
{
    const bw_plan_t *pl = it->pl;
    for (size_t n = 0; n < nvec; n++) {
        put_vector(se, it->vec, pl->dims.bands, pl->spec_cls, it->cls_dir, it->par, it->prev);
        bw_iter_next_vec(it);
    }
}

/* ---- decoder --------------------------------------------------------------- */

static bw_status_t decode_rice(bw_iter_t *it, size_t n, const uint8_t *body, size_t len)
{
    bw_rice_dec_t rd;
    bw_rice_dec_init(&rd, body, len);
    int32_t v[BW_STRIP];
    for (size_t base = 0; base < n; base += BW_STRIP) {
        unsigned cnt = n - base < BW_STRIP ? (unsigned)(n - base) : BW_STRIP;
        if (!bw_rice_dec_strip(&rd, v, cnt))
            return BW_ERR_CORRUPT;
        for (unsigned b = 0; b < cnt; b++) {
            uint8_t cls;
            const int32_t *par, *prv;
            *bw_iter_next(it, &cls, &par, &prv) = v[b];
        }
    }
    return BW_OK;
}

static bw_status_t decode_rc(bw_iter_t *it, size_t n, bw_rc_dec_t *rc, bw_models_t *m,
                             unsigned coder)
{
    bw_strip_state_t st;
    memset(&st, 0, sizeof st);
    for (size_t base = 0; base < n; base += BW_STRIP) {
        unsigned cnt = n - base < BW_STRIP ? (unsigned)(n - base) : BW_STRIP;
        int32_t *dst[BW_STRIP], v[BW_STRIP];
        const int32_t *par[BW_STRIP], *prv[BW_STRIP];
        uint8_t cls[BW_STRIP];
        for (unsigned b = 0; b < cnt; b++)
            dst[b] = bw_iter_next(it, &cls[b], &par[b], &prv[b]);
        bool ok = BW_CFG_CODER_MS && coder == BW_CODER_MS
                      ? range_strip(true, m, NULL, rc, &st, cnt, v, cls, NULL, NULL, NULL, dst, par,
                                    prv)
                      : range_strip(false, m, NULL, rc, &st, cnt, v, cls, NULL, NULL, NULL, dst, par,
                                    prv);
        if (!ok)
            return BW_ERR_CORRUPT;
    }
    /* a whole code is read to 3 or 4 bytes past its end: more, a cut body */
    return rc->pos > rc->len + 4u ? BW_ERR_CORRUPT : BW_OK;
}

bw_status_t bw_decode_coefs(bw_iter_t *it, size_t n, const uint8_t *body, size_t len,
                            unsigned coder, bw_models_t *m)
{
    if (coder == BW_CODER_RICE)
        return decode_rice(it, n, body, len);
#if BW_CFG_CODER_TAB
    if (coder == BW_CODER_TAB)
        return bw_tab_decode(it, n, body, len, &m->tab);
#endif
    bw_models_init(m, coder);
    bw_rc_dec_t rc;
    bw_rc_dec_init(&rc, body, len);
    return decode_rc(it, n, &rc, m, coder);
}

bw_status_t bw_decode_body(const bw_plan_t *pl, int32_t *x, const uint8_t *body, size_t len,
                           unsigned coder, bw_models_t *m)
{
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    return bw_decode_coefs(&it, pl->n, body, len, coder, m);
}
