/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Analytic BRDF models of the virtual goniometer (`brdfwave synth`).
 *
 * Directions are unit vectors pointing away from the surface, normal = +z;
 * wi the incoming (light) direction, wo the outgoing (view) direction.
 * Values are in 1/sr.
 *
 *   phong: kd/pi + ks (n+2)/(2 pi) max(0, r.wo)^n, r = mirror of wi about z
 *          (modified Phong, Lafortune & Willems 1994). Reciprocal; its
 *          directional albedo is at most kd + ks, with equality of the
 *          specular part (ks) at normal incidence.
 *   ward:  kd/pi + ks exp(-(hx^2/ax^2 + hy^2/ay^2)/hz^2)
 *                 / (4 pi ax ay sqrt(cos_i cos_o)),  h = wi + wo
 *          (Ward 1992, anisotropic); cosines are clamped to BWH_BRDF_COS_MIN
 *          so grazing directions stay finite. Reciprocal.
 */
#ifndef BWH_BRDF_MODELS_H
#define BWH_BRDF_MODELS_H

#ifdef __cplusplus
extern "C" {
#endif

#define BWH_BRDF_PI 3.14159265358979323846
#define BWH_BRDF_COS_MIN 1e-6 /* clamp for cos_i, cos_o and h_z (ward) */

typedef struct {
    double kd, ks; /* diffuse and specular albedo */
    double n;      /* phong exponent */
    double ax, ay; /* ward roughness along x and y */
} bwh_brdf_params_t;

double bwh_brdf_phong(const bwh_brdf_params_t *p, const double wi[3], const double wo[3]);
double bwh_brdf_ward(const bwh_brdf_params_t *p, const double wi[3], const double wo[3]);

#ifdef __cplusplus
}
#endif

#endif
