/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * bwref wavedec -i SIGNAL [--basis NAME|all] [--levels J|deep]
 *
 * For every basis: its four filters, the multi-level periodized transform of
 * the signal (PyWavelets' wavedec order) and the round-trip error, as text
 * lines with 17 significant digits, for comparison with PyWavelets.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_dwt.h"
#include "bwref.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"

static void print_row(const char *tag, const double *v, size_t n)
{
    fputs(tag, stdout);
    for (size_t i = 0; i < n; i++)
        printf(" %.17g", v[i]);
    putchar('\n');
}

static int one(const bwr_filter_t *f, const double *x, size_t n, int levels, bwr_ext_t mode)
{
    bwr_dwt_plan_t p;
    if (bwr_dwt_plan_ext(&p, f, n, levels, mode) != 0)
        return cli_fail("%s: cannot make %d levels on %zu samples", f->name, levels, n);
    double hi[BWR_MAX_FILTER_LEN];
    printf("basis %s family %s len %zu levels %u ncoef %zu mode %s\n", f->name, f->family, f->len,
           p.levels, p.ncoef, mode == BWR_EXT_SYMMETRIC ? "symmetric" : "periodization");
    print_row("dec_lo", f->dec_lo, f->len);
    bwr_filter_dec_hi(f, hi);
    print_row("dec_hi", hi, f->len);
    print_row("rec_lo", f->rec_lo, f->len);
    bwr_filter_rec_hi(f, hi);
    print_row("rec_hi", hi, f->len);
    printf("lens %zu", p.len[p.levels]);
    for (unsigned j = p.levels; j >= 1; j--)
        printf(" %zu", p.len[j]);
    putchar('\n');
    double *c = malloc(p.ncoef * sizeof *c), *y = malloc(n * sizeof *y);
    if (c == NULL || y == NULL || bwr_dwt_forward(&p, &bwr_type_real, x, c) != 0 ||
        bwr_dwt_inverse(&p, &bwr_type_real, c, y) != 0) {
        free(c);
        free(y);
        return cli_fail("out of memory");
    }
    print_row("coef", c, p.ncoef);
    double e = 0.0;
    for (size_t i = 0; i < n; i++)
        e = fmax(e, fabs(y[i] - x[i]));
    printf("roundtrip_max_abs %.3g\n", e);
    free(c);
    free(y);
    return 0;
}

static const char wavedec_help[] =
    "usage: bwref wavedec -i SIGNAL [--basis NAME|all] [--levels J|deep]\n"
    "                    [--mode periodization|symmetric]\n"
    "SIGNAL: whitespace-separated numbers. Prints, per basis, the\n"
    "filters, the multi-level coefficients (PyWavelets wavedec order,\n"
    "mode 'periodization' or 'symmetric') and the round-trip error.\n"
    "Without --levels: the maximum level (PyWavelets' dwt_max_level);\n"
    "deep: halvings down to 2 approximation coefficients.\n";

/* --levels J|deep */
static int parse_levels(const char *v, void *dest)
{
    uint32_t z;
    if (!strcmp(v, "deep")) {
        *(int *)dest = BWR_DWT_DEEP;
        return 0;
    }
    if (cli_u32(v, 0, BWR_DWT_MAX_LEVELS, 0, &z) != 0)
        return -1;
    *(int *)dest = (int)z;
    return 0;
}

int bwref_cmd_wavedec(int argc, char **argv)
{
    static const char *const modes[] = {"periodization", "symmetric", NULL};
    const char *in = NULL, *basis = "all";
    int levels = -1, mode = 0;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &in},
        {"basis", 0, CLI_STRING, .dest = &basis},
        {"levels", 0, CLI_CALL, .dest = &levels, .parse = parse_levels,
         .what = "--levels needs 0..24 or deep"},
        {"mode", 0, CLI_CHOICE, .dest = &mode, .choices = modes},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, wavedec_help, NULL, &st))
        return st;
    if (in == NULL)
        return cli_usage("-i SIGNAL is required");
    double *x;
    size_t n;
    if (bwref_read_text(in, &x, &n) != 0 || n == 0)
        return cli_fail("cannot read numbers from '%s'", in);
    int rc = 0;
    bwr_ext_t ext = mode ? BWR_EXT_SYMMETRIC : BWR_EXT_PERIODIZATION;
    if (strcmp(basis, "all") == 0) {
        for (size_t k = 0; k < BWR_NUM_FILTERS && rc == 0; k++)
            rc = one(&bwr_filters[k], x, n, levels, ext);
    } else {
        const bwr_filter_t *f = bwr_filter_find(basis);
        rc = f ? one(f, x, n, levels, ext) : cli_usage("unknown basis '%s'", basis);
    }
    free(x);
    return rc;
}
