/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Element types of the generic wavelet transform (paper sec. 4.1-4.2).
 *
 * A transform is written once against the operations below; an element type
 * supplies them. The same transform code then works on reals, on Spectrum
 * vectors, on Reflectance objects (a spherical signal used as one element of
 * a BRDF) and on compressed sparse arrays (bwr_sparse.h).
 *
 * Elements live in plain arrays, `size` bytes each. A type whose elements own
 * memory provides init/fini; the others leave them NULL.
 */
#ifndef BWR_TYPE_H
#define BWR_TYPE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct bwr_type bwr_type_t;

struct bwr_type {
    const char *name;
    size_t size; /* bytes of one element */
    size_t n;    /* doubles per element for the dense types, else a parameter */
    /* x = a valid zero element on uninitialised storage (NULL: zero does it) */
    void (*init)(const bwr_type_t *t, void *x);
    /* releases what init/ops allocated (NULL: nothing to do) */
    void (*fini)(const bwr_type_t *t, void *x);
    void (*zero)(const bwr_type_t *t, void *x);
    void (*copy)(const bwr_type_t *t, void *dst, const void *src);
    /* dst = a + b, a - b, s * a; dst may be the same object as a or b */
    void (*add)(const bwr_type_t *t, void *dst, const void *a, const void *b);
    void (*sub)(const bwr_type_t *t, void *dst, const void *a, const void *b);
    void (*scale)(const bwr_type_t *t, void *dst, const void *a, double s);
    /* inner product <a, b> (for magnitudes: |a| = sqrt(<a, a>)) */
    double (*dot)(const bwr_type_t *t, const void *a, const void *b);
    const void *ctx;
};

/* The real numbers (element = one double). */
extern const bwr_type_t bwr_type_real;

/* Dense vectors of n doubles: a Spectrum, or a whole Reflectance / Spectral
 * Reflectance stored flat (as an element of a BRDF). */
bwr_type_t bwr_type_vector(size_t n);

/* Element i of an array of t-elements. */
static inline void *bwr_at(const bwr_type_t *t, void *base, size_t i)
{
    return (char *)base + i * t->size;
}
static inline const void *bwr_cat(const bwr_type_t *t, const void *base, size_t i)
{
    return (const char *)base + i * t->size;
}

/* Array helpers: allocate n zero elements (NULL on failure), release them. */
void *bwr_array_new(const bwr_type_t *t, size_t n);
void bwr_array_free(const bwr_type_t *t, void *a, size_t n);

/* y += s * x, through scale and add; tmp is a valid element used as scratch. */
void bwr_axpy(const bwr_type_t *t, void *y, double s, const void *x, void *tmp);

/* |x| = sqrt(<x, x>). */
double bwr_norm(const bwr_type_t *t, const void *x);

#ifdef __cplusplus
}
#endif

#endif
