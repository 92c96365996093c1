/* SPDX-License-Identifier: BSD-2-Clause */
/* A sampled or decoded BRDF as a function (brdf_eval.h). */
#include "brdf_eval.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_meta.h"
#include "geodesic.h"

#define E_PI 3.14159265358979323846

void bwh_brdf_data_free(bwh_brdf_data_t *d)
{
    free(d->theta_in);
    free(d->planes);
    free(d->mean);
    if (d->s_out.n)
        bwh_sphere_interp_free(&d->s_out);
    memset(d, 0, sizeof *d);
}

int bwh_brdf_data_init(bwh_brdf_data_t *d, const bw_dims_t *dims, const float *values,
                       const double *theta_in_deg, double lambda_first, double lambda_last)
{
    memset(d, 0, sizeof *d);
    if (dims->shape != BW_SHAPE_REFLECTANCE && dims->shape != BW_SHAPE_BRDF_ISO &&
        dims->shape != BW_SHAPE_BRDF_FULL)
        return bwh_fail("not a BRDF or a reflectance (shape %u)", dims->shape);
    if (dims->level_out > BWH_GRID_MAX_LEVEL || dims->bands < 1 || dims->n_in < 1 ||
        dims->n_out != bwh_grid_count(dims->level_out))
        return bwh_fail("inconsistent BRDF dimensions");
    if (dims->shape == BW_SHAPE_BRDF_FULL &&
        (dims->level_in > BWH_GRID_MAX_LEVEL || dims->n_in != bwh_grid_count(dims->level_in)))
        return bwh_fail("inconsistent incoming level");
    d->shape = dims->shape;
    d->level_out = dims->level_out;
    d->level_in = dims->level_in;
    d->n_in = dims->shape == BW_SHAPE_REFLECTANCE ? 1 : dims->n_in;
    d->n_out = dims->n_out;
    d->bands = dims->bands;
    d->lambda_first = lambda_first;
    d->lambda_last = lambda_last;
    size_t n = d->n_in * d->n_out;
    d->planes = malloc(n * d->bands * sizeof *d->planes);
    d->mean = malloc(n * sizeof *d->mean);
    if (!d->planes || !d->mean || bwh_sphere_interp_init(&d->s_out, d->level_out) != 0) {
        bwh_brdf_data_free(d);
        return bwh_fail("out of memory");
    }
    for (size_t i = 0; i < d->n_in; i++)
        for (size_t o = 0; o < d->n_out; o++) {
            double m = 0.0;
            for (size_t k = 0; k < d->bands; k++) {
                double v = values[(i * d->n_out + o) * d->bands + k];
                d->planes[(i * d->bands + k) * d->n_out + o] = v;
                m += v;
            }
            d->mean[i * d->n_out + o] = m / (double)d->bands;
        }
    if (d->shape == BW_SHAPE_BRDF_ISO) {
        d->theta_in = malloc(d->n_in * sizeof *d->theta_in);
        if (!d->theta_in) {
            bwh_brdf_data_free(d);
            return bwh_fail("out of memory");
        }
        for (size_t i = 0; i < d->n_in; i++) {
            double deg = theta_in_deg ? theta_in_deg[i] : (i + 0.5) * 90.0 / (double)d->n_in;
            d->theta_in[i] = deg * E_PI / 180.0;
            if (!(deg >= 0.0 && deg <= 90.0) || (i && !(d->theta_in[i] > d->theta_in[i - 1]))) {
                bwh_brdf_data_free(d);
                return bwh_fail("incoming angles must ascend within [0, 90] degrees");
            }
        }
    }
    return 0;
}

int bwh_brdf_data_load(bwh_brdf_data_t *d, const char *path)
{
    uint8_t *buf;
    size_t len;
    memset(d, 0, sizeof *d);
    if (bwh_read_file(path, &buf, &len) != 0)
        return -1;
    bw_header_t h;
    int32_t *samples;
    float *values;
    int rc = bwh_decode(buf, len, &h, &samples, &values);
    bwh_meta_t meta;
    bwh_meta_init(&meta);
    if (rc == 0)
        rc = bwh_meta_of_payload(buf, len, &h, &meta);
    free(buf);
    if (rc != 0) {
        free(samples);
        free(values);
        return bwh_fail("%s: %s", path, bwh_last_error());
    }
    free(samples);
    /* the measured incidence angles and wavelength range the payload
     * carries (docs/FORMAT.md, Metadata), else the defaults */
    double *theta_deg = NULL, lf = 0.0, ll = 0.0;
    if (h.dims.shape == BW_SHAPE_BRDF_ISO && meta.incidence.n == h.dims.n_in) {
        theta_deg = malloc(meta.incidence.n * sizeof *theta_deg);
        if (!theta_deg) {
            free(values);
            bwh_meta_free(&meta);
            return bwh_fail("out of memory");
        }
        for (size_t i = 0; i < meta.incidence.n; i++)
            theta_deg[i] = meta.inc_unit == BWH_ANGLE_RAD ? meta.incidence.v[i] * 180.0 / E_PI
                                                          : meta.incidence.v[i];
    }
    if (meta.wavelengths.n == h.dims.bands && meta.wl_unit == BWH_WL_NM && h.dims.bands > 1) {
        lf = meta.wavelengths.v[0];
        ll = meta.wavelengths.v[h.dims.bands - 1];
    }
    rc = bwh_brdf_data_init(d, &h.dims, values, theta_deg, lf, ll);
    free(theta_deg);
    free(values);
    bwh_meta_free(&meta);
    if (rc != 0)
        return bwh_fail("%s: %s", path, bwh_last_error());
    return 0;
}

