/* SPDX-License-Identifier: BSD-2-Clause */
/* Sparse arrays of 32-element strips and their algebra. */
#include "bwr_sparse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static unsigned long g_failures;

unsigned long bwr_sparse_failures(void)
{
    return g_failures;
}

static unsigned popcount32(uint32_t x)
{
    unsigned c = 0;
    while (x) {
        x &= x - 1;
        c++;
    }
    return c;
}

/* position of bit e among the valid bits below it */
static unsigned rank(uint32_t valid, unsigned e)
{
    return popcount32(valid & ((e == 0) ? 0u : (0xffffffffu >> (32u - e))));
}

void bwr_sparse_init(bwr_sparse_t *a, size_t length)
{
    a->length = length;
    a->nstrips = 0;
    a->cap = 0;
    a->s = NULL;
}

void bwr_sparse_free(bwr_sparse_t *a)
{
    for (size_t k = 0; k < a->nstrips; k++)
        free(a->s[k].v);
    free(a->s);
    a->s = NULL;
    a->nstrips = 0;
    a->cap = 0;
}

static int reserve(bwr_sparse_t *a, size_t n)
{
    if (n <= a->cap)
        return 0;
    size_t c = a->cap ? a->cap : 4;
    while (c < n)
        c *= 2;
    bwr_strip_t *s = realloc(a->s, c * sizeof *s);
    if (s == NULL)
        return -1;
    a->s = s;
    a->cap = c;
    return 0;
}

/* index of the strip with this number, or the insertion point (negative - 1) */
static long find_strip(const bwr_sparse_t *a, uint32_t number)
{
    size_t lo = 0, hi = a->nstrips;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (a->s[mid].number < number)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo < a->nstrips && a->s[lo].number == number)
        return (long)lo;
    return -(long)lo - 1;
}

int bwr_sparse_from_dense(bwr_sparse_t *a, const double *x, size_t n)
{
    bwr_sparse_free(a);
    a->length = n;
    for (size_t base = 0; base < n; base += BWR_STRIP_SIZE) {
        uint32_t valid = 0;
        size_t end = base + BWR_STRIP_SIZE < n ? base + BWR_STRIP_SIZE : n;
        for (size_t i = base; i < end; i++)
            if (x[i] != 0.0)
                valid |= 1u << (i - base);
        if (!valid)
            continue;
        if (reserve(a, a->nstrips + 1) != 0)
            goto oom;
        bwr_strip_t *s = &a->s[a->nstrips];
        s->number = (uint32_t)(base / BWR_STRIP_SIZE);
        s->valid = valid;
        s->v = malloc(popcount32(valid) * sizeof(double));
        if (s->v == NULL)
            goto oom;
        a->nstrips++;
        unsigned q = 0;
        for (size_t i = base; i < end; i++)
            if (x[i] != 0.0)
                s->v[q++] = x[i];
    }
    return 0;
oom:
    bwr_sparse_free(a);
    return -1;
}

void bwr_sparse_to_dense(const bwr_sparse_t *a, double *x)
{
    memset(x, 0, a->length * sizeof *x);
    for (size_t k = 0; k < a->nstrips; k++) {
        const bwr_strip_t *s = &a->s[k];
        unsigned q = 0;
        for (unsigned e = 0; e < BWR_STRIP_SIZE; e++)
            if (s->valid & (1u << e))
                x[(size_t)s->number * BWR_STRIP_SIZE + e] = s->v[q++];
    }
}

double bwr_sparse_get(const bwr_sparse_t *a, size_t i)
{
    long k = find_strip(a, (uint32_t)(i / BWR_STRIP_SIZE));
    if (k < 0)
        return 0.0;
    unsigned e = (unsigned)(i % BWR_STRIP_SIZE);
    const bwr_strip_t *s = &a->s[k];
    if (!(s->valid & (1u << e)))
        return 0.0;
    return s->v[rank(s->valid, e)];
}

int bwr_sparse_is_valid(const bwr_sparse_t *a, size_t i)
{
    long k = find_strip(a, (uint32_t)(i / BWR_STRIP_SIZE));
    return k >= 0 && (a->s[k].valid & (1u << (i % BWR_STRIP_SIZE))) != 0;
}

