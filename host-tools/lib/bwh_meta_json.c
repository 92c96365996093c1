/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The metadata as JSON, both ways (bwh_meta.h): the text form the command
 * line's sidecars and the Python package exchange. Numbers are written as
 * the shortest decimal that reads back as the same double, times as ISO 8601.
 * The reader takes any JSON (RFC 8259) and keeps the keys it knows; an
 * unknown key or a value of the wrong kind is an error that names it.
 */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "bwh_meta.h"

/* ---- writing ------------------------------------------------------------- */

typedef struct {
    char *b;
    size_t n, cap;
    int oom;
} sbuf_t;

static void put(sbuf_t *s, const char *t, size_t n)
{
    if (s->oom)
        return;
    if (s->n + n + 1 > s->cap) {
        size_t c = s->cap ? s->cap : 1024;
        while (c < s->n + n + 1)
            c *= 2;
        char *nb = realloc(s->b, c);
        if (!nb) {
            s->oom = 1;
            return;
        }
        s->b = nb;
        s->cap = c;
    }
    memcpy(s->b + s->n, t, n);
    s->n += n;
    s->b[s->n] = 0;
}

static void puts_(sbuf_t *s, const char *t) { put(s, t, strlen(t)); }

__attribute__((format(printf, 2, 3))) static void putf(sbuf_t *s, const char *fmt, ...)
{
    char b[128];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b, sizeof b, fmt, ap);
    va_end(ap);
    if (n > 0)
        put(s, b, (size_t)n < sizeof b ? (size_t)n : sizeof b - 1);
}

void bwh_json_number(double v, char *buf, size_t cap)
{
    if (!isfinite(v)) {
        snprintf(buf, cap, "null");
        return;
    }
    double a = fabs(v);
    if (a == 0 || (a >= 1e-5 && a < 1e15)) {
        /* plain decimals: the fewest that read back */
        for (int d = 0; d <= 20; d++) {
            snprintf(buf, cap, "%.*f", d, v);
            if (strtod(buf, NULL) == v)
                return;
        }
    }
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, cap, "%.*g", p, v);
        if (strtod(buf, NULL) == v)
            break;
    }
}

static void put_number(sbuf_t *s, double v)
{
    char b[40];
    bwh_json_number(v, b, sizeof b);
    puts_(s, b);
}

static void put_str(sbuf_t *s, const char *t)
{
    put(s, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)t; *p; p++) {
        switch (*p) {
        case '"':
            puts_(s, "\\\"");
            break;
        case '\\':
            puts_(s, "\\\\");
            break;
        case '\n':
            puts_(s, "\\n");
            break;
        case '\r':
            puts_(s, "\\r");
            break;
        case '\t':
            puts_(s, "\\t");
            break;
        default:
            if (*p < 0x20)
                putf(s, "\\u%04x", *p);
            else
                put(s, (const char *)p, 1);
        }
    }
    put(s, "\"", 1);
}

static void key(sbuf_t *s, int *first, const char *k)
{
    puts_(s, *first ? "{" : ", ");
    *first = 0;
    put_str(s, k);
    puts_(s, ": ");
}

static void put_numbers(sbuf_t *s, const bwh_numbers_t *n)
{
    put(s, "[", 1);
    for (size_t i = 0; i < n->n; i++) {
        if (i)
            puts_(s, ", ");
        put_number(s, n->v[i]);
    }
    put(s, "]", 1);
}

static void put_strings(sbuf_t *s, const bwh_strings_t *n)
{
    put(s, "[", 1);
    for (size_t i = 0; i < n->n; i++) {
        if (i)
            puts_(s, ", ");
        put_str(s, n->s[i]);
    }
    put(s, "]", 1);
}

static void put_time(sbuf_t *s, double t, int tz)
{
    if (!isfinite(t)) {
        puts_(s, "null");
        return;
    }
    char b[64];
    bwh_time_format(t, tz, b, sizeof b);
    put_str(s, b);
}

int bwh_meta_to_json(const bwh_meta_t *m, char **json)
{
    return bwh_meta_to_json_layout(m, -1, json);
}

