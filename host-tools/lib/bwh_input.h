/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Measurement files in: the formats of the field and the lab read to samples
 * and metadata (bwh_meta.h), each by a reader of its own, and one call that
 * picks the reader from the name and the content and joins several files
 * into one set of spectra.
 *
 *   f32 u16 i32  raw little-endian samples (bwh_raw.c), with the JSON
 *                sidecar PATH.json when there is one
 *   sed          Spectral Evolution (bwh_sed.c)
 *   sig          Spectra Vista SVC (bwh_sig.c)
 *   asd          ASD FieldSpec / Indico binary, every version (bwh_asd.c)
 *   usgs         USGS splib07 ASCII spectrum and its wavelength table (bwh_usgs.c)
 *   envi         ENVI header with a spectral library or an image cube (bwh_envi.c)
 *   csv          a wavelength column and one column per spectrum, or angle
 *                columns for directional data (bwh_csv.c)
 *   npy          numpy arrays (bwh_npy.c), with the JSON sidecar
 *   bsdf         an RGL BRDF sampled on the grid (bwh_rgl.c)
 *   gonio        a goniometer's scattered directions projected onto the grid
 *                (bwh_gonio.c)
 *
 * Every reader refuses a damaged, truncated or unknown file with one line
 * naming the file and what is wrong (bwh_last_error()).
 */
#ifndef BWH_INPUT_H
#define BWH_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"
#include "bwh_meta.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BWH_IN_AUTO = 0,
    BWH_IN_F32,
    BWH_IN_U16,
    BWH_IN_I32,
    BWH_IN_SED,
    BWH_IN_SIG,
    BWH_IN_ASD,
    BWH_IN_USGS,
    BWH_IN_ENVI,
    BWH_IN_CSV,
    BWH_IN_NPY,
    BWH_IN_BSDF,
    BWH_IN_GONIO,
    BWH_IN_COUNT
} bwh_input_format_t;

/* "auto", "f32", ... "gonio"; and back (-1: unknown) */
const char *bwh_input_format_name(int f);
int bwh_input_format_from_name(const char *name);
/* The format of a file from its content (magic bytes, first lines) and
 * then its name; BWH_IN_F32 (raw) when nothing else fits. -1 if it cannot
 * be read. */
int bwh_input_detect(const char *path);

/* What some readers need besides the file */
typedef struct {
    int level;          /* grid level of data sampled onto the grid (bsdf,
                         * gonio, scattered CSV); -1: 4 */
    int channel;        /* bsdf: 0 rgb, 1 r, 2 g, 3 b */
    int column;         /* sed, sig: BWH_COL_* */
    int has_ignore;     /* a value that marks missing samples (besides the */
    double ignore;      /* one the file names) */
    const char *wavelengths; /* usgs: the wavelength table (NULL: found beside) */
} bwh_read_opts_t;

#define BWH_READ_OPTS_INIT {-1, 0, 0, 0, 0.0, NULL}

enum { BWH_COL_REFLECTANCE = 0, BWH_COL_TARGET = 1, BWH_COL_REFERENCE = 2 };

/* A measurement read from files: float values, or integers whose value is
 * scale * integer (decimal text read exactly, integer files); its shape
 * when the file says it; its metadata. */
typedef struct {
    float *values;      /* or */
    int32_t *ints;
    double scale;       /* ints: the value of one unit */
    size_t count;       /* samples */
    uint32_t bands;     /* 0: the file does not say (raw) */
    int shape;          /* bw_shape_t, or -1: the file does not say */
    unsigned level_out, level_in;
    uint32_t n_in;      /* spectra, or incoming directions */
    bwh_meta_t meta;
} bwh_measure_t;

void bwh_measure_init(bwh_measure_t *m);
void bwh_measure_free(bwh_measure_t *m);
/* float values of the samples (ints converted), allocated */
float *bwh_measure_floats(const bwh_measure_t *m);

/* Reads paths[n] of format f (BWH_IN_AUTO: bwh_input_detect each). Several
 * files make one set of spectra: every one a set of spectra with the same
 * bands and wavelengths; their names, times and locations are kept per
 * spectrum, the other metadata where all agree (free fields that differ
 * are left out; a different instrument, quantity or unit is refused).
 * 0, or -1. */
int bwh_measure_read(const char *const *paths, int n, int f, const bwh_read_opts_t *o,
                     bwh_measure_t *m);

/* The readers, one file each (same contract) */
int bwh_read_raw(const char *path, int f, bwh_measure_t *m);
int bwh_read_sed(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_sig(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_asd(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_usgs(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_envi(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_csv(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_npy(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_bsdf(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);
int bwh_read_gonio(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m);

/* The metadata of the JSON sidecar PATH.json beside a raw or npy file, if
 * there is one (m empty otherwise); layout, when not NULL, receives the
 * sidecar's "shape" (bw_shape_t) or -1. 0, or -1. */
int bwh_sidecar_read(const char *path, bwh_meta_t *m, int *layout);

/* Marks the samples equal to `ignore` missing (m->meta) and puts the
 * nearest valid sample of the same spectrum in their place (0 where a
 * spectrum has none), so that they cost little to code. */
int bwh_measure_mark_missing(bwh_measure_t *m, double ignore);

#ifdef __cplusplus
}
#endif

#endif
