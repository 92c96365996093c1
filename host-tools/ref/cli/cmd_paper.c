/* bwref paper: the paper's experiments (filled in below). */
#include "bwref.h"

int bwref_cmd_paper(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return bwref_fail("paper", "not available");
}
