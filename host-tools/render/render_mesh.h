/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Triangle meshes for `brdfwave render`: a bounding volume hierarchy over the
 * triangles and the nearest hit of a ray (Moller-Trumbore, both faces).
 */
#ifndef RENDER_MESH_H
#define RENDER_MESH_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    double v0[3], e1[3], e2[3]; /* a corner and the two edges from it */
    double n[3];                /* unit normal: e1 x e2 normalised */
} render_mesh_tri_t;

typedef struct {
    double lo[3], hi[3]; /* box around the node's triangles */
    uint32_t first;      /* leaf: its first triangle; inner node: its second child
                          * (the first follows the node) */
    uint32_t count;      /* leaf: its triangles (1 .. RENDER_MESH_LEAF); inner node: 0 */
} render_mesh_node_t;

typedef struct {
    render_mesh_tri_t *tri; /* in the hierarchy's order */
    size_t n_tri;
    render_mesh_node_t *node; /* node 0 is the root; none for an empty mesh */
    size_t n_node;
} render_mesh_t;

#define RENDER_MESH_LEAF 4u              /* triangles per leaf at most */
#define RENDER_MESH_MAX_TRI (1u << 24)   /* triangles per mesh at most */

/* A mesh of the n_idx triangles idx (corners: indices into vert). Triangles
 * of zero area are left out. Fails (bwh_last_error) on an index out of
 * range, a vertex that is not finite, too many triangles or no memory. */
int render_mesh_build(render_mesh_t *m, const double (*vert)[3], size_t n_vert,
                   const uint32_t (*idx)[3], size_t n_idx);

/* A torus about the z axis: ring radius `major`, tube radius `minor`
 * (0 < minor < major), n_around x n_tube quads (3 .. 4096 each) of two
 * triangles each. */
int render_mesh_torus(render_mesh_t *m, const double centre[3], double major, double minor,
                   unsigned n_around, unsigned n_tube);

void render_mesh_free(render_mesh_t *m);

/* The ray o + t d hits triangle tri at t in (tmin, tmax): 1 and *t, else 0. */
int render_tri_hit(const render_mesh_tri_t *tri, const double o[3], const double d[3], double tmin,
                double tmax, double *t);

/* The nearest triangle the ray o + t d hits at t in (tmin, *t): its index
 * into m->tri, *t lowered to its distance; -1 (and *t unchanged) if none. */
long render_mesh_hit(const render_mesh_t *m, const double o[3], const double d[3], double tmin,
                  double *t);

#endif