int bwh_meta_to_json_layout(const bwh_meta_t *m, int layout, char **json)
{
    sbuf_t s = {0};
    int first = 1;
    if (layout >= 0 && layout <= 3) {
        static const char *const shapes[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
        key(&s, &first, "shape");
        put_str(&s, shapes[layout]);
    }
    if (m->present & BWH_M_QUANTITY) {
        key(&s, &first, "quantity");
        put_str(&s, bwh_quantity_name(m->quantity));
    }
    if ((m->present & BWH_M_QUANTITY) || m->unit) {
        key(&s, &first, "unit");
        put_str(&s, bwh_meta_unit(m));
    }
    if (m->present & BWH_M_SAMPLE_TYPE) {
        key(&s, &first, "sample_type");
        put_str(&s, bwh_sample_type_name(m->sample_type));
    }
    if (m->wavelengths.n || m->fwhm.n) {
        key(&s, &first, "wavelength_unit");
        put_str(&s, bwh_wl_unit_name(m->wl_unit));
    }
    if (m->wavelengths.n) {
        key(&s, &first, "wavelengths");
        put_numbers(&s, &m->wavelengths);
    }
    if (m->fwhm.n) {
        key(&s, &first, "fwhm");
        put_numbers(&s, &m->fwhm);
    }
    if (m->band_names.n) {
        key(&s, &first, "band_names");
        put_strings(&s, &m->band_names);
    }
    if (m->incidence.n) {
        key(&s, &first, "incidence_unit");
        put_str(&s, bwh_angle_unit_name(m->inc_unit));
        key(&s, &first, "incidence");
        put_numbers(&s, &m->incidence);
    }
    if (m->instrument) {
        key(&s, &first, "instrument");
        put_str(&s, m->instrument);
    }
    if (m->serial) {
        key(&s, &first, "serial");
        put_str(&s, m->serial);
    }
    if (m->present & BWH_M_TIME) {
        key(&s, &first, "time");
        put_time(&s, m->time, m->time_tz);
    }
    if (m->present & BWH_M_LOCATION) {
        key(&s, &first, "location");
        puts_(&s, "[");
        put_number(&s, m->lat);
        puts_(&s, ", ");
        put_number(&s, m->lon);
        if (m->present & BWH_M_ALTITUDE) {
            puts_(&s, ", ");
            put_number(&s, m->alt);
        }
        puts_(&s, "]");
    }
    if (m->spectrum_names.n) {
        key(&s, &first, "spectrum_names");
        put_strings(&s, &m->spectrum_names);
    }
    if (m->spectrum_times.n) {
        key(&s, &first, "spectrum_times");
        put(&s, "[", 1);
        for (size_t i = 0; i < m->spectrum_times.n; i++) {
            if (i)
                puts_(&s, ", ");
            put_time(&s, m->spectrum_times.v[i], m->spectrum_tz);
        }
        put(&s, "]", 1);
    }
    if (m->spectrum_lat.n) {
        key(&s, &first, "spectrum_locations");
        put(&s, "[", 1);
        for (size_t i = 0; i < m->spectrum_lat.n; i++) {
            puts_(&s, i ? ", [" : "[");
            put_number(&s, m->spectrum_lat.v[i]);
            puts_(&s, ", ");
            put_number(&s, m->spectrum_lon.v[i]);
            if (m->spectrum_alt.n) {
                puts_(&s, ", ");
                put_number(&s, m->spectrum_alt.v[i]);
            }
            puts_(&s, "]");
        }
        put(&s, "]", 1);
    }
    if (m->present & BWH_M_MISSING) {
        key(&s, &first, "missing");
        puts_(&s, "{\"value\": ");
        put_number(&s, m->missing_value);
        puts_(&s, ", \"runs\": [");
        for (size_t i = 0; i < m->n_missing; i++)
            putf(&s, "%s[%llu, %llu]", i ? ", " : "", (unsigned long long)m->missing[i][0],
                 (unsigned long long)m->missing[i][1]);
        puts_(&s, "]}");
    }
    if (m->n_fields) {
        key(&s, &first, "fields");
        for (size_t i = 0; i < m->n_fields; i++) {
            puts_(&s, i ? ", " : "{");
            put_str(&s, m->keys[i]);
            puts_(&s, ": ");
            put_str(&s, m->values[i]);
        }
        puts_(&s, "}");
    }
    puts_(&s, first ? "{}" : "}");
    if (s.oom) {
        free(s.b);
        return bwh_fail("out of memory");
    }
    *json = s.b;
    return 0;
}

/* ---- reading ------------------------------------------------------------- */

enum { J_NULL, J_BOOL, J_NUM, J_STR, J_ARR, J_OBJ };

typedef struct jv {
    int type;
    double num;
    char *str;
    size_t n;
    struct jv *items; /* array items or object values */
    char **keys;      /* object keys */
} jv_t;

typedef struct {
    const char *p, *start;
    int depth;
} jp_t;

static void jv_free(jv_t *v)
{
    free(v->str);
    for (size_t i = 0; i < v->n; i++) {
        jv_free(&v->items[i]);
        if (v->keys)
            free(v->keys[i]);
    }
    free(v->items);
    free(v->keys);
}

static int jfail(const jp_t *j, const char *why)
{
    return bwh_fail("metadata JSON at byte %ld: %s", (long)(j->p - j->start), why);
}

static void ws(jp_t *j)
{
    while (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r')
        j->p++;
}

static int hex4(const char *p, unsigned *u)
{
    *u = 0;
    for (int i = 0; i < 4; i++) {
        int c = p[i], d = isdigit(c) ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10
                                               : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : -1;
        if (d < 0)
            return -1;
        *u = *u << 4 | (unsigned)d;
    }
    return 0;
}

static void utf8(sbuf_t *s, unsigned c)
{
    char b[4];
    size_t n;
    if (c < 0x80) {
        b[0] = (char)c;
        n = 1;
    } else if (c < 0x800) {
        b[0] = (char)(0xC0 | c >> 6);
        b[1] = (char)(0x80 | (c & 0x3F));
        n = 2;
    } else if (c < 0x10000) {
        b[0] = (char)(0xE0 | c >> 12);
        b[1] = (char)(0x80 | (c >> 6 & 0x3F));
        b[2] = (char)(0x80 | (c & 0x3F));
        n = 3;
    } else {
        b[0] = (char)(0xF0 | c >> 18);
        b[1] = (char)(0x80 | (c >> 12 & 0x3F));
        b[2] = (char)(0x80 | (c >> 6 & 0x3F));
        b[3] = (char)(0x80 | (c & 0x3F));
        n = 4;
    }
    put(s, b, n);
}

static int jstring(jp_t *j, char **out)
{
    sbuf_t s = {0};
    put(&s, "", 0);
    j->p++; /* the opening quote */
    for (;;) {
        unsigned char c = (unsigned char)*j->p;
        if (!c) {
            free(s.b);
            return jfail(j, "a string without its closing quote");
        }
        if (c < 0x20) {
            free(s.b);
            return jfail(j, "a control character in a string");
        }
        j->p++;
        if (c == '"')
            break;
        if (c != '\\') {
            put(&s, (const char *)&c, 1);
            continue;
        }
        char e = *j->p++;
        const char *esc = strchr("\"\\/bfnrt", e);
        if (e && esc) {
            static const char to[] = "\"\\/\b\f\n\r\t";
            put(&s, &to[esc - "\"\\/bfnrt"], 1);
            continue;
        }
        unsigned u;
        if (e != 'u' || hex4(j->p, &u)) {
            free(s.b);
            return jfail(j, "a bad escape in a string");
        }
        j->p += 4;
        if (u >= 0xD800 && u < 0xDC00) {
            unsigned lo;
            if (j->p[0] != '\\' || j->p[1] != 'u' || hex4(j->p + 2, &lo) || lo < 0xDC00 ||
                lo > 0xDFFF) {
                free(s.b);
                return jfail(j, "an unpaired surrogate in a string");
            }
            j->p += 6;
            u = 0x10000 + ((u - 0xD800) << 10) + (lo - 0xDC00);
        } else if (u >= 0xDC00 && u < 0xE000) {
            free(s.b);
            return jfail(j, "an unpaired surrogate in a string");
        }
        if (!u) {
            free(s.b);
            return jfail(j, "a NUL character in a string");
        }
        utf8(&s, u);
    }
    if (s.oom) {
        free(s.b);
        return bwh_fail("out of memory");
    }
    *out = s.b;
    return 0;
}

static int jvalue(jp_t *j, jv_t *v);

static int jlist(jp_t *j, jv_t *v, int obj)
{
    char close = obj ? '}' : ']';
    j->p++;
    ws(j);
    if (*j->p == close) {
        j->p++;
        return 0;
    }
    size_t cap = 0;
    for (;;) {
        if (v->n == cap) {
            cap = cap ? cap * 2 : 8;
            jv_t *ni = realloc(v->items, cap * sizeof *ni);
            char **nk = obj ? realloc(v->keys, cap * sizeof *nk) : NULL;
            if (ni)
                v->items = ni;
            if (nk)
                v->keys = nk;
            if (!ni || (obj && !nk))
                return bwh_fail("out of memory");
        }
        memset(&v->items[v->n], 0, sizeof *v->items);
        if (obj) {
            ws(j);
            if (*j->p != '"')
                return jfail(j, "expected a key");
            if (jstring(j, &v->keys[v->n]))
                return -1;
            ws(j);
            if (*j->p != ':') {
                free(v->keys[v->n]);
                return jfail(j, "expected ':'");
            }
            j->p++;
        }
        v->n++;
        if (jvalue(j, &v->items[v->n - 1]))
            return -1;
        ws(j);
        if (*j->p == ',') {
            j->p++;
            continue;
        }
        if (*j->p == close) {
            j->p++;
            return 0;
        }
        return jfail(j, obj ? "expected ',' or '}'" : "expected ',' or ']'");
    }
}

static int jvalue(jp_t *j, jv_t *v)
{
    memset(v, 0, sizeof *v);
    ws(j);
    if (++j->depth > 16)
        return jfail(j, "nested too deep");
    int rc = 0;
    char c = *j->p;
    if (c == '{' || c == '[') {
        v->type = c == '{' ? J_OBJ : J_ARR;
        rc = jlist(j, v, c == '{');
    } else if (c == '"') {
        v->type = J_STR;
        rc = jstring(j, &v->str);
    } else if (!strncmp(j->p, "null", 4)) {
        v->type = J_NULL;
        j->p += 4;
    } else if (!strncmp(j->p, "true", 4) || !strncmp(j->p, "false", 5)) {
        v->type = J_BOOL;
        v->num = c == 't';
        j->p += c == 't' ? 4 : 5;
    } else if (c == '-' || isdigit((unsigned char)c)) {
        char *e;
        v->type = J_NUM;
        v->num = strtod(j->p, &e);
        if (e == j->p || !isfinite(v->num))
            return jfail(j, "a bad number");
        j->p = e;
    } else {
        rc = jfail(j, "expected a value");
    }
    j->depth--;
    return rc;
}

/* ---- JSON to the metadata ---------------------------------------------- */

static int kind(const char *k, const jv_t *v, int type, const char *what)
{
    if (v->type != type)
        return bwh_fail("metadata JSON: \"%s\" must be %s", k, what);
    return 0;
}

static int to_numbers(const char *k, const jv_t *v, bwh_numbers_t *out)
{
    if (kind(k, v, J_ARR, "an array of numbers"))
        return -1;
    double *x = malloc((v->n ? v->n : 1) * sizeof *x);
    if (!x)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < v->n; i++) {
        if (v->items[i].type != J_NUM && v->items[i].type != J_NULL) {
            free(x);
            return bwh_fail("metadata JSON: \"%s\" item %zu is not a number", k, i);
        }
        x[i] = v->items[i].type == J_NUM ? v->items[i].num : NAN;
    }
    int rc = bwh_meta_set_numbers(out, x, v->n);
    free(x);
    return rc;
}

static int to_strings(const char *k, const jv_t *v, bwh_strings_t *out)
{
    if (kind(k, v, J_ARR, "an array of strings"))
        return -1;
    const char **s = malloc((v->n ? v->n : 1) * sizeof *s);
    if (!s)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < v->n; i++) {
        if (v->items[i].type != J_STR) {
            free(s);
            return bwh_fail("metadata JSON: \"%s\" item %zu is not a string", k, i);
        }
        s[i] = v->items[i].str;
    }
    int rc = bwh_meta_set_strings(out, s, v->n);
    free(s);
    return rc;
}

