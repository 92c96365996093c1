/*
 * libbrdfwave: the host side of the codec.
 *
 * The codec core (firmware/codec) works on integer samples. This layer maps
 * float measurements to integers and back (value = offset + scale * sample,
 * both recorded in the payload header), reads the input formats, and
 * computes the error metrics the tools report.
 */
#ifndef BWHOST_H
#define BWHOST_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Error text of the last failing bwh_* call (thread-local). */
const char *bwh_last_error(void);

/* Whole-file I/O. bwh_read_file allocates *buf (free() it); "-" is standard
 * input. bwh_write_file writes "-" to standard output, and a path that is
 * not a regular file (a device, a pipe) directly; a regular file (or a
 * symbolic link to one, followed) is written beside it and renamed over it,
 * so that a failure leaves the old file; a symbolic link to nothing is
 * refused. */
int bwh_read_file(const char *path, uint8_t **buf, size_t *len);
int bwh_write_file(const char *path, const void *buf, size_t len);

/* Stores a received payload in dir as payload-ID-CRC.bwv (ID the device's
 * payload id, CRC the payload's CRC-32 field in hex: a device that counts ids from 1 again
 * after a reboot cannot collide with what is stored), through a temporary
 * file, fsync and a link that never replaces an existing file; the name
 * goes to path[cap]. 0 when stored, 1 when that very payload was stored
 * before (a repeat whose acknowledgement was lost), -1 on failure. */
int bwh_store_payload(const char *dir, uint32_t id, const uint8_t *p, size_t n, char *path,
                      size_t cap);

/* Spectral Evolution .sed: reflectance column, parsed exactly as decimal
 * text into integers of 10^-5 (the files print 5 decimals). *values is
 * allocated; *bands receives the channel count; wavelengths (optional,
 * allocated) in nm. */
int bwh_sed_read(const char *path, int32_t **values, uint32_t *bands, double **wavelengths);
#define BWH_SED_SCALE 1e-5

typedef enum { BWH_FMT_F32 = 0, BWH_FMT_U16 = 1, BWH_FMT_I32 = 2 } bwh_format_t;

/* Encoder options' flags beside the header's: without BW_FLAG_MIRROR,
 * BW_FLAG_RECIPROCAL or this, a host encode of directional data also tries
 * BW_FLAG_MIRROR (and for a full BRDF on one grid level BW_FLAG_RECIPROCAL
 * and both) and keeps the smallest payload (for a byte budget: the one that
 * decodes closest); with this it uses the symmetry flags given, if any. */
#define BWH_NO_MIRROR 0x100u

typedef struct {
    bw_mode_t mode;     /* LOSSLESS, MAX_ERROR or BYTES */
    double max_error;   /* MAX_ERROR, in value units */
    size_t byte_budget; /* BYTES */
    unsigned basis;     /* bw_basis_t or BW_BASIS_AUTO */
    double scale;       /* > 0: force the integer step of float input */
    unsigned flags;     /* header flags (BW_FLAG_DECIMAL_SCALE, BW_FLAG_MIRROR and
                         * BW_FLAG_RECIPROCAL: always), and BWH_NO_MIRROR */
    /* encode on a device instead of the host: NULL or "qemu" (the emulated
     * co-processor); the host then decodes and checks the payload */
    const char *device;
    const char *firmware;          /* NULL: the default image */
    double device_timeout;         /* seconds, 0: 120 */
    int drop_chunk;                /* tests: lose the first copy of a chunk, -1: none */
    uint64_t *device_instructions; /* out: the device's count for the encode */
} bwh_encode_opts_t;

/* Sets bwh_last_error(); returns -1. */
int bwh_fail(const char *fmt, ...);

/* k if scale is float32(10^-k), k = 1..9, else 0. */
int bwh_decimal_exponent(float scale);

/* Encodes float samples (NaN/Inf rejected). *out is allocated. The mapping
 * to integers is chosen from the mode:
 *   LOSSLESS   every value must be an integer multiple of `scale` (default 1)
 *   MAX_ERROR  scale = E / 3.5: integer bound 3 plus half a step of rounding
 *   BYTES      scale = max|x| / 2^20, fine enough to vanish under the budget
 * and the result is checked in float against the input. */
int bwh_encode_f32(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o, uint8_t **out,
                   size_t *out_len);

/* Encodes integer samples with scale 1 (or the given scale/offset bits). */
int bwh_encode_i32(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                   float scale, float offset, uint8_t **out, size_t *out_len);

/* Decodes a payload. *samples (allocated, may be NULL) receives the integer
 * samples and *values (allocated, may be NULL) the float values; a value
 * that float32 cannot hold is an error. Payloads that decode to more than
 * max_samples samples are refused before anything is allocated (0: the
 * default, BWH_MAX_SAMPLES_DEFAULT): a few bytes can describe gigabytes. */
#define BWH_MAX_SAMPLES_DEFAULT ((size_t)1 << 26) /* 256 MiB of float32 */
int bwh_decode_limit(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                     int32_t **samples, float **values);
/* bwh_decode_limit with the default limit */
int bwh_decode(const uint8_t *p, size_t len, bw_header_t *h, int32_t **samples, float **values);

/* Checks a payload as a receiver must before it stores and acknowledges it:
 * header, CRC, the sample limit (0: the default) and a full decode. */
int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h);

/* Float value of a header's scale / offset fields. */
float bwh_bits_to_float(uint32_t bits);
uint32_t bwh_float_to_bits(float f);

typedef struct {
    size_t n;
    size_t zero_ref;  /* samples whose reference is 0 (left out of rel. L1/L2) */
    double rel_l1;    /* percent, paper eq. 7 */
    double rel_l2;    /* percent, paper eq. 8 */
    double rmse;
    double max_abs;
    double psnr;      /* dB, peak = max |reference| */
} bwh_metrics_t;

void bwh_metrics(const float *ref, const float *test, size_t n, bwh_metrics_t *m);

const char *bwh_shape_name(unsigned shape);
const char *bwh_basis_name(unsigned basis);
const char *bwh_mode_name(unsigned mode);

#ifdef __cplusplus
}
#endif

#endif
