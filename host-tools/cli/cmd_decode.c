/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave decode: a payload to raw samples. */
#include <stdint.h>
#include <stdlib.h>

#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_progress.h"
#include "commands.h"

static const char decode_help[] =
    "usage: brdfwave decode -i IN.bwv -o OUT [--output-format f32|i32] [--max-samples N]\n"
    "\n"
    "Decodes a payload to raw little-endian samples in the encoder's layout:\n"
    "float32 values (default) or the codec's int32 samples. '-' is standard input\n"
    "or output; an OUT that is a device or a pipe is written to directly.\n"
    "  --max-samples N  refuse payloads that decode to more than N samples\n"
    "                   (default 67108864, 256 MiB of float32): a small payload\n"
    "                   can describe gigabytes\n"
    "On a terminal a progress line shows while the work takes more than a second.\n";

int bw_cmd_decode(int argc, char **argv)
{
    static const char *const formats[] = {"f32", "i32", NULL};
    const char *inp = NULL, *outp = NULL;
    int as_int = 0;
    uint32_t max_samples = 0;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &inp},
        {"output", 'o', CLI_STRING, .dest = &outp},
        {"output-format", 0, CLI_CHOICE, .dest = &as_int, .choices = formats},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = BW_MAX_SAMPLES},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, decode_help, NULL, &st))
        return st;
    if (!inp || !outp)
        return cli_usage("needs -i IN.bwv and -o OUT");
    uint8_t *p;
    size_t len;
    if (bwh_read_file(inp, &p, &len) != 0)
        return cli_fail("%s", bwh_last_error());
    bw_header_t h;
    int32_t *s = NULL;
    float *v = NULL;
    /* one array: the integers, or the values in their place */
    cli_progress_start("%zu bytes", len);
    if (bwh_decode_limit(p, len, max_samples, &h, as_int ? &s : NULL, as_int ? NULL : &v) != 0) {
        free(p);
        cli_progress_end();
        return cli_fail("%s: %s", inp, bwh_last_error());
    }
    free(p);
    void *samples = as_int ? (void *)s : (void *)v;
    cli_progress_text("%zu samples, writing", bw_dims_samples(&h.dims));
    int rc = bwh_raw_write(outp, samples, bw_dims_samples(&h.dims), as_int);
    free(samples);
    cli_progress_end();
    return rc ? cli_fail("%s", bwh_last_error()) : CLI_EXIT_OK;
}
