/* SPDX-License-Identifier: BSD-2-Clause */
/* Materials of the renderer (render_material.h). */
#include "render_material.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "geodesic.h"

static double analytic_f(void *ctx, const double wi[3], const double wo[3])
{
    const material_t *m = ctx;
    return m->kind == MAT_PHONG ? bwh_brdf_phong(&m->p, wi, wo) : bwh_brdf_ward(&m->p, wi, wo);
}

v3 render_material_eval(const material_t *m, const double wi[3], const double wo[3])
{
    switch (m->kind) {
    case MAT_DIFFUSE:
        return mul(m->albedo, 1.0 / R_PI);
    case MAT_PHONG: {
        double f = bwh_brdf_phong(&m->p, wi, wo);
        return vec(f, f, f);
    }
    case MAT_WARD: {
        double f = bwh_brdf_ward(&m->p, wi, wo);
        return vec(f, f, f);
    }
    case MAT_DATA: {
        double c[3];
        for (size_t k = 0; k < 3; k++) {
            double v = bwh_brdf_data_band(&m->data, wi, wo, m->data.bands == 3 ? k : 0);
            c[k] = v > 0.0 ? v : 0.0; /* values below 0 left by compression */
        }
        return vec(c[0], c[1], c[2]);
    }
    default:
        return vec(0, 0, 0);
    }
}

/* the hierarchy of m (sec. 5.2, 6.1) */
static int build_sampler(material_t *m, const render_sampler_opts_t *so)
{
    int rc;
    if (m->kind == MAT_DATA) {
        const bwh_brdf_data_t *d = &m->data;
        rc = d->shape == BW_SHAPE_BRDF_ISO
                 ? bwh_sampler_build(&m->sampler, BWH_SAMPLER_ISO, so->level, d->n_in,
                                     d->theta_in, 0, bwh_brdf_data_mean_cb, &m->data,
                                     so->supersample, so->mix)
                 : bwh_sampler_build(&m->sampler, BWH_SAMPLER_FULL, so->level, d->n_in, NULL,
                                     d->level_in, bwh_brdf_data_mean_cb, &m->data,
                                     so->supersample, so->mix);
    } else if (m->kind == MAT_PHONG || m->p.ax == m->p.ay) {
        /* isotropic (Phong, Ward with AX = AY): tables over theta_i only,
         * turned to the hit's azimuth (sec. 5.2) */
        unsigned long n = so->tables ? so->tables : 32;
        double *th = malloc(n * sizeof *th);
        if (!th)
            return bwh_fail("out of memory");
        for (unsigned long k = 0; k < n; k++)
            th[k] = k * 0.5 * R_PI / (double)n; /* from normal incidence */
        rc = bwh_sampler_build(&m->sampler, BWH_SAMPLER_ISO, so->level, n, th, 0, analytic_f,
                               m, so->supersample, so->mix);
        free(th);
    } else {
        /* anisotropic: one table per incoming triangle, at least --tables of
         * them; by default the level whose triangles (their width taken as
         * the square root of their solid angle, 2 pi / count) are at most
         * 1.6 x the narrower roughness, so that the lobe moves by less than
         * its width within one triangle */
        unsigned li = 0;
        double a = fmin(m->p.ax, m->p.ay);
        while (li < 4 && (so->tables ? bwh_grid_count(li) < so->tables
                                     : sqrt(2.0 * R_PI / (double)bwh_grid_count(li)) > 1.6 * a))
            li++;
        rc = bwh_sampler_build(&m->sampler, BWH_SAMPLER_FULL, so->level, bwh_grid_count(li), NULL,
                               li, analytic_f, m, so->supersample, so->mix);
    }
    return rc;
}

int render_material_init(material_t *m, const render_material_spec_t *spec,
                         const render_sampler_opts_t *so, int want_sampler)
{
    memset(m, 0, sizeof *m);
    snprintf(m->spec, sizeof m->spec, "%s", spec->spec);
    m->kind = spec->kind;
    m->p = spec->p;
    if (m->kind == MAT_DATA) {
        if (bwh_brdf_data_load(&m->data, spec->path) != 0)
            return -1;
        if (m->data.shape == BW_SHAPE_REFLECTANCE) {
            bwh_brdf_data_free(&m->data);
            return bwh_fail("%s: a reflectance, not a BRDF (needs --incoming or --level-in)",
                            spec->path);
        }
        if (m->data.bands != 1 && m->data.bands != 3) {
            size_t bands = m->data.bands;
            bwh_brdf_data_free(&m->data);
            return bwh_fail("%s: %zu bands; render reads 1 band or 3 (R, G, B)", spec->path,
                            bands);
        }
    }
    if (!want_sampler)
        return 0;
    if (build_sampler(m, so) != 0) {
        render_material_free(m);
        return -1;
    }
    m->has_sampler = 1;
    return 0;
}

void render_material_free(material_t *m)
{
    if (m->kind == MAT_DATA)
        bwh_brdf_data_free(&m->data);
    if (m->has_sampler)
        bwh_sampler_free(&m->sampler);
    m->has_sampler = 0;
    m->kind = MAT_DIFFUSE;
}
