/* SPDX-License-Identifier: BSD-2-Clause */
/* A measurement's metadata: the model, its names and checks (bwh_meta.h). */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include "bwh_meta.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "bwh_error.h"

void bwh_meta_init(bwh_meta_t *m)
{
    memset(m, 0, sizeof *m);
    m->time_tz = BWH_TZ_LOCAL;
    m->spectrum_tz = BWH_TZ_LOCAL;
}

static void free_numbers(bwh_numbers_t *n)
{
    free(n->v);
    n->v = NULL;
    n->n = 0;
}

static void free_strings(bwh_strings_t *s)
{
    for (size_t i = 0; i < s->n; i++)
        free(s->s[i]);
    free(s->s);
    s->s = NULL;
    s->n = 0;
}

void bwh_meta_free(bwh_meta_t *m)
{
    free(m->unit);
    free_numbers(&m->wavelengths);
    free_numbers(&m->fwhm);
    free_strings(&m->band_names);
    free_numbers(&m->incidence);
    free(m->instrument);
    free(m->serial);
    free_strings(&m->spectrum_names);
    free_numbers(&m->spectrum_times);
    free_numbers(&m->spectrum_lat);
    free_numbers(&m->spectrum_lon);
    free_numbers(&m->spectrum_alt);
    free(m->missing);
    for (size_t i = 0; i < m->n_fields; i++) {
        free(m->keys[i]);
        free(m->values[i]);
    }
    free(m->keys);
    free(m->values);
    bwh_meta_init(m);
}

int bwh_meta_empty(const bwh_meta_t *m)
{
    return !m->present && !m->unit && !m->wavelengths.n && !m->fwhm.n && !m->band_names.n &&
           !m->incidence.n && !m->instrument && !m->serial && !m->spectrum_names.n &&
           !m->spectrum_times.n && !m->spectrum_lat.n && !m->spectrum_lon.n &&
           !m->spectrum_alt.n && !m->n_fields;
}

int bwh_meta_set_string(char **dst, const char *s)
{
    char *c = NULL;
    if (s && !(c = strdup(s)))
        return bwh_fail("out of memory");
    free(*dst);
    *dst = c;
    return 0;
}

int bwh_meta_set_numbers(bwh_numbers_t *dst, const double *v, size_t n)
{
    double *c = NULL;
    if (n) {
        c = malloc(n * sizeof *c);
        if (!c)
            return bwh_fail("out of memory");
        memcpy(c, v, n * sizeof *c);
    }
    free(dst->v);
    dst->v = c;
    dst->n = n;
    return 0;
}

int bwh_meta_set_strings(bwh_strings_t *dst, const char *const *s, size_t n)
{
    bwh_strings_t c = {n, n ? calloc(n, sizeof(char *)) : NULL};
    if (n && !c.s)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < n; i++)
        if (!(c.s[i] = strdup(s[i] ? s[i] : ""))) {
            free_strings(&c);
            return bwh_fail("out of memory");
        }
    free_strings(dst);
    *dst = c;
    return 0;
}

int bwh_meta_add_field(bwh_meta_t *m, const char *key, const char *value)
{
    char **k = realloc(m->keys, (m->n_fields + 1) * sizeof *k);
    if (!k)
        return bwh_fail("out of memory");
    m->keys = k;
    char **v = realloc(m->values, (m->n_fields + 1) * sizeof *v);
    if (!v)
        return bwh_fail("out of memory");
    m->values = v;
    char *kc = strdup(key), *vc = strdup(value ? value : "");
    if (!kc || !vc) {
        free(kc);
        free(vc);
        return bwh_fail("out of memory");
    }
    m->keys[m->n_fields] = kc;
    m->values[m->n_fields] = vc;
    m->n_fields++;
    return 0;
}

const char *bwh_meta_field(const bwh_meta_t *m, const char *key)
{
    for (size_t i = 0; i < m->n_fields; i++)
        if (!strcmp(m->keys[i], key))
            return m->values[i];
    return NULL;
}

