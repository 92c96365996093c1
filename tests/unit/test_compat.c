/* SPDX-License-Identifier: BSD-2-Clause */
/* Archived payloads keep decoding: every payload under tests/golden/v<N>/,
 * written by the encoder of format version N, decodes to the samples and
 * values its MANIFEST records (CRC-32 of the little-endian int32 samples and
 * float32 values), and its header says version N. From version 7 on a
 * payload NAME.bwv with a metadata record (docs/FORMAT.md, Metadata) has
 * NAME.json beside it, the metadata it decodes to; one without has none. From version 6 on every
 * decoder must pass this for every earlier version. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_config.h"
#include "bw_crc32.h"
#include "bw_le.h"
#include "bwh_meta.h"
#include "bwhost.h"

/* the versions with archived payloads, oldest first */
static const unsigned versions[] = {6, 7};

/* The metadata of payload p[len] (header h) is that of the JSON file
 * path: both read to a bwh_meta_t and written again as JSON, which must be
 * the same text. */
static void assert_metadata_is(const uint8_t *p, size_t len, const bw_header_t *h,
                               const char *path)
{
    bwh_meta_t got, want;
    if (bwh_meta_of_payload(p, len, h, &got) != 0)
        fail_msg("%s: %s", path, bwh_last_error());
    if (bwh_meta_empty(&got))
        fail_msg("%s: the payload has no metadata", path);
    uint8_t *j;
    size_t jn;
    if (bwh_read_file(path, &j, &jn) != 0)
        fail_msg("%s", bwh_last_error());
    char *text = realloc(j, jn + 1);
    assert_non_null(text);
    text[jn] = 0;
    if (bwh_meta_from_json(text, &want) != 0)
        fail_msg("%s: %s", path, bwh_last_error());
    free(text);
    char *a, *b;
    assert_int_equal(bwh_meta_to_json(&got, &a), 0);
    assert_int_equal(bwh_meta_to_json(&want, &b), 0);
    if (strcmp(a, b))
        fail_msg("%s: the payload's metadata differs from the file's", path);
    free(a);
    free(b);
    bwh_meta_free(&got);
    bwh_meta_free(&want);
}

/* CRC-32 of n 32-bit words (int32 or float32) written little-endian */
static uint32_t crc_of_words(const void *words, size_t n)
{
    uint8_t *b = malloc(n * 4 + 1);
    assert_non_null(b);
    for (size_t i = 0; i < n; i++) {
        uint32_t w;
        memcpy(&w, (const uint8_t *)words + 4 * i, 4);
        bw_put_u32(b + 4 * i, w);
    }
    uint32_t c = bw_crc32(b, n * 4);
    free(b);
    return c;
}

static void every_archived_payload_decodes_to_its_recorded_samples(void **state)
{
    (void)state;
    unsigned checked = 0;
    for (size_t v = 0; v < sizeof versions / sizeof *versions; v++) {
        char dir[64], path[512], line[512];
        snprintf(dir, sizeof dir, "tests/golden/v%u", versions[v]);
        snprintf(path, sizeof path, "%s/MANIFEST", dir);
        FILE *m = fopen(path, "r");
        if (!m)
            fail_msg("%s: cannot open (run the tests from the repository root)", path);
        unsigned in_version = 0;
        while (fgets(line, sizeof line, m)) {
            char name[200];
            unsigned long n;
            unsigned crc_s, crc_v;
            if (line[0] == '#')
                continue;
            if (sscanf(line, "%199s %lu %x %x", name, &n, &crc_s, &crc_v) != 4)
                fail_msg("%s: bad line: %s", path, line);
            snprintf(path, sizeof path, "%s/%s.bwv", dir, name);
            uint8_t *p;
            size_t len;
            if (bwh_read_file(path, &p, &len) != 0)
                fail_msg("%s", bwh_last_error());
            bw_header_t h;
            int32_t *s;
            float *x;
            if ((!BW_CFG_EMBED || !BW_CFG_SEGMENTS) && strstr(name, "_embedded")) {
                /* a build without embedded segments says so */
                assert_int_equal(bw_header_read(p, len, &h), BW_ERR_NOT_BUILT);
                free(p);
                in_version++;
                continue;
            }
            if (!BW_CFG_BANDS && strstr(name, "_bands")) {
                /* a build without band access knows no record 0x06 */
                assert_int_equal(bw_header_read(p, len, &h), BW_ERR_EXTENSION);
                free(p);
                in_version++;
                continue;
            }
            if (!BW_CFG_CHUNK_STEPS && strstr(name, "_chunks")) {
                /* a build without steps per chunk says so */
                assert_int_equal(bw_header_read(p, len, &h), BW_ERR_NOT_BUILT);
                free(p);
                in_version++;
                continue;
            }
            if (!BW_CFG_CODER_MS && len > 5 && (p[5] & BW_FLAG_MS)) {
                /* a build without the multi-symbol coder says so */
                assert_int_equal(bw_header_read(p, len, &h), BW_ERR_NOT_BUILT);
                free(p);
                in_version++;
                continue;
            }
            if (bwh_decode(p, len, &h, &s, &x) != 0)
                fail_msg("%s: %s", path, bwh_last_error());
            if (h.version != versions[v])
                fail_msg("%s: version %u, archived as version %u", path, h.version, versions[v]);
            size_t got = bw_dims_samples(&h.dims);
            if (got != n)
                fail_msg("%s: %zu samples, recorded %lu", path, got, n);
            if (crc_of_words(s, n) != crc_s || crc_of_words(x, n) != crc_v)
                fail_msg("%s: decodes to other samples than recorded", path);
            if (versions[v] >= 7) {
                /* with NAME.json, the metadata it holds; else none */
                snprintf(path, sizeof path, "%s/%s.json", dir, name);
                FILE *js = fopen(path, "r");
                if (js) {
                    fclose(js);
                    assert_metadata_is(p, len, &h, path);
                } else {
                    bwh_meta_t none;
                    if (bwh_meta_of_payload(p, len, &h, &none) != 0)
                        fail_msg("%s: %s", path, bwh_last_error());
                    if (!bwh_meta_empty(&none))
                        fail_msg("%s.bwv: metadata, but no %s", name, path);
                    bwh_meta_free(&none);
                }
            }
            free(s);
            free(x);
            free(p);
            in_version++;
            checked++;
        }
        fclose(m);
        if (in_version < 10)
            fail_msg("%s holds only %u payloads", dir, in_version);
    }
    print_message("%u archived payloads decoded as recorded\n", checked);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_archived_payload_decodes_to_its_recorded_samples),
    };
    return cmocka_run_group_tests_name("compat", tests, NULL, NULL);
}
