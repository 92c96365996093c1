/* SPDX-License-Identifier: BSD-2-Clause */
/* A sampled or decoded BRDF as a function (brdf_eval.h). */
#include "brdf_eval.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_ext.h"
#include "bwh_file.h"
#include "bwh_meta.h"
#include "geodesic.h"

#define E_PI 3.14159265358979323846

void bwh_brdf_data_free(bwh_brdf_data_t *d)
{
    free(d->theta_in);
    if (d->mean != d->planes) /* one band: the same table */
        free(d->mean);
    free(d->planes);
    free(d->row_of);
    if (d->s_out.n)
        bwh_sphere_interp_free(&d->s_out);
    memset(d, 0, sizeof *d);
}

/* The incoming angles of an isotropic BRDF in radians (theta_in_deg NULL:
 * the defaults), checked. */
static int iso_angles(bwh_brdf_data_t *d, const double *theta_in_deg)
{
    d->theta_in = malloc(d->n_in * sizeof *d->theta_in);
    if (!d->theta_in)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < d->n_in; i++) {
        double deg = theta_in_deg ? theta_in_deg[i] : (i + 0.5) * 90.0 / (double)d->n_in;
        d->theta_in[i] = deg * E_PI / 180.0;
        if (!(deg >= 0.0 && deg <= 90.0) || (i && !(d->theta_in[i] > d->theta_in[i - 1])))
            return bwh_fail("incoming angles must ascend within [0, 90] degrees");
    }
    return 0;
}

/* The fields of dims, checked; no tables yet. */
static int data_dims(bwh_brdf_data_t *d, const bw_dims_t *dims, double lambda_first,
                     double lambda_last)
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
    return 0;
}

/* The tables of `rows` rows of values [rows][n_out][bands]. */
static int data_tables(bwh_brdf_data_t *d, const float *values, size_t rows)
{
    size_t n = rows * d->n_out;
    d->planes = malloc((n ? n : 1) * d->bands * sizeof *d->planes);
    if (!d->planes || bwh_sphere_interp_init(&d->s_out, d->level_out) != 0)
        return bwh_fail("out of memory");
    if (d->bands == 1) { /* the mean over one band is the band */
        for (size_t t = 0; t < n; t++)
            d->planes[t] = values[t];
        d->mean = d->planes;
        return 0;
    }
    d->mean = malloc((n ? n : 1) * sizeof *d->mean);
    if (!d->mean)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < rows; i++)
        for (size_t o = 0; o < d->n_out; o++) {
            double m = 0.0;
            for (size_t k = 0; k < d->bands; k++) {
                double v = values[(i * d->n_out + o) * d->bands + k];
                d->planes[(i * d->bands + k) * d->n_out + o] = v;
                m += v;
            }
            d->mean[i * d->n_out + o] = m / (double)d->bands;
        }
    return 0;
}

int bwh_brdf_data_init(bwh_brdf_data_t *d, const bw_dims_t *dims, const float *values,
                       const double *theta_in_deg, double lambda_first, double lambda_last)
{
    if (data_dims(d, dims, lambda_first, lambda_last) != 0)
        return -1;
    if (data_tables(d, values, d->n_in) != 0 ||
        (d->shape == BW_SHAPE_BRDF_ISO && iso_angles(d, theta_in_deg) != 0)) {
        bwh_brdf_data_free(d);
        return -1;
    }
    return 0;
}

/* The incidences of an isotropic BRDF about wi: up to two rows and their
 * weights; wo turned into the frame of the tables. */
static int iso_rows(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                    size_t pl[2], double w[2], double wo_r[3])
{
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
    return iso_rows(d, wi, wo, pl, w, wo_r);
}

int bwh_brdf_data_load(bwh_brdf_data_t *d, const char *path)
{
    uint8_t *buf;
    size_t len;
    memset(d, 0, sizeof *d);
    if (bwh_read_file(path, &buf, &len) != 0)
        return -1;
    int rc = bwh_brdf_data_from_payload(d, buf, len, NULL, 0);
    free(buf);
    return rc != 0 ? bwh_fail("%s: %s", path, bwh_last_error()) : 0;
}

/* The rows f at wi[n] reads, marked in rows[n_in] (d: dims and angles);
 * returns how many, or stops once more than `most`. */
static size_t rows_for(const bwh_brdf_data_t *d, const double (*wi)[3], size_t n, uint8_t *rows,
                       size_t most)
{
    size_t count = 0;
    memset(rows, 0, d->n_in);
    for (size_t j = 0; j < n && count <= most; j++) {
        size_t pl[2];
        double w[2], wo_r[3], up[3] = {0, 0, 1};
        int k = locate_in(d, wi[j], up, pl, w, wo_r);
        for (int i = 0; i < k; i++) {
            count += !rows[pl[i]];
            rows[pl[i]] = 1;
        }
    }
    return count;
}

