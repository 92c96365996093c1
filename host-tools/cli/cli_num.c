/* SPDX-License-Identifier: BSD-2-Clause */
/* Strict numbers on the command line (cli_num.h). */
#include "cli_num.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int cli_u32(const char *s, uint32_t lo, uint32_t hi, int hex_ok, uint32_t *out)
{
    if (!s || !isdigit((unsigned char)*s))
        return -1;
    int base = hex_ok && s[0] == '0' && (s[1] == 'x' || s[1] == 'X') ? 16 : 10;
    if (base == 16 && !isxdigit((unsigned char)s[2]))
        return -1;
    char *e;
    errno = 0;
    unsigned long long v = strtoull(s, &e, base);
    if (errno || *e || v < lo || v > hi)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

/* a finite double: the whole of s */
static int finite_double(const char *s, double *out)
{
    if (!s || !*s || isspace((unsigned char)*s))
        return -1;
    char *e;
    errno = 0;
    double v = strtod(s, &e);
    if (e == s || *e || errno == ERANGE || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

int cli_real(const char *s, double lo, double hi, double *out)
{
    double v;
    if (finite_double(s, &v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int cli_positive(const char *s, double hi, double *out)
{
    double v;
    if (finite_double(s, &v) || !(v > 0.0) || v > hi)
        return -1;
    *out = v;
    return 0;
}

int cli_real_list(const char *s, double lo, double hi, double *out, size_t cap, size_t *n)
{
    size_t k = 0;
    const char *p = s;
    if (!s)
        return -1;
    for (;;) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char field[64];
        if (k == cap || len == 0 || len >= sizeof field)
            return -1;
        memcpy(field, p, len);
        field[len] = 0;
        if (cli_real(field, lo, hi, &out[k]) != 0)
            return -1;
        k++;
        if (!comma)
            break;
        p = comma + 1;
    }
    *n = k;
    return 0;
}

int cli_size2(const char *s, uint32_t lo, uint32_t hi, uint32_t *w, uint32_t *h)
{
    const char *x = s ? strchr(s, 'x') : NULL;
    char first[16];
    if (!x || (size_t)(x - s) >= sizeof first)
        return -1;
    memcpy(first, s, (size_t)(x - s));
    first[x - s] = 0;
    return cli_u32(first, lo, hi, 0, w) || cli_u32(x + 1, lo, hi, 0, h) ? -1 : 0;
}
