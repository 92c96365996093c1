/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The encoder: one pass at fixed settings (load, symmetry, transform or
 * prediction, quantise, code, header and CRC), the choice of the basis, and
 * the self-check of the mode's guarantee.
 */
#include <string.h>

#include "bw_crc32.h"
#include "bw_internal.h"
#include "bw_le.h"
#include "bw_strip_coder.h"

bw_status_t bw_encode_pass(bw_plan_t *pl, const bw_params_t *pa, unsigned mode,
                           const int32_t *samples, int32_t *work, bw_ctx_t *ctx, uint8_t *out,
                           size_t cap, size_t *len)
{
    bw_status_t st = bw_encode_prepare(pl, samples, work);
    if (st != BW_OK)
        return st;
    if (pl->step_q8 > BW_STEP_ONE_Q8)
        bw_quantise(pl, work, true);
    return bw_encode_code(pl, pa, mode, work, ctx, out, cap, len);
}

bw_status_t bw_encode_prepare(bw_plan_t *pl, const int32_t *samples, int32_t *work)
{
    unsigned done;
    bw_status_t st = bw_load(pl, work, samples, &done);
    if (st == BW_OK && (pl->mirror || pl->recip))
        st = bw_symmetry(pl, work, true);
    if (st != BW_OK)
        return st;
    if (BW_CFG_ENCODE_PRED && pl->basis == BW_BASIS_PRED)
        bw_predict(pl, work, work + pl->n, true);
    else
        bw_transform_fwd(pl, work, done);
    bw_plan_tables(pl);
    return BW_OK;
}

/* BW_CODER_AUTO takes Rice strips at most this share (Q8) of the order-0
 * estimate: on the field spectra and the benchmark's sets of spectra Rice
 * strips come to 0.91-0.93 of it where they are within 2 % of the
 * multi-symbol coder's bytes; 0.95 and more on errors that are mostly zero
 * and on uniform noise, where they are 4 % and more above it */
#define BW_AUTO_RICE_Q8 248u

/* hist[33] by bit length from h[32], counts by clz(2a + 1) (31 - the bit
 * length); returns the sum of the bit lengths. */
static uint64_t bitlen_of_clz(const uint32_t h[32], uint32_t hist[33])
{
    uint64_t sum = 0;
    for (unsigned e = 0; e < 32u; e++) {
        hist[e] = h[31u - e];
        sum += (uint64_t)hist[e] * e;
    }
    hist[32] = 0;
    return sum;
}

/* The bit lengths of the prediction errors x (each below 2^26, n <= 2^32 -
 * 1), of every one, or of every fourth from 4096 on: how many of each into
 * hist[33] (their count *m), and their sum. */
static uint64_t bitlen_hist(const bw_plan_t *pl, const int32_t *x, uint32_t hist[33], size_t *m)
{
    uint32_t h[32] = {0}; /* by clz(2a + 1): 31 - the bit length */
    size_t step = pl->n >= 4096u ? 4u : 1u;
    const int32_t *end = x + pl->n;
    for (const int32_t *p = x; p < end; p += step)
        h[bw_clz32(bw_abs32(*p) << 1 | 1u)]++;
    *m = (pl->n + step - 1u) / step;
    return bitlen_of_clz(h, hist);
}

/* The bits of an order-0 coding of n coefficients of those bit lengths in
 * Q16: each bit length at its frequency, then the bits below the leading
 * one and the sign (as many bits as its length: sum). */
static uint64_t order0_bits(const uint32_t hist[33], size_t n, uint64_t sum)
{
    uint64_t bits = sum << 16;
    uint32_t ln = bw_log2_q16((uint32_t)n);
    for (unsigned e = 0; e < 33u; e++)
        if (hist[e])
            bits += (uint64_t)hist[e] * (ln - bw_log2_q16(hist[e]));
    return bits;
}

/* BW_CODER_AUTO on prediction errors: Rice strips where the errors' bit
 * lengths average at least 7/8 and their payload stays within
 * BW_AUTO_RICE_Q8 / 256 of an order-0 coding of the bit lengths, the bits
 * below the leading one and the signs (which the multi-symbol coder, with
 * its contexts, mostly undercuts): true of errors close to geometric. Both
 * from every fourth error of a large measurement. true: coded so (*st).
 * chosen: the request with BW_CODER_BY_FLAGS. */