int bwh_brdf_data_from_payload(bwh_brdf_data_t *d, const uint8_t *p, size_t len,
                               const double (*wi)[3], size_t n)
{
    memset(d, 0, sizeof *d);
    /* in segments, the table's CRC vouches for the header: the rows read
     * check their own segments' */
    bw_header_t h;
    int st = bwh_header_salvage(p, len, &h);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    bwh_meta_t meta;
    bwh_meta_init(&meta);
    if (bwh_meta_of_payload(p, len, &h, &meta) != 0)
        return -1;
    /* the measured incidence angles and wavelength range the payload
     * carries (docs/FORMAT.md, Metadata), else the defaults */
    double *theta_deg = NULL, lf = 0.0, ll = 0.0;
    float *values = NULL;
    int rc = -1;
    if (h.dims.shape == BW_SHAPE_BRDF_ISO && meta.incidence.n == h.dims.n_in) {
        theta_deg = malloc(meta.incidence.n * sizeof *theta_deg);
        if (!theta_deg) {
            bwh_fail("out of memory");
            goto out;
        }
        for (size_t i = 0; i < meta.incidence.n; i++)
            theta_deg[i] = meta.inc_unit == BWH_ANGLE_RAD ? meta.incidence.v[i] * 180.0 / E_PI
                                                          : meta.incidence.v[i];
    }
    if (meta.wavelengths.n == h.dims.bands && meta.wl_unit == BWH_WL_NM && h.dims.bands > 1) {
        lf = meta.wavelengths.v[0];
        ll = meta.wavelengths.v[h.dims.bands - 1];
    }
    if (data_dims(d, &h.dims, lf, ll) != 0 ||
        (d->shape == BW_SHAPE_BRDF_ISO && iso_angles(d, theta_deg) != 0))
        goto out;
    const uint8_t *xd;
    uint32_t xl;
    /* rows alone: not where every row depends on the others, nor with a
     * float tail (record 0x01), nor for a reflectance (one row), nor for
     * more than half the rows */
    bool whole = !wi || d->shape == BW_SHAPE_REFLECTANCE || (h.flags & BW_FLAG_RECIPROCAL) ||
                 bwh_ext_find(p, &h, BW_EXT_FLOAT_EXACT, &xd, &xl) == 1;
    bw_header_t hd;
    uint8_t *rows = whole ? NULL : malloc(d->n_in);
    uint32_t k = 0;
    if (!whole && !rows) {
        bwh_fail("out of memory");
        goto out;
    }
    /* more than half the rows: the whole decode is as quick */
    if (!whole && rows_for(d, wi, n, rows, d->n_in / 2u) > d->n_in / 2u)
        whole = true;
    if (whole) {
        free(rows);
        int32_t *samples = NULL;
        if (bwh_decode(p, len, &hd, &samples, &values) != 0)
            goto out;
        free(samples);
        rc = data_tables(d, values, d->n_in);
        goto out;
    }
    d->row_of = malloc(d->n_in * sizeof *d->row_of);
    if (!d->row_of) {
        free(rows);
        bwh_fail("out of memory");
        goto out;
    }
    k = 0;
    for (size_t i = 0; i < d->n_in; i++)
        d->row_of[i] = rows[i] ? k++ : UINT32_MAX;
    bw_dims_t sub;
    rc = k ? bwh_decode_rows(p, len, rows, &hd, &sub, NULL, &values) : 0;
    free(rows);
    if (rc == 0)
        rc = data_tables(d, values, k);
out:
    free(values);
    free(theta_deg);
    bwh_meta_free(&meta);
    if (rc != 0)
        bwh_brdf_data_free(d);
    return rc;
}

int bwh_brdf_data_eval_many(const bwh_brdf_data_t *d, size_t n, const double *wi,
                            const double *wo, const double *lambda, long band, double *out)
{
    if (band >= 0 && (size_t)band >= d->bands)
        return bwh_fail("band %ld is past the last (%zu)", band, d->bands - 1);
    double *work = lambda ? malloc(d->bands * sizeof *work) : NULL;
    if (lambda && !work)
        return bwh_fail("out of memory");
    for (size_t j = 0; j < n; j++)
        out[j] = lambda      ? bwh_brdf_data_eval(d, wi + 3 * j, wo + 3 * j, lambda[j], work)
                 : band >= 0 ? bwh_brdf_data_band(d, wi + 3 * j, wo + 3 * j, (size_t)band)
                             : bwh_brdf_data_mean(d, wi + 3 * j, wo + 3 * j);
    free(work);
    return 0;
}

int bwh_payload_eval(const uint8_t *p, size_t len, size_t n, const double *wi, const double *wo,
                     const double *lambda, long band, double *out)
{
    bwh_brdf_data_t d;
    if (bwh_brdf_data_from_payload(&d, p, len, (const double(*)[3])wi, n) != 0)
        return -1;
    int rc = bwh_brdf_data_eval_many(&d, n, wi, wo, lambda, band, out);
    bwh_brdf_data_free(&d);
    return rc;
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
    for (int i = 0; i < n; i++) {
        size_t r = d->row_of ? d->row_of[pl[i]] : pl[i];
        if (r == UINT32_MAX)
            return NAN;
        v += w[i] * bwh_sphere_interp(&d->s_out, plane_of_in0 + r * stride, wo_r);
    }
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