int bwh_meta_add_missing_run(bwh_meta_t *m, uint64_t start, uint64_t len)
{
    if (!len)
        return 0;
    if (m->n_missing) {
        uint64_t *last = m->missing[m->n_missing - 1];
        if (start < last[0] + last[1])
            return bwh_fail("missing samples out of order");
        if (start == last[0] + last[1]) {
            last[1] += len;
            return 0;
        }
    }
    uint64_t(*r)[2] = realloc(m->missing, (m->n_missing + 1) * sizeof *r);
    if (!r)
        return bwh_fail("out of memory");
    m->missing = r;
    r[m->n_missing][0] = start;
    r[m->n_missing][1] = len;
    m->n_missing++;
    m->present |= BWH_M_MISSING;
    return 0;
}

int bwh_meta_add_missing(bwh_meta_t *m, uint64_t index)
{
    return bwh_meta_add_missing_run(m, index, 1);
}

static int copy_numbers(bwh_numbers_t *d, const bwh_numbers_t *s)
{
    return bwh_meta_set_numbers(d, s->v, s->n);
}

static int copy_strings(bwh_strings_t *d, const bwh_strings_t *s)
{
    return bwh_meta_set_strings(d, (const char *const *)s->s, s->n);
}

int bwh_meta_copy(bwh_meta_t *d, const bwh_meta_t *s)
{
    bwh_meta_init(d);
    d->present = s->present;
    d->quantity = s->quantity;
    d->sample_type = s->sample_type;
    d->wl_unit = s->wl_unit;
    d->inc_unit = s->inc_unit;
    d->time = s->time;
    d->time_tz = s->time_tz;
    d->lat = s->lat;
    d->lon = s->lon;
    d->alt = s->alt;
    d->spectrum_tz = s->spectrum_tz;
    d->missing_value = s->missing_value;
    int bad = bwh_meta_set_string(&d->unit, s->unit) || copy_numbers(&d->wavelengths, &s->wavelengths) ||
              copy_numbers(&d->fwhm, &s->fwhm) || copy_strings(&d->band_names, &s->band_names) ||
              copy_numbers(&d->incidence, &s->incidence) ||
              bwh_meta_set_string(&d->instrument, s->instrument) ||
              bwh_meta_set_string(&d->serial, s->serial) ||
              copy_strings(&d->spectrum_names, &s->spectrum_names) ||
              copy_numbers(&d->spectrum_times, &s->spectrum_times) ||
              copy_numbers(&d->spectrum_lat, &s->spectrum_lat) ||
              copy_numbers(&d->spectrum_lon, &s->spectrum_lon) ||
              copy_numbers(&d->spectrum_alt, &s->spectrum_alt);
    if (!bad && s->n_missing) {
        d->missing = malloc(s->n_missing * sizeof *d->missing);
        bad = !d->missing;
        if (!bad) {
            memcpy(d->missing, s->missing, s->n_missing * sizeof *d->missing);
            d->n_missing = s->n_missing;
        }
    }
    for (size_t i = 0; !bad && i < s->n_fields; i++)
        bad = bwh_meta_add_field(d, s->keys[i], s->values[i]);
    if (bad) {
        bwh_meta_free(d);
        return bwh_fail("out of memory");
    }
    return 0;
}

/* dst's list of n_dst followed by src's of n_src; absent sides filled */
static int append_numbers(bwh_numbers_t *d, size_t n_dst, const bwh_numbers_t *s, size_t n_src)
{
    if (!d->n && !s->n)
        return 0;
    double *v = malloc((n_dst + n_src ? n_dst + n_src : 1) * sizeof *v);
    if (!v)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < n_dst; i++)
        v[i] = d->n == n_dst ? d->v[i] : NAN;
    for (size_t i = 0; i < n_src; i++)
        v[n_dst + i] = s->n == n_src ? s->v[i] : NAN;
    free(d->v);
    d->v = v;
    d->n = n_dst + n_src;
    return 0;
}

