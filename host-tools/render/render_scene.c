/* SPDX-License-Identifier: BSD-2-Clause */
/* The scenes of the renderer (render_scene.h). */
#include "render_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"

static void add_quad(render_scene_t *s, v3 o, v3 u, v3 v, int mat)
{
    quad_t *q = &s->quad[s->n_quad++];
    q->o = o;
    q->u = u;
    q->v = v;
    q->n = norm(cross(u, v));
    q->mat = mat;
}

/* box [x0,x1] x [y0,y1] x [z0,z1], normals outwards */
static void add_box(render_scene_t *s, v3 lo, v3 hi, int mat)
{
    double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
    add_quad(s, lo, vec(0, dy, 0), vec(dx, 0, 0), mat);             /* bottom, -z */
    add_quad(s, vec(lo.x, lo.y, hi.z), vec(dx, 0, 0), vec(0, dy, 0), mat); /* top */
    add_quad(s, lo, vec(dx, 0, 0), vec(0, 0, dz), mat);             /* -y */
    add_quad(s, vec(lo.x, hi.y, lo.z), vec(0, 0, dz), vec(dx, 0, 0), mat); /* +y */
    add_quad(s, lo, vec(0, 0, dz), vec(0, dy, 0), mat);             /* -x */
    add_quad(s, vec(hi.x, lo.y, lo.z), vec(0, dy, 0), vec(0, 0, dz), mat); /* +x */
}

/* the room: x in [-1, 1] (left/right), y in [-1, 1] (back at +1), z in
 * [0, 2] (up); normals point inwards; a light panel under the ceiling */
static void add_room(render_scene_t *s)
{
    add_quad(s, vec(-1, -1, 0), vec(2, 0, 0), vec(0, 2, 0), MAT_WALL);     /* floor */
    add_quad(s, vec(-1, -1, 2), vec(0, 2, 0), vec(2, 0, 0), MAT_WALL);     /* ceiling */
    add_quad(s, vec(-1, 1, 0), vec(2, 0, 0), vec(0, 0, 2), MAT_WALL);      /* back */
    add_quad(s, vec(-1, -1, 0), vec(0, 0, 2), vec(2, 0, 0), MAT_WALL);     /* front */
    add_quad(s, vec(-1, -1, 0), vec(0, 2, 0), vec(0, 0, 2), MAT_WALL_RED); /* left */
    add_quad(s, vec(1, -1, 0), vec(0, 0, 2), vec(0, 2, 0), MAT_WALL);      /* right */
    add_quad(s, vec(-0.8, -0.8, 1.999), vec(0, 1.6, 0), vec(1.6, 0, 0), MAT_LIGHT_ID);
    s->light = &s->quad[s->n_quad - 1];
    v3 c = cross(s->light->u, s->light->v);
    s->light_area = sqrt(dot(c, c));
}

static void flake_build(flake_t *f, v3 c, double r, v3 up, int depth, int mat)
{
    f->c = c;
    f->r = r;
    f->mat = mat;
    f->bound = 2.0 * r; /* r (1 + 2/3 + 2/9 + ...) < 2 r */
    f->n_child = 0;
    f->child = NULL;
    if (depth == 0)
        return;
    f->child = calloc(9, sizeof *f->child);
    if (!f->child)
        return;
    v3 t = fabs(up.z) < 0.9 ? norm(cross(vec(0, 0, 1), up)) : norm(cross(vec(1, 0, 0), up));
    v3 b = cross(up, t);
    for (int k = 0; k < 9; k++) {
        double el = k < 6 ? 0.0 : R_PI / 3.0;
        double az = k < 6 ? k * R_PI / 3.0 : (k - 6) * 2.0 * R_PI / 3.0 + R_PI / 6.0;
        v3 d = add(add(mul(t, cos(el) * cos(az)), mul(b, cos(el) * sin(az))), mul(up, sin(el)));
        flake_build(&f->child[k], add(c, mul(d, r * (1.0 + 1.0 / 3.0))), r / 3.0, d, depth - 1,
                    mat);
    }
    f->n_child = 9;
}

static void flake_free(flake_t *f)
{
    for (int k = 0; k < f->n_child; k++)
        flake_free(&f->child[k]);
    free(f->child);
}

static int hit_sphere(v3 c, double r, v3 o, v3 d, double tmax, double *t)
{
    v3 oc = sub(o, c);
    double b = dot(oc, d), cc = dot(oc, oc) - r * r, disc = b * b - cc;
    if (disc < 0.0)
        return 0;
    double sq = sqrt(disc), t0 = -b - sq;
    if (t0 > R_EPS && t0 < tmax) {
        *t = t0;
        return 1;
    }
    t0 = -b + sq;
    if (t0 > R_EPS && t0 < tmax) {
        *t = t0;
        return 1;
    }
    return 0;
}

