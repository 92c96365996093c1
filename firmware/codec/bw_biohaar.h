/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Integer Bio-Haar lifting on the geodesic hemisphere, on vectors.
 *
 * Triangle t of the finest level holds the vector x[t*V .. t*V+V). For every
 * parent P (children c0..c3, c0 the centre child, weights L_m = a_m / a_P):
 *     d_m = x_m - x_0                          m = 1..3
 *     s_P = x_0 + round(sum_m L_m d_m)         (= sum_i L_i x_i, area average)
 * computed in place: s_P is stored where c0's value was and d_m where c_m's
 * was, so after all levels the scaling coefficient of base b sits at leaf
 * position b*4^L and details in the positions of the non-centre children.
 * bw_biohaar_pos() maps a coarse-to-fine (Mallat) coefficient index to that
 * position; coding walks the coefficients in Mallat order.
 */
#ifndef BW_BIOHAAR_H
#define BW_BIOHAAR_H

#include <stddef.h>
#include <stdint.h>

void bw_biohaar_fwd(int32_t *x, unsigned level, size_t vlen);

/* One parent's forward step on its children's vectors (c0 the centre child),
 * weights {L1, L2, L3} in Q16: c0 becomes s_P and c_m become d_m. */
void bw_biohaar_lift4(int32_t *c0, int32_t *c1, int32_t *c2, int32_t *c3, const uint16_t *w,
                      size_t vlen);
void bw_biohaar_inv(int32_t *x, unsigned level, size_t vlen);
/* bw_biohaar_fwd and _inv with vlen 1 on `blocks` hemispheres, the first at
 * x, each `stride` values after the one before (BW_CFG_UNROLL builds). */
void bw_biohaar_fwd_blocks(int32_t *x, unsigned level, size_t blocks, size_t stride);
void bw_biohaar_inv_blocks(int32_t *x, unsigned level, size_t blocks, size_t stride);
/* The inverse step of one parent p at level j (0 the coarsest) of a tree of
 * depth `level`: its four children from its scaling value and details. */
void bw_biohaar_inv_node(int32_t *x, unsigned level, size_t vlen, unsigned j, uint32_t p);

/* Mallat index -> in-place leaf position. Mallat order: the 4 base scaling
 * coefficients, then the 12 details of level 0's parents, then the 48 of
 * level 1, ...: detail (parent P at level j, child m) has index
 * 4^(j+1) + 3P + (m-1). */
uint32_t bw_biohaar_pos(uint32_t idx, unsigned level);

/* Level of the parent of a Mallat coefficient (-1 for a base scaling
 * coefficient). */
int bw_biohaar_coef_level(uint32_t idx);

/* 1/sqrt(synthesis gain) as Q16 of a coefficient of the given parent level
 * (-1 = scaling) in a transform of depth `level`: scaling coefficients spread
 * over 4^level leaves with gain 1, a detail of a parent at level j over
 * 4^(level-j-1) leaves of each child with energy about 3/4 of that. */
uint32_t bw_biohaar_inv_gain_q16(unsigned level, int coef_level);

#endif
