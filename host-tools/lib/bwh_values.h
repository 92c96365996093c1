/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Float values and the codec's integer samples: value = offset + scale *
 * sample (or exp of that for a payload with BW_FLAG_LOG_VALUE), scale and
 * offset as float32 bits in the payload header.
 */
#ifndef BWH_VALUES_H
#define BWH_VALUES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Float value of a header's scale / offset fields, and back. */
float bwh_bits_to_float(uint32_t bits);
uint32_t bwh_float_to_bits(float f);

/* k if scale is float32(10^-k), k = 1..9, else 0. */
int bwh_decimal_exponent(float scale);

/* The float value of an integer sample. With BW_FLAG_DECIMAL_SCALE the
 * scale stands for 10^-k exactly (1e-5 for .sed reflectance) and samples are
 * divided by 10^k in double, so decimal data comes back as the float nearest
 * its decimal value rather than one ulp off through the rounded float32
 * scale. */
typedef struct {
    double scale, offset, divisor;
    int log; /* BW_FLAG_LOG_VALUE: value = exp(offset + scale * q) */
} bwh_value_map_t;

bwh_value_map_t bwh_value_map(float scale, float offset, unsigned flags);
float bwh_value_of(const bwh_value_map_t *m, int32_t q);

#ifdef __cplusplus
}
#endif

#endif
