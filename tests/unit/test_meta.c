/* SPDX-License-Identifier: BSD-2-Clause */
/* The metadata record (docs/FORMAT.md, Metadata, type 0x81) and its JSON
 * form: every field comes back bit for bit, through the record, through
 * JSON and through a payload; an empty set writes no record (version 6);
 * malformed records and metadata that does not fit the dimensions are
 * refused with a message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "brdf_eval.h"
#include "bw_codec.h"
#include "bwh_decode.h"
#include "bwh_encode.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_meta.h"

#define N_SPECTRA 3u
#define BANDS 7u

static int same(double a, double b) { return !memcmp(&a, &b, sizeof a); }

static void assert_numbers_equal(const bwh_numbers_t *a, const bwh_numbers_t *b)
{
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++)
        assert_true(same(a->v[i], b->v[i]) || (isnan(a->v[i]) && isnan(b->v[i])));
}

static void assert_strings_equal(const bwh_strings_t *a, const bwh_strings_t *b)
{
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++)
        assert_string_equal(a->s[i], b->s[i]);
}

static void assert_opt_string(const char *a, const char *b)
{
    if (!a || !b)
        assert_ptr_equal(a, b);
    else
        assert_string_equal(a, b);
}

static void assert_meta_equal(const bwh_meta_t *a, const bwh_meta_t *b)
{
    assert_int_equal(a->present, b->present);
    assert_int_equal(a->quantity, b->quantity);
    assert_opt_string(a->unit, b->unit);
    assert_int_equal(a->sample_type, b->sample_type);
    assert_int_equal(a->wl_unit, b->wl_unit);
    assert_numbers_equal(&a->wavelengths, &b->wavelengths);
    assert_numbers_equal(&a->fwhm, &b->fwhm);
    assert_strings_equal(&a->band_names, &b->band_names);
    assert_int_equal(a->inc_unit, b->inc_unit);
    assert_numbers_equal(&a->incidence, &b->incidence);
    assert_opt_string(a->instrument, b->instrument);
    assert_opt_string(a->serial, b->serial);
    if (a->present & BWH_M_TIME) {
        assert_true(same(a->time, b->time));
        assert_int_equal(a->time_tz, b->time_tz);
    }
    if (a->present & BWH_M_LOCATION) {
        assert_true(same(a->lat, b->lat));
        assert_true(same(a->lon, b->lon));
    }
    if (a->present & BWH_M_ALTITUDE)
        assert_true(same(a->alt, b->alt));
    assert_strings_equal(&a->spectrum_names, &b->spectrum_names);
    assert_numbers_equal(&a->spectrum_times, &b->spectrum_times);
    if (a->spectrum_times.n)
        assert_int_equal(a->spectrum_tz, b->spectrum_tz);
    assert_numbers_equal(&a->spectrum_lat, &b->spectrum_lat);
    assert_numbers_equal(&a->spectrum_lon, &b->spectrum_lon);
    assert_numbers_equal(&a->spectrum_alt, &b->spectrum_alt);
    assert_int_equal(a->n_missing, b->n_missing);
    for (size_t i = 0; i < a->n_missing; i++) {
        assert_int_equal(a->missing[i][0], b->missing[i][0]);
        assert_int_equal(a->missing[i][1], b->missing[i][1]);
    }
    if (a->present & BWH_M_MISSING)
        assert_true(same(a->missing_value, b->missing_value));
    assert_int_equal(a->n_fields, b->n_fields);
    for (size_t i = 0; i < a->n_fields; i++) {
        assert_string_equal(a->keys[i], b->keys[i]);
        assert_string_equal(a->values[i], b->values[i]);
    }
}

/* a full set: uneven wavelengths (Rice-coded), float32 bandwidths, every
 * context field, per-spectrum lists, a missing run, free fields */