int bwr_sparse_set(bwr_sparse_t *a, size_t i, double v)
{
    if (i >= a->length)
        return -1;
    uint32_t number = (uint32_t)(i / BWR_STRIP_SIZE);
    unsigned e = (unsigned)(i % BWR_STRIP_SIZE);
    long k = find_strip(a, number);
    if (k < 0) {
        size_t at = (size_t)(-k - 1);
        if (reserve(a, a->nstrips + 1) != 0)
            return -1;
        double *vals = malloc(sizeof(double));
        if (vals == NULL)
            return -1;
        memmove(&a->s[at + 1], &a->s[at], (a->nstrips - at) * sizeof *a->s);
        a->s[at].number = number;
        a->s[at].valid = 1u << e;
        a->s[at].v = vals;
        vals[0] = v;
        a->nstrips++;
        return 0;
    }
    bwr_strip_t *s = &a->s[k];
    unsigned r = rank(s->valid, e);
    if (s->valid & (1u << e)) {
        s->v[r] = v;
        return 0;
    }
    unsigned c = popcount32(s->valid);
    double *nv = realloc(s->v, (c + 1) * sizeof *nv);
    if (nv == NULL)
        return -1;
    memmove(nv + r + 1, nv + r, (c - r) * sizeof *nv);
    nv[r] = v;
    s->v = nv;
    s->valid |= 1u << e;
    return 0;
}

static void remove_strip(bwr_sparse_t *a, size_t k)
{
    free(a->s[k].v);
    memmove(&a->s[k], &a->s[k + 1], (a->nstrips - k - 1) * sizeof *a->s);
    a->nstrips--;
}

void bwr_sparse_invalidate(bwr_sparse_t *a, size_t i)
{
    long k = find_strip(a, (uint32_t)(i / BWR_STRIP_SIZE));
    if (k < 0)
        return;
    unsigned e = (unsigned)(i % BWR_STRIP_SIZE);
    bwr_strip_t *s = &a->s[k];
    if (!(s->valid & (1u << e)))
        return;
    unsigned r = rank(s->valid, e), c = popcount32(s->valid);
    memmove(s->v + r, s->v + r + 1, (c - r - 1) * sizeof *s->v);
    s->valid &= ~(1u << e);
    if (!s->valid)
        remove_strip(a, (size_t)k);
}

void bwr_sparse_threshold(bwr_sparse_t *a, double eps)
{
    size_t w = 0;
    for (size_t k = 0; k < a->nstrips; k++) {
        bwr_strip_t s = a->s[k];
        uint32_t valid = 0;
        unsigned q = 0, o = 0;
        for (unsigned e = 0; e < BWR_STRIP_SIZE; e++) {
            if (!(s.valid & (1u << e)))
                continue;
            double v = s.v[q++];
            if (fabs(v) >= eps) {
                s.v[o++] = v;
                valid |= 1u << e;
            }
        }
        if (!valid) {
            free(s.v);
            continue;
        }
        s.valid = valid;
        a->s[w++] = s;
    }
    a->nstrips = w;
}

size_t bwr_sparse_count(const bwr_sparse_t *a)
{
    size_t c = 0;
    for (size_t k = 0; k < a->nstrips; k++)
        c += popcount32(a->s[k].valid);
    return c;
}

/* r = a + sign * b, built into a fresh array */
static int combine(bwr_sparse_t *dst, const bwr_sparse_t *a, const bwr_sparse_t *b, double sign)
{
    if (a->length != b->length)
        return -1;
    bwr_sparse_t r;
    bwr_sparse_init(&r, a->length);
    if (reserve(&r, a->nstrips + b->nstrips) != 0)
        goto oom;
    size_t i = 0, j = 0;
    while (i < a->nstrips || j < b->nstrips) {
        const bwr_strip_t *sa = i < a->nstrips ? &a->s[i] : NULL;
        const bwr_strip_t *sb = j < b->nstrips ? &b->s[j] : NULL;
        bwr_strip_t *o = &r.s[r.nstrips];
        if (sb == NULL || (sa != NULL && sa->number < sb->number)) {
            /* only in a: copied */
            unsigned c = popcount32(sa->valid);
            o->number = sa->number;
            o->valid = sa->valid;
            o->v = malloc(c * sizeof(double));
            if (o->v == NULL)
                goto oom;
            memcpy(o->v, sa->v, c * sizeof(double));
            i++;
        } else if (sa == NULL || sb->number < sa->number) {
            /* only in b: copied with its sign */
            unsigned c = popcount32(sb->valid);
            o->number = sb->number;
            o->valid = sb->valid;
            o->v = malloc(c * sizeof(double));
            if (o->v == NULL)
                goto oom;
            for (unsigned q = 0; q < c; q++)
                o->v[q] = sign * sb->v[q];
            j++;
        } else {
            /* in both: element by element over the union of the valid bits */
            uint32_t u = sa->valid | sb->valid;
            o->number = sa->number;
            o->valid = u;
            o->v = malloc(popcount32(u) * sizeof(double));
            if (o->v == NULL)
                goto oom;
            unsigned qa = 0, qb = 0, q = 0;
            for (unsigned e = 0; e < BWR_STRIP_SIZE; e++) {
                uint32_t bit = 1u << e;
                if (!(u & bit))
                    continue;
                double va = (sa->valid & bit) ? sa->v[qa++] : 0.0;
                double vb = (sb->valid & bit) ? sb->v[qb++] : 0.0;
                o->v[q++] = va + sign * vb;
            }
            i++;
            j++;
        }
        r.nstrips++;
    }
    bwr_sparse_free(dst);
    *dst = r;
    return 0;
oom:
    bwr_sparse_free(&r);
    bwr_sparse_free(dst);
    return -1;
}

