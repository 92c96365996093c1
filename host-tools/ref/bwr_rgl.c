/* SPDX-License-Identifier: BSD-2-Clause */
/* RGL measured BRDFs: tensor files, the 2-D warp and its inverse, evaluation. */
#include "bwr_rgl.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RGL_PI 3.14159265358979323846

/* ---- the warp ------------------------------------------------------------ */

void bwr_warp_free(bwr_warp_t *w)
{
    for (unsigned d = 0; d < BWR_WARP_MAX_DIM; d++)
        free(w->param_values[d]);
    free(w->data);
    free(w->marginal_cdf);
    free(w->conditional_cdf);
    memset(w, 0, sizeof *w);
}

int bwr_warp_init(bwr_warp_t *w, uint32_t cols, uint32_t rows, const float *data, unsigned dim,
                  const uint32_t *param_res, const double *const *param_values, int build_cdf)
{
    memset(w, 0, sizeof *w);
    if (cols < 2 || rows < 2 || dim > BWR_WARP_MAX_DIM)
        return -1;
    w->size[0] = cols;
    w->size[1] = rows;
    w->dim = dim;
    w->inv_patch[0] = (double)(cols - 1);
    w->inv_patch[1] = (double)(rows - 1);
    size_t slices = 1;
    for (unsigned d = dim; d-- > 0;) {
        if (param_res[d] < 1)
            goto fail;
        w->param_size[d] = param_res[d];
        w->param_values[d] = malloc(param_res[d] * sizeof(double));
        if (w->param_values[d] == NULL)
            goto fail;
        memcpy(w->param_values[d], param_values[d], param_res[d] * sizeof(double));
        w->param_stride[d] = param_res[d] > 1 ? (uint32_t)slices : 0;
        slices *= param_res[d];
    }
    w->slices = slices;
    size_t n = (size_t)cols * rows;
    w->data = malloc(slices * n * sizeof(double));
    if (w->data == NULL)
        goto fail;
    for (size_t i = 0; i < slices * n; i++)
        w->data[i] = data[i];
    if (!build_cdf)
        return 0;
    w->marginal_cdf = malloc(slices * rows * sizeof(double));
    w->conditional_cdf = malloc(slices * n * sizeof(double));
    if (w->marginal_cdf == NULL || w->conditional_cdf == NULL)
        goto fail;
    for (size_t sl = 0; sl < slices; sl++) {
        double *cc = w->conditional_cdf + sl * n, *mc = w->marginal_cdf + sl * rows;
        double *dd = w->data + sl * n;
        /* conditional CDF of every row (trapezoids) */
        for (uint32_t y = 0; y < rows; y++) {
            size_t i = (size_t)y * cols;
            double sum = 0.0;
            cc[i] = 0.0;
            for (uint32_t x = 0; x + 1 < cols; x++, i++) {
                sum += 0.5 * (dd[i] + dd[i + 1]);
                cc[i + 1] = sum;
            }
        }
        /* marginal CDF over rows */
        double sum = 0.0;
        mc[0] = 0.0;
        for (uint32_t y = 0; y + 1 < rows; y++) {
            sum += 0.5 * (cc[(size_t)(y + 1) * cols - 1] + cc[(size_t)(y + 2) * cols - 1]);
            mc[y + 1] = sum;
        }
        double norm = mc[rows - 1] > 0.0 ? 1.0 / mc[rows - 1] : 0.0;
        for (size_t i = 0; i < n; i++) {
            cc[i] *= norm;
            dd[i] *= norm;
        }
        for (uint32_t y = 0; y < rows; y++)
            mc[y] *= norm;
    }
    return 0;
fail:
    bwr_warp_free(w);
    return -1;
}

