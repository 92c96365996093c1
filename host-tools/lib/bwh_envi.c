/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * ENVI files, both ways: a text header (first line "ENVI", then "key =
 * value" lines; a value in braces may span lines; keys are compared without
 * case) beside a binary data file.
 *
 * Read: spectral libraries (file type "ENVI Spectral Library": samples are
 * the channels, lines the spectra) and images (each pixel a spectrum of
 * `bands`, interleave bsq, bil or bip), data types 1-5 and 12-15, either
 * byte order, a header offset. Kept: wavelength (and its units), fwhm, band
 * names, spectra names, sensor type as the instrument, acquisition time,
 * data ignore value (those samples are marked missing), and every other key
 * as a free field with its text; brdfwave's own keys (below) give back what
 * this writer wrote.
 *
 * Written: a library for a set of spectra, else a BIP image with lines the
 * incoming and samples the outgoing directions; the metadata as the keys
 * above and "brdfwave shape", "brdfwave level", "brdfwave level in",
 * "brdfwave quantity", "brdfwave unit", "brdfwave sample type", "brdfwave
 * serial", "brdfwave location", "brdfwave incidence", "brdfwave incidence
 * unit", "brdfwave spectrum times", "brdfwave spectrum latitudes", "...
 * longitudes", "... altitudes", and a free field ENVI cannot hold as a key
 * as "brdfwave json field = [key, value]".
 */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_input.h"
#include "bwh_output.h"
#include "bwh_text.h"
#include "geodesic.h"

int bwh_envi_header_of(const char *path, char *hdr, size_t cap); /* bwh_input.c */

typedef struct {
    size_t n;
    char **key, **val;
} envi_hdr_t;

static void hdr_free(envi_hdr_t *h)
{
    for (size_t i = 0; i < h->n; i++) {
        free(h->key[i]);
        free(h->val[i]);
    }
    free(h->key);
    free(h->val);
    memset(h, 0, sizeof *h);
}

static const char *hdr_get(const envi_hdr_t *h, const char *key)
{
    for (size_t i = 0; i < h->n; i++)
        if (!strcasecmp(h->key[i], key))
            return h->val[i];
    return NULL;
}

static int hdr_parse(const char *path, envi_hdr_t *h)
{
    memset(h, 0, sizeof *h);
    bwh_text_t t;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    char *line = bwh_text_line(&t);
    if (!line || strncmp(bwh_trim(line), "ENVI", 4)) {
        bwh_text_close(&t);
        return bwh_fail("%s: not an ENVI header (its first line is not 'ENVI')", path);
    }
    while ((line = bwh_text_line(&t))) {
        char *eq = strchr(line, '=');
        if (!*bwh_trim(line))
            continue;
        if (!eq) {
            unsigned ln = t.line;
            bwh_text_close(&t);
            hdr_free(h);
            return bwh_fail("%s:%u: a line that is not 'key = value'", path, ln);
        }
        *eq = 0;
        char *k = bwh_trim(line), *v = bwh_trim(eq + 1);
        /* a brace value to its closing brace, across lines */
        size_t cap = strlen(v) + 1, n = strlen(v);
        char *val = malloc(cap);
        if (!val)
            goto oom;
        memcpy(val, v, n + 1);
        if (*v == '{') {
            while (!strchr(val, '}')) {
                char *more = bwh_text_line(&t);
                if (!more) {
                    /* (k is in the text's buffer: the message before it goes) */
                    bwh_fail("%s: the value of '%s' has no closing brace (the header is cut "
                             "short)",
                             path, k);
                    free(val);
                    bwh_text_close(&t);
                    hdr_free(h);
                    return -1;
                }
                size_t m = strlen(more);
                char *nv = realloc(val, n + m + 2);
                if (!nv) {
                    free(val);
                    goto oom;
                }
                val = nv;
                val[n++] = '\n';
                memcpy(val + n, more, m + 1);
                n += m;
            }
        }
        char **nk = realloc(h->key, (h->n + 1) * sizeof *nk);
        if (nk)
            h->key = nk;
        char **nvv = nk ? realloc(h->val, (h->n + 1) * sizeof *nvv) : NULL;
        if (nvv)
            h->val = nvv;
        char *kc = strdup(k);
        if (!nk || !nvv || !kc) {
            free(kc);
            free(val);
            goto oom;
        }
        h->key[h->n] = kc;
        h->val[h->n] = val;
        h->n++;
    }
    bwh_text_close(&t);
    return 0;
oom:
    bwh_text_close(&t);
    hdr_free(h);
    return bwh_fail("out of memory");
}

