/* SPDX-License-Identifier: BSD-2-Clause */
/* Shape options to the library's shape (cli_shape.h). */
#include "cli_shape.h"

#include "bwh_error.h"
#include "cli_errors.h"

int cli_shape_get(const cli_shape_t *c, bwh_shape_t *s)
{
    *s = (bwh_shape_t)BWH_SHAPE_INIT;
    if (c->has_level)
        s->level = (int)c->level;
    if (c->has_level_in)
        s->level_in = (int)c->level_in;
    if (c->has_incoming)
        s->incoming = c->incoming;
    if (c->has_bands)
        s->bands = c->bands;
    return bwh_shape_check(s) != 0 ? cli_usage("%s", bwh_last_error()) : 0;
}
