/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The payload header (docs/FORMAT.md, Header): written from a plan, read
 * and validated field by field, and the CRC-32 trailer checked.
 */
#include <string.h>

#include "bw_crc32.h"
#include "bw_internal.h"
#include "bw_le.h"

#define SCALE_ONE_BITS 0x3F800000u /* 1.0f: the default scale, not stored */
#define H_SCALE 0x40u              /* byte 3: a scale field follows          */
#define H_OFFSET 0x80u             /* byte 3: an offset field follows        */

/* Reads a LEB128 value of at most 32 bits at q, before end, in its shortest
 * form only (every encoding is then unique); returns the next byte, or NULL. */
static const uint8_t *get_varint(const uint8_t *q, const uint8_t *end, uint32_t *v)
{
    uint32_t x = 0;
    for (unsigned sh = 0; q < end && sh < 35u; sh += 7u) {
        uint32_t b = *q++;
        if (sh == 28u && b > 0x0Fu)
            return NULL; /* beyond 32 bits */
        x |= (b & 0x7Fu) << sh;
        if (!(b & 0x80u)) {
            *v = x;
            return sh && !b ? NULL : q; /* NULL: not the shortest form */
        }
    }
    return NULL;
}

/* Writes v as a LEB128 varint at q; returns its length. */
static size_t put_varint(uint8_t *q, uint32_t v)
{
    size_t n = 0;
    for (;; v >>= 7) {
        q[n++] = (uint8_t)(v | (v > 0x7Fu ? 0x80u : 0u));
        if (v <= 0x7Fu)
            return n;
    }
}

/* The header's numbers: n_in, bands, the mode's parameter (E, or the step
 * above 1), then the scale and offset bits, stored when they differ from
 * 1.0f and 0. */
enum { HV_N_IN, HV_BANDS, HV_PARAM, HV_SCALE, HV_OFFSET, HV_COUNT };

size_t bw_header_write(uint8_t *out, const bw_plan_t *pl, const bw_params_t *pa, unsigned mode)
{
    uint8_t tmp[BW_HEADER_MAX], *h = out ? out : tmp;
    uint32_t v[HV_COUNT] = {pl->dims.n_in, pl->dims.bands,
                            mode == BW_MODE_MAX_ERROR ? pa->max_error
                                                      : pl->step_q8 - BW_STEP_ONE_Q8,
                            pa->scale_bits, pa->offset_bits};
    uint32_t b3 = pl->dims.shape | mode << 2 | pl->basis << 4;
    size_t n = BW_HEADER_FIXED;
    for (unsigned k = 0; k < HV_COUNT; k++) {
        if (k < HV_SCALE) {
            if (k != HV_PARAM || mode != BW_MODE_LOSSLESS)
                n += put_varint(h + n, v[k]);
        } else if (v[k] != (k == HV_SCALE ? SCALE_ONE_BITS : 0u)) {
            b3 |= H_SCALE << (k - HV_SCALE);
            bw_put_u32(h + n, v[k]);
            n += 4u;
        }
    }
    h[0] = BW_MAGIC0;
    h[1] = BW_MAGIC1;
    /* the segments' record after the caller's: type, length, V (or band
     * access's) */
    uint8_t seg[10];
    size_t sl = 0;
    if (BW_CFG_SEGMENTS && pl->seg_vec) {
        seg[0] = BW_EXT_SEGMENTS;
        sl = put_varint(seg + 2, pl->seg_vec);
        seg[1] = (uint8_t)sl;
        sl += 2u;
        if (BW_CFG_EMBED && pl->embed) { /* and its segments embedded: the form */
            seg[sl++] = BW_EXT_EMBEDDED;
            seg[sl++] = 1u;
            seg[sl++] = (uint8_t)(pl->embed - 1u);
        }
    }
    if (BW_CFG_BANDS && pl->bands) { /* band access: no data */
        seg[sl++] = BW_EXT_BANDS;
        seg[sl++] = 0u;
    }
    /* then the chunks' steps: type, length, K, a byte per chunk */
    size_t cl = 0, cn = 0;
#if BW_CFG_CHUNK_STEPS
    uint8_t ck[12];
    if (pl->chunk_vec) {
        uint32_t nvec = pl->dims.n_in * pl->dims.n_out;
        cn = (nvec - 1u) / pl->chunk_vec + 1u;
        size_t kl = put_varint(ck + 6, pl->chunk_vec);
        ck[0] = BW_EXT_CHUNK_STEPS;
        cl = 1u + put_varint(ck + 1, (uint32_t)(kl + cn));
        memmove(ck + cl, ck + 6, kl);
        cl += kl;
    }
#endif
    uint32_t el = pa->ext_len + (uint32_t)(sl + cl + cn);
    h[2] = el || (pa->flags & BW_FLAG_MS) ? BW_VERSION_EXT : BW_VERSION;
    h[3] = (uint8_t)b3;
    h[4] = (uint8_t)(pl->dims.level_out | pl->dims.level_in << 4);
    h[5] = (uint8_t)((pa->flags & BW_FLAGS_KNOWN) | (el ? BW_FLAG_EXT : 0u));
    h[6] = (uint8_t)pl->spec_levels;
    if (el) {
        /* the records' length, then the records (bw_ext_valid checked them) */
        uint8_t len_field[5];
        size_t k = put_varint(len_field, el);
        if (out) {
            memcpy(out + n, len_field, k);
            if (pa->ext_len)
                memcpy(out + n + k, pa->ext, pa->ext_len);
            memcpy(out + n + k + pa->ext_len, seg, sl);
#if BW_CFG_CHUNK_STEPS
            if (cl) {
                memcpy(out + n + k + pa->ext_len + sl, ck, cl);
                memcpy(out + n + k + pa->ext_len + sl + cl, pl->chunk_d, cn);
            }
#endif
        }
        n += k + el;
    }
    return n;
}

