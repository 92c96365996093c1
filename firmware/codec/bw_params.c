/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Which shapes, modes, bases and flags go together: one set of rules for the
 * encoder's parameters, the streaming encoder's and a payload's header
 * (docs/FORMAT.md, Header).
 */
#include "bw_internal.h"

bool bw_pred_applies(const bw_dims_t *d, unsigned mode, unsigned flags)
{
    return d->shape == BW_SHAPE_SPECTRA && mode <= BW_MODE_MAX_ERROR &&
           !(flags & BW_FLAG_STREAM_ORDER);
}

/* The basis: a transform; BW_BASIS_AUTO for bw_encode; prediction where it
 * applies, in every payload and from bw_encode built with it. */
static bool basis_ok(const bw_dims_t *d, unsigned mode, unsigned basis, unsigned flags,
                     unsigned use)
{
    if (basis < BW_BASIS_COUNT)
        return true;
    if (basis == BW_BASIS_AUTO)
        return use == BW_FOR_ENCODE;
    return basis == BW_BASIS_PRED && (use == BW_FOR_PAYLOAD || BW_CFG_ENCODE_PRED) &&
           bw_pred_applies(d, mode, flags);
}

bw_status_t bw_params_check(const bw_dims_t *d, unsigned mode, unsigned basis, unsigned flags,
                            uint32_t param, unsigned use)
{
    bw_status_t st = bw_dims_check(d);
    if (st != BW_OK)
        return st;
    /* the streaming encoder: stream order, which leaves out the full BRDF
     * (its incoming transform needs every hemisphere at once), and neither
     * the byte budget, prediction nor the symmetry steps (the partner of a
     * direction may arrive after it) */
    unsigned refused = ~BW_FLAGS_KNOWN;
    if (use == BW_FOR_STREAM) {
        if (d->shape == BW_SHAPE_BRDF_FULL)
            return BW_ERR_SHAPE;
        flags |= BW_FLAG_STREAM_ORDER;
        refused |= BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL;
        if (mode == BW_MODE_BYTES)
            return BW_ERR_ARG;
    }
    if (mode > BW_MODE_STEP || !basis_ok(d, mode, basis, flags, use) || (flags & refused) != 0u)
        return BW_ERR_ARG;
    /* both coders' flags: the static-table coder, which counts the whole
     * body before it codes (not for the streaming encoder) */
    bool tab = (flags & BW_FLAG_RICE) && (flags & BW_FLAG_MS);
    if (BW_CFG_CODER_TAB && tab && use == BW_FOR_STREAM)
        return BW_ERR_ARG;
    if ((flags & BW_FLAG_STREAM_ORDER) && d->shape == BW_SHAPE_BRDF_FULL)
        return BW_ERR_SHAPE; /* the incoming transform needs every hemisphere at once */
    if ((flags & BW_FLAG_MIRROR) && d->shape == BW_SHAPE_SPECTRA)
        return BW_ERR_SHAPE; /* no directions to mirror */
    if ((flags & BW_FLAG_RECIPROCAL) &&
        (d->shape != BW_SHAPE_BRDF_FULL || d->level_in != d->level_out))
        return BW_ERR_SHAPE; /* incoming and outgoing on different grids */
    if (mode == BW_MODE_MAX_ERROR && (param < 1u || param > BW_SAMPLE_MAX))
        return BW_ERR_ARG;
    if (mode == BW_MODE_STEP && param < BW_STEP_ONE_Q8)
        return BW_ERR_ARG;
    /* last: a valid request or payload this build cannot code */
    if ((!BW_CFG_CODER_MS && (flags & BW_FLAG_MS)) ||
        (BW_CFG_CODER_MS && !BW_CFG_CODER_TAB && tab)) /* (without MS, MS alone says it) */
        return BW_ERR_NOT_BUILT;
    return BW_OK;
}
