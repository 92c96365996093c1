/* SPDX-License-Identifier: BSD-2-Clause */
/* Shape options to dimensions (bwh_shape.h). */
#include "bwh_shape.h"

#include <math.h>

#include "bwh_error.h"
#include "geodesic.h"

#define SHAPE_PI 3.14159265358979323846

int bwh_shape_check(const bwh_shape_t *s)
{
    if (s->level < -1 || s->level > (int)BW_MAX_LEVEL)
        return bwh_fail("--level must be 0..%u", BW_MAX_LEVEL);
    if (s->level_in < -1 || s->level_in > (int)BW_MAX_LEVEL)
        return bwh_fail("--level-in must be 0..%u", BW_MAX_LEVEL);
    if (s->incoming > BW_MAX_N_IN)
        return bwh_fail("--incoming must be 1..%u", BW_MAX_N_IN);
    if (s->bands > BW_MAX_BANDS)
        return bwh_fail("--bands must be 1..%u", BW_MAX_BANDS);
    if (s->incoming && s->level_in >= 0)
        return bwh_fail("--incoming and --level-in exclude each other");
    if ((s->incoming || s->level_in >= 0) && s->level < 0)
        return bwh_fail("--incoming / --level-in need --level");
    return 0;
}

int bwh_shape_dims(const bwh_shape_t *s, size_t count, bw_dims_t *d)
{
    if (bwh_shape_check(s) != 0)
        return -1;
    if (!s->bands)
        return bwh_fail("--bands must be 1..%u", BW_MAX_BANDS);
    bw_status_t st;
    if (s->level < 0) {
        if (count % s->bands || count == 0)
            return bwh_fail("%zu samples is not a whole number of %u-band spectra", count,
                            s->bands);
        size_t n = count / s->bands;
        st = n > BW_MAX_N_IN ? BW_ERR_ARG
                             : bw_dims_make(d, BW_SHAPE_SPECTRA, 0, 0, (uint32_t)n, s->bands);
    } else if (s->level_in >= 0) {
        st = bw_dims_make(d, BW_SHAPE_BRDF_FULL, (unsigned)s->level, (unsigned)s->level_in, 0,
                          s->bands);
    } else if (s->incoming) {
        st = bw_dims_make(d, BW_SHAPE_BRDF_ISO, (unsigned)s->level, 0, s->incoming, s->bands);
    } else {
        st = bw_dims_make(d, BW_SHAPE_REFLECTANCE, (unsigned)s->level, 0, 1, s->bands);
    }
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t need = bw_dims_samples(d);
    if (count && need != count)
        return bwh_fail("input has %zu samples, the shape needs %zu (%u incoming x %u outgoing x "
                        "%u bands)",
                        count, need, d->n_in, d->n_out, d->bands);
    return 0;
}

double bwh_shape_theta_in(size_t k, size_t n)
{
    return ((double)k + 0.5) * (SHAPE_PI / 2.0) / (double)n;
}

int bwh_shape_incoming(const bw_dims_t *d, double (*wi)[3])
{
    if (d->shape == BW_SHAPE_BRDF_FULL)
        return bwh_grid_centres(d->level_in, wi, NULL) == 0 ? 0 : bwh_fail("out of memory");
    for (size_t i = 0; i < d->n_in; i++) {
        double th = d->shape == BW_SHAPE_BRDF_ISO ? bwh_shape_theta_in(i, d->n_in) : 0.0;
        wi[i][0] = sin(th);
        wi[i][1] = 0.0;
        wi[i][2] = cos(th);
    }
    return 0;
}
