/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * A command's report as "key: value" lines, or with --json as one JSON
 * object (keys in the same order, numbers as numbers, a value that is not
 * finite as null), from the same calls:
 *
 *   cli_kv_t kv;
 *   cli_kv_begin(&kv, stdout, json);
 *   cli_kv_str(&kv, "shape", "reflectance");
 *   cli_kv_uint(&kv, "bands", 3);
 *   cli_kv_num(&kv, "rmse", "%.9g", rmse);
 *   cli_kv_end(&kv);
 */
#ifndef CLI_KV_H
#define CLI_KV_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    FILE *f;
    int json;
    int n; /* fields written */
} cli_kv_t;

void cli_kv_begin(cli_kv_t *kv, FILE *f, int json);
void cli_kv_str(cli_kv_t *kv, const char *key, const char *value);
void cli_kv_uint(cli_kv_t *kv, const char *key, unsigned long long value);
/* fmt prints the number in both forms ("%.9g", "%.4f"); JSON: null when it
 * is not finite */
void cli_kv_num(cli_kv_t *kv, const char *key, const char *fmt, double value);
/* a number already written as text (a valid JSON number) */
void cli_kv_numtext(cli_kv_t *kv, const char *key, const char *text);
/* JSON only: a value that is JSON text already (an object, an array);
 * nothing in the key: value form */
void cli_kv_json(cli_kv_t *kv, const char *key, const char *json);
void cli_kv_end(cli_kv_t *kv);

/* s as a JSON string, quotes included */
void cli_json_string(FILE *f, const char *s);

#ifdef __cplusplus
}
#endif

#endif
