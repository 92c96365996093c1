/* SPDX-License-Identifier: BSD-2-Clause */
/* Float values and integer samples (bwh_values.h). */
#include "bwh_values.h"

#include <math.h>
#include <string.h>

#include "bw_codec.h"

float bwh_bits_to_float(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

uint32_t bwh_float_to_bits(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

int bwh_decimal_exponent(float scale)
{
    for (int k = 1; k <= 9; k++)
        if ((float)pow(10.0, -k) == scale)
            return k;
    return 0;
}

bwh_value_map_t bwh_value_map(float scale, float offset, unsigned flags)
{
    bwh_value_map_t m = {scale, offset, 0, (flags & BW_FLAG_LOG_VALUE) != 0};
    int k = bwh_decimal_exponent(scale);
    if ((flags & BW_FLAG_DECIMAL_SCALE) && k)
        m.divisor = pow(10.0, k);
    return m;
}

float bwh_value_of(const bwh_value_map_t *m, int32_t q)
{
    double v = m->offset + (m->divisor ? (double)q / m->divisor : m->scale * (double)q);
    return (float)(m->log ? exp(v) : v);
}