static bool auto_rice(const bw_plan_t *pl, bw_params_t *chosen, unsigned mode, int32_t *work,
                      bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len, bw_status_t *st)
{
    if (pl->basis != BW_BASIS_PRED || pl->n > UINT32_MAX)
        return false;
    uint32_t hist[33];
    size_t m;
    uint64_t sum = bitlen_hist(pl, work, hist, &m);
    if (sum * 8u < (uint64_t)m * 7u)
        return false;
    uint64_t est = order0_bits(hist, m, sum) / m * pl->n;
    chosen->flags |= BW_FLAG_RICE;
    *st = bw_encode_code(pl, chosen, mode, work, ctx, out, cap, len);
    chosen->flags &= (uint8_t)~BW_FLAG_RICE;
    return (*st == BW_OK || *st == BW_ERR_OUTPUT_FULL) &&
           ((uint64_t)*len * 8u << 16) * 256u <= est * BW_AUTO_RICE_Q8;
}

#if BW_CFG_CODER_TAB
/* BW_CODER_AUTO on a set of spectra transformed, coded in one body without
 * a rate ahead of the coder: the static-table coder (make bench-device: on
 * its spectra within 3 % of the binary range coder's bytes in less than
 * half the multi-symbol coder's instructions; on directional sets, whose
 * strips of zeros the strip coders code in a bit, 1 to 40 % more bytes),
 * unless its counts put the body below BW_AUTO_TAB_MIN_Q8 / 256 bits a
 * coefficient: there too the strips of zeros win (the Spectralon set within
 * 0.0005: 0.12 bits a sample, the static tables 1.035 x the multi-symbol
 * coder's bytes), and the multi-symbol coder is cheap (the sparsest rows of
 * make bench-device: 0.8 bits a sample and more). */
#define BW_AUTO_TAB_MIN_Q8 128u
static bool auto_tab(const bw_plan_t *pl)
{
#if BW_RATE
    if (pl->rate)
        return false;
#endif
    return pl->dims.shape == BW_SHAPE_SPECTRA && pl->basis < BW_BASIS_COUNT && !pl->stream &&
           !(BW_CFG_SEGMENTS && pl->seg_vec);
}
#endif

#if BW_CFG_EMBED
/* The bytes of every embedded segment coded whole (counted): a byte
 * budget over several cuts each at its share. Out of line, as the next:
 * their iterators stay off the strip coder's stack. */
static BW_NOINLINE size_t embed_total(const bw_plan_t *pl, int32_t *x, bw_models_t *m)
{
    uint32_t segs = bw_plan_segments(pl);
    size_t nv = (size_t)pl->dims.n_in * pl->dims.n_out, total = 0;
    bw_iter_t c;
    bw_iter_init(&c, pl, x);
    for (uint32_t s = 0; s < segs; s++) {
        size_t nvec = nv - (size_t)s * pl->seg_vec;
        nvec = nvec < pl->seg_vec ? nvec : pl->seg_vec;
        bw_iter_segment(&c);
        bw_iter_t start = c;
        bool o;
        total += bw_embed_encode(&start, nvec * pl->dims.bands, NULL, 0, false, m, &o);
        for (size_t k = 0; k < nvec; k++)
            bw_iter_next_vec(&c);
    }
    return total;
}

/* One embedded segment of nvec vectors from *it (left past them) into
 * out[cap]; with a budget over several (total > spare), cut at its share
 * of spare. */
static BW_NOINLINE size_t embed_segment(bw_iter_t *it, size_t nvec, uint8_t *out, size_t cap,
                                        bool truncate, size_t spare, size_t total,
                                        bw_models_t *m, bool *over)
{
    bw_iter_t start = *it;
    size_t n = nvec * it->pl->dims.bands;
    if (total > spare) { /* this segment's share of the budget, its start at least */
        bool o;
        size_t share =
            (size_t)((uint64_t)spare * bw_embed_encode(&start, n, NULL, 0, false, m, &o) / total);
        cap = share < 8u ? (cap < 8u ? cap : 8u) : share < cap ? share : cap;
    }
    size_t sl = bw_embed_encode(&start, n, out, cap, truncate, m, over);
    for (size_t k = 0; k < nvec; k++)
        bw_iter_next_vec(it);
    return sl;
}
#endif

