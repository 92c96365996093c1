/* SPDX-License-Identifier: BSD-2-Clause */
/* Measurement files in: format names, detection, sets of files (bwh_input.h). */
#define _POSIX_C_SOURCE 200809L
#include "bwh_input.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_raw.h"
#include "bwh_text.h"
#include "geodesic.h"

static const char *const in_names[BWH_IN_COUNT] = {"auto", "f32",  "u16",  "i32",  "sed",
                                                    "sig",  "asd",  "usgs", "envi", "csv",
                                                    "npy",  "bsdf", "gonio"};

const char *bwh_input_format_name(int f)
{
    return f >= 0 && f < BWH_IN_COUNT ? in_names[f] : "?";
}

int bwh_input_format_from_name(const char *name)
{
    for (int f = 0; name && f < BWH_IN_COUNT; f++)
        if (!strcmp(name, in_names[f]))
            return f;
    return -1;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && !strcasecmp(s + n - k, suffix);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* the ENVI header of a data file: PATH.hdr, or PATH with its extension
 * replaced by .hdr */
int bwh_envi_header_of(const char *path, char *hdr, size_t cap);
int bwh_envi_header_of(const char *path, char *hdr, size_t cap)
{
    if (ends_with(path, ".hdr")) {
        snprintf(hdr, cap, "%s", path);
        return exists(hdr) ? 0 : -1;
    }
    snprintf(hdr, cap, "%s.hdr", path);
    if (exists(hdr))
        return 0;
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (dot && (!slash || dot > slash)) {
        snprintf(hdr, cap, "%.*s.hdr", (int)(dot - path), path);
        if (exists(hdr))
            return 0;
    }
    return -1;
}

int bwh_input_detect(const char *path)
{
    char head[4096];
    size_t n = 0;
    if (strcmp(path, "-")) {
        FILE *f = fopen(path, "rb");
        if (!f)
            return bwh_fail("%s: cannot open: no such file or not readable", path);
        n = fread(head, 1, sizeof head - 1, f);
        fclose(f);
    }
    head[n] = 0;
    char hdr[4096];
    if (n >= 3 && (!memcmp(head, "ASD", 3) || !memcmp(head, "as6", 3) || !memcmp(head, "as7", 3) ||
                   !memcmp(head, "as8", 3)))
        return BWH_IN_ASD;
    if (n >= 6 && !memcmp(head, "\x93NUMPY", 6))
        return BWH_IN_NPY;
    if (n >= 12 && !memcmp(head, "tensor_file", 12))
        return BWH_IN_BSDF;
    if (!strncmp(head, "/*** Spectra Vista", 18))
        return BWH_IN_SIG;
    if (!strncmp(head, "ENVI", 4) && (head[4] == '\n' || head[4] == '\r'))
        return BWH_IN_ENVI;
    if (!strncmp(head, "# 'counter', 'incidence', 'emission'", 36) ||
        !strncmp(head, "Database of origin,", 19))
        return BWH_IN_GONIO;
    if (strstr(head, "\nChannels:") && (strstr(head, "\nData:") || n == sizeof head - 1) &&
        (strstr(head, "Instrument:") || strstr(head, "Measurement:")))
        return BWH_IN_SED;
    const char *nl = strchr(head, '\n');
    if (nl && strstr(head, "Record=") && strstr(head, "Record=") < nl)
        return BWH_IN_USGS;
    static const struct {
        const char *ext;
        int f;
    } by_name[] = {{".sed", BWH_IN_SED}, {".sig", BWH_IN_SIG},   {".asd", BWH_IN_ASD},
                   {".npy", BWH_IN_NPY}, {".bsdf", BWH_IN_BSDF}, {".hdr", BWH_IN_ENVI},
                   {".csv", BWH_IN_CSV}, {".u16", BWH_IN_U16},   {".i32", BWH_IN_I32},
                   {".f32", BWH_IN_F32}};
    for (size_t i = 0; i < sizeof by_name / sizeof *by_name; i++)
        if (ends_with(path, by_name[i].ext))
            return by_name[i].f;
    /* a data file of any other name with its ENVI header beside it (a
     * name of the formats above keeps its format: a decoded OUT.csv beside
     * the OUT.hdr of an ENVI decode is still CSV) */
    if (bwh_envi_header_of(path, hdr, sizeof hdr) == 0)
        return BWH_IN_ENVI;
    return BWH_IN_F32;
}

void bwh_measure_init(bwh_measure_t *m)
{
    memset(m, 0, sizeof *m);
    m->scale = 1.0;
    m->shape = -1;
    bwh_meta_init(&m->meta);
}

void bwh_measure_free(bwh_measure_t *m)
{
    free(m->values);
    free(m->ints);
    bwh_meta_free(&m->meta);
    bwh_measure_init(m);
}

float *bwh_measure_floats(const bwh_measure_t *m)
{
    float *v = malloc((m->count ? m->count : 1) * sizeof *v);
    if (!v) {
        bwh_fail("out of memory");
        return NULL;
    }
    for (size_t i = 0; i < m->count; i++)
        v[i] = m->values ? m->values[i]
                         : (m->scale == 1.0 ? (float)m->ints[i] : (float)(m->ints[i] * m->scale));
    return v;
}

/* the geodesic level of n directions, -1 if none */
static int level_of(size_t n)
{
    for (unsigned l = 0; l <= BW_MAX_LEVEL; l++)
        if (bwh_grid_count(l) == n)
            return (int)l;
    return -1;
}

/* The shape of raw samples from their sidecar: the layout it names, its
 * bands (one wavelength, bandwidth or name each) and incidence angles;
 * what they do not settle stays for the shape options. */
static void raw_shape(bwh_measure_t *m, int layout)
{
    const bwh_meta_t *x = &m->meta;
    size_t bands = x->wavelengths.n ? x->wavelengths.n : x->band_names.n ? x->band_names.n
                                                                         : x->fwhm.n;
    if (!bands || m->count % bands)
        return;
    m->bands = (uint32_t)bands;
    size_t rows = m->count / bands;
    int l;
    if (layout == BW_SHAPE_SPECTRA) {
        m->shape = layout;
        m->n_in = (uint32_t)rows;
    } else if (layout == BW_SHAPE_REFLECTANCE && (l = level_of(rows)) >= 0) {
        m->shape = layout;
        m->level_out = (unsigned)l;
        m->n_in = 1;
    } else if (layout == BW_SHAPE_BRDF_ISO && x->incidence.n && rows % x->incidence.n == 0 &&
               (l = level_of(rows / x->incidence.n)) >= 0) {
        m->shape = layout;
        m->level_out = (unsigned)l;
        m->n_in = (uint32_t)x->incidence.n;
    }
}

int bwh_read_raw(const char *path, int f, bwh_measure_t *m)
{
    bwh_measure_init(m);
    int layout = -1;
    if (bwh_sidecar_read(path, &m->meta, &layout) != 0) {
        bwh_measure_free(m);
        return -1;
    }
    /* the type: the format asked for, or for f32 (the default) the
     * sidecar's, as 'decode --output-format raw' wrote it */
    int t = f == BWH_IN_U16 ? BWH_ST_U16 : f == BWH_IN_I32 ? BWH_ST_I32 : BWH_ST_F32;
    if (t == BWH_ST_F32 && (m->meta.present & BWH_M_SAMPLE_TYPE))
        t = m->meta.sample_type;
    uint8_t *b;
    size_t len, es = bwh_sample_type_size(t);
    if (bwh_read_file(path, &b, &len) != 0) {
        bwh_measure_free(m);
        return -1;
    }
    if (!es || len % es || !len) {
        free(b);
        bwh_measure_free(m);
        return bwh_fail("%s: %zu bytes is not a whole number of %s samples", path, len,
                        bwh_sample_type_name(t));
    }
    size_t n = len / es;
    int integer = t != BWH_ST_F32 && t != BWH_ST_F64;
    if (integer)
        m->ints = malloc(n * sizeof *m->ints);
    else
        m->values = malloc(n * sizeof *m->values);
    if (!m->ints && !m->values) {
        free(b);
        bwh_measure_free(m);
        return bwh_fail("%s: out of memory", path);
    }
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = b + i * es;
        uint32_t u = 0;
        uint64_t w = 0;
        for (size_t k = 0; k < es && k < 4; k++)
            u |= (uint32_t)p[k] << (8 * k);
        switch (t) {
        case BWH_ST_U8:
            m->ints[i] = p[0];
            break;
        case BWH_ST_I16:
            m->ints[i] = (int16_t)u;
            break;
        case BWH_ST_U16:
            m->ints[i] = (int32_t)(u & 0xFFFFu);
            break;
        case BWH_ST_I32:
            m->ints[i] = (int32_t)u;
            break;
        case BWH_ST_F64: {
            double d;
            for (size_t k = 0; k < 8; k++)
                w |= (uint64_t)p[k] << (8 * k);
            memcpy(&d, &w, 8);
            m->values[i] = (float)d;
            break;
        }
        default: {
            float v;
            memcpy(&v, &u, 4);
            m->values[i] = v;
        }
        }
    }
    free(b);
    m->count = n;
    raw_shape(m, layout);
    /* f32 is what a writer gives without a sample type: raw float input
     * without a sidecar keeps a payload without metadata */
    if (!(m->meta.present & BWH_M_SAMPLE_TYPE) && t != BWH_ST_F32) {
        m->meta.sample_type = t;
        m->meta.present |= BWH_M_SAMPLE_TYPE;
    }
    return 0;
}

