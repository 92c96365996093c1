/* SPDX-License-Identifier: BSD-2-Clause */
#include "bwr_eval.h"

#define EVAL_PI 3.14159265358979323846

#include <math.h>
#include <stdlib.h>
#include <string.h>

int bwr_brdf_init(bwr_brdf_t *b, int shape, unsigned level_out, unsigned level_in, size_t n_in,
                  size_t bands, const float *values, const double *theta_in_deg,
                  double lambda_first, double lambda_last, int smooth)
{
    memset(b, 0, sizeof *b);
    if (!values || bands < 1 || level_out > 6 || level_in > 6 ||
        (shape != BWR_EVAL_REFLECTANCE && shape != BWR_EVAL_ISO && shape != BWR_EVAL_FULL))
        return -1;
    b->shape = shape;
    b->level_out = level_out;
    b->level_in = level_in;
    b->n_out = (size_t)4 << (2 * level_out);
    b->n_in = shape == BWR_EVAL_FULL ? (size_t)4 << (2 * level_in)
              : shape == BWR_EVAL_ISO ? n_in
                                      : 1;
    if (b->n_in < 1)
        return -1;
    b->bands = bands;
    b->lambda_first = lambda_first;
    b->lambda_last = lambda_last;
    b->smooth = smooth;
    b->planes = malloc(b->n_in * bands * b->n_out * sizeof *b->planes);
    b->tmp_in = malloc(b->n_in * sizeof *b->tmp_in);
    b->tmp_band = malloc(bands * sizeof *b->tmp_band);
    if (!b->planes || !b->tmp_in || !b->tmp_band || bwr_sinterp_init(&b->s_out, level_out) != 0)
        goto fail;
    if (shape == BWR_EVAL_FULL && bwr_sinterp_init(&b->s_in, level_in) != 0)
        goto fail;
    for (size_t i = 0; i < b->n_in; i++)
        for (size_t o = 0; o < b->n_out; o++)
            for (size_t k = 0; k < bands; k++)
                b->planes[(i * bands + k) * b->n_out + o] = values[(i * b->n_out + o) * bands + k];
    if (shape == BWR_EVAL_ISO) {
        b->theta_in = malloc(b->n_in * sizeof *b->theta_in);
        if (!b->theta_in)
            goto fail;
        for (size_t i = 0; i < b->n_in; i++) {
            double deg = theta_in_deg ? theta_in_deg[i] : (i + 0.5) * 90.0 / (double)b->n_in;
            b->theta_in[i] = deg * EVAL_PI / 180.0;
            if (i && !(b->theta_in[i] > b->theta_in[i - 1]))
                goto fail;
        }
    }
    return 0;
fail:
    bwr_brdf_free(b);
    return -1;
}

void bwr_brdf_free(bwr_brdf_t *b)
{
    free(b->planes);
    free(b->tmp_in);
    free(b->tmp_band);
    free(b->theta_in);
    if (b->s_out.n)
        bwr_sinterp_free(&b->s_out);
    if (b->s_in.n)
        bwr_sinterp_free(&b->s_in);
    memset(b, 0, sizeof *b);
}

static double sphere(const bwr_brdf_t *b, const bwr_sinterp_t *s, const double *v,
                     const double d[3])
{
    return b->smooth ? bwr_sinterp_smooth(s, v, d) : bwr_sinterp_linear(s, v, d);
}

/* The value of band k at (wi, wo). */
static double at_band(bwr_brdf_t *b, const double wi[3], const double wo[3], size_t k)
{
    size_t plane = b->bands * b->n_out;
    if (b->shape == BWR_EVAL_REFLECTANCE)
        return sphere(b, &b->s_out, b->planes + k * b->n_out, wo);
    if (b->shape == BWR_EVAL_FULL) {
        for (size_t i = 0; i < b->n_in; i++)
            b->tmp_in[i] = sphere(b, &b->s_out, b->planes + i * plane + k * b->n_out, wo);
        return sphere(b, &b->s_in, b->tmp_in, wi);
    }
    /* isotropic: turn both directions about z until phi_i = 0 */
    double phi = atan2(wi[1], wi[0]), c = cos(-phi), s = sin(-phi);
    double wo_r[3] = {c * wo[0] - s * wo[1], s * wo[0] + c * wo[1], wo[2]};
    double theta = acos(fmin(1.0, fmax(-1.0, wi[2])));
    size_t n = b->n_in;
    if (n == 1 || theta <= b->theta_in[0])
        return sphere(b, &b->s_out, b->planes + k * b->n_out, wo_r);
    if (theta >= b->theta_in[n - 1])
        return sphere(b, &b->s_out, b->planes + (n - 1) * plane + k * b->n_out, wo_r);
    size_t j = 0;
    while (j + 2 < n && b->theta_in[j + 1] <= theta)
        j++;
    double t = (theta - b->theta_in[j]) / (b->theta_in[j + 1] - b->theta_in[j]);
    double v0 = sphere(b, &b->s_out, b->planes + j * plane + k * b->n_out, wo_r);
    double v1 = sphere(b, &b->s_out, b->planes + (j + 1) * plane + k * b->n_out, wo_r);
    return (1 - t) * v0 + t * v1;
}

double bwr_brdf_eval(bwr_brdf_t *b, const double wi[3], const double wo[3], double lambda)
{
    if (!(wi[2] >= 0) || !(wo[2] >= 0))
        return NAN;
    if (b->bands == 1)
        return at_band(b, wi, wo, 0);
    for (size_t k = 0; k < b->bands; k++)
        b->tmp_band[k] = at_band(b, wi, wo, k);
    bwr_bspline_coefficients(b->tmp_band, b->bands, b->tmp_band);
    double span = b->lambda_last - b->lambda_first;
    double x = span != 0 ? (lambda - b->lambda_first) / span * (double)(b->bands - 1) : 0;
    return bwr_bspline_eval(b->tmp_band, b->bands, x);
}
