/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave decode: a payload to samples, with its metadata where the output
 * format holds it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_meta.h"
#include "bwh_output.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_progress.h"
#include "commands.h"

static const char decode_help[] =
    "usage: brdfwave decode -i IN.bwv -o OUT [--output-format F] [--max-samples N]\n"
    "\n"
    "Decodes a payload in the encoder's layout, [incoming][outgoing][band], with\n"
    "its metadata (wavelengths, units, incidence angles, ...: 'brdfwave info').\n"
    "'-' is standard input or output; an OUT that is a device or a pipe is\n"
    "written to directly.\n"
    "  --output-format F  f32: float32 values (the default, and for a name ending\n"
    "                     in none of the below); i32: the codec's int32 samples;\n"
    "                     u16: those as uint16; raw: the type the input came in as;\n"
    "                     npy: a numpy array of that type (.npy); csv: a wavelength\n"
    "                     column and a column per spectrum, or a row per direction\n"
    "                     (.csv); envi: an ENVI header OUT.hdr beside the data (.img,\n"
    "                     .sli). f32, i32, u16, raw and npy keep the metadata in\n"
    "                     OUT.json (not on standard output)\n"
    "  --max-samples N    refuse payloads that decode to more than N samples\n"
    "                     (default 67108864, 256 MiB of float32): a small payload\n"
    "                     can describe gigabytes\n"
    "On a terminal a progress line shows while the work takes more than a second.\n";

static int parse_format(const char *v, void *dest)
{
    int f = bwh_output_format_from_name(v);
    if (f < 0)
        return -1;
    *(int *)dest = f;
    return 0;
}

/* the format a name asks for by its ending, f32 otherwise */
static int format_of_name(const char *path)
{
    static const struct {
        const char *end;
        int f;
    } ends[] = {{".npy", BWH_OUT_NPY}, {".csv", BWH_OUT_CSV}, {".img", BWH_OUT_ENVI},
                {".sli", BWH_OUT_ENVI}, {".bsq", BWH_OUT_ENVI}, {".bip", BWH_OUT_ENVI}};
    size_t n = strlen(path);
    for (size_t i = 0; i < sizeof ends / sizeof *ends; i++) {
        size_t e = strlen(ends[i].end);
        if (n > e && !strcmp(path + n - e, ends[i].end))
            return ends[i].f;
    }
    return BWH_OUT_F32;
}

int bw_cmd_decode(int argc, char **argv)
{
    const char *inp = NULL, *outp = NULL;
    int fmt = -1;
    uint32_t max_samples = 0;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &inp},
        {"output", 'o', CLI_STRING, .dest = &outp},
        {"output-format", 0, CLI_CALL, .dest = &fmt, .parse = parse_format,
         .what = "--output-format must be f32, i32, u16, raw, npy, csv or envi"},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = BW_MAX_SAMPLES},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, decode_help, NULL, &st))
        return st;
    if (!inp || !outp)
        return cli_usage("needs -i IN.bwv and -o OUT");
    if (fmt < 0)
        fmt = format_of_name(outp);
    if (fmt == BWH_OUT_ENVI && !strcmp(outp, "-"))
        return cli_usage("--output-format envi writes a header beside its data: not to '-'");
    uint8_t *p;
    size_t len;
    if (bwh_read_file(inp, &p, &len) != 0)
        return cli_fail("%s", bwh_last_error());
    bw_header_t h;
    int32_t *s = NULL;
    float *v = NULL;
    bwh_meta_t meta;
    bwh_meta_init(&meta);
    /* the integer formats need no values (a scale can take the values
     * beyond float32 where the integers are fine) */
    int ints_only = fmt == BWH_OUT_I32 || fmt == BWH_OUT_U16;
    cli_progress_start("%zu bytes", len);
    if (bwh_decode_limit(p, len, max_samples, &h, &s, ints_only ? NULL : &v) != 0 ||
        bwh_meta_of_payload(p, len, &h, &meta) != 0) {
        free(p);
        free(s);
        free(v);
        cli_progress_end();
        return cli_fail("%s: %s", inp, bwh_last_error());
    }
    free(p);
    size_t n = bw_dims_samples(&h.dims);
    if (v)
        bwh_meta_put_missing(&meta, v, n);
    bwh_decoded_t d;
    d.dims = h.dims;
    d.values = v;
    d.ints = s;
    /* the integer samples are the values themselves */
    d.ints_are_values = h.scale_bits == 0x3F800000u && (h.offset_bits & 0x7FFFFFFFu) == 0 &&
                        !(h.flags & (BW_FLAG_LOG_VALUE | BW_FLAG_DECIMAL_SCALE)) &&
                        !(meta.present & BWH_M_MISSING);
    d.meta = &meta;
    cli_progress_text("%zu samples, writing", n);
    int rc = bwh_output_write(outp, fmt, &d);
    free(s);
    free(v);
    bwh_meta_free(&meta);
    cli_progress_end();
    return rc ? cli_fail("%s", bwh_last_error()) : CLI_EXIT_OK;
}