static int append_strings(bwh_strings_t *d, size_t n_dst, const bwh_strings_t *s, size_t n_src)
{
    if (!d->n && !s->n)
        return 0;
    bwh_strings_t c = {n_dst + n_src, calloc(n_dst + n_src ? n_dst + n_src : 1, sizeof(char *))};
    if (!c.s)
        return bwh_fail("out of memory");
    for (size_t i = 0; i < c.n; i++) {
        const char *x = i < n_dst ? (d->n == n_dst ? d->s[i] : "")
                                  : (s->n == n_src ? s->s[i - n_dst] : "");
        if (!(c.s[i] = strdup(x))) {
            free_strings(&c);
            return bwh_fail("out of memory");
        }
    }
    free_strings(d);
    *d = c;
    return 0;
}

int bwh_meta_append_spectra(bwh_meta_t *d, size_t n_dst, const bwh_meta_t *s, size_t n_src)
{
    if (!d->spectrum_times.n && s->spectrum_times.n)
        d->spectrum_tz = s->spectrum_tz;
    return append_strings(&d->spectrum_names, n_dst, &s->spectrum_names, n_src) ||
                   append_numbers(&d->spectrum_times, n_dst, &s->spectrum_times, n_src) ||
                   append_numbers(&d->spectrum_lat, n_dst, &s->spectrum_lat, n_src) ||
                   append_numbers(&d->spectrum_lon, n_dst, &s->spectrum_lon, n_src) ||
                   append_numbers(&d->spectrum_alt, n_dst, &s->spectrum_alt, n_src)
               ? -1
               : 0;
}

/* keeps item k of a list of one per row (none: stays none) */
/* Whether row i is kept: marked in rows, or (rows NULL) row k. */
static int kept(const uint8_t *rows, size_t k, size_t i)
{
    return rows ? rows[i] != 0 : i == k;
}

/* A per-row list cut to the rows kept, in order (a list of another length
 * than the rows' is dropped). */
static void keep_numbers(bwh_numbers_t *l, size_t n_rows, const uint8_t *rows, size_t k)
{
    if (l->n != n_rows) {
        free_numbers(l);
        return;
    }
    size_t j = 0;
    for (size_t i = 0; i < l->n; i++)
        if (kept(rows, k, i))
            l->v[j++] = l->v[i];
    l->n = j;
}

static void keep_strings(bwh_strings_t *l, size_t n_rows, const uint8_t *rows, size_t k)
{
    if (l->n != n_rows) {
        free_strings(l);
        return;
    }
    size_t j = 0;
    for (size_t i = 0; i < l->n; i++) {
        if (kept(rows, k, i)) {
            l->s[j++] = l->s[i];
        } else {
            free(l->s[i]);
        }
    }
    l->n = j;
}

/* The rows kept of every per-row list; the missing values' list dropped
 * (their positions are the source's). */
static void keep_rows(bwh_meta_t *m, const bw_dims_t *d, const uint8_t *rows, size_t k)
{
    free(m->missing);
    m->missing = NULL;
    m->n_missing = 0;
    m->present &= ~BWH_M_MISSING;
    size_t n = d->n_in;
    if (d->shape != BW_SHAPE_SPECTRA) {
        if (rows && d->shape == BW_SHAPE_BRDF_ISO)
            keep_numbers(&m->incidence, n, rows, k);
        else
            free_numbers(&m->incidence);
        return;
    }
    keep_strings(&m->spectrum_names, n, rows, k);
    keep_numbers(&m->spectrum_times, n, rows, k);
    keep_numbers(&m->spectrum_lat, n, rows, k);
    keep_numbers(&m->spectrum_lon, n, rows, k);
    keep_numbers(&m->spectrum_alt, n, rows, k);
}

int bwh_meta_row(bwh_meta_t *m, const bw_dims_t *d, uint32_t in)
{
    keep_rows(m, d, NULL, in);
    return 0;
}

int bwh_meta_rows(bwh_meta_t *m, const bw_dims_t *d, const uint8_t *rows)
{
    keep_rows(m, d, rows, 0);
    return 0;
}

/* A sample run [a, e) of a source of nb bands, where band k of it lands at
 * rank[k] of nk (UINT32_MAX: not kept), added to the runs out[*n] (merged
 * with the last where they touch). */
