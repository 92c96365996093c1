/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Spectra Vista (SVC) .sig text files (HR-1024i and alike): the magic line
 * "Spectra Vista SIG Data" between its stars (or the older HR-1024 one), "key=
 * value" lines (pairs "reference, target"), "data=", then rows of four
 * columns: wavelength (nm), reference, target, reflectance in percent. A
 * raw export holds every detector pixel, the overlaps of the detectors
 * included, so its wavelengths go back where a detector ends: they are kept
 * in file order, as the samples are. The column read: the reflectance
 * (default), the target or the reference, each exactly as its 2 printed
 * decimals. Kept: wavelengths, instrument model and serial, the target's
 * time and GPS position, the units, the other keys as free fields.
 */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bwh_error.h"
#include "bwh_input.h"
#include "bwh_sed.h"
#include "bwh_text.h"

/* item k (0 reference, 1 target) of "a, b", trimmed, into out */
static void pair(const char *v, int k, char *out, size_t cap)
{
    const char *c = strchr(v, ',');
    if (k == 1 && c)
        v = c + 1;
    size_t n = k == 0 && c ? (size_t)(c - v) : strlen(v);
    snprintf(out, cap, "%.*s", (int)n, v);
    char *t = bwh_trim(out);
    memmove(out, t, strlen(t) + 1);
}

/* "8/6/2015 9:32:30 AM": local time */
static int time_of(const char *s, double *t)
{
    int mo, d, y, h, mi, se;
    char ap[3] = "";
    if (sscanf(s, "%d/%d/%d %d:%d:%d %2s", &mo, &d, &y, &h, &mi, &se, ap) < 6 || mo < 1 ||
        mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || se > 60)
        return -1;
    if (!strcmp(ap, "PM") && h < 12)
        h += 12;
    else if (!strcmp(ap, "AM") && h == 12)
        h = 0;
    *t = bwh_time_of(y, mo, d, h, mi, se);
    return 0;
}

/* "09231.1627W" (dddmm.mmmm and a hemisphere): degrees, west and south
 * negative */
static int angle_of(const char *s, double *deg)
{
    char *e;
    errno = 0;
    double v = strtod(s, &e);
    if (e == s || errno || !strchr("NSEW", *e) || !*e)
        return -1;
    double dd = floor(v / 100.0), mm = v - 100.0 * dd;
    *deg = (dd + mm / 60.0) * (*e == 'S' || *e == 'W' ? -1.0 : 1.0);
    return 0;
}

