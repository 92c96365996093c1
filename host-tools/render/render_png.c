/* SPDX-License-Identifier: BSD-2-Clause */
/* A small PNG writer (render_png.h): signature, IHDR, one IDAT of the
 * zlib-compressed rows (filter type 0 on every row), IEND. */
#include "render_png.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "bwh_error.h"

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static int chunk(FILE *f, const char *type, const uint8_t *data, size_t len)
{
    uint8_t hdr[8], crc[4];
    put_be32(hdr, (uint32_t)len);
    memcpy(hdr + 4, type, 4);
    uLong c = crc32(0L, Z_NULL, 0);
    c = crc32(c, hdr + 4, 4);
    if (len)
        c = crc32(c, data, (uInt)len);
    put_be32(crc, (uint32_t)c);
    return fwrite(hdr, 1, 8, f) == 8 && (len == 0 || fwrite(data, 1, len, f) == len) &&
                   fwrite(crc, 1, 4, f) == 4
               ? 0
               : -1;
}

int render_png_write(const char *path, const uint8_t *rgb, unsigned width, unsigned height)
{
    if (width == 0 || height == 0 || width > 1u << 16 || height > 1u << 16)
        return bwh_fail("png: bad image size %ux%u", width, height);
    size_t row = (size_t)width * 3 + 1, raw_len = row * height;
    uint8_t *raw = malloc(raw_len);
    uLongf z_len = compressBound((uLong)raw_len);
    uint8_t *z = malloc(z_len);
    if (!raw || !z) {
        free(raw);
        free(z);
        return bwh_fail("png: out of memory");
    }
    for (unsigned y = 0; y < height; y++) {
        raw[y * row] = 0;
        memcpy(raw + y * row + 1, rgb + (size_t)y * width * 3, (size_t)width * 3);
    }
    int zr = compress2(z, &z_len, raw, (uLong)raw_len, 9);
    free(raw);
    if (zr != Z_OK) {
        free(z);
        return bwh_fail("png: zlib error %d", zr);
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        free(z);
        return bwh_fail("%s: cannot write", path);
    }
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint8_t ihdr[13];
    put_be32(ihdr, width);
    put_be32(ihdr + 4, height);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 2;  /* colour type: RGB */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering */
    ihdr[12] = 0; /* no interlace */
    int ok = fwrite(sig, 1, 8, f) == 8 && chunk(f, "IHDR", ihdr, 13) == 0 &&
             chunk(f, "IDAT", z, z_len) == 0 && chunk(f, "IEND", NULL, 0) == 0;
    free(z);
    if (fclose(f) != 0)
        ok = 0;
    if (!ok) {
        remove(path);
        return bwh_fail("%s: write error", path);
    }
    return 0;
}