static void full_meta(bwh_meta_t *m)
{
    static const double wl[BANDS] = {339.3, 340.8, 342.3, 343.9, 345.4, 1012.7, 2509.4};
    static const double fwhm[BANDS] = {1.5f, 1.5f, 1.5f, 1.6f, 1.6f, 3.8f, 6.5f};
    static const char *const bands[BANDS] = {"b1", "b2", "b3", "b4", "b5", "b6", "b7"};
    static const char *const names[N_SPECTRA] = {"1116037_00041.sed", "1116037_00042.sed",
                                                 "1116037_00043.sed"};
    static const double times[N_SPECTRA] = {1554112320, 1554112380.5, 1554112441};
    static const double lat[N_SPECTRA] = {-25.75371, -25.75372, -25.75374};
    static const double lon[N_SPECTRA] = {28.23021, 28.23022, 28.2302};
    bwh_meta_init(m);
    m->present = BWH_M_QUANTITY | BWH_M_SAMPLE_TYPE | BWH_M_TIME | BWH_M_LOCATION |
                 BWH_M_ALTITUDE | BWH_M_MISSING;
    m->quantity = BWH_Q_REFLECTANCE;
    m->sample_type = BWH_ST_F32;
    m->wl_unit = BWH_WL_NM;
    assert_int_equal(bwh_meta_set_numbers(&m->wavelengths, wl, BANDS), 0);
    assert_int_equal(bwh_meta_set_numbers(&m->fwhm, fwhm, BANDS), 0);
    assert_int_equal(bwh_meta_set_strings(&m->band_names, bands, BANDS), 0);
    assert_int_equal(bwh_meta_set_string(&m->instrument, "PSR-3500"), 0);
    assert_int_equal(bwh_meta_set_string(&m->serial, "1116037"), 0);
    m->time = 1554112320.25;
    m->time_tz = 120;
    m->lat = -25.75371;
    m->lon = 28.23021;
    m->alt = 1342.5;
    assert_int_equal(bwh_meta_set_strings(&m->spectrum_names, names, N_SPECTRA), 0);
    assert_int_equal(bwh_meta_set_numbers(&m->spectrum_times, times, N_SPECTRA), 0);
    m->spectrum_tz = BWH_TZ_LOCAL;
    assert_int_equal(bwh_meta_set_numbers(&m->spectrum_lat, lat, N_SPECTRA), 0);
    assert_int_equal(bwh_meta_set_numbers(&m->spectrum_lon, lon, N_SPECTRA), 0);
    m->missing_value = -9999;
    assert_int_equal(bwh_meta_add_missing_run(m, 3, 2), 0);
    assert_int_equal(bwh_meta_add_missing(m, 20), 0);
    assert_int_equal(bwh_meta_add_field(m, "operator", "N. M\xc3\xa9ndez"), 0);
    assert_int_equal(bwh_meta_add_field(m, "target", "dry grass, \"plot 4\"\n"), 0);
}

static bw_dims_t spectra_dims(void)
{
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, N_SPECTRA, BANDS), BW_OK);
    return d;
}

static void record_should_give_back_every_field(void **state)
{
    (void)state;
    bwh_meta_t m, back;
    full_meta(&m);
    bw_dims_t d = spectra_dims();
    assert_int_equal(bwh_meta_check(&m, &d), 0);
    uint8_t *area;
    size_t len;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    assert_non_null(area);
    assert_int_equal(area[0], BW_EXT_METADATA);
    /* type, varint length, data */
    size_t pos = 0;
    uint8_t type;
    const uint8_t *data;
    uint32_t dl;
    assert_true(bw_ext_next(area, (uint32_t)len, &pos, &type, &data, &dl));
    assert_int_equal(pos, len);
    assert_int_equal(bwh_meta_decode(data, dl, &back), 0);
    assert_meta_equal(&m, &back);
    bwh_meta_free(&back);
    free(area);
    bwh_meta_free(&m);
}

static void json_should_give_back_every_field(void **state)
{
    (void)state;
    bwh_meta_t m, back;
    full_meta(&m);
    char *json;
    assert_int_equal(bwh_meta_to_json(&m, &json), 0);
    assert_non_null(strstr(json, "PSR-3500"));
    assert_int_equal(bwh_meta_from_json(json, &back), 0);
    assert_meta_equal(&m, &back);
    free(json);
    bwh_meta_free(&back);
    bwh_meta_free(&m);
}

