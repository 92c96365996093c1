/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Integer helpers shared by the transforms and the coder.
 *
 * Lifting arithmetic is done modulo 2^32 (through uint32_t). Every lifting
 * step adds to one sample a function of the others, so the inverse subtracts
 * the very same value and the transform stays exactly reversible even if an
 * intermediate wraps; valid input never wraps (see BW_SAMPLE_MAX), and a
 * corrupted payload decodes to garbage instead of undefined behaviour.
 */
#ifndef BW_FIXED_H
#define BW_FIXED_H

#include <stdint.h>

#include "bw_config.h"

/* q16_t: signed Q15.16, used for lifting constants. */
typedef int32_t q16_t;
/* uq16_t: unsigned Q16.16, gains (65536 = 1.0). */
typedef uint32_t uq16_t;
/* uq24_8_t: unsigned Q24.8, quantiser steps in sample units (256 = 1.0). */
typedef uint32_t uq24_8_t;
/* uq56_8_t: unsigned Q56.8, a step times its gains. */
typedef uint64_t uq56_8_t;

static inline int32_t bw_wadd(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); }
static inline int32_t bw_wsub(int32_t a, int32_t b) { return (int32_t)((uint32_t)a - (uint32_t)b); }

/* Arithmetic shift right with flooring (floor(v / 2^s)). The compilers the
 * core supports (GCC, Clang) shift signed values arithmetically, one
 * instruction; the assertion stops a build where that does not hold. */
_Static_assert((-1 >> 1) == -1 && (-5 >> 1) == -3, "signed >> must be arithmetic");
static inline int64_t bw_asr64(int64_t v, unsigned s) { return v >> s; }
static inline int32_t bw_asr32(int32_t v, unsigned s) { return v >> s; }

/* round(c * v / 2^16) for a Q16 constant: floor(c*v + 1/2), the rounding the
 * inverse repeats; a 32x32->64 multiply. The result is truncated to 32 bits
 * (see above). */
static inline int32_t bw_mul_q16_round(q16_t c, int32_t v)
{
    return (int32_t)(uint32_t)(uint64_t)(((int64_t)c * v + 32768) >> 16);
}

/* A helper kept out of line in the small code forms (BW_CFG_UNROLL 0,
 * bw_config.h). */
#if !BW_CFG_UNROLL && defined(__GNUC__)
#define BW_NOINLINE_SMALL __attribute__((noinline))
#else
#define BW_NOINLINE_SMALL
#endif

/* A function kept out of line, so that it does not change how its callers'
 * other calls inline. */
#if defined(__GNUC__)
#define BW_NOINLINE __attribute__((noinline))
#else
#define BW_NOINLINE
#endif

/* A helper whose constant arguments must specialise it at each call. */
#if defined(__GNUC__)
#define BW_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define BW_ALWAYS_INLINE inline
#endif

/* Before a hot loop: unrolled 8 times with BW_CFG_UNROLL. */
#if BW_CFG_UNROLL && defined(__GNUC__)
#define BW_PRAGMA_(x) _Pragma(#x)
#define BW_UNROLL8 BW_PRAGMA_(GCC unroll 8)
#else
#define BW_UNROLL8
#endif

/* A condition that holds far more often than not (block layout only). */
#if defined(__GNUC__)
#define BW_LIKELY(c) __builtin_expect(!!(c), 1)
#else
#define BW_LIKELY(c) (c)
#endif

/* Number of significant bits of v (0 for 0). */
static inline unsigned bw_bitlen(uint32_t v)
{
#if defined(__GNUC__)
    return v ? 32u - (unsigned)__builtin_clz(v) : 0u;
#else
    unsigned n = 0;
    while (v) { n++; v >>= 1; }
    return n;
#endif
}

/* Leading zeros of v != 0. */
static inline unsigned bw_clz32(uint32_t v)
{
#if defined(__GNUC__)
    return (unsigned)__builtin_clz(v);
#else
    return 32u - bw_bitlen(v);
#endif
}

static inline uint32_t bw_abs32(int32_t v) { return v < 0 ? 0u - (uint32_t)v : (uint32_t)v; }

#endif
