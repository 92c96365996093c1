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

/* Checks a payload as a receiver must before it stores and acknowledges it:
 * header, CRC, the sample limit (0: the default) and a full decode. */
int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h);

#ifdef __cplusplus
}
#endif

#endif
