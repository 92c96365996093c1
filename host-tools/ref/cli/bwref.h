/* bwref: command line of the float reference model. */
#ifndef BWREF_H
#define BWREF_H

#include <stddef.h>

int bwref_cmd_wavedec(int argc, char **argv);
int bwref_cmd_ratios(int argc, char **argv);
int bwref_cmd_import_rgl(int argc, char **argv);
int bwref_cmd_project(int argc, char **argv);

/* Reads whitespace-separated numbers (text) or raw float32 into *out. */
int bwref_read_text(const char *path, double **out, size_t *n);
int bwref_read_f32(const char *path, double **out, size_t *n);
/* "PROG CMD: message" on stderr (PROG = bwref_progname); returns 2. */
int bwref_fail(const char *cmd, const char *fmt, ...);

/* Program name in error and usage lines: "bwref", or "brdfwave" when the
 * command runs as a brdfwave subcommand. */
extern const char *bwref_progname;

#endif
