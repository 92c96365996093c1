/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The embedded body (docs/FORMAT.md, Embedded segments): each segment's
 * coefficients coded bit plane by bit plane, the most significant first, so
 * that any prefix of a segment decodes to an approximation of all its
 * coefficients and every further byte refines it. A coefficient's plane b
 * is coded in pass P = b + e, e its plane offset (the log2 of its subband's
 * synthesis gain when the coefficients are exact, so that a pass lowers the
 * squared error of every subband alike; 0 after a quantiser, whose steps
 * already weigh the subbands). Per pass, in coding order, strips of 32
 * coefficients: a strip with none significant yet codes one flag (does one
 * become significant now), then its coefficients their significance and
 * sign; significant coefficients code their refinement bit. Form 3 (the
 * encoder's for several bands) splits each pass in two: first the
 * significance of every coefficient not yet significant, then the
 * refinement bits of those that were, so that a pass cut short has found
 * the new coefficients first (the same bits in each model, in another
 * order). Form 4 (the encoder's for one band, where a strip holds
 * neighbouring directions) in three: the significance in the strips
 * already significant, the refinement, then the strips not yet
 * significant, whose values are more often isolated and small. Form 5
 * (the encoder's for several bands) is form 3 subband by subband: each
 * spectral subband over the segment's vectors, those a pass weighs most
 * (the highest quarter of a plane above their offset) first.
 */
#include <string.h>

#include "bw_internal.h"
#include "bw_le.h"
#include "bw_rc.h"

#if BW_CFG_EMBED

#define STRIP 32u
#define GROUP 1024u /* 32 strips */
#define SIG_CTX (BW_CODER_CLASSES * 4u * 3u * 3u)

typedef struct {
    bw_prob_t group[2][BW_CODER_CLASSES];
    bw_prob_t strip[2][2][BW_CODER_CLASSES];
    bw_prob_t sig[SIG_CTX];
    bw_prob_t sign[9];
    bw_prob_t ref[2][BW_CODER_CLASSES];
} embed_models_t;

/* the models live in the strip coder's (bw_models_t, unused by an embedded
 * segment): off the stack of a device */
_Static_assert(sizeof(embed_models_t) <= sizeof(bw_models_t), "embedded models in bw_models_t");

/* The spectral subbands (bw_spec_bands), the plane offset of each and
 * (form 5) the order the walk visits them in. */
typedef struct {
    spec_bands_t b;
    uint8_t e[BW_SPEC_MAX_LEVELS + 1u];
    uint8_t ord[BW_SPEC_MAX_LEVELS + 1u];
    bool sub; /* form 5: subband by subband */
} spec_off_t;

/* floor(4 log2(1.414 / g)), g an inverse gain in Q16: the plane offset in
 * quarters of a plane (its floor / 4: 0 for g near 1, L for 2^-L, a
 * Bio-Haar scaling coefficient, L - j - 1 for a detail). */
static unsigned gain_quarters(uint32_t g_q16)
{
    static const uint32_t q16[4] = {65536u, 77936u, 92682u, 110218u}; /* 2^(r/4) */
    unsigned e = 0;
    while (g_q16 && ((((uint64_t)g_q16 << ((e + 1u) >> 2)) * q16[(e + 1u) & 3u]) >> 16) <= 92681u)
        e++;
    return e;
}

/* The offsets; form 5 (sub) visits the subbands by the quarter of a plane
 * above their offset, the most first (the highest weight of a pass), then
 * coarse to fine. */
static BW_NOINLINE void spec_offsets(const bw_plan_t *pl, bool weigh, bool sub, spec_off_t *so)
{
    bw_spec_bands(pl, &so->b);
    unsigned q[BW_SPEC_MAX_LEVELS + 1u], n = 0;
    for (unsigned i = 0; i < so->b.count; i++) {
        q[i] = weigh && pl->spec_levels ? gain_quarters(so->b.gain_q16[i]) : 0u;
        so->e[i] = (uint8_t)(q[i] >> 2);
    }
    for (unsigned r = 4; r-- > 0;)
        for (unsigned i = 0; i < so->b.count; i++)
            if ((q[i] & 3u) == r)
                so->ord[n++] = (uint8_t)i;
    so->sub = sub;
}

/* The plane offset of the incoming block of the iterator, and of its
 * vector's outgoing coefficient (exact coefficients; else 0). */
static unsigned in_offset(const bw_iter_t *it, bool weigh)
{
    const bw_dims_t *d = &it->pl->dims;
    if (!weigh || !bw_has_in(d))
        return 0;
    int j = bw_biohaar_coef_level(it->i);
    return j < 0 ? d->level_in : d->level_in - (unsigned)j - 1u;
}

static inline unsigned out_offset(const bw_iter_t *it, bool weigh)
{
    const bw_dims_t *d = &it->pl->dims;
    if (!weigh || !bw_has_out(d))
        return 0;
    return it->lvl < 0 ? d->level_out : d->level_out - (unsigned)it->lvl - 1u;
}

/* One segment's coder state, encoder or decoder. */
typedef struct {
    bool enc;
    bw_rc_enc_t re;
    bw_rc_dec_t rd;
    size_t avail;   /* decoder of a cut segment: bytes there (else SIZE_MAX) */
    size_t budget;  /* encoder: bytes the coded bits may take */
    uint32_t *map;  /* encoder: significance, one bit per coefficient */
    uint32_t *strips; /* a bit per strip of the segment: one is significant */
    uint32_t *groups; /* a bit per group of 32 strips: one is significant */
    uint8_t *stop;  /* encoder: per strip, 1 + the highest plane a coefficient's
                     * leading bit is in (0: none), the pass it becomes significant in */
    uint8_t *gtop;  /* encoder: the same per group */
    bool bad;       /* decoder: a plane no coefficient can have (a malformed segment) */
    bool weigh;     /* plane offsets from the gains (exact coefficients) */
    bool groups_on; /* form 1: groups of 32 strips, each with a flag */
    bool inpar_on;  /* form 2: the incoming parent block as a neighbour */
    bool split;     /* form 3: each pass significance first, then refinement */
    bool split3;    /* form 4: significance in significant strips, refinement,
                     * then the other strips */
    spec_off_t so;  /* form 5 (so.sub): form 3 subband by subband */
    const int32_t *x0;
    embed_models_t *m;
    bool stopped;
} embed_t;

/* enc: c->enc, a constant where pass() is inlined */
static BW_ALWAYS_INLINE bool is_sig(const embed_t *c, const int32_t *p, bool enc)
{
    if (!p)
        return false;
    if (!enc)
        return *p != 0;
    size_t i = (size_t)(p - c->x0);
    return (c->map[i >> 5] >> (i & 31u)) & 1u;
}

static inline void set_sig(embed_t *c, const int32_t *p)
{
    size_t i = (size_t)(p - c->x0);
    c->map[i >> 5] |= 1u << (i & 31u);
}

/* Whether one more symbol may be coded: an encoder stops before its bytes
 * could pass the budget, a decoder of a cut segment before its code value
 * holds a byte that is not there. */
static BW_ALWAYS_INLINE bool room(embed_t *c, bool enc)
{
    if (c->stopped)
        return false;
    c->stopped = enc ? c->re.pos + 2u > c->budget : c->rd.pos > c->avail;
    return !c->stopped;
}

static BW_ALWAYS_INLINE unsigned bit(embed_t *c, bw_prob_t *p, unsigned b, bool enc)
{
    if (enc) {
        bw_rc_enc_bit(&c->re, p, b);
        return b;
    }
    return bw_rc_dec_bit(&c->rd, p);
}

/* A neighbour's state for the significance of a coefficient at plane b: 0
 * none or not significant, 1 significant with a leading bit at most one
 * plane above b, 2 higher (its leading bit is known once it is
 * significant). */
static BW_ALWAYS_INLINE unsigned nb_state(const embed_t *c, const int32_t *p, unsigned b,
                                          bool enc)
{
    if (!p || !is_sig(c, p, enc))
        return 0u;
    return bw_bitlen((uint32_t)bw_abs32(*p)) <= b + 2u ? 1u : 2u;
}

/* sign context of a known value: 0 none or zero, 1 positive, 2 negative */
static BW_ALWAYS_INLINE unsigned sgn(const embed_t *c, const int32_t *p, bool enc)
{
    return p && is_sig(c, p, enc) ? 1u + (*p < 0) : 0u;
}

/* A walk over a segment's coefficients in coding order with each one's
 * plane offset; form 5 takes the segment's spectral subbands in turn
 * (so->ord), each over the segment's vectors in coding order. */
typedef struct {
    bw_iter_t it;
    const spec_off_t *so;
    bool weigh;
    unsigned ed, ei, sb; /* offsets: the vector's, its block's; its subband */
    uint32_t i;
    size_t vi, v0;       /* the vector; the segment's first */
    const int32_t *last; /* the coefficient before (NULL after a seek) */
    bool inpar;          /* form 2: a one-band full BRDF's incoming parent block */
    bool ip;             /* the block has one: ... */
    uint32_t ipcf;       /* its coarse-to-fine index, */
    size_t ipbase;       /* its first vector in place */
    unsigned oi;         /* form 5: the subband's place in so->ord, */
    size_t vr, nv;       /* the vector in the segment, of nv, */
    uint32_t khi;        /* the subband's end */
} walk_t;

/* The incoming parent block of the walk's block (form 2, full BRDF). */
static void walk_block(walk_t *w)
{
    const bw_dims_t *d = &w->it.pl->dims;
    int j = bw_has_in(d) ? bw_biohaar_coef_level(w->it.i) : -1;
    w->ip = w->inpar && j >= 0;
    if (w->ip) {
        unsigned L = d->level_in;
        uint32_t t = bw_biohaar_pos(w->it.i, L);
        uint32_t pp = t & ~(3u << (2u * (L - 1u - (unsigned)j)));
        w->ipcf = bw_cf_index(pp, L);
        w->ipbase = (size_t)pp * d->n_out;
    }
}

static void walk_offsets(walk_t *w)
{
    w->vi = w->it.vi;
    if (w->it.i != w->i) {
        w->i = w->it.i;
        w->ei = in_offset(&w->it, w->weigh);
        walk_block(w);
    }
    w->ed = w->ei + out_offset(&w->it, w->weigh);
    w->sb = w->so->sub ? w->so->ord[w->oi] : 0u;
    w->khi = w->so->b.lo[w->sb + 1u];
}

/* Form 5: the walk at band k of vector vr of the segment in the subband
 * at place oi (past the last: the walk is over). */
static void walk_sub_at(walk_t *w, unsigned oi, size_t vr, uint32_t k)
{
    w->oi = oi;
    w->vr = vr;
    if (oi >= w->so->b.count)
        return;
    bw_iter_seek(&w->it, w->v0 + vr);
    walk_offsets(w);
    w->it.k = w->so->b.lo[w->sb] + k;
}

/* Form 5: past the subband's last band of a vector (the iterator at
 * its end, or past it: k = 0 at the next vector). */
static void walk_sub_next(walk_t *w)
{
    if (w->vr + 1u >= w->nv) {
        walk_sub_at(w, w->oi + 1u, 0, 0);
        return;
    }
    w->vr++;
    if (w->it.k)
        bw_iter_next_vec(&w->it);
    walk_offsets(w);
    w->it.k = w->so->b.lo[w->sb];
}

static void walk_start(walk_t *w, const bw_iter_t *start, size_t n, const spec_off_t *so,
                       bool weigh, bool inpar)
{
    w->it = *start;
    w->so = so;
    w->weigh = weigh;
    w->inpar = inpar && start->pl->dims.bands == 1u;
    w->i = start->i;
    w->ei = in_offset(start, weigh);
    w->v0 = start->vi;
    w->last = NULL;
    w->oi = 0;
    w->vr = 0;
    w->nv = n / start->pl->dims.bands;
    walk_block(w);
    walk_offsets(w);
    if (so->sub)
        w->it.k = so->b.lo[w->sb];
}

/* The walk at coefficient c of the segment. */
static void walk_seek(walk_t *w, size_t c)
{
    uint32_t b = w->it.pl->dims.bands;
    w->last = NULL;
    if (w->so->sub) {
        unsigned oi = 0;
        uint32_t len = 0;
        for (; oi < w->so->b.count; oi++) {
            unsigned sb = w->so->ord[oi];
            len = w->so->b.lo[sb + 1u] - w->so->b.lo[sb];
            if (c < (size_t)len * w->nv)
                break;
            c -= (size_t)len * w->nv;
        }
        walk_sub_at(w, oi, c / len, (uint32_t)(c % len)); /* no subband is empty */
        return;
    }
    bw_iter_seek(&w->it, w->v0 + c / b);
    w->it.k = (uint32_t)(c % b);
    walk_offsets(w);
}

/* Form 5: after a coefficient, past its subband's end in the vector (at k
 * = khi, or at the next vector when the subband ends the vector): on to the
 * next vector or subband. */
static inline void walk_sub_end(walk_t *w)
{
    if (w->so->sub && (w->it.k == w->khi || !w->it.k))
        walk_sub_next(w);
}

/* The plane offset of the coefficient the walk is at. */
static inline unsigned walk_offset(walk_t *w)
{
    if (w->it.vi != w->vi)
        walk_offsets(w);
    while (w->it.k >= w->so->b.lo[w->sb + 1u])
        w->sb++;
    return w->ed + w->so->e[w->sb];
}

/* The next coefficient: its place, class, neighbours and plane offset. */
static BW_ALWAYS_INLINE int32_t *walk_next(walk_t *w, uint8_t *cls, const int32_t **par,
                                           const int32_t **prv, const int32_t **left, unsigned *e)
{
    *e = walk_offset(w);
    *left = w->last; /* the band before, or the vector before's last */
    /* form 2, one band: the same outgoing coefficient of the incoming
     * parent block stands for the band above (coded before, when not
     * before the segment) */
    const int32_t *up = NULL;
    if (w->ip && (size_t)w->ipcf * w->it.pl->dims.n_out + w->it.o >= w->it.seg0)
        up = w->it.x + w->ipbase + ((size_t)(w->it.vec - w->it.x) - w->it.base);
    int32_t *p = bw_iter_next(&w->it, cls, par, prv);
    if (!*prv)
        *prv = up;
    w->last = p;
    walk_sub_end(w);
    return p;
}

/* The same for a refinement pass, which needs no neighbours. */
static inline int32_t *walk_next_ref(walk_t *w, uint8_t *cls, unsigned *e)
{
    *e = walk_offset(w);
    uint32_t k = w->it.k;
    int32_t *p = w->it.vec + k;
    *cls = (uint8_t)bw_coef_cls(w->it.pl->spec_cls[k], w->it.cls_dir);
    if (++w->it.k == w->it.pl->dims.bands)
        bw_iter_next_vec(&w->it);
    w->last = p;
    walk_sub_end(w);
    return p;
}

#define STRIP_SIG(c, s) (((c)->strips[(s) >> 5] >> ((s)&31u)) & 1u)
#define GROUP_SIG(c, g) (((c)->groups[(g) >> 5] >> ((g)&31u)) & 1u)

/* What a pass codes: every bit of plane P in coding order (forms 0 to 2),
 * or (form 3) the significance of the coefficients not yet significant,
 * then the refinement of the others; or (form 4) that significance in the
 * strips with a significant coefficient (OLD), the refinement, then the
 * significance in the other strips (NEW). */
enum { PASS_ALL, PASS_SIG, PASS_REF, PASS_SIG_OLD, PASS_SIG_NEW };

/* One pass at plane P over the n coefficients from start, up to
 * coefficient `limit`; returns where it stopped (n: the whole pass). A
 * group, then a strip, with no significant coefficient yet (c->groups,
 * c->strips) codes a flag: does one become significant now; only then its
 * coefficients are visited (what: PASS_*; a refinement pass visits only the
 * strips with a coefficient significant before plane P). */
static BW_ALWAYS_INLINE size_t pass(embed_t *c, const bw_iter_t *start, size_t n, unsigned P,
                                    size_t limit, bool enc, unsigned what)
{
    walk_t w;
    walk_start(&w, start, n, &c->so, c->weigh, c->inpar_on);
    size_t at = 0; /* the coefficient the walk is at */
    for (size_t s = 0; s < n; s += STRIP) {
        size_t cnt = n - s < STRIP ? n - s : STRIP, si = s / STRIP, gi = s / GROUP;
        bool any_sig = STRIP_SIG(c, si);
        if (at != s) {
            walk_seek(&w, s);
            at = s;
        }
        if (what == PASS_SIG_NEW && any_sig)
            continue;
        if ((what == PASS_REF || what == PASS_SIG_OLD) && !any_sig) {
            if (s % GROUP == 0u && !GROUP_SIG(c, gi))
                s += GROUP - STRIP; /* nor any of its group */
            continue;
        }
        if (c->groups_on && s % GROUP == 0u && !GROUP_SIG(c, gi)) {
            /* a group of strips none significant yet: does one of its
             * coefficients become so now (context: the group before, the
             * class of its first coefficient) */
            unsigned pg = gi ? GROUP_SIG(c, gi - 1u) : 0u;
            uint8_t cls0 = (uint8_t)bw_coef_cls(w.it.pl->spec_cls[w.it.k], w.it.cls_dir);
            if (s >= limit || !room(c, enc))
                return s;
            if (!bit(c, &c->m->group[pg][cls0], enc && c->gtop[gi] == P + 1u, enc)) {
                s += GROUP - STRIP; /* the next group */
                continue;
            }
        }
        if (!any_sig) {
            /* the previous strip, the first coefficient's parent and class */
            unsigned pc = si ? STRIP_SIG(c, si - 1u) : 0u;
            int32_t sc = w.it.pl->spec_cls[w.it.k];
            uint8_t cls0 = (uint8_t)bw_coef_cls(sc, w.it.cls_dir);
            unsigned pp = is_sig(c, bw_parent_of(w.it.par, w.it.vec, sc, w.it.k), enc);
            if (s >= limit || !room(c, enc))
                return s;
            if (!bit(c, &c->m->strip[pp][pc][cls0], enc && c->stop[si] == P + 1u, enc))
                continue;
        }
        for (size_t k = 0; k < cnt; k++) {
            uint8_t cls;
            const int32_t *par = NULL, *prv = NULL, *left = NULL;
            unsigned e;
            int32_t *p = what == PASS_REF ? walk_next_ref(&w, &cls, &e)
                                          : walk_next(&w, &cls, &par, &prv, &left, &e);
            at++;
            if (P < e)
                continue; /* every plane coded */
            unsigned b = P - e;
            if (b > 30u) { /* |c| < 2^31: only a malformed segment says more */
                c->bad = c->stopped = true;
                return s + k;
            }
            uint32_t a = (uint32_t)bw_abs32(*p);
            bool sig = is_sig(c, p, enc);
            /* a refinement pass: those significant before plane b (not
             * those whose leading bit is b, found by this plane's first
             * half); a significance pass: the others */
            if (what == PASS_REF ? !sig || a >> b == 1u : what != PASS_ALL && sig)
                continue;
            if (s + k >= limit || !room(c, enc))
                return s + k;
            if (sig) { /* refinement */
                unsigned r = bit(c, &c->m->ref[(a >> (b + 1u)) == 1u][cls], (a >> b) & 1u, enc);
                if (!enc && r)
                    *p = *p < 0 ? -(int32_t)(a | 1u << b) : (int32_t)(a | 1u << b);
                continue;
            }
            unsigned pc = par ? 1u + nb_state(c, par, b, enc) : 0u;
            unsigned ctx = ((cls * 4u + pc) * 3u + nb_state(c, left, b, enc)) * 3u +
                           nb_state(c, prv, b, enc);
            if (!bit(c, &c->m->sig[ctx], (a >> b) & 1u, enc))
                continue;
            /* its sign, then it is significant */
            if (!room(c, enc))
                return s + k;
            unsigned neg =
                bit(c, &c->m->sign[3u * sgn(c, par, enc) + sgn(c, left, enc)], *p < 0, enc);
            if (enc)
                set_sig(c, p);
            else
                *p = neg ? -(int32_t)(1u << b) : (int32_t)(1u << b);
            c->strips[si >> 5] |= 1u << (si & 31u);
            c->groups[gi >> 5] |= 1u << (gi & 31u);
        }
    }
    return n;
}

/* pass() for each side, its tests of the side folded, each out of line
 * with a frame of its own: a refinement part, whose walk reads no
 * neighbours, in a copy of its own; the others in one */
static BW_NOINLINE size_t pass_dec(embed_t *c, const bw_iter_t *start, size_t n, unsigned P,
                                   size_t limit, unsigned what)
{
    if (what == PASS_REF)
        return pass(c, start, n, P, limit, false, PASS_REF);
    return pass(c, start, n, P, limit, false, what);
}

static BW_NOINLINE size_t pass_enc(embed_t *c, const bw_iter_t *start, size_t n, unsigned P,
                                   size_t limit, unsigned what)
{
    if (what == PASS_REF)
        return pass(c, start, n, P, limit, true, PASS_REF);
    return pass(c, start, n, P, limit, true, what);
}

/* The positions of a plane: 0..n (forms 0 to 2), 0..2n (form 3: its
 * significance half, then n + the refinement half's) or 0..3n (form 4: the
 * significance in significant strips, n + the refinement's, 2n + the
 * significance in the others'). */
static inline size_t plane_end(const embed_t *c, size_t n)
{
    return c->split3 ? 3u * n : c->split ? 2u * n : n;
}

/* Plane P up to position limit; returns where it stopped (plane_end: the
 * whole plane). In line, so that no frame lies between the segment's
 * coder and its passes. */
static BW_ALWAYS_INLINE size_t plane(embed_t *c, const bw_iter_t *start, size_t n, unsigned P,
                                     size_t limit, bool enc)
{
    size_t (*f)(embed_t *, const bw_iter_t *, size_t, unsigned, size_t, unsigned) =
        enc ? pass_enc : pass_dec;
    if (!c->split)
        return f(c, start, n, P, limit, PASS_ALL);
    /* each part up to the limit; a recorded stop in a part ends the plane
     * there even with nothing left to code at it (a malformed segment) */
    size_t at = f(c, start, n, P, limit < n ? limit : n, c->split3 ? PASS_SIG_OLD : PASS_SIG);
    if (at < n || limit < n)
        return at;
    at = f(c, start, n, P, limit - n < n ? limit - n : n, PASS_REF);
    if (!c->split3 || at < n || limit < 2u * n)
        return n + at;
    return 2u * n + f(c, start, n, P, limit - 2u * n, PASS_SIG_NEW);
}

/* The encoder's passes of a segment: 1 + the highest plane any
 * coefficient has (0: all zero), and the same per strip and per group (the
 * pass each becomes significant in: an insignificant strip's or group's
 * flag is whether that pass is now); its coefficients' significance
 * cleared. */
static BW_NOINLINE unsigned passes_of(embed_t *c, const bw_iter_t *start, size_t n)
{
    walk_t w;
    walk_start(&w, start, n, &c->so, c->weigh, false);
    unsigned top = 0;
    for (size_t k = 0; k < n; k++) {
        uint8_t cls;
        const int32_t *par, *prv, *left;
        unsigned e;
        int32_t *p = walk_next(&w, &cls, &par, &prv, &left, &e);
        size_t i = (size_t)(p - start->x);
        c->map[i >> 5] &= ~(1u << (i & 31u));
        unsigned bl = bw_bitlen((uint32_t)bw_abs32(*p)), t = bl ? bl + e : 0u;
        uint8_t *st = &c->stop[k / STRIP], *gt = &c->gtop[k / GROUP];
        if (k % STRIP == 0u)
            *st = 0;
        if (k % GROUP == 0u)
            *gt = 0;
        *st = t > *st ? (uint8_t)t : *st;
        *gt = t > *gt ? (uint8_t)t : *gt;
        top = t > top ? t : top;
    }
    return top;
}

static void models_init(embed_models_t *m)
{
    bw_prob_t *pr = &m->group[0][0];
    for (size_t i = 0; i < sizeof *m / sizeof *pr; i++)
        pr[i] = BW_PROB_INIT;
}

#define EMBED_HEAD 6u /* passes u8, passes done u8, coefficients of the next u32 */

/* The embedded coder's scratch after the plan's tables (BW_WORK_BOUND): a
 * bit per coefficient, then a bit per strip. */
static uint32_t *scratch(const bw_plan_t *pl, int32_t *x)
{
    return (uint32_t *)(x + pl->n + 2u * pl->dims.bands + 16u);
}

/* The scratch of a segment of n coefficients: the encoder's map of the
 * plan's coefficients, a bit per strip and per group (zeroed), and the
 * encoder's byte per strip and per group (BW_WORK_BOUND holds n / 16 + 8
 * words for them). */
static void scratch_of(embed_t *c, const bw_plan_t *pl, int32_t *x, size_t n)
{
    size_t sn = (n + STRIP - 1u) / STRIP, gn = (n + GROUP - 1u) / GROUP;
    size_t sw = (sn + 31u) / 32u, gw = (gn + 31u) / 32u;
    c->map = scratch(pl, x);
    c->strips = c->map + (pl->n + 31u) / 32u;
    c->groups = c->strips + sw;
    c->stop = (uint8_t *)(c->groups + gw);
    c->gtop = c->stop + sn;
    memset(c->strips, 0, (sw + gw) * sizeof *c->strips);
}

/* A coder of the n coefficients from start: its state, models, scratch. */
static void embed_init(embed_t *c, bool enc, const bw_iter_t *start, size_t n, bw_models_t *m)
{
    c->enc = enc;
    c->bad = c->stopped = false;
    c->x0 = start->x;
    scratch_of(c, start->pl, start->x, n);
    c->weigh = start->pl->step_q8 <= BW_STEP_ONE_Q8;
    c->groups_on = start->pl->embed >= 2u;
    c->inpar_on = start->pl->embed >= 3u;
    c->split = start->pl->embed >= 4u;
    c->split3 = start->pl->embed == 5u;
    spec_offsets(start->pl, c->weigh, start->pl->embed >= 6u, &c->so);
    c->m = (embed_models_t *)(void *)m;
    models_init(c->m);
}

size_t bw_embed_encode(const bw_iter_t *start, size_t n, uint8_t *out, size_t cap, bool truncate,
                       bw_models_t *m, bool *over)
{
    embed_t c;
    embed_init(&c, true, start, n, m);
    *over = out && cap < EMBED_HEAD;
    if (*over)
        return EMBED_HEAD;
    c.budget = out && truncate ? cap - EMBED_HEAD : SIZE_MAX;
    bw_rc_enc_init(&c.re, out ? out + EMBED_HEAD : NULL, out ? cap - EMBED_HEAD : 0u);
    unsigned np = passes_of(&c, start, n), done = 0;
    size_t end = plane_end(&c, n), at = end;
    for (; done < np; done++) {
        at = plane(&c, start, n, np - 1u - done, end, true);
        if (at < end)
            break;
    }
    size_t len = bw_rc_enc_finish(&c.re);
    if (out) {
        out[0] = (uint8_t)np;
        out[1] = (uint8_t)done;
        bw_put_u32(out + 2, done == np ? 0u : (uint32_t)at);
        *over = c.re.overflow;
    }
    return EMBED_HEAD + len;
}

/* Each coefficient of the segment, in a frame of its own (not below the
 * passes'): to zero (zero), or, the decoding stopped in pass P before
 * position `stop`, a significant coefficient whose planes below b are not
 * known to the middle of their span (forms 3 to 5: those found in this
 * pass, and those its refinement part, positions n to 2n, reached, know
 * plane b; the others b + 1). */
static BW_NOINLINE void settle(embed_t *c, const bw_iter_t *start, size_t n, bool zero,
                               unsigned P, size_t stop)
{
    walk_t w;
    walk_start(&w, start, n, &c->so, c->weigh, false);
    for (size_t k = 0; k < n; k++) {
        uint8_t cls;
        const int32_t *par, *prv, *left;
        unsigned e;
        int32_t *p = walk_next(&w, &cls, &par, &prv, &left, &e);
        if (zero) {
            *p = 0;
            continue;
        }
        /* forms 3 to 5: found in this pass (magnitude 2^b), or reached by
         * its refinement part (stop - n >= n: all) */
        bool at_b = !c->split ? k < stop
                              : (P >= e && P - e <= 30u && (uint32_t)bw_abs32(*p) >> (P - e) == 1u) ||
                                    (stop > n && k < stop - n);
        unsigned lo = at_b ? P : P + 1u; /* its lowest plane known, + e */
        if (*p && lo > e && lo - e <= 30u) {
            uint32_t add = ((1u << (lo - e)) - 1u) >> 1;
            *p = *p < 0 ? *p - (int32_t)add : *p + (int32_t)add;
        }
    }
}

bw_status_t bw_embed_decode(const bw_iter_t *start, size_t n, const uint8_t *in, size_t len,
                            bool cut, bw_models_t *m, bool *inexact)
{
    embed_t c;
    embed_init(&c, false, start, n, m);
    settle(&c, start, n, true, 0, 0); /* the coefficients start at zero */
    *inexact = true;
    if (len < EMBED_HEAD)
        return cut ? BW_OK : BW_ERR_CORRUPT;
    unsigned np = in[0], done = in[1];
    uint32_t at = bw_get_u32(in + 2);
    size_t end = plane_end(&c, n);
    if (np > 64u || done > np || (done == np && at) || (done < np && at >= end))
        return BW_ERR_CORRUPT;
    c.avail = cut ? len - EMBED_HEAD : SIZE_MAX;
    bw_rc_dec_init(&c.rd, in + EMBED_HEAD, len - EMBED_HEAD);
    /* the passes the encoder coded, the last up to where it stopped; a cut
     * segment to where its bytes end */
    unsigned t = 0;
    size_t stop = end;
    for (; t < np; t++) {
        if (t > done) { /* pass `done` ended where its coding did */
            stop = 0;
            break;
        }
        stop = plane(&c, start, n, np - 1u - t, t < done ? end : at, false);
        if (stop < end)
            break;
    }
    if (c.bad)
        return BW_ERR_CORRUPT;
    if (t >= np) {
        *inexact = false;
        return BW_OK;
    }
    settle(&c, start, n, false, np - 1u - t, stop);
    return BW_OK;
}

#endif
