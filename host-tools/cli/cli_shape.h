/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The shape options of the commands (--level L, --incoming N, --level-in Li,
 * --bands B) as table entries (cli_args.h), handed to the library's one rule
 * (bwh_shape.h) that turns them into dimensions.
 */
#ifndef CLI_SHAPE_H
#define CLI_SHAPE_H

#include <stdint.h>

#include "bw_codec.h"
#include "bwh_shape.h"
#include "cli_args.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint32_t level, level_in, incoming, bands;
    int has_level, has_level_in, has_incoming, has_bands;
} cli_shape_t;

/* --level and --level-in */
#define CLI_SHAPE_LEVELS(s)                                                                    \
    {"level", 0, CLI_U32, .dest = &(s)->level, .hi = BW_MAX_LEVEL, .seen = &(s)->has_level},   \
    {"level-in", 0, CLI_U32, .dest = &(s)->level_in, .hi = BW_MAX_LEVEL,                       \
     .seen = &(s)->has_level_in}
/* --incoming N */
#define CLI_SHAPE_INCOMING(s)                                                                  \
    {"incoming", 0, CLI_U32, .dest = &(s)->incoming, .lo = 1, .hi = BW_MAX_N_IN,               \
     .seen = &(s)->has_incoming}
/* --bands B */
#define CLI_SHAPE_BANDS(s)                                                                     \
    {"bands", 0, CLI_U32, .dest = &(s)->bands, .lo = 1, .hi = BW_MAX_BANDS,                    \
     .seen = &(s)->has_bands}

/* The options given as the library's shape (what is not given: none, bands
 * 0), checked against each other (bwh_shape_check). 0, or CLI_EXIT_USAGE
 * after printing the usage error. */
int cli_shape_get(const cli_shape_t *c, bwh_shape_t *s);

#ifdef __cplusplus
}
#endif

#endif