static void flake_hit(const flake_t *f, v3 o, v3 d, render_hit_t *h)
{
    double t;
    if (!hit_sphere(f->c, f->bound, o, d, INFINITY, &t) && dot(sub(o, f->c), sub(o, f->c)) >
                                                              f->bound * f->bound)
        return;
    if (hit_sphere(f->c, f->r, o, d, h->t, &t)) {
        h->t = t;
        h->p = add(o, mul(d, t));
        h->n = norm(sub(h->p, f->c));
        h->mat = f->mat;
    }
    for (int k = 0; k < f->n_child; k++)
        flake_hit(&f->child[k], o, d, h);
}

int render_intersect(const render_scene_t *s, v3 o, v3 d, render_hit_t *h)
{
    h->t = INFINITY;
    h->mat = -1;
    for (size_t i = 0; i < s->n_quad; i++) {
        const quad_t *q = &s->quad[i];
        double dn = dot(d, q->n);
        if (fabs(dn) < 1e-12)
            continue;
        double t = dot(sub(q->o, o), q->n) / dn;
        if (!(t > R_EPS && t < h->t))
            continue;
        v3 p = sub(add(o, mul(d, t)), q->o);
        /* coordinates in (u, v) */
        double uu = dot(q->u, q->u), uv = dot(q->u, q->v), vv = dot(q->v, q->v);
        double pu = dot(p, q->u), pv = dot(p, q->v), det = uu * vv - uv * uv;
        double a = (pu * vv - pv * uv) / det, b = (pv * uu - pu * uv) / det;
        if (a < 0.0 || a > 1.0 || b < 0.0 || b > 1.0)
            continue;
        h->t = t;
        h->p = add(o, mul(d, t));
        h->n = q->n;
        h->mat = q->mat;
    }
    for (size_t i = 0; i < s->n_sph; i++) {
        double t;
        if (hit_sphere(s->sph[i].c, s->sph[i].r, o, d, h->t, &t)) {
            h->t = t;
            h->p = add(o, mul(d, t));
            h->n = norm(sub(h->p, s->sph[i].c));
            h->mat = s->sph[i].mat;
        }
    }
    if (s->flake)
        flake_hit(s->flake, o, d, h);
    if (s->mesh.n_tri) {
        long k = render_mesh_hit(&s->mesh, (const double[3]){o.x, o.y, o.z},
                              (const double[3]){d.x, d.y, d.z}, R_EPS, &h->t);
        if (k >= 0) {
            const double *n = s->mesh.tri[k].n;
            h->p = add(o, mul(d, h->t));
            h->n = vec(n[0], n[1], n[2]);
            h->mat = s->mesh_mat;
        }
    }
    return h->mat >= 0;
}

void render_scene_init(render_scene_t *s)
{
    memset(s, 0, sizeof *s);
    s->mat[MAT_WALL] = (material_t){.kind = MAT_DIFFUSE, .albedo = {0.7, 0.7, 0.7}};
    s->mat[MAT_WALL_RED] = (material_t){.kind = MAT_DIFFUSE, .albedo = {0.7, 0.25, 0.2}};
    s->mat[MAT_LIGHT_ID] = (material_t){.kind = MAT_LIGHT, .albedo = {1.5, 1.5, 1.5}};
}

int render_scene_build(render_scene_t *s, int which, int n_materials)
{
    s->n_mat = MAT_SLOT0 + n_materials;
    add_room(s);
    s->up = vec(0, 0, 1);
    s->fov_deg = 55.0;
    if (which == RENDER_SPHEREFLAKE) {
        flake_build(&s->root, vec(0, 0.2, 0.32), 0.32, vec(0, 0, 1), 2, MAT_SLOT0);
        s->flake = &s->root;
        s->eye = vec(0, -0.95, 1.1);
        s->look = vec(0, 0.2, 0.4);
        return 0;
    }
    int m0 = MAT_SLOT0, m1 = MAT_SLOT0 + 1 % n_materials, m2 = MAT_SLOT0 + 2 % n_materials,
        m3 = MAT_SLOT0 + 3 % n_materials;
    add_box(s, vec(-0.85, 0.1, 0.0), vec(0.05, 0.85, 0.5), m0); /* table */
    s->sph[0] = (sphere_t){vec(0.5, 0.45, 0.38), 0.38, m1};
    s->n_sph = 1;
    /* a torus of 6,144 triangles lying on the table */
    if (render_mesh_torus(&s->mesh, (const double[3]){-0.38, 0.45, 0.56}, 0.17, 0.06, 96, 32) != 0)
        return -1;
    s->mesh_mat = m2;
    flake_build(&s->root, vec(0.45, -0.25, 0.16), 0.16, vec(0, 0, 1), 2, m3);
    s->flake = &s->root;
    s->eye = vec(0, -0.97, 1.2);
    s->look = vec(0, 0.3, 0.45);
    return 0;
}

void render_scene_free(render_scene_t *s)
{
    if (s->flake)
        flake_free(s->flake);
    s->flake = NULL;
    render_mesh_free(&s->mesh);
}
