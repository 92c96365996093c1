/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Sparse array of strips (paper §4.3-4.4).
 *
 * A dense array of `length` int32 elements is cut into strips of BW_STRIP
 * (32) elements. A strip with at least one valid (non-zero) element is kept
 * as its number, a 32-bit valid index (bit b = element 32*number + b is
 * valid) and its valid values packed in index order; empty strips are absent.
 * Strips are kept in ascending order. Storage belongs to the caller:
 * BW_SPARSE_STRIPS_BOUND(length) strips and `length` values always suffice.
 *
 * The operators work on the compressed form directly: a strip present in
 * only one operand is copied (or negated, or dropped for the inner product),
 * strips present in both are combined element by element through their valid
 * indices. Results are canonical: an element that comes out 0 is invalidated
 * and a strip that comes out empty is removed, so a result equals
 * bw_sparse_from_dense() of the dense result. Arithmetic saturates to int32.
 */
#ifndef BW_STRIP_H
#define BW_STRIP_H

#include <stddef.h>
#include <stdint.h>

#include "bw_error.h"

#define BW_SPARSE_STRIPS_BOUND(length) (((size_t)(length) + 31u) / 32u)

typedef struct {
    uint32_t length;     /* elements of the dense array              */
    uint32_t n_strips;   /* strips present                           */
    uint32_t n_values;   /* valid elements                           */
    uint32_t cap_strips;
    uint32_t cap_values;
    uint32_t *strip_no;  /* [cap_strips] ascending strip numbers     */
    uint32_t *mask;      /* [cap_strips] valid index of each strip   */
    uint32_t *first;     /* [cap_strips] offset of its first value   */
    int32_t *values;     /* [cap_values] packed valid values         */
} bw_sparse_t;

size_t bw_sparse_strips_bound(size_t length);

/* Attaches caller storage; the array starts empty (all zero). */
bw_status_t bw_sparse_init(bw_sparse_t *s, uint32_t length, uint32_t *strip_no, uint32_t *mask,
                           uint32_t *first, uint32_t cap_strips, int32_t *values,
                           uint32_t cap_values);

/* Keeps the elements with |x| > threshold (threshold 0: every non-zero). */
bw_status_t bw_sparse_from_dense(bw_sparse_t *s, const int32_t *dense, uint32_t threshold);
void bw_sparse_to_dense(const bw_sparse_t *s, int32_t *dense);
int32_t bw_sparse_get(const bw_sparse_t *s, uint32_t i);

/* out = a + b, out = a - b (out must not alias a or b). */
bw_status_t bw_sparse_add(const bw_sparse_t *a, const bw_sparse_t *b, bw_sparse_t *out);
bw_status_t bw_sparse_sub(const bw_sparse_t *a, const bw_sparse_t *b, bw_sparse_t *out);

/* out = round(a * num / 2^shift), shift 0..31 (out may alias a). */
bw_status_t bw_sparse_scale(const bw_sparse_t *a, int32_t num, unsigned shift, bw_sparse_t *out);

/* sum of a_i * b_i over the elements valid in both (exact below 2^63). */
bw_status_t bw_sparse_dot(const bw_sparse_t *a, const bw_sparse_t *b, int64_t *result);

/* Memory of the paper's accounting, in bytes: values (4 each) and strips
 * (number, index and value offset, 4 bytes each). */
size_t bw_sparse_bytes(const bw_sparse_t *s);

#endif
