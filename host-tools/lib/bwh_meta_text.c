/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The metadata as "key: value" lines, for 'brdfwave info' (bwh_meta.h):
 * one line per part, lists in full (numbers space-separated as JSON writes
 * them, texts as JSON strings), so that a script can read any of them.
 */
#include <stdio.h>
#include <string.h>

#include "bwh_meta.h"

static void numbers(FILE *f, const char *key, const bwh_numbers_t *n, const char *unit)
{
    char b[32];
    fprintf(f, "%s:", key);
    for (size_t i = 0; i < n->n; i++) {
        bwh_json_number(n->v[i], b, sizeof b);
        fprintf(f, " %s", b);
    }
    if (unit)
        fprintf(f, " (%s)", unit);
    fputc('\n', f);
}

/* a text as a JSON string: quotes, backslashes and controls escaped */
static void text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static void strings(FILE *f, const char *key, const bwh_strings_t *s)
{
    fprintf(f, "%s:", key);
    for (size_t i = 0; i < s->n; i++) {
        fputc(' ', f);
        text(f, s->s[i]);
    }
    fputc('\n', f);
}

static void times(FILE *f, const char *key, const bwh_numbers_t *t, int tz)
{
    char b[48];
    fprintf(f, "%s:", key);
    for (size_t i = 0; i < t->n; i++) {
        if (t->v[i] != t->v[i]) {
            fprintf(f, " -");
            continue;
        }
        bwh_time_format(t->v[i], tz, b, sizeof b);
        fprintf(f, " %s", b);
    }
    fputc('\n', f);
}

void bwh_meta_print(const bwh_meta_t *m, FILE *f)
{
    if (m->present & BWH_M_QUANTITY)
        fprintf(f, "quantity: %s\n", bwh_quantity_name(m->quantity));
    if ((m->present & BWH_M_QUANTITY) || m->unit)
        fprintf(f, "unit: %s\n", bwh_meta_unit(m));
    if (m->present & BWH_M_SAMPLE_TYPE)
        fprintf(f, "sample_type: %s\n", bwh_sample_type_name(m->sample_type));
    if (m->wavelengths.n)
        numbers(f, "wavelengths", &m->wavelengths, bwh_wl_unit_name(m->wl_unit));
    if (m->fwhm.n)
        numbers(f, "fwhm", &m->fwhm, bwh_wl_unit_name(m->wl_unit));
    if (m->band_names.n)
        strings(f, "band_names", &m->band_names);
    if (m->incidence.n)
        numbers(f, "incidence", &m->incidence, bwh_angle_unit_name(m->inc_unit));
    if (m->instrument) {
        fprintf(f, "instrument: ");
        text(f, m->instrument);
        fputc('\n', f);
    }
    if (m->serial) {
        fprintf(f, "serial: ");
        text(f, m->serial);
        fputc('\n', f);
    }
    if (m->present & BWH_M_TIME) {
        bwh_numbers_t t = {1, (double *)&m->time};
        times(f, "time", &t, m->time_tz);
    }
    if (m->present & BWH_M_LOCATION) {
        char a[32], b[32], c[32];
        bwh_json_number(m->lat, a, sizeof a);
        bwh_json_number(m->lon, b, sizeof b);
        fprintf(f, "location: %s %s", a, b);
        if (m->present & BWH_M_ALTITUDE) {
            bwh_json_number(m->alt, c, sizeof c);
            fprintf(f, " %s", c);
        }
        fprintf(f, " (deg N, deg E%s)\n", (m->present & BWH_M_ALTITUDE) ? ", m" : "");
    }
    if (m->spectrum_names.n)
        strings(f, "spectrum_names", &m->spectrum_names);
    if (m->spectrum_times.n)
        times(f, "spectrum_times", &m->spectrum_times, m->spectrum_tz);
    if (m->spectrum_lat.n) {
        numbers(f, "spectrum_latitudes", &m->spectrum_lat, "deg N");
        numbers(f, "spectrum_longitudes", &m->spectrum_lon, "deg E");
        if (m->spectrum_alt.n)
            numbers(f, "spectrum_altitudes", &m->spectrum_alt, "m");
    }
    if (m->present & BWH_M_MISSING) {
        char b[32];
        uint64_t total = 0;
        for (size_t i = 0; i < m->n_missing; i++)
            total += m->missing[i][1];
        bwh_json_number(m->missing_value, b, sizeof b);
        fprintf(f, "missing: %llu samples in %zu runs, value %s\n", (unsigned long long)total,
                m->n_missing, b);
    }
    for (size_t i = 0; i < m->n_fields; i++) {
        fprintf(f, "field: ");
        text(f, m->keys[i]);
        fputc(' ', f);
        text(f, m->values[i]);
        fputc('\n', f);
    }
}