/* A segmented body (docs/FORMAT.md, Segments) at body[cap] (NULL: only
 * counts): the table, then each segment's vectors coded afresh, its length
 * and CRC-32 in the table (the table's own CRC is the caller's, after the
 * header). Returns the body's size; *over: it did not fit cap. */
static size_t code_segments(const bw_plan_t *pl, int32_t *x, bw_strip_enc_t *se, uint8_t *body,
                            size_t cap, unsigned coder, bool truncate, bool *over)
{
    uint32_t segs = bw_plan_segments(pl);
    size_t nv = (size_t)pl->dims.n_in * pl->dims.n_out, pos = bw_segment_table_size(segs);
    bw_iter_t it;
    bw_iter_init(&it, pl, x);
    *over = body && pos > cap;
#if BW_CFG_EMBED
    /* a byte budget over several embedded segments: each cut at its share
     * of the bytes, in proportion to its whole coding (counted first) */
    size_t total = 0, spare = cap > pos ? cap - pos : 0u;
    if (pl->embed && truncate && body && segs > 1u)
        total = embed_total(pl, x, &se->m);
#else
    (void)truncate;
#endif
    for (uint32_t s = 0; s < segs; s++) {
        size_t first = (size_t)s * pl->seg_vec, nvec = nv - first;
        size_t at = pos < cap ? pos : cap;
        if (nvec > pl->seg_vec)
            nvec = pl->seg_vec;
        bw_iter_segment(&it);
        size_t sl;
        bool so = false;
#if BW_CFG_EMBED
        if (pl->embed) {
            sl = embed_segment(&it, nvec, body ? body + at : NULL, cap - at, truncate, spare, total,
                               &se->m, &so);
        } else
#endif
#if BW_CFG_CODER_TAB
            if (coder == BW_CODER_TAB) {
            sl = bw_tab_encode(&it, nvec * pl->dims.bands, &se->m.tab, body ? body + at : NULL,
                               cap - at, 0u, &so);
        } else
#endif
        {
            bw_strip_enc_init(se, body ? body + at : NULL, cap - at, coder);
            bw_code_vectors(&it, se, nvec);
            sl = bw_strip_enc_finish(se);
            so = bw_strip_enc_overflow(se);
        }
        if (body && (so || sl > cap - at)) {
            *over = true;
        } else if (body) {
            bw_put_u32(body + (size_t)s * BW_SEG_ENTRY, (uint32_t)sl);
            bw_put_u32(body + (size_t)s * BW_SEG_ENTRY + 4u, bw_crc32(body + at, sl));
        }
        pos += sl;
    }
    return pos;
}

