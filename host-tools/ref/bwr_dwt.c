/* SPDX-License-Identifier: BSD-2-Clause */
/* Generic 1-D periodized DWT. */
#include "bwr_dwt.h"

#include <stdlib.h>
#include <string.h>

const bwr_filter_t *bwr_filter_find(const char *name)
{
    for (size_t i = 0; i < BWR_NUM_FILTERS; i++)
        if (strcmp(bwr_filters[i].name, name) == 0)
            return &bwr_filters[i];
    return NULL;
}

void bwr_filter_dec_hi(const bwr_filter_t *f, double *out)
{
    for (size_t n = 0; n < f->len; n++)
        out[n] = (n % 2 ? 1.0 : -1.0) * f->rec_lo[n];
}

void bwr_filter_rec_hi(const bwr_filter_t *f, double *out)
{
    for (size_t n = 0; n < f->len; n++)
        out[n] = (n % 2 ? -1.0 : 1.0) * f->dec_lo[n];
}

unsigned bwr_dwt_max_level(size_t n, size_t filter_len)
{
    if (filter_len < 2 || n < filter_len - 1)
        return 0;
    unsigned j = 0;
    /* largest j with (F - 1) * 2^j <= n */
    while (j < BWR_DWT_MAX_LEVELS && (filter_len - 1) << (j + 1) <= n)
        j++;
    return j;
}

static size_t next_len(bwr_ext_t mode, size_t m, size_t F)
{
    return mode == BWR_EXT_SYMMETRIC ? (m + F - 1) / 2 : (m + 1) / 2;
}

int bwr_dwt_plan_ext(bwr_dwt_plan_t *p, const bwr_filter_t *f, size_t n, int levels,
                     bwr_ext_t mode)
{
    memset(p, 0, sizeof *p);
    if (f == NULL || n == 0 || f->len > BWR_MAX_FILTER_LEN ||
        (mode != BWR_EXT_PERIODIZATION && mode != BWR_EXT_SYMMETRIC))
        return -1;
    size_t F = f->len;
    unsigned J;
    if (levels == BWR_DWT_DEEP) {
        size_t m = n;
        for (J = 0; m > 2 && next_len(mode, m, F) < m && J < BWR_DWT_MAX_LEVELS; J++)
            m = next_len(mode, m, F);
    } else {
        J = levels < 0 ? bwr_dwt_max_level(n, F) : (unsigned)levels;
    }
    if (J > BWR_DWT_MAX_LEVELS)
        return -1;
    p->f = f;
    p->mode = mode;
    p->n = n;
    p->levels = J;
    p->len[0] = n;
    p->maxlen = n;
    for (unsigned j = 1; j <= J; j++) {
        if (p->len[j - 1] < 2 && mode == BWR_EXT_PERIODIZATION)
            return -1;
        p->len[j] = next_len(mode, p->len[j - 1], F);
        if (p->len[j] > p->maxlen)
            p->maxlen = p->len[j];
    }
    /* [cA_J, cD_J, ..., cD_1] */
    p->off[0] = 0;
    size_t o = p->len[J];
    for (unsigned j = J; j >= 1; j--) {
        p->off[j] = o;
        o += p->len[j];
    }
    p->ncoef = o;
    bwr_filter_dec_hi(f, p->dec_hi);
    bwr_filter_rec_hi(f, p->rec_hi);
    return 0;
}

int bwr_dwt_plan(bwr_dwt_plan_t *p, const bwr_filter_t *f, size_t n, int levels)
{
    return bwr_dwt_plan_ext(p, f, n, levels, BWR_EXT_PERIODIZATION);
}

/* sample index of the extended signal at position q (may be negative) */
static size_t ext_index(const bwr_dwt_plan_t *p, long q, size_t m)
{
    if (p->mode == BWR_EXT_SYMMETRIC) {
        /* half-sample symmetric: x[-1-k] = x[k], x[m+k] = x[m-1-k], repeated */
        long period = 2 * (long)m;
        long r = q % period;
        if (r < 0)
            r += period;
        return r < (long)m ? (size_t)r : (size_t)(period - 1 - r);
    }
    /* periodization: an odd m is extended by a copy of its last sample */
    long me = (long)(m + (m & 1u));
    long r = q % me;
    if (r < 0)
        r += me;
    return r == (long)m ? m - 1 : (size_t)r;
}

void bwr_dwt_step(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *x, size_t m, void *a,
                  void *d, void *tmp)
{
    size_t F = p->f->len, h = next_len(p->mode, m, F);
    /* periodization: a[i] = sum_k h[k] x[(2i + F/2 - k) mod m'];
     * symmetric:     a[i] = sum_k h[k] x_ext[2i + 1 - k] */
    long shift = p->mode == BWR_EXT_SYMMETRIC ? 1 : (long)(F / 2);
    for (size_t i = 0; i < h; i++) {
        void *ai = bwr_at(t, a, i), *di = bwr_at(t, d, i);
        t->zero(t, ai);
        t->zero(t, di);
        for (size_t k = 0; k < F; k++) {
            const void *xv = bwr_cat(t, x, ext_index(p, 2 * (long)i + shift - (long)k, m));
            if (p->f->dec_lo[k] != 0.0)
                bwr_axpy(t, ai, p->f->dec_lo[k], xv, tmp);
            if (p->dec_hi[k] != 0.0)
                bwr_axpy(t, di, p->dec_hi[k], xv, tmp);
        }
    }
}