static void keep_run(uint64_t a, uint64_t e, uint32_t nb, const uint32_t *rank, uint32_t nk,
                     uint64_t (*out)[2], size_t *n)
{
    for (uint64_t t = a; t < e; t++) {
        uint32_t r = rank[t % nb];
        if (r == UINT32_MAX)
            continue;
        uint64_t to = t / nb * nk + r;
        if (*n && out[*n - 1][0] + out[*n - 1][1] == to) {
            out[*n - 1][1]++;
        } else {
            out[*n][0] = to;
            out[*n][1] = 1;
            ++*n;
        }
    }
}

int bwh_meta_bands(bwh_meta_t *m, const bw_dims_t *d, const uint8_t *bands)
{
    uint32_t nb = d->bands, nk = 0;
    uint32_t *rank = malloc((size_t)nb * sizeof *rank);
    if (!rank)
        return bwh_fail("out of memory");
    for (uint32_t k = 0; k < nb; k++)
        rank[k] = bands[k] ? nk++ : UINT32_MAX;
    keep_numbers(&m->wavelengths, nb, bands, 0);
    keep_numbers(&m->fwhm, nb, bands, 0);
    keep_strings(&m->band_names, nb, bands, 0);
    if (m->n_missing) {
        /* a run keeps at most one run per spectrum it touches */
        size_t cap = 0, n = 0;
        for (size_t i = 0; i < m->n_missing; i++)
            cap += (size_t)(m->missing[i][1] / nb) + 2u;
        uint64_t(*out)[2] = cap <= SIZE_MAX / sizeof *out ? malloc(cap * sizeof *out) : NULL;
        if (!out) {
            free(rank);
            return bwh_fail("out of memory");
        }
        for (size_t i = 0; i < m->n_missing; i++) {
            uint64_t a = m->missing[i][0];
            keep_run(a, a + m->missing[i][1], nb, rank, nk, out, &n);
        }
        free(m->missing);
        m->missing = out;
        m->n_missing = n;
        if (!n)
            m->present &= ~BWH_M_MISSING;
    }
    free(rank);
    return 0;
}

int bwh_bands_of_wavelengths(const bwh_meta_t *m, size_t n, double lo, double hi, uint8_t *bands)
{
    if (m->wavelengths.n != n || !n)
        return bwh_fail("the payload has no wavelength per band: choose bands by number");
    int k = 0;
    for (size_t i = 0; i < n; i++) {
        double w = m->wavelengths.v[i];
        bands[i] = w >= lo && w <= hi;
        k += bands[i];
    }
    return k;
}

/* ---- names -------------------------------------------------------------- */

static const char *const quantity_names[BWH_Q_COUNT] = {
    "", "reflectance factor", "reflectance percent", "radiance", "irradiance", "brdf",
    "counts", "transmittance", "absorbance", "other"};
static const char *const quantity_units[BWH_Q_COUNT] = {
    "", "1", "%", "W m^-2 sr^-1 nm^-1", "W m^-2 nm^-1", "sr^-1", "DN", "1", "1", ""};

const char *bwh_quantity_name(int q)
{
    return q >= 0 && q < BWH_Q_COUNT ? quantity_names[q] : "?";
}

const char *bwh_quantity_unit(int q)
{
    return q >= 0 && q < BWH_Q_COUNT ? quantity_units[q] : "";
}

int bwh_quantity_from_name(const char *s)
{
    for (int q = 1; s && q < BWH_Q_COUNT; q++)
        if (!strcasecmp(s, quantity_names[q]))
            return q;
    return s && !*s ? BWH_Q_NONE : -1;
}

const char *bwh_meta_unit(const bwh_meta_t *m)
{
    return m->unit ? m->unit : bwh_quantity_unit(m->quantity);
}

static const char *const st_names[BWH_ST_COUNT] = {"", "u8", "i16", "u16", "i32", "f32", "f64"};
static const unsigned char st_sizes[BWH_ST_COUNT] = {0, 1, 2, 2, 4, 4, 8};

const char *bwh_sample_type_name(int t) { return t >= 0 && t < BWH_ST_COUNT ? st_names[t] : "?"; }
size_t bwh_sample_type_size(int t) { return t >= 0 && t < BWH_ST_COUNT ? st_sizes[t] : 0; }

