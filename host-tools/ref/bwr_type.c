/* SPDX-License-Identifier: BSD-2-Clause */
/* Element types: reals and dense vectors. */
#include "bwr_type.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void real_zero(const bwr_type_t *t, void *x)
{
    (void)t;
    *(double *)x = 0.0;
}
static void real_copy(const bwr_type_t *t, void *d, const void *s)
{
    (void)t;
    *(double *)d = *(const double *)s;
}
static void real_add(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    (void)t;
    *(double *)d = *(const double *)a + *(const double *)b;
}
static void real_sub(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    (void)t;
    *(double *)d = *(const double *)a - *(const double *)b;
}
static void real_scale(const bwr_type_t *t, void *d, const void *a, double s)
{
    (void)t;
    *(double *)d = s * *(const double *)a;
}
static double real_dot(const bwr_type_t *t, const void *a, const void *b)
{
    (void)t;
    return *(const double *)a * *(const double *)b;
}

const bwr_type_t bwr_type_real = {
    "real", sizeof(double), 1, NULL, NULL, real_zero, real_copy,
    real_add, real_sub, real_scale, real_dot, NULL};

static void vec_zero(const bwr_type_t *t, void *x)
{
    memset(x, 0, t->n * sizeof(double));
}
static void vec_copy(const bwr_type_t *t, void *d, const void *s)
{
    memmove(d, s, t->n * sizeof(double));
}
static void vec_add(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    double *o = d;
    const double *x = a, *y = b;
    for (size_t i = 0; i < t->n; i++)
        o[i] = x[i] + y[i];
}
static void vec_sub(const bwr_type_t *t, void *d, const void *a, const void *b)
{
    double *o = d;
    const double *x = a, *y = b;
    for (size_t i = 0; i < t->n; i++)
        o[i] = x[i] - y[i];
}
static void vec_scale(const bwr_type_t *t, void *d, const void *a, double s)
{
    double *o = d;
    const double *x = a;
    for (size_t i = 0; i < t->n; i++)
        o[i] = s * x[i];
}
static double vec_dot(const bwr_type_t *t, const void *a, const void *b)
{
    const double *x = a, *y = b;
    double s = 0.0;
    for (size_t i = 0; i < t->n; i++)
        s += x[i] * y[i];
    return s;
}

bwr_type_t bwr_type_vector(size_t n)
{
    bwr_type_t t = {"vector", n * sizeof(double), n, NULL, NULL, vec_zero, vec_copy,
                    vec_add, vec_sub, vec_scale, vec_dot, NULL};
    return t;
}

void *bwr_array_new(const bwr_type_t *t, size_t n)
{
    if (n != 0 && t->size > ((size_t)-1) / n)
        return NULL;
    void *a = malloc(n * t->size != 0 ? n * t->size : 1);
    if (a == NULL)
        return NULL;
    for (size_t i = 0; i < n; i++) {
        if (t->init != NULL)
            t->init(t, bwr_at(t, a, i));
        else
            t->zero(t, bwr_at(t, a, i));
    }
    return a;
}

void bwr_array_free(const bwr_type_t *t, void *a, size_t n)
{
    if (a == NULL)
        return;
    if (t->fini != NULL)
        for (size_t i = 0; i < n; i++)
            t->fini(t, bwr_at(t, a, i));
    free(a);
}

void bwr_axpy(const bwr_type_t *t, void *y, double s, const void *x, void *tmp)
{
    t->scale(t, tmp, x, s);
    t->add(t, y, y, tmp);
}

double bwr_norm(const bwr_type_t *t, const void *x)
{
    return sqrt(t->dot(t, x, x));
}
