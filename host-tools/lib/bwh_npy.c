/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * numpy .npy files (format versions 1.0, 2.0 and 3.0): the magic, the
 * version, the header's length and the header, a Python dict literal with
 * 'descr', 'fortran_order' and 'shape', then the data. Read: float32/64
 * and 8- to 64-bit integers of either byte order, C or Fortran order, of 1
 * to 3 dimensions, the last the bands. Written: version 1.0, C order, the
 * output's type, little-endian.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_input.h"
#include "bwh_output.h"
#include "geodesic.h"

#define NPY_MAX_DIM 3

/* the value of 'key' in the header dict: a pointer just after its colon */
static const char *dict_value(const char *h, const char *key)
{
    char k1[32], k2[32];
    snprintf(k1, sizeof k1, "'%s'", key);
    snprintf(k2, sizeof k2, "\"%s\"", key);
    const char *p = strstr(h, k1);
    if (!p)
        p = strstr(h, k2);
    if (!p)
        return NULL;
    p += strlen(k1);
    while (*p == ' ')
        p++;
    if (*p != ':')
        return NULL;
    p++;
    while (*p == ' ')
        p++;
    return p;
}

/* big-endian (or native-order) element of size es at p as a little-endian
 * one, then as int64 / double */
static uint64_t load(const uint8_t *p, size_t es, int big)
{
    uint64_t u = 0;
    for (size_t i = 0; i < es; i++)
        u |= (uint64_t)p[big ? es - 1 - i : i] << (8 * i);
    return u;
}

int bwh_read_npy(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    (void)o;
    bwh_measure_init(m);
    uint8_t *b;
    size_t len;
    if (bwh_read_file(path, &b, &len) != 0)
        return -1;
    int rc = -1;
    char *h = NULL;
    if (len < 10 || memcmp(b, "\x93NUMPY", 6)) {
        bwh_fail("%s: not a numpy .npy file (no \\x93NUMPY magic)", path);
        goto out;
    }
    if (b[6] < 1 || b[6] > 3) {
        bwh_fail("%s: numpy format version %u.%u, not one of 1.0, 2.0, 3.0", path, b[6], b[7]);
        goto out;
    }
    size_t hl = b[6] == 1 ? bw_get_u16(b + 8) : (len >= 12 ? bw_get_u32(b + 8) : (size_t)-1);
    size_t off = b[6] == 1 ? 10 : 12;
    if (hl > len - off || hl > 1u << 20) {
        bwh_fail("%s: truncated: the header of %zu bytes goes past the end of the file", path, hl);
        goto out;
    }
    h = malloc(hl + 1);
    if (!h) {
        bwh_fail("out of memory");
        goto out;
    }
    memcpy(h, b + off, hl);
    h[hl] = 0;
    off += hl;
    /* 'descr': '<f4' */
    const char *d = dict_value(h, "descr");
    char order = 0, kind = 0;
    int es = 0;
    if (d && (*d == '\'' || *d == '"') && strchr("<>|=", d[1]) && strchr("fiu", d[2]) &&
        isdigit((unsigned char)d[3]) && d[4] == d[0]) {
        order = d[1];
        kind = d[2];
        es = d[3] - '0';
    }
    if (!es || (kind == 'f' && es != 4 && es != 8) || (kind != 'f' && es != 1 && es != 2 && es != 4 && es != 8)) {
        bwh_fail("%s: numpy dtype %.12s is not a float32/64 or 8..64-bit integer array", path,
                 d ? d : "(none)");
        goto out;
    }
    const char *fo = dict_value(h, "fortran_order");
    const char *sh = dict_value(h, "shape");
    if (!fo || !sh || *sh != '(') {
        bwh_fail("%s: the numpy header lacks 'fortran_order' or 'shape'", path);
        goto out;
    }
    int fortran = !strncmp(fo, "True", 4);
    size_t dim[NPY_MAX_DIM + 1], nd = 0, total = 1;
    for (const char *p = sh + 1; *p && *p != ')';) {
        while (*p == ' ' || *p == ',')
            p++;
        if (*p == ')')
            break;
        char *e;
        unsigned long long v = strtoull(p, &e, 10);
        if (e == p || nd == NPY_MAX_DIM + 1) {
            bwh_fail("%s: numpy shape %.40s is not 1 to 3 dimensions", path, sh);
            goto out;
        }
        if (v > BW_MAX_SAMPLES || (v && total > BW_MAX_SAMPLES / v)) {
            bwh_fail("%s: numpy shape %.40s holds more than %u samples", path, sh, BW_MAX_SAMPLES);
            goto out;
        }
        dim[nd++] = (size_t)v;
        total *= (size_t)v;
        p = e;
    }
    if (nd < 1 || nd > NPY_MAX_DIM || !total) {
        bwh_fail("%s: numpy shape %.40s: need 1 to 3 dimensions, none of them 0", path, sh);
        goto out;
    }
    if (len - off != total * (size_t)es) {
        bwh_fail("%s: %s: %zu bytes of data, the shape needs %zu", path,
                 len - off < total * (size_t)es ? "truncated" : "damaged", len - off,
                 total * (size_t)es);
        goto out;
    }
    int big = order == '>';
    int st = kind == 'f' ? (es == 4 ? BWH_ST_F32 : BWH_ST_F64)
             : es == 1    ? (kind == 'u' ? BWH_ST_U8 : BWH_ST_I16)
             : es == 2    ? (kind == 'u' ? BWH_ST_U16 : BWH_ST_I16)
                          : BWH_ST_I32;
    if (kind == 'f')
        m->values = malloc(total * sizeof *m->values);
    else
        m->ints = malloc(total * sizeof *m->ints);
    if (!m->values && !m->ints) {
        bwh_fail("out of memory");
        goto out;
    }
    /* C order index of element i of the file */
    for (size_t i = 0; i < total; i++) {
        size_t c = i;
        if (fortran && nd > 1) {
            size_t idx[NPY_MAX_DIM], r = i;
            for (size_t k = 0; k < nd; k++) {
                idx[k] = r % dim[k];
                r /= dim[k];
            }
            c = 0;
            for (size_t k = 0; k < nd; k++)
                c = c * dim[k] + idx[k];
        }
        uint64_t u = load(b + off + i * (size_t)es, (size_t)es, big);
        if (kind == 'f') {
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
                bwh_fail("%s: value %zu = %g is beyond float32", path, i, x);
                goto out;
            }
            m->values[c] = (float)x;
        } else {
            int64_t v = kind == 'u' ? (int64_t)u
                        : es == 1   ? (int8_t)u
                        : es == 2   ? (int16_t)u
                        : es == 4   ? (int32_t)u
                                    : (int64_t)u;
            if ((kind == 'u' && es == 8 && u > INT32_MAX) || v > INT32_MAX || v < INT32_MIN) {
                bwh_fail("%s: integer %zu = %lld is beyond 32 bits", path, i, (long long)v);
                goto out;
            }
            m->ints[c] = (int32_t)v;
        }
    }
    m->count = total;
    m->bands = (uint32_t)dim[nd - 1];
    int layout = -1;
    if (bwh_sidecar_read(path, &m->meta, &layout) != 0)
        goto out;
    if (!(m->meta.present & BWH_M_SAMPLE_TYPE)) {
        m->meta.sample_type = st;
        m->meta.present |= BWH_M_SAMPLE_TYPE;
    }
    if (nd == 1 || (nd == 2 && layout != BW_SHAPE_REFLECTANCE)) {
        m->shape = BW_SHAPE_SPECTRA;
        m->n_in = nd == 1 ? 1u : (uint32_t)dim[0];
    } else {
        size_t n_out = dim[nd - 2];
        int level = -1;
        for (unsigned l = 0; l <= BW_MAX_LEVEL; l++)
            if (bwh_grid_count(l) == n_out)
                level = (int)l;
        if (level < 0) {
            bwh_fail("%s: %zu directions is not a geodesic level's 4*4^L (the array is "
                     "(incoming, outgoing, bands))",
                     path, n_out);
            goto out;
        }
        m->level_out = (unsigned)level;
        m->n_in = nd == 3 ? (uint32_t)dim[0] : 1u;
        m->shape = nd == 2 ? BW_SHAPE_REFLECTANCE : BW_SHAPE_BRDF_ISO;
        if (nd == 3 && layout == BW_SHAPE_BRDF_FULL) {
            m->shape = BW_SHAPE_BRDF_FULL;
            m->level_in = 99;
            for (unsigned l = 0; l <= BW_MAX_LEVEL; l++)
                if (bwh_grid_count(l) == dim[0])
                    m->level_in = l;
            if (m->level_in > BW_MAX_LEVEL) {
                bwh_fail("%s: %zu incoming directions is not a geodesic level's", path, dim[0]);
                goto out;
            }
        }
    }
    rc = 0;