/* the items of "{a, b, c}" (trimmed, allocated, in place of a copy); the
 * count, or -1 */
static long list_items(const char *v, char ***items)
{
    *items = NULL;
    if (*v != '{')
        return -1;
    const char *e = strrchr(v, '}');
    if (!e)
        return -1;
    char *c = strndup(v + 1, (size_t)(e - v - 1));
    if (!c)
        return -1;
    size_t cap = 16, n = 0;
    char **it = malloc(cap * sizeof *it);
    if (!it) {
        free(c);
        return -1;
    }
    char *p = c;
    if (*bwh_trim(c)) {
        for (;;) {
            char *comma = strchr(p, ',');
            if (comma)
                *comma = 0;
            if (n == cap) {
                char **g = realloc(it, (cap *= 2) * sizeof *g);
                if (!g) {
                    for (size_t i = 0; i < n; i++)
                        free(it[i]);
                    free(it);
                    free(c);
                    return -1;
                }
                it = g;
            }
            it[n++] = strdup(bwh_trim(p));
            if (!comma)
                break;
            p = comma + 1;
        }
    }
    free(c);
    for (size_t i = 0; i < n; i++)
        if (!it[i]) {
            for (size_t j = 0; j < n; j++)
                free(it[j]);
            free(it);
            return -1;
        }
    *items = it;
    return (long)n;
}

static void items_free(char **it, long n)
{
    for (long i = 0; i < n; i++)
        free(it[i]);
    free(it);
}

/* The items of the {list} v of `key`, want of them (0: any number); -1
 * (the error said) if it is none or has another count. */
static long list_want(const char *path, const char *key, const char *v, size_t want, char ***it)
{
    long n = list_items(v, it);
    if (n < 0)
        return bwh_fail("%s: '%s' is not a {list}", path, key);
    if (want && (size_t)n != want) {
        items_free(*it, n);
        return bwh_fail("%s: '%s' has %ld items, expected %zu", path, key, n, want);
    }
    return n;
}

static int list_numbers(const char *path, const char *key, const char *v, size_t want,
                        bwh_numbers_t *out)
{
    char **it;
    long n = list_want(path, key, v, want, &it);
    if (n < 0)
        return -1;
    double *x = malloc((n ? (size_t)n : 1) * sizeof *x);
    int rc = x ? 0 : bwh_fail("out of memory");
    for (long i = 0; !rc && i < n; i++) {
        char *e;
        errno = 0;
        x[i] = strtod(it[i], &e);
        if (e == it[i] || *e || errno == ERANGE)
            rc = bwh_fail("%s: '%s' item %ld ('%s') is not a number", path, key, i, it[i]);
    }
    if (!rc)
        rc = bwh_meta_set_numbers(out, x, (size_t)n);
    free(x);
    items_free(it, n);
    return rc;
}

static int list_strings(const char *path, const char *key, const char *v, size_t want,
                        bwh_strings_t *out)
{
    char **it;
    long n = list_want(path, key, v, want, &it);
    if (n < 0)
        return -1;
    int rc = bwh_meta_set_strings(out, (const char *const *)it, (size_t)n);
    items_free(it, n);
    return rc;
}

static int header_number(const char *path, const envi_hdr_t *h, const char *key, long def,
                         long lo, long hi, long *out)
{
    const char *v = hdr_get(h, key);
    if (!v) {
        if (def < 0)
            return bwh_fail("%s: the header has no '%s'", path, key);
        *out = def;
        return 0;
    }
    char *e;
    errno = 0;
    long x = strtol(v, &e, 10);
    if (e == v || *bwh_trim(e) || errno || x < lo || x > hi)
        return bwh_fail("%s: '%s = %s' is not an integer %ld..%ld", path, key, v, lo, hi);
    *out = x;
    return 0;
}

/* the keys the reader turns into metadata (not kept as free fields) */
static int consumed(const char *k)
{
    static const char *const keys[] = {
        "samples", "lines", "bands", "header offset", "file type", "data type", "interleave",
        "byte order", "wavelength units", "wavelength", "fwhm", "band names", "spectra names",
        "sensor type", "acquisition time", "data ignore value", NULL};
    for (int i = 0; keys[i]; i++)
        if (!strcasecmp(k, keys[i]))
            return 1;
    return !strncasecmp(k, "brdfwave ", 9);
}

