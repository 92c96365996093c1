/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Sparse arrays of strips (sec. 4.3) and their algebra (sec. 4.4).
 *
 * A strip covers B_s = 32 consecutive indices [32 k, 32 k + 32): its number
 * k, a 32-bit valid index (bit e set: element 32 k + e is stored) and the
 * packed values of the valid elements, in index order. An array is the list
 * of its non-empty strips by increasing number; a strip whose elements are
 * all invalid is removed, so consecutive strips may have non-consecutive
 * numbers. Invalid elements read as 0.
 *
 * Memory (the accounting of Table 4): data = valid values x value size;
 * localisation = strips x 8 bytes (32-bit valid index + 32-bit strip number);
 * the strips are kept in one array sorted by number, so there are no list
 * pointers.
 *
 * Algebra on compressed arrays (Figure 4): a + b and a - b visit the strips
 * of both arrays in order; a strip in neither stays absent, a strip in one
 * is copied (negated for the subtrahend), a strip in both is combined element
 * by element according to the two valid indices (union of the valid bits).
 * Scaling and the inner product touch the stored values only.
 */
#ifndef BWR_SPARSE_H
#define BWR_SPARSE_H

#include <stddef.h>
#include <stdint.h>

#include "bwr_type.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_STRIP_SIZE 32u
#define BWR_STRIP_INDEX_BYTES 8u /* valid index + strip number */

typedef struct {
    uint32_t number;
    uint32_t valid;
    double *v; /* popcount(valid) values */
} bwr_strip_t;

typedef struct {
    size_t length;
    size_t nstrips, cap;
    bwr_strip_t *s;
} bwr_sparse_t;

void bwr_sparse_init(bwr_sparse_t *a, size_t length);
void bwr_sparse_free(bwr_sparse_t *a); /* back to an empty array of the same length */

/* Every non-zero x[i] becomes a valid element. 0, or -1 (out of memory). */
int bwr_sparse_from_dense(bwr_sparse_t *a, const double *x, size_t n);
void bwr_sparse_to_dense(const bwr_sparse_t *a, double *x); /* a->length values */

double bwr_sparse_get(const bwr_sparse_t *a, size_t i);
int bwr_sparse_is_valid(const bwr_sparse_t *a, size_t i);
/* Sets element i valid with value v. 0, or -1 (index out of range, out of memory). */
int bwr_sparse_set(bwr_sparse_t *a, size_t i, double v);
/* Invalidates element i (removing its strip when it was the last one). */
void bwr_sparse_invalidate(bwr_sparse_t *a, size_t i);
/* Invalidates every element with |value| < eps. */
void bwr_sparse_threshold(bwr_sparse_t *a, double eps);

size_t bwr_sparse_count(const bwr_sparse_t *a); /* valid values */

/* dst = a + b, a - b, s a, src. dst may be a or b. 0, or -1 (lengths differ,
 * out of memory: dst is then empty). */
int bwr_sparse_add(bwr_sparse_t *dst, const bwr_sparse_t *a, const bwr_sparse_t *b);
int bwr_sparse_sub(bwr_sparse_t *dst, const bwr_sparse_t *a, const bwr_sparse_t *b);
int bwr_sparse_scale(bwr_sparse_t *dst, const bwr_sparse_t *a, double s);
int bwr_sparse_copy(bwr_sparse_t *dst, const bwr_sparse_t *src);
double bwr_sparse_dot(const bwr_sparse_t *a, const bwr_sparse_t *b);

typedef struct {
    size_t values;
    size_t strips;
    size_t data_bytes;
    size_t strip_bytes;
    size_t total_bytes;
} bwr_memory_t;

/* Memory of a with value_bytes per value (8: doubles as in the paper). */
void bwr_sparse_memory(const bwr_sparse_t *a, size_t value_bytes, bwr_memory_t *mem);
/* Adds b to a (a += b, field by field). */
void bwr_memory_add(bwr_memory_t *a, const bwr_memory_t *b);

/* The element type "sparse array of `length` reals" for the generic
 * transforms: elements are bwr_sparse_t. The operations cannot return
 * errors; an allocation failure is counted and reported by
 * bwr_sparse_failures(). */
bwr_type_t bwr_type_sparse(size_t length);
unsigned long bwr_sparse_failures(void);

#ifdef __cplusplus
}
#endif

#endif