int bwh_sidecar_read(const char *path, bwh_meta_t *m, int *layout)
{
    bwh_meta_init(m);
    if (layout)
        *layout = -1;
    if (!strcmp(path, "-"))
        return 0;
    char side[4096];
    if (snprintf(side, sizeof side, "%s.json", path) >= (int)sizeof side || !exists(side))
        return 0;
    uint8_t *b;
    size_t n;
    if (bwh_read_file(side, &b, &n) != 0)
        return -1;
    char *s = realloc(b, n + 1);
    if (!s) {
        free(b);
        return bwh_fail("%s: out of memory", side);
    }
    s[n] = 0;
    int rc = bwh_meta_from_json_layout(s, m, layout);
    free(s);
    if (rc)
        return bwh_fail("%s: %s", side, bwh_last_error());
    return 0;
}

int bwh_measure_mark_missing(bwh_measure_t *m, double ignore)
{
    if (!m->values && !m->ints)
        return 0;
    size_t bands = m->bands ? m->bands : m->count, rows = bands ? m->count / bands : 0;
    float mark = (float)ignore;
    /* integer samples (decimal text read exactly): the marker is the
     * integer whose value it is, if there is one */
    int32_t qmark = 0;
    int int_mark = 0;
    if (m->ints) {
        double q = ignore / m->scale;
        if (!(fabs(q) <= 2147483647.0) || q != nearbyint(q))
            return 0; /* no integer sample has that value */
        qmark = (int32_t)q;
        int_mark = 1;
    }
    int any = 0;
    for (size_t r = 0; r < rows; r++)
        for (size_t k = 0; k < bands; k++) {
            size_t i = r * bands + k;
            int miss = int_mark ? m->ints[i] == qmark
                                : m->values[i] == mark || (isnan(mark) && isnan(m->values[i]));
            if (miss) {
                if (bwh_meta_add_missing(&m->meta, i))
                    return -1;
                any = 1;
            }
        }
    if (!any)
        return 0;
    m->meta.missing_value = (double)mark == ignore || int_mark ? ignore : (double)mark;
    /* fill: the nearest valid sample before, else after, in the spectrum */
    size_t run = 0;
    for (size_t r = 0; r < rows; r++) {
        uint64_t base = (uint64_t)r * bands;
        size_t last = 0;
        int have = 0;
        for (size_t k = 0; k < bands; k++) {
            uint64_t i = base + k;
            while (run < m->meta.n_missing && m->meta.missing[run][0] + m->meta.missing[run][1] <= i)
                run++;
            int miss = run < m->meta.n_missing && i >= m->meta.missing[run][0];
            if (!miss) {
                for (size_t j = have ? k : 0; !have && j < k; j++) {
                    if (int_mark)
                        m->ints[base + j] = m->ints[i];
                    else
                        m->values[base + j] = m->values[i];
                }
                last = (size_t)i;
                have = 1;
            } else if (int_mark) {
                m->ints[i] = have ? m->ints[last] : 0;
            } else {
                m->values[i] = have ? m->values[last] : 0.0f;
            }
        }
    }
    return 0;
}

