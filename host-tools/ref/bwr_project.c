/* SPDX-License-Identifier: BSD-2-Clause */
/* Projection of scattered measurements onto the geodesic grid (bwr_project.h). */
#include "bwr_project.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_geodesic.h"

#define PROJECT_PI 3.14159265358979323846
#define PROJECT_SAME 1e-12 /* rad: a measurement at the centre itself */

/* geodesic angle between unit vectors, accurate for small angles */
static double angle(const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    return atan2(sqrt(x * x + y * y + z * z), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

void bwr_dir_from_degrees(double theta_deg, double phi_deg, double d[3])
{
    double th = theta_deg * (PROJECT_PI / 180.0), ph = phi_deg * (PROJECT_PI / 180.0);
    d[0] = sin(th) * cos(ph);
    d[1] = sin(th) * sin(ph);
    d[2] = cos(th);
}

int bwr_project(const double (*dir)[3], const double *values, size_t n, size_t bands,
                unsigned level, unsigned k, double *out)
{
    if (k == 0)
        k = BWR_PROJECT_K_DEFAULT;
    if (dir == NULL || values == NULL || out == NULL || n == 0 || bands == 0 ||
        level > BWR_GRID_MAX_LEVEL || k > BWR_PROJECT_K_MAX)
        return -1;
    if (bands > ((size_t)-1) / sizeof(double) / n)
        return -1;
    for (size_t i = 0; i < n * bands; i++)
        if (!isfinite(values[i]))
            return -1;
    size_t nt = bwr_grid_count(level);
    double(*u)[3] = malloc(n * sizeof *u);
    double(*c)[3] = malloc(nt * sizeof *c);
    double *acc = malloc(bands * sizeof *acc);
    if (u == NULL || c == NULL || acc == NULL || bwr_grid_centres(level, c, NULL) != 0)
        goto fail;
    for (size_t i = 0; i < n; i++) {
        double len = sqrt(dir[i][0] * dir[i][0] + dir[i][1] * dir[i][1] + dir[i][2] * dir[i][2]);
        if (!isfinite(len) || !(len > 0.0) || !(dir[i][2] / len >= -1e-9))
            goto fail;
        for (int a = 0; a < 3; a++)
            u[i][a] = dir[i][a] / len;
    }

    /* the k + 1 nearest (largest cosine), kept sorted */
    size_t m = k < n ? (size_t)k + 1 : n; /* candidates kept */
    size_t idx[BWR_PROJECT_K_MAX + 1];
    double cosv[BWR_PROJECT_K_MAX + 1], r[BWR_PROJECT_K_MAX + 1];
    for (size_t t = 0; t < nt; t++) {
        size_t have = 0;
        for (size_t i = 0; i < n; i++) {
            double cs = c[t][0] * u[i][0] + c[t][1] * u[i][1] + c[t][2] * u[i][2];
            if (have == m && !(cs > cosv[m - 1]))
                continue;
            size_t p = have < m ? have++ : m - 1;
            while (p > 0 && cosv[p - 1] < cs) {
                cosv[p] = cosv[p - 1];
                idx[p] = idx[p - 1];
                p--;
            }
            cosv[p] = cs;
            idx[p] = i;
        }
        for (size_t q = 0; q < have; q++)
            r[q] = angle(c[t], u[idx[q]]);
        double *o = out + t * bands;
        const double *v1 = values + idx[0] * bands;

        if (r[0] < PROJECT_SAME) { /* a measurement at the centre */
            size_t cnt = 0;
            memset(acc, 0, bands * sizeof *acc);
            for (size_t q = 0; q < have && r[q] < PROJECT_SAME; q++, cnt++)
                for (size_t b = 0; b < bands; b++)
                    acc[b] += values[idx[q] * bands + b] - v1[b];
            for (size_t b = 0; b < bands; b++)
                o[b] = v1[b] + acc[b] / (double)cnt;
            continue;
        }
        size_t used = n <= k ? have : (size_t)k; /* neighbours */
        double R = n <= k ? 2.0 * r[have - 1] : r[k];
        double den = 0.0;
        memset(acc, 0, bands * sizeof *acc);
        for (size_t q = 0; q < used; q++) {
            double w = (R - r[q]) / (R * r[q]);
            if (!(w > 0.0))
                continue;
            w *= w;
            den += w;
            for (size_t b = 0; b < bands; b++)
                acc[b] += w * (values[idx[q] * bands + b] - v1[b]);
        }
        if (!(den > 0.0)) { /* every neighbour exactly R away: equal weights */
            for (size_t q = 0; q < used; q++)
                for (size_t b = 0; b < bands; b++)
                    acc[b] += values[idx[q] * bands + b] - v1[b];
            den = (double)used;
        }
        for (size_t b = 0; b < bands; b++)
            o[b] = v1[b] + acc[b] / den;
    }
    free(u);
    free(c);
    free(acc);
    return 0;
fail:
    free(u);
    free(c);
    free(acc);
    return -1;
}