int bwh_sample_type_from_name(const char *s)
{
    for (int t = 1; s && t < BWH_ST_COUNT; t++)
        if (!strcmp(s, st_names[t]))
            return t;
    return -1;
}

static const char *const wl_names[BWH_WL_COUNT] = {"nm", "um", "cm-1"};

const char *bwh_wl_unit_name(int u) { return u >= 0 && u < BWH_WL_COUNT ? wl_names[u] : "?"; }

int bwh_wl_unit_from_name(const char *s)
{
    static const struct {
        const char *name;
        int unit;
    } alias[] = {{"nm", BWH_WL_NM},         {"nanometers", BWH_WL_NM},
                 {"nanometer", BWH_WL_NM},  {"um", BWH_WL_UM},
                 {"micrometers", BWH_WL_UM}, {"micrometer", BWH_WL_UM},
                 {"microns", BWH_WL_UM},    {"micron", BWH_WL_UM},
                 {"\xc2\xb5m", BWH_WL_UM},  {"cm-1", BWH_WL_WAVENUMBER},
                 {"wavenumber", BWH_WL_WAVENUMBER}};
    for (size_t i = 0; s && i < sizeof alias / sizeof *alias; i++)
        if (!strcasecmp(s, alias[i].name))
            return alias[i].unit;
    return -1;
}

const char *bwh_angle_unit_name(int u) { return u == BWH_ANGLE_RAD ? "rad" : u == 0 ? "deg" : "?"; }

int bwh_angle_unit_from_name(const char *s)
{
    if (s && (!strcmp(s, "deg") || !strcasecmp(s, "degrees")))
        return BWH_ANGLE_DEG;
    if (s && (!strcmp(s, "rad") || !strcasecmp(s, "radians")))
        return BWH_ANGLE_RAD;
    return -1;
}

/* ---- time --------------------------------------------------------------- */

/* days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's
 * days_from_civil) */
static long long days_from_civil(long long y, unsigned m, unsigned d)
{
    y -= m <= 2;
    long long era = (y >= 0 ? y : y - 399) / 400;
    unsigned yoe = (unsigned)(y - era * 400);
    unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + (long long)doe - 719468;
}

static void civil_from_days(long long z, long long *y, unsigned *m, unsigned *d)
{
    z += 719468;
    long long era = (z >= 0 ? z : z - 146096) / 146097;
    unsigned doe = (unsigned)(z - era * 146097);
    unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    unsigned mp = (5 * doy + 2) / 153;
    *d = doy - (153 * mp + 2) / 5 + 1;
    *m = mp < 10 ? mp + 3 : mp - 9;
    *y = (long long)yoe + era * 400 + (*m <= 2);
}

double bwh_time_of(int year, int month, int day, int hour, int min, double sec)
{
    return (double)days_from_civil(year, (unsigned)month, (unsigned)day) * 86400.0 +
           hour * 3600.0 + min * 60.0 + sec;
}

void bwh_time_format(double t, int tz, char *buf, size_t cap)
{
    if (!isfinite(t) || fabs(t) > 1e15) {
        snprintf(buf, cap, "?");
        return;
    }
    double whole = floor(t);
    double frac = t - whole;
    long long s = (long long)whole;
    long long days = s >= 0 ? s / 86400 : -((-s + 86399) / 86400);
    long long rem = s - days * 86400;
    long long y;
    unsigned mo, d;
    civil_from_days(days, &y, &mo, &d);
    int n = snprintf(buf, cap, "%04lld-%02u-%02uT%02lld:%02lld:%02lld", y, mo, d, rem / 3600,
                     rem / 60 % 60, rem % 60);
    if (frac > 0 && n > 0 && (size_t)n < cap) {
        /* the fraction's shortest decimal digits that read back */
        char f[32];
        for (int p = 1; p <= 9; p++) {
            snprintf(f, sizeof f, "%.*f", p, frac);
            if (f[0] == '1') /* rounds up to a whole second: keep 9 nines */
                snprintf(f, sizeof f, "0.999999999");
            char t2[48];
            snprintf(t2, sizeof t2, "%lld%s", (long long)whole, f + 1);
            if (strtod(t2, NULL) == t || p == 9)
                break;
        }
        n += snprintf(buf + n, cap - (size_t)n, "%s", f + 1);
    }
    if (n > 0 && (size_t)n < cap && tz != BWH_TZ_LOCAL) {
        if (tz == 0)
            snprintf(buf + n, cap - (size_t)n, "Z");
        else
            snprintf(buf + n, cap - (size_t)n, "%c%02d:%02d", tz < 0 ? '-' : '+', abs(tz) / 60,
                     abs(tz) % 60);
    }
}

