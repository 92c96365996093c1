/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Flat calls for bindings (the Python package's ctypes layer): the sizes of
 * the structures a binding lays out itself, and the metadata and the
 * readers with JSON and plain arrays instead of the structures of
 * bwh_meta.h and bwh_input.h, so that a binding cannot drift from them.
 */
#ifndef BWH_FLAT_H
#define BWH_FLAT_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* sizeof the named structure ("bw_dims_t", "bw_header_t", "bwh_shape_t",
 * "bwh_encode_opts_t", "bwh_i2c_t", "bwh_i2c_payload_t"), 0 for another
 * name: a binding checks its copies against these when it loads */
size_t bwh_abi_size(const char *name);

/* The extension area (bw_params_t.ext) of the metadata JSON json (the keys
 * of 'brdfwave info --json'; NULL or "" or "{}": none), checked against the
 * dimensions d. *area allocated (NULL and 0 when empty). 0, or -1. */
int bwh_meta_area_from_json(const char *json, const bw_dims_t *d, uint8_t **area, size_t *len);

/* The metadata of payload p[len] as JSON ("{}" without), allocated. 0, or
 * -1 (a malformed payload or record). */
int bwh_meta_json_of_payload(const uint8_t *p, size_t len, char **json);
/* The same for row `in` alone (bwh_meta_row): what `decode --incoming` keeps. */
int bwh_meta_row_json(const uint8_t *p, size_t len, uint32_t in, char **json);
/* The same for the rows marked in rows[n_in] (bwh_meta_rows): what
 * `decode --rows` keeps. */
int bwh_meta_rows_json(const uint8_t *p, size_t len, const uint8_t *rows, char **json);
/* Metadata JSON json of a measurement of `bands` bands cut to the bands
 * marked in marks[bands] (bwh_meta_bands): what `decode --bands` keeps, as
 * JSON in *out (allocated). 0, or -1. */
int bwh_meta_json_bands(const char *json, uint32_t bands, const uint8_t *marks, char **out);

/* Reads the files paths[n] (bwh_measure_read; format a name of
 * bwh_input.h, NULL or "auto": detected; level -1: the default; channel,
 * column: their index in bwh_read_opts_t; wavelengths NULL or a table) to
 * float values (allocated), their dimensions when the files say them
 * (dims->bands 0 otherwise: raw samples without a sidecar), the layout
 * (bw_shape_t, or -1) and the metadata as JSON (allocated). 0, or -1. */
int bwh_read_flat(const char *const *paths, int n, const char *format, int level, int channel,
                  int column, const char *wavelengths, int has_ignore, double ignore,
                  float **values, size_t *count, bw_dims_t *dims, char **json);

#ifdef __cplusplus
}
#endif

#endif