/* ---- sets of files ------------------------------------------------------ */

static int same_numbers(const bwh_numbers_t *a, const bwh_numbers_t *b)
{
    return a->n == b->n && (!a->n || !memcmp(a->v, b->v, a->n * sizeof *a->v));
}

static int same_string(const char *a, const char *b)
{
    return (!a && !b) || (a && b && !strcmp(a, b));
}

/* m gets b's spectra after its own; metadata checked to agree */
static int join(bwh_measure_t *m, const char *first, bwh_measure_t *b, const char *path)
{
    if (b->shape != BW_SHAPE_SPECTRA || m->shape != BW_SHAPE_SPECTRA)
        return bwh_fail("%s: only sets of spectra are joined (this file holds directional data)",
                        path);
    if (b->bands != m->bands)
        return bwh_fail("%s has %u bands, %s %u", path, b->bands, first, m->bands);
    bwh_meta_t *x = &m->meta, *y = &b->meta;
    if (!same_numbers(&x->wavelengths, &y->wavelengths) || x->wl_unit != y->wl_unit)
        return bwh_fail("%s: its wavelengths differ from those of %s", path, first);
    if (x->quantity != y->quantity || !same_string(bwh_meta_unit(x), bwh_meta_unit(y)))
        return bwh_fail("%s holds %s (%s), %s %s (%s): encode them apart", path,
                        bwh_quantity_name(y->quantity), bwh_meta_unit(y), first,
                        bwh_quantity_name(x->quantity), bwh_meta_unit(x));
    if (!same_string(x->instrument, y->instrument) || !same_string(x->serial, y->serial))
        return bwh_fail("%s comes from instrument %s %s, %s from %s %s: encode them apart", path,
                        y->instrument ? y->instrument : "(none)", y->serial ? y->serial : "",
                        first, x->instrument ? x->instrument : "(none)",
                        x->serial ? x->serial : "");
    if (!same_numbers(&x->fwhm, &y->fwhm))
        bwh_meta_set_numbers(&x->fwhm, NULL, 0);
    if (x->sample_type != y->sample_type)
        x->present &= ~BWH_M_SAMPLE_TYPE;
    if (x->spectrum_tz != y->spectrum_tz && x->spectrum_times.n && y->spectrum_times.n)
        return bwh_fail("%s: its times are in another time zone than those of %s", path, first);
    /* free fields: those every file has with the same value */
    size_t keep = 0;
    for (size_t i = 0; i < x->n_fields; i++) {
        const char *v = bwh_meta_field(y, x->keys[i]);
        if (v && !strcmp(v, x->values[i])) {
            x->keys[keep] = x->keys[i];
            x->values[keep] = x->values[i];
            keep++;
        } else {
            free(x->keys[i]);
            free(x->values[i]);
        }
    }
    x->n_fields = keep;
    if (bwh_meta_append_spectra(x, m->n_in, y, b->n_in) != 0)
        return -1;
    /* samples: integers while both are integers of one scale */
    size_t n = m->count + b->count;
    if (m->ints && b->ints && m->scale == b->scale) {
        int32_t *g = realloc(m->ints, n * sizeof *g);
        if (!g)
            return bwh_fail("out of memory");
        memcpy(g + m->count, b->ints, b->count * sizeof *g);
        m->ints = g;
    } else {
        float *fa = m->values ? m->values : bwh_measure_floats(m);
        float *fb = b->values ? b->values : bwh_measure_floats(b);
        float *g = fa ? realloc(fa, n * sizeof *g) : NULL;
        if (!g) {
            if (fb != b->values)
                free(fb);
            return bwh_fail("out of memory");
        }
        memcpy(g + m->count, fb, b->count * sizeof *g);
        if (fb != b->values)
            free(fb);
        if (m->ints) {
            free(m->ints);
            m->ints = NULL;
        }
        m->values = g;
        if (x->sample_type != BWH_ST_F64)
            x->sample_type = BWH_ST_F32;
    }
    if (y->present & BWH_M_MISSING) {
        if ((x->present & BWH_M_MISSING) && x->missing_value != y->missing_value &&
            !(isnan(x->missing_value) && isnan(y->missing_value)))
            return bwh_fail("%s marks missing samples with another value than %s", path, first);
        x->missing_value = y->missing_value;
        for (size_t i = 0; i < y->n_missing; i++)
            if (bwh_meta_add_missing_run(x, m->count + y->missing[i][0], y->missing[i][1]))
                return -1;
    }
    m->count = n;
    m->n_in += b->n_in;
    return 0;
}

