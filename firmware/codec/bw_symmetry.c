/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Symmetry steps before the transform (docs/FORMAT.md, Transform, steps 0):
 * the mirror image (x, -y, z) of the outgoing hemisphere (BW_FLAG_MIRROR)
 * and reciprocity, f(wi, wo) = f(wo, wi) (BW_FLAG_RECIPROCAL).
 */
#include "bw_internal.h"

/* The direction index of the mirror image (x, -y, z) of direction o at a
 * level: base triangle b goes to 3 - b, and in every child digit the
 * corners 2 and 3 trade places (0, 1, 2, 3 -> 0, 1, 3, 2). */
BW_NOINLINE_SMALL uint32_t bw_mirror_index(uint32_t o, unsigned level)
{
    unsigned sh = 2u * level;
    uint32_t r = o & ((1u << sh) - 1u);
    return (3u - (o >> sh)) << sh | (r ^ ((r >> 1) & 0x55555555u));
}

/* The symmetry steps, on whole vectors of samples; a vector whose partner
 * comes first in [incoming][outgoing] order is coded as its difference
 * from the partner:
 *   BW_FLAG_MIRROR      the mirrored half, each vector against its mirror
 *                       image: (i, m(o)), or for a full BRDF (m(i), m(o))
 *                       for the incoming half i >= n_in / 2;
 *   BW_FLAG_RECIPROCAL  then, in the rows MIRROR leaves (all, or i < n / 2),
 *                       (i, o) against (o, i), or with MIRROR and o in the
 *                       mirrored half against (m(o), m(i)).
 * Forward runs the steps in that order and each backwards (every partner
 * still holds its samples); inverse the other way round. In 32-bit wrapping
 * arithmetic: a corrupt body decodes to wrong samples, never to undefined
 * behaviour; forward, BW_ERR_RANGE if a difference leaves +-BW_SAMPLE_MAX. */
bw_status_t bw_symmetry(const bw_plan_t *pl, int32_t *x, bool forward)
{
    const bw_dims_t *d = &pl->dims;
    unsigned lo = d->level_out, li = d->level_in, sh = 2u * lo + 2u;
    uint32_t ni = d->n_in, no = d->n_out, rows = pl->mirror ? ni / 2u : ni;
    bool full = bw_has_in(d);
    size_t b = d->bands, total = (size_t)ni << sh;
    uint32_t neg = forward ? ~0u : 0u, bad = 0; /* p ^ neg - neg: -p or p */
    for (unsigned step = 0; step < 2u; step++) {
        bool rec = (step == 0u) != forward;
        if (rec ? !pl->recip : !pl->mirror)
            continue;
        for (size_t t = 0; t < total; t++) {
            size_t s = forward ? total - 1u - t : t;
            uint32_t i = (uint32_t)(s >> sh), o = (uint32_t)s & (no - 1u), a = i, c = o;
            if (rec) {
                if (i < rows) {
                    a = o;
                    c = i;
                    if (o >= rows) {
                        a = bw_mirror_index(o, lo);
                        c = bw_mirror_index(i, lo);
                    }
                }
            } else if (full ? i >= ni / 2u : o >= no / 2u) {
                if (full)
                    a = bw_mirror_index(i, li);
                c = bw_mirror_index(o, lo);
            }
            size_t ps = ((size_t)a << sh) + c;
            if (ps >= s)
                continue;
            uint32_t *v = (uint32_t *)x + s * b;
            const uint32_t *p = (const uint32_t *)x + ps * b;
            for (size_t k = 0; k < b; k++) {
                uint32_t r = v[k] + ((p[k] ^ neg) - neg);
                bad |= r + BW_SAMPLE_MAX > 2u * BW_SAMPLE_MAX;
                v[k] = r;
            }
        }
    }
    return bad & neg ? BW_ERR_RANGE : BW_OK;
}
