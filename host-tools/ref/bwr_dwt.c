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

int bwr_dwt_plan(bwr_dwt_plan_t *p, const bwr_filter_t *f, size_t n, int levels)
{
    memset(p, 0, sizeof *p);
    if (f == NULL || n == 0 || f->len > BWR_MAX_FILTER_LEN)
        return -1;
    unsigned J = levels < 0 ? bwr_dwt_max_level(n, f->len) : (unsigned)levels;
    if (J > BWR_DWT_MAX_LEVELS)
        return -1;
    p->f = f;
    p->n = n;
    p->levels = J;
    p->len[0] = n;
    for (unsigned j = 1; j <= J; j++) {
        if (p->len[j - 1] < 2)
            return -1;
        p->len[j] = (p->len[j - 1] + 1) / 2;
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

void bwr_dwt_step(const bwr_dwt_plan_t *p, const bwr_type_t *t, const void *x, size_t m, void *a,
                  void *d, void *tmp)
{
    size_t me = m + (m & 1u), h = me / 2, F = p->f->len;
    for (size_t i = 0; i < h; i++) {
        void *ai = bwr_at(t, a, i), *di = bwr_at(t, d, i);
        t->zero(t, ai);
        t->zero(t, di);
        for (size_t k = 0; k < F; k++) {
            /* (2i + F/2 - k) mod me, kept non-negative */
            size_t idx = (2 * i + F / 2 + me * ((F / me) + 1) - k) % me;
            if (idx == m) /* the extension sample */
                idx = m - 1;
            const void *xv = bwr_cat(t, x, idx);
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
    size_t me = 2 * h, F = p->f->len;
    for (size_t i = 0; i < me; i++)
        t->zero(t, bwr_at(t, ext, i));
    for (size_t i = 0; i < h; i++) {
        const void *ai = bwr_cat(t, a, i), *di = bwr_cat(t, d, i);
        for (size_t k = 0; k < F; k++) {
            size_t idx = (2 * i + F / 2 + me * ((F / me) + 1) - k) % me;
            void *e = bwr_at(t, ext, idx);
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
    size_t n = p->n;
    if (p->levels == 0) {
        for (size_t i = 0; i < n; i++)
            t->copy(t, bwr_at(t, out, i), bwr_cat(t, in, i));
        return 0;
    }
    void *cur = bwr_array_new(t, n), *tmp = bwr_array_new(t, 1);
    void *a = bwr_array_new(t, (n + 1) / 2);
    if (cur == NULL || tmp == NULL || a == NULL) {
        bwr_array_free(t, cur, n);
        bwr_array_free(t, tmp, 1);
        bwr_array_free(t, a, (n + 1) / 2);
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
    bwr_array_free(t, cur, n);
    bwr_array_free(t, tmp, 1);
    bwr_array_free(t, a, (n + 1) / 2);
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
    size_t ne = n + 1;
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
