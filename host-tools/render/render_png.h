/* SPDX-License-Identifier: BSD-2-Clause */
/* A small PNG writer (8-bit RGB, zlib). */
#ifndef RENDER_PNG_H
#define RENDER_PNG_H

#include <stddef.h>
#include <stdint.h>

/* rgb: height rows of width * 3 bytes. 0, or -1 (message in bwh_last_error()). */
int render_png_write(const char *path, const uint8_t *rgb, unsigned width, unsigned height);

#endif
