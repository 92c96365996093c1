/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Scaling and overflow: s_P is a convex combination of its children, so
 * scaling coefficients stay within the sample range; details are differences
 * of scaling values, at most twice the range. The update sum is formed in 64
 * bits (|d| < 2^26, L_m < 2^16).
 */
#include "bw_biohaar.h"

#include <stdbool.h>

#include "bw_fixed.h"
#include "bw_geodesic.h"

void bw_geo_weights_finest(uint32_t parent_in_base, uint16_t w[3])
{
    /* rotate the digits until the first non-zero one is 1: the stored
     * parent c, r the rotation; its rank among the stored parents is
     * c - 2 (4^t - 1) / 3 for the digit t after its first non-zero one */
    uint32_t c = 0, rank = 0;
    unsigned r = 0;
    for (int k = 2 * (int)BW_GEO_TABLE_LEVELS - 4; k >= 0; k -= 2) {
        unsigned x = (parent_in_base >> k) & 3u;
        if (x && !c) {
            r = x - 1u;
            rank = 2u * ((1u << k) - 1u) / 3u;
        }
        c = c << 2 | (x ? (x + 2u - r) % 3u + 1u : 0u);
    }
    uint32_t i = 3u * (c - rank);
    for (unsigned m = 0; m < 3u; m++, i++)
        w[(m + r) % 3u] =
            (uint16_t)(16384u - ((bw_geo_weight_finest[i >> 1] >> (4u * (i & 1u))) & 15u));
}

static inline int32_t update_term(const uint16_t *w, int32_t d1, int32_t d2, int32_t d3)
{
    int64_t acc = (int64_t)w[0] * d1 + (int64_t)w[1] * d2 + (int64_t)w[2] * d3;
    return (int32_t)(uint32_t)(uint64_t)bw_asr64(acc + 32768, 16);
}

void bw_biohaar_lift4(int32_t *c0, int32_t *c1, int32_t *c2, int32_t *c3, const uint16_t *w,
                      size_t vlen)
{
    for (size_t e = 0; e < vlen; e++) {
        int32_t d1 = bw_wsub(c1[e], c0[e]);
        int32_t d2 = bw_wsub(c2[e], c0[e]);
        int32_t d3 = bw_wsub(c3[e], c0[e]);
        c0[e] = bw_wadd(c0[e], update_term(w, d1, d2, d3));
        c1[e] = d1;
        c2[e] = d2;
        c3[e] = d3;
    }
}

/* One parent's inverse step: c0 = s_P and c_m = d_m become the children. */
static void unlift4(int32_t *c0, int32_t *c1, int32_t *c2, int32_t *c3, const uint16_t *w,
                    size_t vlen)
{
    for (size_t e = 0; e < vlen; e++) {
        int32_t s0 = bw_wsub(c0[e], update_term(w, c1[e], c2[e], c3[e]));
        c0[e] = s0;
        c1[e] = bw_wadd(c1[e], s0);
        c2[e] = bw_wadd(c2[e], s0);
        c3[e] = bw_wadd(c3[e], s0);
    }
}

/* Every parent's step, the finest parents first (forward) or the coarsest
 * (inverse); built once per direction with BW_CFG_UNROLL, else one copy
 * runs both. */
#if BW_CFG_UNROLL
#define RUN_INLINE BW_ALWAYS_INLINE
#else
#define RUN_INLINE BW_NOINLINE
#endif
static RUN_INLINE void biohaar_run(int32_t *x, unsigned level, size_t vlen, bool inverse)
{
    for (unsigned i = 0; i < level; i++) {
        unsigned j = inverse ? i : level - 1u - i;
        size_t h = (size_t)1 << (2u * (level - j - 1u)); /* child stride, leaves */
        uint32_t per_base = 1u << (2u * j);
        for (uint32_t p = 0; p < 4u * per_base; p++) {
            uint16_t w[3];
            bw_geo_weights(j, p & (per_base - 1u), w);
            int32_t *c0 = x + (size_t)p * 4u * h * vlen;
            int32_t *c1 = c0 + h * vlen, *c2 = c1 + h * vlen, *c3 = c2 + h * vlen;
            if (inverse)
                unlift4(c0, c1, c2, c3, w, vlen);
            else
                bw_biohaar_lift4(c0, c1, c2, c3, w, vlen);
        }
    }
}

void bw_biohaar_fwd(int32_t *x, unsigned level, size_t vlen) { biohaar_run(x, level, vlen, false); }

void bw_biohaar_inv(int32_t *x, unsigned level, size_t vlen) { biohaar_run(x, level, vlen, true); }

#if BW_CFG_UNROLL
/* biohaar_run on the trees of `blocks` hemispheres `stride` apart, one
 * value each (vlen 1): each parent's weights found once for all of them,
 * the step on each tree in turn (the same values as one tree at a time). */
static BW_ALWAYS_INLINE void biohaar_run_blocks(int32_t *x, unsigned level, size_t blocks,
                                                size_t stride, bool inverse)
{
    for (unsigned i = 0; i < level; i++) {
        unsigned j = inverse ? i : level - 1u - i;
        size_t h = (size_t)1 << (2u * (level - j - 1u));
        uint32_t per_base = 1u << (2u * j);
        for (uint32_t p = 0; p < 4u * per_base; p++) {
            uint16_t w[3];
            bw_geo_weights(j, p & (per_base - 1u), w);
            int32_t *c0 = x + (size_t)p * 4u * h;
            for (size_t b = 0; b < blocks; b++, c0 += stride) {
                if (inverse)
                    unlift4(c0, c0 + h, c0 + 2u * h, c0 + 3u * h, w, 1u);
                else
                    bw_biohaar_lift4(c0, c0 + h, c0 + 2u * h, c0 + 3u * h, w, 1u);
            }
        }
    }
}

void bw_biohaar_fwd_blocks(int32_t *x, unsigned level, size_t blocks, size_t stride)
{
    biohaar_run_blocks(x, level, blocks, stride, false);
}

void bw_biohaar_inv_blocks(int32_t *x, unsigned level, size_t blocks, size_t stride)
{
    biohaar_run_blocks(x, level, blocks, stride, true);
}
#endif

void bw_biohaar_inv_node(int32_t *x, unsigned level, size_t vlen, unsigned j, uint32_t p)
{
    size_t h = (size_t)1 << (2u * (level - j - 1u));
    uint32_t per_base = 1u << (2u * j);
    uint16_t w[3];
    bw_geo_weights(j, p & (per_base - 1u), w);
    int32_t *c0 = x + (size_t)p * 4u * h * vlen;
    unlift4(c0, c0 + h * vlen, c0 + 2u * h * vlen, c0 + 3u * h * vlen, w, vlen);
}

int bw_biohaar_coef_level(uint32_t idx)
{
    if (idx < 4u)
        return -1;
    int j = 0;
    while (idx >= (1u << (2u * (unsigned)(j + 2))))
        j++;
    return j;
}

uint32_t bw_biohaar_pos(uint32_t idx, unsigned level)
{
    if (idx < 4u)
        return idx << (2u * level);
    unsigned j = (unsigned)bw_biohaar_coef_level(idx);
    uint32_t r = idx - (1u << (2u * (j + 1u)));
    uint32_t p = r / 3u, m = r % 3u + 1u;
    return (4u * p + m) << (2u * (level - j - 1u));
}

uint32_t bw_biohaar_inv_gain_q16(unsigned level, int coef_level)
{
    if (coef_level < 0)
        return 65536u >> level;
    /* 1 / (sqrt(3/4) * 2^(level - j - 1)) */
    return 75674u >> (level - (unsigned)coef_level - 1u);
}
