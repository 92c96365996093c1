/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * USGS spectral library (splib07) ASCII spectra: a title line ("splib07a
 * Record=18377: Brick GDS355 ... ASDFRa AREF"), then one value per line.
 * The wavelengths are in a table of the same layout, in micrometres: the
 * one given (bwh_read_opts_t.wavelengths), or one beside the file whose
 * name holds "Wavelengths" and the family of the spectrum's instrument
 * code (ASD for ASDFR, ASDHR, ASDNG; BECK, NIC4, AVIRIS ...) and which has as
 * many values. Values are float32 printed with 8 digits, and read as such.
 * Deleted channels (-1.23e34) are marked missing. Kept: the
 * title, the wavelengths, the quantity (AREF and RREF: reflectance factor).
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bwh_error.h"
#include "bwh_input.h"
#include "bwh_text.h"

#define USGS_DELETED -1.23e34

/* title (allocated) and values of one file: float32 printed with 8
 * digits, read as float32 */
static int read_table(const char *path, char **title, double **v, size_t *n)
{
    bwh_text_t t;
    *v = NULL;
    *n = 0;
    *title = NULL;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    char *line = bwh_text_line(&t);
    if (!line || !strstr(line, "Record=")) {
        bwh_text_close(&t);
        return bwh_fail("%s: not a USGS ASCII spectrum (its first line has no 'Record=')", path);
    }
    *title = strdup(bwh_trim(line));
    size_t cap = 0;
    while ((line = bwh_text_line(&t))) {
        char *s = bwh_trim(line);
        if (!*s)
            continue;
        char *e;
        errno = 0;
        double x = strtof(s, &e);
        if (e == s || *e || !isfinite(x)) {
            bwh_fail("%s:%u: '%s' is not a number", path, t.line, s);
            goto fail;
        }
        if (t.last_cut) {
            bwh_fail("%s:%u: the last value has no line end (the file is cut short)", path, t.line);
            goto fail;
        }
        if (*n == cap) {
            cap = cap ? cap * 2 : 4096;
            double *g = cap <= BW_MAX_BANDS * 2u ? realloc(*v, cap * sizeof *g) : NULL;
            if (!g) {
                bwh_fail("%s: more than %u values", path, BW_MAX_BANDS);
                goto fail;
            }
            *v = g;
        }
        (*v)[(*n)++] = x;
    }
    bwh_text_close(&t);
    if (!*n || *n > BW_MAX_BANDS) {
        free(*v);
        free(*title);
        *v = NULL;
        *title = NULL;
        return bwh_fail("%s: %zu values (1 to %u expected)", path, *n, BW_MAX_BANDS);
    }
    if (!*title) {
        free(*v);
        return bwh_fail("out of memory");
    }
    return 0;
fail:
    bwh_text_close(&t);
    free(*v);
    free(*title);
    *v = NULL;
    *title = NULL;
    return -1;
}

/* a wavelength table beside path for n channels of the title's instrument */
static int find_table(const char *path, const char *title, size_t n, char *out, size_t cap)
{
    const char *slash = strrchr(path, '/');
    char dir[4096];
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    /* the instrument code: the word before AREF / RREF, without its letter */
    char fam[16] = "";
    const char *w = strstr(title, "ASD") ? "ASD" : strstr(title, "BECK") ? "BECK"
                    : strstr(title, "NIC4") ? "NIC4" : strstr(title, "AVIRIS") ? "AVIRIS" : "";
    snprintf(fam, sizeof fam, "%s", w);
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    struct dirent *e;
    int found = -1;
    while ((e = readdir(d)) && found < 0) {
        if (!strstr(e->d_name, "Wavelengths") || (*fam && !strstr(e->d_name, fam)))
            continue;
        char p[4096 + 256];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        char *ti;
        double *v;
        size_t k;
        if (read_table(p, &ti, &v, &k) == 0) {
            if (k == n) {
                snprintf(out, cap, "%s", p);
                found = 0;
            }
            free(ti);
            free(v);
        }
    }
    closedir(d);
    return found;
}

int bwh_read_usgs(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    char *title;
    double *v;
    size_t n;
    if (read_table(path, &title, &v, &n) != 0)
        return -1;
    int rc = -1;
    m->values = malloc(n * sizeof *m->values);
    if (!m->values) {
        bwh_fail("out of memory");
        goto out;
    }
    for (size_t i = 0; i < n; i++) {
        if (fabs(v[i]) > 3.4e38) {
            bwh_fail("%s: value %zu = %g is beyond float32", path, i, v[i]);
            goto out;
        }
        m->values[i] = (float)v[i];
    }
    m->count = m->bands = (uint32_t)n;
    m->shape = BW_SHAPE_SPECTRA;
    m->n_in = 1;
    bwh_meta_t *meta = &m->meta;
    const char *name = bwh_basename(path);
    if (bwh_meta_set_strings(&meta->spectrum_names, &name, 1) ||
        bwh_meta_add_field(meta, "title", title))
        goto out;
    meta->sample_type = BWH_ST_F32;
    meta->present |= BWH_M_SAMPLE_TYPE;
    if (strstr(title, "AREF") || strstr(title, "RREF")) {
        meta->quantity = BWH_Q_REFLECTANCE;
        meta->present |= BWH_M_QUANTITY;
    }
    char table[4096 + 512];
    const char *tp = o->wavelengths;
    if (!tp && !strstr(title, "Wavelengths") && find_table(path, title, n, table, sizeof table) == 0)
        tp = table;
    if (tp) {
        char *tt;
        double *w;
        size_t k;
        if (read_table(tp, &tt, &w, &k) != 0)
            goto out;
        free(tt);
        if (k != n) {
            free(w);
            bwh_fail("%s: %zu wavelengths in %s for %zu values", path, k, tp, n);
            goto out;
        }
        meta->wl_unit = BWH_WL_UM;
        int bad = bwh_meta_set_numbers(&meta->wavelengths, w, n);
        free(w);
        if (bad)
            goto out;
    }
    if (bwh_measure_mark_missing(m, USGS_DELETED) != 0)
        goto out;
    rc = 0;
out:
    free(title);
    free(v);
    if (rc)
        bwh_measure_free(m);
    return rc;
}
