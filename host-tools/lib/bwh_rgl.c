/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * RGL .bsdf files (Dupuy and Jakob's RGB tensor files) sampled on the grid:
 * the reference model's loader (host-tools/ref/bwr_rgl.h) evaluated at the
 * centres of the outgoing triangles of one level, for each measured
 * incidence below 89 degrees (in the plane phi = 0), as `import-rgl` does.
 * The incidence angles are kept as the file gives them (float32 radians),
 * with the quantity (BRDF, sr^-1), the channels' names and the file's
 * description.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "bwh_input.h"
#include "bwr_rgl.h"
#include "geodesic.h"

#define RGL_GRAZING (89.0 * 3.14159265358979323846 / 180.0)

int bwh_read_bsdf(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    char err[512];
    bwr_rgl_t b;
    if (bwr_rgl_load(&b, path, err, sizeof err) != 0)
        return bwh_fail("%s", err);
    unsigned level = o->level >= 0 ? (unsigned)o->level : 4u;
    int channel = o->channel;
    size_t nb = channel == 0 ? 3 : 1, c0 = channel == 0 ? 0 : (size_t)channel - 1;
    size_t n_out = bwh_grid_count(level), n_in = 0;
    double(*wo)[3] = malloc(n_out * sizeof *wo);
    double *theta = malloc((b.n_theta ? b.n_theta : 1) * sizeof *theta);
    int rc = -1;
    if (!wo || !theta || level > BW_MAX_LEVEL || bwh_grid_centres(level, wo, NULL) != 0) {
        bwh_fail(level > BW_MAX_LEVEL ? "%s: level above 6" : "%s: out of memory", path);
        goto out;
    }
    for (size_t k = 0; k < b.n_theta; k++)
        if (b.theta_i[k] < RGL_GRAZING)
            theta[n_in++] = b.theta_i[k];
    if (!n_in) {
        bwh_fail("%s: no incidence below 89 degrees", path);
        goto out;
    }
    m->values = malloc(n_in * n_out * nb * sizeof *m->values);
    if (!m->values) {
        bwh_fail("%s: out of memory", path);
        goto out;
    }
    for (size_t i = 0; i < n_in; i++) {
        double wi[3] = {sin(theta[i]), 0.0, cos(theta[i])};
        for (size_t r = 0; r < n_out; r++) {
            double v[3];
            bwr_rgl_eval(&b, wi, wo[r], v);
            for (size_t c = 0; c < nb; c++)
                m->values[(i * n_out + r) * nb + c] = (float)v[c0 + c];
        }
    }
    static const char *const names[] = {"red", "green", "blue"};
    bwh_meta_t *meta = &m->meta;
    meta->quantity = BWH_Q_BRDF;
    meta->sample_type = BWH_ST_F32;
    meta->present |= BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE;
    meta->inc_unit = BWH_ANGLE_RAD;
    if (bwh_meta_set_numbers(&meta->incidence, theta, n_in) ||
        bwh_meta_set_strings(&meta->band_names, names + c0, nb) ||
        (b.description[0] && bwh_meta_add_field(meta, "description", b.description)))
        goto out;
    m->shape = BW_SHAPE_BRDF_ISO;
    m->level_out = level;
    m->n_in = (uint32_t)n_in;
    m->bands = (uint32_t)nb;
    m->count = n_in * n_out * nb;
    rc = 0;
out:
    free(wo);
    free(theta);
    bwr_rgl_free(&b);
    if (rc)
        bwh_measure_free(m);
    return rc;
}
