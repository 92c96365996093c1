/* SPDX-License-Identifier: BSD-2-Clause */
/* Generic spherical Bio-Haar transform in double precision. */
#include "bwr_biohaar.h"

#include <stdlib.h>
#include <string.h>

#include "bwr_geodesic.h"

static size_t tri_offset(unsigned j) /* triangles of levels < j */
{
    return 4 * (((size_t)1 << (2u * j)) - 1) / 3;
}

void bwr_sphere_free(bwr_sphere_t *s)
{
    free(s->weight);
    free(s->area);
    free(s->psi2);
    free(s->coef_level);
    memset(s, 0, sizeof *s);
}

int bwr_sphere_init(bwr_sphere_t *s, unsigned level)
{
    memset(s, 0, sizeof *s);
    if (level > BWR_SPHERE_MAX_LEVEL)
        return -1;
    s->level = level;
    s->n = (size_t)4 << (2u * level);
    size_t total = tri_offset(level + 1);
    s->area = malloc(total * sizeof *s->area);
    s->weight = malloc((tri_offset(level) ? 4 * tri_offset(level) : 1) * sizeof *s->weight);
    s->psi2 = malloc(s->n * sizeof *s->psi2);
    s->coef_level = malloc(s->n * sizeof *s->coef_level);
    bwr_tri_t *tri = malloc(s->n * sizeof *tri);
    if (s->area == NULL || s->weight == NULL || s->psi2 == NULL || s->coef_level == NULL ||
        tri == NULL) {
        free(tri);
        bwr_sphere_free(s);
        return -1;
    }
    for (unsigned j = 0; j <= level; j++) {
        size_t nt = (size_t)4 << (2u * j);
        bwr_grid_triangles(j, tri);
        for (size_t t = 0; t < nt; t++)
            s->area[tri_offset(j) + t] = bwr_tri_area(tri[t].v[0], tri[t].v[1], tri[t].v[2]);
    }
    free(tri);
    for (unsigned j = 0; j < level; j++) {
        size_t np = (size_t)4 << (2u * j);
        const double *ca = s->area + tri_offset(j + 1);
        for (size_t p = 0; p < np; p++) {
            double aP = ca[4 * p] + ca[4 * p + 1] + ca[4 * p + 2] + ca[4 * p + 3];
            double *w = s->weight + 4 * (tri_offset(j) + p);
            for (unsigned i = 0; i < 4; i++)
                w[i] = ca[4 * p + i] / aP;
            for (unsigned m = 1; m < 4; m++) {
                size_t c = bwr_sphere_level_start(j) + 3 * p + m - 1;
                s->psi2[c] = ca[4 * p + m] * (1.0 - w[m]);
                s->coef_level[c] = (int)j;
            }
        }
    }
    for (size_t b = 0; b < 4; b++) {
        s->psi2[b] = s->area[b];
        s->coef_level[b] = -1;
    }
    return 0;
}

double bwr_sphere_area(const bwr_sphere_t *s, unsigned j, size_t t)
{
    return s->area[tri_offset(j) + t];
}

int bwr_biohaar_forward(const bwr_sphere_t *s, const bwr_type_t *t, const void *in, void *out)
{
    size_t n = s->n;
    void *cur = bwr_array_new(t, n), *tmp = bwr_array_new(t, 1);
    if (cur == NULL || tmp == NULL) {
        bwr_array_free(t, cur, n);
        bwr_array_free(t, tmp, 1);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        t->copy(t, bwr_at(t, cur, i), bwr_cat(t, in, i));
    for (unsigned j = s->level; j-- > 0;) {
        size_t np = (size_t)4 << (2u * j);
        for (size_t p = 0; p < np; p++) {
            const double *w = s->weight + 4 * (tri_offset(j) + p);
            void *c0 = bwr_at(t, cur, 4 * p);
            for (unsigned m = 1; m < 4; m++) {
                void *d = bwr_at(t, out, bwr_sphere_level_start(j) + 3 * p + m - 1);
                t->sub(t, d, bwr_at(t, cur, 4 * p + m), c0);
            }
            /* s_P = s_0 + sum L_m d_m, written to cur[p] (p <= 4p: already read) */
            void *sp = bwr_at(t, cur, p);
            if (p != 0)
                t->copy(t, sp, c0);
            for (unsigned m = 1; m < 4; m++)
                bwr_axpy(t, sp, w[m], bwr_at(t, out, bwr_sphere_level_start(j) + 3 * p + m - 1),
                         tmp);
        }
    }
    for (size_t b = 0; b < 4; b++)
        t->copy(t, bwr_at(t, out, b), bwr_at(t, cur, b));
    bwr_array_free(t, cur, n);
    bwr_array_free(t, tmp, 1);
    return 0;
}

int bwr_biohaar_inverse(const bwr_sphere_t *s, const bwr_type_t *t, const void *in, void *out)
{
    size_t n = s->n;
    void *tmp = bwr_array_new(t, 1), *sp = bwr_array_new(t, 1);
    if (tmp == NULL || sp == NULL) {
        bwr_array_free(t, tmp, 1);
        bwr_array_free(t, sp, 1);
        return -1;
    }
    /* out doubles as the working array: parents at [0, np), expanded in
     * place from the last parent down (children 4p..4p+3 lie at or after p) */
    for (size_t b = 0; b < 4; b++)
        t->copy(t, bwr_at(t, out, b), bwr_cat(t, in, b));
    for (unsigned j = 0; j < s->level; j++) {
        size_t np = (size_t)4 << (2u * j);
        for (size_t p = np; p-- > 0;) {
            const double *w = s->weight + 4 * (tri_offset(j) + p);
            t->copy(t, sp, bwr_at(t, out, p));
            void *c0 = bwr_at(t, out, 4 * p);
            t->copy(t, c0, sp);
            for (unsigned m = 1; m < 4; m++)
                bwr_axpy(t, c0, -w[m], bwr_cat(t, in, bwr_sphere_level_start(j) + 3 * p + m - 1),
                         tmp);
            for (unsigned m = 1; m < 4; m++)
                t->add(t, bwr_at(t, out, 4 * p + m), c0,
                       bwr_cat(t, in, bwr_sphere_level_start(j) + 3 * p + m - 1));
        }
    }
    (void)n;
    bwr_array_free(t, tmp, 1);
    bwr_array_free(t, sp, 1);
    return 0;
}