static void arithmetic_wavelengths_should_cost_a_few_bytes(void **state)
{
    (void)state;
    bwh_meta_t m, back;
    bwh_meta_init(&m);
    double wl[1024];
    for (int i = 0; i < 1024; i++)
        wl[i] = 350.0 + 0.5 * i;
    assert_int_equal(bwh_meta_set_numbers(&m.wavelengths, wl, 1024), 0);
    uint8_t *area;
    size_t len;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    /* the example of docs/FORMAT.md, Metadata: the record's type and
     * length, then the field */
    static const uint8_t want[] = {0x81, 10, 0x03, 0x08, 0x00, 0x80, 0x08,
                                   0x00, 0x01, 0xD8, 0x36, 0x0A};
    assert_int_equal(len, sizeof want);
    assert_memory_equal(area, want, sizeof want);
    size_t pos = 0;
    uint8_t type;
    const uint8_t *data;
    uint32_t dl;
    assert_true(bw_ext_next(area, (uint32_t)len, &pos, &type, &data, &dl));
    assert_int_equal(bwh_meta_decode(data, dl, &back), 0);
    assert_numbers_equal(&m.wavelengths, &back.wavelengths);
    bwh_meta_free(&back);
    free(area);
    bwh_meta_free(&m);
}

static void empty_metadata_should_write_no_record(void **state)
{
    (void)state;
    bwh_meta_t m;
    bwh_meta_init(&m);
    assert_true(bwh_meta_empty(&m));
    uint8_t *area = (uint8_t *)&m;
    size_t len = 99;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    assert_null(area);
    assert_int_equal(len, 0);
}

static void every_cut_of_a_record_should_be_refused_or_read(void **state)
{
    (void)state;
    bwh_meta_t m, back;
    full_meta(&m);
    uint8_t *area;
    size_t len;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    size_t pos = 0;
    uint8_t type;
    const uint8_t *data;
    uint32_t dl;
    assert_true(bw_ext_next(area, (uint32_t)len, &pos, &type, &data, &dl));
    /* a record cut anywhere inside a field is refused; cut between fields
     * it is a shorter valid record */
    int refused = 0;
    for (uint32_t n = 0; n < dl; n++) {
        uint8_t *c = malloc(n ? n : 1);
        memcpy(c, data, n);
        if (bwh_meta_decode(c, n, &back) != 0) {
            refused++;
            assert_non_null(strstr(bwh_last_error(), "metadata record"));
        } else {
            bwh_meta_free(&back);
        }
        free(c);
    }
    assert_true(refused > (int)dl / 2);
    /* every single flipped bit is refused or read without a crash */
    for (uint32_t i = 0; i < dl * 8; i++) {
        uint8_t *c = malloc(dl);
        memcpy(c, data, dl);
        c[i / 8] ^= (uint8_t)(1u << (i % 8));
        if (bwh_meta_decode(c, dl, &back) == 0)
            bwh_meta_free(&back);
        free(c);
    }
    free(area);
    bwh_meta_free(&m);
}

static void fields_out_of_order_should_be_refused(void **state)
{
    (void)state;
    /* instrument (7) before quantity (1) */
    static const uint8_t rec[] = {7, 2, 'A', 'B', 1, 1, 1};
    bwh_meta_t m;
    assert_int_equal(bwh_meta_decode(rec, sizeof rec, &m), -1);
    assert_non_null(strstr(bwh_last_error(), "out of order"));
    /* a field longer than the record */
    static const uint8_t longer[] = {7, 9, 'A'};
    assert_int_equal(bwh_meta_decode(longer, sizeof longer, &m), -1);
    /* an unknown quantity code */
    static const uint8_t q[] = {1, 1, 99};
    assert_int_equal(bwh_meta_decode(q, sizeof q, &m), -1);
    assert_non_null(strstr(bwh_last_error(), "quantity"));
    /* a later version's field (tag 40) is skipped */
    static const uint8_t later[] = {7, 2, 'A', 'B', 40, 3, 1, 2, 3};
    assert_int_equal(bwh_meta_decode(later, sizeof later, &m), 0);
    assert_string_equal(m.instrument, "AB");
    bwh_meta_free(&m);
}

