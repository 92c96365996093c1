/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Numbers on the command line, strictly: the whole string, finite, in range;
 * nothing is guessed (no leading '+' or '-' for counts, no trailing text).
 */
#ifndef CLI_NUM_H
#define CLI_NUM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A decimal integer lo..hi (hex_ok: also 0x...). 0, or -1. */
int cli_u32(const char *s, uint32_t lo, uint32_t hi, int hex_ok, uint32_t *out);

/* A finite number lo..hi (both included). 0, or -1. */
int cli_real(const char *s, double lo, double hi, double *out);

/* A finite number > 0 and <= hi. 0, or -1. */
int cli_positive(const char *s, double hi, double *out);

/* 1..cap comma-separated finite numbers lo..hi into out, their count in
 * *n. 0, or -1. */
int cli_real_list(const char *s, double lo, double hi, double *out, size_t cap, size_t *n);

/* "WxH", two integers lo..hi. 0, or -1. */
int cli_size2(const char *s, uint32_t lo, uint32_t hi, uint32_t *w, uint32_t *h);

#ifdef __cplusplus
}
#endif

#endif
