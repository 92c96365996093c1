/* SPDX-License-Identifier: BSD-2-Clause */
/* Spectral Evolution .sed files (bwh_sed.h). */
#define _POSIX_C_SOURCE 200809L
#include "bwh_sed.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bwh_error.h"
#include "bwh_input.h"
#include "bwh_text.h"

/* Parses a non-negative or negative decimal with at most `decimals`
 * fraction digits into units of 10^-decimals, exactly. */
static int parse_fixed(const char *s, int decimals, const char **end, int32_t *out)
{
    while (*s == ' ' || *s == '\t')
        s++;
    int neg = 0;
    if (*s == '-' || *s == '+')
        neg = *s++ == '-';
    if (!isdigit((unsigned char)*s) && *s != '.')
        return -1;
    int64_t v = 0;
    int digits = 0;
    while (isdigit((unsigned char)*s)) {
        v = v * 10 + (*s++ - '0');
        if (v > 100000000)
            return -1;
        digits++;
    }
    int frac = 0;
    if (*s == '.') {
        s++;
        while (isdigit((unsigned char)*s)) {
            if (frac == decimals)
                return -1; /* more precision than the format carries */
            v = v * 10 + (*s++ - '0');
            frac++;
            digits++;
        }
    }
    if (!digits)
        return -1;
    while (frac++ < decimals)
        v *= 10;
    if (v > BW_SAMPLE_MAX || (*s && !isspace((unsigned char)*s)))
        return -1;
    *end = s;
    *out = (int32_t)(neg ? -v : v);
    return 0;
}

int bwh_parse_fixed(const char *s, int decimals, const char **end, int32_t *out)
{
    return parse_fixed(s, decimals, end, out);
}

/* "PSR-3500_SN1116037 [3]": the model and the serial number */
static int instrument_of(bwh_meta_t *m, const char *v)
{
    const char *sn = strstr(v, "_SN");
    if (!sn)
        return bwh_meta_set_string(&m->instrument, v);
    char model[256], serial[256];
    snprintf(model, sizeof model, "%.*s", (int)(sn - v), v);
    snprintf(serial, sizeof serial, "%s", sn + 3);
    serial[strcspn(serial, " [")] = 0;
    return bwh_meta_set_string(&m->instrument, model) || bwh_meta_set_string(&m->serial, serial);
}

/* item k (0 or 1) of "a,b" */
static void item(const char *v, int k, char *out, size_t cap)
{
    const char *c = strchr(v, ',');
    if (k == 1 && c)
        v = c + 1;
    size_t n = k == 0 && c ? (size_t)(c - v) : strlen(v);
    snprintf(out, cap, "%.*s", (int)n, v);
}

/* Date "MM/DD/YYYY,MM/DD/YYYY", Time "hh:mm:ss,hh:mm:ss": the target's
 * (the second), local time */
static int time_of(const char *date, const char *time, double *t)
{
    char d[64], c[64];
    item(date, 1, d, sizeof d);
    item(time, 1, c, sizeof c);
    int mo, dd, y, h, mi, s;
    if (sscanf(d, "%d/%d/%d", &mo, &dd, &y) != 3 || sscanf(c, "%d:%d:%d", &h, &mi, &s) != 3 ||
        mo < 1 || mo > 12 || dd < 1 || dd > 31 || h > 23 || mi > 59 || s > 60)
        return -1;
    *t = bwh_time_of(y, mo, dd, h, mi, s);
    return 0;
}

static int number(const char *v, double *x)
{
    char *e;
    errno = 0;
    *x = strtod(v, &e);
    return e == v || errno || !isfinite(*x) || *bwh_trim(e) ? -1 : 0;
}