static int to_time(const char *k, const jv_t *v, double *t, int *tz, int *have_tz)
{
    if (v->type == J_NULL) {
        *t = NAN;
        return 0;
    }
    if (v->type == J_NUM) { /* seconds since 1970, UTC */
        *t = v->num;
        if (*have_tz && *tz != 0)
            return bwh_fail("metadata JSON: \"%s\": times in different time zones", k);
        *tz = 0;
        *have_tz = 1;
        return 0;
    }
    if (v->type != J_STR)
        return bwh_fail("metadata JSON: \"%s\" must be an ISO 8601 time", k);
    int z;
    if (bwh_time_parse(v->str, t, &z) != 0)
        return bwh_fail("metadata JSON: \"%s\": %s", k, bwh_last_error());
    if (*have_tz && z != *tz)
        return bwh_fail("metadata JSON: \"%s\": times in different time zones", k);
    *tz = z;
    *have_tz = 1;
    return 0;
}

static int to_location(const char *k, const jv_t *v, double *lat, double *lon, double *alt,
                       int *n)
{
    if (v->type != J_ARR || v->n < 2 || v->n > 3)
        return bwh_fail("metadata JSON: \"%s\" must be [latitude, longitude] or [latitude, "
                        "longitude, altitude]",
                        k);
    double x[3];
    for (size_t i = 0; i < v->n; i++) {
        if (v->items[i].type != J_NUM && v->items[i].type != J_NULL)
            return bwh_fail("metadata JSON: \"%s\" holds a value that is not a number", k);
        x[i] = v->items[i].type == J_NUM ? v->items[i].num : NAN;
    }
    *lat = x[0];
    *lon = x[1];
    *alt = v->n == 3 ? x[2] : NAN;
    *n = (int)v->n;
    return 0;
}

