/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave: the commands. Each takes its own argv (argv[0] is the command's
 * name) and returns the exit status (cli_errors.h: 0, 1 or 2). */
#ifndef BW_COMMANDS_H
#define BW_COMMANDS_H

int bw_cmd_encode(int argc, char **argv);
int bw_cmd_decode(int argc, char **argv);
int bw_cmd_info(int argc, char **argv);
int bw_cmd_compare(int argc, char **argv);
int bw_cmd_grid(int argc, char **argv);
int bw_cmd_synth(int argc, char **argv);
int bw_cmd_receive(int argc, char **argv);
int bw_cmd_acquire(int argc, char **argv);
int bw_cmd_render(int argc, char **argv);
int bw_cmd_plot(int argc, char **argv);
int bw_cmd_eval(int argc, char **argv);

#endif
