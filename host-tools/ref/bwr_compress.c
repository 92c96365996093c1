/* SPDX-License-Identifier: BSD-2-Clause */
/* Thresholds per space, keep-count selection, error metrics, best basis. */
#include "bwr_compress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_desc(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a < b) - (a > b);
}

/* 1 if coefficient (vector v, spectral index k) is a scaling coefficient in
 * every transformed space */
static int is_coarse(const bwr_model_t *m, size_t v, size_t k)
{
    size_t i = v / m->n_out, o = v % m->n_out;
    if (m->have_in && i >= 4)
        return 0;
    if (m->have_in1d && i >= m->dwt_in.len[m->dwt_in.levels])
        return 0;
    if (m->have_out && o >= 4)
        return 0;
    if (m->have_spec && k >= m->dwt.len[m->dwt.levels])
        return 0;
    return 1;
}

/* the factor that turns |c| into the compared magnitude (infinite for the
 * coarse coefficients when they are always kept) */
static double weight(const bwr_model_t *m, const bwr_thresholds_t *th, size_t v, size_t k)
{
    if (th->keep_coarse && is_coarse(m, v, k))
        return INFINITY;
    if (th->raw)
        return 1.0;
    return sqrt(bwr_model_norm2(m, v / m->n_out, v % m->n_out, k));
}

/* Keeps the `keep` largest weighted magnitudes among the non-zero
 * coefficients out[q0 .. q1) (ties by index); *eps receives the smallest
 * magnitude kept (0 when all stay). 0, or -1 (out of memory). */
static int keep_largest(const bwr_model_t *m, const bwr_thresholds_t *th, double *out, size_t q0,
                        size_t q1, size_t keep, double *eps)
{
    size_t ns = m->ncoef_spec, alive = 0;
    for (size_t q = q0; q < q1; q++)
        alive += out[q] != 0.0;
    if (alive <= keep) {
        *eps = 0.0;
        return 0;
    }
    if (keep == 0) {
        memset(out + q0, 0, (q1 - q0) * sizeof *out);
        *eps = INFINITY;
        return 0;
    }
    double *mag = malloc(alive * sizeof *mag);
    if (mag == NULL)
        return -1;
    size_t a = 0;
    for (size_t q = q0; q < q1; q++)
        if (out[q] != 0.0)
            mag[a++] = fabs(out[q]) * weight(m, th, q / ns, q % ns);
    qsort(mag, alive, sizeof *mag, cmp_desc);
    double e = mag[keep - 1];
    size_t above = 0; /* how many equal to e may stay */
    while (above < keep && mag[above] > e)
        above++;
    size_t ties_left = keep - above;
    free(mag);
    for (size_t q = q0; q < q1; q++) {
        if (out[q] == 0.0)
            continue;
        double g = fabs(out[q]) * weight(m, th, q / ns, q % ns);
        if (g > e)
            continue;
        if (g == e && ties_left > 0) {
            ties_left--;
            continue;
        }
        out[q] = 0.0;
    }
    *eps = e;
    return 0;
}

