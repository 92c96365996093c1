/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The decoder: header and CRC, the body, then the quantiser, the transforms
 * and the symmetry steps backwards, or prediction. Every payload the format
 * allows decodes in every build, whatever its encoder leaves out
 * (bw_config.h).
 */
#include <string.h>

#include "bw_crc32.h"
#include "bw_internal.h"
#include "bw_le.h"
#include "bw_strip_coder.h"

/* The plan of payload p's header h, its tables after the n coefficients of
 * work (p only for its chunks' steps). */
#if BW_CFG_CHUNK_STEPS
#define PLAN_OF(pl, h, p, work, n) plan_of(pl, h, p, work, n)
static void plan_of(bw_plan_t *pl, const bw_header_t *h, const uint8_t *p, int32_t *work,
                    size_t n)
#else
#define PLAN_OF(pl, h, p, work, n) plan_of(pl, h, work, n)
static void plan_of(bw_plan_t *pl, const bw_header_t *h, int32_t *work, size_t n)
#endif
{
    bw_plan_make(pl, &h->dims, h->basis, h->mode,
                 h->mode == BW_MODE_MAX_ERROR ? h->max_error : h->step_q8, h->flags, 0u, work + n,
                 work + n);
    if (BW_CFG_SEGMENTS) /* (0 from bw_plan_make: a core without them refuses them) */
        pl->seg_vec = h->segment_vectors;
    if (BW_CFG_EMBED)
        pl->embed = (uint8_t)h->embedded;
#if BW_CFG_CHUNK_STEPS
    pl->chunk_vec = bw_chunk_steps(p, h, &pl->chunk_d);
#endif
    bw_plan_tables(pl);
}

/* What the segments of a decode came to (bw_decode_salvage's outputs). */
typedef struct {
    bool salvage;     /* the payload may be damaged or cut: decode what is whole */
    uint8_t *seg_ok;  /* may be NULL */
    size_t seg_cap;
    uint8_t *vec_lost; /* may be NULL: 1 lost, 2 inexact (an embedded segment cut) */
    uint32_t lost;
} seg_out_t;

#if BW_CFG_EMBED
/* An embedded segment (below); out of line, so that its iterator stays off
 * the stack of every other decode. */
static BW_NOINLINE bw_status_t decode_embedded(bw_iter_t *it, size_t nvec, const uint8_t *in,
                                               size_t sl, size_t there, bw_models_t *m,
                                               bool *inexact)
{
    bw_iter_t start = *it;
    bool cut = there < sl;
    bw_status_t st = bw_embed_decode(&start, nvec * it->pl->dims.bands, in, cut ? there : sl,
                                     cut, m, inexact);
    *inexact = *inexact && cut; /* a whole segment decodes to what its encoder coded */
    for (size_t k = 0; k < nvec; k++)
        bw_iter_next_vec(it);
    return st;
}
#endif

/* One segment of sl bytes at in (of which `there` arrived) into the nvec
 * vectors from it, which it leaves past them: the strip coder's, or an
 * embedded one, whole or (there < sl) cut; *inexact for the latter's
 * approximations. */
static bw_status_t decode_segment(bw_iter_t *it, const bw_plan_t *pl, size_t nvec,
                                  const uint8_t *in, size_t sl, size_t there, unsigned coder,
                                  bw_models_t *m, bool *inexact)
{
    *inexact = false;
#if BW_CFG_EMBED
    if (pl->embed)
        return decode_embedded(it, nvec, in, sl, there, m, inexact);
#else
    (void)there;
#endif
    return bw_decode_coefs(it, nvec * pl->dims.bands, in, sl, coder, m);
}

/* A segmented body (docs/FORMAT.md, Segments): its table, whose CRC covers
 * the header, then each segment decoded afresh; with so->salvage the
 * segments that are not whole within payload[len] or fail their CRC are
 * lost (their coefficients zero), else any such is an error. */
