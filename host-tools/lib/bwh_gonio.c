/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Goniometer measurements at scattered directions (the University of Bern's
 * PHIRE-2 CSV, as in shared/data/brdf/goniometer): a "# 'counter',
 * 'incidence', ..." title comment, then rows "counter, incidence, emission,
 * azimuth, phase, reflectance_factor, ..., bandpass_central, bandpass_FWHM,
 * ..." with one row per geometry and band. For each incidence the measured
 * directions (emission from the normal, azimuth from the plane of incidence
 * on the side of the source) and their mirror images across that plane
 * (the half the instrument does not visit, for an isotropic sample) are
 * projected onto the outgoing triangles of one level (bwh_project.h), as
 * the paper's 474 measured directions are. Kept: the incidence angles, the
 * bands' centres and widths, the quantity (reflectance factor), the time of
 * the first measurement, and how many directions each incidence had.
 * The same data pivoted, one column per geometry (parse_wide), reads alike
 * (without bandwidths and time, which that layout does not hold).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "bwh_input.h"
#include "bwh_project.h"
#include "bwh_text.h"
#include "geodesic.h"

#define DEG (3.14159265358979323846 / 180.0)
#define MAX_BANDS 64
enum { C_INC = 1, C_EMI = 2, C_AZI = 3, C_RF = 5, C_TIME = 9, C_WL = 11, C_FWHM = 12, C_MIN = 13 };

typedef struct {
    double inc, emi, azi, v[MAX_BANDS];
    unsigned have; /* bands seen, as bits of the first 32 */
    size_t nv;
} geom_t;

/* The same data pivoted (the WWU "autospec" layout of shared/data's
 * spectralon.csv): "Database of origin, ...", "Sample Name, ...",
 * "Viewing geometry, i=I e=E az=A, ..." (one column per geometry), then
 * after a line "Wavelength" one row per band: the wavelength and the
 * values of every geometry. Fills g[ng] and wl[nb]; 0, or -1. */
static int parse_wide(bwh_text_t *t, const char *path, geom_t **pg, size_t *png, double *wl,
                      size_t *pnb, char *sample, size_t sample_cap)
{
    char *line;
    geom_t *g = NULL;
    size_t ng = 0, nb = 0;
    int in_rows = 0;
    while ((line = bwh_text_line(t))) {
        char *l = bwh_trim(line);
        if (!*l)
            continue;
        if (!strncmp(l, "Sample Name,", 12)) {
            char *c = bwh_trim(l + 12), *e = strchr(c, ',');
            snprintf(sample, sample_cap, "%.*s", e ? (int)(e - c) : (int)strlen(c), c);
            bwh_trim(sample);
            continue;
        }
        if (!strncmp(l, "Viewing geometry,", 17)) {
            size_t cap = 0;
            for (char *p = l + 17; p && *p;) {
                double i, e, a;
                if (sscanf(p, " i=%lf e=%lf az=%lf", &i, &e, &a) != 3 || !isfinite(i) ||
                    !isfinite(e) || !isfinite(a) || i < 0 || i >= 90 || e < 0 || e > 90) {
                    bwh_fail("%s:%u: geometry %zu is not \"i=I e=E az=A\" within [0, 90) "
                             "degrees", path, t->line, ng + 1);
                    free(g);
                    return -1;
                }
                if (ng == cap) {
                    geom_t *n2 = realloc(g, (cap = cap ? cap * 2 : 256) * sizeof *g);
                    if (!n2) {
                        free(g);
                        return bwh_fail("out of memory");
                    }
                    g = n2;
                }
                memset(&g[ng], 0, sizeof *g);
                g[ng].inc = i;
                g[ng].emi = e;
                g[ng].azi = a;
                ng++;
                p = strchr(p, ',');
                if (p)
                    p++;
            }
            continue;
        }
        if (!strcmp(l, "Wavelength")) {
            in_rows = 1;
            continue;
        }
        if (!in_rows)
            continue; /* other header lines */
        if (!ng) {
            free(g);
            return bwh_fail("%s:%u: rows before a \"Viewing geometry\" line", path, t->line);
        }
        if (nb == MAX_BANDS) {
            free(g);
            return bwh_fail("%s:%u: more than %d bands", path, t->line, MAX_BANDS);
        }
        char *p = l, *e;
        errno = 0;
        wl[nb] = strtod(p, &e);
        if (e == p || errno || !isfinite(wl[nb]) || (nb && wl[nb] <= wl[nb - 1])) {
            free(g);
            return bwh_fail("%s:%u: not a wavelength above the one before", path, t->line);
        }
        p = e;
        for (size_t k = 0; k < ng; k++) {
            while (*p == ' ')
                p++;
            if (*p++ != ',') {
                free(g);
                return bwh_fail("%s:%u: %zu values, %zu geometries%s", path, t->line, k, ng,
                                t->last_cut ? " (the file is cut short)" : "");
            }
            errno = 0;
            g[k].v[nb] = strtod(p, &e);
            if (e == p || errno || !isfinite(g[k].v[nb])) {
                free(g);
                return bwh_fail("%s:%u: value %zu is not a number", path, t->line, k + 1);
            }
            p = e;
        }
        while (*p == ' ' || *p == ',')
            p++;
        if (*p || t->last_cut) {
            free(g);
            return bwh_fail("%s:%u: %s", path, t->line,
                            *p ? "more values than geometries" : "the file is cut short");
        }
        nb++;
    }
    if (!ng || !nb) {
        free(g);
        return bwh_fail("%s: no %s", path, ng ? "band rows after \"Wavelength\"" :
                                               "\"Viewing geometry\" line");
    }
    for (size_t k = 0; k < ng; k++)
        g[k].nv = nb;
    *pg = g;
    *png = ng;
    *pnb = nb;
    return 0;
}