int bwh_read_sed(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    bwh_text_t t;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    bwh_meta_t *meta = &m->meta;
    long channels = -1;
    char date[64] = "", time[64] = "";
    double lat = NAN, lon = NAN, alt = NAN;
    char *line;
    int data = 0;
    /* header: "Key: value" lines up to "Data:" */
    while ((line = bwh_text_line(&t))) {
        if (!strncmp(line, "Data:", 5)) {
            data = 1;
            break;
        }
        char *colon = strchr(line, ':');
        if (!colon)
            continue;
        *colon = 0;
        char *k = bwh_trim(line), *v = bwh_trim(colon + 1);
        int rc = 0;
        if (!strcmp(k, "Channels"))
            channels = strtol(v, NULL, 10);
        else if (!strcmp(k, "Instrument"))
            rc = instrument_of(meta, v);
        else if (!strcmp(k, "Date"))
            snprintf(date, sizeof date, "%s", v);
        else if (!strcmp(k, "Time"))
            snprintf(time, sizeof time, "%s", v);
        else if (!strcmp(k, "Latitude"))
            number(v, &lat);
        else if (!strcmp(k, "Longitude"))
            number(v, &lon);
        else if (!strcmp(k, "Altitude"))
            number(v, &alt);
        else if (strcmp(k, "File Name") && strncmp(k, "Columns", 7) && *v)
            rc = bwh_meta_add_field(meta, k, v);
        if (rc)
            goto fail;
    }
    if (!data) {
        bwh_fail("%s: no 'Data:' section: not a Spectral Evolution .sed file, or cut short", path);
        goto fail;
    }
    if (channels < 1 || channels > (long)BW_MAX_BANDS) {
        bwh_fail("%s: missing or invalid 'Channels:' header", path);
        goto fail;
    }
    /* the column titles pick the column */
    line = bwh_text_line(&t);
    int col = -1, ncols = 0, pct = 0;
    for (char *c = line, *tab; c; c = tab ? tab + 1 : NULL, ncols++) {
        tab = strchr(c, '\t');
        char title[128];
        snprintf(title, sizeof title, "%.*s", (int)(tab ? tab - c : (long)strlen(c)), c);
        char *ti = bwh_trim(title);
        int want = o->column == BWH_COL_TARGET ? !strncmp(ti, "Rad. (Target)", 13)
                   : o->column == BWH_COL_REFERENCE ? !strncmp(ti, "Rad. (Ref.)", 11)
                                                  : !strncmp(ti, "Reflect.", 8);
        if (want && col < 0) {
            col = ncols;
            pct = strchr(ti, '%') != NULL;
        }
    }
    if (!line || col < 1) {
        bwh_fail("%s:%u: no %s column in the titles", path, t.line,
                 o->column == BWH_COL_TARGET      ? "'Rad. (Target)'"
                 : o->column == BWH_COL_REFERENCE ? "'Rad. (Ref.)'"
                                                  : "'Reflect.'");
        goto fail;
    }
    int exact = o->column == BWH_COL_REFLECTANCE;
    double *wl = calloc((size_t)channels, sizeof *wl);
    if (exact)
        m->ints = calloc((size_t)channels, sizeof *m->ints);
    else
        m->values = calloc((size_t)channels, sizeof *m->values);
    if (!wl || (!m->ints && !m->values)) {
        free(wl);
        bwh_fail("%s: out of memory", path);
        goto fail;
    }
    uint32_t n = 0;
    while ((line = bwh_text_line(&t))) {
        const char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (!*s)
            continue;
        if (t.last_cut) {
            bwh_fail("%s:%u: the last row has no line end (the file is cut short)", path, t.line);
            free(wl);
            goto fail;
        }
        if (n >= (uint32_t)channels) {
            bwh_fail("%s:%u: more data rows than 'Channels: %ld'", path, t.line, channels);
            free(wl);
            goto fail;
        }
        char *e;
        double cols[8];
        int c;
        for (c = 0; c < col; c++) {
            errno = 0;
            cols[c] = strtod(s, &e);
            if (e == s || errno || !isfinite(cols[c]))
                break;
            s = e;
        }
        const char *end;
        int bad = c < col;
        if (!bad && exact)
            bad = parse_fixed(s, 5, &end, &m->ints[n]) != 0;
        else if (!bad) {
            errno = 0;
            double x = strtod(s, &e);
            bad = e == s || errno || !isfinite(x) || fabs(x) > 3.4e38;
            if (!bad)
                m->values[n] = (float)x;
        }
        if (bad) {
            bwh_fail("%s:%u: expected %d numeric columns with a %s", path, t.line, ncols,
                     exact ? "reflectance of at most 5 decimals" : "finite value");
            free(wl);
            goto fail;
        }
        wl[n] = cols[0];
        n++;
    }
    if (n != (uint32_t)channels) {
        bwh_fail("%s: truncated data (%u of %ld rows)", path, n, channels);
        free(wl);
        goto fail;
    }
    bwh_text_close(&t);
    m->scale = exact ? BWH_SED_SCALE : 1.0;
    m->count = m->bands = n;
    m->shape = BW_SHAPE_SPECTRA;
    m->n_in = 1;
    meta->quantity = !exact ? BWH_Q_RADIANCE : pct ? BWH_Q_REFLECTANCE_PCT : BWH_Q_REFLECTANCE;
    meta->present |= BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE;
    meta->sample_type = BWH_ST_F32;
    const char *units = bwh_meta_field(meta, "Units");
    int rc = (!exact && units && bwh_meta_set_string(&meta->unit, units)) ||
             bwh_meta_set_numbers(&meta->wavelengths, wl, n);
    free(wl);
    meta->wl_unit = BWH_WL_NM;
    const char *name = bwh_basename(path);
    double tm;
    rc = rc || bwh_meta_set_strings(&meta->spectrum_names, &name, 1);
    if (!rc && *date && *time && time_of(date, time, &tm) == 0)
        rc = bwh_meta_set_numbers(&meta->spectrum_times, &tm, 1);
    if (!rc && isfinite(lat) && isfinite(lon))
        rc = bwh_meta_set_numbers(&meta->spectrum_lat, &lat, 1) ||
             bwh_meta_set_numbers(&meta->spectrum_lon, &lon, 1) ||
             (isfinite(alt) && bwh_meta_set_numbers(&meta->spectrum_alt, &alt, 1));
    if (rc) {
        bwh_measure_free(m);
        return -1;
    }
    return 0;
fail:
    bwh_text_close(&t);
    bwh_measure_free(m);
    return -1;
}