/* the plane (values over the outgoing grid) selection: up to two planes
 * with weights, and wo in the frame of the tables */
static int locate_in(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                     size_t pl[2], double w[2], double wo_r[3])
{
    memcpy(wo_r, wo, 3 * sizeof *wo_r);
    pl[0] = 0;
    w[0] = 1.0;
    if (d->shape == BW_SHAPE_REFLECTANCE)
        return 1;
    if (d->shape == BW_SHAPE_BRDF_FULL) {
        long k = bwh_grid_locate(d->level_in, wi);
        pl[0] = k < 0 ? 0 : (size_t)k;
        return 1;
    }
    double r = hypot(wi[0], wi[1]), c = 1.0, s = 0.0;
    if (r > 1e-300) {
        c = wi[0] / r;
        s = wi[1] / r;
    }
    wo_r[0] = c * wo[0] + s * wo[1];
    wo_r[1] = -s * wo[0] + c * wo[1];
    double th = atan2(r, wi[2]);
    size_t n = d->n_in;
    if (n == 1 || th <= d->theta_in[0])
        return 1;
    if (th >= d->theta_in[n - 1]) {
        pl[0] = n - 1;
        return 1;
    }
    size_t j = 0;
    while (j + 2 < n && d->theta_in[j + 1] <= th)
        j++;
    double t = (th - d->theta_in[j]) / (d->theta_in[j + 1] - d->theta_in[j]);
    pl[0] = j;
    w[0] = 1.0 - t;
    pl[1] = j + 1;
    w[1] = t;
    return 2;
}

static double interp(const bwh_brdf_data_t *d, const double *plane_of_in0, size_t stride,
                     const double wi[3], const double wo[3])
{
    if (!(wi[2] >= 0.0) || !(wo[2] >= 0.0))
        return NAN;
    size_t pl[2];
    double w[2], wo_r[3];
    int n = locate_in(d, wi, wo, pl, w, wo_r);
    double v = 0.0;
    for (int i = 0; i < n; i++)
        v += w[i] * bwh_sphere_interp(&d->s_out, plane_of_in0 + pl[i] * stride, wo_r);
    return v;
}

double bwh_brdf_data_band(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                          size_t k)
{
    if (k >= d->bands)
        return NAN;
    return interp(d, d->planes + k * d->n_out, d->bands * d->n_out, wi, wo);
}

double bwh_brdf_data_mean(const bwh_brdf_data_t *d, const double wi[3], const double wo[3])
{
    return interp(d, d->mean, d->n_out, wi, wo);
}

double bwh_brdf_data_mean_cb(void *ctx, const double wi[3], const double wo[3])
{
    return bwh_brdf_data_mean((const bwh_brdf_data_t *)ctx, wi, wo);
}

double bwh_brdf_data_band_cb(void *ctx, const double wi[3], const double wo[3])
{
    const bwh_brdf_band_t *b = ctx;
    return bwh_brdf_data_band(b->data, wi, wo, b->band);
}

double bwh_brdf_data_eval(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                          double lambda, double *work)
{
    if (d->bands == 1)
        return bwh_brdf_data_band(d, wi, wo, 0);
    for (size_t k = 0; k < d->bands; k++)
        work[k] = bwh_brdf_data_band(d, wi, wo, k);
    if (isnan(work[0]))
        return NAN;
    bwh_bspline_coefficients(work, d->bands, work);
    double span = d->lambda_last - d->lambda_first;
    double x = span != 0.0 ? (lambda - d->lambda_first) / span * (double)(d->bands - 1) : 0.0;
    return bwh_bspline_eval(work, d->bands, x);
}
