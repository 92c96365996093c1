/* A small PNG writer (8-bit RGB, zlib). */
#ifndef BW_RENDER_PNG_H
#define BW_RENDER_PNG_H

#include <stddef.h>
#include <stdint.h>

/* rgb: height rows of width * 3 bytes. 0, or -1 (message in bwh_last_error()). */
int bw_png_write(const char *path, const uint8_t *rgb, unsigned width, unsigned height);

#endif
