/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The streaming encoder: spectra as they arrive, each transformed on
 * arrival, the Bio-Haar lifting run up the triangle tree as soon as four
 * siblings are complete, and every completed vector quantised and coded at
 * once, in stream order (docs/FORMAT.md, Body). The payload is bw_encode's
 * with BW_FLAG_STREAM_ORDER.
 *
 * The caller's memory (BW_STREAM_MEM_BOUND int32): the spectral tables
 * (2 * bands), the lifting scratch (bands), then 4 pending vectors per level
 * (4 * (level + 1) * bands).
 */
#include <string.h>

#include "bw_crc32.h"
#include "bw_geodesic.h"
#include "bw_internal.h"
#include "bw_le.h"
#include "bw_strip_coder.h"

static void stream_plan(const bw_stream_t *s, bw_plan_t *pl)
{
    const bw_params_t *pa = &s->params;
    size_t b = s->dims.bands;
    bw_plan_make(pl, &s->dims, pa->basis, pa->mode,
                 pa->mode == BW_MODE_MAX_ERROR ? pa->max_error : pa->step_q8, pa->flags,
                 pa->vec_thresh_q8, s->mem, s->mem + 2u * b);
    if (BW_CFG_SEGMENTS)
        pl->seg_vec = pa->segment_vectors;
}

/* The body's start: after the header and, with segments, their table. */
static size_t body_at(const bw_plan_t *pl, size_t hl)
{
    return hl + (BW_CFG_SEGMENTS && pl->seg_vec ? bw_segment_table_size(bw_plan_segments(pl)) : 0u);
}

/* The strip coder from byte `at` of the body on (the table's room kept). */
static void coder_at(bw_stream_t *s, size_t hl, size_t at)
{
    size_t room = s->cap - hl - BW_TRAILER_SIZE;
    bw_strip_enc_init(&s->se, s->out + hl + (at < room ? at : room), at < room ? room - at : 0u,
                      bw_coder_of(s->params.flags));
}

/* Ends the segment being coded: its length and CRC into the table. */
static void segment_end(bw_stream_t *s)
{
    size_t hl = s->hl, len = bw_strip_enc_finish(&s->se), room = s->cap - hl - BW_TRAILER_SIZE;
    uint8_t *e = s->out + hl + (size_t)s->seg * BW_SEG_ENTRY;
    if (bw_strip_enc_overflow(&s->se) || s->seg_at + len > room) {
        s->err = BW_ERR_OUTPUT_FULL;
        return;
    }
    bw_put_u32(e, (uint32_t)len);
    bw_put_u32(e + 4u, bw_crc32(s->out + hl + s->seg_at, len));
    s->seg_at += len;
    s->seg++;
}

static int32_t *pend_slot(const bw_stream_t *s, unsigned level, unsigned slot)
{
    return s->mem + (3u + (size_t)level * 4u + slot) * s->dims.bands;
}

bw_status_t bw_stream_init(bw_stream_t *s, const bw_dims_t *dims, const bw_params_t *pa,
                           int32_t *mem, size_t mem_len, uint8_t *out, size_t cap)
{
    if (!s || !dims || !pa || !mem || !out)
        return BW_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->err = BW_ERR_ARG;
    bw_status_t st = bw_params_check(dims, pa->mode, pa->basis, pa->flags,
                                     pa->mode == BW_MODE_MAX_ERROR ? pa->max_error : pa->step_q8,
                                     BW_FOR_STREAM);
    if (st != BW_OK)
        return st;
    if (!bw_ext_valid(pa->ext, pa->ext_len) || !bw_coder_choice_ok(pa))
        return BW_ERR_ARG; /* the records are read again at bw_stream_finish */
    if (!BW_CFG_SEGMENTS && pa->segment_vectors)
        return BW_ERR_NOT_BUILT;
    if (mem_len < bw_stream_mem_bound(dims->level_out, dims->bands))
        return BW_ERR_WORK;
    s->dims = *dims;
    s->params = *pa;
    s->params.flags |= BW_FLAG_STREAM_ORDER;
    if (BW_CFG_SEGMENTS && s->params.segment_vectors > dims->n_in * dims->n_out)
        s->params.segment_vectors = dims->n_in * dims->n_out;
    s->mem = mem;
    bw_plan_t pl;
    stream_plan(s, &pl);
    if (BW_AUTO_CODER != 0u && pa->coder == BW_CODER_AUTO) { /* no prediction in stream order */
        s->params.flags |= (uint8_t)BW_AUTO_CODER;
        s->params.coder = BW_CODER_BY_FLAGS;
    }
    bw_plan_tables(&pl);
    size_t hl = bw_header_write(NULL, &pl, &s->params, s->params.mode);
    if (cap < body_at(&pl, hl) + BW_TRAILER_SIZE)
        return BW_ERR_OUTPUT_FULL;
    s->out = out;
    s->cap = cap;
    s->seg_at = body_at(&pl, hl) - hl;
    if (BW_CFG_SEGMENTS)
        s->hl = hl;
    coder_at(s, hl, s->seg_at);
    s->err = BW_OK;
    return BW_OK;
}