bw_status_t bw_encode_code(const bw_plan_t *pl, const bw_params_t *pa, unsigned mode,
                           int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len)
{
    bw_params_t chosen;
#if BW_CFG_CODER_TAB
    unsigned tab_min_q8 = 0;
#endif
    if ((BW_CFG_ENCODE_PRED || BW_AUTO_CODER != 0u) && pa->coder == BW_CODER_AUTO) {
        /* (a core without prediction's encoder and the multi-symbol coder
         * codes AUTO with the binary coder: the flags as they are) */
        chosen = *pa;
        chosen.coder = BW_CODER_BY_FLAGS;
        bw_status_t st;
        if (BW_CFG_ENCODE_PRED && auto_rice(pl, &chosen, mode, work, ctx, out, cap, len, &st))
            return st;
        chosen.flags |= (uint8_t)BW_AUTO_CODER;
        pa = &chosen;
#if BW_CFG_CODER_TAB
        if (auto_tab(pl)) {
            chosen.flags |= BW_FLAG_RICE | BW_FLAG_MS;
            tab_min_q8 = BW_AUTO_TAB_MIN_Q8;
        }
#endif
    }
    bw_strip_enc_t *se = &ctx->enc;
    bool counting = out == NULL;
    size_t body_cap = 0, hl = bw_header_write(NULL, pl, pa, mode);
    if (!counting) {
        if (cap < hl + BW_TRAILER_SIZE)
            return BW_ERR_OUTPUT_FULL;
        body_cap = cap - hl - BW_TRAILER_SIZE;
    }
    size_t body;
    bool over;
    if (BW_CFG_SEGMENTS && pl->seg_vec) {
        body = code_segments(pl, work, se, counting ? NULL : out + hl, body_cap,
                             bw_coder_of(pa->flags),
                             BW_CFG_EMBED && pl->embed && mode == BW_MODE_BYTES, &over);
#if BW_CFG_CODER_TAB
    } else if (bw_coder_of(pa->flags) == BW_CODER_TAB) {
        bw_iter_t it;
        bw_iter_init(&it, pl, work);
        body = bw_tab_encode(&it, pl->n, &se->m.tab, counting ? NULL : out + hl, body_cap,
                             tab_min_q8, &over);
        if (body == SIZE_MAX) { /* AUTO, a sparse body: the multi-symbol coder */
            chosen.flags &= (uint8_t)~BW_FLAG_RICE;
            return bw_encode_code(pl, &chosen, mode, work, ctx, out, cap, len);
        }
#endif
    } else {
        bw_strip_enc_init(se, counting ? NULL : out + hl, body_cap, bw_coder_of(pa->flags));
        bw_code_body(pl, work, se);
        body = bw_strip_enc_finish(se);
        over = bw_strip_enc_overflow(se);
    }
    *len = hl + body + BW_TRAILER_SIZE;
    if (counting)
        return BW_OK;
    if (over || *len > UINT32_MAX)
        return BW_ERR_OUTPUT_FULL;
    bw_header_write(out, pl, pa, mode);
    if (BW_CFG_SEGMENTS && pl->seg_vec) { /* the CRC of the header and the segment table */
        size_t t = bw_segment_table_size(bw_plan_segments(pl)) - 4u;
        bw_put_u32(out + hl + t, bw_crc32(out, hl + t));
    }
    bw_put_u32(out + hl + body, bw_crc32(out, hl + body));
    return BW_OK;
}

/* Decodes the payload into verify and checks the mode's guarantee; *sse
 * (may be NULL): the squared error. */
static bw_status_t verify_payload(bw_ctx_t *ctx, const bw_plan_t *pl, const bw_params_t *pa,
                                  uint32_t mode, const int32_t *samples, const uint8_t *out,
                                  size_t len, int32_t *verify, uint64_t *sse)
{
    size_t wb = bw_work_bound(pl->n, pl->dims.bands);
    bw_status_t st = bw_decode_ctx(ctx, out, len, verify, wb, verify, wb, NULL);
    if (st != BW_OK)
        return BW_ERR_VERIFY;
    uint64_t acc = 0;
    for (size_t i = 0; i < pl->n; i++) {
        int64_t diff = (int64_t)verify[i] - samples[i];
        uint64_t ad = (uint64_t)(diff < 0 ? -diff : diff);
        if (mode == BW_MODE_LOSSLESS && ad != 0)
            return BW_ERR_VERIFY;
        if (mode == BW_MODE_MAX_ERROR && ad > pa->max_error)
            return BW_ERR_VERIFY;
        acc += ad * ad;
    }
    if (sse)
        *sse = acc;
    return BW_OK;
}

/* The parameter of the mode for bw_plan_make: E, the step, or (BYTES, whose
 * search sets the step) a step of 1. */
static uint32_t mode_param(const bw_params_t *pa)
{
    return pa->mode == BW_MODE_MAX_ERROR ? pa->max_error
           : pa->mode == BW_MODE_STEP    ? pa->step_q8
                                         : BW_STEP_ONE_Q8;
}

/* The plan of one encode with one basis; the work array holds the
 * coefficients, then the spectral tables (which share their room with the
 * lifting scratch). */
