/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Measured BRDFs of the EPFL RGL database (Dupuy and Jakob 2018, "An
 * Adaptive Parameterization for Efficient Material Acquisition and
 * Rendering"), RGB files, in double precision.
 *
 * File: little-endian "tensor_file" (char[12] "tensor_file\0", u8 major = 1,
 * u8 minor = 0, u32 field count; per field u16 name length, name, u16 rank,
 * u8 dtype, u64 absolute offset, u64 shape[rank]; C order). Fields used:
 * theta_i, phi_i (incidence angles of the measurement), ndf and sigma (2-D
 * tables over the unit square), vndf (the sample warp, per incidence), rgb
 * [phi_i][theta_i][3][n][n] (reflectance samples on the warped grid) and
 * jacobian (u8 flag).
 *
 * Evaluating f(wi, wo) inverts the warp, as the authors' reference loader
 * does: the half vector wm maps to u_wm = (sqrt(theta_m 2/pi), phi / 2pi +
 * 1/2) (phi_m - phi_i for isotropic data), the VNDF warp of the incidence is
 * inverted to the sample position s, the rgb table is interpolated
 * bilinearly at s (and linearly between the tabulated incidences), and with
 * the jacobian flag the result is scaled by ndf(u_wm) / (4 sigma(u_wi)).
 * That value is the BRDF times the cosine of the outgoing direction (the
 * loader's "f_r * cos"); bwr_rgl_eval divides it out.
 *
 * The warp (Marginal2D of the loader): a density on an n0 x n1 grid over
 * [0,1]^2, bilinear inside each patch, optionally depending on parameters
 * (linear interpolation between tabulated parameter values); sampling
 * inverts the marginal CDF over rows, then the conditional CDF over columns;
 * bwr_rgl_warp_invert is its exact inverse.
 */
#ifndef BWR_RGL_H
#define BWR_RGL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BWR_WARP_MAX_DIM 3

typedef struct {
    uint32_t size[2];          /* columns (contiguous, first coordinate), rows */
    unsigned dim;              /* parameters */
    uint32_t param_size[BWR_WARP_MAX_DIM];
    uint32_t param_stride[BWR_WARP_MAX_DIM]; /* in slices; 0 when size 1 */
    double *param_values[BWR_WARP_MAX_DIM];
    size_t slices;
    double *data;              /* slices x rows x columns (normalised when it has CDFs) */
    double *marginal_cdf;      /* slices x rows, or NULL */
    double *conditional_cdf;   /* slices x rows x columns, or NULL */
    double inv_patch[2];       /* size - 1 */
} bwr_warp_t;

/* data: slices x size[1] x size[0] floats. With build_cdf the density is
 * normalised to integrate to 1 over the unit square and can be sampled;
 * without it eval returns the bilinear interpolation of data. 0, or -1. */
int bwr_warp_init(bwr_warp_t *w, uint32_t cols, uint32_t rows, const float *data, unsigned dim,
                  const uint32_t *param_res, const double *const *param_values, int build_cdf);
void bwr_warp_free(bwr_warp_t *w);
double bwr_warp_eval(const bwr_warp_t *w, const double pos[2], const double *param);
/* u in [0,1]^2 -> warped position (out) and density (pdf). Needs the CDFs. */
void bwr_warp_sample(const bwr_warp_t *w, const double u[2], const double *param, double out[2],
                     double *pdf);
/* The inverse: warped position -> u (out), density at pos (pdf). */
void bwr_warp_invert(const bwr_warp_t *w, const double pos[2], const double *param,
                     double out[2], double *pdf);

typedef struct {
    char description[256];
    size_t n_theta, n_phi;
    double *theta_i, *phi_i;   /* radians */
    int isotropic, jacobian;
    bwr_warp_t ndf, sigma, vndf, rgb;
} bwr_rgl_t;

/* Reads an RGB .bsdf file. 0, or -1 with a message in err (size errlen). */
int bwr_rgl_load(bwr_rgl_t *b, const char *path, char *err, size_t errlen);
void bwr_rgl_free(bwr_rgl_t *b);

/* f(wi, wo) in 1/sr for the three channels (directions away from the
 * surface, z = normal); 0 when either is below the horizon. The value
 * times wo[2] is the loader's "f_r * cos". */
void bwr_rgl_eval(const bwr_rgl_t *b, const double wi[3], const double wo[3], double rgb[3]);
void bwr_rgl_eval_cos(const bwr_rgl_t *b, const double wi[3], const double wo[3], double rgb[3]);

#ifdef __cplusplus
}
#endif

#endif
