/* SPDX-License-Identifier: BSD-2-Clause */
/* Archived payloads keep decoding: every payload under tests/golden/v<N>/,
 * written by the encoder of format version N, decodes to the samples and
 * values its MANIFEST records (CRC-32 of the little-endian int32 samples and
 * float32 values), and its header says version N. From version 6 on every
 * decoder must pass this for every earlier version. */
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
#include "bwhost.h"

/* the versions with archived payloads, oldest first */
static const unsigned versions[] = {6};

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
            if (bwh_decode(p, len, &h, &s, &x) != 0)
                fail_msg("%s: %s", path, bwh_last_error());
            if (h.version != versions[v])
                fail_msg("%s: version %u, archived as version %u", path, h.version, versions[v]);
            size_t got = bw_dims_samples(&h.dims);
            if (got != n)
                fail_msg("%s: %zu samples, recorded %lu", path, got, n);
            if (crc_of_words(s, n) != crc_s || crc_of_words(x, n) != crc_v)
                fail_msg("%s: decodes to other samples than recorded", path);
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
