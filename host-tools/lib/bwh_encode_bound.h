/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Float input under a per-sample guarantee, for bwh_encode_f32: lossless bit
 * for bit (bwh_exact.h), the relative bound alone or with the absolute one
 * (bwh_logmap.h); and for every guaranteed payload the last step: its
 * records added, then decoded and checked sample by sample in float.
 */
#ifndef BWH_ENCODE_BOUND_H
#define BWH_ENCODE_BOUND_H

#include <stddef.h>
#include <stdint.h>

#include "bwh_encode.h"
#include "bwh_guarantee.h"

#ifdef __cplusplus
extern "C" {
#endif

/* x[n] bit for bit (the lossless mode of float input); the payload records
 * g (NULL: exact), a bound exact coding meets. */
int bwh_encode_exact(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                     const bwh_guarantee_t *g, uint8_t **out, size_t *out_len);

/* Every value within max(R |x|, F) of the input (R = o->max_rel_error,
 * F = o->rel_floor), with mode MAX_ERROR also within o->max_error. */
int bwh_encode_relative(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                        uint8_t **out, size_t *out_len);

/* The last step of an encode under guarantee g: adds recs[rlen] (the
 * records the values need) and tail, then the guarantee's record, to the
 * payload *out; decodes it and checks every value against x[n]. With fix
 * (a lossy guarantee, no BW_EXT_FLOAT_EXACT among recs), values that miss
 * the bound (a subnormal that float32 rounding moves too far) are written
 * exactly as exceptions, at most one in 16. 0, or -1 (*out freed). */
int bwh_encode_seal(uint8_t **out, size_t *out_len, const float *x, size_t n,
                    const bwh_guarantee_t *g, const uint8_t *recs, size_t rlen,
                    const uint8_t *tail, size_t tlen, int fix);

#ifdef __cplusplus
}
#endif

#endif
