/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave: the command line. Finds the command and runs it. */
#define _DEFAULT_SOURCE /* readlink */
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "bwh_device.h"
#include "bwref.h"
#include "cli_args.h"
#include "commands.h"

static const cli_command_t commands[] = {
    {"encode", bw_cmd_encode, "compress a measurement into a payload"},
    {"decode", bw_cmd_decode, "decode a payload to raw samples"},
    {"info", bw_cmd_info, "print a payload's header"},
    {"eval", bw_cmd_eval, "f(wi, wo, lambda) of a BRDF payload at direction pairs"},
    {"compare", bw_cmd_compare, "error metrics between two raw sample files"},
    {"grid", bw_cmd_grid, "print the geodesic triangle grid as CSV"},
    {"synth", bw_cmd_synth, "sample an analytic BRDF (Phong, Ward) on the grid"},
    {"receive", bw_cmd_receive, "store payloads arriving on a serial port"},
    {"acquire", bw_cmd_acquire, "store payloads offered over I2C on a data-ready edge"},
    /* the reference model's importer (host-tools/ref/cli/cmd_rgl.c), also `bwref import-rgl` */
    {"import-rgl", bwref_cmd_import_rgl, "sample a measured RGL BRDF on the grid"},
    {"render", bw_cmd_render, "path-trace a scene, comparing sampling strategies"},
    {"plot", bw_cmd_plot, "PNG pictures: hemisphere map, spectra, rate-distortion curve"},
};

static void usage(FILE *f)
{
    fputs("usage: brdfwave COMMAND [options]   (brdfwave COMMAND --help)\n"
          "       brdfwave --version\n\ncommands:\n",
          f);
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].what);
    fputs("\nexit status: 0 success; 1 the command failed (one line on standard error says\n"
          "why: a bad input file, a payload that does not decode, a device that does not\n"
          "answer); 2 a usage error (an unknown option, a bad or missing value).\n",
          f);
}

/* the library looks for the device images beside this program */
static void tell_the_library_where_we_are(void)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return;
    exe[n] = 0;
    char *slash = strrchr(exe, '/');
    if (slash)
        *slash = 0;
    bwh_device_set_program_dir(exe);
}

int main(int argc, char **argv)
{
    tell_the_library_where_we_are();
    return cli_dispatch("brdfwave", commands, sizeof commands / sizeof *commands, argc, argv,
                        usage);
}