int bwr_sparse_add(bwr_sparse_t *dst, const bwr_sparse_t *a, const bwr_sparse_t *b)
{
    return combine(dst, a, b, 1.0);
}

int bwr_sparse_sub(bwr_sparse_t *dst, const bwr_sparse_t *a, const bwr_sparse_t *b)
{
    return combine(dst, a, b, -1.0);
}

int bwr_sparse_copy(bwr_sparse_t *dst, const bwr_sparse_t *src)
{
    if (dst == src)
        return 0;
    bwr_sparse_t r;
    bwr_sparse_init(&r, src->length);
    if (reserve(&r, src->nstrips) != 0)
        return -1;
    for (size_t k = 0; k < src->nstrips; k++) {
        unsigned c = popcount32(src->s[k].valid);
        r.s[k] = src->s[k];
        r.s[k].v = malloc(c * sizeof(double));
        if (r.s[k].v == NULL) {
            r.nstrips = k;
            bwr_sparse_free(&r);
            return -1;
        }
        memcpy(r.s[k].v, src->s[k].v, c * sizeof(double));
    }
    r.nstrips = src->nstrips;
    bwr_sparse_free(dst);
    *dst = r;
    return 0;
}

int bwr_sparse_scale(bwr_sparse_t *dst, const bwr_sparse_t *a, double s)
{
    if (dst != a && bwr_sparse_copy(dst, a) != 0)
        return -1;
    for (size_t k = 0; k < dst->nstrips; k++) {
        unsigned c = popcount32(dst->s[k].valid);
        for (unsigned q = 0; q < c; q++)
            dst->s[k].v[q] *= s;
    }
    return 0;
}

double bwr_sparse_dot(const bwr_sparse_t *a, const bwr_sparse_t *b)
{
    double sum = 0.0;
    size_t i = 0, j = 0;
    while (i < a->nstrips && j < b->nstrips) {
        const bwr_strip_t *sa = &a->s[i], *sb = &b->s[j];
        if (sa->number < sb->number) {
            i++;
        } else if (sb->number < sa->number) {
            j++;
        } else {
            uint32_t both = sa->valid & sb->valid;
            for (unsigned e = 0; e < BWR_STRIP_SIZE; e++)
                if (both & (1u << e))
                    sum += sa->v[rank(sa->valid, e)] * sb->v[rank(sb->valid, e)];
            i++;
            j++;
        }
    }
    return sum;
}

void bwr_sparse_memory(const bwr_sparse_t *a, size_t value_bytes, bwr_memory_t *mem)
{
    mem->values = bwr_sparse_count(a);
    mem->strips = a->nstrips;
    mem->data_bytes = mem->values * value_bytes;
    mem->strip_bytes = mem->strips * BWR_STRIP_INDEX_BYTES;
    mem->total_bytes = mem->data_bytes + mem->strip_bytes;
}

void bwr_memory_add(bwr_memory_t *a, const bwr_memory_t *b)
{
    a->values += b->values;
    a->strips += b->strips;
    a->data_bytes += b->data_bytes;
    a->strip_bytes += b->strip_bytes;
    a->total_bytes += b->total_bytes;
}

/* ---- the element type ---- */

static void sp_init(const bwr_type_t *t, void *x)
{
    bwr_sparse_init(x, t->n);
}
static void sp_fini(const bwr_type_t *t, void *x)
{
    (void)t;
    bwr_sparse_free(x);
}
static void sp_zero(const bwr_type_t *t, void *x)
{
    (void)t;
    bwr_sparse_free(x);
}
static void sp_copy(const bwr_type_t *t, void *d, const void *s)
{
    (void)t;
    if (bwr_sparse_copy(d, s) != 0)
        g_failures++;
}
static void sp_add(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    (void)t;
    if (bwr_sparse_add(d, a, b) != 0)
        g_failures++;
}
static void sp_sub(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    (void)t;
    if (bwr_sparse_sub(d, a, b) != 0)
        g_failures++;
}
static void sp_scale(const bwr_type_t *t, void *d, const void *a, double s)
{
    (void)t;
    if (bwr_sparse_scale(d, a, s) != 0)
        g_failures++;
}
static double sp_dot(const bwr_type_t *t, const void *a, const void *b)
{
    (void)t;
    return bwr_sparse_dot(a, b);
}

bwr_type_t bwr_type_sparse(size_t length)
{
    bwr_type_t t = {"sparse", sizeof(bwr_sparse_t), length, sp_init, sp_fini, sp_zero, sp_copy,
                    sp_add, sp_sub, sp_scale, sp_dot, NULL};
    return t;
}
