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

int bwr_compress(const bwr_model_t *m, const double *coef, const bwr_thresholds_t *th, double *out,
                 bwr_compress_info_t *info)
{
    bwr_compress_info_t inf;
    memset(&inf, 0, sizeof inf);
    size_t nvec = m->n_in * m->n_out, ns = m->ncoef_spec;
    size_t blk = m->n_out * ns;
    if (out != coef)
        memcpy(out, coef, m->n_coefs * sizeof *out);

    /* 1. incoming objects */
    if (m->have_in && th->eps_in > 0.0) {
        for (size_t i = 0; i < m->n_in; i++) {
            double e = 0.0;
            for (size_t o = 0; o < m->n_out; o++)
                for (size_t k = 0; k < ns; k++) {
                    double c = out[i * blk + o * ns + k];
                    e += c * c * m->out_psi2[o] * m->spec_norm2[k];
                }
            if (sqrt(e * m->in_psi2[i]) < th->eps_in) {
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
                e += c * c * m->spec_norm2[k];
                nz |= c != 0.0;
            }
            if (nz && sqrt(e * m->in_psi2[i] * m->out_psi2[o]) < th->eps_vec) {
                memset(out + v * ns, 0, ns * sizeof *out);
                inf.vec_dropped++;
            }
        }
    }
    /* 3. elements */
    size_t alive = 0;
    for (size_t q = 0; q < m->n_coefs; q++)
        alive += out[q] != 0.0;
    double eps = th->eps_elem;
    if (th->keep > 0) {
        if (alive <= th->keep) {
            eps = 0.0;
        } else {
            double *mag = malloc(alive * sizeof *mag);
            if (mag == NULL)
                return -1;
            size_t a = 0;
            for (size_t q = 0; q < m->n_coefs; q++) {
                if (out[q] == 0.0)
                    continue;
                size_t v = q / ns, k = q % ns;
                mag[a++] = fabs(out[q]) * sqrt(bwr_model_norm2(m, v / m->n_out, v % m->n_out, k));
            }
            qsort(mag, alive, sizeof *mag, cmp_desc);
            eps = mag[th->keep - 1];
            /* how many equal to eps may stay */
            size_t above = 0;
            while (above < th->keep && mag[above] > eps)
                above++;
            size_t ties_left = th->keep - above;
            free(mag);
            for (size_t q = 0; q < m->n_coefs; q++) {
                if (out[q] == 0.0)
                    continue;
                size_t v = q / ns, k = q % ns;
                double g = fabs(out[q]) * sqrt(bwr_model_norm2(m, v / m->n_out, v % m->n_out, k));
                if (g > eps)
                    continue;
                if (g == eps && ties_left > 0) {
                    ties_left--;
                    continue;
                }
                out[q] = 0.0;
            }
            eps = -eps; /* marks "already applied" */
        }
    }
    if (eps > 0.0) {
        for (size_t q = 0; q < m->n_coefs; q++) {
            if (out[q] == 0.0)
                continue;
            size_t v = q / ns, k = q % ns;
            if (fabs(out[q]) * sqrt(bwr_model_norm2(m, v / m->n_out, v % m->n_out, k)) < eps)
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
