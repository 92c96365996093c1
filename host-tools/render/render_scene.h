/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The scenes of the renderer: a closed room (x in [-1, 1] left to right,
 * y in [-1, 1] front to back, z in [0, 2] up) with diffuse walls and a light
 * panel under the ceiling, and objects in it (spheres, a sphereflake,
 * parallelograms, a triangle mesh) that carry the materials given; the
 * camera; the nearest hit of a ray.
 */
#ifndef RENDER_SCENE_H
#define RENDER_SCENE_H

#include <stddef.h>

#include "render_material.h"
#include "render_mesh.h"
#include "render_vec.h"

#define R_EPS 1e-6
#define RENDER_MAX_MATERIALS 8

enum { RENDER_SPHEREFLAKE, RENDER_ROOM };

typedef struct {
    v3 c;
    double r;
    int mat;
} sphere_t;

typedef struct {
    v3 o, u, v, n; /* parallelogram o + s u + t v, s, t in [0, 1] */
    int mat;
} quad_t;

/* sphereflake node: a sphere with 9 children of a third of its radius */
typedef struct flake {
    v3 c;
    double r, bound;
    int mat;
    int n_child;
    struct flake *child;
} flake_t;

/* the materials: the walls, the light, then the objects' (MAT_SLOT0 ..) */
enum { MAT_WALL = 0, MAT_WALL_RED, MAT_LIGHT_ID, MAT_SLOT0 };

typedef struct {
    quad_t quad[7 + 6]; /* the room, the light, a box */
    size_t n_quad;
    sphere_t sph[1];
    size_t n_sph;
    flake_t root;
    flake_t *flake;      /* NULL or &root */
    render_mesh_t mesh;  /* triangles, all of material mesh_mat */
    int mesh_mat;
    v3 eye, look, up;
    double fov_deg;
    material_t mat[RENDER_MAX_MATERIALS + 3];
    int n_mat;
    const quad_t *light; /* the emitting panel */
    double light_area;
} render_scene_t;

typedef struct {
    double t;
    v3 p, n;
    int mat;
} render_hit_t;

/* The walls' and the light's materials, before the objects' are made in
 * s->mat[MAT_SLOT0 ..]. */
void render_scene_init(render_scene_t *s);

/* Scene `which` (RENDER_SPHEREFLAKE: one sphereflake on the floor;
 * RENDER_ROOM: a table, a sphere, a torus of 6,144 triangles on the table, a
 * sphereflake) with its objects taking the n_materials materials in
 * s->mat[MAT_SLOT0 ..] in turn. 0, or -1 (bwh_last_error()). */
int render_scene_build(render_scene_t *s, int which, int n_materials);
/* frees the geometry (not the materials) */
void render_scene_free(render_scene_t *s);

/* The nearest hit of the ray o + t d (t > R_EPS): 1 and *h, else 0. */
int render_intersect(const render_scene_t *s, v3 o, v3 d, render_hit_t *h);

#endif