int bwh_sed_read(const char *path, int32_t **values, uint32_t *bands, double **wavelengths)
{
    *values = NULL;
    if (wavelengths)
        *wavelengths = NULL;
    bwh_read_opts_t o = BWH_READ_OPTS_INIT;
    bwh_measure_t m;
    if (bwh_read_sed(path, &o, &m) != 0)
        return -1;
    if (wavelengths) {
        *wavelengths = m.meta.wavelengths.v;
        m.meta.wavelengths.v = NULL;
        m.meta.wavelengths.n = 0;
    }
    *values = m.ints;
    m.ints = NULL;
    *bands = m.bands;
    bwh_measure_free(&m);
    return 0;
}

int bwh_sed_read_set(const char *const *paths, int n, int32_t **values, uint32_t *bands,
                     size_t *count)
{
    bwh_read_opts_t o = BWH_READ_OPTS_INIT;
    bwh_measure_t m;
    *values = NULL;
    if (bwh_measure_read(paths, n, BWH_IN_SED, &o, &m) != 0)
        return -1;
    if (*bands && m.bands != *bands) {
        bwh_measure_free(&m);
        return bwh_fail("%s has %u channels, expected %u", paths[0], m.bands, *bands);
    }
    *bands = m.bands;
    *values = m.ints;
    *count = m.count;
    m.ints = NULL;
    bwh_measure_free(&m);
    return 0;
}