int bwh_read_sig(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    bwh_text_t t;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    char *line = bwh_text_line(&t);
    double *wl = NULL;
    float *vals = NULL;
    size_t cap = 0, n = 0;
    int exact = 1;
    if (!line || (strncmp(line, "/*** Spectra Vista SIG Data ***/", 32) &&
                  strncmp(line, "/*** Spectra Vista HR-1024 ***/", 30))) {
        bwh_fail("%s: not a Spectra Vista .sig file (no '/*** Spectra Vista SIG Data ***/' line)",
                 path);
        goto fail;
    }
    bwh_meta_t *meta = &m->meta;
    char units[64] = "", tm[64] = "", lat[64] = "", lon[64] = "";
    int data = 0;
    while ((line = bwh_text_line(&t))) {
        char *eq = strchr(line, '=');
        if (!eq)
            continue;
        *eq = 0;
        char *k = bwh_trim(line), *v = bwh_trim(eq + 1);
        if (!strcmp(k, "data")) {
            data = 1;
            break;
        }
        int rc = 0;
        if (!strcmp(k, "instrument")) {
            /* "HI: 1152050 (HR-1024i)" */
            char model[128] = "", serial[128] = "";
            const char *c = strchr(v, ':'), *p = strchr(v, '(');
            if (c && p && p > c && strchr(p, ')')) {
                snprintf(serial, sizeof serial, "%.*s", (int)(p - c - 1), c + 1);
                snprintf(model, sizeof model, "%.*s", (int)(strchr(p, ')') - p - 1), p + 1);
                rc = bwh_meta_set_string(&meta->instrument, bwh_trim(model)) ||
                     bwh_meta_set_string(&meta->serial, bwh_trim(serial));
            } else {
                rc = bwh_meta_set_string(&meta->instrument, v);
            }
        } else if (!strcmp(k, "units")) {
            pair(v, o->column == BWH_COL_REFERENCE ? 0 : 1, units, sizeof units);
            rc = bwh_meta_add_field(meta, k, v);
        } else if (!strcmp(k, "time")) {
            pair(v, 1, tm, sizeof tm);
        } else if (!strcmp(k, "latitude")) {
            pair(v, 1, lat, sizeof lat);
        } else if (!strcmp(k, "longitude")) {
            pair(v, 1, lon, sizeof lon);
        } else if (strcmp(k, "name") && *v) {
            rc = bwh_meta_add_field(meta, k, v);
        }
        if (rc)
            goto fail;
    }
    if (!data) {
        bwh_fail("%s: no 'data=' line (the file is cut short)", path);
        goto fail;
    }
    int col = o->column == BWH_COL_REFERENCE ? 1 : o->column == BWH_COL_TARGET ? 2 : 3;
    while ((line = bwh_text_line(&t))) {
        const char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (!*s)
            continue;
        if (t.last_cut) {
            bwh_fail("%s:%u: the last row has no line end (the file is cut short)", path, t.line);
            goto fail;
        }
        if (n == cap) {
            cap = cap ? cap * 2 : 1024;
            double *g = cap <= BW_MAX_BANDS ? realloc(wl, cap * sizeof *g) : NULL;
            int32_t *q = g ? realloc(m->ints, cap * sizeof *q) : NULL;
            float *fv = q ? realloc(vals, cap * sizeof *fv) : NULL;
            if (g)
                wl = g;
            if (q)
                m->ints = q;
            if (fv)
                vals = fv;
            if (!g || !q || !fv) {
                bwh_fail("%s:%u: more than %u rows", path, t.line, BW_MAX_BANDS);
                goto fail;
            }
        }
        char *e;
        int c, bad = 0;
        double w = 0;
        for (c = 0; c <= 3 && !bad; c++) {
            const char *end;
            int32_t q;
            errno = 0;
            double x = strtod(s, &e);
            bad = e == s || errno || !isfinite(x) || fabs(x) > 3.4e38;
            if (c == 0)
                w = x;
            if (!bad && c == col) {
                /* exactly as its decimals, while they fit the codec's range */
                if (exact && (bwh_parse_fixed(s, 2, &end, &q) != 0 || end != e))
                    exact = 0;
                m->ints[n] = exact ? q : 0;
                vals[n] = (float)x;
            }
            s = e;
        }
        while (!bad && (*s == ' ' || *s == '\t'))
            s++;
        if (bad || *s) {
            bwh_fail("%s:%u: expected 4 numeric columns: wavelength, reference, target, "
                     "reflectance",
                     path, t.line);
            goto fail;
        }
        wl[n++] = w;
    }
    if (!n) {
        bwh_fail("%s: no data rows after 'data='", path);
        goto fail;
    }
    bwh_text_close(&t);
    if (exact) {
        free(vals);
        m->scale = 0.01;
    } else {
        free(m->ints);
        m->ints = NULL;
        m->values = vals;
    }
    m->count = m->bands = (uint32_t)n;
    m->shape = BW_SHAPE_SPECTRA;
    m->n_in = 1;
    meta->present |= BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE;
    meta->sample_type = BWH_ST_F32;
    int rc = 0;
    if (col == 3) {
        meta->quantity = BWH_Q_REFLECTANCE_PCT;
    } else if (!strcmp(units, "Radiance")) {
        meta->quantity = BWH_Q_RADIANCE;
        rc = bwh_meta_set_string(&meta->unit, "10^-10 W cm^-2 sr^-1 nm^-1");
    } else {
        meta->quantity = !strcmp(units, "Counts") ? BWH_Q_COUNTS : BWH_Q_OTHER;
        if (meta->quantity == BWH_Q_OTHER)
            rc = bwh_meta_set_string(&meta->unit, units);
    }
    meta->wl_unit = BWH_WL_NM;
    const char *name = bwh_basename(path);
    double tt, la, lo;
    rc = rc || bwh_meta_set_numbers(&meta->wavelengths, wl, n) ||
         bwh_meta_set_strings(&meta->spectrum_names, &name, 1);
    if (!rc && *tm && time_of(tm, &tt) == 0)
        rc = bwh_meta_set_numbers(&meta->spectrum_times, &tt, 1);
    if (!rc && angle_of(lat, &la) == 0 && angle_of(lon, &lo) == 0)
        rc = bwh_meta_set_numbers(&meta->spectrum_lat, &la, 1) ||
             bwh_meta_set_numbers(&meta->spectrum_lon, &lo, 1);
    free(wl);
    if (rc) {
        bwh_measure_free(m);
        return -1;
    }
    return 0;
fail:
    free(wl);
    free(vals);
    bwh_text_close(&t);
    bwh_measure_free(m);
    return -1;
}