static void metadata_that_does_not_fit_should_be_refused(void **state)
{
    (void)state;
    bwh_meta_t m;
    full_meta(&m);
    bw_dims_t d;
    /* one band more than the wavelengths */
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, N_SPECTRA, BANDS + 1), BW_OK);
    assert_int_equal(bwh_meta_check(&m, &d), -1);
    assert_non_null(strstr(bwh_last_error(), "wavelength"));
    bwh_meta_free(&m);
    /* incidence angles for an isotropic BRDF of 2 incoming directions */
    bwh_meta_init(&m);
    static const double inc[3] = {0, 27.67, 39.86};
    assert_int_equal(bwh_meta_set_numbers(&m.incidence, inc, 3), 0);
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_BRDF_ISO, 2, 0, 2, 1), BW_OK);
    assert_int_equal(bwh_meta_check(&m, &d), -1);
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_BRDF_ISO, 2, 0, 3, 1), BW_OK);
    assert_int_equal(bwh_meta_check(&m, &d), 0);
    bwh_meta_free(&m);
}

/* through the encoder: version 7, the CRC covers the record, the metadata
 * reads back from the payload; without metadata version 6 */
static void payload_should_carry_the_metadata(void **state)
{
    (void)state;
    bwh_meta_t m, back;
    full_meta(&m);
    bw_dims_t d = spectra_dims();
    float x[N_SPECTRA * BANDS];
    for (size_t i = 0; i < N_SPECTRA * BANDS; i++)
        x[i] = (float)(100 + (i * 37) % 11);
    uint8_t *area, *p, *p0;
    size_t len, plen, plen0;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_LOSSLESS;
    o.basis = BW_BASIS_53;
    o.ext = area;
    o.ext_len = len;
    int rc = bwh_encode_f32(&d, x, &o, &p, &plen);
    if (rc)
        print_error("%s\n", bwh_last_error());
    assert_int_equal(rc, 0);
    o.ext = NULL;
    o.ext_len = 0;
    assert_int_equal(bwh_encode_f32(&d, x, &o, &p0, &plen0), 0);
    bw_header_t h;
    assert_int_equal(bw_header_read(p, plen, &h), BW_OK);
    assert_int_equal(h.version, 7);
    assert_int_equal(bwh_meta_of_payload(p, plen, &h, &back), 0);
    assert_meta_equal(&m, &back);
    bwh_meta_free(&back);
    /* the metadata costs its record and the area's length, nothing more */
    assert_true(plen - plen0 <= len + 3);
    assert_true(plen > plen0 + len);
    bw_header_t h0;
    assert_int_equal(bw_header_read(p0, plen0, &h0), BW_OK);
    assert_int_equal(h0.version, 6);
    assert_int_equal(bwh_meta_of_payload(p0, plen0, &h0, &back), 0);
    assert_true(bwh_meta_empty(&back));
    /* a changed byte of the record fails the CRC */
    p[h.ext_off + h.ext_len / 2] ^= 0x10;
    assert_int_not_equal(bw_header_read(p, plen, &h), BW_OK);
    free(p);
    free(p0);
    free(area);
    bwh_meta_free(&m);
}

static void times_should_read_back_as_iso_8601(void **state)
{
    (void)state;
    double t;
    int tz;
    char buf[40];
    assert_int_equal(bwh_time_parse("2019-04-01T10:32:00.25+02:00", &t, &tz), 0);
    assert_int_equal(tz, 120);
    assert_true(t == bwh_time_of(2019, 4, 1, 10, 32, 0.25));
    bwh_time_format(t, tz, buf, sizeof buf);
    assert_string_equal(buf, "2019-04-01T10:32:00.25+02:00");
    assert_int_equal(bwh_time_parse("2019-04-01T10:32:00", &t, &tz), 0);
    assert_int_equal(tz, BWH_TZ_LOCAL);
    assert_int_equal(bwh_time_parse("2019-13-01T10:32:00", &t, &tz), -1);
}

