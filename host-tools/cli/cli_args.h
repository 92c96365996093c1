/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The options of every command, from one table: a wrapper around
 * getopt_long that fills the variables the table points to, checks every
 * value (cli_num.h) and names the offending option in its one-line usage
 * error, with the option the user probably meant:
 *
 *   brdfwave encode: unknown option '--levle' (did you mean '--level'?)
 *
 * --help and -h are added to every table: they print the command's help;
 * --version the program's version.
 *
 *   uint32_t level = 4;
 *   const char *out = NULL;
 *   const cli_opt_t opts[] = {
 *       {"level", 0, CLI_U32, .dest = &level, .lo = 0, .hi = 6},
 *       {"output", 'o', CLI_STRING, .dest = &out},
 *       {NULL}};
 *   int first, status;
 *   if (!cli_parse(argc, argv, opts, help, &first, &status))
 *       return status;
 *   // argv[first .. argc): the positional arguments
 */
#ifndef CLI_ARGS_H
#define CLI_ARGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    CLI_FLAG,     /* no value: *(int *)dest = 1 */
    CLI_STRING,   /* *(const char **)dest = the value */
    CLI_LIST,     /* repeatable: the values appended to a cli_list_t */
    CLI_U32,      /* *(uint32_t *)dest, an integer lo..hi (.hex: 0x... too) */
    CLI_REAL,     /* *(double *)dest, a number lo..hi */
    CLI_POSITIVE, /* *(double *)dest, a number > 0 and <= hi */
    CLI_CHOICE,   /* *(int *)dest = the index of the value in .choices */
    CLI_CALL,     /* .parse(value, dest) == 0; otherwise the usage error .what */
} cli_kind_t;

typedef struct {
    const char *name;  /* long name, without "--" (every option has one); NULL ends
                        * the table */
    char letter;       /* short option, 0: none */
    cli_kind_t kind;
    void *dest;
    double lo, hi;                 /* CLI_U32, CLI_REAL; CLI_POSITIVE: hi (0: none) */
    const char *const *choices;    /* CLI_CHOICE: NULL-terminated */
    int (*parse)(const char *value, void *dest); /* CLI_CALL */
    const char *what;  /* the usage error for a bad value (NULL: made from the kind) */
    int *seen;         /* not NULL: counts the times the option is given */
    int hex;           /* CLI_U32: 0x... accepted too */
} cli_opt_t;

/* the values of a CLI_LIST option: item[0 .. n), at most cap of them */
typedef struct {
    const char **item;
    int n, cap;
} cli_list_t;

/* Parses argv[1 ..] by opts (at most 60 options). Returns true when the
 * command goes on, with its positional arguments in argv[*first .. argc)
 * (getopt_long moves them behind the options; first NULL: the command takes
 * none, and one is a usage error); false when the command must return
 * *status: CLI_EXIT_OK after printing `help` to standard output,
 * CLI_EXIT_USAGE after a usage error (cli_errors.h). */
bool cli_parse(int argc, char **argv, const cli_opt_t *opts, const char *help, int *first,
               int *status);

/* a program's commands */
typedef struct {
    const char *name;
    int (*run)(int argc, char **argv); /* argv[0]: the command's name */
    const char *what;                  /* one line for the program's usage */
} cli_command_t;

/* Runs the command argv[1] of cmds[n] (cli_set_name(prog, its name) first)
 * and returns its status. "-h", "--help" and "help" print usage(stdout)
 * (status 0), "-V" and "--version" the version (status 0); no command prints
 * usage(stderr) (status 2); an unknown one is a usage error. */
int cli_dispatch(const char *prog, const cli_command_t *cmds, size_t n, int argc, char **argv,
                 void (*usage)(FILE *f));

#ifdef __cplusplus
}
#endif

#endif
