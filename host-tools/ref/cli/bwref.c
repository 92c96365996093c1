/*
 * bwref: the float reference model of Claustres, Paulin and Boucher (2003)
 * on the host: coefficient dumps for cross-checks and the paper's tables.
 */
#include "bwref.h"

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

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "wavedec") == 0)
        return bwref_cmd_wavedec(argc - 1, argv + 1);
    if (strcmp(argv[1], "ratios") == 0)
        return bwref_cmd_ratios(argc - 1, argv + 1);
    if (strcmp(argv[1], "import-rgl") == 0)
        return bwref_cmd_import_rgl(argc - 1, argv + 1);
    if (strcmp(argv[1], "project") == 0)
        return bwref_cmd_project(argc - 1, argv + 1);
    fprintf(stderr, "bwref: unknown command '%s' (see --help)\n", argv[1]);
    return 2;
}
