/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Types of the strip coder's state, so that callers can own it (bw_ctx_t
 * and the streaming encoder's context embed one). The functions are in
 * bw_strip_coder.c, declared in bw_strip_coder.h.
 */
#ifndef BW_CODER_H
#define BW_CODER_H

#include <stdbool.h>
#include <stdint.h>

#include "bw_rc.h"
#include "bw_rice.h"

#define BW_CODER_CLASSES 12u /* 3 * spectral class (0..3) + direction class (0..2) */
#define BW_CODER_NB_CTX 8u

/* the body's coders: the binary range coder, Rice strips (BW_FLAG_RICE), the
 * multi-symbol range coder (BW_FLAG_MS), the static-table coder (both flags) */
enum { BW_CODER_RANGE = 0, BW_CODER_RICE = 1, BW_CODER_MS = 2, BW_CODER_TAB = 3 };

/* The binary range coder's adaptive models, 7,302 bytes. */
typedef struct {
    bw_prob_t present[BW_CODER_CLASSES][2];
    bw_prob_t valid[BW_CODER_CLASSES][2][6]; /* [previous bit][above bit + 2 parent] */
    bw_prob_t mag[BW_CODER_CLASSES][BW_CODER_NB_CTX][32];
    bw_prob_t mant[BW_CODER_CLASSES][32];
    bw_prob_t sign[27]; /* [left + 3 parent + 9 above], each 0 none/zero, 1 +, 2 - */
} bw_rc_models_t;

/* The multi-symbol coder's models (BW_FLAG_MS): per class and neighbourhood
 * the frequencies of an element's bit length (0: zero; BW_MS_ESC: that or
 * more), the bit below the leading one, the signs. */
typedef struct {
    bw_prob_t present[BW_CODER_CLASSES][2];
    bw_prob_t valid[BW_CODER_CLASSES][2][6]; /* as the binary coder's */
    bw_ms_model_t e[BW_CODER_CLASSES][BW_CODER_NB_CTX]; /* e - 1 of a non-zero element */
    bw_prob_t sign[27];
} bw_ms_models_t;

/* The static-table coder's tables (BW_FLAG_RICE | BW_FLAG_MS, bw_tab.c),
 * 7,128 bytes: per class and neighbourhood (BW_TAB_BINS) the cumulative
 * frequencies, in 1/4096, of its BW_TAB_SYMS symbols; in the encoder first
 * its counts. */
#define BW_TAB_BINS 11u
#define BW_TAB_SYMS 26u
#define BW_TAB_CTX (BW_CODER_CLASSES * BW_TAB_BINS)
typedef struct {
    uint16_t cum[BW_TAB_CTX][BW_TAB_SYMS + 1u];
} bw_tab_models_t;

typedef union {
    bw_rc_models_t rc;
    bw_ms_models_t ms;
    bw_tab_models_t tab;
} bw_models_t;

/* What a strip leaves for the next one's contexts. */
typedef struct {
    union {
        uint8_t e_above[32]; /* bit lengths of its elements (0: zero) */
        uint32_t e_above_w[8]; /* the same, cleared four at a time */
    };
    uint32_t prev_mask;  /* its valid bits (0: absent) */
    unsigned e_left;     /* bit length of its last element */
} bw_strip_state_t;

/* The strip encoder, fed one coefficient at a time. */
typedef struct {
    unsigned coder; /* BW_CODER_RANGE, _RICE (re) or _MS (rc + m) */
    bw_rice_enc_t re;
    bw_rc_enc_t rc;
    bw_models_t m;
    int32_t v[32];
    uint8_t cls[32];
    uint8_t pe[32]; /* bit lengths of the parent and of the same band in */
    uint8_t pv[32]; /* the previous vector (0xFF: none)                   */
    uint8_t ps[32]; /* their signs' part of the sign model (sign_ctx_up)    */
    unsigned cnt;
    uint32_t mask; /* the non-zero values among those put (bit b: v[b]) */
    bw_strip_state_t st;
} bw_strip_enc_t;

#endif
