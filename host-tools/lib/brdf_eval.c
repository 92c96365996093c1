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

/* What f reads besides the values [rows][n_out][bands] of `rows` rows: the
 * outgoing grid's interpolation and, with more than one band, the mean over
 * the bands. */
static int interp_tables(bwh_brdf_data_t *d, const float *values, size_t rows)
{
    size_t n = rows * d->n_out;
    if (bwh_sphere_interp_init(&d->s_out, d->level_out) != 0)
        return -1;
    if (d->bands == 1)
        return 0;
    d->mean = malloc((n ? n : 1) * sizeof *d->mean);
    if (!d->mean)
        return bwh_fail("out of memory");
    for (size_t t = 0; t < n; t++) {
        double m = 0.0;
        for (size_t k = 0; k < d->bands; k++)
            m += values[t * d->bands + k];
        d->mean[t] = m / (double)d->bands;
    }
    return 0;
}

/* The tables of `rows` rows of values [rows][n_out][bands]. */
static int data_tables(bwh_brdf_data_t *d, const float *values, size_t rows)
{
    size_t n = rows * d->n_out;
    d->planes = malloc((n ? n : 1) * d->bands * sizeof *d->planes);
    if (!d->planes)
        return bwh_fail("out of memory");
    if (interp_tables(d, values, rows) != 0)
        return -1;
    if (d->bands == 1) { /* the mean over one band is the band */
        for (size_t t = 0; t < n; t++)
            d->planes[t] = values[t];
        d->mean = d->planes;
        return 0;
    }
    for (size_t i = 0; i < rows; i++)
        for (size_t o = 0; o < d->n_out; o++)
            for (size_t k = 0; k < d->bands; k++)
                d->planes[(i * d->bands + k) * d->n_out + o] =
                    values[(i * d->n_out + o) * d->bands + k];
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

/* d's dimensions, angles and rows, and the values of the rows f at wi[n]
 * reads (wi NULL: all), [*rows][n_out][bands] in *values (to free; NULL
 * when no row is read); no tables yet. */
static int load_rows(bwh_brdf_data_t *d, const uint8_t *p, size_t len, const double (*wi)[3],
                     size_t n, float **values, size_t *nrows)
{
    memset(d, 0, sizeof *d);
    *values = NULL;
    *nrows = 0;
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
        if (bwh_decode(p, len, &hd, &samples, values) != 0)
            goto out;
        free(samples);
        *nrows = d->n_in;
        rc = 0;
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
    rc = k ? bwh_decode_rows(p, len, rows, &hd, &sub, NULL, values) : 0;
    free(rows);
    *nrows = k;
out:
    free(theta_deg);
    bwh_meta_free(&meta);
    if (rc != 0) {
        free(*values);
        *values = NULL;
        bwh_brdf_data_free(d);
    }
    return rc;
}

int bwh_brdf_data_from_payload(bwh_brdf_data_t *d, const uint8_t *p, size_t len,
                               const double (*wi)[3], size_t n)
{
    float *values;
    size_t rows;
    if (load_rows(d, p, len, wi, n, &values, &rows) != 0)
        return -1;
    int rc = data_tables(d, values, rows);
    free(values);
    if (rc != 0)
        bwh_brdf_data_free(d);
    return rc;
}

/* Where f at (wi, wo) reads: up to two rows r with weights w, and the
 * point of the outgoing grid; 0 where f is NAN (a direction below the
 * horizon, a row not decoded). */
static int where(const bwh_brdf_data_t *d, const double wi[3], const double wo[3], size_t r[2],
                 double w[2], bwh_sphere_at_t *at)
{
    if (!(wi[2] >= 0.0) || !(wo[2] >= 0.0))
        return 0;
    size_t pl[2];
    double wo_r[3];
    int n = locate_in(d, wi, wo, pl, w, wo_r);
    for (int i = 0; i < n; i++) {
        r[i] = d->row_of ? d->row_of[pl[i]] : pl[i];
        if (r[i] == UINT32_MAX)
            return 0;
    }
    return bwh_sphere_locate(&d->s_out, wo_r, at) != 0 ? 0 : n;
}

/* The value there of band k, or of the band mean (k = bands): from d's
 * tables, or (fv not NULL) from the decoded values fv [rows][n_out][bands]
 * of d's rows with, for more than one band, d->mean (bwh_payload_eval). */
static double value(const bwh_brdf_data_t *d, const float *fv, int n, const size_t r[2],
                    const double w[2], const bwh_sphere_at_t *at, size_t k)
{
    const bwh_sphere_interp_t *s = &d->s_out;
    double v = 0.0;
    for (int i = 0; i < n; i++) {
        double x;
        if (k == d->bands)
            x = d->mean ? bwh_sphere_value(s, at, d->mean + r[i] * d->n_out)
                        : bwh_sphere_value_f32(s, at, fv + r[i] * d->n_out, 1); /* one band */
        else
            x = fv ? bwh_sphere_value_f32(s, at, fv + r[i] * d->n_out * d->bands + k, d->bands)
                   : bwh_sphere_value(s, at, d->planes + (r[i] * d->bands + k) * d->n_out);
        v += w[i] * x;
    }
    return v;
}

static double band_of(const bwh_brdf_data_t *d, const float *fv, const double wi[3],
                      const double wo[3], size_t k)
{
    size_t r[2];
    double w[2];
    bwh_sphere_at_t at;
    int n = k < d->bands ? where(d, wi, wo, r, w, &at) : 0;
    return n ? value(d, fv, n, r, w, &at, k) : NAN;
}

static double mean_of(const bwh_brdf_data_t *d, const float *fv, const double wi[3],
                      const double wo[3])
{
    size_t r[2];
    double w[2];
    bwh_sphere_at_t at;
    int n = where(d, wi, wo, r, w, &at);
    return n ? value(d, fv, n, r, w, &at, d->bands) : NAN;
}

/* f at lambda: every band's value (located once), then their B-spline */
static double eval_of(const bwh_brdf_data_t *d, const float *fv, const double wi[3],
                      const double wo[3], double lambda, double *work)
{
    size_t r[2];
    double w[2];
    bwh_sphere_at_t at;
    int n = where(d, wi, wo, r, w, &at);
    if (!n)
        return NAN;
    if (d->bands == 1)
        return value(d, fv, n, r, w, &at, 0);
    for (size_t k = 0; k < d->bands; k++)
        work[k] = value(d, fv, n, r, w, &at, k);
    if (isnan(work[0]))
        return NAN;
    bwh_bspline_coefficients(work, d->bands, work);
    double span = d->lambda_last - d->lambda_first;
    double x = span != 0.0 ? (lambda - d->lambda_first) / span * (double)(d->bands - 1) : 0.0;
    return bwh_bspline_eval(work, d->bands, x);
}

static int eval_many(const bwh_brdf_data_t *d, const float *fv, size_t n, const double *wi,
                     const double *wo, const double *lambda, long band, double *out)
{
    if (band >= 0 && (size_t)band >= d->bands)
        return bwh_fail("band %ld is past the last (%zu)", band, d->bands - 1);
    double *work = lambda ? malloc(d->bands * sizeof *work) : NULL;
    if (lambda && !work)
        return bwh_fail("out of memory");
    for (size_t j = 0; j < n; j++)
        out[j] = lambda      ? eval_of(d, fv, wi + 3 * j, wo + 3 * j, lambda[j], work)
                 : band >= 0 ? band_of(d, fv, wi + 3 * j, wo + 3 * j, (size_t)band)
                             : mean_of(d, fv, wi + 3 * j, wo + 3 * j);
    free(work);
    return 0;
}

int bwh_brdf_data_eval_many(const bwh_brdf_data_t *d, size_t n, const double *wi,
                            const double *wo, const double *lambda, long band, double *out)
{
    return eval_many(d, NULL, n, wi, wo, lambda, band, out);
}

/* Straight from the decoded values of the rows the pairs read: no tables
 * but the band mean's (more than one band), the same values to the bit. */
int bwh_payload_eval(const uint8_t *p, size_t len, size_t n, const double *wi, const double *wo,
                     const double *lambda, long band, double *out)
{
    bwh_brdf_data_t d;
    float *values;
    size_t rows;
    if (load_rows(&d, p, len, (const double(*)[3])wi, n, &values, &rows) != 0)
        return -1;
    int rc = interp_tables(&d, values, rows);
    if (rc == 0)
        rc = eval_many(&d, values, n, wi, wo, lambda, band, out);
    free(values);
    bwh_brdf_data_free(&d);
    return rc;
}

double bwh_brdf_data_band(const bwh_brdf_data_t *d, const double wi[3], const double wo[3],
                          size_t k)
{
    return band_of(d, NULL, wi, wo, k);
}

double bwh_brdf_data_mean(const bwh_brdf_data_t *d, const double wi[3], const double wo[3])
{
    return mean_of(d, NULL, wi, wo);
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
    return eval_of(d, NULL, wi, wo, lambda, work);
}
