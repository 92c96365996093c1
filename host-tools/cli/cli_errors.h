/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * How a command ends: its exit status and its one line on standard error.
 *
 *   0  success
 *   1  the command ran and failed (a missing or bad input file, a payload
 *      that does not decode, a device that does not answer, ...)
 *   2  the command line is wrong (an unknown option, a missing or bad
 *      value, options that exclude each other)
 *
 * Every message is one line, "PROG COMMAND: what went wrong"; usage errors
 * point to "PROG COMMAND --help".
 */
#ifndef CLI_ERRORS_H
#define CLI_ERRORS_H

#ifdef __cplusplus
extern "C" {
#endif

/* CLI_EXIT_INCOMPLETE: the job was done with parts of its input lost (a
 * damaged payload decoded in part) */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAIL = 1, CLI_EXIT_USAGE = 2, CLI_EXIT_INCOMPLETE = 3 };

/* The names in every message: the program ("brdfwave", "bwref") and the
 * command running ("encode"). The strings must outlive the command. */
void cli_set_name(const char *prog, const char *cmd);
const char *cli_prog(void);
const char *cli_cmd(void);

/* "PROG CMD: message"; returns CLI_EXIT_FAIL. */
__attribute__((format(printf, 1, 2))) int cli_fail(const char *fmt, ...);

/* "PROG CMD: message (see 'PROG CMD --help')"; returns CLI_EXIT_USAGE. */
__attribute__((format(printf, 1, 2))) int cli_usage(const char *fmt, ...);

/* "PROG CMD: message", a usage error that says itself what to do (a
 * suggestion); returns CLI_EXIT_USAGE. */
__attribute__((format(printf, 1, 2))) int cli_usage_plain(const char *fmt, ...);

#ifdef __cplusplus
}
#endif

#endif
