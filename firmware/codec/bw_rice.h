/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Adaptive Rice coding of strips of 32 coefficients (the fast coder).
 *
 * An alternative to the range coder for the body of a payload (header flag
 * BW_FLAG_RICE, see docs/FORMAT.md), built for instruction count on a small
 * core: every strip chooses its own code from the strip's statistics, so
 * there is no per-symbol adaptation and no multiplication per value.
 *
 * Bits are packed MSB first (the first bit of the body is bit 7 of byte 0).
 * A strip starts with its mode, coded as the difference to the previous
 * strip's mode (0 before the first strip): zigzag(delta) in unary (zeros, then
 * a one), or after 15 zeros the mode itself in 6 bits. Modes:
 *   0      zero strip: nothing follows
 *   1      sparse strip: a 2-bit magnitude parameter km, a 3-bit gap
 *          parameter kg, then for every non-zero value the number of zeros
 *          before it (Rice kg), |v| - 1 (Rice km) and the sign bit; the
 *          strip ends after a gap that reaches its last element, coded as
 *          one more gap (zeros to the end, Rice kg) when the strip does not
 *          end on a non-zero value
 *   2 + k  dense strip: every value as zigzag(v) = 2v (v >= 0) or -2v - 1,
 *          Rice parameter k (k = 0..31)
 * A Rice code of u with parameter k is q = u >> k zeros, a one, then the k
 * low bits of u; a quotient of 16 or more is sent as 16 zeros followed by u
 * in 32 bits.
 */
#ifndef BW_RICE_H
#define BW_RICE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Bit writer: MSB first into a caller buffer, a 32-bit word at a time;
 * out == NULL counts only. */
typedef struct {
    uint32_t buf;  /* its low 32 - left bits are pending */
    unsigned left; /* free bits in buf, 1..32 */
    uint8_t *out;  /* NULL: count only */
    size_t cap;
    size_t pos;
    bool overflow;
} bw_bitw_t;

/* The state of the Rice strip encoder. */
typedef struct {
    bw_bitw_t w;
    unsigned mode; /* of the previous strip */
} bw_rice_enc_t;

typedef struct {
    uint64_t acc; /* the next nb bits, MSB aligned */
    unsigned nb;
    const uint8_t *in;
    size_t len;
    size_t pos;
    bool overrun; /* read past the end of the input */
} bw_bitr_t;

typedef struct {
    bw_bitr_t r;
    unsigned mode;
} bw_rice_dec_t;

#define BW_RICE_STRIP_MAX 32u

void bw_rice_enc_init(bw_rice_enc_t *e, uint8_t *out, size_t cap);
/* Codes one strip of cnt (1..BW_RICE_STRIP_MAX) values. */
void bw_rice_enc_strip(bw_rice_enc_t *e, const int32_t *v, unsigned cnt);
/* Pads to a byte; returns the number of bytes produced. */
size_t bw_rice_enc_finish(bw_rice_enc_t *e);

void bw_rice_dec_init(bw_rice_dec_t *d, const uint8_t *in, size_t len);
/* Decodes one strip of cnt values; false if the data is not a valid strip
 * (or runs past the end of the input). */
bool bw_rice_dec_strip(bw_rice_dec_t *d, int32_t *v, unsigned cnt);

#endif
