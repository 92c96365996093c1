/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave grid: the geodesic triangles of one level as CSV. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli_args.h"
#include "cli_errors.h"
#include "commands.h"
#include "geodesic.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

static const char grid_help[] =
    "usage: brdfwave grid --level L\n"
    "\n"
    "Print the geodesic hemisphere triangles of level L (0..6) as CSV, one\n"
    "row per triangle in codec index order:\n"
    "  index,theta_deg,phi_deg,x,y,z,solid_angle_sr\n"
    "(x, y, z) is the triangle's direction, theta = acos(z) and\n"
    "phi = atan2(y, x) in [0, 360).\n"
    "\n"
    "options:\n"
    "  -l, --level L   subdivision level, 0..6 (4 * 4^L triangles)\n"
    "  -h, --help      show this help\n";

int bw_cmd_grid(int argc, char **argv)
{
    uint32_t level = 0;
    int has_level = 0;
    const cli_opt_t opts[] = {
        {"level", 'l', CLI_U32, .dest = &level, .hi = BWH_GRID_MAX_LEVEL, .seen = &has_level},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, grid_help, NULL, &st))
        return st;
    if (!has_level)
        return cli_usage("needs --level L (0..6)");

    size_t n = bwh_grid_count(level);
    double(*xyz)[3] = malloc(n * sizeof *xyz);
    double *sa = malloc(n * sizeof *sa);
    if (xyz == NULL || sa == NULL || bwh_grid_centres(level, xyz, sa) != 0) {
        free(xyz);
        free(sa);
        return cli_fail("out of memory");
    }

    printf("index,theta_deg,phi_deg,x,y,z,solid_angle_sr\n");
    for (size_t i = 0; i < n; i++) {
        double x = xyz[i][0], y = xyz[i][1], z = xyz[i][2];
        double theta = acos(z > 1.0 ? 1.0 : (z < -1.0 ? -1.0 : z)) * RAD2DEG;
        double phi = atan2(y, x) * RAD2DEG;
        if (phi < 0.0)
            phi += 360.0;
        if (phi >= 360.0) /* a tiny negative angle rounds up to 360 */
            phi = 0.0;
        /* + 0.0 turns a negative zero into a plain one for the CSV. */
        printf("%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", i, theta + 0.0, phi + 0.0, x + 0.0,
               y + 0.0, z + 0.0, sa[i]);
    }
    free(xyz);
    free(sa);

    if (fflush(stdout) != 0 || ferror(stdout))
        return cli_fail("write error on standard output");
    return CLI_EXIT_OK;
}
