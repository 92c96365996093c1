/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Importance sampling of a BRDF from the triangle hierarchy (sec. 6.1).
 *
 * For each tabulated incoming direction the sampler forms, on the geodesic
 * triangles of one level (the "level of accuracy"), the integral of
 * max(0, f(wi, wo)) cos(theta_o) over each triangle, and above them the sums
 * of the children up to the 4 base triangles: every node's integral over its
 * subtree. f is a scalar given by a callback: the BRDF integrated over
 * wavelength, or one channel (bwh_brdf_data_band_cb), so analytic models and
 * decoded payloads are sampled the same way. A cosine lobe with weight
 * `mix` is mixed into every table: leaf k's probability is
 *   (1 - mix) integral_k / sum of integrals + mix proj_k / pi
 * (proj_k: the integral of cos(theta_o) over the leaf), positive on every
 * leaf, hence wherever the BRDF is. These are kept as where each node's
 * part of [0, 2^31) ends, the parts of 4 siblings following each other
 * inside their parent's (a node's probability is its part's width / 2^31;
 * a node of positive probability has a part at least 1 wide, one of
 * probability 0 an empty one): the ends of every leaf (4 bytes a leaf) and
 * of the nodes of every other level above them, level - 1, level - 3, ...
 * (4/15 of a node per leaf: about 1 byte more per leaf).
 *
 *   sample   descend from the base triangles, picking the child whose part
 *            holds the point floor(u0 2^31), so each child with probability
 *            its integral over its parent's: two levels a step (the one of
 *            16 grandchildren whose part holds the point) down to the
 *            leaves' parents, then the leaf: O(log4 n). Then a uniform
 *            direction in the leaf's spherical triangle (Arvo 1995, from u1
 *            and u2); with it the pdf and, on request, the BRDF's value
 *            there;
 *   pdf      leaf probability / leaf solid angle: piecewise constant. The
 *            descent's leaf has the width the build gave it, so sample's pdf
 *            and pdf() agree to the bit away from leaf edges.
 *
 * Negative values (left by lossy compression) and values that are not finite
 * count as 0, by one clamp used for the leaf integrals and for sample's
 * value, so sample, pdf and the value see the same function.
 *
 * Incoming directions:
 *   BWH_SAMPLER_ISO   tables at zenith angles theta_k in the plane phi = 0;
 *                     wi and wo are turned about the normal until phi_i = 0
 *                     (the azimuthal rotation of sec. 5.2) and the two
 *                     tables around theta_i are mixed with the weights
 *                     sin(theta_i - theta_lo) and sin(theta_hi - theta_i),
 *                     normalised (within d^2 / 32 of the linear weight for
 *                     tables d radians apart, and no inverse trigonometry);
 *                     the two are found from cos(theta_i) by a bucket map
 *                     (a binary search if two tables' cosines lie closer
 *                     than 2^-16); sample picks one with its weight (by
 *                     u2, then rescaled for Arvo), pdf is the mixture;
 *   BWH_SAMPLER_FULL  one table per geodesic centre of level level_in; wi
 *                     selects the table of the triangle it falls in.
 *
 * Directions are unit vectors pointing away from the surface, normal +z.
 * A built sampler is read-only: any number of threads may sample it.
 */
#ifndef BW_SAMPLE_H
#define BW_SAMPLE_H

#include <stddef.h>
#include <stdint.h>

#include "brdf_models.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BWH_SAMPLER_MAX_LEVEL 6u /* the grid's */
#define BWH_SAMPLER_MAX_SUPERSAMPLE 3u

enum { BWH_SAMPLER_ISO = 2, BWH_SAMPLER_FULL = 3 };

/* f(wi, wo): scalar BRDF value in 1/sr (may be negative; clamped). */
typedef double (*bwh_brdf_fn)(void *ctx, const double wi[3], const double wo[3]);

/* One triangle of the sampled level, ready for Arvo's method (vertices
 * a, b, c): 128 bytes. */
typedef struct {
    double a[3], b[3];
    double e[3];     /* unit, in the plane of a and c, normal to a */
    double opc, omc; /* 1 + a . b, 1 - a . b (as |a - b|^2 / 2) */
    double k1, k2;   /* |a . (b x e)|, b . e */
    double area;     /* solid angle */
    double inv_area; /* 1 / area */
    double proj;     /* integral of cos(theta) over it */
} bwh_leaf_t;

