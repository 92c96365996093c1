/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The guarantee a payload was made under (docs/FORMAT.md, record 0x82):
 * what every decoded value x' promises about its input value x, in the
 * values' units. Written by the host's encoders, read back from a payload,
 * and checked against a decoded file.
 *
 *   kind       every sample
 *   none       nothing (a byte budget: the best the budget allows)
 *   exact      x' is x bit for bit (float32 input: signed zeros, subnormals,
 *              NaN payloads and infinities included; integer input: the integers)
 *   absolute   |x' - x| <= E
 *   relative   |x' - x| <= max(R |x|, F)           (F = 0: R |x|, so 0 stays 0)
 *   both       |x' - x| <= min(E, max(R |x|, F))   (the tighter of the two, as
 *              CCSDS 123.0-B-2 combines its absolute and relative limits)
 */
#ifndef BWH_GUARANTEE_H
#define BWH_GUARANTEE_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BWH_GUARANTEE_NONE = 0,
    BWH_GUARANTEE_EXACT = 1,
    BWH_GUARANTEE_ABSOLUTE = 2,
    BWH_GUARANTEE_RELATIVE = 3,
    BWH_GUARANTEE_BOTH = 4
} bwh_guarantee_kind_t;

typedef struct {
    int kind;             /* bwh_guarantee_kind_t */
    int recorded;         /* 1: the payload's record 0x82; 0: taken from its header (below) */
    int width;            /* record: 8 when a bound is float64, else 4; 0 unrecorded */
    double max_error;     /* E: absolute, both */
    double max_rel_error; /* R: relative, both */
    double rel_floor;     /* F: relative, both (0: none) */
} bwh_guarantee_t;

/* The guarantee of a payload: its record 0x82, or without one what its
 * header says (lossless: exact; max-error: absolute E x |scale|, the bound
 * on the coded samples, which says nothing of how the encoder mapped its
 * input to samples; byte budget, fixed step: none). bwh_guarantee_read
 * checks the header and the CRC first; bwh_guarantee_of takes a header
 * already read. 0, or -1 (bwh_last_error) for a bad payload or record. */
int bwh_guarantee_read(const uint8_t *p, size_t len, bwh_guarantee_t *g);
int bwh_guarantee_of(const uint8_t *p, const bw_header_t *h, bwh_guarantee_t *g);

/* Record 0x82 of g (its data, type and length included) at out (NULL: only
 * counts); returns its length. Each bound is written as float32 when that
 * holds it exactly, else as float64; a floor of 0 is left out. */
size_t bwh_guarantee_record(const bwh_guarantee_t *g, uint8_t *out);
/* Parses the data of record 0x82. 0, or -1 when malformed. */
int bwh_guarantee_parse(const uint8_t *data, size_t n, bwh_guarantee_t *g);

/* The bound of one input value x (a finite value; <0: none, for kind none). */
double bwh_guarantee_bound(const bwh_guarantee_t *g, double x);
/* 1 when the decoded value v keeps the guarantee for the input value x:
 * exact compares the bits; every other kind keeps non-finite inputs bit for
 * bit too (a lossy mode refuses them, so it never has to). */
int bwh_guarantee_holds(const bwh_guarantee_t *g, float x, float v);
/* Checks decoded values v[n] against the input x[n]: the number of samples
 * that break the guarantee, and the first of them in *first (may be NULL). */
size_t bwh_guarantee_check(const bwh_guarantee_t *g, const float *x, const float *v, size_t n,
                           size_t *first);

/* The kind's word: none, exact, absolute, relative, both. */
const char *bwh_guarantee_name(int kind);
/* The rule as text, e.g. "|x' - x| <= max(0.001 |x|, 1e-06)". */
void bwh_guarantee_rule(const bwh_guarantee_t *g, char *buf, size_t cap);
/* v in the fewest significant digits that read back as v */
void bwh_shortest(double v, char *buf, size_t cap);

#ifdef __cplusplus
}
#endif

#endif
