/* brdfwave: the command line. */
#define _DEFAULT_SOURCE
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "bwh_device.h"
#include "bwref.h"
#include "commands.h"

static const struct {
    const char *name;
    int (*run)(int, char **);
    const char *what;
} commands[] = {
    {"encode", bw_cmd_encode, "compress a measurement into a payload"},
    {"decode", bw_cmd_decode, "decode a payload to raw samples"},
    {"info", bw_cmd_info, "print a payload's header"},
    {"compare", bw_cmd_compare, "error metrics between two raw sample files"},
    {"grid", bw_cmd_grid, "print the geodesic triangle grid as CSV"},
    {"synth", bw_cmd_synth, "sample an analytic BRDF (Phong, Ward) on the grid"},
    {"receive", bw_cmd_receive, "store payloads arriving on a serial port"},
    {"acquire", bw_cmd_acquire, "store payloads offered over I2C on a data-ready edge"},
    {"import-rgl", bw_cmd_import_rgl, "sample a measured RGL BRDF on the grid"},
    {"render", bw_cmd_render, "path-trace a scene, comparing sampling strategies"},
};

int bw_cmd_import_rgl(int argc, char **argv)
{
    bwref_progname = "brdfwave";
    return bwref_cmd_import_rgl(argc, argv);
}

static void usage(FILE *f)
{
    fputs("usage: brdfwave COMMAND [options]   (brdfwave COMMAND --help)\n\ncommands:\n", f);
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].what);
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
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        if (!strcmp(argv[1], commands[i].name))
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "brdfwave: unknown command '%s' (see 'brdfwave --help')\n", argv[1]);
    return 2;
}
