/* SPDX-License-Identifier: BSD-2-Clause */
/* Text files line by line (bwh_text.h). */
#include "bwh_text.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "bwh_file.h"

int bwh_text_from(bwh_text_t *t, const char *path, const char *buf, size_t len)
{
    memset(t, 0, sizeof *t);
    t->path = path;
    if (memchr(buf, 0, len))
        return bwh_fail("%s: not a text file (it holds NUL bytes)", path);
    t->buf = malloc(len + 1);
    if (!t->buf)
        return bwh_fail("%s: out of memory", path);
    memcpy(t->buf, buf, len);
    t->buf[len] = 0;
    t->len = len;
    return 0;
}

int bwh_text_open(bwh_text_t *t, const char *path)
{
    uint8_t *b;
    size_t n;
    memset(t, 0, sizeof *t);
    if (bwh_read_file(path, &b, &n) != 0)
        return -1;
    int rc = bwh_text_from(t, path, (const char *)b, n);
    free(b);
    return rc;
}

void bwh_text_close(bwh_text_t *t)
{
    free(t->buf);
    memset(t, 0, sizeof *t);
}

char *bwh_text_line(bwh_text_t *t)
{
    if (!t->buf || t->pos >= t->len)
        return NULL;
    char *s = t->buf + t->pos, *nl = memchr(s, '\n', t->len - t->pos);
    size_t n = nl ? (size_t)(nl - s) : t->len - t->pos;
    t->pos += n + (nl ? 1 : 0);
    t->last_cut = !nl;
    if (n && s[n - 1] == '\r')
        n--;
    s[n] = 0;
    t->line++;
    return s;
}

char *bwh_trim(char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
        s[--n] = 0;
    return s;
}

const char *bwh_basename(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}