static int digits(const char **p, int n, int *out)
{
    int v = 0;
    for (int i = 0; i < n; i++) {
        if (!isdigit((unsigned char)(*p)[i]))
            return -1;
        v = v * 10 + ((*p)[i] - '0');
    }
    *p += n;
    *out = v;
    return 0;
}

int bwh_time_parse(const char *s, double *sec, int *tz)
{
    int y, mo, d, h, mi, se;
    const char *p = s;
    int neg = *p == '-';
    if (*p == '-' || *p == '+')
        p++;
    if (digits(&p, 4, &y) || *p++ != '-' || digits(&p, 2, &mo) || *p++ != '-' ||
        digits(&p, 2, &d) || (*p != 'T' && *p != ' ') || (p++, digits(&p, 2, &h)) ||
        *p++ != ':' || digits(&p, 2, &mi) || *p++ != ':' || digits(&p, 2, &se))
        return bwh_fail("'%s' is not an ISO 8601 time (YYYY-MM-DDThh:mm:ss)", s);
    if (neg)
        y = -y;
    if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || se > 60)
        return bwh_fail("'%s': a date or time field out of range", s);
    double frac = 0;
    if (*p == '.') {
        const char *f = p;
        p++;
        if (!isdigit((unsigned char)*p))
            return bwh_fail("'%s': bad fraction of a second", s);
        while (isdigit((unsigned char)*p))
            p++;
        char b[32];
        snprintf(b, sizeof b, "0%.*s", (int)(p - f), f);
        frac = strtod(b, NULL);
    }
    int z = BWH_TZ_LOCAL;
    if (*p == 'Z') {
        z = 0;
        p++;
    } else if (*p == '+' || *p == '-') {
        int sign = *p++ == '-' ? -1 : 1, zh, zm;
        if (digits(&p, 2, &zh) || *p++ != ':' || digits(&p, 2, &zm) || zm > 59)
            return bwh_fail("'%s': bad time zone (+hh:mm)", s);
        z = sign * (zh * 60 + zm);
        if (abs(z) > BWH_TZ_MAX)
            return bwh_fail("'%s': time zone out of range", s);
    }
    if (*p)
        return bwh_fail("'%s': unexpected text after the time", s);
    double whole = bwh_time_of(y, mo, d, h, mi, se);
    /* the fraction as the decimal it is written as */
    if (frac > 0) {
        char b[64];
        snprintf(b, sizeof b, "%.0f%s", whole, strchr(s, '.'));
        b[strcspn(b, "Z+-")] = 0;
        *sec = whole < 0 ? whole + frac : strtod(b, NULL);
    } else {
        *sec = whole;
    }
    *tz = z;
    return 0;
}

/* ---- checks ------------------------------------------------------------- */

static int count_is(const char *what, size_t have, size_t want, const char *per)
{
    if (have && have != want)
        return bwh_fail("metadata: %zu %s for %zu %s", have, what, want, per);
    return 0;
}

static int valid_utf8(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        int n = *p < 0x80 ? 0 : (*p & 0xE0) == 0xC0 ? 1 : (*p & 0xF0) == 0xE0 ? 2
                : (*p & 0xF8) == 0xF0 ? 3 : -1;
        if (n < 0 || (n == 1 && *p < 0xC2))
            return 0;
        p++;
        for (int i = 0; i < n; i++, p++)
            if ((*p & 0xC0) != 0x80)
                return 0;
    }
    return 1;
}

static int strings_ok(const char *what, const bwh_strings_t *s)
{
    for (size_t i = 0; i < s->n; i++)
        if (!valid_utf8(s->s[i]))
            return bwh_fail("metadata: %s %zu is not UTF-8", what, i);
    return 0;
}