int bwr_compress(const bwr_model_t *m, const double *coef, const bwr_thresholds_t *th, double *out,
                 bwr_compress_info_t *info)
{
    bwr_compress_info_t inf;
    memset(&inf, 0, sizeof inf);
    size_t nvec = m->nci * m->n_out, ns = m->ncoef_spec;
    size_t blk = m->n_out * ns;
    if (out != coef)
        memcpy(out, coef, m->n_coefs * sizeof *out);

    /* 1. incoming objects */
    if ((m->have_in || m->have_in1d) && th->eps_in > 0.0) {
        for (size_t i = 0; i < m->nci; i++) {
            double e = 0.0;
            for (size_t o = 0; o < m->n_out; o++)
                for (size_t k = 0; k < ns; k++) {
                    double c = out[i * blk + o * ns + k];
                    e += c * c * (th->raw ? 1.0 : m->out_psi2[o] * m->spec_norm2[k]);
                }
            if (sqrt(e * (th->raw ? 1.0 : m->in_psi2[i])) < th->eps_in) {
                int nz = 0;
                for (size_t q = 0; q < blk; q++)
                    nz |= out[i * blk + q] != 0.0;
                memset(out + i * blk, 0, blk * sizeof *out);
                inf.in_dropped += nz != 0;
            }
        }
    }
    /* 2. vectors */
    if (ns > 1 && th->eps_vec > 0.0) {
        for (size_t v = 0; v < nvec; v++) {
            size_t i = v / m->n_out, o = v % m->n_out;
            double e = 0.0;
            int nz = 0;
            for (size_t k = 0; k < ns; k++) {
                double c = out[v * ns + k];
                e += c * c * (th->raw ? 1.0 : m->spec_norm2[k]);
                nz |= c != 0.0;
            }
            if (nz && sqrt(e * (th->raw ? 1.0 : m->in_psi2[i] * m->out_psi2[o])) < th->eps_vec) {
                memset(out + v * ns, 0, ns * sizeof *out);
                inf.vec_dropped++;
            }
        }
    }
    /* 3. elements */
    double eps = th->eps_elem;
    if (th->keep > 0) {
        if (th->per_in) {
            size_t blk3 = m->n_out * ns;
            for (size_t i = 0; i < m->nci; i++) {
                size_t k = th->keep / m->nci + (i < th->keep % m->nci);
                if (keep_largest(m, th, out, i * blk3, (i + 1) * blk3, k, &eps) != 0)
                    return -1;
            }
        } else if (keep_largest(m, th, out, 0, m->n_coefs, th->keep, &eps) != 0) {
            return -1;
        }
        eps = -eps; /* applied */
    }
    if (eps > 0.0) {
        for (size_t q = 0; q < m->n_coefs; q++) {
            if (out[q] == 0.0)
                continue;
            size_t v = q / ns, k = q % ns;
            if (fabs(out[q]) * weight(m, th, v, k) < eps)
                out[q] = 0.0;
        }
    }
    inf.eps_elem = fabs(eps);
    for (size_t q = 0; q < m->n_coefs; q++)
        inf.kept += out[q] != 0.0;
    if (info != NULL)
        *info = inf;
    return 0;
}

void bwr_error(const double *ref, const double *test, size_t n, bwr_error_t *e)
{
    double s1 = 0.0, s2 = 0.0, se = 0.0, mx = 0.0;
    size_t nz = 0, zero = 0;
    for (size_t i = 0; i < n; i++) {
        double d = test[i] - ref[i];
        se += d * d;
        if (fabs(d) > mx)
            mx = fabs(d);
        if (ref[i] == 0.0) {
            zero++;
            continue;
        }
        double r = d / ref[i];
        s1 += fabs(r);
        s2 += r * r;
        nz++;
    }
    e->n = n;
    e->zero_ref = zero;
    e->rel_l1 = nz ? 100.0 * s1 / (double)nz : 0.0;
    e->rel_l2 = nz ? 100.0 * sqrt(s2 / (double)nz) : 0.0;
    e->rmse = n ? sqrt(se / (double)n) : 0.0;
    e->max_abs = mx;
}

int bwr_best_basis(const bwr_shape_t *shape, const double *samples, const bwr_thresholds_t *th,
                   const bwr_filter_t *const *cand, size_t ncand, size_t *best, double *err)
{
    double best_e = INFINITY;
    int rc = -1;
    *best = 0;
    for (size_t c = 0; c < ncand; c++) {
        bwr_shape_t s = *shape;
        s.basis = cand[c];
        bwr_model_t m;
        if (bwr_model_init(&m, &s) != 0)
            return -1;
        double *coef = malloc(m.n_coefs * sizeof *coef);
        double *rec = malloc(m.n_samples * sizeof *rec);
        bwr_error_t e;
        int ok = coef != NULL && rec != NULL && bwr_model_forward(&m, samples, coef) == 0 &&
                 bwr_compress(&m, coef, th, coef, NULL) == 0 &&
                 bwr_model_inverse(&m, coef, rec) == 0;
        if (ok) {
            bwr_error(samples, rec, m.n_samples, &e);
            if (err != NULL)
                err[c] = e.rel_l2;
            if (e.rel_l2 < best_e) {
                best_e = e.rel_l2;
                *best = c;
            }
        }
        free(coef);
        free(rec);
        bwr_model_free(&m);
        if (!ok)
            return -1;
        rc = 0;
    }
    return rc;
}

