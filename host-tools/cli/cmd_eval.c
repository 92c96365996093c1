/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave eval: f(wi, wo, lambda) of a BRDF payload at direction pairs,
 * decoding only the incoming directions they read. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdf_eval.h"
#include "bwr_project.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "commands.h"

static const char eval_help[] =
    "usage: brdfwave eval -i IN.bwv [--wavelength NM | --band K]\n"
    "                     (--at THETA_I,PHI_I,THETA_O,PHI_O ... | --directions FILE)\n"
    "\n"
    "Prints f(wi, wo) of a BRDF (or reflectance) payload at direction pairs, one\n"
    "value per line (%.9g; nan below the horizon), straight from the payload:\n"
    "only the incoming directions the pairs read are decoded (a full BRDF's\n"
    "triangle holding wi, an isotropic BRDF's two incidences about it; with\n"
    "segments only the segments that hold them; a payload coded with the\n"
    "reciprocity step, or keeping float bits in a tail, is decoded whole). f is\n"
    "interpolated as the renderer does: barycentric over the outgoing triangle\n"
    "centres, linear in the incidence angle between tables, a B-spline over\n"
    "the bands.\n"
    "  --at TI,PI,TO,PO   one pair: zenith and azimuth of wi, then of wo, in\n"
    "                     degrees (up to 256 of them; more with --directions)\n"
    "  --directions FILE  pairs, one a line, the same four numbers separated by\n"
    "                     spaces or commas ('-': standard input; '#' starts a\n"
    "                     comment)\n"
    "  --wavelength NM    f at that wavelength (the payload's wavelength range)\n"
    "  --band K           f of band K; without either, the mean over the bands\n";

/* Appends a pair (four angles) to the growing arrays. 0, or -1. */
static int add_pair(const double a[4], double **wi, double **wo, size_t *n, size_t *cap)
{
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 64;
        double *i2 = realloc(*wi, c * 3 * sizeof **wi);
        if (!i2)
            return -1;
        *wi = i2;
        double *o2 = realloc(*wo, c * 3 * sizeof **wo);
        if (!o2)
            return -1;
        *wo = o2;
        *cap = c;
    }
    bwr_dir_from_degrees(a[0], a[1], *wi + 3 * *n);
    bwr_dir_from_degrees(a[2], a[3], *wo + 3 * *n);
    (*n)++;
    return 0;
}

static int angles_ok(const double a[4])
{
    return a[0] >= 0 && a[0] <= 180 && a[2] >= 0 && a[2] <= 180 && fabs(a[1]) <= 360 &&
           fabs(a[3]) <= 360;
}

/* The pairs of a file, one a line. 0, or a failure status. */
static int read_pairs(const char *path, double **wi, double **wo, size_t *n, size_t *cap)
{
    FILE *f = strcmp(path, "-") ? fopen(path, "r") : stdin;
    if (!f)
        return cli_fail("%s: %s", path, strerror(errno));
    char line[512];
    unsigned long ln = 0;
    int rc = 0;
    while (!rc && fgets(line, sizeof line, f)) {
        ln++;
        char *h = strchr(line, '#');
        if (h)
            *h = 0;
        for (char *c = line; *c; c++)
            if (*c == ',')
                *c = ' ';
        double a[4];
        char extra;
        int k = sscanf(line, "%lf %lf %lf %lf %c", &a[0], &a[1], &a[2], &a[3], &extra);
        if (k <= 0 && strspn(line, " \t\r\n") == strlen(line))
            continue;
        if (k != 4 || !angles_ok(a))
            rc = cli_fail("%s:%lu: four angles in degrees (theta_i phi_i theta_o phi_o)", path,
                          ln);
        else if (add_pair(a, wi, wo, n, cap) != 0)
            rc = cli_fail("out of memory");
    }
    if (!rc && ferror(f))
        rc = cli_fail("%s: read error", path);
    if (f != stdin)
        fclose(f);
    return rc;
}

int bw_cmd_eval(int argc, char **argv)
{
    const char *inp = NULL, *dirs = NULL;
    double lambda = 0;
    uint32_t band = 0;
    int has_lambda = 0, has_band = 0;
    const char *at_items[256];
    cli_list_t at = {at_items, 0, 256};
    const cli_opt_t opts[] = {{"input", 'i', CLI_STRING, .dest = &inp},
                              {"at", 0, CLI_LIST, .dest = &at},
                              {"directions", 0, CLI_STRING, .dest = &dirs},
                              {"wavelength", 0, CLI_REAL, .dest = &lambda, .lo = -1e9, .hi = 1e9,
                               .seen = &has_lambda},
                              {"band", 0, CLI_U32, .dest = &band, .hi = 65534, .seen = &has_band},
                              {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, eval_help, NULL, &st))
        return st;
    double *wi = NULL, *wo = NULL;
    size_t n = 0, cap = 0;
    int rc = 0;
    if (!inp)
        rc = cli_usage("needs -i IN.bwv");
    else if (has_lambda && has_band)
        rc = cli_usage("give --wavelength or --band, not both");
    else if (!at.n && !dirs)
        rc = cli_usage("needs --at TI,PI,TO,PO or --directions FILE");
    for (int k = 0; !rc && k < at.n; k++) {
        double a[4];
        size_t got = 0;
        if (cli_real_list(at.item[k], -360, 360, a, 4, &got) != 0 || got != 4 || !angles_ok(a))
            rc = cli_usage("--at %s: four angles in degrees, THETA_I,PHI_I,THETA_O,PHI_O",
                           at.item[k]);
        else if (add_pair(a, &wi, &wo, &n, &cap) != 0)
            rc = cli_fail("out of memory");
    }
    if (!rc && dirs)
        rc = read_pairs(dirs, &wi, &wo, &n, &cap);
    uint8_t *p = NULL;
    size_t len = 0;
    double *out = NULL, *lam = NULL;
    if (!rc && bwh_read_file(inp, &p, &len) != 0)
        rc = cli_fail("%s", bwh_last_error());
    if (!rc && (!(out = malloc((n ? n : 1) * sizeof *out)) ||
                (has_lambda && !(lam = malloc((n ? n : 1) * sizeof *lam)))))
        rc = cli_fail("out of memory");
    for (size_t j = 0; !rc && lam && j < n; j++)
        lam[j] = lambda;
    if (!rc && n &&
        bwh_payload_eval(p, len, n, wi, wo, lam, has_band ? (long)band : -1, out) != 0)
        rc = cli_fail("%s: %s", inp, bwh_last_error());
    for (size_t j = 0; !rc && j < n; j++)
        printf("%.9g\n", out[j]);
    free(p);
    free(wi);
    free(wo);
    free(out);
    free(lam);
    if (!rc && (fflush(stdout) != 0 || ferror(stdout)))
        rc = cli_fail("write error on standard output");
    return rc ? rc : CLI_EXIT_OK;
}