bool bw_ext_next(const uint8_t *area, size_t len, size_t *pos, uint8_t *type,
                 const uint8_t **data, uint32_t *data_len)
{
    if (!area || *pos >= len)
        return false;
    const uint8_t *q = area + *pos, *end = area + len;
    uint32_t l;
    *type = *q++;
    q = get_varint(q, end, &l);
    if (!q || l > (size_t)(end - q))
        return false;
    *data = q;
    *data_len = l;
    *pos = (size_t)(q + l - area);
    return true;
}

/* The bytes BW_EXT_FLOAT_EXACT sets apart at the body's end (its first
 * field; 0 without it), or BW_ERR_HEADER for a malformed record,
 * BW_ERR_EXTENSION for a critical type this decoder does not know; the
 * core's own records into h, and BW_EXT_CHUNK_STEPS's K and count of
 * steps into chunk[0] and chunk[1] (0 and 0 without it). */
static int32_t ext_scan(const uint8_t *area, size_t len, bw_header_t *h, uint32_t chunk[2])
{
    size_t pos = 0;
    uint8_t type;
    const uint8_t *d;
    uint32_t dl, tail = 0;
    int32_t st = 0;
    h->segment_vectors = 0;
    if (BW_CFG_BANDS)
        h->band_access = 0;
    if (BW_CFG_EMBED)
        h->embedded = 0;
#if BW_CFG_CHUNK_STEPS
    chunk[0] = chunk[1] = 0;
#else
    (void)chunk;
#endif
    while (pos < len) {
        if (!bw_ext_next(area, len, &pos, &type, &d, &dl) ||
            (type == BW_EXT_FLOAT_EXACT && (!get_varint(d, d + dl, &tail) || tail > INT32_MAX)))
            return BW_ERR_HEADER;
        if ((type == BW_EXT_SEGMENTS && !BW_CFG_SEGMENTS) ||
            (type == BW_EXT_CHUNK_STEPS && !BW_CFG_CHUNK_STEPS)) {
            st = BW_ERR_NOT_BUILT;
        } else if (type == BW_EXT_SEGMENTS) {
            /* one record, its data one varint V >= 1 */
            if (h->segment_vectors || get_varint(d, d + dl, &h->segment_vectors) != d + dl ||
                !h->segment_vectors)
                return BW_ERR_HEADER;
        } else if (BW_CFG_BANDS && type == BW_EXT_BANDS) {
            /* one record, no data */
            if (h->band_access || dl)
                return BW_ERR_HEADER;
            h->band_access = 1u;
        } else if (type == BW_EXT_EMBEDDED && !BW_CFG_EMBED) {
            st = BW_ERR_NOT_BUILT;
        } else if (type == BW_EXT_EMBEDDED) {
            /* one record after the segments': no data (form 0, the first),
             * or the form, one byte (1: with groups of strips, 2: and the
             * incoming parent block as a neighbour, 3: and each pass
             * significance first, 4: in three parts, 5: as 3 subband by
             * subband) */
            if (h->embedded || dl > 1u || (dl && d[0] > 5u) || !h->segment_vectors)
                return BW_ERR_HEADER;
            h->embedded = 1u + (dl ? d[0] : 0u);
#if BW_CFG_CHUNK_STEPS
        } else if (type == BW_EXT_CHUNK_STEPS) {
            /* one record: a varint K >= 1, then the chunks' steps (their
             * count is checked against the dimensions by the caller) */
            const uint8_t *q = chunk[0] ? NULL : get_varint(d, d + dl, &chunk[0]);
            if (!q || !chunk[0])
                return BW_ERR_HEADER;
            chunk[1] = (uint32_t)(d + dl - q);
#endif
        } else if (type < BW_EXT_ANCILLARY && (uint8_t)(type - BW_EXT_FLOAT_EXACT) > 1u) {
            st = BW_ERR_EXTENSION;
        }
    }
    return st < 0 ? st : (int32_t)tail;
}

