/* SPDX-License-Identifier: BSD-2-Clause */
/* Error metrics between a reference and a test signal (`brdfwave compare`). */
#ifndef BWH_METRICS_H
#define BWH_METRICS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    size_t n;
    size_t zero_ref;  /* samples whose reference is 0 (left out of rel. L1/L2) */
    double rel_l1;    /* percent, paper eq. 7 */
    double rel_l2;    /* percent, paper eq. 8 */
    double rmse;
    double max_abs;
    double psnr;      /* dB, peak = max |reference| */
} bwh_metrics_t;

void bwh_metrics(const float *ref, const float *test, size_t n, bwh_metrics_t *m);

#ifdef __cplusplus
}
#endif

#endif
