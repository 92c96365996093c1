/* SPDX-License-Identifier: BSD-2-Clause */
/* A command's report as key: value lines or one JSON object (cli_kv.h). */
#include "cli_kv.h"

#include <math.h>

void cli_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p < 0x20)
            fprintf(f, "\\u%04x", *p);
        else
            fputc(*p, f);
    }
    fputc('"', f);
}

void cli_kv_begin(cli_kv_t *kv, FILE *f, int json)
{
    kv->f = f;
    kv->json = json;
    kv->n = 0;
    if (json)
        fputc('{', f);
}

static void key(cli_kv_t *kv, const char *k)
{
    if (kv->json) {
        fputs(kv->n ? ",\n  " : "\n  ", kv->f);
        cli_json_string(kv->f, k);
        fputs(": ", kv->f);
    } else {
        fprintf(kv->f, "%s: ", k);
    }
    kv->n++;
}

static void done(cli_kv_t *kv)
{
    if (!kv->json)
        fputc('\n', kv->f);
}

void cli_kv_str(cli_kv_t *kv, const char *k, const char *value)
{
    key(kv, k);
    if (kv->json)
        cli_json_string(kv->f, value);
    else
        fputs(value, kv->f);
    done(kv);
}

void cli_kv_uint(cli_kv_t *kv, const char *k, unsigned long long value)
{
    key(kv, k);
    fprintf(kv->f, "%llu", value);
    done(kv);
}

void cli_kv_num(cli_kv_t *kv, const char *k, const char *fmt, double value)
{
    key(kv, k);
    if (kv->json && !isfinite(value))
        fputs("null", kv->f);
    else
        fprintf(kv->f, fmt, value);
    done(kv);
}

void cli_kv_numtext(cli_kv_t *kv, const char *k, const char *text)
{
    key(kv, k);
    fputs(text, kv->f);
    done(kv);
}

void cli_kv_json(cli_kv_t *kv, const char *k, const char *json)
{
    if (!kv->json)
        return;
    key(kv, k);
    fputs(json, kv->f);
}

void cli_kv_end(cli_kv_t *kv)
{
    if (kv->json)
        fputs(kv->n ? "\n}\n" : "}\n", kv->f);
}
