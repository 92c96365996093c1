/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * A measurement's metadata: its physical axes and context, carried in the
 * payload as an ancillary extension record of type BW_EXT_METADATA
 * (docs/FORMAT.md, Metadata). The codec core only copies the record's bytes;
 * the host builds and reads it here.
 *
 *   axes       per-band wavelengths (and bandwidths, band names); the
 *              incidence angles of an isotropic BRDF
 *   values     the quantity and its unit; the type the samples came in as;
 *              samples that were missing in the source (an ignore value)
 *   context    instrument name and serial, measurement time, location;
 *              for a set of spectra, each spectrum's name, time and location
 *   fields     named free fields (UTF-8 key and value), in order
 *
 * Every part is optional; an empty bwh_meta_t writes no record at all, and
 * the payload stays version 6. Numbers are doubles and come back bit for bit
 * (decimal values exactly as their decimal text). JSON (bwh_meta_json.c) is
 * the text form the tools and the Python package exchange.
 */
#ifndef BWH_META_H
#define BWH_META_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* the quantity the values are; each has a unit by default */
typedef enum {
    BWH_Q_NONE = 0,          /* not said                              */
    BWH_Q_REFLECTANCE = 1,   /* reflectance factor, a fraction: "1"   */
    BWH_Q_REFLECTANCE_PCT = 2, /* reflectance in percent: "%"         */
    BWH_Q_RADIANCE = 3,      /* "W m^-2 sr^-1 nm^-1"                  */
    BWH_Q_IRRADIANCE = 4,    /* "W m^-2 nm^-1"                        */
    BWH_Q_BRDF = 5,          /* "sr^-1"                               */
    BWH_Q_COUNTS = 6,        /* raw detector counts: "DN"             */
    BWH_Q_TRANSMITTANCE = 7, /* "1"                                   */
    BWH_Q_ABSORBANCE = 8,    /* "1"                                   */
    BWH_Q_OTHER = 9,         /* the unit says what                    */
    BWH_Q_COUNT
} bwh_quantity_t;

/* the type the source's samples came in as (what a writer gives back) */
typedef enum {
    BWH_ST_NONE = 0,
    BWH_ST_U8 = 1,
    BWH_ST_I16 = 2,
    BWH_ST_U16 = 3,
    BWH_ST_I32 = 4,
    BWH_ST_F32 = 5,
    BWH_ST_F64 = 6,
    BWH_ST_COUNT
} bwh_sample_type_t;

/* the unit of the wavelengths (and bandwidths) */
typedef enum { BWH_WL_NM = 0, BWH_WL_UM = 1, BWH_WL_WAVENUMBER = 2, BWH_WL_COUNT } bwh_wl_unit_t;

/* the unit of the incidence angles */
typedef enum { BWH_ANGLE_DEG = 0, BWH_ANGLE_RAD = 1, BWH_ANGLE_COUNT } bwh_angle_unit_t;

/* a time zone offset that is not known: the clock's local time */
#define BWH_TZ_LOCAL 0x7FFF
/* time zone offsets in minutes east of UTC lie within +-BWH_TZ_MAX */
#define BWH_TZ_MAX (18 * 60)

typedef struct {
    size_t n;
    double *v;
} bwh_numbers_t;

typedef struct {
    size_t n;
    char **s;
} bwh_strings_t;

/* present: which of the scalar parts below are set */
#define BWH_M_QUANTITY 0x01u
#define BWH_M_SAMPLE_TYPE 0x02u
#define BWH_M_TIME 0x04u
#define BWH_M_LOCATION 0x08u
#define BWH_M_ALTITUDE 0x10u /* with BWH_M_LOCATION */
#define BWH_M_MISSING 0x20u