int bwh_read_gonio(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    bwh_text_t t;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    char *line = bwh_text_line(&t);
    int rc = -1;
    geom_t *g = NULL;
    size_t ng = 0, cap = 0, nb = 0;
    double wl[MAX_BANDS], fwhm[MAX_BANDS], t0 = NAN;
    double *inc = NULL, *val = NULL, *res = NULL;
    double(*dir)[3] = NULL;
    char sample[256] = "";
    int wide = line && !strncmp(line, "Database of origin", 18);
    if (!line || (!wide && strncmp(line, "# 'counter', 'incidence', 'emission', 'azimuth'", 47))) {
        bwh_fail("%s: not a goniometer CSV (its first line is neither \"# 'counter', "
                 "'incidence', 'emission', 'azimuth', ...\" nor \"Database of origin, ...\")",
                 path);
        goto out;
    }
    if (wide && parse_wide(&t, path, &g, &ng, wl, &nb, sample, sizeof sample) != 0)
        goto out;
    while (!wide && (line = bwh_text_line(&t))) {
        if (!*bwh_trim(line))
            continue;
        double c[C_MIN];
        char *p = line, *e;
        int k;
        for (k = 0; k < C_MIN; k++) {
            errno = 0;
            c[k] = strtod(p, &e);
            if (e == p || errno || !isfinite(c[k]))
                break;
            p = e;
            while (*p == ' ')
                p++;
            if (*p != ',' && k < C_MIN - 1)
                break;
            if (*p == ',')
                p++;
        }
        if (k < C_MIN) {
            bwh_fail("%s:%u: column %d is not a number%s", path, t.line, k + 1,
                     t.last_cut ? " (the file is cut short)" : "");
            goto out;
        }
        if (t.last_cut) {
            bwh_fail("%s:%u: the last row has no line end (the file is cut short)", path, t.line);
            goto out;
        }
        if (c[C_INC] < 0 || c[C_INC] >= 90 || c[C_EMI] < 0 || c[C_EMI] > 90) {
            bwh_fail("%s:%u: incidence %g or emission %g outside [0, 90) degrees", path, t.line,
                     c[C_INC], c[C_EMI]);
            goto out;
        }
        if (isnan(t0))
            t0 = c[C_TIME];
        /* the band */
        size_t b;
        for (b = 0; b < nb && wl[b] != c[C_WL]; b++)
            ;
        if (b == nb) {
            if (nb == MAX_BANDS) {
                bwh_fail("%s:%u: more than %d bands", path, t.line, MAX_BANDS);
                goto out;
            }
            for (b = nb; b > 0 && wl[b - 1] > c[C_WL]; b--) {
                wl[b] = wl[b - 1];
                fwhm[b] = fwhm[b - 1];
                for (size_t i = 0; i < ng; i++)
                    g[i].v[b] = g[i].v[b - 1];
            }
            wl[b] = c[C_WL];
            fwhm[b] = c[C_FWHM];
            nb++;
            for (size_t i = 0; i < ng; i++)
                g[i].nv = nb;
        }
        /* the geometry */
        size_t i;
        for (i = ng; i > 0; i--)
            if (g[i - 1].inc == c[C_INC] && g[i - 1].emi == c[C_EMI] && g[i - 1].azi == c[C_AZI])
                break;
        if (!i) {
            if (ng == cap) {
                geom_t *ng2 = realloc(g, (cap = cap ? cap * 2 : 256) * sizeof *g);
                if (!ng2) {
                    bwh_fail("out of memory");
                    goto out;
                }
                g = ng2;
            }
            memset(&g[ng], 0, sizeof *g);
            g[ng].inc = c[C_INC];
            g[ng].emi = c[C_EMI];
            g[ng].azi = c[C_AZI];
            for (size_t q = 0; q < MAX_BANDS; q++)
                g[ng].v[q] = NAN;
            i = ++ng;
        }
        if (!isnan(g[i - 1].v[b])) {
            bwh_fail("%s:%u: geometry (%g, %g, %g) at %g nm given twice", path, t.line, c[C_INC],
                     c[C_EMI], c[C_AZI], c[C_WL]);
            goto out;
        }
        g[i - 1].v[b] = c[C_RF];
    }
    if (!ng) {
        bwh_fail("%s: no measurements", path);
        goto out;
    }
    for (size_t i = 0; i < ng; i++)
        for (size_t b = 0; b < nb; b++)
            if (isnan(g[i].v[b])) {
                bwh_fail("%s: geometry (incidence %g, emission %g, azimuth %g) lacks the band at "
                         "%g nm (the file is cut short or damaged)",
                         path, g[i].inc, g[i].emi, g[i].azi, wl[b]);
                goto out;
            }
    /* the incidences, ascending */
    inc = malloc(ng * sizeof *inc);
    if (!inc) {
        bwh_fail("out of memory");
        goto out;
    }
    size_t n_in = 0;
    for (size_t i = 0; i < ng; i++) {
        size_t k;
        for (k = 0; k < n_in && inc[k] != g[i].inc; k++)
            ;
        if (k == n_in) {
            for (k = n_in; k > 0 && inc[k - 1] > g[i].inc; k--)
                inc[k] = inc[k - 1];
            inc[k] = g[i].inc;
            n_in++;
        }
    }
    unsigned level = o->level >= 0 ? (unsigned)o->level : 4u;
    size_t n_out = bwh_grid_count(level);
    dir = malloc(2 * ng * sizeof *dir);
    val = malloc(2 * ng * nb * sizeof *val);
    res = malloc(n_out * nb * sizeof *res);
    m->values = malloc(n_in * n_out * nb * sizeof *m->values);
    if (!dir || !val || !res || !m->values) {
        bwh_fail("out of memory");
        goto out;
    }
    char counts[512] = "";
    for (size_t k = 0; k < n_in; k++) {
        size_t n = 0, measured = 0;
        for (size_t i = 0; i < ng; i++) {
            if (g[i].inc != inc[k])
                continue;
            measured++;
            for (int mirror = 0; mirror < 2; mirror++) {
                double az = mirror ? -g[i].azi : g[i].azi;
                if (mirror && (fmod(fabs(g[i].azi), 180.0) == 0.0 || g[i].emi == 0.0))
                    continue; /* on the plane: its own image */
                double e = g[i].emi * DEG, a = az * DEG;
                dir[n][0] = sin(e) * cos(a);
                dir[n][1] = sin(e) * sin(a);
                dir[n][2] = cos(e);
                memcpy(val + n * nb, g[i].v, nb * sizeof *val);
                n++;
            }
        }
        if (bwh_project(dir, val, n, nb, level, res) != 0) {
            bwh_fail("%s: incidence %g: %s", path, inc[k], bwh_last_error());
            goto out;
        }
        for (size_t q = 0; q < n_out * nb; q++)
            m->values[k * n_out * nb + q] = (float)res[q];
        size_t l = strlen(counts);
        snprintf(counts + l, sizeof counts - l, "%s%zu", k ? ", " : "", measured);
    }
    bwh_meta_t *meta = &m->meta;
    meta->quantity = BWH_Q_REFLECTANCE;
    meta->sample_type = BWH_ST_F32;
    meta->present |= BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE;
    meta->wl_unit = BWH_WL_NM;
    meta->inc_unit = BWH_ANGLE_DEG;
    char proj[sizeof counts + 160];
    snprintf(proj, sizeof proj,
             "measured directions per incidence %s (and their mirror images), projected onto "
             "level %u by local modified Shepard interpolation over the 8 nearest",
             counts, level);
    if (bwh_meta_set_numbers(&meta->wavelengths, wl, nb) ||
        (!wide && bwh_meta_set_numbers(&meta->fwhm, fwhm, nb)) ||
        bwh_meta_set_numbers(&meta->incidence, inc, n_in) ||
        (sample[0] && bwh_meta_add_field(meta, "sample", sample)) ||
        bwh_meta_add_field(meta, "projection", proj))
        goto out;
    if (isfinite(t0)) {
        meta->time = t0;
        meta->time_tz = 0;
        meta->present |= BWH_M_TIME;
    }
    m->shape = BW_SHAPE_BRDF_ISO;
    m->level_out = level;
    m->n_in = (uint32_t)n_in;
    m->bands = (uint32_t)nb;
    m->count = n_in * n_out * nb;
    rc = 0;
out:
    bwh_text_close(&t);
    free(g);
    free(inc);
    free(dir);
    free(val);
    free(res);
    if (rc)
        bwh_measure_free(m);
    return rc;
}
