/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The relative bound's map of values to samples (record 0x02,
 * BW_EXT_LOG_MAP; docs/FORMAT.md): y is linear in x near zero, logarithmic
 * in between and linear again above a cap, continuous with its slope, odd:
 *
 *   a = |x|:  y = a / T1                          a <= T1
 *             y = 1 + ln(a / T1)                  T1 < a <= T2 (or no T2)
 *             y = 1 + ln(T2 / T1) + (a - T2) / T2 a > T2
 *   sample q = sign(x) round(y / h); a sample with |q| <= Z decodes to 0.
 *
 * A bound of h (E + 1/2) on y (E the core's bound in samples) then bounds
 * the error by h (E + 1/2) T1 below T1 (the floor F = R T1), by the
 * relative e^(h (E + 1/2)) - 1 from T1 to T2, and by h (E + 1/2) T2 above
 * T2 (the absolute bound, T2 = E / R): |x' - x| <= min(E, max(R |x|, F)).
 * Without a floor T1 is the smallest non-zero |x| and Z the core's bound,
 * so zeros decode to exactly 0 and nothing else does.
 */
#ifndef BWH_LOGMAP_H
#define BWH_LOGMAP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    float t1;   /* > 0: the end of the linear part near zero */
    float t2;   /* 0: none; else >= t1, the start of the linear part above */
    float h;    /* > 0: y per sample unit */
    uint32_t z; /* samples with |q| <= z decode to 0 */
} bwh_logmap_t;

/* y of a finite value x */
double bwh_logmap_y(const bwh_logmap_t *m, double x);
/* the value of sample q (float32; magnitudes above the largest float32
 * give the largest float32) */
float bwh_logmap_value(const bwh_logmap_t *m, int32_t q);

/* Record 0x02 of m, whole, at out (NULL: only counts); returns its length. */
size_t bwh_logmap_record(const bwh_logmap_t *m, uint8_t *out);
/* Parses the data of record 0x02: 0, or -1 when malformed. */
int bwh_logmap_parse(const uint8_t *d, uint32_t dl, bwh_logmap_t *m);

#ifdef __cplusplus
}
#endif

#endif
