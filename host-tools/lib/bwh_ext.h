/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Extension records on the host (docs/FORMAT.md, Extensions): records added
 * to a finished payload, the one record of a type found, and the tail that
 * BW_EXT_FLOAT_EXACT sets apart at the body's end.
 */
#ifndef BWH_EXT_H
#define BWH_EXT_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes one record (type, varint length, data) at out (NULL: only
 * counts); returns its length. */
size_t bwh_ext_put(uint8_t *out, uint8_t type, const uint8_t *data, size_t n);

/* Writes v as a LEB128 varint at out (NULL: only counts); returns its length. */
size_t bwh_varint_put(uint8_t *out, uint32_t v);
/* Reads a LEB128 varint of at most 32 bits (shortest form) at *q before end;
 * advances *q. 0, or -1 when malformed. */
int bwh_varint_get(const uint8_t **q, const uint8_t *end, uint32_t *v);

/* Adds records recs[rlen] (whole records) to the extension area of the
 * payload *p[*len] (made version 7 if it was 6; records already there are
 * kept, before the new ones) and tail[tlen] between its body and its CRC
 * (only with a BW_EXT_FLOAT_EXACT record among recs whose first field is
 * tlen, and none in the payload before). The header's fields, the body and
 * every decoded sample stay as they were; the CRC is rewritten. *p is
 * reallocated. 0, or -1 (bwh_last_error) when the result would not be a
 * valid payload. */
int bwh_ext_add(uint8_t **p, size_t *len, const uint8_t *recs, size_t rlen, const uint8_t *tail,
                size_t tlen);

/* The payload's one record of `type` (h from bw_header_read): 1 and its
 * data, 0 when there is none, -1 when there are two. */
int bwh_ext_find(const uint8_t *p, const bw_header_t *h, uint8_t type, const uint8_t **data,
                 uint32_t *data_len);

/* The tail of a payload (h from bw_header_read): the bytes between the
 * coded body and the CRC, set apart by a BW_EXT_FLOAT_EXACT record. */
size_t bwh_ext_tail(const uint8_t *p, const bw_header_t *h, const uint8_t **tail);

#ifdef __cplusplus
}
#endif

#endif