static int read_one(const char *path, int f, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    if (f == BWH_IN_AUTO && (f = bwh_input_detect(path)) < 0)
        return -1;
    switch (f) {
    case BWH_IN_F32:
    case BWH_IN_U16:
    case BWH_IN_I32:
        return bwh_read_raw(path, f, m);
    case BWH_IN_SED:
        return bwh_read_sed(path, o, m);
    case BWH_IN_SIG:
        return bwh_read_sig(path, o, m);
    case BWH_IN_ASD:
        return bwh_read_asd(path, o, m);
    case BWH_IN_USGS:
        return bwh_read_usgs(path, o, m);
    case BWH_IN_ENVI:
        return bwh_read_envi(path, o, m);
    case BWH_IN_CSV:
        return bwh_read_csv(path, o, m);
    case BWH_IN_NPY:
        return bwh_read_npy(path, o, m);
    case BWH_IN_BSDF:
        return bwh_read_bsdf(path, o, m);
    case BWH_IN_GONIO:
        return bwh_read_gonio(path, o, m);
    default:
        bwh_measure_init(m);
        return bwh_fail("%s: unknown input format %d", path, f);
    }
}

int bwh_measure_read(const char *const *paths, int n, int f, const bwh_read_opts_t *o,
                     bwh_measure_t *m)
{
    bwh_read_opts_t def = BWH_READ_OPTS_INIT;
    if (!o)
        o = &def;
    bwh_measure_init(m);
    if (n < 1)
        return bwh_fail("no input file");
    if (read_one(paths[0], f, o, m) != 0)
        return -1;
    for (int k = 1; k < n; k++) {
        bwh_measure_t b;
        if (read_one(paths[k], f, o, &b) != 0) {
            bwh_measure_free(m);
            return -1;
        }
        int rc = join(m, paths[0], &b, paths[k]);
        bwh_measure_free(&b);
        if (rc) {
            bwh_measure_free(m);
            return -1;
        }
    }
    if (o->has_ignore && bwh_measure_mark_missing(m, o->ignore) != 0) {
        bwh_measure_free(m);
        return -1;
    }
    return 0;
}