#if BW_CFG_CHUNK_STEPS
uint32_t bw_chunk_steps(const uint8_t *p, const bw_header_t *h, const int8_t **steps)
{
    size_t pos = 0;
    uint8_t type;
    const uint8_t *d;
    uint32_t dl, K = 0;
    if (!(h->flags & BW_FLAG_EXT)) /* (a header's ext fields are only set with records) */
        return 0;
    while (bw_ext_next(p + h->ext_off, h->ext_len, &pos, &type, &d, &dl)) {
        const uint8_t *q = type == BW_EXT_CHUNK_STEPS ? get_varint(d, d + dl, &K) : NULL;
        if (q) {
            *steps = (const int8_t *)q;
            return K;
        }
    }
    return 0;
}
#endif

/* the encoder writes records without a tail (it codes no bytes past the
 * body) and without segments or chunk steps (its own records say those) */
bool bw_ext_valid(const uint8_t *area, size_t len)
{
    bw_header_t h;
    uint32_t chunk[2] = {0, 0};
    return len <= BW_EXT_MAX && (!len || area) && ext_scan(area, len, &h, chunk) == 0 &&
           !h.segment_vectors && !(BW_CFG_BANDS && h.band_access) &&
           !(BW_CFG_CHUNK_STEPS && chunk[0]);
}

bw_status_t bw_header_read(const uint8_t *p, size_t len, bw_header_t *h)
{
    if (!p || !h)
        return BW_ERR_ARG;
    memset(h, 0, sizeof *h);
    /* a wrong magic or version, or too short for a header, comes first;
     * then the CRC; then the fields the CRC vouches for */
    bw_status_t st = bw_header_parse_fields(p, len, h);
    if (st == BW_ERR_MAGIC || st == BW_ERR_VERSION || st == BW_ERR_TRUNCATED)
        return st;
    h->crc = bw_get_u32(p + len - BW_TRAILER_SIZE);
    if (bw_crc32(p, len - BW_TRAILER_SIZE) != h->crc)
        return BW_ERR_CRC;
    return st;
}

/* The fields; with cut, a tail (record 0x01) longer than what follows the
 * header is cut to it. */
