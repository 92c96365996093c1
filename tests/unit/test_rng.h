/* SPDX-License-Identifier: BSD-2-Clause */
/* Uniform random numbers for the host tests and benches: xorshift64*, the
 * top 53 bits of each output, in [0, 1). Each program keeps its own state,
 * so its numbers do not depend on what other programs draw. */
#ifndef TEST_RNG_H
#define TEST_RNG_H

#include <stdint.h>

static inline double test_uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 0x2545f4914f6cdd1dull) >> 11) * 0x1.0p-53;
}

#endif