static int named(const char *k, const jv_t *v, int (*from)(const char *), int *out)
{
    if (kind(k, v, J_STR, "a string"))
        return -1;
    int c = from(v->str);
    if (c < 0)
        return bwh_fail("metadata JSON: \"%s\": unknown value \"%s\"", k, v->str);
    *out = c;
    return 0;
}

static int apply(const char *k, const jv_t *v, bwh_meta_t *m, const char **unit, int *layout)
{
    if (!strcmp(k, "shape")) {
        static const char *const shapes[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
        if (kind(k, v, J_STR, "a string"))
            return -1;
        for (int i = 0; i < 4; i++)
            if (!strcmp(v->str, shapes[i])) {
                if (layout)
                    *layout = i;
                return 0;
            }
        return bwh_fail("metadata JSON: \"shape\": unknown value \"%s\"", v->str);
    }
    if (!strcmp(k, "quantity")) {
        if (named(k, v, bwh_quantity_from_name, &m->quantity))
            return -1;
        m->present |= BWH_M_QUANTITY;
        return 0;
    }
    if (!strcmp(k, "unit"))
        return kind(k, v, J_STR, "a string") ? -1 : (*unit = v->str, 0);
    if (!strcmp(k, "sample_type")) {
        if (named(k, v, bwh_sample_type_from_name, &m->sample_type))
            return -1;
        m->present |= BWH_M_SAMPLE_TYPE;
        return 0;
    }
    if (!strcmp(k, "wavelength_unit"))
        return named(k, v, bwh_wl_unit_from_name, &m->wl_unit);
    if (!strcmp(k, "wavelengths"))
        return to_numbers(k, v, &m->wavelengths);
    if (!strcmp(k, "fwhm"))
        return to_numbers(k, v, &m->fwhm);
    if (!strcmp(k, "band_names"))
        return to_strings(k, v, &m->band_names);
    if (!strcmp(k, "incidence_unit"))
        return named(k, v, bwh_angle_unit_from_name, &m->inc_unit);
    if (!strcmp(k, "incidence"))
        return to_numbers(k, v, &m->incidence);
    if (!strcmp(k, "instrument") || !strcmp(k, "serial"))
        return kind(k, v, J_STR, "a string")
                   ? -1
                   : bwh_meta_set_string(k[0] == 'i' ? &m->instrument : &m->serial, v->str);
    if (!strcmp(k, "time")) {
        int have = 0;
        if (v->type == J_NULL)
            return 0;
        if (to_time(k, v, &m->time, &m->time_tz, &have))
            return -1;
        m->present |= BWH_M_TIME;
        return 0;
    }
    if (!strcmp(k, "location")) {
        int n;
        if (to_location(k, v, &m->lat, &m->lon, &m->alt, &n))
            return -1;
        m->present |= BWH_M_LOCATION | (n == 3 ? BWH_M_ALTITUDE : 0u);
        return 0;
    }
    if (!strcmp(k, "spectrum_names"))
        return to_strings(k, v, &m->spectrum_names);
    if (!strcmp(k, "spectrum_times")) {
        if (kind(k, v, J_ARR, "an array of times"))
            return -1;
        double *t = malloc((v->n ? v->n : 1) * sizeof *t);
        if (!t)
            return bwh_fail("out of memory");
        int have = 0;
        m->spectrum_tz = BWH_TZ_LOCAL;
        for (size_t i = 0; i < v->n; i++)
            if (to_time(k, &v->items[i], &t[i], &m->spectrum_tz, &have)) {
                free(t);
                return -1;
            }
        int rc = bwh_meta_set_numbers(&m->spectrum_times, t, v->n);
        free(t);
        return rc;
    }
    if (!strcmp(k, "spectrum_locations")) {
        if (kind(k, v, J_ARR, "an array of locations"))
            return -1;
        size_t n = v->n;
        double *x = malloc((n ? n : 1) * 3 * sizeof *x);
        if (!x)
            return bwh_fail("out of memory");
        int first = 0, c = 0;
        for (size_t i = 0; i < n; i++) {
            if (to_location(k, &v->items[i], &x[i], &x[n + i], &x[2 * n + i], &c) ||
                (i && c != first)) {
                free(x);
                return i && c != first ? bwh_fail("metadata JSON: \"%s\": locations with and "
                                                  "without altitude",
                                                  k)
                                       : -1;
            }
            first = c;
        }
        int rc = bwh_meta_set_numbers(&m->spectrum_lat, x, n) ||
                 bwh_meta_set_numbers(&m->spectrum_lon, x + n, n) ||
                 bwh_meta_set_numbers(&m->spectrum_alt, x + 2 * n, first == 3 ? n : 0);
        free(x);
        return rc ? -1 : 0;
    }
    if (!strcmp(k, "missing")) {
        const jv_t *val = NULL, *runs = NULL;
        if (kind(k, v, J_OBJ, "an object {\"value\": V, \"runs\": [[start, length], ...]}"))
            return -1;
        for (size_t i = 0; i < v->n; i++) {
            if (!strcmp(v->keys[i], "value"))
                val = &v->items[i];
            else if (!strcmp(v->keys[i], "runs"))
                runs = &v->items[i];
        }
        if (!val || val->type != J_NUM || !runs || runs->type != J_ARR)
            return bwh_fail("metadata JSON: \"missing\" needs a number \"value\" and \"runs\"");
        for (size_t i = 0; i < runs->n; i++) {
            const jv_t *r = &runs->items[i];
            if (r->type != J_ARR || r->n != 2 || r->items[0].type != J_NUM ||
                r->items[1].type != J_NUM || !(r->items[0].num >= 0) || !(r->items[1].num >= 1) ||
                r->items[0].num > 1e18 || r->items[1].num > 1e18 ||
                r->items[0].num != floor(r->items[0].num) || r->items[1].num != floor(r->items[1].num))
                return bwh_fail("metadata JSON: \"missing\" run %zu is not [start, length]", i);
            if (bwh_meta_add_missing_run(m, (uint64_t)r->items[0].num, (uint64_t)r->items[1].num))
                return bwh_fail("metadata JSON: \"missing\" runs overlap or are out of order");
        }
        m->missing_value = val->num;
        m->present |= BWH_M_MISSING;
        return 0;
    }
    if (!strcmp(k, "fields")) {
        if (kind(k, v, J_OBJ, "an object of strings"))
            return -1;
        for (size_t i = 0; i < v->n; i++) {
            if (v->items[i].type != J_STR)
                return bwh_fail("metadata JSON: field \"%s\" is not a string", v->keys[i]);
            if (bwh_meta_add_field(m, v->keys[i], v->items[i].str))
                return -1;
        }
        return 0;
    }
    return bwh_fail("metadata JSON: unknown key \"%s\"", k);
}

int bwh_meta_from_json(const char *json, bwh_meta_t *m)
{
    return bwh_meta_from_json_layout(json, m, NULL);
}

int bwh_meta_from_json_layout(const char *json, bwh_meta_t *m, int *layout)
{
    if (layout)
        *layout = -1;
    bwh_meta_init(m);
    jp_t j = {json, json, 0};
    jv_t root;
    if (jvalue(&j, &root)) {
        jv_free(&root);
        return -1;
    }
    ws(&j);
    if (*j.p) {
        jv_free(&root);
        return jfail(&j, "text after the JSON value");
    }
    if (root.type != J_OBJ) {
        jv_free(&root);
        return bwh_fail("metadata JSON: not an object");
    }
    const char *unit = NULL;
    for (size_t i = 0; i < root.n; i++) {
        for (size_t k = 0; k < i; k++)
            if (!strcmp(root.keys[k], root.keys[i])) {
                bwh_fail("metadata JSON: key \"%s\" given twice", root.keys[i]);
                goto fail;
            }
        if (apply(root.keys[i], &root.items[i], m, &unit, layout))
            goto fail;
    }
    /* a unit is kept only where it is not the quantity's own */
    if (unit && strcmp(unit, bwh_quantity_unit(m->quantity)) && bwh_meta_set_string(&m->unit, unit))
        goto fail;
    jv_free(&root);
    return 0;
fail:
    jv_free(&root);
    bwh_meta_free(m);
    return -1;
}