static bw_status_t decode_segments(const bw_plan_t *pl, int32_t *x, const uint8_t *p, size_t len,
                                   const bw_header_t *h, bw_models_t *m, seg_out_t *so)
{
    uint32_t segs = h->segments, bands = pl->dims.bands;
    size_t hl = h->header_len, tab = bw_segment_table_size(segs);
    bool salvage = BW_CFG_SALVAGE && so->salvage;
    size_t avail = salvage ? len - hl : h->body_len;
    size_t nv = (size_t)pl->dims.n_in * pl->dims.n_out, pos = tab;
    const uint8_t *t = p + hl;
    if (tab > avail || bw_get_u32(t + tab - 4u) != bw_crc32(p, hl + tab - 4u))
        return salvage ? BW_ERR_CRC : BW_ERR_CORRUPT;
    unsigned coder = bw_coder_of(h->flags);
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    for (uint32_t s = 0; s < segs; s++) {
        size_t first = (size_t)s * pl->seg_vec, nvec = nv - first;
        uint32_t sl = bw_get_u32(t + (size_t)s * BW_SEG_ENTRY);
        if (nvec > pl->seg_vec)
            nvec = pl->seg_vec;
        bool ok = pos <= avail && sl <= avail - pos &&
                  bw_crc32(p + hl + pos, sl) == bw_get_u32(t + (size_t)s * BW_SEG_ENTRY + 4u);
        /* an embedded segment cut short decodes to an approximation from
         * the bytes that arrived (its CRC is of all of them) */
        size_t there = ok ? sl : 0u;
        if (BW_CFG_EMBED && pl->embed && salvage && !ok && pos <= avail && sl > avail - pos)
            there = avail - pos;
        bw_iter_segment(&it);
        bool inexact = false;
        if (ok || there) {
            bw_status_t st = decode_segment(&it, pl, nvec, p + hl + pos, sl, there, coder, m,
                                            &inexact);
            if (st != BW_OK && !salvage)
                return st;
            ok = st == BW_OK;
        } else if (!salvage) {
            return BW_ERR_CORRUPT;
        }
        if (BW_CFG_SALVAGE && (!ok || inexact)) {
            /* lost (its vectors zero) or approximations (a cut embedded
             * segment): marked so, the iterator past them */
            so->lost++;
            bw_iter_at(&it, pl, x, first);
            for (size_t k = 0; k < nvec; k++) {
                if (!ok)
                    memset(it.vec, 0, bands * sizeof *x);
                if (so->vec_lost)
                    so->vec_lost[(size_t)(it.vec - x) / bands] = ok ? 2u : 1u;
                bw_iter_next_vec(&it);
            }
            ok = false;
        }
        if (so->seg_ok && s < so->seg_cap)
            so->seg_ok[s] = ok;
        pos = pos <= avail && sl <= avail - pos ? pos + sl : avail + 1u;
    }
    /* a whole body is its segments exactly */
    return salvage || pos == avail ? BW_OK : BW_ERR_CORRUPT;
}

static bw_status_t decode_checked(bw_ctx_t *ctx, const uint8_t *p, size_t len,
                                  const bw_header_t *h, int32_t *samples, size_t samples_cap,
                                  int32_t *work, size_t work_cap, seg_out_t *so)
{
    const bw_dims_t *d = &h->dims;
    size_t n = bw_dims_samples(d);
    if (samples_cap < n || work_cap < bw_work_bound(n, d->bands))
        return BW_ERR_WORK;
    seg_out_t strict = {false, NULL, 0, NULL, 0};
    if (!so)
        so = &strict;
    if (BW_CFG_SALVAGE && so->vec_lost)
        memset(so->vec_lost, 0, (size_t)d->n_in * d->n_out);
#if BW_CFG_BANDS
    if (h->band_access) /* (no segments: whole, or lost whole) */
        return bw_bands_decode(h, p, samples);
#endif
    bw_plan_t pl;
    PLAN_OF(&pl, h, p, work, n);
    bw_status_t st = BW_CFG_SEGMENTS && pl.seg_vec ? decode_segments(&pl, work, p, len, h, &ctx->models, so)
                                : bw_decode_body(&pl, work, p + h->header_len, h->body_len,
                                                 bw_coder_of(h->flags), &ctx->models);
    if (st != BW_OK)
        return st;
    if (pl.basis == BW_BASIS_PRED) {
        bw_predict(&pl, work, NULL, false); /* decoded samples: no prequantiser left */
        memcpy(samples, work, n * sizeof *samples);
        return BW_OK;
    }
    if (pl.step_q8 > BW_STEP_ONE_Q8)
        bw_quantise(&pl, work, false);
    bw_transform_inv(&pl, work);
    if (pl.mirror || pl.recip)
        bw_symmetry(&pl, work, false);
    for (size_t i = 0; i < n; i++) {
        int64_t v = (int64_t)work[i] * pl.prequant;
        samples[i] = v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
    }
    return BW_OK;
}

