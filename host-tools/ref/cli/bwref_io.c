/* SPDX-License-Identifier: BSD-2-Clause */
/* Readers and a writer of numbers shared by the bwref commands. */
#include "bwref.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int bwref_read_text(const char *path, double **out, size_t *n)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return -1;
    size_t cap = 1024, k = 0;
    double *v = malloc(cap * sizeof *v);
    if (v == NULL) {
        fclose(f);
        return -1;
    }
    double x;
    int r;
    while ((r = fscanf(f, "%lf", &x)) == 1) {
        if (k == cap) {
            double *nv = realloc(v, 2 * cap * sizeof *v);
            if (nv == NULL) {
                free(v);
                fclose(f);
                return -1;
            }
            v = nv;
            cap *= 2;
        }
        v[k++] = x;
    }
    int bad = r != EOF || ferror(f);
    fclose(f);
    if (bad) {
        free(v);
        return -1;
    }
    *out = v;
    *n = k;
    return 0;
}

int bwref_read_f32(const char *path, double **out, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return -1;
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        return -1;
    }
    long len = ftell(f);
    rewind(f);
    if (len < 0 || len % 4 != 0) {
        fclose(f);
        return -1;
    }
    size_t cnt = (size_t)len / 4;
    unsigned char *buf = malloc(cnt * 4 + 1);
    double *v = malloc((cnt + 1) * sizeof *v);
    if (buf == NULL || v == NULL || fread(buf, 4, cnt, f) != cnt) {
        free(buf);
        free(v);
        fclose(f);
        return -1;
    }
    fclose(f);
    for (size_t i = 0; i < cnt; i++) {
        uint32_t u = (uint32_t)buf[4 * i] | (uint32_t)buf[4 * i + 1] << 8 |
                     (uint32_t)buf[4 * i + 2] << 16 | (uint32_t)buf[4 * i + 3] << 24;
        float fl;
        memcpy(&fl, &u, sizeof fl);
        v[i] = fl;
    }
    free(buf);
    *out = v;
    *n = cnt;
    return 0;
}

void bwref_put_f32(unsigned char *p, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    p[0] = (unsigned char)(u & 0xffu);
    p[1] = (unsigned char)((u >> 8) & 0xffu);
    p[2] = (unsigned char)((u >> 16) & 0xffu);
    p[3] = (unsigned char)((u >> 24) & 0xffu);
}
