/* SPDX-License-Identifier: BSD-2-Clause */
/* Payloads for the host tests of segmented and embedded bodies: the shapes
 * they try, an encode with the encoder's own check into a buffer of the
 * codec's bound, and a decode, salvaging or not, with the mask of what it
 * rebuilt. Include after cmocka.h (fail_msg). */
#ifndef TEST_PAYLOAD_H
#define TEST_PAYLOAD_H

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "bw_codec.h"

static inline void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p)
        fail_msg("out of memory");
    return p;
}

typedef struct {
    unsigned shape, lo, li;
    uint32_t n_in, bands;
} shape_t;

typedef struct {
    uint8_t *p; /* allocated */
    size_t len;
} payload_t;

/* bw_encode with a verify area, into the codec's bound for n samples and
 * their segments' table (and the starts of embedded segments). */
static inline bw_status_t test_encode(const bw_dims_t *d, const bw_params_t *pa, const int32_t *x,
                                      payload_t *out)
{
    size_t n = bw_dims_samples(d), wb = bw_work_bound(n, d->bands);
    size_t cap = bw_payload_bound(n) + BW_SEGMENT_OVERHEAD((size_t)d->n_in * d->n_out) +
                 (pa->band_access ? BW_BANDS_OVERHEAD : 0u) + 64u;
    int32_t *w = xmalloc(wb * 4), *v = xmalloc(wb * 4);
    out->p = xmalloc(cap);
    out->len = 0;
    bw_status_t st = bw_encode(d, pa, x, w, v, out->p, cap, &out->len);
    free(w);
    free(v);
    return st;
}

/* A decode of p[len] into out, salvaging or not; seg_ok[seg_cap] (may be
 * NULL) which segments were whole, mask (may be NULL) the direction pairs'
 * states (bw_salvage_mask). */
static inline bw_status_t test_decode(const uint8_t *p, size_t len, const bw_dims_t *d,
                                      bool salvage, int32_t *out, uint8_t *seg_ok, size_t seg_cap,
                                      uint8_t *mask)
{
    size_t n = bw_dims_samples(d), wb = bw_work_bound(n, d->bands);
    size_t nv = (size_t)d->n_in * d->n_out;
    int32_t *w = xmalloc(wb * 4), *tmp = xmalloc(nv * 4);
    uint8_t *lost = xmalloc(nv);
    bw_ctx_t ctx;
    bw_header_t h;
    bw_status_t st = salvage ? bw_decode_salvage(&ctx, p, len, out, n, w, wb, &h, seg_ok, seg_cap,
                                                 lost)
                             : bw_decode(p, len, out, n, w, wb, &h);
    if (salvage && mask && (st == BW_OK || st == BW_ERR_INCOMPLETE))
        bw_salvage_mask(&h, lost, mask, tmp);
    free(w);
    free(tmp);
    free(lost);
    return st;
}

#endif
