/* SPDX-License-Identifier: BSD-2-Clause */
/* Archived payloads of float input keep decoding: every payload under
 * tests/golden/v7_values/ (written by tests/golden/v7_values/make.py with
 * the records 0x01, 0x02 and 0x82) decodes on the host to the samples and
 * values its MANIFEST records (CRC-32 of the little-endian int32 samples and
 * float32 values), says version 7, and reads back the guarantee it was made
 * under. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_crc32.h"
#include "bw_le.h"
#include "bwh_guarantee.h"
#include "bwhost.h"

#define DIR "tests/golden/v7_values"

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

static void every_archived_float_payload_decodes_to_its_values_and_guarantee(void **state)
{
    (void)state;
    char path[512], line[512];
    FILE *m = fopen(DIR "/MANIFEST", "r");
    if (!m)
        fail_msg(DIR "/MANIFEST: cannot open (run the tests from the repository root)");
    unsigned checked = 0;
    while (fgets(line, sizeof line, m)) {
        char name[200], kind[32];
        unsigned long n;
        unsigned crc_s, crc_v;
        if (line[0] == '#')
            continue;
        if (sscanf(line, "%199s %lu %x %x %31s", name, &n, &crc_s, &crc_v, kind) != 5)
            fail_msg("MANIFEST: bad line: %s", line);
        snprintf(path, sizeof path, DIR "/%s.bwv", name);
        uint8_t *p;
        size_t len;
        if (bwh_read_file(path, &p, &len) != 0)
            fail_msg("%s", bwh_last_error());
        bw_header_t h;
        int32_t *s;
        float *x;
        if (bwh_decode(p, len, &h, &s, &x) != 0)
            fail_msg("%s: %s", path, bwh_last_error());
        if (h.version != 7 || !h.ext_len)
            fail_msg("%s: version %u with %u bytes of records", path, h.version, h.ext_len);
        if (bw_dims_samples(&h.dims) != n)
            fail_msg("%s: %zu samples, recorded %lu", path, bw_dims_samples(&h.dims), n);
        if (crc_of_words(s, n) != crc_s || crc_of_words(x, n) != crc_v)
            fail_msg("%s: decodes to other samples or values than recorded", path);
        bwh_guarantee_t g;
        if (bwh_guarantee_read(p, len, &g) != 0)
            fail_msg("%s: %s", path, bwh_last_error());
        if (strcmp(bwh_guarantee_name(g.kind), kind) != 0)
            fail_msg("%s: guarantee %s, recorded %s", path, bwh_guarantee_name(g.kind), kind);
        free(s);
        free(x);
        free(p);
        checked++;
    }
    fclose(m);
    if (checked < 8)
        fail_msg(DIR " holds only %u payloads", checked);
    print_message("%u archived float payloads decoded as recorded\n", checked);
}

/* Every byte of every archived payload changed (three ways, the CRC made
 * right again, so that the records and the tail are what is read): the host
 * decodes it or refuses it with a message, and its guarantee reads or is
 * refused, never a crash (tests/sanitize.sh runs this under ASan and UBSan). */
static void a_payload_with_any_byte_changed_decodes_or_is_refused_with_a_message(void **state)
{
    (void)state;
    static const char *const names[] = {"phong_lossless_planes", "odd_lossless_exceptions",
                                        "decimal_lossless_exceptions", "phong_rel_log_value",
                                        "signed_rel_logmap", "signed_both_97"};
    static const uint8_t flips[] = {0x01, 0x80, 0xFF};
    unsigned decoded = 0, refused = 0;
    for (size_t f = 0; f < sizeof names / sizeof names[0]; f++) {
        char path[256];
        snprintf(path, sizeof path, DIR "/%s.bwv", names[f]);
        uint8_t *p;
        size_t len;
        if (bwh_read_file(path, &p, &len) != 0)
            fail_msg("%s", bwh_last_error());
        uint8_t *e = malloc(len);
        assert_non_null(e);
        for (size_t at = 0; at + 4 < len; at++) {
            for (size_t k = 0; k < sizeof flips; k++) {
                memcpy(e, p, len);
                e[at] ^= flips[k];
                bw_put_u32(e + len - 4, bw_crc32(e, len - 4));
                bw_header_t h;
                int32_t *s = NULL;
                float *x = NULL;
                if (bwh_decode(e, len, &h, &s, &x) == 0) {
                    decoded++;
                    free(s);
                    free(x);
                } else {
                    if (!*bwh_last_error())
                        fail_msg("%s, byte %zu ^ 0x%02x: refused without a message", path, at,
                                 flips[k]);
                    refused++;
                }
                bwh_guarantee_t g;
                if (bwh_guarantee_read(e, len, &g) != 0 && !*bwh_last_error())
                    fail_msg("%s, byte %zu: guarantee refused without a message", path, at);
            }
        }
        free(e);
        free(p);
    }
    assert_true(refused > 0 && decoded > 0);
    print_message("%u changed payloads decoded, %u refused\n", decoded, refused);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_archived_float_payload_decodes_to_its_values_and_guarantee),
        cmocka_unit_test(a_payload_with_any_byte_changed_decodes_or_is_refused_with_a_message),
    };
    return cmocka_run_group_tests_name("golden values", tests, NULL, NULL);
}