void bwr_idwt_step(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *a, const void *d,
                   size_t h, void *y, size_t m, void *ext, void *tmp)
{
    size_t F = p->f->len;
    if (p->mode == BWR_EXT_SYMMETRIC) {
        /* y[n] = sum_i a[i] rec_lo[n + F - 2 - 2i] + d[i] rec_hi[...], n < m */
        for (size_t n = 0; n < m; n++) {
            void *yn = bwr_at(t, y, n);
            t->zero(t, yn);
            for (size_t i = 0; i < h; i++) {
                long k = (long)n + (long)F - 2 - 2 * (long)i;
                if (k < 0 || k >= (long)F)
                    continue;
                if (p->f->rec_lo[k] != 0.0)
                    bwr_axpy(t, yn, p->f->rec_lo[k], bwr_cat(t, a, i), tmp);
                if (p->rec_hi[k] != 0.0)
                    bwr_axpy(t, yn, p->rec_hi[k], bwr_cat(t, d, i), tmp);
            }
        }
        return;
    }
    /* periodization: the transposed (dual) filter bank on 2h samples */
    size_t me = 2 * h;
    for (size_t i = 0; i < me; i++)
        t->zero(t, bwr_at(t, ext, i));
    for (size_t i = 0; i < h; i++) {
        const void *ai = bwr_cat(t, a, i), *di = bwr_cat(t, d, i);
        for (size_t k = 0; k < F; k++) {
            long q = (2 * (long)i + (long)(F / 2) - (long)k) % (long)me;
            if (q < 0)
                q += (long)me;
            void *e = bwr_at(t, ext, (size_t)q);
            double cl = p->f->rec_lo[F - 1 - k], ch = p->rec_hi[F - 1 - k];
            if (cl != 0.0)
                bwr_axpy(t, e, cl, ai, tmp);
            if (ch != 0.0)
                bwr_axpy(t, e, ch, di, tmp);
        }
    }
    for (size_t i = 0; i < m; i++)
        t->copy(t, bwr_at(t, y, i), bwr_at(t, ext, i));
}

int bwr_dwt_forward(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *in, void *out)
{
    size_t n = p->n, L = p->maxlen;
    if (p->levels == 0) {
        for (size_t i = 0; i < n; i++)
            t->copy(t, bwr_at(t, out, i), bwr_cat(t, in, i));
        return 0;
    }
    void *cur = bwr_array_new(t, L), *tmp = bwr_array_new(t, 1), *a = bwr_array_new(t, L);
    if (cur == NULL || tmp == NULL || a == NULL) {
        bwr_array_free(t, cur, L);
        bwr_array_free(t, tmp, 1);
        bwr_array_free(t, a, L);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        t->copy(t, bwr_at(t, cur, i), bwr_cat(t, in, i));
    for (unsigned j = 1; j <= p->levels; j++) {
        size_t m = p->len[j - 1], h = p->len[j];
        bwr_dwt_step(p, t, cur, m, a, bwr_at(t, out, p->off[j]), tmp);
        for (size_t i = 0; i < h; i++)
            t->copy(t, bwr_at(t, cur, i), bwr_at(t, a, i));
    }
    for (size_t i = 0; i < p->len[p->levels]; i++)
        t->copy(t, bwr_at(t, out, i), bwr_at(t, cur, i));
    bwr_array_free(t, cur, L);
    bwr_array_free(t, tmp, 1);
    bwr_array_free(t, a, L);
    return 0;
}

int bwr_dwt_inverse(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *in, void *out)
{
    size_t n = p->n;
    if (p->levels == 0) {
        for (size_t i = 0; i < n; i++)
            t->copy(t, bwr_at(t, out, i), bwr_cat(t, in, i));
        return 0;
    }
    size_t ne = 2 * p->maxlen + 2;
    void *cur = bwr_array_new(t, ne), *nxt = bwr_array_new(t, ne), *ext = bwr_array_new(t, ne);
    void *tmp = bwr_array_new(t, 1);
    int rc = -1;
    if (cur == NULL || nxt == NULL || ext == NULL || tmp == NULL)
        goto done;
    for (size_t i = 0; i < p->len[p->levels]; i++)
        t->copy(t, bwr_at(t, cur, i), bwr_cat(t, in, i));
    for (unsigned j = p->levels; j >= 1; j--) {
        size_t h = p->len[j], m = p->len[j - 1];
        bwr_idwt_step(p, t, cur, bwr_cat(t, in, p->off[j]), h, nxt, m, ext, tmp);
        void *sw = cur;
        cur = nxt;
        nxt = sw;
    }
    for (size_t i = 0; i < n; i++)
        t->copy(t, bwr_at(t, out, i), bwr_at(t, cur, i));
    rc = 0;
done:
    bwr_array_free(t, cur, ne);
    bwr_array_free(t, nxt, ne);
    bwr_array_free(t, ext, ne);
    bwr_array_free(t, tmp, 1);
    return rc;
}

int bwr_dwt_synthesis_norms2(const bwr_dwt_plan_t *p, double *out)
{
    const bwr_type_t *t = &bwr_type_real;
    double *c = calloc(p->ncoef, sizeof *c), *x = malloc(p->n * sizeof *x);
    if (c == NULL || x == NULL) {
        free(c);
        free(x);
        return -1;
    }
    /* one representative per subband: the middle coefficient (periodic
     * shift invariance makes the others equal, up to the extension sample
     * of odd lengths) */
    for (unsigned j = 0; j <= p->levels; j++) {
        size_t start = j == 0 ? 0 : p->off[j];
        size_t len = j == 0 ? p->len[p->levels] : p->len[j];
        size_t k = start + len / 2;
        c[k] = 1.0;
        if (bwr_dwt_inverse(p, t, c, x) != 0) {
            free(c);
            free(x);
            return -1;
        }
        c[k] = 0.0;
        double s = 0.0;
        for (size_t i = 0; i < p->n; i++)
            s += x[i] * x[i];
        for (size_t q = start; q < start + len; q++)
            out[q] = s;
    }
    free(c);
    free(x);
    return 0;
}