bw_status_t bw_decode_ctx(bw_ctx_t *ctx, const uint8_t *payload, size_t len, int32_t *samples,
                          size_t samples_cap, int32_t *work, size_t work_cap, bw_header_t *hdr_out)
{
    bw_header_t h;
    if (!ctx || !payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_read(payload, len, &h);
    if (hdr_out)
        *hdr_out = h;
    if (st != BW_OK)
        return st;
    return decode_checked(ctx, payload, len, &h, samples, samples_cap, work, work_cap, NULL);
}

bw_status_t bw_decode_salvage(bw_ctx_t *ctx, const uint8_t *payload, size_t len,
                              int32_t *samples, size_t samples_cap, int32_t *work,
                              size_t work_cap, bw_header_t *hdr_out, uint8_t *seg_ok,
                              size_t seg_cap, uint8_t *vec_lost)
{
    bw_header_t h;
    if (!ctx || !payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_read(payload, len, &h);
    if (!BW_CFG_SALVAGE)
        seg_cap = 0;
    seg_out_t so = {st != BW_OK, seg_ok, seg_cap, vec_lost, 0};
    if (BW_CFG_SALVAGE && (st == BW_ERR_CRC || st == BW_ERR_HEADER)) {
        /* not whole: the header's fields as they read, which the segment
         * table's CRC vouches for (the segments are found from the table:
         * a host's tail, whose place a cut moves, plays no part); a payload
         * without segments is lost whole */
        bw_header_t f;
        memset(&f, 0, sizeof f);
        if (bw_header_parse_cut(payload, len, &f) == BW_OK && f.segment_vectors) {
            h = f;
            st = BW_OK;
        }
    }
    if (hdr_out)
        *hdr_out = h;
    if (st != BW_OK)
        return st;
    st = decode_checked(ctx, payload, len, &h, samples, samples_cap, work, work_cap, &so);
    if (st == BW_OK && seg_ok && !h.segment_vectors && seg_cap)
        seg_ok[0] = 1;
    return st == BW_OK && so.lost ? BW_ERR_INCOMPLETE : st;
}

bw_status_t bw_decode(const uint8_t *payload, size_t len, int32_t *samples, size_t samples_cap,
                      int32_t *work, size_t work_cap, bw_header_t *hdr_out)
{
    bw_ctx_t ctx;
    return bw_decode_ctx(&ctx, payload, len, samples, samples_cap, work, work_cap, hdr_out);
}

bw_status_t bw_decode_unchecked(const uint8_t *payload, size_t len, int32_t *samples,
                                size_t samples_cap, int32_t *work, size_t work_cap)
{
    bw_header_t h;
    bw_ctx_t ctx;
    if (!payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_parse_fields(payload, len, &h); /* every field but crc */
    if (st != BW_OK)
        return st;
    return decode_checked(&ctx, payload, len, &h, samples, samples_cap, work, work_cap, NULL);
}

/* ---- incoming directions, coarser levels ----------------------------------- */

/* What a partial decode wants of the coding order: with by_rows, the
 * incoming blocks that the marked rows need (block_needed): those marked
 * in `rows`, or (rows NULL) row `one`; else the first `coarse` vectors of
 * every incoming block (of the first `blocks` only, when not 0). */
typedef struct {
    bool by_rows;
    const uint8_t *rows;
    uint32_t one;
    const bw_plan_t *pl;
    size_t coarse, blocks;
} want_t;

static inline bool marked(const want_t *w, uint32_t t)
{
    return w->rows ? w->rows[t] != 0u : t == w->one;
}

/* Whether row t is rebuilt: marked, or the partner that a marked row of a
 * full BRDF's mirrored half was coded against. */
static bool row_needed(const want_t *w, uint32_t t)
{
    const bw_dims_t *d = &w->pl->dims;
    return marked(w, t) || (w->pl->mirror && bw_has_in(d) && t < d->n_in / 2u &&
                            marked(w, bw_mirror_index(t, d->level_in)));
}

/* Whether a needed row lies in [lo, hi). */
static bool rows_within(const want_t *w, uint32_t lo, uint32_t hi)
{
    if (!w->rows) { /* one row, and its partner */
        const bw_dims_t *d = &w->pl->dims;
        uint32_t m = w->pl->mirror && bw_has_in(d) && w->one >= d->n_in / 2u
                         ? bw_mirror_index(w->one, d->level_in)
                         : w->one;
        return (w->one >= lo && w->one < hi) || (m >= lo && m < hi);
    }
    for (uint32_t t = lo; t < hi; t++)
        if (row_needed(w, t))
            return true;
    return false;
}

/* Whether incoming block c (coding order) is needed by the rows: a full
 * BRDF's blocks are needed by every row below their parent (the inverse
 * step of a parent takes its three details and its scaling value). */
static bool block_needed(const want_t *w, uint32_t c)
{
    const bw_dims_t *d = &w->pl->dims;
    if (!bw_has_in(d))
        return row_needed(w, c);
    unsigned L = d->level_in;
    int j = bw_biohaar_coef_level(c);
    uint32_t span = j < 0 ? 1u << (2u * L) : 1u << (2u * (L - (unsigned)j)),
             lo = bw_biohaar_pos(c, L) / span * span;
    return rows_within(w, lo, lo + span);
}

/* The end of the last wanted vector in [a, b), a when there is none. */
static size_t wanted_end(const want_t *w, size_t no, size_t a, size_t b)
{
    if (w->by_rows) {
        for (size_t c = (b - 1u) / no + 1u; c-- > a / no;)
            if (block_needed(w, (uint32_t)c))
                return (c + 1u) * no < b ? (c + 1u) * no : b;
        return a;
    }
    if (w->blocks && b > w->blocks * no)
        b = w->blocks * no;
    if (b <= a)
        return a;
    size_t k = (b - 1u) / no * no, e = k + w->coarse < b ? k + w->coarse : b;
    return e > a ? e : a;
}

/* Decodes the wanted vectors: the segments that hold them, or a body in one
 * piece up to the last of them. */
static bw_status_t decode_ranges(const bw_plan_t *pl, int32_t *x, const uint8_t *p,
                                 const bw_header_t *h, bw_models_t *m, const want_t *w)
{
    uint32_t b = pl->dims.bands, V = pl->seg_vec;
    unsigned coder = bw_coder_of(h->flags);
    bw_iter_t it;
    size_t no = pl->dims.n_out, nv = (size_t)pl->dims.n_in * no;
    if (!V) { /* whole strips: a strip's presence is of all its 32 values */
        size_t last = wanted_end(w, no, 0, nv);
        size_t c = (last * b + BW_STRIP - 1u) / BW_STRIP * BW_STRIP;
        bw_iter_init(&it, pl, x);
        return bw_decode_coefs(&it, c < pl->n ? c : pl->n, p + h->header_len, h->body_len,
                               coder, m);
    }
    const uint8_t *t = p + h->header_len;
    size_t tab = bw_segment_table_size(h->segments), pos = tab;
    if (tab > h->body_len || bw_get_u32(t + tab - 4u) != bw_crc32(p, h->header_len + tab - 4u))
        return BW_ERR_CRC;
    for (size_t s = 0; s < h->segments; s++) {
        size_t first = s * V, cnt = nv - first < V ? nv - first : V;
        uint32_t sl = bw_get_u32(t + s * BW_SEG_ENTRY);
        if (pos > h->body_len || sl > h->body_len - pos)
            return BW_ERR_CRC;
        size_t end = wanted_end(w, no, first, first + cnt);
        if (end > first) {
            if (bw_crc32(t + pos, sl) != bw_get_u32(t + s * BW_SEG_ENTRY + 4u))
                return BW_ERR_CRC;
            bw_iter_at(&it, pl, x, first);
            bw_iter_segment(&it);
            bool inexact;
            /* the strip coder stops at the strip holding the last wanted
             * value; an embedded segment's planes hold every vector */
            size_t nc = ((end - first) * b + BW_STRIP - 1u) / BW_STRIP * BW_STRIP;
            bw_status_t st =
                pl->embed ? decode_segment(&it, pl, cnt, t + pos, sl, sl, coder, m, &inexact)
                          : bw_decode_coefs(&it, nc < cnt * b ? nc : cnt * b, t + pos, sl, coder,
                                            m);
            if (st != BW_OK)
                return st;
        }
        pos += sl;
    }
    return BW_OK;
}

/* The arguments and the header of a partial decode: in segments the CRCs
 * of the table and of the segments read vouch for what is used (no pass
 * over the whole payload); a body in one piece, its CRC. */
static bw_status_t partial_header(const bw_ctx_t *ctx, const uint8_t *payload, size_t len,
                                  const int32_t *samples, const int32_t *work, bw_header_t *h,
                                  bw_header_t *hdr_out)
{
    if (!ctx || !payload || !samples || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_parse_fields(payload, len, h);
    if (st == BW_OK && !(BW_CFG_SEGMENTS && h->segment_vectors))
        st = bw_header_read(payload, len, h);
    if (hdr_out)
        *hdr_out = *h;
    return st;
}

/* A row's outgoing and spectral inverse steps (its incoming ones done). */
static void rebuild_row(const bw_plan_t *pl, int32_t *y)
{
    const bw_dims_t *d = &pl->dims;
    size_t b = d->bands;
    if (bw_has_out(d))
        bw_biohaar_inv(y, d->level_out, b);
    for (size_t o = 0; pl->spec_levels && o < d->n_out; o++)
        bw_spec_inv(y + o * b, (uint32_t)b, pl->basis, pl->spec_levels, pl->tmp);
}

/* The mirror step's inverse on one rebuilt row x: within the row (a BRDF
 * of incidences), or, for a full BRDF's mirrored half, the partner row mr
 * it was coded against added back (mr NULL: x is not of that half). */
static void unmirror_row(const bw_plan_t *pl, int32_t *x, const int32_t *mr)
{
    const bw_dims_t *d = &pl->dims;
    size_t b = d->bands;
    if (!bw_has_in(d)) { /* the symmetry steps of a plan of one row */
        bw_plan_t sub = *pl;
        sub.dims.n_in = 1u;
        sub.dims.shape = BW_SHAPE_BRDF_ISO;
        bw_symmetry(&sub, x, false);
        return;
    }
    for (uint32_t o = 0; mr && o < d->n_out; o++) {
        const int32_t *pv = mr + (size_t)bw_mirror_index(o, d->level_out) * b;
        for (size_t k = 0; k < b; k++)
            x[o * b + k] = (int32_t)((uint32_t)x[o * b + k] + (uint32_t)pv[k]);
    }
}

/* A rebuilt row's samples: times the prequantiser, saturated. */
static void put_row(const int32_t *x, size_t row, uint32_t pq, int32_t *out)
{
    for (size_t k = 0; k < row; k++) {
        int64_t v = (int64_t)x[k] * pq;
        out[k] = v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
    }
}

/* The rows marked in rows[n_in], or (rows NULL) row `one` (bw_decode_rows,
 * bw_decode_incoming). */
static bw_status_t decode_rows(bw_ctx_t *ctx, const uint8_t *payload, size_t len,
                               const uint8_t *rows, uint32_t one, int32_t *samples,
                               size_t samples_cap, int32_t *work, size_t work_cap,
                               bw_header_t *hdr_out)
{
    bw_header_t h;
    bw_status_t st = partial_header(ctx, payload, len, samples, work, &h, hdr_out);
    if (st != BW_OK)
        return st;
    const bw_dims_t *d = &h.dims;
    size_t n = bw_dims_samples(d), no = d->n_out, row = no * d->bands, nr = rows ? 0u : 1u;
    if (d->shape == BW_SHAPE_REFLECTANCE || (h.flags & BW_FLAG_RECIPROCAL) ||
        (!rows && one >= d->n_in))
        return BW_ERR_ARG;
    for (uint32_t t = 0; rows && t < d->n_in; t++)
        nr += rows[t] != 0u;
    if (samples_cap < nr * row || work_cap < bw_work_bound(n, d->bands))
        return BW_ERR_WORK;
#if BW_CFG_BANDS
    if (h.band_access) { /* every spectrum, then the rows marked */
        st = bw_bands_decode(&h, payload, work);
        for (uint32_t t = 0; st == BW_OK && t < d->n_in; t++)
            if (rows ? rows[t] != 0u : t == one) {
                memcpy(samples, work + (size_t)t * row, row * sizeof *samples);
                samples += row;
            }
        return st;
    }
#endif
    bw_plan_t pl;
    PLAN_OF(&pl, &h, payload, work, n);
    want_t w = {.by_rows = true, .rows = rows, .one = one, .pl = &pl};
    st = decode_ranges(&pl, work, payload, &h, &ctx->models, &w);
    if (st != BW_OK)
        return st;
    bool pred = pl.basis == BW_BASIS_PRED;
    /* prediction: each segment's spectra from its first to its last marked
     * one (decoded: a segment decodes from its first vector) */
    for (uint32_t f = 0, V = pl.seg_vec ? pl.seg_vec : d->n_in; pred && f < d->n_in; f += V) {
        uint32_t last = 0, e = d->n_in - f < V ? d->n_in : f + V;
        for (uint32_t t = f; t < e; t++)
            last = marked(&w, t) ? t + 1u : last;
        bw_plan_t sub = pl;
        sub.dims.n_in = last - f;
        if (last)
            bw_predict(&sub, work + (size_t)f * row, NULL, false);
    }
    for (uint32_t c = 0; c < d->n_in && !pred && pl.step_q8 > BW_STEP_ONE_Q8; c++)
        if (block_needed(&w, c))
            bw_dequant_block(&pl, work, c);
    if (bw_has_in(d)) /* the parents above a needed row, coarse to fine */
        for (unsigned j = 0, L = d->level_in; j < L; j++)
            for (uint32_t p = 0, span = 1u << (2u * (L - j)); p < (4u << (2u * j)); p++)
                if (rows_within(&w, p * span, (p + 1u) * span))
                    bw_biohaar_inv_node(work, L, row, j, p);
    for (uint32_t t = 0; t < d->n_in && !pred; t++)
        if (row_needed(&w, t))
            rebuild_row(&pl, work + (size_t)t * row);
    int32_t *out = samples;
    for (uint32_t t = 0; t < d->n_in; t++) {
        if (!marked(&w, t))
            continue;
        int32_t *x = work + (size_t)t * row;
        if (pl.mirror)
            unmirror_row(&pl, x,
                         bw_has_in(d) && t >= d->n_in / 2u
                             ? work + (size_t)bw_mirror_index(t, d->level_in) * row
                             : NULL);
        put_row(x, row, pred ? 1u : pl.prequant, out); /* prediction: none left */
        out += row;
    }
    return BW_OK;
}

bw_status_t bw_decode_rows(bw_ctx_t *ctx, const uint8_t *payload, size_t len, const uint8_t *rows,
                           int32_t *samples, size_t samples_cap, int32_t *work, size_t work_cap,
                           bw_header_t *hdr_out)
{
    if (!rows)
        return BW_ERR_ARG;
    return decode_rows(ctx, payload, len, rows, 0u, samples, samples_cap, work, work_cap,
                       hdr_out);
}

bw_status_t bw_decode_incoming(bw_ctx_t *ctx, const uint8_t *payload, size_t len, uint32_t in,
                               int32_t *samples, size_t samples_cap, int32_t *work,
                               size_t work_cap, bw_header_t *hdr_out)
{
    return decode_rows(ctx, payload, len, NULL, in, samples, samples_cap, work, work_cap,
                       hdr_out);
}

/* ---- a coarser outgoing level ---------------------------------------------- */

bw_status_t bw_decode_lod(bw_ctx_t *ctx, const uint8_t *payload, size_t len, unsigned level,
                          unsigned level_in, int32_t *samples, size_t samples_cap, int32_t *work,
                          size_t work_cap, bw_header_t *hdr_out)
{
    bw_header_t h;
    bw_status_t st = partial_header(ctx, payload, len, samples, work, &h, hdr_out);
    if (st != BW_OK)
        return st;
    const bw_dims_t *d = &h.dims;
    bool full = bw_has_in(d);
    if (level_in == BW_LEVEL_OWN)
        level_in = d->level_in;
    size_t n = bw_dims_samples(d), b = d->bands, nc = (size_t)4u << (2u * level);
    size_t ni = full ? (size_t)4u << (2u * level_in) : d->n_in;
    if (!bw_has_out(d) || level > d->level_out || level_in > d->level_in ||
        (h.flags & BW_FLAG_RECIPROCAL))
        return BW_ERR_ARG;
    if (samples_cap < ni * nc * b || work_cap < bw_work_bound(n, b))
        return BW_ERR_WORK;
    bw_plan_t pl;
    PLAN_OF(&pl, &h, payload, work, n);
    /* the decoder writes every value of the strips it decodes, which hold
     * all the vectors read below; dequantisation walks every vector */
    if (pl.step_q8 > BW_STEP_ONE_Q8)
        memset(work, 0, n * sizeof *work);
    /* the first 4 4^level vectors of each block in coarse-to-fine order are
     * the coefficients of the outgoing levels above (streamed order: all),
     * the first 4 4^level_in blocks those of the incoming levels above */
    want_t w = {.coarse = pl.stream ? d->n_out : nc, .blocks = full ? ni : 0u};
    st = decode_ranges(&pl, work, payload, &h, &ctx->models, &w);
    if (st != BW_OK)
        return st;
    if (pl.step_q8 > BW_STEP_ONE_Q8)
        bw_quantise(&pl, work, false);
    /* the coarse coefficients into a level's layout: at level L, position
     * t << 2 (L - level) of the same coefficient at `level`, on both
     * hemispheres */
    unsigned sh = 2u * (d->level_out - level), shi = full ? 2u * (d->level_in - level_in) : 0u;
    for (size_t i = 0; i < ni; i++)
        for (size_t t = 0; t < nc; t++)
            memmove(work + (i * nc + t) * b, work + ((i << shi) * d->n_out + (t << sh)) * b,
                    b * sizeof *work);
    bw_dims_t dl = *d;
    dl.level_out = (uint8_t)level;
    dl.n_out = (uint32_t)nc;
    dl.level_in = (uint8_t)level_in;
    dl.n_in = (uint32_t)ni;
    bw_plan_t pc = pl;
    pc.dims = dl;
    pc.n = bw_dims_samples(&dl);
    bw_transform_inv(&pc, work);
    if (pc.mirror)
        bw_symmetry(&pc, work, false);
    put_row(work, pc.n, pl.prequant, samples);
    return BW_OK;
}

bw_status_t bw_decode_level(bw_ctx_t *ctx, const uint8_t *payload, size_t len, unsigned level,
                            int32_t *samples, size_t samples_cap, int32_t *work, size_t work_cap,
                            bw_header_t *hdr_out)
{
    return bw_decode_lod(ctx, payload, len, level, BW_LEVEL_OWN, samples, samples_cap, work,
                         work_cap, hdr_out);
}