typedef struct {
    unsigned present;
    int quantity;             /* bwh_quantity_t */
    char *unit;               /* NULL: the quantity's own */
    int sample_type;          /* bwh_sample_type_t */
    int wl_unit;              /* bwh_wl_unit_t of wavelengths and fwhm */
    bwh_numbers_t wavelengths; /* one per band, or none */
    bwh_numbers_t fwhm;       /* bandwidths, one per band, or none */
    bwh_strings_t band_names; /* one per band, or none */
    int inc_unit;             /* bwh_angle_unit_t */
    bwh_numbers_t incidence;  /* zenith angles of an isotropic BRDF's incoming
                               * directions (in the plane phi = 0), one per
                               * incoming direction, or none */
    char *instrument, *serial;
    double time;              /* seconds since 1970-01-01T00:00:00 of the clock */
    int time_tz;              /* its offset east of UTC in minutes, or BWH_TZ_LOCAL */
    double lat, lon, alt;     /* degrees north, east; metres */
    /* a set of spectra: per spectrum (each list has one per spectrum, or
     * none; alt may be none when the others are there) */
    bwh_strings_t spectrum_names;
    bwh_numbers_t spectrum_times;
    int spectrum_tz;
    bwh_numbers_t spectrum_lat, spectrum_lon, spectrum_alt;
    /* samples the source marked missing: runs [start, start + len) in sample
     * order, where a writer puts missing_value back */
    double missing_value;
    size_t n_missing;
    uint64_t (*missing)[2];
    /* named free fields, in order */
    size_t n_fields;
    char **keys, **values;
} bwh_meta_t;

void bwh_meta_init(bwh_meta_t *m);
void bwh_meta_free(bwh_meta_t *m); /* and init */
/* nothing set: no record is written */
int bwh_meta_empty(const bwh_meta_t *m);
/* a deep copy (dst is initialised first). 0, or -1 */
int bwh_meta_copy(bwh_meta_t *dst, const bwh_meta_t *src);

/* Every part src has replaces dst's; free fields of the same name too,
 * the others are added. 0, or -1. */
int bwh_meta_merge(bwh_meta_t *dst, const bwh_meta_t *src);

/* Setters: copies of their arguments. 0, or -1 (out of memory). */
int bwh_meta_set_string(char **dst, const char *s);
int bwh_meta_set_numbers(bwh_numbers_t *dst, const double *v, size_t n);
int bwh_meta_set_strings(bwh_strings_t *dst, const char *const *s, size_t n);
int bwh_meta_add_field(bwh_meta_t *m, const char *key, const char *value);
/* the value of free field key, or NULL */
const char *bwh_meta_field(const bwh_meta_t *m, const char *key);
/* adds a missing sample, or a run of len from start (ascending, not
 * overlapping); 0, or -1 */
int bwh_meta_add_missing(bwh_meta_t *m, uint64_t index);
int bwh_meta_add_missing_run(bwh_meta_t *m, uint64_t start, uint64_t len);
/* appends src's spectra (names, times, locations) after dst's n_dst ones
 * and src's n_src: lists that only one side has are filled with "" and NaN */
int bwh_meta_append_spectra(bwh_meta_t *dst, size_t n_dst, const bwh_meta_t *src, size_t n_src);

/* The metadata of row `in` alone of a measurement of dimensions d (a
 * spectrum of a set keeps its own name, time and location; an incoming
 * direction of a BRDF becomes a reflectance: no incidence list), missing
 * runs left out. 0, or -1. */
int bwh_meta_row(bwh_meta_t *m, const bw_dims_t *d, uint32_t in);
/* The same for the rows marked in rows[n_in] (bwh_decode_rows): a set of
 * spectra keeps the marked spectra's names, times and locations, an
 * isotropic BRDF the marked incidences, in order. 0, or -1. */
int bwh_meta_rows(bwh_meta_t *m, const bw_dims_t *d, const uint8_t *rows);

/* The metadata of the bands marked in bands[d->bands] (bwh_keep_bands):
 * their wavelengths, bandwidths and names, in order; the missing runs moved
 * to the samples kept. 0, or -1. */
int bwh_meta_bands(bwh_meta_t *m, const bw_dims_t *d, const uint8_t *bands);
/* Marks in bands[n] the bands whose wavelength lies in [lo, hi] (in the
 * metadata's wavelength unit). Returns how many, or -1 when the metadata
 * has no wavelength per band. */
int bwh_bands_of_wavelengths(const bwh_meta_t *m, size_t n, double lo, double hi,
                             uint8_t *bands);

/* The metadata fits a measurement of these dimensions: one wavelength,
 * bandwidth and band name per band, one incidence angle per incoming
 * direction of an isotropic BRDF, one name, time and location per spectrum
 * of a set, missing runs within the samples, known codes and time zones.
 * 0, or -1 (bwh_last_error() says which part and why). */
