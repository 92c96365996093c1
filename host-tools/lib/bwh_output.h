/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Decoded measurements out, with their metadata where the format holds it:
 *
 *   f32 i32 u16  raw little-endian samples: the float values, the codec's
 *                integer samples, or those as uint16 (0..65535)
 *   raw          raw samples of the type the source came in as (the
 *                metadata's sample type: integers when the values are
 *                the integer samples, f64 widened from the decoded float32;
 *                f32 when there is none)
 *   npy          a numpy array of that type, shape (spectra, bands),
 *                (directions, bands) or (incoming, outgoing, bands)
 *   csv          text: "# key: value" metadata lines, then a wavelength column
 *                and one column per spectrum, or for directional data one
 *                row per direction (its angles) and one column per band
 *   envi         an ENVI header PATH.hdr beside the data PATH: a spectral
 *                library for spectra, a BIP image (lines = incoming,
 *                samples = outgoing) otherwise; the metadata as ENVI keys
 *
 * raw, f32, i32, u16 and npy keep the metadata in a JSON sidecar PATH.json
 * (not for "-", standard output), which the readers take back.
 */
#ifndef BWH_OUTPUT_H
#define BWH_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"
#include "bwh_meta.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BWH_OUT_F32 = 0,
    BWH_OUT_I32,
    BWH_OUT_U16,
    BWH_OUT_RAW,
    BWH_OUT_NPY,
    BWH_OUT_CSV,
    BWH_OUT_ENVI,
    BWH_OUT_COUNT
} bwh_output_format_t;

const char *bwh_output_format_name(int f);
int bwh_output_format_from_name(const char *name);

/* A decoded measurement: its dimensions, float values (missing samples put
 * back), its integer samples and whether they are the values (scale 1,
 * offset 0, not logarithmic), and its metadata. */
typedef struct {
    bw_dims_t dims;
    const float *values;
    const int32_t *ints;
    int ints_are_values;
    const bwh_meta_t *meta;
} bwh_decoded_t;

/* Writes d to path in format f (bwh_write_file: "-" is standard output; ENVI
 * needs a file). 0, or -1 (bwh_last_error()). */
int bwh_output_write(const char *path, int f, const bwh_decoded_t *d);

/* The element type an output of format f writes d in (bwh_sample_type_t). */
int bwh_output_type(int f, const bwh_decoded_t *d);

/* One sample, little-endian, of type t at dst: from the integer q for the
 * integer types, else from the value v. */
void bwh_put_sample(uint8_t *dst, int t, float v, int32_t q);

/* The samples of d as little-endian elements of type t (allocated; the
 * integer types need the integer samples, and they must fit). NULL on
 * failure. */
uint8_t *bwh_output_samples(const bwh_decoded_t *d, int t, size_t *len);

/* The JSON sidecar of a raw or npy file: path + ".json" with the metadata
 * and the layout (bwh_meta_to_json_layout); nothing for "-", and for
 * empty metadata none (an old one is removed). 0, or -1. */
int bwh_sidecar_write(const char *path, const bwh_meta_t *m, int shape);

/* Writers of one format each (bwh_npy.c, bwh_csv.c, bwh_envi.c) */
int bwh_npy_write(const char *path, const bwh_decoded_t *d, int type);
int bwh_csv_write(const char *path, const bwh_decoded_t *d);
int bwh_envi_write(const char *path, const bwh_decoded_t *d, int type);

#ifdef __cplusplus
}
#endif

#endif
