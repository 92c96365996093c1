/* SPDX-License-Identifier: BSD-2-Clause */
/* Analytic BRDF models of the virtual goniometer (brdf_models.h). */
#include "brdf_models.h"

#include <math.h>

double bwh_brdf_phong(const bwh_brdf_params_t *p, const double wi[3], const double wo[3])
{
    /* mirror of wi about the normal z */
    double c = -wi[0] * wo[0] - wi[1] * wo[1] + wi[2] * wo[2];
    double f = p->kd / BWH_BRDF_PI;
    if (c > 0.0)
        f += p->ks * (p->n + 2.0) / (2.0 * BWH_BRDF_PI) * pow(c, p->n);
    return f;
}

double bwh_brdf_ward(const bwh_brdf_params_t *p, const double wi[3], const double wo[3])
{
    double cos_i = wi[2] > BWH_BRDF_COS_MIN ? wi[2] : BWH_BRDF_COS_MIN;
    double cos_o = wo[2] > BWH_BRDF_COS_MIN ? wo[2] : BWH_BRDF_COS_MIN;
    double hx = wi[0] + wo[0];
    double hy = wi[1] + wo[1];
    double hz = wi[2] + wo[2];
    double hz2, e, spec;
    if (hz < BWH_BRDF_COS_MIN)
        hz = BWH_BRDF_COS_MIN;
    hz2 = hz * hz;
    e = (hx * hx / (p->ax * p->ax) + hy * hy / (p->ay * p->ay)) / hz2;
    spec = exp(-e) / (4.0 * BWH_BRDF_PI * p->ax * p->ay * sqrt(cos_i * cos_o));
    return p->kd / BWH_BRDF_PI + p->ks * spec;
}
