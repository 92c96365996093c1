/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Float32 values kept bit for bit (record 0x01, BW_EXT_FLOAT_EXACT; docs/
 * FORMAT.md): the integer samples the core codes exactly, and what the
 * decoder needs besides them to give back every input bit.
 *
 * Three maps, the first that fits:
 *   binary     every value a whole multiple of 2^-k (k >= 0) within the
 *              core's range: scale 2^-k in the header
 *   decimal    every value the float32 of a decimal with k = 1..9 digits
 *              after the point (a .sed file's 5): scale 10^-k, DECIMAL_SCALE
 *   bit planes any float32: the bits as a monotone integer m (sign and
 *              magnitude to two's complement, so -0.0 sorts just below
 *              +0.0), the high plane (m >> s) - c coded by the core and the
 *              s low bits of every sample raw in the payload's tail
 * Samples a map cannot give back (NaN and infinities always, -0.0 under a
 * scale, a few values off the decimal grid) are exceptions: their positions
 * and bits in the tail, written over the decoded values.
 */
#ifndef BWH_EXACT_H
#define BWH_EXACT_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* record 0x01's map: the payload's value map, or the bit planes */
enum { BWH_EXACT_VALUES = 0, BWH_EXACT_PLANES = 1 };

typedef struct {
    int map;         /* BWH_EXACT_VALUES (a scale) or BWH_EXACT_PLANES */
    float scale;     /* the header's scale (1 for the planes) */
    unsigned flags;  /* BW_FLAG_DECIMAL_SCALE for a decimal scale */
    unsigned s;      /* planes: low bits per sample, 0..8 */
    int32_t c;       /* planes: the high plane is (m >> s) - c */
    int32_t *q;      /* [n] the core's samples (allocated) */
    size_t n_exc;    /* exceptions */
    uint8_t *rec;    /* record 0x01, whole (allocated; NULL when no record is needed) */
    size_t rec_len;
    uint8_t *tail;   /* its tail (allocated, may be NULL) */
    size_t tail_len;
} bwh_exact_t;

/* Chooses the map for x[n] and makes the samples, the record and the tail.
 * 0, or -1 (bwh_last_error). */
int bwh_exact_map(const float *x, size_t n, bwh_exact_t *m);
void bwh_exact_free(bwh_exact_t *m);

/* Record 0x01 and its tail for the map BWH_EXACT_VALUES with exceptions at
 * the positions idx[k] (ascending) of x: the bits x[idx[k]] written over
 * whatever the payload's value map decodes there. 0, or -1. */
int bwh_exact_exceptions(const float *x, const size_t *idx, size_t k, bwh_exact_t *m);

/* Decode side: the values v[n] from the samples q[n] and record 0x01
 * (data d[dl]) with the payload's tail: for BWH_EXACT_PLANES from the
 * planes, for BWH_EXACT_VALUES by overwriting the exceptions in v (which the
 * value map filled). *map receives the map. 0, or -1 for a malformed record
 * or tail. tail NULL: the tail is not there to trust (a payload that is not
 * whole: no CRC of its own vouches for it): the planes' low bits take the
 * middle of their range and the exceptions stay as the map gives them;
 * then 1 when that leaves values approximate (low bits, or exceptions). */
int bwh_exact_apply(const uint8_t *d, uint32_t dl, const uint8_t *tail, size_t tail_len,
                    const int32_t *q, float *v, size_t n, int *map);
/* The map of record 0x01 (data d[dl]) without applying it; -1 if malformed. */
int bwh_exact_map_of(const uint8_t *d, uint32_t dl);
/* Its map, low bits and number of exceptions: 0, or -1 if malformed. */
int bwh_exact_fields(const uint8_t *d, uint32_t dl, int *map, unsigned *s, uint32_t *n_exc);

#ifdef __cplusplus
}
#endif

#endif
