/* SPDX-License-Identifier: BSD-2-Clause */
/* Extension records on the host (bwh_ext.h). */
#include "bwh_ext.h"

#include <stdlib.h>
#include <string.h>

#include "bw_crc32.h"
#include "bwh_error.h"

size_t bwh_varint_put(uint8_t *out, uint32_t v)
{
    size_t n = 0;
    for (;; v >>= 7) {
        if (out)
            out[n] = (uint8_t)(v | (v > 0x7Fu ? 0x80u : 0u));
        n++;
        if (v <= 0x7Fu)
            return n;
    }
}

int bwh_varint_get(const uint8_t **q, const uint8_t *end, uint32_t *v)
{
    uint32_t x = 0;
    const uint8_t *s = *q;
    for (unsigned sh = 0; s < end && sh < 35u; sh += 7u) {
        uint32_t b = *s++;
        if (sh == 28u && b > 0x0Fu)
            return -1;
        x |= (b & 0x7Fu) << sh;
        if (!(b & 0x80u)) {
            if (sh && !b)
                return -1; /* not the shortest form */
            *v = x;
            *q = s;
            return 0;
        }
    }
    return -1;
}

size_t bwh_ext_put(uint8_t *out, uint8_t type, const uint8_t *data, size_t n)
{
    size_t k = 1 + bwh_varint_put(NULL, (uint32_t)n);
    if (out) {
        out[0] = type;
        bwh_varint_put(out + 1, (uint32_t)n);
        if (n)
            memcpy(out + k, data, n);
    }
    return k + n;
}

int bwh_ext_add(uint8_t **pp, size_t *plen, const uint8_t *recs, size_t rlen, const uint8_t *tail,
                size_t tlen)
{
    const uint8_t *p = *pp;
    size_t len = *plen;
    bw_header_t h;
    int st = bw_header_read(p, len, &h);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    if (!rlen && !tlen)
        return 0;
    /* where the header's own fields end: before the area's length, or the
     * header's end */
    size_t fields = h.header_len, old_area = 0;
    if (h.ext_len) {
        fields = h.ext_off - bwh_varint_put(NULL, h.ext_len);
        old_area = h.ext_len;
    }
    const uint8_t *old_tail;
    if (tlen && bwh_ext_tail(p, &h, &old_tail))
        return bwh_fail("the payload has a tail already");
    size_t area = old_area + rlen;
    if (area > BW_EXT_MAX)
        return bwh_fail("extension records of %zu bytes: more than the %u a payload holds", area,
                        (unsigned)BW_EXT_MAX);
    size_t body_end = h.header_len + h.body_len, rest = len - BW_TRAILER_SIZE - body_end;
    size_t nlen = fields + bwh_varint_put(NULL, (uint32_t)area) + area + h.body_len + rest + tlen +
                  BW_TRAILER_SIZE;
    if (nlen > UINT32_MAX)
        return bwh_fail("the payload would exceed 4 GiB");
    uint8_t *o = malloc(nlen);
    if (!o)
        return bwh_fail("out of memory");
    size_t k = 0;
    memcpy(o, p, fields);
    o[2] = 7; /* records follow: version 7 and flag bit 6 */
    o[5] |= BW_FLAG_EXT;
    k = fields;
    k += bwh_varint_put(o + k, (uint32_t)area);
    if (old_area)
        memcpy(o + k, p + h.ext_off, old_area);
    k += old_area;
    memcpy(o + k, recs, rlen);
    k += rlen;
    memcpy(o + k, p + h.header_len, h.body_len + rest);
    if (h.segment_vectors) { /* the segment table's CRC covers the header */
        size_t t = k + BW_SEGMENT_TABLE_SIZE(h.segments) - 4u;
        uint32_t tc = bw_crc32(o, t);
        for (unsigned b = 0; b < 4; b++)
            o[t + b] = (uint8_t)(tc >> (8 * b));
    }
    if (h.band_access) { /* so does the band tables' */
        size_t tb = bw_bands_tables(&h, p);
        if (!tb) {
            free(o);
            return bwh_fail("the band access tables do not fit the body");
        }
        uint32_t tc = bw_crc32(o, k + tb);
        for (unsigned b = 0; b < 4; b++)
            o[k + tb + b] = (uint8_t)(tc >> (8 * b));
    }
    k += h.body_len + rest;
    if (tlen)
        memcpy(o + k, tail, tlen);
    k += tlen;
    uint32_t crc = bw_crc32(o, k);
    for (unsigned b = 0; b < 4; b++)
        o[k + b] = (uint8_t)(crc >> (8 * b));
    /* the result must read back as a payload */
    bw_header_t h2;
    st = bw_header_read(o, nlen, &h2);
    if (st != BW_OK || h2.body_len != h.body_len) {
        free(o);
        return bwh_fail("records do not make a valid payload: %s",
                        st != BW_OK ? bw_strerror(st) : "the tail does not match");
    }
    free(*pp);
    *pp = o;
    *plen = nlen;
    return 0;
}

int bwh_ext_find(const uint8_t *p, const bw_header_t *h, uint8_t type, const uint8_t **data,
                 uint32_t *data_len)
{
    size_t pos = 0;
    uint8_t t;
    const uint8_t *d;
    uint32_t dl;
    int found = 0;
    while (h->ext_len && bw_ext_next(p + h->ext_off, h->ext_len, &pos, &t, &d, &dl)) {
        if (t != type)
            continue;
        if (found)
            return -1;
        found = 1;
        *data = d;
        *data_len = dl;
    }
    return found;
}

size_t bwh_ext_tail(const uint8_t *p, const bw_header_t *h, const uint8_t **tail)
{
    size_t at = (size_t)h->header_len + h->body_len;
    *tail = p + at;
    return h->payload_len - BW_TRAILER_SIZE - at;
}
