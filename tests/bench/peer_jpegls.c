/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * JPEG-LS reference point for the codec benchmark (CharLS C API).
 *
 * usage: peer_jpegls [-b BITS] WIDTH HEIGHT NEAR IN.u16 OUT.jls DECODED.u16
 *
 * Reads WIDTH*HEIGHT native-endian uint16 greyscale samples from IN.u16,
 * encodes them as JPEG-LS with the given NEAR parameter (0 = lossless) and
 * BITS bits per sample (default 16), writes the code stream to OUT.jls,
 * decodes it again and writes the samples to DECODED.u16. Prints the number
 * of encoded bytes on stdout. Exit status 0 on success, 1 on failure.
 */
#include <charls/charls.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const char *what, const char *detail)
{
    fprintf(stderr, "peer_jpegls: %s%s%s\n", what, detail ? ": " : "",
            detail ? detail : "");
    return 1;
}

static int parse_u32(const char *s, unsigned long max, uint32_t *out)
{
    char *end;
    unsigned long v = strtoul(s, &end, 10);
    if (end == s || *end != '\0' || v > max)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int write_file(const char *path, const void *buf, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return -1;
    if (fwrite(buf, 1, n, f) != n) {
        fclose(f);
        return -1;
    }
    return fclose(f) == 0 ? 0 : -1;
}

int main(int argc, char **argv)
{
    uint32_t bits = 16, width, height, near_value;
    int a = 1;
    size_t n, in_bytes, cap = 0, written = 0, dec_size = 0;
    uint16_t *in = NULL, *dec = NULL;
    unsigned char *code = NULL;
    charls_jpegls_encoder *enc = NULL;
    charls_jpegls_decoder *decd = NULL;
    charls_jpegls_errc ec;
    FILE *f;
    int rc = 1;

    if (argc > 2 && strcmp(argv[1], "-b") == 0) {
        if (parse_u32(argv[2], 16, &bits) != 0 || bits < 2)
            return fail("bad -b value (2..16)", argv[2]);
        a = 3;
    }
    if (argc - a != 6) {
        fputs("usage: peer_jpegls [-b BITS] WIDTH HEIGHT NEAR IN.u16 OUT.jls DECODED.u16\n",
              stderr);
        return 1;
    }
    if (parse_u32(argv[a], 65535, &width) != 0 || width == 0 ||
        parse_u32(argv[a + 1], 65535, &height) != 0 || height == 0)
        return fail("bad image size", NULL);
    if (parse_u32(argv[a + 2], 255, &near_value) != 0)
        return fail("bad NEAR value", argv[a + 2]);

    n = (size_t)width * height;
    in_bytes = n * sizeof(uint16_t);
    in = malloc(in_bytes);
    if (in == NULL)
        return fail("out of memory", NULL);
    f = fopen(argv[a + 3], "rb");
    if (f == NULL) {
        free(in);
        return fail("cannot open input", argv[a + 3]);
    }
    if (fread(in, 1, in_bytes, f) != in_bytes || fgetc(f) != EOF) {
        fclose(f);
        free(in);
        return fail("input size does not match WIDTH*HEIGHT*2 bytes", argv[a + 3]);
    }
    fclose(f);

    enc = charls_jpegls_encoder_create();
    decd = charls_jpegls_decoder_create();
    if (enc == NULL || decd == NULL) {
        fail("cannot create CharLS encoder/decoder", NULL);
        goto done;
    }
    {
        charls_frame_info fi;
        fi.width = width;
        fi.height = height;
        fi.bits_per_sample = (int32_t)bits;
        fi.component_count = 1;
        ec = charls_jpegls_encoder_set_frame_info(enc, &fi);
        if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
            fail("set_frame_info", charls_get_error_message(ec));
            goto done;
        }
    }
    ec = charls_jpegls_encoder_set_near_lossless(enc, (int32_t)near_value);
    if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
        fail("set_near_lossless", charls_get_error_message(ec));
        goto done;
    }
    ec = charls_jpegls_encoder_get_estimated_destination_size(enc, &cap);
    if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
        fail("get_estimated_destination_size", charls_get_error_message(ec));
        goto done;
    }
    code = malloc(cap);
    if (code == NULL) {
        fail("out of memory", NULL);
        goto done;
    }
    ec = charls_jpegls_encoder_set_destination_buffer(enc, code, cap);
    if (ec == CHARLS_JPEGLS_ERRC_SUCCESS)
        ec = charls_jpegls_encoder_encode_from_buffer(enc, in, in_bytes, 0);
    if (ec == CHARLS_JPEGLS_ERRC_SUCCESS)
        ec = charls_jpegls_encoder_get_bytes_written(enc, &written);
    if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
        fail("encode", charls_get_error_message(ec));
        goto done;
    }
    if (write_file(argv[a + 4], code, written) != 0) {
        fail("cannot write", argv[a + 4]);
        goto done;
    }

    ec = charls_jpegls_decoder_set_source_buffer(decd, code, written);
    if (ec == CHARLS_JPEGLS_ERRC_SUCCESS)
        ec = charls_jpegls_decoder_read_header(decd);
    if (ec == CHARLS_JPEGLS_ERRC_SUCCESS)
        ec = charls_jpegls_decoder_get_destination_size(decd, 0, &dec_size);
    if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
        fail("decode header", charls_get_error_message(ec));
        goto done;
    }
    if (dec_size != in_bytes) {
        fail("decoded size differs from the input size", NULL);
        goto done;
    }
    dec = malloc(dec_size);
    if (dec == NULL) {
        fail("out of memory", NULL);
        goto done;
    }
    ec = charls_jpegls_decoder_decode_to_buffer(decd, dec, dec_size, 0);
    if (ec != CHARLS_JPEGLS_ERRC_SUCCESS) {
        fail("decode", charls_get_error_message(ec));
        goto done;
    }
    if (write_file(argv[a + 5], dec, dec_size) != 0) {
        fail("cannot write", argv[a + 5]);
        goto done;
    }
    printf("%zu\n", written);
    rc = 0;

done:
    charls_jpegls_decoder_destroy(decd);
    charls_jpegls_encoder_destroy(enc);
    free(dec);
    free(code);
    free(in);
    return rc;
}
