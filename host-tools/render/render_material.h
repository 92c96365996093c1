/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Materials of the renderer: diffuse walls, the light, and the materials of
 * the objects (analytic Phong or Ward, or a decoded payload), each with the
 * sampling hierarchy of bw_sample.h when the wavelet strategy needs it.
 */
#ifndef RENDER_MATERIAL_H
#define RENDER_MATERIAL_H

#include "brdf_eval.h"
#include "brdf_models.h"
#include "bw_sample.h"
#include "render_vec.h"

enum mat_kind { MAT_DIFFUSE, MAT_PHONG, MAT_WARD, MAT_DATA, MAT_LIGHT };

/* An object's material as given (`--material`): kind MAT_PHONG (p: kd, ks,
 * n), MAT_WARD (p: kd, ks, ax, ay) or MAT_DATA (path: a payload file); spec
 * the text it came from. */
typedef struct {
    enum mat_kind kind;
    bwh_brdf_params_t p;
    const char *path;
    const char *spec;
} render_material_spec_t;

/* the hierarchy's options (`--level`, `--supersample`, `--tables`, `--mix`) */
typedef struct {
    uint32_t level, supersample;
    unsigned long tables; /* 0: by the material */
    double mix;
} render_sampler_opts_t;

typedef struct {
    enum mat_kind kind;
    v3 albedo;            /* diffuse: reflectance; light: emitted radiance */
    bwh_brdf_params_t p;  /* phong, ward */
    bwh_brdf_data_t data; /* decoded payload */
    bwh_sampler_t sampler;
    int has_sampler;
    char spec[256];
} material_t;

/* An object's material, with its hierarchy when want_sampler. The sampler
 * keeps m as its context: m must stay where it is. 0, or -1
 * (bwh_last_error(): a payload that does not load or is not a BRDF of 1 or
 * 3 bands, out of memory). */
int render_material_init(material_t *m, const render_material_spec_t *spec,
                         const render_sampler_opts_t *so, int want_sampler);
void render_material_free(material_t *m);

/* f(wi, wo) per channel, directions in the local frame (z = normal) */
v3 render_material_eval(const material_t *m, const double wi[3], const double wo[3]);

#endif
