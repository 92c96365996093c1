/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The plan of one encode or decode: dims, basis, prequantiser, step and
 * flags, where the spectral tables and the lifting scratch live, and the
 * tables themselves (the context class, spectral parent and inverse gain of
 * each band). One constructor for the encoder, the decoder and the
 * streaming encoder.
 */
#include "bw_internal.h"

void bw_plan_make(bw_plan_t *pl, const bw_dims_t *dims, unsigned basis, unsigned mode,
                  uint32_t param, unsigned flags, uint32_t vec_thresh_q8, int32_t *tables,
                  int32_t *tmp)
{
    pl->dims = *dims;
    pl->n = bw_dims_samples(dims);
    pl->basis = basis;
    pl->spec_levels = bw_plan_spec_levels(basis, dims->bands);
    pl->prequant = bw_prequant(mode, param);
    pl->step_q8 = mode >= BW_MODE_BYTES ? param : BW_STEP_ONE_Q8;
    pl->vec_thresh_q8 = vec_thresh_q8 ? vec_thresh_q8 : BW_VEC_THRESH_Q8;
    pl->round_q8 = 0;
    pl->round_cut = 0;
    pl->mirror = (flags & BW_FLAG_MIRROR) != 0u;
    pl->recip = (flags & BW_FLAG_RECIPROCAL) != 0u;
    pl->stream = (flags & BW_FLAG_STREAM_ORDER) != 0u;
    pl->seg_vec = 0;
    if (BW_CFG_BANDS)
        pl->bands = false;
    if (BW_CFG_EMBED)
        pl->embed = 0u;
#if BW_CFG_CHUNK_STEPS
    pl->chunk_vec = 0;
    pl->chunk_d = NULL;
#endif
#if BW_RATE
    pl->rate = NULL;
#endif
    pl->spec_cls = tables;
    pl->spec_gain = tables + dims->bands;
    pl->tmp = tmp;
}

/* The spectral parent of a detail coefficient (Mallat order) is the one at
 * the same place in the next coarser detail band; the coarsest details and
 * the approximation have none. */
void bw_plan_tables(const bw_plan_t *pl)
{
    unsigned L = pl->spec_levels;
    /* band sb = 1..L (1 finest) is [len_sb, len_sb-1), len_0 = bands and
     * len_sb = (len_sb-1 + 1) / 2; then the approximation [0, len_L) */
    for (uint32_t end = pl->dims.bands, sb = 1;; sb++) {
        bool approx = sb > L;
        uint32_t lo = approx ? 0u : (end + 1u) / 2u, plo = (lo + 1u) / 2u;
        /* 0 finest details, 1 next, 2 coarser details, 3 approximation */
        uint32_t cls = approx ? 3u : sb >= 3u ? 2u : sb - 1u;
        int32_t gain = (int32_t)bw_spec_inv_gain_q16(pl->basis, L, approx ? 0u : sb);
        for (uint32_t k = lo; k < end; k++) {
            uint32_t par = 0, i = (k - lo) / 2u;
            if (sb < L)
                par = 1u + plo + (i < lo - plo ? i : lo - plo - 1u);
            pl->spec_cls[k] = (int32_t)(cls | par << 2);
            pl->spec_gain[k] = gain;
        }
        if (approx)
            return;
        end = lo;
    }
}
