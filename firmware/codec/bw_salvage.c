/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * What a decode of a damaged payload rebuilt (bw_decode_salvage): the lost
 * coefficient vectors carried through the decoder's inverse steps, so that
 * every direction pair is known to be exact, approximate or missing.
 */
#include <string.h>

#include "bw_internal.h"

#define AFF 1u  /* depends on a lost coefficient                      */
#define MISS 2u /* and its coarsest level (a scaling coefficient) was lost */

/* One Bio-Haar tree of a level-L hemisphere (elements `stride` apart),
 * coarse to fine as the inverse lifting runs: the centre child is rebuilt
 * from the parent's scaling value and the three details, each corner child
 * from its detail and the centre child. */
static void mask_tree(uint8_t *a, unsigned L, size_t stride)
{
    size_t n = (size_t)4u << (2u * L);
    for (unsigned j = 0; j < L; j++) {
        size_t q = (size_t)1 << (2u * (L - j - 1u));
        for (size_t p = 0; p < n; p += 4u * q) {
            uint8_t *s = a + p * stride, *d1 = s + q * stride, *d2 = d1 + q * stride,
                    *d3 = d2 + q * stride;
            uint8_t x0 = (uint8_t)(*s | ((*d1 | *d2 | *d3) & AFF));
            *s = x0;
            *d1 = (uint8_t)((*d1 & AFF) | x0);
            *d2 = (uint8_t)((*d2 & AFF) | x0);
            *d3 = (uint8_t)((*d3 & AFF) | x0);
        }
    }
}

void bw_salvage_mask(const bw_header_t *h, const uint8_t *vec_lost, uint8_t *mask, int32_t *tmp)
{
    const bw_dims_t *d = &h->dims;
    size_t nv = (size_t)d->n_in * d->n_out;
    for (size_t k = 0; k < nv; k++)
        mask[k] = vec_lost[k] == 1u ? AFF | MISS : vec_lost[k] ? AFF : 0u;
    if (bw_has_in(d))
        for (uint32_t o = 0; o < d->n_out; o++)
            mask_tree(mask + o, d->level_in, d->n_out);
    if (bw_has_out(d))
        for (uint32_t i = 0; i < d->n_in; i++)
            mask_tree(mask + (size_t)i * d->n_out, d->level_out, 1u);
    if (h->flags & (BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL)) {
        /* the symmetry steps add each partner back: a count of lost
         * dependencies per flag, carried by the same additions */
        bw_dims_t one = *d;
        one.bands = 1u;
        bw_plan_t pl;
        bw_plan_make(&pl, &one, BW_BASIS_HAAR, BW_MODE_LOSSLESS, 0u, h->flags, 0u, tmp, tmp);
        for (unsigned bit = AFF; bit <= MISS; bit <<= 1) {
            for (size_t k = 0; k < nv; k++)
                tmp[k] = (mask[k] & bit) != 0u;
            bw_symmetry(&pl, tmp, false);
            for (size_t k = 0; k < nv; k++)
                if (tmp[k])
                    mask[k] |= (uint8_t)bit;
        }
    }
    for (size_t k = 0; k < nv; k++)
        mask[k] = mask[k] & MISS ? BW_SAMPLE_MISSING : mask[k] & AFF ? BW_SAMPLE_APPROX
                                                                     : BW_SAMPLE_EXACT;
}