static void plan_for(bw_plan_t *pl, const bw_dims_t *dims, unsigned basis, const bw_params_t *pa,
                     int32_t *work)
{
    int32_t *tables = work + bw_dims_samples(dims);
    bw_plan_make(pl, dims, basis, pa->mode, mode_param(pa), pa->flags, pa->vec_thresh_q8, tables,
                 tables);
    uint32_t nv = dims->n_in * dims->n_out;
    pl->seg_vec = !BW_CFG_SEGMENTS ? 0u : pa->segment_vectors < nv ? pa->segment_vectors : nv;
    /* embedded: in segments, one without them */
    if (BW_CFG_EMBED) {
        /* the current forms: 4 for one band, else 5 */
        pl->embed = !pa->progressive ? 0u : dims->bands == 1u ? 5u : 6u;
        if (pl->embed && !pl->seg_vec)
            pl->seg_vec = nv;
    }
}

/* Encodes with one basis; for BYTES searches the step. */
static bw_status_t encode_basis(bw_ctx_t *ctx, bw_plan_t *pl, const bw_params_t *pa,
                                const int32_t *samples, int32_t *work, uint8_t *out, size_t cap,
                                size_t *len)
{
    if (pa->mode != BW_MODE_BYTES)
        return bw_encode_pass(pl, pa, pa->mode, samples, work, ctx, out, cap, len);
    if (BW_CFG_EMBED && pl->embed) { /* the exact coding cut at the budget */
        size_t b = pa->byte_budget < cap ? pa->byte_budget : cap;
        bw_status_t st = bw_encode_pass(pl, pa, pa->mode, samples, work, ctx, out, b, len);
        return st == BW_ERR_OUTPUT_FULL ? BW_ERR_BUDGET : st;
    }
    if (BW_CFG_FAST_BUDGET && pa->effort == BW_EFFORT_FAST)
        return bw_budget_encode_fast(pl, pa, samples, work, ctx, out, cap, len);
    return bw_budget_encode(pl, pa, samples, work, ctx, out, cap, len);
}

/* The parts of the measurement that a fast BW_BASIS_AUTO codes with every
 * basis: ones that the same transforms code alike, each contiguous in the
 * samples, together about an eighth of the measurement: a block of whole
 * spectra (of 16 or more; or of one long spectrum's bands), a block of
 * incoming directions (of 16 or more), or two outgoing subtrees two levels
 * below the base triangles (hemispheres two levels coarser: the centre ones
 * of bases 0 and 2). Returns how many (their offsets in first[]); 0: too
 * small to take a part of, every basis codes the whole. */
static unsigned quick_parts(const bw_dims_t *d, bw_dims_t *part, size_t first[2])
{
    uint32_t bands = d->bands;
    *part = *d;
    if (d->shape == BW_SHAPE_SPECTRA) {
        if (d->n_in >= 16u) {
            part->n_in = (d->n_in + 7u) / 8u;
            first[0] = (size_t)((d->n_in - part->n_in) / 2u) * bands;
            return 1u;
        }
        if (d->n_in > 1u || bands < 512u)
            return 0u; /* a few spectra: the spectrum before counts */
        /* one long spectrum: the middle eighth of its bands */
        part->bands = bands / 8u;
        first[0] = (bands - part->bands) / 2u;
        return 1u;
    }
    if (d->shape != BW_SHAPE_REFLECTANCE && d->n_in >= 16u) {
        part->shape = BW_SHAPE_BRDF_ISO;
        part->level_in = 0u;
        part->n_in = d->n_in / 8u;
        first[0] = (size_t)((d->n_in - part->n_in) / 2u) * d->n_out * bands;
        return 1u;
    }
    if (d->level_out < 2u)
        return 0u;
    /* of the middle incoming direction */
    uint32_t leaves = d->n_out / 16u;
    part->shape = BW_SHAPE_REFLECTANCE;
    part->level_out = (uint8_t)(d->level_out - 2u);
    part->level_in = 0u;
    part->n_in = 1u;
    part->n_out = leaves;
    first[0] = (size_t)(d->n_in / 2u) * d->n_out * bands;
    first[1] = first[0] + (size_t)8u * leaves * bands;
    return 2u;
}

