/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The transform driver: the spectral lifting (bw_spectral.c) on every
 * spectrum, then Bio-Haar (bw_biohaar.c) on the outgoing hemisphere of every
 * incoming direction, then, for a full BRDF, on the incoming hemisphere with
 * whole [outgoing][band] blocks as its vectors; the inverse in the other
 * order (docs/FORMAT.md, Transform).
 *
 * Scaling and overflow: see bw_spectral.c and bw_biohaar.c. Samples of at
 * most 2^24 in magnitude give coefficients well inside int32; beyond that
 * the lifting wraps modulo 2^32 and stays reversible (bw_fixed.h).
 */
#include "bw_internal.h"

void bw_transform_fwd(const bw_plan_t *pl, int32_t *x, unsigned done)
{
    const bw_dims_t *d = &pl->dims;
    size_t vectors = (size_t)d->n_in * d->n_out;
    uint32_t n = d->bands;
    for (unsigned l = 0; l < done; l++)
        n = (n + 1u) / 2u;
    unsigned levels = pl->spec_levels - done;
    if (levels)
        for (size_t v = 0; v < vectors; v++)
            bw_spec_fwd(x + v * d->bands, n, pl->basis, levels, pl->tmp);
#if BW_CFG_UNROLL
    if (bw_has_out(d) && d->bands == 1u) /* the incoming blocks together */
        bw_biohaar_fwd_blocks(x, d->level_out, d->n_in, d->n_out);
    else
#endif
    if (bw_has_out(d))
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_fwd(x + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
    if (bw_has_in(d))
        bw_biohaar_fwd(x, d->level_in, (size_t)d->n_out * d->bands);
}

void bw_transform_inv(const bw_plan_t *pl, int32_t *x)
{
    const bw_dims_t *d = &pl->dims;
    size_t vectors = (size_t)d->n_in * d->n_out;
    if (bw_has_in(d))
        bw_biohaar_inv(x, d->level_in, (size_t)d->n_out * d->bands);
#if BW_CFG_UNROLL
    if (bw_has_out(d) && d->bands == 1u)
        bw_biohaar_inv_blocks(x, d->level_out, d->n_in, d->n_out);
    else
#endif
    if (bw_has_out(d))
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_inv(x + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
    if (pl->spec_levels)
        for (size_t v = 0; v < vectors; v++)
            bw_spec_inv(x + v * d->bands, d->bands, pl->basis, pl->spec_levels, pl->tmp);
}
