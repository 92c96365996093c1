/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libFuzzer target: the host library's readers of a payload on arbitrary
 * bytes (libbrdfwave, host-tools/lib): the metadata and the other extension
 * records, the float tail and the log map turned into values, the salvage
 * decode and its mask, one row, a set of rows, a coarser level, a band
 * range, and f(wi, wo) straight from the payload.
 *
 * The input is read three ways: as a payload; as the same payload with its
 * trailing CRC-32 made right (so that a changed header, record or body is
 * read past the check); and as a metadata record's data and as metadata
 * JSON (bwh_meta_decode, bwh_meta_from_json), whose readings must survive
 * writing and reading back unchanged.
 *
 * Every call must return its documented status (0, 1 where documented, or
 * -1 with a message) without a fault the sanitizers see, and on a payload
 * that decodes whole: the salvage decode gives the same samples with every
 * sample exact, one row and a set of rows give those rows of the whole
 * decode, a band range gives those bands, and f from the payload is f of
 * the whole decode. A header declaring more than FUZZ_MAX_SAMPLES samples
 * is only decoded with that limit (which must refuse it).
 *
 * Built by tests/fuzz/run.sh as the fuzz_decode target is (the library's
 * sources with the core's).
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdf_eval.h"
#include "bw_codec.h"
#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_meta.h"
#include "bw_crc32.h"
#include "bw_le.h"

#define FUZZ_MAX_SAMPLES ((size_t)1 << 18)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int cond, const char *what)
{
    if (!cond) {
        fprintf(stderr, "fuzz_host: %s (last error: %s)\n", what, bwh_last_error());
        abort();
    }
}

/* a status of the library: 0 or -1 (1 where the call documents it) */
static void status(int rc, int most, const char *what)
{
    require(rc >= -1 && rc <= most, what);
    if (rc < 0)
        require(bwh_last_error()[0] != '\0', "an error without a message");
}

static int same_bits(const float *a, const float *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

/* The metadata record's reader, then writing and reading back. */
static void meta_record(const uint8_t *data, size_t size)
{
    bwh_meta_t m, back;
    bwh_meta_init(&m);
    int rc = bwh_meta_decode_limit(data, size, 4096, &m);
    status(rc, 0, "bwh_meta_decode_limit");
    if (rc == 0) {
        uint8_t *area = NULL;
        size_t len = 0;
        char *j1 = NULL, *j2 = NULL;
        require(bwh_meta_encode(&m, &area, &len) == 0, "bwh_meta_encode of what was read");
        /* the area is one record: its type, its length (a varint), its data */
        size_t at = len ? 1u : 0u;
        while (at < len && (area[at] & 0x80u))
            at++;
        at += at < len;
        require(bwh_meta_decode_limit(len ? area + at : area, len - at, 4096, &back) == 0,
                "bwh_meta_decode of what bwh_meta_encode wrote");
        require(bwh_meta_to_json(&m, &j1) == 0 && bwh_meta_to_json(&back, &j2) == 0,
                "bwh_meta_to_json");
        require(strcmp(j1, j2) == 0, "metadata written and read back differ");
        free(area);
        free(j1);
        free(j2);
        bwh_meta_free(&back);
    }
    bwh_meta_free(&m);
}

/* The JSON reader, then writing and reading back. */
static void meta_json(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    require(text != NULL, "out of memory");
    memcpy(text, data, size);
    text[size] = '\0';
    bwh_meta_t m, back;
    bwh_meta_init(&m);
    int rc = bwh_meta_from_json(text, &m);
    status(rc, 0, "bwh_meta_from_json");
    if (rc == 0) {
        char *j1 = NULL, *j2 = NULL;
        require(bwh_meta_to_json(&m, &j1) == 0, "bwh_meta_to_json of what was read");
        require(bwh_meta_from_json(j1, &back) == 0, "bwh_meta_from_json of bwh_meta_to_json's");
        require(bwh_meta_to_json(&back, &j2) == 0 && strcmp(j1, j2) == 0,
                "metadata JSON written and read back differs");
        free(j1);
        free(j2);
        bwh_meta_free(&back);
    }
    bwh_meta_free(&m);
    free(text);
}

static void payload(const uint8_t *data, size_t size)
{
    bw_header_t h, hd;
    int32_t *s = NULL;
    float *v = NULL;
    if (bwh_header_salvage(data, size, &h) != BW_OK) {
        status(bwh_decode_limit(data, size, FUZZ_MAX_SAMPLES, &hd, &s, &v), 0, "bwh_decode_limit");
        require(!s && !v, "a refused payload left buffers");
        return;
    }
    size_t n = bw_dims_samples(&h.dims);
    if (n == 0 || n > FUZZ_MAX_SAMPLES) {
        int rc = bwh_decode_limit(data, size, FUZZ_MAX_SAMPLES, &hd, &s, &v);
        require(rc == -1, "bwh_decode_limit: a payload past the limit decodes");
        return;
    }
    const bw_dims_t *d = &h.dims;
    size_t row = (size_t)d->n_out * d->bands;

    /* the metadata and its JSON */
    bwh_meta_t meta;
    bwh_meta_init(&meta);
    if (bwh_meta_of_payload(data, size, &h, &meta) == 0) {
        char *json = NULL;
        status(bwh_meta_to_json(&meta, &json), 0, "bwh_meta_to_json");
        free(json);
    }
    bwh_meta_free(&meta);

    /* the whole decode, then the salvage decode */
    int whole = bwh_decode_limit(data, size, FUZZ_MAX_SAMPLES, &hd, &s, &v);
    status(whole, 0, "bwh_decode_limit");
    if (whole != 0)
        require(!s && !v, "a refused payload left buffers");
    int32_t *ss = NULL;
    float *sv = NULL;
    uint8_t *mask = NULL;
    bwh_salvage_t info;
    int rc = bwh_decode_salvage(data, size, FUZZ_MAX_SAMPLES, &hd, &ss, &sv, &mask, &info);
    status(rc, 1, "bwh_decode_salvage");
    if (whole == 0) {
        require(rc == 0 && memcmp(ss, s, n * sizeof *s) == 0 && same_bits(sv, v, n),
                "the salvage decode of a whole payload differs");
        for (size_t k = 0; k < n; k++)
            require(mask[k] == BW_SAMPLE_EXACT, "a whole payload with a sample not exact");
    }
    free(ss);
    free(sv);
    free(mask);

    bool rows_apart = d->shape != BW_SHAPE_REFLECTANCE && d->n_in > 1;
    if (rows_apart) {
        /* one row, then every third row from one the input picks */
        uint32_t in = (uint32_t)(size * 2654435761u) % d->n_in;
        bw_dims_t sub;
        int32_t *rs = NULL;
        float *rv = NULL;
        rc = bwh_decode_incoming(data, size, in, &hd, &sub, &rs, &rv);
        status(rc, 0, "bwh_decode_incoming");
        if (whole == 0 && rc == 0)
            require(memcmp(rs, s + (size_t)in * row, row * sizeof *s) == 0 &&
                        same_bits(rv, v + (size_t)in * row, row),
                    "one row differs from the whole decode's");
        free(rs);
        free(rv);
        uint8_t *marks = calloc(d->n_in, 1);
        require(marks != NULL, "out of memory");
        for (uint32_t t = (uint32_t)(size % 3u); t < d->n_in; t += 3u)
            marks[t] = 1;
        rs = NULL;
        rv = NULL;
        rc = bwh_decode_rows(data, size, marks, &hd, &sub, &rs, &rv);
        status(rc, 0, "bwh_decode_rows");
        if (whole == 0 && rc == 0)
            for (uint32_t t = 0, k = 0; t < d->n_in; t++)
                if (marks[t]) {
                    require(memcmp(rs + (size_t)k * row, s + (size_t)t * row, row * sizeof *s) == 0,
                            "a set of rows differs from the whole decode's");
                    k++;
                }
        free(rs);
        free(rv);
        free(marks);
    }
    if (d->shape != BW_SHAPE_SPECTRA && d->level_out <= BW_MAX_LEVEL) {
        /* a coarser level */
        bw_dims_t lod;
        int32_t *ls = NULL;
        float *lv = NULL;
        rc = bwh_decode_level(data, size, (unsigned)(size % (d->level_out + 1u)), &hd, &lod, &ls,
                              &lv);
        status(rc, 0, "bwh_decode_level");
        free(ls);
        free(lv);
    }
    if (whole == 0 && d->bands > 1) {
        /* every other band, from one the input picks */
        uint8_t *bands = calloc(d->bands, 1);
        require(bands != NULL, "out of memory");
        for (uint32_t b = (uint32_t)(size % 2u); b < d->bands; b += 2u)
            bands[b] = 1;
        bw_dims_t kd = *d;
        int32_t *ks = malloc(n * sizeof *ks);
        float *kv = malloc(n * sizeof *kv);
        require(ks && kv, "out of memory");
        memcpy(ks, s, n * sizeof *ks);
        memcpy(kv, v, n * sizeof *kv);
        rc = bwh_keep_bands(&kd, bands, ks, kv, NULL);
        status(rc, 0, "bwh_keep_bands");
        if (rc == 0)
            for (size_t t = 0, k = 0; t < n; t++)
                if (bands[t % d->bands]) {
                    require(ks[k] == s[t] && same_bits(kv + k, v + t, 1),
                            "a band range differs from those bands of the whole decode");
                    k++;
                }
        free(bands);
        free(ks);
        free(kv);
    }
    if (d->shape == BW_SHAPE_BRDF_ISO || d->shape == BW_SHAPE_BRDF_FULL ||
        d->shape == BW_SHAPE_REFLECTANCE) {
        /* f straight from the payload, and of the whole decode */
        enum { NP = 3 };
        const double wi[NP][3] = {{0, 0, 1}, {0.6, 0, 0.8}, {0, 1, 0}};
        const double wo[NP][3] = {{0, 0, 1}, {-0.48, 0.6, 0.64}, {0.28, 0, 0.96}};
        const double lam[NP] = {0, 500, 1e9};
        double got[NP], want[NP];
        for (int mode = 0; mode < 2; mode++) {
            const double *l = mode ? lam : NULL;
            rc = bwh_payload_eval(data, size, NP, &wi[0][0], &wo[0][0], l, -1, got);
            status(rc, 0, "bwh_payload_eval");
            bwh_brdf_data_t all;
            int ra = whole == 0 ? bwh_brdf_data_from_payload(&all, data, size, NULL, 0) : -1;
            status(ra, 0, "bwh_brdf_data_from_payload");
            if (ra == 0) {
                require(rc == 0, "f from the payload refused where the whole decode evaluates");
                require(bwh_brdf_data_eval_many(&all, NP, &wi[0][0], &wo[0][0], l, -1, want) == 0,
                        "bwh_brdf_data_eval_many");
                for (int j = 0; j < NP; j++)
                    require(memcmp(&got[j], &want[j], sizeof got[j]) == 0 ||
                                (isnan(got[j]) && isnan(want[j])),
                            "f from the payload differs from f of the whole decode");
                bwh_brdf_data_free(&all);
            }
        }
    }
    free(s);
    free(v);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    payload(data, size);
    if (size > BW_TRAILER_SIZE) {
        /* the same with its CRC-32 right */
        uint8_t *fixed = malloc(size);
        require(fixed != NULL, "out of memory");
        memcpy(fixed, data, size);
        bw_put_u32(fixed + size - BW_TRAILER_SIZE, bw_crc32(fixed, size - BW_TRAILER_SIZE));
        payload(fixed, size);
        free(fixed);
    }
    meta_record(data, size);
    meta_json(data, size);
    return 0;
}

#ifdef BW_FUZZ_REPLAY
#define BW_FUZZ_NAME "fuzz_host"
#include "replay_main.h"
#endif