/* An isotropic BRDF of 3 incoming planes, plane k all k, written with and
 * without the incidence angles 0, 30, 60 degrees: evaluation at theta_i =
 * 30 degrees reads plane 1 with them, and halfway between the default
 * angles 15 and 45 without. */
static double value_at_30_degrees(int with_angles)
{
    enum { LEVEL = 1, N_OUT = 16, N_IN = 3 };
    bw_dims_t d;
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_BRDF_ISO, LEVEL, 0, N_IN, 1), BW_OK);
    float x[N_IN * N_OUT];
    for (size_t i = 0; i < N_IN * N_OUT; i++)
        x[i] = (float)(i / N_OUT);
    bwh_meta_t m;
    bwh_meta_init(&m);
    static const double inc[N_IN] = {0, 30, 60};
    if (with_angles)
        assert_int_equal(bwh_meta_set_numbers(&m.incidence, inc, N_IN), 0);
    assert_int_equal(bwh_meta_check(&m, &d), 0);
    uint8_t *area, *p;
    size_t len, plen;
    assert_int_equal(bwh_meta_encode(&m, &area, &len), 0);
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_LOSSLESS;
    o.basis = BW_BASIS_HAAR;
    o.ext = area;
    o.ext_len = len;
    assert_int_equal(bwh_encode_f32(&d, x, &o, &p, &plen), 0);
    char path[64];
    snprintf(path, sizeof path, "/tmp/test_meta_%d_%d.bwv", (int)getpid(), with_angles);
    assert_int_equal(bwh_write_file(path, p, plen), 0);
    bwh_brdf_data_t b;
    assert_int_equal(bwh_brdf_data_load(&b, path), 0);
    unlink(path);
    double t = 30.0 * 3.14159265358979323846 / 180.0;
    double wi[3] = {sin(t), 0, cos(t)}, wo[3] = {0, 0, 1};
    double v = bwh_brdf_data_band(&b, wi, wo, 0);
    bwh_brdf_data_free(&b);
    free(p);
    free(area);
    bwh_meta_free(&m);
    return v;
}

/* Every choice of bands of a set of spectra: the kept bands' wavelengths,
 * bandwidths and names in order; the missing samples where they fall
 * (against each sample taken one by one), runs maximal; the samples,
 * values and mask cut alike (bwh_keep_bands). */
