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

void bw_models_init(bw_models_t *m)
{
    bw_prob_t *p = (bw_prob_t *)m;
    for (size_t i = 0; i < sizeof *m / sizeof *p; i++)
        p[i] = BW_PROB_INIT;
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

void bw_strip_enc_init(bw_strip_enc_t *se, uint8_t *out, size_t cap, bool rice)
{
    se->rice = rice;
    if (rice) {
        bw_rice_enc_init(&se->re, out, cap);
    } else {
        bw_rc_enc_init(&se->rc, out, cap);
        bw_models_init(&se->m);
    }
    se->cnt = 0;
    memset(se->e_above, 0, sizeof se->e_above);
    se->prev_mask = 0;
    se->e_left = 0;
}

void bw_strip_enc_code(bw_strip_enc_t *se)
{
    if (se->rice) {
        bw_rice_enc_strip(&se->re, se->v, se->cnt);
        se->cnt = 0;
        return;
    }
    bw_rc_enc_t *rc = &se->rc;
    bw_models_t *m = &se->m;
    unsigned cnt = se->cnt;
    const int32_t *v = se->v;
    const uint8_t *cls = se->cls;
    uint32_t mask = 0;
    se->cnt = 0;
    for (unsigned b = 0; b < cnt; b++)
        if (v[b])
            mask |= 1u << b;
    bw_rc_enc_bit(rc, &m->present[cls[0]][se->prev_mask != 0], mask != 0);
    if (!mask) {
        se->prev_mask = 0;
        memset(se->e_above, 0, sizeof se->e_above);
        se->e_left = 0;
        return;
    }
    unsigned prev_bit = 0;
    for (unsigned b = 0; b < cnt; b++) {
        unsigned bit = (mask >> b) & 1u;
        unsigned pe = se->pe[b];
        bw_rc_enc_bit(rc, &m->valid[cls[b]][prev_bit][valid_ctx((se->prev_mask >> b) & 1u, pe)], bit);
        prev_bit = bit;
        if (!bit) {
            se->e_above[b] = 0;
            se->e_left = 0;
            continue;
        }
        uint32_t a = bw_abs32(v[b]);
        unsigned e = bw_bitlen(a); /* 1..32 */
        unsigned above = se->pv[b] != NO_CTX ? se->pv[b] : se->e_above[b];
        bw_prob_t *tree = m->mag[cls[b]][mag_ctx(se->e_left, above, pe)];
        unsigned node = 1, sym = e - 1u;
        for (int sh = 4; sh >= 0; sh--) {
            unsigned bt = (sym >> sh) & 1u;
            bw_rc_enc_bit(rc, &tree[node], bt);
            node = node * 2u + bt;
        }
        if (e >= 2u) {
            bw_rc_enc_bit(rc, &m->mant[cls[b]][e], (a >> (e - 2u)) & 1u);
            if (e >= 3u)
                bw_rc_enc_direct(rc, a, e - 2u);
        }
        bw_rc_enc_bit(rc, &m->sign[(b ? sign_ctx(&v[b - 1]) : 0u) + se->ps[b]], v[b] < 0);
        se->e_above[b] = (uint8_t)e;
        se->e_left = e;
    }
    se->prev_mask = mask;
}

size_t bw_strip_enc_finish(bw_strip_enc_t *se)
{
    if (se->cnt)
        bw_strip_enc_code(se);
    return se->rice ? bw_rice_enc_finish(&se->re) : bw_rc_enc_finish(&se->rc);
}

bool bw_strip_enc_overflow(const bw_strip_enc_t *se)
{
    return se->rice ? se->re.w.overflow : se->rc.overflow;
}

/* par, prv: the parent and the same band in the previous vector (NULL:
 * none); their bit lengths and signs are the contexts */
static inline void strip_put(bw_strip_enc_t *se, int32_t v, unsigned cls, const int32_t *par,
                             const int32_t *prv)
{
    se->v[se->cnt] = v;
    se->cls[se->cnt] = (uint8_t)cls;
    se->pe[se->cnt] = (uint8_t)ctx_len(par);
    se->ps[se->cnt] = (uint8_t)sign_ctx_up(par, prv);
    se->pv[se->cnt] = (uint8_t)ctx_len(prv);
    if (++se->cnt == BW_STRIP)
        bw_strip_enc_code(se);
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
    if (se->rice) {
        rice_vector(se, v, b);
        return;
    }
    for (uint32_t k = 0; k < b; k++) {
        int32_t sc = spec_cls[k];
        strip_put(se, v[k], BW_SPEC_CLS(sc) * 3u + cls_dir, bw_parent_of(par, v, sc, k),
                  prev ? prev + k : NULL);
    }
}

void bw_strip_put_vector(bw_strip_enc_t *se, const int32_t *v, uint32_t b,
                         const int32_t *spec_cls, unsigned cls_dir, const int32_t *par,
                         const int32_t *prev)
{
    put_vector(se, v, b, spec_cls, cls_dir, par, prev);
}

void bw_code_body(const bw_plan_t *pl, int32_t *x, bw_strip_enc_t *se)
{
    const bw_dims_t *d = &pl->dims;
    uint32_t b = d->bands;
    if (BW_CFG_FAST_RICE && se->rice && !pl->stream) {
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
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    size_t vectors = (size_t)d->n_in * d->n_out;
    for (size_t n = 0; n < vectors; n++) {
        put_vector(se, it.vec, b, pl->spec_cls, it.cls_dir, it.par, it.prev);
        bw_iter_next_vec(&it);
    }
}

/* ---- decoder --------------------------------------------------------------- */

static bw_status_t decode_rice(const bw_plan_t *pl, int32_t *x, const uint8_t *body, size_t len)
{
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    bw_rice_dec_t rd;
    bw_rice_dec_init(&rd, body, len);
    int32_t v[BW_STRIP];
    for (size_t base = 0; base < pl->n; base += BW_STRIP) {
        unsigned cnt = pl->n - base < BW_STRIP ? (unsigned)(pl->n - base) : BW_STRIP;
        if (!bw_rice_dec_strip(&rd, v, cnt))
            return BW_ERR_CORRUPT;
        for (unsigned b = 0; b < cnt; b++) {
            unsigned cls;
            const int32_t *par, *prv;
            *bw_iter_next(&it, &cls, &par, &prv) = v[b];
        }
    }
    return BW_OK;
}

static bw_status_t decode_rc(const bw_plan_t *pl, int32_t *x, bw_rc_dec_t *rc, bw_models_t *m)
{
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    uint8_t e_above[BW_STRIP] = {0};
    uint32_t prev_mask = 0;
    unsigned e_left = 0;
    for (size_t base = 0; base < pl->n; base += BW_STRIP) {
        unsigned cnt = pl->n - base < BW_STRIP ? (unsigned)(pl->n - base) : BW_STRIP;
        int32_t *dst[BW_STRIP];
        const int32_t *par[BW_STRIP], *prv[BW_STRIP];
        unsigned cls[BW_STRIP];
        cls[0] = 0;
        for (unsigned b = 0; b < cnt; b++)
            dst[b] = bw_iter_next(&it, &cls[b], &par[b], &prv[b]);
        if (!bw_rc_dec_bit(rc, &m->present[cls[0]][prev_mask != 0])) {
            for (unsigned b = 0; b < cnt; b++)
                *dst[b] = 0;
            prev_mask = 0;
            memset(e_above, 0, sizeof e_above);
            e_left = 0;
            continue;
        }
        uint32_t mask = 0;
        unsigned prev_bit = 0;
        for (unsigned b = 0; b < cnt; b++) {
            unsigned pe = ctx_len(par[b]);
            unsigned bit =
                bw_rc_dec_bit(rc, &m->valid[cls[b]][prev_bit][valid_ctx((prev_mask >> b) & 1u, pe)]);
            mask |= (uint32_t)bit << b;
            prev_bit = bit;
            if (!bit) {
                *dst[b] = 0;
                e_above[b] = 0;
                e_left = 0;
                continue;
            }
            unsigned above = prv[b] ? ctx_len(prv[b]) : e_above[b];
            bw_prob_t *tree = m->mag[cls[b]][mag_ctx(e_left, above, pe)];
            unsigned node = 1;
            for (int s = 0; s < 5; s++)
                node = node * 2u + bw_rc_dec_bit(rc, &tree[node]);
            unsigned e = node - 32u + 1u;
            if (e > 31u)
                return BW_ERR_CORRUPT;
            uint32_t a = 1u;
            if (e >= 2u) {
                a = (a << 1) | bw_rc_dec_bit(rc, &m->mant[cls[b]][e]);
                if (e >= 3u)
                    a = (a << (e - 2u)) | bw_rc_dec_direct(rc, e - 2u);
            }
            unsigned sc = (b ? sign_ctx(dst[b - 1]) : 0u) + sign_ctx_up(par[b], prv[b]);
            *dst[b] = bw_rc_dec_bit(rc, &m->sign[sc]) ? -(int32_t)a : (int32_t)a;
            e_above[b] = (uint8_t)e;
            e_left = e;
        }
        if (!mask)
            return BW_ERR_CORRUPT; /* a present strip holds at least one value */
        prev_mask = mask;
    }
    /* a whole code is read to 3 or 4 bytes past its end: more, a cut body */
    return rc->pos > rc->len + 4u ? BW_ERR_CORRUPT : BW_OK;
}

bw_status_t bw_decode_body(const bw_plan_t *pl, int32_t *x, const uint8_t *body, size_t len,
                           bool rice, bw_models_t *m)
{
    if (rice)
        return decode_rice(pl, x, body, len);
    bw_models_init(m);
    bw_rc_dec_t rc;
    bw_rc_dec_init(&rc, body, len);
    return decode_rc(pl, x, &rc, m);
}