static bw_status_t parse_fields(const uint8_t *p, size_t len, bw_header_t *h, bool cut)
{
    if (len >= 2u && (p[0] != BW_MAGIC0 || p[1] != BW_MAGIC1))
        return BW_ERR_MAGIC;
    if (len >= 3u && p[2] != BW_VERSION && p[2] != BW_VERSION_EXT)
        return BW_ERR_VERSION;
    if (len < BW_HEADER_FIXED + BW_TRAILER_SIZE)
        return BW_ERR_TRUNCATED;
    const uint8_t *q = p + BW_HEADER_FIXED, *end = p + len - BW_TRAILER_SIZE;
    bw_dims_t *d = &h->dims;
    h->version = p[2];
    h->segment_vectors = 0;
    h->embedded = 0;
    if (BW_CFG_BANDS)
        h->band_access = 0;
    uint32_t chunk[2] = {0, 0}; /* record BW_EXT_CHUNK_STEPS: K, its steps' count */
    d->shape = p[3] & 3u;
    h->mode = (uint8_t)(p[3] >> 2 & 3u);
    h->basis = (uint8_t)(p[3] >> 4 & 3u);
    d->level_out = p[4] & 15u;
    d->level_in = p[4] >> 4;
    h->flags = p[5];
    h->spectral_levels = p[6];
    uint32_t v[HV_COUNT] = {0u, 0u, 0u, SCALE_ONE_BITS, 0u};
    for (unsigned k = 0; k < HV_COUNT; k++) {
        if (k < HV_SCALE) {
            if (k != HV_PARAM || h->mode != BW_MODE_LOSSLESS)
                q = get_varint(q, end, &v[k]);
        } else if (p[3] & (H_SCALE << (k - HV_SCALE))) {
            /* stored only when it is not the default */
            uint32_t w = end - q >= 4 ? bw_get_u32(q) : v[k];
            q = w == v[k] ? NULL : q + 4;
            v[k] = w;
        }
        if (!q)
            return BW_ERR_HEADER;
    }
    d->n_in = v[HV_N_IN];
    d->bands = v[HV_BANDS];
    uint32_t e = v[HV_PARAM];
    bool me = h->mode == BW_MODE_MAX_ERROR;
    h->max_error = me ? e : 0u;
    h->prequant = bw_prequant(h->mode, e);
    h->step_q8 = BW_STEP_ONE_Q8 + (me ? 0u : e);
    h->scale_bits = v[HV_SCALE];
    h->offset_bits = v[HV_OFFSET];
    /* version 7 exactly when it is needed (records, or the multi-symbol
     * coder): one encoding per header */
    if ((h->version == BW_VERSION_EXT) != ((h->flags & (BW_FLAG_EXT | BW_FLAG_MS)) != 0u))
        return BW_ERR_HEADER;
    if (h->flags & BW_FLAG_EXT) {
        uint32_t el;
        q = get_varint(q, end, &el);
        if (!q || el == 0u || el > BW_EXT_MAX || el > (size_t)(end - q))
            return BW_ERR_HEADER;
        h->ext_off = (uint32_t)(q - p);
        h->ext_len = el;
        int32_t tail = ext_scan(q, el, h, chunk);
        if (tail < 0)
            return (bw_status_t)tail;
        q += el;
        /* the tail is the host's, between the coded body and the CRC */
        if ((size_t)tail > (size_t)(end - q)) {
            if (!(BW_CFG_SALVAGE && cut))
                return BW_ERR_HEADER;
            tail = (int32_t)(end - q);
        }
        end -= tail;
    }
    h->header_len = (uint32_t)(q - p);
    h->body_len = (uint32_t)(end - q);
    h->payload_len = (uint32_t)len;
    d->n_out = d->shape == BW_SHAPE_SPECTRA ? 1u
               : d->level_out <= BW_MAX_LEVEL ? bw_tri_count(d->level_out)
                                              : 0u;
    /* the step above 1 must not wrap; then the rules every payload follows,
     * and the spectral depth its basis implies */
    bw_status_t pc = bw_params_check(d, h->mode, h->basis, h->flags & ~BW_FLAG_EXT,
                                     me ? e : h->step_q8, BW_FOR_PAYLOAD);
    if ((!me && e > UINT32_MAX - BW_STEP_ONE_Q8) || (pc != BW_OK && pc != BW_ERR_NOT_BUILT) ||
        h->spectral_levels != bw_plan_spec_levels(h->basis, d->bands) ||
        (BW_CFG_EMBED && h->embedded &&
         (h->basis == BW_BASIS_PRED || (h->flags & BW_FLAG_STREAM_ORDER) ||
          (BW_CFG_CODER_TAB &&
           (h->flags & (BW_FLAG_RICE | BW_FLAG_MS)) == (BW_FLAG_RICE | BW_FLAG_MS)))))
        return BW_ERR_HEADER;
    /* band access: prediction of a set of spectra, in one body of its own */
    if (BW_CFG_BANDS && h->band_access &&
        (h->basis != BW_BASIS_PRED || d->shape != BW_SHAPE_SPECTRA || h->segment_vectors ||
         chunk[0] || (h->flags & (BW_FLAG_RICE | BW_FLAG_MS | BW_FLAG_STREAM_ORDER))))
        return BW_ERR_HEADER;
    /* segments of V vectors, V at most their number (one encoding) */
    h->segments = 1u;
    if (BW_CFG_SEGMENTS && h->segment_vectors) {
        uint32_t nvec = d->n_in * d->n_out, sv = h->segment_vectors;
        if (sv > nvec)
            return BW_ERR_HEADER;
        h->segments = (nvec - 1u) / sv + 1u;
    }
    /* steps per chunk of K vectors: one per chunk, K at most the vectors;
     * a quantised transform coded in one body in coarse-to-fine order */
    if (BW_CFG_CHUNK_STEPS && chunk[0]) {
        uint32_t nvec = d->n_in * d->n_out, K = chunk[0];
        if (K > nvec || chunk[1] != (nvec - 1u) / K + 1u || h->segment_vectors ||
            h->step_q8 <= BW_STEP_ONE_Q8 || h->mode == BW_MODE_MAX_ERROR ||
            h->basis == BW_BASIS_PRED || (h->flags & BW_FLAG_STREAM_ORDER))
            return BW_ERR_HEADER;
    }
    return pc; /* a valid header, or one this build cannot decode */
}

bw_status_t bw_header_parse_fields(const uint8_t *p, size_t len, bw_header_t *h)
{
    return parse_fields(p, len, h, false);
}

bw_status_t bw_header_parse_cut(const uint8_t *p, size_t len, bw_header_t *h)
{
    return parse_fields(p, len, h, true);
}