/* The bits (Q16) of an order-0 coding of the coefficients x of the plan in
 * each spectral subband on its own (order0_bits: the bit lengths at their
 * frequencies, the bits below the leading one and the signs): what ranks
 * the transform bases for a fast BW_BASIS_AUTO without coding them. */
static uint64_t subband_bits(const bw_plan_t *pl, const int32_t *x)
{
    spec_bands_t sb;
    bw_spec_bands(pl, &sb);
    uint32_t b = pl->dims.bands;
    const int32_t *end = x + pl->n;
    uint64_t bits = 0;
    for (unsigned s = 0; s < sb.count; s++) {
        uint32_t h[32] = {0}, hist[33]; /* h by clz(2a + 1): 31 - the bit length */
        for (const int32_t *v = x; v < end; v += b)
            for (uint32_t k = sb.lo[s]; k < sb.lo[s + 1u]; k++)
                h[bw_clz32(bw_abs32(v[k]) << 1 | 1u)]++;
        uint64_t sum = bitlen_of_clz(h, hist);
        size_t m = (size_t)(pl->n / b) * (sb.lo[s + 1u] - sb.lo[s]);
        if (m)
            bits += order0_bits(hist, m, sum);
    }
    return bits;
}

/* The transform basis first..last whose coefficients of the parts (at
 * at[parts] in samples, each of dims part) subband_bits finds smallest;
 * BW_BASIS_COUNT: none. Out of line: its frame stays off the encodes'. */
static BW_NOINLINE unsigned quick_wave(const bw_dims_t *part, const bw_params_t *pq,
                                       const int32_t *samples, const size_t *at, unsigned parts,
                                       int32_t *work, unsigned first, unsigned last)
{
    uint64_t least = UINT64_MAX;
    unsigned wave = BW_BASIS_COUNT;
    for (unsigned b = first; b <= last; b++) {
        bw_plan_t pl;
        uint64_t bits = 0;
        if (bw_params_check(part, pq->mode, b, pq->flags, mode_param(pq), BW_FOR_ENCODE) != BW_OK)
            continue;
        unsigned k;
        for (k = 0; k < parts; k++) {
            plan_for(&pl, part, b, pq, work);
            if (bw_encode_prepare(&pl, samples + at[k], work) != BW_OK)
                break;
            if (pl.step_q8 > BW_STEP_ONE_Q8)
                bw_quantise(&pl, work, true);
            bits += subband_bits(&pl, work);
        }
        if (k == parts && bits < least) {
            least = bits;
            wave = b;
        }
    }
    return wave;
}

/* A fast BW_BASIS_AUTO: the basis first..last that codes the parts smallest
 * (lossless for a byte budget). The transform bases are ranked by
 * subband_bits and the first of them coded, with prediction where it
 * applies; every basis is coded where the measurement has no spectral
 * transform. false: no parts, or no basis codes them. */
static bool quick_choice(bw_ctx_t *ctx, const bw_dims_t *dims, const bw_params_t *pa,
                         const int32_t *samples, int32_t *work, unsigned first, unsigned last,
                         unsigned *best)
{
    bw_dims_t part;
    size_t at[2], best_sz = SIZE_MAX;
    unsigned parts = quick_parts(dims, &part, at);
    if (parts == 0u)
        return false;
    bw_params_t pq = *pa;
    pq.flags &= (uint8_t) ~(BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL);
    pq.ext = NULL;
    pq.ext_len = 0;
    if (pq.mode == BW_MODE_BYTES) {
        pq.mode = BW_MODE_LOSSLESS;
        /* a byte budget met in one encode (BW_RATE): half the parts, so
         * that the choice stays a small share of the whole */
        if (BW_RATE && parts == 2u)
            parts = 1u;
        else if (BW_RATE && part.n_in >= 2u)
            part.n_in /= 2u;
    }
    /* the transform bases by their estimate: the smallest stays to be coded
     * (all alike without a spectral transform: the first) */
    unsigned wave = BW_BASIS_COUNT;
    if (first < BW_BASIS_COUNT && bw_spec_levels(part.bands) == 0u)
        wave = first;
    else if (first < BW_BASIS_COUNT) {
        wave = quick_wave(&part, &pq, samples, at, parts, work, first,
                          last < BW_BASIS_COUNT ? last : BW_BASIS_COUNT - 1u);
        if (wave < BW_BASIS_COUNT && last < BW_BASIS_COUNT) {
            *best = wave; /* transform bases alone: no need to code one */
            return true;
        }
    }
    for (unsigned b = first; b <= last; b++) {
        bw_plan_t pl;
        size_t sz, total = 0;
        if (wave < BW_BASIS_COUNT && b < BW_BASIS_COUNT && b != wave)
            continue;
        if (bw_params_check(&part, pq.mode, b, pq.flags, mode_param(&pq), BW_FOR_ENCODE) != BW_OK)
            continue;
        unsigned k;
        for (k = 0; k < parts; k++) {
            plan_for(&pl, &part, b, &pq, work);
            if (bw_encode_pass(&pl, &pq, pq.mode, samples + at[k], work, ctx, NULL, 0, &sz) !=
                BW_OK)
                break;
            total += sz;
        }
        if (k == parts && total < best_sz) {
            best_sz = total;
            *best = b;
        }
    }
    return best_sz != SIZE_MAX;
}

