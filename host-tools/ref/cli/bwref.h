/* SPDX-License-Identifier: BSD-2-Clause */
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
/* v as the 4 bytes of a little-endian float32 at p */
void bwref_put_f32(unsigned char *p, float v);

/* Options, numbers, exit statuses and error lines: the command line's own
 * modules (host-tools/cli/cli_args.h, cli_num.h, cli_errors.h), with the
 * program's name set by bwref's main or, for import-rgl, brdfwave's. */

#endif