static void keeping_bands_keeps_their_metadata_and_moves_the_missing_samples(void **state)
{
    (void)state;
    enum { N = N_SPECTRA * BANDS };
    bwh_meta_t src;
    full_meta(&src);
    /* full_meta's runs and one across two spectra */
    free(src.missing);
    src.missing = NULL;
    src.n_missing = 0;
    assert_int_equal(bwh_meta_add_missing_run(&src, 3, 2), 0);
    assert_int_equal(bwh_meta_add_missing_run(&src, 9, 6), 0);
    assert_int_equal(bwh_meta_add_missing_run(&src, 20, 1), 0);
    uint8_t miss[N] = {0};
    for (size_t r = 0; r < src.n_missing; r++)
        for (uint64_t t = src.missing[r][0]; t < src.missing[r][0] + src.missing[r][1]; t++)
            miss[t] = 1;
    bw_dims_t d = spectra_dims();
    for (unsigned set = 1; set < 1u << BANDS; set++) {
        uint8_t bands[BANDS];
        unsigned nk = 0;
        for (unsigned k = 0; k < BANDS; k++)
            nk += bands[k] = (uint8_t)(set >> k & 1u);
        bwh_meta_t m;
        assert_int_equal(bwh_meta_copy(&m, &src), 0);
        assert_int_equal(bwh_meta_bands(&m, &d, bands), 0);
        assert_int_equal(m.wavelengths.n, nk);
        assert_int_equal(m.fwhm.n, nk);
        assert_int_equal(m.band_names.n, nk);
        uint8_t want[N] = {0}, got[N] = {0};
        for (unsigned i = 0, j = 0; i < N; i++) {
            if (!bands[i % BANDS])
                continue;
            if (i < BANDS) {
                assert_true(same(m.wavelengths.v[j], src.wavelengths.v[i]));
                assert_true(same(m.fwhm.v[j], src.fwhm.v[i]));
                assert_string_equal(m.band_names.s[j], src.band_names.s[i]);
            }
            want[j++] = miss[i];
        }
        for (size_t r = 0; r < m.n_missing; r++) {
            assert_true(m.missing[r][1] > 0 && m.missing[r][0] + m.missing[r][1] <= N_SPECTRA * nk);
            if (r)
                assert_true(m.missing[r][0] > m.missing[r - 1][0] + m.missing[r - 1][1]);
            for (uint64_t t = m.missing[r][0]; t < m.missing[r][0] + m.missing[r][1]; t++)
                got[t] = 1;
        }
        assert_memory_equal(got, want, N);
        assert_int_equal((m.present & BWH_M_MISSING) != 0, m.n_missing != 0);
        bwh_meta_free(&m);
        /* the samples: sample i holds i, its value i / 2, its mask i % 3 */
        int32_t sm[N];
        float v[N];
        uint8_t mk[N];
        for (unsigned i = 0; i < N; i++) {
            sm[i] = (int32_t)i;
            v[i] = (float)i / 2.0f;
            mk[i] = (uint8_t)(i % 3u);
        }
        bw_dims_t dk = d;
        assert_int_equal(bwh_keep_bands(&dk, bands, sm, v, mk), 0);
        assert_int_equal(dk.bands, nk);
        for (unsigned i = 0, j = 0; i < N; i++) {
            if (!bands[i % BANDS])
                continue;
            assert_int_equal(sm[j], (int32_t)i);
            assert_true(v[j] == (float)i / 2.0f);
            assert_int_equal(mk[j], i % 3u);
            j++;
        }
    }
    /* none chosen: refused; by wavelength: those in the range, none without */
    uint8_t none[BANDS] = {0}, by_wl[BANDS];
    assert_int_equal(bwh_keep_bands(&d, none, NULL, NULL, NULL), -1);
    assert_int_equal(bwh_bands_of_wavelengths(&src, BANDS, 340.0, 344.0, by_wl), 3);
    assert_memory_equal(by_wl, ((uint8_t[BANDS]){0, 1, 1, 1, 0, 0, 0}), BANDS);
    assert_int_equal(bwh_bands_of_wavelengths(&src, BANDS, 0.0, 1.0, by_wl), 0);
    bwh_meta_t bare;
    bwh_meta_init(&bare);
    assert_int_equal(bwh_bands_of_wavelengths(&bare, BANDS, 0.0, 1e9, by_wl), -1);
    bwh_meta_free(&src);
}

static void evaluation_should_use_the_measured_incidence_angles(void **state)
{
    (void)state;
    assert_true(fabs(value_at_30_degrees(1) - 1.0) < 1e-9);
    assert_true(fabs(value_at_30_degrees(0) - 0.5) < 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(record_should_give_back_every_field),
        cmocka_unit_test(json_should_give_back_every_field),
        cmocka_unit_test(arithmetic_wavelengths_should_cost_a_few_bytes),
        cmocka_unit_test(empty_metadata_should_write_no_record),
        cmocka_unit_test(every_cut_of_a_record_should_be_refused_or_read),
        cmocka_unit_test(fields_out_of_order_should_be_refused),
        cmocka_unit_test(metadata_that_does_not_fit_should_be_refused),
        cmocka_unit_test(payload_should_carry_the_metadata),
        cmocka_unit_test(times_should_read_back_as_iso_8601),
        cmocka_unit_test(keeping_bands_keeps_their_metadata_and_moves_the_missing_samples),
        cmocka_unit_test(evaluation_should_use_the_measured_incidence_angles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
