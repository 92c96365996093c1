/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Text files line by line, for the readers of the text formats (.sed,
 * .sig, USGS ASCII, ENVI headers, CSV): the whole file in memory ("-" is
 * standard input), lines without their CR LF or LF, the line number for
 * messages, and whether the last line was cut short (no line end).
 */
#ifndef BWH_TEXT_H
#define BWH_TEXT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    char *buf;
    size_t len, pos;
    unsigned line;      /* number of the line last returned, from 1 */
    int last_cut;       /* the line last returned had no line end */
    const char *path;   /* for messages */
} bwh_text_t;

/* Reads path; a file with a NUL byte is refused as not text. 0, or -1. */
int bwh_text_open(bwh_text_t *t, const char *path);
/* the same over a copy of buf[len] */
int bwh_text_from(bwh_text_t *t, const char *path, const char *buf, size_t len);
void bwh_text_close(bwh_text_t *t);
/* the next line (NUL-terminated, within t's buffer), NULL at the end */
char *bwh_text_line(bwh_text_t *t);

/* s without leading and trailing blanks (in place) */
char *bwh_trim(char *s);
/* the final part of a path, after its last '/' */
const char *bwh_basename(const char *path);

#ifdef __cplusplus
}
#endif

#endif
