/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * bwref project: scattered measurements (CSV theta_deg,phi_deg,value[,...])
 * onto the geodesic grid (bwr_project.h), raw float32 in grid order.
 */
#define _POSIX_C_SOURCE 200809L /* getline */

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_project.h"
#include "bwref.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "bwr_geodesic.h"

#define PROJECT_MAX_COLS 4096

static const char project_help[] =
    "usage: bwref project -i IN.csv -o OUT.f32 [--level L] [--k K]\n"
    "\n"
    "Projects measurements at scattered directions onto the geodesic grid of\n"
    "level L (default 4, 4*4^L triangles): every triangle takes the value\n"
    "interpolated at its centre by a local modified Shepard scheme (Franke and\n"
    "Little) over the K measured directions nearest by angle (default 8,\n"
    "at most 64); constants are reproduced exactly.\n"
    "\n"
    "IN.csv: one measurement per line, theta_deg,phi_deg,value (theta from the\n"
    "normal, 0..90; phi from x towards y); more value columns are bands\n"
    "(a spectrum), the same number on every line. A first line that is not\n"
    "numeric (a header), blank lines and lines starting with # are skipped.\n"
    "OUT.f32: raw little-endian float32, [triangle][band] in grid order\n"
    "(the outgoing layout of `brdfwave synth`).\n";
_Static_assert(BWR_PROJECT_K_DEFAULT == 8 && BWR_PROJECT_K_MAX == 64, "the help states K's range");

/* Splits a line at commas into numbers; the count, or -1 if a field is not
 * a number, -2 if there are too many. */
static long parse_row(char *line, double *v, size_t cap)
{
    size_t n = 0;
    char *p = line;
    for (;;) {
        char *end;
        while (*p == ' ' || *p == '\t')
            p++;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno == ERANGE)
            return -1;
        p = end;
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
            p++;
        if (n == cap)
            return -2;
        v[n++] = x;
        if (*p == '\0')
            return (long)n;
        if (*p != ',')
            return -1;
        p++;
    }
}

static int blank(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    return *s == '\0';
}

int bwref_cmd_project(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    uint32_t level = 4, k = BWR_PROJECT_K_DEFAULT;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &in},
        {"output", 'o', CLI_STRING, .dest = &out},
        {"level", 0, CLI_U32, .dest = &level, .lo = 0, .hi = BWR_GRID_MAX_LEVEL},
        {"k", 0, CLI_U32, .dest = &k, .lo = 1, .hi = BWR_PROJECT_K_MAX},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, project_help, NULL, &st))
        return st;
    if (in == NULL || out == NULL)
        return cli_usage("-i IN.csv and -o OUT.f32 are required");

    FILE *f = fopen(in, "r");
    if (f == NULL)
        return cli_fail("cannot open '%s': %s", in, strerror(errno));
    size_t cap = 0, n = 0, cols = 0, lineno = 0, bands = 0;
    double(*dir)[3] = NULL, *val = NULL, *row = malloc(PROJECT_MAX_COLS * sizeof *row);
    char *line = NULL;
    size_t linecap = 0;
    int rc = CLI_EXIT_FAIL, seen_data = 0;
    unsigned char *buf = NULL;
    double *grid = NULL;
    if (row == NULL) {
        rc = cli_fail("out of memory");
        goto done;
    }
    while (getline(&line, &linecap, f) != -1) {
        lineno++;
        if (blank(line) || line[strspn(line, " \t")] == '#')
            continue;
        long c = parse_row(line, row, PROJECT_MAX_COLS);
        if (c == -1 && !seen_data && lineno == 1)
            continue; /* header */
        seen_data = 1;
        if (c == -2) {
            rc = cli_fail("%s:%zu: more than %d columns", in, lineno,
                            PROJECT_MAX_COLS);
            goto done;
        }
        if (c < 3) {
            rc = cli_fail("%s:%zu: expected theta_deg,phi_deg,value[,...]", in,
                            lineno);
            goto done;
        }
        if (cols == 0) {
            cols = (size_t)c;
            bands = cols - 2;
        } else if ((size_t)c != cols) {
            rc = cli_fail("%s:%zu: %ld columns, the first line had %zu", in, lineno,
                            c, cols);
            goto done;
        }
        for (size_t j = 0; j < cols; j++)
            if (!isfinite(row[j])) {
                rc = cli_fail("%s:%zu: value not finite", in, lineno);
                goto done;
            }
        if (row[0] < 0.0 || row[0] > 90.0) {
            rc = cli_fail("%s:%zu: theta %g outside 0..90 degrees", in, lineno,
                            row[0]);
            goto done;
        }
        if (n == cap) {
            size_t nc = cap ? 2 * cap : 512;
            double(*nd)[3] = realloc(dir, nc * sizeof *dir);
            if (nd != NULL)
                dir = nd;
            double *nv = realloc(val, nc * bands * sizeof *val);
            if (nv != NULL)
                val = nv;
            if (nd == NULL || nv == NULL) {
                rc = cli_fail("out of memory");
                goto done;
            }
            cap = nc;
        }
        bwr_dir_from_degrees(row[0], row[1], dir[n]);
        memcpy(val + n * bands, row + 2, bands * sizeof *val);
        n++;
    }
    if (ferror(f)) {
        rc = cli_fail("read error on '%s'", in);
        goto done;
    }
    if (n == 0) {
        rc = cli_fail("%s: no measurements", in);
        goto done;
    }

    size_t nt = bwr_grid_count(level);
    grid = malloc(nt * bands * sizeof *grid);
    buf = malloc(nt * bands * 4);
    if (grid == NULL || buf == NULL ||
        bwr_project((const double(*)[3])dir, val, n, bands, level, k, grid) != 0) {
        rc = cli_fail("projection failed (out of memory)");
        goto done;
    }
    double vmin = INFINITY, vmax = -INFINITY;
    for (size_t i = 0; i < nt * bands; i++) {
        if (fabs(grid[i]) > 3.4028234663852886e38) {
            rc = cli_fail("value not representable as float32");
            goto done;
        }
        vmin = fmin(vmin, grid[i]);
        vmax = fmax(vmax, grid[i]);
        bwref_put_f32(buf + 4 * i, (float)grid[i]);
    }
    FILE *o = fopen(out, "wb");
    if (o == NULL) {
        rc = cli_fail("cannot create '%s': %s", out, strerror(errno));
        goto done;
    }
    int bad = fwrite(buf, 4, nt * bands, o) != nt * bands;
    if (fclose(o) != 0 || bad) {
        remove(out);
        rc = cli_fail("write to '%s' failed", out);
        goto done;
    }
    printf("measurements: %zu\ntriangles: %zu (level %u)\nbands: %zu\nneighbours: %u\n"
           "values: min %.6g, max %.6g\n",
           n, nt, level, bands, k < n ? k : (unsigned)n, vmin, vmax);
    rc = 0;
done:
    fclose(f);
    free(line);
    free(row);
    free(dir);
    free(val);
    free(grid);
    free(buf);
    return rc;
}
