/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * bwref: the float reference model of Claustres, Paulin and Boucher (2003)
 * on the host: coefficient dumps for cross-checks and the paper's tables.
 */
#include "bwref.h"
#include "cli_args.h"

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

static const cli_command_t commands[] = {
    {"wavedec", bwref_cmd_wavedec, NULL},
    {"ratios", bwref_cmd_ratios, NULL},
    {"import-rgl", bwref_cmd_import_rgl, NULL},
    {"project", bwref_cmd_project, NULL},
};

int main(int argc, char **argv)
{
    return cli_dispatch("bwref", commands, sizeof commands / sizeof *commands, argc, argv, usage);
}
