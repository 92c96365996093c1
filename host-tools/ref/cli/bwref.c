/*
 * bwref: the float reference model of Claustres, Paulin and Boucher (2003)
 * on the host: coefficient dumps for cross-checks and the paper's tables.
 */
#include "bwref.h"
#include "cli_errors.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fputs("usage: bwref COMMAND [options]\n"
          "\n"
          "Float reference model of the paper (Claustres, Paulin, Boucher 2003).\n"
          "\n"
          "  wavedec   1-D wavelet coefficients of a signal for every basis\n"
          "  ratios    compress a data set at given ratios or byte budgets (CSV)\n"
          "  import-rgl  sample a measured RGL BRDF on the geodesic grid\n"
          "  project   scattered measured directions onto the geodesic grid\n"
          "\n"
          "bwref COMMAND --help for the options of a command.\n",
          f);
}

static const struct {
    const char *name;
    int (*run)(int, char **);
} commands[] = {
    {"wavedec", bwref_cmd_wavedec},
    {"ratios", bwref_cmd_ratios},
    {"import-rgl", bwref_cmd_import_rgl},
    {"project", bwref_cmd_project},
};

int main(int argc, char **argv)
{
    cli_set_name("bwref", "");
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            cli_set_name("bwref", commands[i].name);
            return commands[i].run(argc - 1, argv + 1);
        }
    return cli_usage("unknown command '%s'", argv[1]);
}