/* Quantises (as bw_quantise does) and codes one completed vector whose
 * parent level is j (-1: scaling); stream order has no directional parent
 * and no previous vector. */
static void stream_emit(bw_stream_t *s, const bw_plan_t *pl, int32_t *v, int j)
{
    if (BW_CFG_SEGMENTS && pl->seg_vec && s->emitted && s->emitted % pl->seg_vec == 0u) {
        /* the next segment: a coder of its own */
        segment_end(s);
        coder_at(s, s->hl, s->seg_at);
    }
    s->emitted++;
    bw_quant_vector(pl, v, j);
    bw_strip_put_vector(&s->se, v, s->dims.bands, pl->spec_cls, bw_level_cls(pl, j), NULL, NULL);
}

bw_status_t bw_stream_push(bw_stream_t *s, const int32_t *spectrum)
{
    if (!s || !spectrum)
        return BW_ERR_ARG;
    if (s->err != BW_OK)
        return s->err;
    const bw_dims_t *d = &s->dims;
    if (s->pushed >= (size_t)d->n_in * d->n_out)
        return s->err = BW_ERR_ARG; /* more spectra than the shape holds */
    uint32_t b = d->bands;
    unsigned L = d->level_out;
    bw_plan_t pl;
    stream_plan(s, &pl);
    unsigned lv = bw_has_out(d) ? L : 0u;
    int32_t *v = pend_slot(s, lv, s->pend_n[lv]);
    unsigned done;
    bw_status_t st = bw_load_spectrum(&pl, v, spectrum, &done);
    if (st != BW_OK)
        return s->err = st;
    if (pl.spec_levels > done)
        bw_spec_fwd(v, bw_spec_approx_len(b, done), pl.basis, pl.spec_levels - done, pl.tmp);
    s->pushed++;
    if (!bw_has_out(d)) {
        stream_emit(s, &pl, v, -1);
        return BW_OK;
    }
    /* up the tree while four siblings are complete */
    s->pend_n[L]++;
    uint32_t t = s->leaf;
    for (unsigned j = L; j > 0u && s->pend_n[j] == 4u; j--) {
        unsigned k = L - j + 1u; /* the parent is t >> 2k at level j - 1 */
        uint32_t p = t >> (2u * k);
        uint32_t per_base = 1u << (2u * (j - 1u));
        uint16_t w[3];
        bw_geo_weights(j - 1u, p & (per_base - 1u), w);
        bw_biohaar_lift4(pend_slot(s, j, 0), pend_slot(s, j, 1), pend_slot(s, j, 2),
                         pend_slot(s, j, 3), w, b);
        for (unsigned m = 1; m <= 3u; m++)
            stream_emit(s, &pl, pend_slot(s, j, m), (int)j - 1);
        /* the parent's scaling vector moves up a level */
        memcpy(pend_slot(s, j - 1u, s->pend_n[j - 1u]), pend_slot(s, j, 0), (size_t)b * sizeof *v);
        s->pend_n[j - 1u]++;
        s->pend_n[j] = 0;
    }
    if (s->pend_n[0] == 1u) { /* a base triangle is complete */
        stream_emit(s, &pl, pend_slot(s, 0, 0), -1);
        s->pend_n[0] = 0;
    }
    if (++s->leaf == d->n_out)
        s->leaf = 0;
    return BW_OK;
}

bw_status_t bw_stream_finish(bw_stream_t *s, size_t *len)
{
    if (!s || !len)
        return BW_ERR_ARG;
    *len = 0;
    if (s->err != BW_OK)
        return s->err;
    if (s->pushed != (size_t)s->dims.n_in * s->dims.n_out)
        return s->err = BW_ERR_ARG; /* fewer spectra than the shape holds */
    bw_plan_t pl;
    stream_plan(s, &pl);
    size_t body;
    if (BW_CFG_SEGMENTS && pl.seg_vec) {
        segment_end(s);
        if (s->err != BW_OK)
            return s->err;
        body = s->seg_at;
    } else {
        body = bw_strip_enc_finish(&s->se);
    }
    /* the header's room was kept at init */
    size_t hl = bw_header_write(s->out, &pl, &s->params, s->params.mode);
    if (bw_strip_enc_overflow(&s->se) || hl + body + BW_TRAILER_SIZE > UINT32_MAX)
        return s->err = BW_ERR_OUTPUT_FULL;
    if (BW_CFG_SEGMENTS && pl.seg_vec) { /* the CRC of the header and the table */
        size_t t = bw_segment_table_size(bw_plan_segments(&pl)) - 4u;
        bw_put_u32(s->out + hl + t, bw_crc32(s->out, hl + t));
    }
    bw_put_u32(s->out + hl + body, bw_crc32(s->out, hl + body));
    *len = hl + body + BW_TRAILER_SIZE;
    s->err = BW_ERR_ARG; /* finished: no more pushes */
    return BW_OK;
}
