/* SPDX-License-Identifier: BSD-2-Clause */
/* The relative bound's map of values to samples (bwh_logmap.h). */
#include "bwh_logmap.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "bw_codec.h"
#include "bwh_ext.h"
#include "bwh_values.h"

/* ln(T2 / T1), the y where the logarithmic part ends less 1 */
static double log_span(const bwh_logmap_t *m)
{
    return m->t2 > 0 ? log((double)m->t2 / (double)m->t1) : INFINITY;
}

double bwh_logmap_y(const bwh_logmap_t *m, double x)
{
    double a = fabs(x), t1 = m->t1, t2 = m->t2, y;
    if (a <= t1)
        y = a / t1;
    else if (!(t2 > 0) || a <= t2)
        y = 1.0 + log(a / t1);
    else
        y = 1.0 + log_span(m) + (a - t2) / t2;
    return x < 0 ? -y : y;
}

float bwh_logmap_value(const bwh_logmap_t *m, int32_t q)
{
    uint32_t aq = q < 0 ? 0u - (uint32_t)q : (uint32_t)q;
    if (aq <= m->z)
        return 0.0f;
    double a = (double)m->h * aq, mag;
    if (a <= 1.0) {
        mag = (double)m->t1 * a;
    } else {
        double span = log_span(m);
        if (a - 1.0 <= span)
            mag = (double)m->t1 * exp(a - 1.0);
        else
            mag = (double)m->t2 * (1.0 + (a - 1.0 - span));
    }
    /* a value within the bound of one near the largest float32 may lie
     * just above it: the largest float32 is nearer still */
    if (!(mag <= (double)FLT_MAX))
        mag = FLT_MAX;
    return (float)(q < 0 ? -mag : mag);
}

static void put_f32(uint8_t *d, float f)
{
    uint32_t b = bwh_float_to_bits(f);
    for (unsigned i = 0; i < 4; i++)
        d[i] = (uint8_t)(b >> (8 * i));
}

static float get_f32(const uint8_t *d)
{
    uint32_t b = 0;
    for (unsigned i = 0; i < 4; i++)
        b |= (uint32_t)d[i] << (8 * i);
    return bwh_bits_to_float(b);
}

size_t bwh_logmap_record(const bwh_logmap_t *m, uint8_t *out)
{
    uint8_t d[12 + 5];
    put_f32(d, m->t1);
    put_f32(d + 4, m->t2);
    put_f32(d + 8, m->h);
    size_t n = 12 + bwh_varint_put(d + 12, m->z);
    return bwh_ext_put(out, BW_EXT_LOG_MAP, d, n);
}

int bwh_logmap_parse(const uint8_t *d, uint32_t dl, bwh_logmap_t *m)
{
    memset(m, 0, sizeof *m);
    if (dl < 13)
        return -1;
    m->t1 = get_f32(d);
    m->t2 = get_f32(d + 4);
    m->h = get_f32(d + 8);
    const uint8_t *q = d + 12;
    if (bwh_varint_get(&q, d + dl, &m->z) != 0 || q != d + dl)
        return -1;
    if (!(m->t1 > 0) || !isfinite(m->t1) || !(m->h > 0) || !isfinite(m->h) ||
        !isfinite(m->t2) || (m->t2 != 0 && !(m->t2 >= m->t1)) || m->z > BW_SAMPLE_MAX)
        return -1;
    return 0;
}
