/*
 * Importance sampling of a BRDF from the triangle hierarchy (sec. 6.1).
 *
 * For each tabulated incoming direction the sampler forms, on the geodesic
 * triangles of one level (the "level of accuracy"), the integral of
 * max(0, f(wi, wo)) cos(theta_o) over each triangle, and above them the sums
 * of the children up to the 4 base triangles: every node's integral over its
 * subtree. f is a scalar given by a callback: the BRDF integrated over
 * wavelength, or one channel (bwh_brdf_data_band_cb), so analytic models and
 * decoded payloads are sampled the same way. The integrals are kept as
 * where each node's part of [0, 2^31) ends, the parts of 4 siblings
 * following each other inside their parent's (a node's integral, relative
 * to the whole table, is its part's width; a node of positive integral has
 * a part at least 1 wide, a node of integral 0 an empty one): per group of
 * 4 siblings above the leaves the ends of the first 3 (12 bytes), and
 * where each leaf's part ends (4 bytes a leaf): a leaf's probability is its
 * part's width / 2^31.
 *
 *   sample   descend from the base triangles, picking the child whose part
 *            holds the point floor(u 2^31), so each child with probability
 *            its integral over its parent's (O(log4 n)), then a uniform direction in
 *            the leaf's spherical triangle (Arvo 1995); with it the pdf and,
 *            on request, the BRDF's value there;
 *   pdf      leaf probability / leaf solid angle: piecewise constant. The
 *            descent's leaf has the width the build gave it, so sample's pdf
 *            and pdf() agree to the bit away from leaf edges.
 *
 * Negative values (left by lossy compression) and values that are not finite
 * count as 0, by one clamp used for the leaf integrals and for sample's
 * value, so sample, pdf and the value see the same function. A
 * cosine lobe with weight `mix` is mixed in: the pdf is
 *   mix * cos(theta_o) / pi + (1 - mix) * p_tree(wo),
 * positive over the whole hemisphere, hence wherever the BRDF is.
 *
 * Incoming directions:
 *   BWH_SAMPLER_ISO   tables at zenith angles theta_k in the plane phi = 0;
 *                     wi and wo are turned about the normal until phi_i = 0
 *                     (the azimuthal rotation of sec. 5.2) and the two
 *                     tables around theta_i are mixed with the weights
 *                     sin(theta_i - theta_lo) and sin(theta_hi - theta_i),
 *                     normalised (within d^2 / 32 of the linear weight for
 *                     tables d radians apart, and no inverse trigonometry);
 *                     sample picks one with its weight, pdf is the mixture;
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

/* One group of 4 siblings in a table: where the parts of children 0, 1, 2
 * end, in units of 2^-31 of the table (child 3 ends where the parent does). */
typedef struct {
    uint32_t end[3];
} bwh_cdf_group_t;

/* One triangle of the sampled level, ready for Arvo's method (vertices
 * a, b, c): 128 bytes. */
typedef struct {
    double a[3], b[3];
    double alpha, cos_alpha, sin_alpha; /* angle at vertex a */
    double cos_c;                       /* a . b */
    double e[3];                        /* unit, in the plane of a and c, normal to a */
    double area;                        /* solid angle */
    double inv_area;                    /* 1 / area */
    double proj;                        /* integral of cos(theta) over it */
} bwh_leaf_t;

typedef struct {
    int kind;            /* BWH_SAMPLER_ISO or BWH_SAMPLER_FULL */
    unsigned level;      /* leaf level */
    unsigned level_in;   /* FULL: incoming level */
    size_t n_tables;
    size_t n_leaves;     /* 4 * 4^level */
    size_t n_groups;     /* groups of 4 siblings per table above the leaves */
    double *theta;       /* ISO: ascending zenith angles of the tables (radians) */
    double *trig;        /* ISO: [n_tables][2] cos, sin of theta */
    bwh_cdf_group_t *cdf; /* [n_tables][n_groups]: the groups above the
                             leaves; those of level l (4^l of them, children
                             of level l - 1's nodes) start at (4^l - 1) / 3 */
    uint32_t *end;       /* [n_tables][n_leaves]: where each leaf's part ends
                            (the last at 2^31) */
    bwh_leaf_t *leaf;    /* [n_leaves] */
    double (*cut)[3][3]; /* [triangles above the leaves, or above level_in's if
                            finer]: normals of the great circles cutting off
                            children 1, 2, 3 (leaf and table search) */
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
 * Draws wo for wi (z > 0) from u[0..2] in [0, 1). Returns 0 with *pdf the
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
 * the tree part is constant on a leaf, the cosine part is the leaf's
 * projected solid angle / pi). */
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