/* the largest i in [0, n - 2] with values[i] <= x (0 if none) */
static uint32_t param_interval(const double *values, uint32_t n, double x)
{
    uint32_t lo = 0, hi = n; /* count of values <= x by bisection (sorted) */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (values[mid] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    long i = (long)lo - 1;
    if (i < 0)
        i = 0;
    if (i > (long)n - 2)
        i = (long)n - 2;
    return (uint32_t)i;
}

/* parameter weights; returns the slice offset */
static size_t param_weights(const bwr_warp_t *w, const double *param, double wt[][2])
{
    size_t off = 0;
    for (unsigned d = 0; d < w->dim; d++) {
        if (w->param_size[d] == 1) {
            wt[d][0] = 1.0;
            wt[d][1] = 0.0;
            continue;
        }
        uint32_t i = param_interval(w->param_values[d], w->param_size[d], param[d]);
        double p0 = w->param_values[d][i], p1 = w->param_values[d][i + 1];
        double t = (param[d] - p0) / (p1 - p0);
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        wt[d][0] = 1.0 - t;
        wt[d][1] = t;
        off += (size_t)w->param_stride[d] * i;
    }
    return off;
}

/* arr[i0] interpolated over the parameters (corner sum) */
static double lookup(const bwr_warp_t *w, const double *arr, size_t i0, size_t size,
                     double wt[][2])
{
    double s = 0.0;
    for (unsigned mask = 0; mask < (1u << w->dim); mask++) {
        double f = 1.0;
        size_t i = i0;
        for (unsigned d = 0; d < w->dim; d++) {
            unsigned bit = (mask >> d) & 1u;
            f *= wt[d][bit];
            if (bit)
                i += (size_t)w->param_stride[d] * size;
        }
        if (f != 0.0)
            s += f * arr[i];
    }
    return s;
}

static uint32_t cell(double s, uint32_t size)
{
    if (!(s > 0.0))
        return 0;
    uint32_t c = s >= (double)(size - 2) ? size - 2 : (uint32_t)s;
    return c;
}

double bwr_warp_eval(const bwr_warp_t *w, const double pos[2], const double *param)
{
    double wt[BWR_WARP_MAX_DIM][2];
    size_t so = param_weights(w, param, wt), n = (size_t)w->size[0] * w->size[1];
    double s0 = pos[0] * w->inv_patch[0], s1 = pos[1] * w->inv_patch[1];
    uint32_t c0 = cell(s0, w->size[0]), c1 = cell(s1, w->size[1]);
    double a = s0 - c0, b = s1 - c1;
    size_t i = c0 + (size_t)c1 * w->size[0] + so * n;
    double v00 = lookup(w, w->data, i, n, wt), v10 = lookup(w, w->data, i + 1, n, wt);
    double v01 = lookup(w, w->data, i + w->size[0], n, wt);
    double v11 = lookup(w, w->data, i + w->size[0] + 1, n, wt);
    double v = (1.0 - b) * ((1.0 - a) * v00 + a * v10) + b * ((1.0 - a) * v01 + a * v11);
    return w->marginal_cdf != NULL ? v * w->inv_patch[0] * w->inv_patch[1] : v;
}

/* t in [0, 1] with r0 t + (r1 - r0) t^2 / 2 = u (stable root) */
static double solve_linear_density(double r0, double r1, double u)
{
    double disc = r0 * r0 + 2.0 * u * (r1 - r0);
    double den = r0 + sqrt(disc > 0.0 ? disc : 0.0);
    return den > 0.0 ? 2.0 * u / den : 0.0;
}

void bwr_warp_sample(const bwr_warp_t *w, const double u[2], const double *param, double out[2],
                     double *pdf)
{
    double wt[BWR_WARP_MAX_DIM][2];
    size_t so = param_weights(w, param, wt);
    uint32_t sx = w->size[0], sy = w->size[1];
    size_t n = (size_t)sx * sy;
    double x = u[0], y = u[1];
    /* row: last index with marginal CDF < y */
    size_t mo = so * sy;
    uint32_t row = 0;
    for (uint32_t r = 1; r + 1 < sy; r++)
        if (lookup(w, w->marginal_cdf, mo + r, sy, wt) < y)
            row = r;
    y -= lookup(w, w->marginal_cdf, mo + row, sy, wt);
    size_t off = (size_t)row * sx + so * n;
    double r0 = lookup(w, w->conditional_cdf, off + sx - 1, n, wt);
    double r1 = lookup(w, w->conditional_cdf, off + 2 * (size_t)sx - 1, n, wt);
    y = solve_linear_density(r0, r1, y);
    x *= (1.0 - y) * r0 + y * r1;
    uint32_t col = 0;
    for (uint32_t c = 1; c + 1 < sx; c++) {
        double cv = (1.0 - y) * lookup(w, w->conditional_cdf, off + c, n, wt) +
                    y * lookup(w, w->conditional_cdf, off + sx + c, n, wt);
        if (cv < x)
            col = c;
    }
    x -= (1.0 - y) * lookup(w, w->conditional_cdf, off + col, n, wt) +
         y * lookup(w, w->conditional_cdf, off + sx + col, n, wt);
    off += col;
    double v00 = lookup(w, w->data, off, n, wt), v10 = lookup(w, w->data, off + 1, n, wt);
    double v01 = lookup(w, w->data, off + sx, n, wt), v11 = lookup(w, w->data, off + sx + 1, n, wt);
    double c0 = (1.0 - y) * v00 + y * v01, c1 = (1.0 - y) * v10 + y * v11;
    x = solve_linear_density(c0, c1, x);
    out[0] = ((double)col + x) / w->inv_patch[0];
    out[1] = ((double)row + y) / w->inv_patch[1];
    if (pdf != NULL)
        *pdf = ((1.0 - x) * c0 + x * c1) * w->inv_patch[0] * w->inv_patch[1];
}

void bwr_warp_invert(const bwr_warp_t *w, const double pos[2], const double *param,
                     double out[2], double *pdf)
{
    double wt[BWR_WARP_MAX_DIM][2];
    size_t so = param_weights(w, param, wt);
    uint32_t sx = w->size[0], sy = w->size[1];
    size_t n = (size_t)sx * sy;
    double s0 = pos[0] * w->inv_patch[0], s1 = pos[1] * w->inv_patch[1];
    uint32_t p0 = cell(s0, sx), p1 = cell(s1, sy);
    s0 -= p0;
    s1 -= p1;
    size_t off = p0 + (size_t)p1 * sx + so * n;
    double v00 = lookup(w, w->data, off, n, wt), v10 = lookup(w, w->data, off + 1, n, wt);
    double v01 = lookup(w, w->data, off + sx, n, wt), v11 = lookup(w, w->data, off + sx + 1, n, wt);
    double c0 = (1.0 - s1) * v00 + s1 * v01, c1 = (1.0 - s1) * v10 + s1 * v11;
    double p = (1.0 - s0) * c0 + s0 * c1;
    /* column: the CDF within the patch, plus the CDF up to it */
    s0 *= c0 + 0.5 * s0 * (c1 - c0);
    s0 += (1.0 - s1) * lookup(w, w->conditional_cdf, off, n, wt) +
          s1 * lookup(w, w->conditional_cdf, off + sx, n, wt);
    size_t roff = (size_t)p1 * sx + so * n;
    double r0 = lookup(w, w->conditional_cdf, roff + sx - 1, n, wt);
    double r1 = lookup(w, w->conditional_cdf, roff + 2 * (size_t)sx - 1, n, wt);
    s0 /= (1.0 - s1) * r0 + s1 * r1;
    /* row */
    s1 *= r0 + 0.5 * s1 * (r1 - r0);
    s1 += lookup(w, w->marginal_cdf, p1 + so * sy, sy, wt);
    out[0] = s0;
    out[1] = s1;
    if (pdf != NULL)
        *pdf = p * w->inv_patch[0] * w->inv_patch[1];
}

/* ---- tensor files ---------------------------------------------------------- */

typedef struct {
    char name[64];
    unsigned dtype;
    unsigned rank;
    uint64_t shape[8];
    uint64_t offset;
    size_t count;
} field_t;

static int fail(char *err, size_t len, const char *fmt, ...)
{
    if (err != NULL && len > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, len, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static size_t dtype_size(unsigned t)
{
    static const size_t sz[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};
    return t < sizeof sz / sizeof sz[0] ? sz[t] : 0;
}

static uint64_t rd_u(const unsigned char *p, unsigned bytes)
{
    uint64_t v = 0;
    for (unsigned k = bytes; k-- > 0;)
        v = (v << 8) | p[k];
    return v;
}

static const field_t *find_field(const field_t *f, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(f[i].name, name) == 0)
            return &f[i];
    return NULL;
}

static float rd_f32(const unsigned char *p)
{
    uint32_t u = (uint32_t)rd_u(p, 4);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* the floats of a float32 field */
static float *field_f32(const unsigned char *buf, const field_t *f)
{
    float *v = malloc((f->count ? f->count : 1) * sizeof *v);
    if (v == NULL)
        return NULL;
    for (size_t i = 0; i < f->count; i++)
        v[i] = rd_f32(buf + f->offset + 4 * i);
    return v;
}

void bwr_rgl_free(bwr_rgl_t *b)
{
    free(b->theta_i);
    free(b->phi_i);
    bwr_warp_free(&b->ndf);
    bwr_warp_free(&b->sigma);
    bwr_warp_free(&b->vndf);
    bwr_warp_free(&b->rgb);
    memset(b, 0, sizeof *b);
}

int bwr_rgl_load(bwr_rgl_t *b, const char *path, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return fail(err, errlen, "cannot open '%s'", path);
    if (fseek(fp, 0, SEEK_END) != 0) {
        fclose(fp);
        return fail(err, errlen, "cannot read '%s'", path);
    }
    long len = ftell(fp);
    rewind(fp);
    if (len < 18) {
        fclose(fp);
        return fail(err, errlen, "'%s' is not a tensor file (too short)", path);
    }
    unsigned char *buf = malloc((size_t)len);
    if (buf == NULL || fread(buf, 1, (size_t)len, fp) != (size_t)len) {
        free(buf);
        fclose(fp);
        return fail(err, errlen, "cannot read '%s'", path);
    }
    fclose(fp);
    size_t L = (size_t)len;
    field_t fields[32];
    size_t nf = 0;
    int rc = -1;
    float *tmp[8] = {0};
    if (memcmp(buf, "tensor_file\0", 12) != 0 || buf[12] != 1 || buf[13] != 0) {
        fail(err, errlen, "'%s': not a version 1.0 tensor file", path);
        goto done;
    }
    uint32_t count = (uint32_t)rd_u(buf + 14, 4);
    size_t pos = 18;
    if (count > 32) {
        fail(err, errlen, "'%s': too many fields (%u)", path, count);
        goto done;
    }
    for (uint32_t k = 0; k < count; k++) {
        field_t *f = &fields[nf];
        if (pos + 2 > L)
            goto trunc;
        size_t nl = (size_t)rd_u(buf + pos, 2);
        pos += 2;
        if (pos + nl + 2 + 1 + 8 > L || nl >= sizeof f->name)
            goto trunc;
        memcpy(f->name, buf + pos, nl);
        f->name[nl] = '\0';
        pos += nl;
        f->rank = (unsigned)rd_u(buf + pos, 2);
        f->dtype = buf[pos + 2];
        f->offset = rd_u(buf + pos + 3, 8);
        pos += 11;
        if (f->rank > 8 || pos + 8 * (size_t)f->rank > L || dtype_size(f->dtype) == 0) {
            fail(err, errlen, "'%s': bad field '%s'", path, f->name);
            goto done;
        }
        f->count = 1;
        for (unsigned r = 0; r < f->rank; r++) {
            f->shape[r] = rd_u(buf + pos, 8);
            pos += 8;
            if (f->shape[r] > (1u << 28) || f->count * f->shape[r] > (1u << 28)) {
                fail(err, errlen, "'%s': field '%s' too large", path, f->name);
                goto done;
            }
            f->count *= (size_t)f->shape[r];
        }
        if (f->offset > L || f->count * dtype_size(f->dtype) > L - f->offset) {
            fail(err, errlen, "'%s': field '%s' lies outside the file", path, f->name);
            goto done;
        }
        nf++;
    }
    const field_t *th = find_field(fields, nf, "theta_i"), *ph = find_field(fields, nf, "phi_i");
    const field_t *nd = find_field(fields, nf, "ndf"), *sg = find_field(fields, nf, "sigma");
    const field_t *vn = find_field(fields, nf, "vndf"), *rg = find_field(fields, nf, "rgb");
    const field_t *jc = find_field(fields, nf, "jacobian");
    const field_t *ds = find_field(fields, nf, "description");
    if (!th || !ph || !nd || !sg || !vn || !rg || !jc) {
        fail(err, errlen, "'%s': not an RGB RGL file (needs theta_i, phi_i, ndf, sigma, vndf, "
                          "rgb, jacobian)", path);
        goto done;
    }
    if (th->dtype != 10 || ph->dtype != 10 || nd->dtype != 10 || sg->dtype != 10 ||
        vn->dtype != 10 || rg->dtype != 10 || jc->dtype != 1 || th->rank != 1 || ph->rank != 1 ||
        nd->rank != 2 || sg->rank != 2 || vn->rank != 4 || rg->rank != 5 || jc->count != 1 ||
        vn->shape[0] != ph->shape[0] || vn->shape[1] != th->shape[0] ||
        rg->shape[0] != ph->shape[0] || rg->shape[1] != th->shape[0] || rg->shape[2] != 3 ||
        th->shape[0] < 2 || nd->shape[0] < 2 || nd->shape[1] < 2 || sg->shape[0] < 2 ||
        sg->shape[1] < 2 || vn->shape[2] < 2 || vn->shape[3] < 2 || rg->shape[3] < 2 ||
        rg->shape[4] < 2) {
        fail(err, errlen, "'%s': unexpected field types or shapes", path);
        goto done;
    }
    if (ds != NULL && ds->dtype == 1) {
        size_t n = ds->count < sizeof b->description - 1 ? ds->count : sizeof b->description - 1;
        memcpy(b->description, buf + ds->offset, n);
        b->description[n] = '\0';
    }
    b->n_theta = (size_t)th->shape[0];
    b->n_phi = (size_t)ph->shape[0];
    b->theta_i = malloc(b->n_theta * sizeof(double));
    b->phi_i = malloc(b->n_phi * sizeof(double));
    if (b->theta_i == NULL || b->phi_i == NULL)
        goto oom;
    for (size_t i = 0; i < b->n_theta; i++)
        b->theta_i[i] = rd_f32(buf + th->offset + 4 * i);
    for (size_t i = 0; i < b->n_phi; i++)
        b->phi_i[i] = rd_f32(buf + ph->offset + 4 * i);
    b->isotropic = b->n_phi <= 2;
    b->jacobian = buf[jc->offset] != 0;
    tmp[0] = field_f32(buf, nd);
    tmp[1] = field_f32(buf, sg);
    tmp[2] = field_f32(buf, vn);
    tmp[3] = field_f32(buf, rg);
    if (!tmp[0] || !tmp[1] || !tmp[2] || !tmp[3])
        goto oom;
    static const double channels[3] = {0.0, 1.0, 2.0};
    uint32_t pr[3] = {(uint32_t)b->n_phi, (uint32_t)b->n_theta, 3};
    const double *pv[3] = {b->phi_i, b->theta_i, channels};
    if (bwr_warp_init(&b->ndf, (uint32_t)nd->shape[1], (uint32_t)nd->shape[0], tmp[0], 0, NULL,
                      NULL, 0) != 0 ||
        bwr_warp_init(&b->sigma, (uint32_t)sg->shape[1], (uint32_t)sg->shape[0], tmp[1], 0, NULL,
                      NULL, 0) != 0 ||
        bwr_warp_init(&b->vndf, (uint32_t)vn->shape[3], (uint32_t)vn->shape[2], tmp[2], 2, pr, pv,
                      1) != 0 ||
        bwr_warp_init(&b->rgb, (uint32_t)rg->shape[4], (uint32_t)rg->shape[3], tmp[3], 3, pr, pv,
                      0) != 0)
        goto oom;
    rc = 0;
    goto done;
trunc:
    fail(err, errlen, "'%s': truncated field table", path);
    goto done;
oom:
    fail(err, errlen, "out of memory reading '%s'", path);
done:
    for (int k = 0; k < 8; k++)
        free(tmp[k]);
    free(buf);
    if (rc != 0)
        bwr_rgl_free(b);
    return rc;
}

static double theta2u(double theta)
{
    return sqrt(theta * (2.0 / RGL_PI));
}

static double phi2u(double phi)
{
    return (phi + RGL_PI) / (2.0 * RGL_PI);
}

void bwr_rgl_eval_cos(const bwr_rgl_t *b, const double wi[3], const double wo[3], double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!(wi[2] > 0.0 && wo[2] > 0.0))
        return;
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double nrm = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    if (!(nrm > 0.0))
        return;
    double s = 1.0 / sqrt(nrm), wm[3] = {h[0] * s, h[1] * s, h[2] * s};
    double ti = acos(wi[2] > 1.0 ? 1.0 : wi[2]), pi_ = atan2(wi[1], wi[0]);
    double tm = acos(wm[2] > 1.0 ? 1.0 : wm[2]), pm = atan2(wm[1], wm[0]);
    double u_wi[2] = {theta2u(ti), phi2u(pi_)};
    double u_wm[2] = {theta2u(tm), phi2u(b->isotropic ? pm - pi_ : pm)};
    u_wm[1] -= floor(u_wm[1]);
    double params[3] = {pi_, ti, 0.0}, sample[2];
    bwr_warp_invert(&b->vndf, u_wm, params, sample, NULL);
    for (int c = 0; c < 3; c++) {
        params[2] = (double)c;
        rgb[c] = bwr_warp_eval(&b->rgb, sample, params);
    }
    if (b->jacobian) {
        double k = bwr_warp_eval(&b->ndf, u_wm, params) / (4.0 * bwr_warp_eval(&b->sigma, u_wi,
                                                                                 params));
        for (int c = 0; c < 3; c++)
            rgb[c] *= k;
    }
}

void bwr_rgl_eval(const bwr_rgl_t *b, const double wi[3], const double wo[3], double rgb[3])
{
    bwr_rgl_eval_cos(b, wi, wo, rgb);
    if (wo[2] > 0.0)
        for (int c = 0; c < 3; c++)
            rgb[c] /= wo[2];
}
