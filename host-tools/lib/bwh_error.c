/* SPDX-License-Identifier: BSD-2-Clause */
/* The library's last error (bwh_error.h). */
#include "bwh_error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static _Thread_local char last_error[512];

const char *bwh_last_error(void) { return last_error; }

int bwh_fail(const char *fmt, ...)
{
    char tmp[sizeof last_error];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tmp, sizeof tmp, fmt, ap); /* the message may quote the last one */
    va_end(ap);
    memcpy(last_error, tmp, sizeof tmp);
    return -1;
}
