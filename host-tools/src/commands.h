/* brdfwave host tool: subcommand entry points. Each takes the subcommand's
 * own argv (argv[0] is the subcommand name) and returns the exit status. */
#ifndef BW_COMMANDS_H
#define BW_COMMANDS_H

int bw_cmd_encode(int argc, char **argv);
int bw_cmd_decode(int argc, char **argv);
int bw_cmd_info(int argc, char **argv);
int bw_cmd_compare(int argc, char **argv);
int bw_cmd_grid(int argc, char **argv);
int bw_cmd_synth(int argc, char **argv);
int bw_cmd_receive(int argc, char **argv);
int bw_cmd_render(int argc, char **argv);
int bw_cmd_acquire(int argc, char **argv);
/* `bwref import-rgl` of the reference model (host-tools/ref/cli/cmd_rgl.c),
 * under the main command */
int bw_cmd_import_rgl(int argc, char **argv);

#endif
