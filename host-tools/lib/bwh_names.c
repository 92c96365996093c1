/* SPDX-License-Identifier: BSD-2-Clause */
/* Names of header fields and encoder choices (bwh_names.h). */
#include "bwh_names.h"

#include <string.h>

#include "bw_codec.h"
#include "bwh_encode.h"

/* the index of name in names[n], or -1 */
static int find(const char *const *names, int n, const char *name)
{
    for (int i = 0; name && i < n; i++)
        if (!strcmp(names[i], name))
            return i;
    return -1;
}

static const char *const shapes[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
static const char *const modes[] = {"lossless", "max-error", "bytes", "step"};
static const char *const bases[] = {"haar", "53", "97", "pred"};
static const char *const symmetries[] = {"none", "mirror", "reciprocal", "both"};
static const char *const coders[] = {"range", "rice", "ms", "tab"};

#define COUNT(a) ((int)(sizeof a / sizeof *a))

const char *bwh_shape_name(unsigned s) { return s < 4 ? shapes[s] : "?"; }

const char *bwh_mode_name(unsigned m) { return m < 4 ? modes[m] : "?"; }

const char *bwh_basis_name(unsigned b) { return b < 4 ? bases[b] : "?"; }

int bwh_basis_from_name(const char *name)
{
    if (name && !strcmp(name, "auto"))
        return BW_BASIS_AUTO;
    return find(bases, COUNT(bases), name);
}

const char *bwh_symmetry_name(unsigned flags)
{
    return symmetries[(flags & BW_FLAG_MIRROR ? 1 : 0) + (flags & BW_FLAG_RECIPROCAL ? 2 : 0)];
}

int bwh_symmetry_from_name(const char *name)
{
    static const unsigned flags[] = {0, BW_FLAG_MIRROR, BW_FLAG_RECIPROCAL,
                                     BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL};
    if (name && !strcmp(name, "auto"))
        return 0;
    int k = find(symmetries, COUNT(symmetries), name);
    return k < 0 ? -1 : (int)(flags[k] | BWH_NO_MIRROR);
}

const char *bwh_coder_name(unsigned flags)
{
    unsigned f = flags & (BW_FLAG_RICE | BW_FLAG_MS);
    return coders[f == (BW_FLAG_RICE | BW_FLAG_MS) ? 3 : f == BW_FLAG_RICE ? 1 : f ? 2 : 0];
}

int bwh_coder_from_name(const char *name)
{
    int k = find(coders, COUNT(coders), name);
    static const unsigned flag[] = {0u, BW_FLAG_RICE, BW_FLAG_MS, BW_FLAG_RICE | BW_FLAG_MS};
    return k < 0 ? -1 : (int)flag[k];
}
