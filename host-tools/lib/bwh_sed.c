/* SPDX-License-Identifier: BSD-2-Clause */
/* Spectral Evolution .sed files (bwh_sed.h). */
#include "bwh_sed.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bwh_error.h"

/* Parses a non-negative or negative decimal with at most 5 fraction digits
 * into units of 10^-5, exactly. */
static int parse_fixed5(const char *s, const char **end, int32_t *out)
{
    while (*s == ' ' || *s == '\t')
        s++;
    int neg = 0;
    if (*s == '-' || *s == '+')
        neg = *s++ == '-';
    if (!isdigit((unsigned char)*s) && *s != '.')
        return -1;
    int64_t v = 0;
    int digits = 0;
    while (isdigit((unsigned char)*s)) {
        v = v * 10 + (*s++ - '0');
        if (v > 100000000)
            return -1;
        digits++;
    }
    int frac = 0;
    if (*s == '.') {
        s++;
        while (isdigit((unsigned char)*s)) {
            if (frac == 5)
                return -1; /* more precision than the format carries */
            v = v * 10 + (*s++ - '0');
            frac++;
            digits++;
        }
    }
    if (!digits)
        return -1;
    while (frac++ < 5)
        v *= 10;
    if (*s && !isspace((unsigned char)*s))
        return -1;
    *end = s;
    *out = (int32_t)(neg ? -v : v);
    return 0;
}

int bwh_sed_read(const char *path, int32_t **values, uint32_t *bands, double **wavelengths)
{
    *values = NULL;
    if (wavelengths)
        *wavelengths = NULL;
    FILE *f = fopen(path, "r");
    if (!f)
        return bwh_fail("%s: %s", path, strerror(errno));
    char line[4096];
    long channels = -1;
    int in_data = 0, header_seen = 0;
    uint32_t n = 0;
    int32_t *v = NULL;
    double *wl = NULL;
    int lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (!in_data) {
            if (!strncmp(line, "Channels:", 9))
                channels = strtol(line + 9, NULL, 10);
            if (!strncmp(line, "Data:", 5)) {
                if (channels < 1 || channels > (long)BW_MAX_BANDS) {
                    fclose(f);
                    return bwh_fail("%s: missing or invalid 'Channels:' header", path);
                }
                v = calloc((size_t)channels, sizeof *v);
                wl = calloc((size_t)channels, sizeof *wl);
                if (!v || !wl) {
                    free(v);
                    free(wl);
                    fclose(f);
                    return bwh_fail("%s: out of memory", path);
                }
                in_data = 1;
            }
            continue;
        }
        if (!header_seen) { /* column titles */
            header_seen = 1;
            continue;
        }
        if (!strchr(line, '\n')) {
            int cut = feof(f) || strlen(line) + 1 < sizeof line;
            free(v);
            free(wl);
            fclose(f);
            if (cut)
                return bwh_fail("%s:%d: the last row has no line end (the file is cut short)", path,
                            lineno);
            return bwh_fail("%s:%d: line longer than %zu bytes", path, lineno, sizeof line - 1);
        }
        const char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (*s == '\n' || *s == '\r' || *s == 0)
            continue;
        if (n >= (uint32_t)channels) {
            free(v);
            free(wl);
            fclose(f);
            return bwh_fail("%s:%d: more data rows than 'Channels: %ld'", path, lineno, channels);
        }
        /* Wvl, Rad.(Ref.), Rad.(Target), -log Reflect., Reflect. */
        char *e;
        double cols[4];
        for (int c = 0; c < 4; c++) {
            errno = 0;
            cols[c] = strtod(s, &e);
            if (e == s || errno || !isfinite(cols[c])) {
                free(v);
                free(wl);
                fclose(f);
                return bwh_fail("%s:%d: expected 5 numeric columns", path, lineno);
            }
            s = e;
        }
        const char *end;
        if (parse_fixed5(s, &end, &v[n]) != 0) {
            free(v);
            free(wl);
            fclose(f);
            return bwh_fail("%s:%d: bad reflectance value", path, lineno);
        }
        wl[n] = cols[0];
        n++;
    }
    fclose(f);
    if (!in_data || n != (uint32_t)channels) {
        free(v);
        free(wl);
        return bwh_fail("%s: %s (%u of %ld rows)", path, in_data ? "truncated data" : "no 'Data:' section",
                    n, channels);
    }
    *values = v;
    *bands = n;
    if (wavelengths)
        *wavelengths = wl;
    else
        free(wl);
    return 0;
}

int bwh_sed_read_set(const char *const *paths, int n, int32_t **values, uint32_t *bands,
                     size_t *count)
{
    int32_t *all = NULL;
    size_t have = 0;
    for (int k = 0; k < n; k++) {
        int32_t *v;
        uint32_t b;
        if (bwh_sed_read(paths[k], &v, &b, NULL) != 0) {
            free(all);
            return -1;
        }
        if (!*bands)
            *bands = b;
        int32_t *grown = b == *bands ? realloc(all, (have + b) * sizeof *all) : NULL;
        if (!grown) {
            free(v);
            free(all);
            if (b != *bands)
                return bwh_fail("%s has %u channels, expected %u", paths[k], b, *bands);
            return bwh_fail("out of memory");
        }
        all = grown;
        memcpy(all + have, v, b * sizeof *v);
        have += b;
        free(v);
    }
    *values = all;
    *count = have;
    return 0;
}
