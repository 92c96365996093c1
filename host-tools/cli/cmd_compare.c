/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave compare: error metrics between two raw sample files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_kv.h"
#include "commands.h"

static const char compare_help[] =
    "usage: brdfwave compare [--format f32|u16|i32] [--json] REFERENCE TEST\n"
    "\n"
    "Compares two raw sample files of equal size: relative L1 and L2 in percent\n"
    "(the paper's eq. 7 and 8; samples whose reference is 0 are counted and left\n"
    "out of those two), RMSE, max absolute error and PSNR (peak = max |reference|),\n"
    "as 'key: value' lines.\n"
    "  --json  as one JSON object instead (the same keys; an infinite PSNR is null)\n";

int bw_cmd_compare(int argc, char **argv)
{
    static const char *const formats[] = {"f32", "u16", "i32", NULL};
    int fmt = BWH_FMT_F32;
    int json = 0;
    const cli_opt_t opts[] = {{"format", 0, CLI_CHOICE, .dest = &fmt, .choices = formats},
                              {"json", 0, CLI_FLAG, .dest = &json},
                              {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, compare_help, &first, &st))
        return st;
    if (argc - first != 2)
        return cli_usage("needs two files: REFERENCE TEST");
    float *a = NULL, *b = NULL;
    size_t na, nb;
    if (bwh_raw_read(argv[first], (bwh_format_t)fmt, &a, NULL, &na) != 0 ||
        bwh_raw_read(argv[first + 1], (bwh_format_t)fmt, &b, NULL, &nb) != 0) {
        free(a);
        return cli_fail("%s", bwh_last_error());
    }
    int rc = CLI_EXIT_OK;
    if (na != nb)
        rc = cli_fail("sizes differ (%zu and %zu samples)", na, nb);
    for (size_t i = 0; i < na && !rc; i++)
        if (!isfinite(a[i]) || !isfinite(b[i]))
            rc = cli_fail("sample %zu is not finite", i);
    if (!rc) {
        bwh_metrics_t m;
        bwh_metrics(a, b, na, &m);
        cli_kv_t kv;
        cli_kv_begin(&kv, stdout, json);
        cli_kv_uint(&kv, "samples", m.n);
        cli_kv_uint(&kv, "zero_reference_samples", m.zero_ref);
        cli_kv_num(&kv, "relative_l1_percent", "%.6g", m.rel_l1);
        cli_kv_num(&kv, "relative_l2_percent", "%.6g", m.rel_l2);
        cli_kv_num(&kv, "rmse", "%.9g", m.rmse);
        cli_kv_num(&kv, "max_abs_error", "%.9g", m.max_abs);
        cli_kv_num(&kv, "psnr_db", "%.4f", m.psnr); /* identical files: inf (JSON null) */
        cli_kv_end(&kv);
    }
    free(a);
    free(b);
    return rc;
}