int bwh_meta_check(const bwh_meta_t *m, const bw_dims_t *d);

/* The extension area for bw_params_t.ext: one record of type
 * BW_EXT_METADATA (type, varint length, data), *len 0 and *area NULL when m
 * is empty. *area is allocated. 0, or -1. */
int bwh_meta_encode(const bwh_meta_t *m, uint8_t **area, size_t *len);
/* A record's data (without its type and length) to m (initialised here).
 * 0, or -1 with the part that is malformed. */
int bwh_meta_decode(const uint8_t *data, size_t len, bwh_meta_t *m);
/* the same with lists of at most max_count items (a payload's: its bands or
 * spectra), so that a few bytes cannot ask for gigabytes */
int bwh_meta_decode_limit(const uint8_t *data, size_t len, uint64_t max_count, bwh_meta_t *m);
/* The metadata of a payload whose header h was read from p: m is empty
 * when it has none; malformed or inconsistent with the header's
 * dimensions: -1. */
int bwh_meta_of_payload(const uint8_t *p, size_t len, const bw_header_t *h, bwh_meta_t *m);

/* Puts missing_value back at the missing samples of values[n] (a no-op
 * without BWH_M_MISSING); values are float32, so the value is rounded. */
void bwh_meta_put_missing(const bwh_meta_t *m, float *values, size_t n);

/* Names of the codes, and back (-1 for an unknown name). */
const char *bwh_quantity_name(int q);       /* "reflectance factor", ... */
const char *bwh_quantity_unit(int q);       /* the default unit */
int bwh_quantity_from_name(const char *s);
const char *bwh_sample_type_name(int t);    /* "u8", "i16", ... "f64" */
int bwh_sample_type_from_name(const char *s);
size_t bwh_sample_type_size(int t);
const char *bwh_wl_unit_name(int u);        /* "nm", "um", "cm-1" */
int bwh_wl_unit_from_name(const char *s);   /* also "Nanometers", "Micrometers", ... */
const char *bwh_angle_unit_name(int u);     /* "deg", "rad" */
int bwh_angle_unit_from_name(const char *s);
/* the metadata's unit: its own, or its quantity's */
const char *bwh_meta_unit(const bwh_meta_t *m);

/* ISO 8601 time, "YYYY-MM-DDThh:mm:ss[.fff]" then "Z", "+hh:mm" or nothing
 * (BWH_TZ_LOCAL), from seconds since 1970 of the clock; buf holds 40
 * bytes. */
void bwh_time_format(double sec, int tz, char *buf, size_t cap);
/* The other way; the time zone is BWH_TZ_LOCAL when the text has none.
 * 0, or -1. */
int bwh_time_parse(const char *s, double *sec, int *tz);
/* seconds since 1970 of a civil date and time (proleptic Gregorian) */
double bwh_time_of(int year, int month, int day, int hour, int min, double sec);

/* The metadata as "key: value" lines, one per part (bwh_meta_text.c):
 * lists in full, texts as JSON strings; nothing for empty metadata. */
void bwh_meta_print(const bwh_meta_t *m, FILE *f);

/* JSON (bwh_meta_json.c): the object of docs/FORMAT.md's metadata table,
 * and back. *json is allocated. 0, or -1. */
int bwh_meta_to_json(const bwh_meta_t *m, char **json);
int bwh_meta_from_json(const char *json, bwh_meta_t *m);
/* The same with the layout of a sidecar (bwh_input.h): "shape", the
 * bw_shape_t of the samples beside it ("spectra", "reflectance",
 * "brdf-iso", "brdf-full"; -1: none), which the payload's header holds and
 * the record does not. */
int bwh_meta_to_json_layout(const bwh_meta_t *m, int layout, char **json);
int bwh_meta_from_json_layout(const char *json, bwh_meta_t *m, int *layout);
/* one number as JSON prints it: the shortest decimal that reads back as v
 * ("null" for NaN and infinities); buf holds 32 bytes */
void bwh_json_number(double v, char *buf, size_t cap);

#ifdef __cplusplus
}
#endif

#endif
