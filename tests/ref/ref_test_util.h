/* SPDX-License-Identifier: BSD-2-Clause */
/* Helpers shared by the reference-model tests. */
#ifndef REF_TEST_UTIL_H
#define REF_TEST_UTIL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

static uint64_t rt_state = 0x9e3779b97f4a7c15ull;

static inline void rt_seed(uint64_t s)
{
    rt_state = s * 0x9e3779b97f4a7c15ull + 1;
}

/* uniform in [0, 1) (xorshift64*) */
static inline double rt_uniform(void)
{
    rt_state ^= rt_state >> 12;
    rt_state ^= rt_state << 25;
    rt_state ^= rt_state >> 27;
    return (double)((rt_state * 0x2545f4914f6cdd1dull) >> 11) * (1.0 / 9007199254740992.0);
}

static inline void rt_fill(double *x, size_t n, double lo, double hi)
{
    for (size_t i = 0; i < n; i++)
        x[i] = lo + (hi - lo) * rt_uniform();
}

static inline double rt_max_abs_diff(const double *a, const double *b, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

#endif