int bwh_meta_check(const bwh_meta_t *m, const bw_dims_t *d)
{
    if (m->quantity < 0 || m->quantity >= BWH_Q_COUNT)
        return bwh_fail("metadata: unknown quantity %d", m->quantity);
    if (m->sample_type < 0 || m->sample_type >= BWH_ST_COUNT)
        return bwh_fail("metadata: unknown sample type %d", m->sample_type);
    if (m->wl_unit < 0 || m->wl_unit >= BWH_WL_COUNT)
        return bwh_fail("metadata: unknown wavelength unit %d", m->wl_unit);
    if (m->inc_unit < 0 || m->inc_unit >= BWH_ANGLE_COUNT)
        return bwh_fail("metadata: unknown angle unit %d", m->inc_unit);
    if (((m->present & BWH_M_TIME) && m->time_tz != BWH_TZ_LOCAL && abs(m->time_tz) > BWH_TZ_MAX) ||
        (m->spectrum_tz != BWH_TZ_LOCAL && abs(m->spectrum_tz) > BWH_TZ_MAX))
        return bwh_fail("metadata: time zone offset beyond +-18 h");
    size_t n_in = d->shape == BW_SHAPE_REFLECTANCE ? 1 : d->n_in;
    if (count_is("wavelengths", m->wavelengths.n, d->bands, "bands") ||
        count_is("bandwidths", m->fwhm.n, d->bands, "bands") ||
        count_is("band names", m->band_names.n, d->bands, "bands"))
        return -1;
    if (m->incidence.n) {
        if (d->shape != BW_SHAPE_BRDF_ISO)
            return bwh_fail("metadata: incidence angles belong to an isotropic BRDF (--incoming)");
        if (count_is("incidence angles", m->incidence.n, n_in, "incoming directions"))
            return -1;
        double top = m->inc_unit == BWH_ANGLE_RAD ? 1.5707963267948966 : 90.0;
        for (size_t i = 0; i < m->incidence.n; i++) {
            double a = m->incidence.v[i];
            if (!(a >= 0 && a <= top) || (i && !(a > m->incidence.v[i - 1])))
                return bwh_fail("metadata: incidence angles must ascend within [0, 90] degrees "
                                "(angle %zu is %g %s)",
                                i, a, bwh_angle_unit_name(m->inc_unit));
        }
    }
    const bwh_numbers_t *lists[] = {&m->spectrum_times, &m->spectrum_lat, &m->spectrum_lon,
                                    &m->spectrum_alt};
    static const char *const what[] = {"spectrum times", "spectrum latitudes",
                                       "spectrum longitudes", "spectrum altitudes"};
    if (m->spectrum_names.n || m->spectrum_times.n || m->spectrum_lat.n || m->spectrum_lon.n ||
        m->spectrum_alt.n) {
        if (d->shape != BW_SHAPE_SPECTRA)
            return bwh_fail("metadata: per-spectrum names, times and locations belong to a set "
                            "of spectra");
        if (count_is("spectrum names", m->spectrum_names.n, n_in, "spectra"))
            return -1;
        for (int i = 0; i < 4; i++)
            if (count_is(what[i], lists[i]->n, n_in, "spectra"))
                return -1;
        if (m->spectrum_lat.n != m->spectrum_lon.n || (m->spectrum_alt.n && !m->spectrum_lat.n))
            return bwh_fail("metadata: spectrum locations need latitudes and longitudes");
    }
    if (m->present & BWH_M_MISSING) {
        uint64_t end = 0, n = bw_dims_samples(d);
        for (size_t i = 0; i < m->n_missing; i++) {
            if (m->missing[i][1] == 0 || m->missing[i][0] < end || m->missing[i][0] > n ||
                m->missing[i][1] > n - m->missing[i][0])
                return bwh_fail("metadata: missing samples beyond the %llu samples or out of order",
                                (unsigned long long)n);
            end = m->missing[i][0] + m->missing[i][1];
        }
    }
    if ((m->unit && !valid_utf8(m->unit)) || (m->instrument && !valid_utf8(m->instrument)) ||
        (m->serial && !valid_utf8(m->serial)))
        return bwh_fail("metadata: a text that is not UTF-8");
    if (strings_ok("band name", &m->band_names) || strings_ok("spectrum name", &m->spectrum_names))
        return -1;
    for (size_t i = 0; i < m->n_fields; i++)
        if (!valid_utf8(m->keys[i]) || !valid_utf8(m->values[i]) || !*m->keys[i])
            return bwh_fail("metadata: free field %zu has an empty or non-UTF-8 name or value", i);
    return 0;
}