out:
    free(b);
    free(h);
    if (rc)
        bwh_measure_free(m);
    return rc;
}

int bwh_npy_write(const char *path, const bwh_decoded_t *d, int t)
{
    size_t len;
    uint8_t *data = bwh_output_samples(d, t, &len);
    if (!data)
        return -1;
    static const char *const descr[BWH_ST_COUNT] = {"<f4", "|u1", "<i2", "<u2", "<i4", "<f4", "<f8"};
    const bw_dims_t *g = &d->dims;
    char shape[96];
    if (g->shape == BW_SHAPE_SPECTRA)
        snprintf(shape, sizeof shape, "(%u, %u)", g->n_in, g->bands);
    else if (g->shape == BW_SHAPE_REFLECTANCE)
        snprintf(shape, sizeof shape, "(%u, %u)", g->n_out, g->bands);
    else
        snprintf(shape, sizeof shape, "(%u, %u, %u)", g->n_in, g->n_out, g->bands);
    char h[256];
    int hn = snprintf(h, sizeof h, "{'descr': '%s', 'fortran_order': False, 'shape': %s, }",
                      descr[t >= 0 && t < BWH_ST_COUNT ? t : 0], shape);
    /* padded with spaces and a line end to a multiple of 64 bytes */
    size_t total = 10 + (size_t)hn + 1;
    size_t pad = (64 - total % 64) % 64;
    uint8_t *out = malloc(total + pad + len);
    if (!out) {
        free(data);
        return bwh_fail("out of memory");
    }
    memcpy(out, "\x93NUMPY\x01\x00", 8);
    bw_put_u16(out + 8, (uint16_t)(hn + pad + 1));
    memcpy(out + 10, h, (size_t)hn);
    memset(out + 10 + hn, ' ', pad);
    out[10 + hn + pad] = '\n';
    memcpy(out + total + pad, data, len);
    free(data);
    int rc = bwh_write_file(path, out, total + pad + len);
    free(out);
    return rc;
}
