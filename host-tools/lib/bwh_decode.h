/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Payloads to samples: the checks every reader makes, and the integer
 * samples or their float values.
 */
#ifndef BWH_DECODE_H
#define BWH_DECODE_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Decodes a payload. *samples (allocated, may be NULL) receives the integer
 * samples and *values (allocated, may be NULL) the float values; a value
 * that float32 cannot hold is an error. Payloads that decode to more than
 * max_samples samples are refused before anything is allocated (0: the
 * default, BWH_MAX_SAMPLES_DEFAULT): a few bytes can describe gigabytes. */
#define BWH_MAX_SAMPLES_DEFAULT ((size_t)1 << 26) /* 256 MiB of float32 */
int bwh_decode_limit(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                     int32_t **samples, float **values);
/* bwh_decode_limit with the default limit */
int bwh_decode(const uint8_t *p, size_t len, bw_header_t *h, int32_t **samples, float **values);

/* The header of p[len] (bw_header_read), or, for a segmented payload that
 * is not whole, its fields as they read when the segment table's CRC-32
 * (which covers the header) vouches for them: BW_OK, else the status of
 * bw_header_read. */
int bwh_header_salvage(const uint8_t *p, size_t len, bw_header_t *h);

/* What bwh_decode_salvage found. */
typedef struct {
    uint32_t segments;      /* the payload's segments (1: a body in one piece) */
    uint32_t lost_segments; /* of them lost: damaged, or cut off */
    size_t approx, missing; /* samples rebuilt from coarser levels (or, below,
                             * without their float bits); samples lost */
    uint32_t tail_lost;     /* 1: a float payload's tail (record 0x01) was not
                             * used (the payload is not whole): every value
                             * decoded from the samples alone, approximate
                             * where the tail held low bits or exceptions */
} bwh_salvage_t;

/* As bwh_decode_limit, for a payload that may be damaged or cut (a file
 * received over a lossy link): a segmented payload (`encode --segments`)
 * whose header and segment table are intact decodes every segment that is
 * whole, and rebuilds the rest from the coarser levels it has. Returns 0
 * for a whole payload, 1 when segments were lost (the samples and values
 * hold what was rebuilt), -1 on error (a payload without segments that is
 * not whole is lost whole). *mask (may be NULL; allocated): per sample,
 * [incoming][outgoing][band], BW_SAMPLE_EXACT, _APPROX or _MISSING. */
int bwh_decode_salvage(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                       int32_t **samples, float **values, uint8_t **mask, bwh_salvage_t *info);

/* One incoming direction of a BRDF, or one spectrum of a set (row `in` of
 * [incoming][outgoing][band]), decoded alone (bw_decode_incoming: only the
 * segments and blocks it depends on): *samples and *values as
 * bwh_decode_limit's (either may be NULL), n_out * bands of them, and the
 * row's own dimensions in *row (a reflectance, or one spectrum). Not for a
 * full BRDF with the reciprocity step, nor a float payload that keeps bits
 * in a tail (record 0x01): those decode whole. 0, or -1. */
int bwh_decode_incoming(const uint8_t *p, size_t len, uint32_t in, bw_header_t *h, bw_dims_t *row,
                        int32_t **samples, float **values);

/* The incoming directions (rows) marked non-zero in rows[n_in] of a BRDF,
 * or the spectra so marked of a set of spectra, decoded together
 * (bw_decode_rows: only the segments and blocks they depend on, once):
 * *samples and *values as bwh_decode_limit's for the marked rows in
 * ascending order, *sub their dimensions (a BRDF of that many incoming
 * directions, or that many spectra). Not with the reciprocity step, nor a
 * float payload that keeps bits in a tail. 0, or -1. */
int bwh_decode_rows(const uint8_t *p, size_t len, const uint8_t *rows, bw_header_t *h,
                    bw_dims_t *sub, int32_t **samples, float **values);

/* Marks in rows[n_in] (h from bw_header_read or bwh_decode_*) a region of
 * the incoming hemisphere: for a full BRDF the incoming directions whose
 * triangles' centres lie within radius_deg of the direction (theta_deg from
 * the normal, phi_deg from the x axis); for an isotropic BRDF the
 * incidences within radius_deg of theta_deg (incidence_deg[n_in], the
 * payload's incidence angles in degrees, or NULL: (i + 1/2) 90 / n_in), the
 * azimuth playing no part. Returns how many, or -1 (not a BRDF, angles out
 * of range). */
int bwh_region_rows(const bw_header_t *h, const double *incidence_deg, double theta_deg,
                    double phi_deg, double radius_deg, uint8_t *rows);

/* A directional measurement at a coarser outgoing level (bw_decode_level):
 * *samples and *values as bwh_decode_limit's for n_in * 4 4^level * bands
 * samples, *lod the dimensions of that level. Not with the reciprocity
 * step, nor a float payload that keeps bits in a tail. 0, or -1. */
int bwh_decode_level(const uint8_t *p, size_t len, unsigned level, bw_header_t *h, bw_dims_t *lod,
                     int32_t **samples, float **values);
/* The same at a coarser level of either hemisphere or both
 * (bw_decode_lod): outgoing level level_out and, for a full BRDF, incoming
 * level level_in (-1: the payload's own). 0, or -1. */
int bwh_decode_levels(const uint8_t *p, size_t len, int level_out, int level_in, bw_header_t *h,
                      bw_dims_t *lod, int32_t **samples, float **values);

/* Bands b0 .. b1 - 1 of every spectrum or direction: *samples and *values
 * as bwh_decode_limit's, n_in * n_out * (b1 - b0) of them, *sub their
 * dimensions. A payload coded with band access (`encode --band-access`)
 * decodes only the columns those bands depend on (bw_decode_band_range:
 * its tables' and those columns' CRCs checked); any other decodes whole,
 * then keeps the bands. Not a float payload that keeps bits in a tail.
 * 0, or -1. */
int bwh_decode_bands(const uint8_t *p, size_t len, uint32_t b0, uint32_t b1, bw_header_t *h,
                     bw_dims_t *sub, int32_t **samples, float **values);

/* Keeps the bands marked non-zero in bands[d->bands] of decoded samples,
 * in order, in place: each of s, v and mask (any may be NULL; a sample's
 * int32, float value, mask byte) in the layout [incoming][outgoing][band]
 * of d, whose bands become the number marked. The decode before it is
 * whole (a band range costs the payload's decode, then the copy). 0, or -1
 * (no band marked). */
int bwh_keep_bands(bw_dims_t *d, const uint8_t *bands, int32_t *s, float *v, uint8_t *mask);

/* Checks a payload as a receiver must before it stores and acknowledges it:
 * header, CRC, the sample limit (0: the default) and a full decode. */
int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h);

#ifdef __cplusplus
}
#endif

#endif
