/* SPDX-License-Identifier: BSD-2-Clause */
/* Flat calls for bindings (bwh_flat.h). */
#include "brdf_eval.h"
#include "bwh_flat.h"

#include <stdlib.h>
#include <string.h>

#include "bwh_encode.h"
#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_i2c.h"
#include "bwh_input.h"
#include "bwh_meta.h"
#include "bwh_shape.h"

size_t bwh_abi_size(const char *name)
{
    static const struct {
        const char *name;
        size_t size;
    } sizes[] = {
        {"bw_dims_t", sizeof(bw_dims_t)},
        {"bw_header_t", sizeof(bw_header_t)},
        {"bwh_shape_t", sizeof(bwh_shape_t)},
        {"bwh_encode_opts_t", sizeof(bwh_encode_opts_t)},
        {"bwh_i2c_t", sizeof(bwh_i2c_t)},
        {"bwh_i2c_payload_t", sizeof(bwh_i2c_payload_t)},
        {"bwh_salvage_t", sizeof(bwh_salvage_t)},
        {"bwh_partial_t", sizeof(bwh_partial_t)},
        {"bwh_brdf_data_t", sizeof(bwh_brdf_data_t)},
    };
    for (size_t i = 0; name && i < sizeof sizes / sizeof *sizes; i++)
        if (!strcmp(name, sizes[i].name))
            return sizes[i].size;
    return 0;
}

int bwh_meta_area_from_json(const char *json, const bw_dims_t *d, uint8_t **area, size_t *len)
{
    *area = NULL;
    *len = 0;
    if (!json || !*json)
        return 0;
    bwh_meta_t m;
    if (bwh_meta_from_json(json, &m) != 0)
        return -1;
    int rc = bwh_meta_check(&m, d) || bwh_meta_encode(&m, area, len) ? -1 : 0;
    bwh_meta_free(&m);
    return rc;
}

/* The metadata of a payload (of row `row` alone, or of the rows marked in
 * rows; -1 and NULL: all) as JSON. The header as bwh_header_salvage reads
 * it: the record is in what the segment table's CRC vouches for. */
static int meta_json(const uint8_t *p, size_t len, int64_t row, const uint8_t *rows, char **json)
{
    *json = NULL;
    bw_header_t h;
    bw_status_t st = bwh_header_salvage(p, len, &h);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    bwh_meta_t m;
    if (bwh_meta_of_payload(p, len, &h, &m) != 0)
        return -1;
    int rc = (row >= 0 && bwh_meta_row(&m, &h.dims, (uint32_t)row)) ||
                     (rows && bwh_meta_rows(&m, &h.dims, rows)) || bwh_meta_to_json(&m, json)
                 ? -1
                 : 0;
    bwh_meta_free(&m);
    return rc;
}

int bwh_meta_json_of_payload(const uint8_t *p, size_t len, char **json)
{
    return meta_json(p, len, -1, NULL, json);
}

int bwh_meta_row_json(const uint8_t *p, size_t len, uint32_t in, char **json)
{
    return meta_json(p, len, in, NULL, json);
}

int bwh_meta_rows_json(const uint8_t *p, size_t len, const uint8_t *rows, char **json)
{
    return meta_json(p, len, -1, rows, json);
}

int bwh_meta_json_bands(const char *json, uint32_t bands, const uint8_t *marks, char **out)
{
    *out = NULL;
    bwh_meta_t m;
    if (bwh_meta_from_json(json ? json : "{}", &m) != 0)
        return -1;
    bw_dims_t d;
    memset(&d, 0, sizeof d);
    d.bands = bands;
    int rc = bwh_meta_bands(&m, &d, marks) || bwh_meta_to_json(&m, out) ? -1 : 0;
    bwh_meta_free(&m);
    return rc;
}

int bwh_read_flat(const char *const *paths, int n, const char *format, int level, int channel,
                  int column, const char *wavelengths, int has_ignore, double ignore,
                  float **values, size_t *count, bw_dims_t *dims, char **json)
{
    *values = NULL;
    *json = NULL;
    *count = 0;
    memset(dims, 0, sizeof *dims);
    int f = format && *format ? bwh_input_format_from_name(format) : BWH_IN_AUTO;
    if (f < 0)
        return bwh_fail("unknown input format '%s'", format);
    bwh_read_opts_t o = BWH_READ_OPTS_INIT;
    o.level = level;
    o.channel = channel;
    o.column = column;
    o.wavelengths = wavelengths;
    o.has_ignore = has_ignore;
    o.ignore = ignore;
    bwh_measure_t m;
    if (bwh_measure_read(paths, n, f, &o, &m) != 0)
        return -1;
    int rc = -1;
    float *v = m.values ? m.values : bwh_measure_floats(&m);
    if (!v)
        goto out;
    if (m.values)
        m.values = NULL;
    if (m.shape >= 0 && m.bands) {
        unsigned n_in = m.shape == BW_SHAPE_REFLECTANCE ? 1u : m.n_in;
        if (bw_dims_make(dims, (bw_shape_t)m.shape, m.level_out, m.level_in, n_in, m.bands) !=
                BW_OK ||
            bw_dims_samples(dims) != m.count) {
            free(v);
            bwh_fail("%s: the file's shape does not make its %zu samples", paths[0], m.count);
            goto out;
        }
    }
    if (bwh_meta_to_json_layout(&m.meta, m.shape, json) != 0) {
        free(v);
        goto out;
    }
    *values = v;
    *count = m.count;
    rc = 0;
out:
    bwh_measure_free(&m);
    return rc;
}