void bwh_meta_put_missing(const bwh_meta_t *m, float *values, size_t n)
{
    if (!(m->present & BWH_M_MISSING))
        return;
    float v = (float)m->missing_value;
    for (size_t r = 0; r < m->n_missing; r++)
        for (uint64_t i = m->missing[r][0]; i < m->missing[r][0] + m->missing[r][1] && i < n; i++)
            values[i] = v;
}

int bwh_meta_merge(bwh_meta_t *d, const bwh_meta_t *s)
{
    int bad = 0;
    if (s->present & BWH_M_QUANTITY) {
        d->quantity = s->quantity;
        d->present |= BWH_M_QUANTITY;
        bad = bad || bwh_meta_set_string(&d->unit, s->unit);
    } else if (s->unit) {
        bad = bad || bwh_meta_set_string(&d->unit, s->unit);
    }
    if (s->present & BWH_M_SAMPLE_TYPE) {
        d->sample_type = s->sample_type;
        d->present |= BWH_M_SAMPLE_TYPE;
    }
    if (s->wavelengths.n || s->fwhm.n)
        d->wl_unit = s->wl_unit;
    if (s->wavelengths.n)
        bad = bad || copy_numbers(&d->wavelengths, &s->wavelengths);
    if (s->fwhm.n)
        bad = bad || copy_numbers(&d->fwhm, &s->fwhm);
    if (s->band_names.n)
        bad = bad || copy_strings(&d->band_names, &s->band_names);
    if (s->incidence.n) {
        d->inc_unit = s->inc_unit;
        bad = bad || copy_numbers(&d->incidence, &s->incidence);
    }
    if (s->instrument)
        bad = bad || bwh_meta_set_string(&d->instrument, s->instrument);
    if (s->serial)
        bad = bad || bwh_meta_set_string(&d->serial, s->serial);
    if (s->present & BWH_M_TIME) {
        d->time = s->time;
        d->time_tz = s->time_tz;
        d->present |= BWH_M_TIME;
    }
    if (s->present & BWH_M_LOCATION) {
        d->lat = s->lat;
        d->lon = s->lon;
        d->alt = s->alt;
        d->present = (d->present & ~BWH_M_ALTITUDE) | (s->present & (BWH_M_LOCATION | BWH_M_ALTITUDE));
    }
    if (s->spectrum_names.n)
        bad = bad || copy_strings(&d->spectrum_names, &s->spectrum_names);
    if (s->spectrum_times.n) {
        d->spectrum_tz = s->spectrum_tz;
        bad = bad || copy_numbers(&d->spectrum_times, &s->spectrum_times);
    }
    if (s->spectrum_lat.n)
        bad = bad || copy_numbers(&d->spectrum_lat, &s->spectrum_lat) ||
              copy_numbers(&d->spectrum_lon, &s->spectrum_lon) ||
              copy_numbers(&d->spectrum_alt, &s->spectrum_alt);
    if (s->present & BWH_M_MISSING) {
        free(d->missing);
        d->missing = NULL;
        d->n_missing = 0;
        for (size_t i = 0; !bad && i < s->n_missing; i++)
            bad = bwh_meta_add_missing_run(d, s->missing[i][0], s->missing[i][1]);
        d->missing_value = s->missing_value;
    }
    for (size_t i = 0; !bad && i < s->n_fields; i++) {
        size_t k;
        for (k = 0; k < d->n_fields && strcmp(d->keys[k], s->keys[i]); k++)
            ;
        if (k < d->n_fields)
            bad = bwh_meta_set_string(&d->values[k], s->values[i]);
        else
            bad = bwh_meta_add_field(d, s->keys[i], s->values[i]);
    }
    return bad ? -1 : 0;
}
