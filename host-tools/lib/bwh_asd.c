/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * ASD FieldSpec / Indico binary files, every version: the old format
 * (magic "ASD": a 484-byte header and the spectrum), and "as6", "as7" and
 * "as8" (then a reference header and spectrum, and optional blocks: the
 * classifier, dependent variables, calibration buffers, an audit log and a
 * signature), as instruments/FORMATS.md describes them, little-endian and
 * packed. The blocks are walked to the end: one cut short or running past
 * the end is refused; bytes after the last block (a trailer) are not.
 *
 * The column read: the reflectance (default) where the file is a
 * reflectance file (the old format's values, else spectrum / reference),
 * otherwise the spectrum's counts; the target (the spectrum as stored) or
 * the reference. Kept: wavelengths (channel 1 and step), instrument model
 * and serial, the save time, the GPS position when there is one, the
 * integration time, the splice wavelengths, the data type and format, the
 * calibration buffers' names.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_input.h"
#include "bwh_text.h"

#define ASD_HEADER 484u

static double f32_at(const uint8_t *p)
{
    uint32_t u = bw_get_u32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static double f64_at(const uint8_t *p)
{
    uint64_t u = bw_get_u32(p) | (uint64_t)bw_get_u32(p + 4) << 32;
    double d;
    memcpy(&d, &u, 8);
    return d;
}

/* a cursor over the blocks after the header */
typedef struct {
    const uint8_t *b;
    size_t len, pos;
    const char *path, *block;
} cur_t;

static int need(cur_t *c, size_t n)
{
    if (n > c->len - c->pos)
        return bwh_fail("%s: truncated or damaged: the %s block needs %zu bytes at offset %zu, "
                        "the file ends %zu bytes on",
                        c->path, c->block, n, c->pos, c->len - c->pos);
    return 0;
}

static int skip(cur_t *c, size_t n)
{
    if (need(c, n))
        return -1;
    c->pos += n;
    return 0;
}

static int get16(cur_t *c, int *v)
{
    if (need(c, 2))
        return -1;
    *v = (int16_t)bw_get_u16(c->b + c->pos);
    c->pos += 2;
    return 0;
}

/* a string: int16 byte length, then the bytes */
static int string(cur_t *c, char *out, size_t cap)
{
    int n;
    if (get16(c, &n))
        return -1;
    if (n < 0)
        return bwh_fail("%s: damaged: a negative string length in the %s block", c->path,
                        c->block);
    if (need(c, (size_t)n))
        return -1;
    if (out)
        snprintf(out, cap, "%.*s", n, (const char *)c->b + c->pos);
    c->pos += (size_t)n;
    return 0;
}

/* a SAFEARRAY descriptor: int16 dims, then (1 dim) int32 count and int32
 * lower bound; the element count */
static int safearray(cur_t *c, long *count)
{
    int dims;
    if (get16(c, &dims))
        return -1;
    if (dims == 0) {
        *count = 0;
        return 0;
    }
    if (dims != 1 || need(c, 8))
        return dims != 1 ? bwh_fail("%s: damaged: an array of %d dimensions in the %s block",
                                    c->path, dims, c->block)
                         : -1;
    int32_t n = (int32_t)bw_get_u32(c->b + c->pos);
    c->pos += 8;
    if (n < 0 || n > 1 << 20)
        return bwh_fail("%s: damaged: an array of %d items in the %s block", c->path, (int)n,
                        c->block);
    *count = n;
    return 0;
}

static int at_end(const cur_t *c) { return c->pos == c->len; }

/* the optional blocks after the reference; the calibration names in cal */
static int walk(cur_t *c, int version, size_t spec_bytes, char *cal, size_t calcap)
{
    if (at_end(c))
        return 0;
    c->block = "classifier";
    long n;
    int k;
    if (skip(c, 2))
        return -1;
    for (int i = 0; i < 20; i++)
        if (string(c, NULL, 0))
            return -1;
    if (get16(c, &k) || safearray(c, &n))
        return -1;
    for (long i = 0; i < n; i++)
        if (string(c, NULL, 0) || string(c, NULL, 0) || skip(c, 9 * 8 + 4 + 2 * 8))
            return -1;
    if (version < 7 || at_end(c))
        return 0;
    c->block = "dependent variables";
    if (skip(c, 2) || get16(c, &k) || safearray(c, &n))
        return -1;
    for (long i = 0; i < n; i++)
        if (string(c, NULL, 0))
            return -1;
    if (safearray(c, &n) || skip(c, (size_t)n * 4))
        return -1;
    if (at_end(c))
        return 0;
    c->block = "calibration header";
    if (need(c, 1))
        return -1;
    unsigned nc = c->b[c->pos++];
    if (need(c, nc * 29u))
        return -1;
    static const char *const types[] = {"ABS", "BSE", "LMP", "FO"};
    for (unsigned i = 0; i < nc; i++) {
        const uint8_t *p = c->b + c->pos + i * 29u;
        size_t l = strlen(cal);
        snprintf(cal + l, calcap - l, "%s%s %.20s", i ? ", " : "",
                 p[0] < 4 ? types[p[0]] : "?", (const char *)p + 1);
    }
    c->pos += nc * 29u;
    c->block = "calibration data";
    if (skip(c, nc * spec_bytes))
        return -1;
    if (version < 8 || at_end(c))
        return 0;
    c->block = "audit log";
    if (skip(c, 4) || safearray(c, &n))
        return -1;
    for (long i = 0; i < n; i++)
        if (string(c, NULL, 0))
            return -1;
    if (at_end(c))
        return 0;
    c->block = "signature";
    if (skip(c, 1 + 8))
        return -1;
    for (int i = 0; i < 7; i++)
        if (string(c, NULL, 0))
            return -1;
    return skip(c, 128);
}

int bwh_read_asd(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    uint8_t *b;
    size_t len;
    if (bwh_read_file(path, &b, &len) != 0)
        return -1;
    int rc = -1, version = 0;
    if (len >= 3)
        version = !memcmp(b, "ASD", 3) ? 1 : !memcmp(b, "as6", 3) ? 6 : !memcmp(b, "as7", 3) ? 7
                  : !memcmp(b, "as8", 3) ? 8 : 0;
    if (!version) {
        bwh_fail("%s: not an ASD file (magic %s)", path,
                 len >= 3 && !memcmp(b, "as", 2) ? "of an unknown version" : "missing");
        goto out;
    }
    if (len < ASD_HEADER) {
        bwh_fail("%s: truncated: %zu bytes, the header alone is %u", path, len, ASD_HEADER);
        goto out;
    }
    unsigned dtype = b[186], fmt = b[199], channels = bw_get_u16(b + 204);
    if (fmt > 2) {
        bwh_fail("%s: data format %u is not float32, int32 or float64", path, fmt);
        goto out;
    }
    if (!channels || channels > BW_MAX_BANDS) {
        bwh_fail("%s: damaged: %u channels", path, channels);
        goto out;
    }
    size_t es = fmt == 2 ? 8 : 4, spec = channels * es;
    cur_t c = {b, len, ASD_HEADER, path, "spectrum"};
    if (skip(&c, spec))
        goto out;
    size_t ref_at = 0;
    double ref_flag = 0;
    if (version > 1) {
        c.block = "reference header";
        int flag;
        if (get16(&c, &flag) || skip(&c, 16) || string(&c, NULL, 0))
            goto out;
        ref_flag = flag != 0;
        ref_at = c.pos;
        c.block = "reference";
        if (skip(&c, spec))
            goto out;
    }
    char cal[512] = "";
    if (version > 1 && walk(&c, version, spec, cal, sizeof cal) != 0)
        goto out;
    /* the values */
    int refl_file = dtype == 1;
    int ratio = o->column == BWH_COL_REFLECTANCE && refl_file && ref_at;
    size_t from = o->column == BWH_COL_REFERENCE ? ref_at : ASD_HEADER;
    if (o->column == BWH_COL_REFERENCE && !ref_at) {
        bwh_fail("%s: the old ASD format holds no reference", path);
        goto out;
    }
    m->values = malloc(channels * sizeof *m->values);
    if (!m->values) {
        bwh_fail("out of memory");
        goto out;
    }
    for (unsigned i = 0; i < channels; i++) {
        const uint8_t *p = b + from + i * es;
        double v = fmt == 2 ? f64_at(p) : fmt == 0 ? f32_at(p) : (double)(int32_t)bw_get_u32(p);
        if (ratio) {
            const uint8_t *r = b + ref_at + i * es;
            double rv = fmt == 2 ? f64_at(r) : fmt == 0 ? f32_at(r) : (double)(int32_t)bw_get_u32(r);
            v = rv != 0 ? v / rv : 0.0;
        }
        if (!isfinite(v) || fabs(v) > 3.4e38) {
            bwh_fail("%s: damaged: channel %u is %g", path, i, v);
            goto out;
        }
        m->values[i] = (float)v;
    }
    m->count = m->bands = channels;
    m->shape = BW_SHAPE_SPECTRA;
    m->n_in = 1;
    bwh_meta_t *meta = &m->meta;
    meta->quantity = (ratio || (version == 1 && refl_file && o->column != BWH_COL_REFERENCE))
                         ? BWH_Q_REFLECTANCE
                         : BWH_Q_COUNTS;
    meta->sample_type = fmt == 2 ? BWH_ST_F64 : fmt == 0 ? BWH_ST_F32 : BWH_ST_I32;
    meta->present |= BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE;
    /* wavelengths: channel 1 and the step */
    double ch1 = f32_at(b + 191), step = f32_at(b + 195);
    double *wl = malloc(channels * sizeof *wl);
    if (!wl) {
        bwh_fail("out of memory");
        goto out;
    }
    for (unsigned i = 0; i < channels; i++)
        wl[i] = ch1 + step * i;
    meta->wl_unit = BWH_WL_NM;
    int bad = bwh_meta_set_numbers(&meta->wavelengths, wl, channels);
    free(wl);
    static const char *const models[] = {"unknown", "PSII", "LSVNIR", "FSVNIR", "FieldSpec FR",
                                         "FSNIR", "CHEM", "FieldSpec FR unattended"};
    static const char *const dtypes[] = {"raw", "reflectance", "radiance", "no units",
                                         "irradiance", "QI", "transmittance", "unknown",
                                         "absorbance"};
    char s[160];
    unsigned model = b[431];
    snprintf(s, sizeof s, "ASD %s", model < 8 ? models[model] : "unknown");
    bad = bad || bwh_meta_set_string(&meta->instrument, s);
    snprintf(s, sizeof s, "%u", bw_get_u16(b + 400));
    bad = bad || bwh_meta_set_string(&meta->serial, s);
    const char *name = bwh_basename(path);
    bad = bad || bwh_meta_set_strings(&meta->spectrum_names, &name, 1);
    /* the save time: struct tm of int16, local */
    int tmv[6];
    for (int i = 0; i < 6; i++)
        tmv[i] = (int16_t)bw_get_u16(b + 160 + 2 * i);
    if (tmv[4] >= 0 && tmv[4] < 12 && tmv[3] >= 1 && tmv[3] <= 31 && tmv[2] >= 0 && tmv[2] < 24) {
        double t = bwh_time_of(tmv[5] + 1900, tmv[4] + 1, tmv[3], tmv[2], tmv[1], tmv[0]);
        bad = bad || bwh_meta_set_numbers(&meta->spectrum_times, &t, 1);
    }
    double lat = f64_at(b + 350), lon = f64_at(b + 358), alt = f64_at(b + 366);
    if ((lat != 0 || lon != 0) && isfinite(lat) && isfinite(lon))
        bad = bad || bwh_meta_set_numbers(&meta->spectrum_lat, &lat, 1) ||
              bwh_meta_set_numbers(&meta->spectrum_lon, &lon, 1) ||
              (isfinite(alt) && bwh_meta_set_numbers(&meta->spectrum_alt, &alt, 1));
    snprintf(s, sizeof s, "%s", dtype < 9 ? dtypes[dtype] : "?");
    bad = bad || bwh_meta_add_field(meta, "asd data type", s);
    snprintf(s, sizeof s, "%u", bw_get_u32(b + 390));
    bad = bad || bwh_meta_add_field(meta, "integration time ms", s);
    snprintf(s, sizeof s, "%u.%u", b[178] >> 4, b[178] & 15);
    bad = bad || bwh_meta_add_field(meta, "program version", s);
    if (version > 1) {
        snprintf(s, sizeof s, "%g, %g", f32_at(b + 444), f32_at(b + 448));
        bad = bad || bwh_meta_add_field(meta, "splice wavelengths nm", s);
        bad = bad || bwh_meta_add_field(meta, "reference taken", ref_flag ? "yes" : "no");
    }
    char comment[158];
    snprintf(comment, sizeof comment, "%.157s", (const char *)b + 3);
    for (char *q = comment; *q; q++)
        if ((unsigned char)*q < 0x20 || (unsigned char)*q > 0x7E)
            *q = '?';
    if (*bwh_trim(comment))
        bad = bad || bwh_meta_add_field(meta, "comments", bwh_trim(comment));
    if (*cal)
        bad = bad || bwh_meta_add_field(meta, "calibration", cal);
    if (c.pos < len) {
        snprintf(s, sizeof s, "%zu", len - c.pos);
        bad = bad || bwh_meta_add_field(meta, "trailing bytes", s);
    }
    if (bad)
        goto out;
    rc = 0;
out:
    free(b);
    if (rc)
        bwh_measure_free(m);
    return rc;
}
