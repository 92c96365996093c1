/* SPDX-License-Identifier: BSD-2-Clause */
/* Exit statuses and error lines of the commands (cli_errors.h). */
#include "cli_errors.h"

#include <stdarg.h>
#include <stdio.h>

static const char *prog = "brdfwave", *cmd = "";

void cli_set_name(const char *p, const char *c)
{
    prog = p;
    cmd = c;
}

const char *cli_prog(void) { return prog; }

const char *cli_cmd(void) { return cmd; }

static void line(const char *fmt, va_list ap, int usage)
{
    fprintf(stderr, "%s%s%s: ", prog, *cmd ? " " : "", cmd);
    vfprintf(stderr, fmt, ap);
    if (usage)
        fprintf(stderr, " (see '%s%s%s --help')", prog, *cmd ? " " : "", cmd);
    fputc('\n', stderr);
}

int cli_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    line(fmt, ap, 0);
    va_end(ap);
    return CLI_EXIT_FAIL;
}

int cli_usage(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    line(fmt, ap, 1);
    va_end(ap);
    return CLI_EXIT_USAGE;
}

int cli_usage_plain(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    line(fmt, ap, 0);
    va_end(ap);
    return CLI_EXIT_USAGE;
}