#if BW_CFG_BANDS
/* A set of spectra with band access: prediction along the bands, coded by
 * columns (bw_bands.c); then the self-check. */
static BW_NOINLINE bw_status_t encode_bands(bw_ctx_t *ctx, const bw_dims_t *dims, const bw_params_t *pa,
                                const int32_t *samples, int32_t *work, int32_t *verify,
                                uint8_t *out, size_t out_cap, size_t *out_len)
{
    if (!ctx || !dims || !samples || !work || !out || !out_len)
        return BW_ERR_ARG;
    *out_len = 0;
    bw_status_t st = bw_params_check(dims, pa->mode, BW_BASIS_PRED, pa->flags, mode_param(pa),
                                     BW_FOR_ENCODE);
    if (st != BW_OK)
        return st;
    if (!bw_ext_valid(pa->ext, pa->ext_len) || pa->effort > BW_EFFORT_FAST ||
        dims->shape != BW_SHAPE_SPECTRA ||
        (pa->mode != BW_MODE_LOSSLESS && pa->mode != BW_MODE_MAX_ERROR) ||
        (pa->basis != BW_BASIS_PRED && pa->basis != BW_BASIS_AUTO) || pa->segment_vectors ||
        pa->progressive || pa->coder != BW_CODER_BY_FLAGS ||
        (pa->flags & (BW_FLAG_RICE | BW_FLAG_MS | BW_FLAG_STREAM_ORDER)))
        return BW_ERR_ARG;
    bw_plan_t pl;
    plan_for(&pl, dims, BW_BASIS_PRED, pa, work);
    pl.bands = true;
    st = bw_bands_encode(&pl, pa, samples, work, out, out_cap, out_len);
    if (st != BW_OK || !verify)
        return st;
    /* the self-check: every sample back, exactly or within E (not through
     * verify_payload: a second caller takes it out of line, which costs
     * bw_encode_ctx's stack, or, inlined twice, the device core's bytes) */
    size_t wb = bw_work_bound(pl.n, dims->bands);
    if (bw_decode_ctx(ctx, out, *out_len, verify, wb, verify, wb, NULL) != BW_OK)
        return BW_ERR_VERIFY;
    for (size_t i = 0; i < pl.n; i++) {
        int64_t e = (int64_t)verify[i] - samples[i];
        if (e > (int64_t)pa->max_error || -e > (int64_t)pa->max_error)
            return BW_ERR_VERIFY;
    }
    return BW_OK;
}
#endif