typedef struct {
    int kind;            /* BWH_SAMPLER_ISO or BWH_SAMPLER_FULL */
    unsigned level;      /* leaf level */
    unsigned level_in;   /* FULL: incoming level */
    size_t n_tables;
    size_t n_leaves;     /* 4 * 4^level */
    size_t node_stride;  /* node ends per table above the leaves, padded */
    double *theta;       /* ISO: ascending zenith angles of the tables (radians) */
    double *trig;        /* ISO: [n_tables][2] cos, sin of theta */
    uint32_t *node_end;  /* [n_tables][node_stride]: where the part of each
                            node of levels level - 2, level - 4, ... (down
                            to 1 or 0) ends, the top level first, each level
                            in node order from a 64-byte boundary (padded
                            with 2^32 - 1) */
    uint32_t *end;       /* [n_tables][n_leaves]: where each leaf's part ends
                            (the last at 2^31), from a 64-byte boundary */
    bwh_leaf_t *leaf;    /* [n_leaves] */
    double (*cut)[3][3]; /* [triangles above the leaves, or above level_in's if
                            finer]: normals of the great circles cutting off
                            children 1, 2, 3 (leaf and table search) */
    uint16_t *zmap;      /* ISO, NULL if the cosines lie too close: for bucket
                            j of n_zmap over [0, 1), how many tables have
                            cos(theta) >= (j + 1) / n_zmap (table search) */
    size_t n_zmap;
    double mix;          /* weight of the cosine lobe, 0 .. 1 */
    bwh_brdf_fn f;       /* the BRDF it was built from, and its context: */
    void *ctx;           /* sample's value */
} bwh_sampler_t;

/*
 * Builds the tables. ISO: n_tables zenith angles theta (radians, strictly
 * ascending, in [0, pi/2]); FULL: theta ignored, n_tables must be
 * 4 * 4^level_in. Each leaf integral is a midpoint sum over the leaf's
 * 4^supersample sub-triangles (f at their centres times their projected
 * solid angle). A table whose integral is 0 samples the cosine lobe.
 * The sampler keeps f and ctx for sample's value: ctx must outlive it, and f
 * be safe to call from every thread that samples with a value.
 * Returns 0, or -1 (bad arguments, out of memory; see bwh_last_error()).
 */
int bwh_sampler_build(bwh_sampler_t *s, int kind, unsigned level, size_t n_tables,
                      const double *theta, unsigned level_in, bwh_brdf_fn f, void *ctx,
                      unsigned supersample, double mix);
void bwh_sampler_free(bwh_sampler_t *s);

/*
 * Draws wo for wi (z > 0) from u[0..2] in [0, 1) (values outside, or NaN,
 * are clamped into it). Returns 0 with *pdf the
 * pdf (per solid angle) of wo and, when value is not NULL, *value the BRDF
 * the sampler was built from at (wi, wo), clamped as the tables are (0 where
 * f is negative or not finite): a path's weight is *value * wo[2] / *pdf.
 * Returns -1 when wi is below the horizon or not finite (wo, pdf, value
 * untouched). Uses the tree: O(level) per sample.
 */
int bwh_sampler_sample(const bwh_sampler_t *s, const double wi[3], const double u[3],
                       double wo[3], double *pdf, double *value);

/* The same distribution, with the leaf found by a linear scan of the
 * leaves' running sum (the O(n) method the tree replaces). For comparison. */
int bwh_sampler_sample_linear(const bwh_sampler_t *s, const double wi[3], const double u[3],
                              double wo[3], double *pdf, double *value);

/* pdf of wo given wi (per solid angle); 0 below the horizon or for wi below
 * the horizon. */
double bwh_sampler_pdf(const bwh_sampler_t *s, const double wi[3], const double wo[3]);

/* Probability that a sample for wi falls in leaf triangle `leaf` (exact:
 * the mixture of the tables' leaf probabilities). */
double bwh_sampler_leaf_mass(const bwh_sampler_t *s, const double wi[3], size_t leaf);

/* Uniform direction in a spherical triangle (Arvo's method), u in [0,1)^2. */
void bwh_leaf_init(bwh_leaf_t *t, const double a[3], const double b[3], const double c[3]);
void bwh_leaf_sample(const bwh_leaf_t *t, double u1, double u2, double out[3]);

/* Integral of cos(theta) (z) over the spherical triangle a, b, c (Lambert's
 * edge formula). */
double bwh_projected_solid_angle(const double a[3], const double b[3], const double c[3]);

/* Cosine-weighted hemisphere direction, pdf z / pi. */
void bwh_sample_cosine(double u1, double u2, double out[3]);

/*
 * Analytic lobe sampling of the models of brdf_models.h (the "analytic
 * importance sampling" the paper compares against): the diffuse term
 * (cosine) with probability kd / (kd + ks), else
 *   phong  the cos^n lobe about the mirror direction, pdf (n+1)/(2 pi) cos^n;
 *   ward   the half vector by Walter's inversion ("Notes on the Ward BRDF",
 *          2005), pdf exp(-tan^2 theta_h (cos^2 phi_h/ax^2 + sin^2 phi_h/ay^2))
 *          / (4 pi ax ay cos^3 theta_h (wo . h)).
 * These are densities on the whole sphere: a direction below the horizon
 * can come out (the caller gives it weight 0); pdf is 0 for wo below it.
 */
void bwh_phong_sample(const bwh_brdf_params_t *p, const double wi[3], const double u[3],
                      double wo[3]);
double bwh_phong_pdf(const bwh_brdf_params_t *p, const double wi[3], const double wo[3]);
void bwh_ward_sample(const bwh_brdf_params_t *p, const double wi[3], const double u[3],
                     double wo[3]);
double bwh_ward_pdf(const bwh_brdf_params_t *p, const double wi[3], const double wo[3]);

#ifdef __cplusplus
}
#endif

#endif
