/* brdfwave grid: list the geodesic triangles of one level as CSV. */
#define _GNU_SOURCE /* getopt_long */

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "commands.h"
#include "geodesic.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

static void grid_usage(FILE *f)
{
    fprintf(f,
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
            "  -h, --help      show this help\n");
}

static int level_error(void)
{
    fprintf(stderr, "brdfwave grid: level must be 0..6\n");
    return 2;
}

/* Strict decimal 0..BWH_GRID_MAX_LEVEL; -1 otherwise. */
static int parse_level(const char *s)
{
    if (s == NULL || *s < '0' || *s > '9')
        return -1;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno != 0 || *end != '\0' || v < 0 || v > (long)BWH_GRID_MAX_LEVEL)
        return -1;
    return (int)v;
}

int bw_cmd_grid(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"level", required_argument, NULL, 'l'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    int level = -1;
    int have_level = 0;

    /* The dispatcher may already have run getopt on another argv; glibc
     * needs optind = 0 to drop its internal state. */
#ifdef __GLIBC__
    optind = 0;
#else
    optind = 1;
#endif
    opterr = 0;
    int opt;
    while ((opt = getopt_long(argc, argv, ":l:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'l':
            have_level = 1;
            level = parse_level(optarg);
            break;
        case 'h':
            grid_usage(stdout);
            return 0;
        case ':':
            if (optopt == 'l')
                return level_error();
            fprintf(stderr, "brdfwave grid: missing option argument\n");
            return 2;
        default:
            if (optopt != 0)
                fprintf(stderr, "brdfwave grid: unknown option '-%c' (try --help)\n",
                        optopt);
            else
                fprintf(stderr, "brdfwave grid: unknown option '%s' (try --help)\n",
                        argv[optind - 1]);
            return 2;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "brdfwave grid: unexpected argument '%s' (try --help)\n",
                argv[optind]);
        return 2;
    }
    if (!have_level || level < 0)
        return level_error();

    size_t n = bwh_grid_count((unsigned)level);
    double(*xyz)[3] = malloc(n * sizeof *xyz);
    double *sa = malloc(n * sizeof *sa);
    if (xyz == NULL || sa == NULL || bwh_grid_centres((unsigned)level, xyz, sa) != 0) {
        free(xyz);
        free(sa);
        fprintf(stderr, "brdfwave grid: out of memory\n");
        return 1;
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

    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "brdfwave grid: write error on standard output\n");
        return 1;
    }
    return 0;
}