static int read_own(const char *path, const envi_hdr_t *h, bwh_measure_t *m, long *shape)
{
    bwh_meta_t *meta = &m->meta;
    const char *v;
    *shape = -1;
    if ((v = hdr_get(h, "brdfwave shape"))) {
        static const char *const shapes[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
        for (int i = 0; i < 4; i++)
            if (!strcmp(v, shapes[i]))
                *shape = i;
        if (*shape < 0)
            return bwh_fail("%s: unknown 'brdfwave shape = %s'", path, v);
    }
    long lv;
    if ((v = hdr_get(h, "brdfwave level"))) {
        if (header_number(path, h, "brdfwave level", 0, 0, BW_MAX_LEVEL, &lv))
            return -1;
        m->level_out = (unsigned)lv;
    }
    if ((v = hdr_get(h, "brdfwave level in"))) {
        if (header_number(path, h, "brdfwave level in", 0, 0, BW_MAX_LEVEL, &lv))
            return -1;
        m->level_in = (unsigned)lv;
    }
    if ((v = hdr_get(h, "brdfwave quantity"))) {
        int q = bwh_quantity_from_name(v);
        if (q < 0)
            return bwh_fail("%s: unknown 'brdfwave quantity = %s'", path, v);
        meta->quantity = q;
        meta->present |= BWH_M_QUANTITY;
    }
    if ((v = hdr_get(h, "brdfwave unit")) && bwh_meta_set_string(&meta->unit, v))
        return -1;
    if ((v = hdr_get(h, "brdfwave sample type"))) {
        int st = bwh_sample_type_from_name(v);
        if (st < 0)
            return bwh_fail("%s: unknown 'brdfwave sample type = %s'", path, v);
        meta->sample_type = st;
        meta->present |= BWH_M_SAMPLE_TYPE;
    }
    if ((v = hdr_get(h, "brdfwave serial")) && bwh_meta_set_string(&meta->serial, v))
        return -1;
    if ((v = hdr_get(h, "brdfwave location"))) {
        bwh_numbers_t l = {0, NULL};
        if (list_numbers(path, "brdfwave location", v, 0, &l))
            return -1;
        if (l.n < 2 || l.n > 3) {
            free(l.v);
            return bwh_fail("%s: 'brdfwave location' is not {lat, lon[, alt]}", path);
        }
        meta->lat = l.v[0];
        meta->lon = l.v[1];
        meta->alt = l.n == 3 ? l.v[2] : 0;
        meta->present |= BWH_M_LOCATION | (l.n == 3 ? BWH_M_ALTITUDE : 0u);
        free(l.v);
    }
    if ((v = hdr_get(h, "brdfwave incidence unit"))) {
        int u = bwh_angle_unit_from_name(v);
        if (u < 0)
            return bwh_fail("%s: unknown 'brdfwave incidence unit = %s'", path, v);
        meta->inc_unit = u;
    }
    if ((v = hdr_get(h, "brdfwave incidence")) &&
        list_numbers(path, "brdfwave incidence", v, 0, &meta->incidence))
        return -1;
    if ((v = hdr_get(h, "brdfwave spectrum times"))) {
        char **it;
        long n = list_items(v, &it);
        if (n < 0)
            return bwh_fail("%s: 'brdfwave spectrum times' is not a {list}", path);
        double *t = malloc((n ? (size_t)n : 1) * sizeof *t);
        int rc = t ? 0 : bwh_fail("out of memory");
        for (long i = 0; !rc && i < n; i++) {
            int tz;
            if (!strcmp(it[i], "null")) {
                t[i] = NAN;
                continue;
            }
            if (bwh_time_parse(it[i], &t[i], &tz) != 0)
                rc = bwh_fail("%s: 'brdfwave spectrum times': %s", path, bwh_last_error());
            else
                meta->spectrum_tz = tz;
        }
        if (!rc)
            rc = bwh_meta_set_numbers(&meta->spectrum_times, t, (size_t)n);
        free(t);
        items_free(it, n);
        if (rc)
            return -1;
    }
    static const char *const loc[] = {"brdfwave spectrum latitudes", "brdfwave spectrum longitudes",
                                      "brdfwave spectrum altitudes"};
    bwh_numbers_t *dst[] = {&meta->spectrum_lat, &meta->spectrum_lon, &meta->spectrum_alt};
    for (int i = 0; i < 3; i++)
        if ((v = hdr_get(h, loc[i])) && list_numbers(path, loc[i], v, 0, dst[i]))
            return -1;
    for (size_t i = 0; i < h->n; i++)
        if (!strcasecmp(h->key[i], "brdfwave json field")) {
            bwh_meta_t f;
            /* ["key", "value"] read as {"fields": {"key": "value"}} */
            size_t n = strlen(h->val[i]);
            char *obj = malloc(n + 32);
            if (!obj)
                return bwh_fail("out of memory");
            const char *p = h->val[i];
            if (*p != '[' || h->val[i][n - 1] != ']') {
                free(obj);
                return bwh_fail("%s: 'brdfwave json field' is not [key, value]", path);
            }
            /* the comma between two JSON strings */
            const char *q = p + 1;
            while (*q == ' ')
                q++;
            int esc = 0;
            const char *c = NULL;
            for (const char *s = q + 1; *s; s++) {
                if (esc) {
                    esc = 0;
                    continue;
                }
                if (*s == '\\')
                    esc = 1;
                else if (*s == '"') {
                    c = s + 1;
                    break;
                }
            }
            while (c && *c == ' ')
                c++;
            if (*q != '"' || !c || *c != ',') {
                free(obj);
                return bwh_fail("%s: 'brdfwave json field' is not [key, value]", path);
            }
            snprintf(obj, n + 32, "{\"fields\": {%.*s: %.*s}}", (int)(c - q), q,
                     (int)(h->val[i] + n - 1 - (c + 1)), c + 1);
            int rc = bwh_meta_from_json(obj, &f);
            free(obj);
            if (rc)
                return bwh_fail("%s: 'brdfwave json field': %s", path, bwh_last_error());
            rc = bwh_meta_add_field(meta, f.keys[0], f.values[0]);
            bwh_meta_free(&f);
            if (rc)
                return -1;
        }
    return 0;
}

/* the data file of a header: the header's name without .hdr, with one of
 * the usual extensions, or as it is */
static int data_of(const char *hdr, char *out, size_t cap)
{
    static const char *const ext[] = {"", ".sli", ".img", ".dat", ".bsq", ".bil", ".bip", ".raw",
                                      ".bin", NULL};
    size_t n = strlen(hdr);
    size_t base = n >= 4 && !strcasecmp(hdr + n - 4, ".hdr") ? n - 4 : n;
    for (int i = 0; ext[i]; i++) {
        snprintf(out, cap, "%.*s%s", (int)base, hdr, ext[i]);
        FILE *f = fopen(out, "rb");
        if (f) {
            fclose(f);
            return 0;
        }
    }
    return -1;
}

int bwh_read_envi(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    (void)o;
    bwh_measure_init(m);
    char hdr[4096], dat[4096];
    size_t pl = strlen(path);
    if (pl >= 4 && !strcasecmp(path + pl - 4, ".hdr")) {
        snprintf(hdr, sizeof hdr, "%s", path);
        if (data_of(hdr, dat, sizeof dat) != 0)
            return bwh_fail("%s: no data file beside the header (tried the name without .hdr, "
                            "and with .sli, .img, .dat, .bsq, .bil, .bip, .raw, .bin)",
                            path);
    } else {
        snprintf(dat, sizeof dat, "%s", path);
        if (bwh_envi_header_of(path, hdr, sizeof hdr) != 0)
            return bwh_fail("%s: no ENVI header beside it (%s.hdr or its name with .hdr)", path,
                            path);
    }
    envi_hdr_t h;
    if (hdr_parse(hdr, &h) != 0)
        return -1;
    long samples, lines, bands, offset, dtype, order;
    int rc = -1;
    uint8_t *raw = NULL;
    if (header_number(hdr, &h, "samples", -1, 1, 1L << 28, &samples) ||
        header_number(hdr, &h, "lines", -1, 1, 1L << 28, &lines) ||
        header_number(hdr, &h, "bands", -1, 1, 1L << 28, &bands) ||
        header_number(hdr, &h, "header offset", 0, 0, 1L << 30, &offset) ||
        header_number(hdr, &h, "data type", -1, 1, 15, &dtype) ||
        header_number(hdr, &h, "byte order", 0, 0, 1, &order))
        goto out;
    static const signed char dsize[16] = {0, 1, 2, 4, 4, 8, -1, 0, 0, -1, 0, 0, 2, 4, 8, 8};
    if (dsize[dtype] <= 0) {
        bwh_fail("%s: data type %ld (%s) is not read", hdr, dtype,
                 dtype == 6 || dtype == 9 ? "complex" : "unknown");
        goto out;
    }
    const char *il = hdr_get(&h, "interleave");
    int inter = !il || !strcasecmp(il, "bsq") ? 0 : !strcasecmp(il, "bil") ? 1
                : !strcasecmp(il, "bip") ? 2 : -1;
    if (inter < 0) {
        bwh_fail("%s: interleave '%s' is not bsq, bil or bip", hdr, il);
        goto out;
    }
    const char *ft = hdr_get(&h, "file type");
    int library = ft && !strcasecmp(ft, "ENVI Spectral Library");
    if (library && bands != 1) {
        bwh_fail("%s: a spectral library with %ld bands (1 expected)", hdr, bands);
        goto out;
    }
    size_t total = (size_t)samples * (size_t)lines * (size_t)bands;
    if (total > BW_MAX_SAMPLES) {
        bwh_fail("%s: %zu values, more than %u", hdr, total, BW_MAX_SAMPLES);
        goto out;
    }
    size_t len, es = (size_t)dsize[dtype];
    if (bwh_read_file(dat, &raw, &len) != 0)
        goto out;
    if (len < (size_t)offset + total * es) {
        bwh_fail("%s: truncated: %zu bytes, the header (%s) says %zu", dat, len, hdr,
                 (size_t)offset + total * es);
        goto out;
    }
    /* spectra: [pixel][band], pixels line by line */
    size_t nb = library ? (size_t)samples : (size_t)bands;
    size_t npix = library ? (size_t)lines : (size_t)lines * (size_t)samples;
    int integer = dtype != 4 && dtype != 5;
    if (integer)
        m->ints = malloc(total * sizeof *m->ints);
    else
        m->values = malloc(total * sizeof *m->values);
    if (!m->ints && !m->values) {
        bwh_fail("out of memory");
        goto out;
    }
    for (size_t l = 0; l < (size_t)lines; l++)
        for (size_t s = 0; s < (size_t)samples; s++)
            for (size_t b = 0; b < (size_t)bands; b++) {
                size_t fi = inter == 0   ? (b * (size_t)lines + l) * (size_t)samples + s
                            : inter == 1 ? (l * (size_t)bands + b) * (size_t)samples + s
                                         : (l * (size_t)samples + s) * (size_t)bands + b;
                size_t di = library ? l * (size_t)samples + s
                                    : (l * (size_t)samples + s) * (size_t)bands + b;
                const uint8_t *p = raw + offset + fi * es;
                uint64_t u = 0;
                for (size_t i = 0; i < es; i++)
                    u |= (uint64_t)p[order ? es - 1 - i : i] << (8 * i);
                if (!integer) {
                    double x;
                    if (es == 4) {
                        uint32_t w = (uint32_t)u;
                        float f;
                        memcpy(&f, &w, 4);
                        x = f;
                    } else {
                        memcpy(&x, &u, 8);
                    }
                    if (isfinite(x) && fabs(x) > 3.4028234663852886e38) {
                        bwh_fail("%s: value %zu = %g is beyond float32", dat, di, x);
                        goto out;
                    }
                    m->values[di] = (float)x;
                    continue;
                }
                int64_t v = dtype == 1    ? (int64_t)(uint8_t)u
                            : dtype == 2  ? (int64_t)(int16_t)u
                            : dtype == 3  ? (int64_t)(int32_t)u
                            : dtype == 12 ? (int64_t)(uint16_t)u
                            : dtype == 13 ? (int64_t)(uint32_t)u
                            : dtype == 14 ? (int64_t)u
                                          : (u > INT64_MAX ? INT64_MAX : (int64_t)u);
                if (v > INT32_MAX || v < INT32_MIN) {
                    bwh_fail("%s: value %zu = %lld is beyond 32 bits", dat, di, (long long)v);
                    goto out;
                }
                m->ints[di] = (int32_t)v;
            }
    m->count = total;
    m->bands = (uint32_t)nb;
    m->n_in = (uint32_t)npix;
    m->shape = BW_SHAPE_SPECTRA;
    bwh_meta_t *meta = &m->meta;
    meta->sample_type = dtype == 1 ? BWH_ST_U8 : dtype == 2 ? BWH_ST_I16 : dtype == 4 ? BWH_ST_F32
                        : dtype == 5 ? BWH_ST_F64 : dtype == 12 ? BWH_ST_U16 : BWH_ST_I32;
    meta->present |= BWH_M_SAMPLE_TYPE;
    const char *v;
    if ((v = hdr_get(&h, "wavelength"))) {
        const char *u = hdr_get(&h, "wavelength units");
        int wu = u ? bwh_wl_unit_from_name(u) : BWH_WL_NM;
        if (list_numbers(hdr, "wavelength", v, nb, &meta->wavelengths))
            goto out;
        meta->wl_unit = wu < 0 ? BWH_WL_NM : wu;
        if (wu < 0 && bwh_meta_add_field(meta, "wavelength units", u))
            goto out;
    }
    if ((v = hdr_get(&h, "fwhm")) && list_numbers(hdr, "fwhm", v, nb, &meta->fwhm))
        goto out;
    /* a library's one ENVI band is not its channels: its name stays a field */
    if (!library && (v = hdr_get(&h, "band names")) &&
        list_strings(hdr, "band names", v, nb, &meta->band_names))
        goto out;
    if ((v = hdr_get(&h, "spectra names")) &&
        list_strings(hdr, "spectra names", v, npix, &meta->spectrum_names))
        goto out;
    if ((v = hdr_get(&h, "sensor type")) && strcasecmp(v, "Unknown") && *v &&
        bwh_meta_set_string(&meta->instrument, v))
        goto out;
    if ((v = hdr_get(&h, "acquisition time"))) {
        int tz;
        if (bwh_time_parse(v, &meta->time, &tz) != 0) {
            bwh_fail("%s: 'acquisition time': %s", hdr, bwh_last_error());
            goto out;
        }
        meta->time_tz = tz;
        meta->present |= BWH_M_TIME;
    }
    long shape;
    if (read_own(hdr, &h, m, &shape))
        goto out;
    for (size_t i = 0; i < h.n; i++)
        if ((!consumed(h.key[i]) || (library && !strcasecmp(h.key[i], "band names"))) &&
            bwh_meta_add_field(meta, h.key[i], h.val[i]))
            goto out;
    if (shape > BW_SHAPE_SPECTRA) {
        /* brdfwave's image: lines incoming, samples outgoing */
        if ((size_t)samples != bwh_grid_count(m->level_out) ||
            (shape == BW_SHAPE_BRDF_FULL && (size_t)lines != bwh_grid_count(m->level_in)) ||
            (shape == BW_SHAPE_REFLECTANCE && lines != 1) || library) {
            bwh_fail("%s: the image's %ld lines and %ld samples do not fit 'brdfwave shape' and "
                     "its levels",
                     hdr, lines, samples);
            goto out;
        }
        m->shape = (int)shape;
        m->n_in = (uint32_t)lines;
    }
    if ((v = hdr_get(&h, "data ignore value"))) {
        char *e;
        double ig = strtod(v, &e);
        if (e == v || *bwh_trim(e)) {
            bwh_fail("%s: 'data ignore value = %s' is not a number", hdr, v);
            goto out;
        }
        if (m->ints && ig == nearbyint(ig) && fabs(ig) <= INT32_MAX) {
            /* integers: the missing ones are noted, their value kept */
            for (size_t i = 0; i < m->count; i++)
                if (m->ints[i] == (int32_t)ig && bwh_meta_add_missing(meta, i))
                    goto out;
            meta->missing_value = ig;
        } else if (bwh_measure_mark_missing(m, ig) != 0) {
            goto out;
        }
        if (!(meta->present & BWH_M_MISSING)) {
            /* none there: the key is kept as it was */
            if (bwh_meta_add_field(meta, "data ignore value", v))
                goto out;
        }
    }
    rc = 0;
out:
    free(raw);
    hdr_free(&h);
    if (rc)
        bwh_measure_free(m);
    return rc;
}

/* ---- writing ------------------------------------------------------------ */

typedef struct {
    char *b;
    size_t n, cap;
    int oom;
} tbuf_t;

static void tput(tbuf_t *t, const char *s)
{
    size_t n = strlen(s);
    if (t->oom)
        return;
    if (t->n + n + 1 > t->cap) {
        size_t c = t->cap ? t->cap : 4096;
        while (c < t->n + n + 1)
            c *= 2;
        char *nb = realloc(t->b, c);
        if (!nb) {
            t->oom = 1;
            return;
        }
        t->b = nb;
        t->cap = c;
    }
    memcpy(t->b + t->n, s, n + 1);
    t->n += n;
}

static void tnum(tbuf_t *t, double v)
{
    char b[40];
    bwh_json_number(v, b, sizeof b);
    tput(t, b);
}

static void tnumbers(tbuf_t *t, const char *key, const bwh_numbers_t *n)
{
    tput(t, key);
    tput(t, " = {");
    for (size_t i = 0; i < n->n; i++) {
        tput(t, i ? ", " : "");
        tnum(t, n->v[i]);
    }
    tput(t, "}\n");
}

/* a list item ENVI reads back as it is: no comma, brace or line end, no
 * blanks at either end */
static int plain_item(const char *s)
{
    size_t n = strlen(s);
    return !strpbrk(s, ",{}\n\r") && (!n || (!isspace((unsigned char)s[0]) &&
                                             !isspace((unsigned char)s[n - 1])));
}

static int tstrings(tbuf_t *t, const char *key, const bwh_strings_t *s)
{
    for (size_t i = 0; i < s->n; i++)
        if (!plain_item(s->s[i]))
            return bwh_fail("ENVI: %s item %zu ('%s') holds a comma, a brace or a line end, "
                            "which an ENVI list cannot",
                            key, i, s->s[i]);
    tput(t, key);
    tput(t, " = {");
    for (size_t i = 0; i < s->n; i++) {
        tput(t, i ? ", " : "");
        tput(t, s->s[i]);
    }
    tput(t, "}\n");
    return 0;
}

static void json_string(tbuf_t *t, const char *s)
{
    tput(t, "\"");
    for (; *s; s++) {
        char e[8] = {0};
        if (*s == '"' || *s == '\\')
            snprintf(e, sizeof e, "\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            snprintf(e, sizeof e, "\\u%04x", (unsigned char)*s);
        else
            e[0] = *s;
        tput(t, e);
    }
    tput(t, "\"");
}

int bwh_envi_write(const char *path, const bwh_decoded_t *d, int type)
{
    if (!strcmp(path, "-"))
        return bwh_fail("ENVI output needs a file name (a header goes beside the data)");
    const bw_dims_t *g = &d->dims;
    const bwh_meta_t *m = d->meta;
    bwh_meta_t none;
    bwh_meta_init(&none);
    if (!m)
        m = &none;
    /* names: PATH.hdr beside PATH; PATH.hdr given: its data beside it */
    char hdr[4096], dat[4096];
    size_t pl = strlen(path);
    int spectra = g->shape == BW_SHAPE_SPECTRA;
    if (pl >= 4 && !strcasecmp(path + pl - 4, ".hdr")) {
        snprintf(hdr, sizeof hdr, "%s", path);
        snprintf(dat, sizeof dat, "%.*s%s", (int)(pl - 4), path, spectra ? ".sli" : ".img");
    } else {
        snprintf(dat, sizeof dat, "%s", path);
        const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
        if (dot && (!slash || dot > slash))
            snprintf(hdr, sizeof hdr, "%.*s.hdr", (int)(dot - path), path);
        else
            snprintf(hdr, sizeof hdr, "%s.hdr", path);
    }
    static const int dtype[BWH_ST_COUNT] = {4, 1, 2, 12, 3, 4, 5};
    tbuf_t t = {0};
    char b[256];
    tput(&t, "ENVI\n");
    size_t n_in = spectra ? g->n_in : g->shape == BW_SHAPE_REFLECTANCE ? 1 : g->n_in;
    snprintf(b, sizeof b, "samples = %u\nlines = %zu\nbands = %u\nheader offset = 0\n",
             spectra ? g->bands : g->n_out, n_in, spectra ? 1u : g->bands);
    tput(&t, b);
    snprintf(b, sizeof b, "file type = %s\ndata type = %d\ninterleave = %s\nbyte order = 0\n",
             spectra ? "ENVI Spectral Library" : "ENVI Standard",
             dtype[type >= 0 && type < BWH_ST_COUNT ? type : 0], spectra ? "bsq" : "bip");
    tput(&t, b);
    if (!spectra) {
        static const char *const shapes[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
        snprintf(b, sizeof b, "brdfwave shape = %s\nbrdfwave level = %u\n", shapes[g->shape],
                 g->level_out);
        tput(&t, b);
        if (g->shape == BW_SHAPE_BRDF_FULL) {
            snprintf(b, sizeof b, "brdfwave level in = %u\n", g->level_in);
            tput(&t, b);
        }
    }
    if (m->wavelengths.n) {
        static const char *const units[] = {"Nanometers", "Micrometers", "Wavenumber"};
        snprintf(b, sizeof b, "wavelength units = %s\n", units[m->wl_unit]);
        tput(&t, b);
        tnumbers(&t, "wavelength", &m->wavelengths);
    }
    if (m->fwhm.n)
        tnumbers(&t, "fwhm", &m->fwhm);
    int rc = 0;
    if (m->band_names.n)
        rc = tstrings(&t, "band names", &m->band_names);
    if (!rc && m->spectrum_names.n)
        rc = tstrings(&t, "spectra names", &m->spectrum_names);
    if (!rc && m->instrument) {
        if (strpbrk(m->instrument, "\n\r{"))
            rc = bwh_fail("ENVI: the instrument name holds a line end or a brace");
        tput(&t, "sensor type = ");
        tput(&t, m->instrument);
        tput(&t, "\n");
    }
    if (rc) {
        free(t.b);
        return -1;
    }
    if (m->present & BWH_M_TIME) {
        bwh_time_format(m->time, m->time_tz, b, sizeof b);
        tput(&t, "acquisition time = ");
        tput(&t, b);
        tput(&t, "\n");
    }
    if (m->present & BWH_M_MISSING) {
        tput(&t, "data ignore value = ");
        tnum(&t, m->missing_value);
        tput(&t, "\n");
    }
    if (m->present & BWH_M_QUANTITY) {
        tput(&t, "brdfwave quantity = ");
        tput(&t, bwh_quantity_name(m->quantity));
        tput(&t, "\n");
    }
    const char *own[] = {m->unit, m->serial};
    static const char *const own_keys[] = {"brdfwave unit = ", "brdfwave serial = "};
    for (int i = 0; i < 2; i++)
        if (own[i]) {
            if (strpbrk(own[i], "\n\r") || *own[i] == '{') {
                free(t.b);
                return bwh_fail("ENVI: %s'%s' cannot be a header value", own_keys[i], own[i]);
            }
            tput(&t, own_keys[i]);
            tput(&t, own[i]);
            tput(&t, "\n");
        }
    if (m->present & BWH_M_SAMPLE_TYPE) {
        tput(&t, "brdfwave sample type = ");
        tput(&t, bwh_sample_type_name(m->sample_type));
        tput(&t, "\n");
    }
    if (m->present & BWH_M_LOCATION) {
        bwh_numbers_t l = {(m->present & BWH_M_ALTITUDE) ? 3u : 2u,
                           (double[3]){m->lat, m->lon, m->alt}};
        tnumbers(&t, "brdfwave location", &l);
    }
    if (m->incidence.n) {
        tput(&t, "brdfwave incidence unit = ");
        tput(&t, bwh_angle_unit_name(m->inc_unit));
        tput(&t, "\n");
        tnumbers(&t, "brdfwave incidence", &m->incidence);
    }
    if (m->spectrum_times.n) {
        tput(&t, "brdfwave spectrum times = {");
        for (size_t i = 0; i < m->spectrum_times.n; i++) {
            tput(&t, i ? ", " : "");
            if (isfinite(m->spectrum_times.v[i]))
                bwh_time_format(m->spectrum_times.v[i], m->spectrum_tz, b, sizeof b);
            else
                snprintf(b, sizeof b, "null");
            tput(&t, b);
        }
        tput(&t, "}\n");
    }
    if (m->spectrum_lat.n) {
        tnumbers(&t, "brdfwave spectrum latitudes", &m->spectrum_lat);
        tnumbers(&t, "brdfwave spectrum longitudes", &m->spectrum_lon);
    }
    if (m->spectrum_alt.n)
        tnumbers(&t, "brdfwave spectrum altitudes", &m->spectrum_alt);
    for (size_t i = 0; i < m->n_fields; i++) {
        const char *k = m->keys[i], *v = m->values[i];
        size_t vl = strlen(v);
        int key_ok = !strpbrk(k, "=\n\r") && !isspace((unsigned char)k[0]) &&
                     !isspace((unsigned char)k[strlen(k) - 1]) && !consumed(k) &&
                     strncasecmp(k, "brdfwave", 8);
        /* a value ENVI reads back as it is: one line not starting with a
         * brace, or one brace group (which may span lines) */
        int val_ok = (vl && !isspace((unsigned char)v[0]) && !isspace((unsigned char)v[vl - 1]) &&
                      ((v[0] != '{' && !strpbrk(v, "\n\r")) ||
                       (v[0] == '{' && strchr(v, '}') == v + vl - 1 && !strchr(v + 1, '{') &&
                        !strchr(v, '\r'))));
        if (key_ok && val_ok) {
            tput(&t, k);
            tput(&t, " = ");
            tput(&t, v);
            tput(&t, "\n");
        } else {
            tput(&t, "brdfwave json field = [");
            json_string(&t, k);
            tput(&t, ", ");
            json_string(&t, v);
            tput(&t, "]\n");
        }
    }
    if (t.oom) {
        free(t.b);
        return bwh_fail("out of memory");
    }
    size_t len;
    uint8_t *data = bwh_output_samples(d, type, &len);
    if (!data) {
        free(t.b);
        return -1;
    }
    rc = bwh_write_file(dat, data, len);
    free(data);
    if (!rc)
        rc = bwh_write_file(hdr, t.b, t.n);
    free(t.b);
    return rc;
}