bw_status_t bw_encode_ctx(bw_ctx_t *ctx, const bw_dims_t *dims, const bw_params_t *pa,
                          const int32_t *samples, int32_t *work, int32_t *verify, uint8_t *out,
                          size_t out_cap, size_t *out_len)
{
#if BW_CFG_BANDS
    if (pa && pa->band_access) /* (first: a call in the caller's frame) */
        return encode_bands(ctx, dims, pa, samples, work, verify, out, out_cap, out_len);
#endif
    if (!ctx || !dims || !pa || !samples || !work || !out || !out_len)
        return BW_ERR_ARG;
    *out_len = 0;
    bw_status_t st = bw_params_check(dims, pa->mode, pa->basis, pa->flags, mode_param(pa),
                                     BW_FOR_ENCODE);
    if (st != BW_OK)
        return st;
    if (!bw_ext_valid(pa->ext, pa->ext_len) || pa->effort > BW_EFFORT_FAST ||
        !bw_coder_choice_ok(pa))
        return BW_ERR_ARG;
    if ((!BW_CFG_SEGMENTS && pa->segment_vectors) || (!BW_CFG_EMBED && pa->progressive) ||
        (!BW_CFG_BANDS && pa->band_access))
        return BW_ERR_NOT_BUILT;
    /* embedded: transform bases, coarse-to-fine order, the embedded coder */
    if (BW_CFG_EMBED && pa->progressive &&
        (pa->basis == BW_BASIS_PRED || (pa->flags & BW_FLAG_STREAM_ORDER) ||
         bw_coder_of(pa->flags) == BW_CODER_TAB))
        return BW_ERR_ARG;
    bool pred = BW_CFG_ENCODE_PRED && !(BW_CFG_EMBED && pa->progressive) &&
                bw_pred_applies(dims, pa->mode, pa->flags);

    bw_plan_t pl;
    bw_status_t fit = BW_OK;
    unsigned first = pa->basis, last = pa->basis;
    if (pa->basis == BW_BASIS_AUTO) {
        first = 0;
        last = pred ? BW_BASIS_PRED : BW_BASIS_COUNT - 1u;
    }
    /* no spectral transform: every transform basis codes alike */
    bool one_transform = bw_spec_levels(dims->bands) == 0u;
    if (one_transform && last < BW_BASIS_COUNT)
        last = first;
    unsigned best = first;
    if (BW_CFG_FAST_BASIS && first != last && pa->effort == BW_EFFORT_FAST &&
        quick_choice(ctx, dims, pa, samples, work, first, last, &best))
        first = last = best;
    if (first != last) {
        /* keep the smallest payload, or for BYTES the smallest error (the
         * smallest step when there is no room to decode) */
        uint64_t best_score = UINT64_MAX;
        size_t best_sz = 0;
        for (unsigned b = first; b <= last; b++) {
            size_t sz;
            if (one_transform && b != first && b < BW_BASIS_COUNT)
                continue;
            plan_for(&pl, dims, b, pa, work);
            st = encode_basis(ctx, &pl, pa, samples, work, pa->mode == BW_MODE_BYTES ? out : NULL,
                              out_cap, &sz);
            if (st == BW_ERR_BUDGET) { /* another basis may still fit */
                fit = st;
                continue;
            }
            if (st != BW_OK)
                return st;
            uint64_t score = sz;
            if (pa->mode == BW_MODE_BYTES) {
                score = pl.step_q8;
                if (verify && verify_payload(ctx, &pl, pa, BW_MODE_BYTES, samples, out, sz, verify,
                                             &score) != BW_OK)
                    return BW_ERR_VERIFY;
            }
            /* a byte budget: the smallest error, then the smallest payload
             * (several bases may code the data exactly) */
            if (score < best_score || (score == best_score && sz < best_sz)) {
                best_score = score;
                best_sz = sz;
                best = b;
            }
        }
        if (best_score == UINT64_MAX)
            return fit; /* no basis fits the budget */
    }
    plan_for(&pl, dims, best, pa, work);
    st = encode_basis(ctx, &pl, pa, samples, work, out, out_cap, out_len);
    if (st != BW_OK)
        return st;
    if (verify)
        return verify_payload(ctx, &pl, pa, pa->mode, samples, out, *out_len, verify, NULL);
    return BW_OK;
}

bw_status_t bw_encode(const bw_dims_t *dims, const bw_params_t *pa, const int32_t *samples,
                      int32_t *work, int32_t *verify, uint8_t *out, size_t out_cap,
                      size_t *out_len)
{
    bw_ctx_t ctx;
    return bw_encode_ctx(&ctx, dims, pa, samples, work, verify, out, out_cap, out_len);
}
