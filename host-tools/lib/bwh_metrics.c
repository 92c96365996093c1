/* SPDX-License-Identifier: BSD-2-Clause */
/* Error metrics (bwh_metrics.h). */
#include "bwh_metrics.h"

#include <math.h>
#include <string.h>

void bwh_metrics(const float *ref, const float *test, size_t n, bwh_metrics_t *m)
{
    memset(m, 0, sizeof *m);
    m->n = n;
    double l1 = 0, l2 = 0, se = 0, peak = 0;
    size_t nz = 0;
    for (size_t i = 0; i < n; i++) {
        double f = ref[i], g = test[i], d = g - f;
        se += d * d;
        if (fabs(d) > m->max_abs)
            m->max_abs = fabs(d);
        if (fabs(f) > peak)
            peak = fabs(f);
        if (f == 0) {
            m->zero_ref++;
            continue;
        }
        l1 += fabs(d) / fabs(f);
        l2 += (d * d) / (f * f);
        nz++;
    }
    m->rel_l1 = nz ? 100.0 * l1 / (double)nz : 0;
    m->rel_l2 = nz ? 100.0 * sqrt(l2 / (double)nz) : 0;
    m->rmse = n ? sqrt(se / (double)n) : 0;
    m->psnr = m->rmse > 0 && peak > 0 ? 20.0 * log10(peak / m->rmse) : INFINITY;
}