/* strips of a "valid" predicate over n indices */
static size_t count_strips(const unsigned char *valid, size_t n)
{
    size_t s = 0;
    for (size_t b = 0; b < n; b += BWR_STRIP_SIZE) {
        int any = 0;
        for (size_t i = b; i < b + BWR_STRIP_SIZE && i < n; i++)
            any |= valid[i];
        s += any != 0;
    }
    return s;
}

void bwr_coef_memory(const bwr_model_t *m, const double *coef, size_t value_bytes,
                     bwr_memory_t *flat, bwr_memory_t *nested)
{
    size_t ns = m->ncoef_spec, no = m->n_out, ni = m->nci;
    size_t values = 0, sflat = 0, snest = 0;
    for (size_t b = 0; b < m->n_coefs; b += BWR_STRIP_SIZE) {
        int any = 0;
        for (size_t q = b; q < b + BWR_STRIP_SIZE && q < m->n_coefs; q++) {
            values += coef[q] != 0.0;
            any |= coef[q] != 0.0;
        }
        sflat += any != 0;
    }
    unsigned char *vin = calloc(ni, 1), *vout = calloc(no, 1), *vsp = calloc(ns, 1);
    if (vin != NULL && vout != NULL && vsp != NULL) {
        for (size_t i = 0; i < ni; i++) {
            for (size_t o = 0; o < no; o++) {
                const double *v = coef + (i * no + o) * ns;
                int any = 0;
                for (size_t k = 0; k < ns; k++) {
                    vsp[k] = v[k] != 0.0;
                    any |= vsp[k];
                }
                vout[o] = (unsigned char)(any != 0);
                if (ns > 1 && any)
                    snest += count_strips(vsp, ns); /* the Spectrum object */
            }
            int anyo = 0;
            for (size_t o = 0; o < no; o++)
                anyo |= vout[o];
            vin[i] = (unsigned char)(anyo != 0);
            if (m->have_out && anyo)
                snest += count_strips(vout, no); /* the (spectral) Reflectance object */
        }
        if (ni > 1)
            snest += count_strips(vin, ni);
    }
    free(vin);
    free(vout);
    free(vsp);
    flat->values = nested->values = values;
    flat->data_bytes = nested->data_bytes = values * value_bytes;
    flat->strips = sflat;
    nested->strips = snest;
    flat->strip_bytes = sflat * BWR_STRIP_INDEX_BYTES;
    nested->strip_bytes = snest * BWR_STRIP_INDEX_BYTES;
    flat->total_bytes = flat->data_bytes + flat->strip_bytes;
    nested->total_bytes = nested->data_bytes + nested->strip_bytes;
}

static size_t div_up(size_t a, size_t b)
{
    return (a + b - 1) / b;
}

void bwr_sample_memory(const bwr_model_t *m, size_t value_bytes, bwr_memory_t *flat,
                       bwr_memory_t *nested)
{
    size_t ns = m->n_samples;
    flat->values = nested->values = ns;
    flat->data_bytes = nested->data_bytes = ns * value_bytes;
    flat->strips = div_up(ns, BWR_STRIP_SIZE);
    nested->strips = (m->n_in > 1 ? div_up(m->n_in, BWR_STRIP_SIZE) : 0) +
                     (m->have_out ? m->n_in * div_up(m->n_out, BWR_STRIP_SIZE) : 0) +
                     (m->bands > 1 ? m->n_in * m->n_out * div_up(m->bands, BWR_STRIP_SIZE) : 0);
    flat->strip_bytes = flat->strips * BWR_STRIP_INDEX_BYTES;
    nested->strip_bytes = nested->strips * BWR_STRIP_INDEX_BYTES;
    flat->total_bytes = flat->data_bytes + flat->strip_bytes;
    nested->total_bytes = nested->data_bytes + nested->strip_bytes;
}
