/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave encode: a measurement file to a payload. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_device.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_progress.h"
#include "cli_shape.h"
#include "commands.h"

static const char encode_help[] =
    "usage: brdfwave encode -i IN [-i IN2 ...] -o OUT.bwv [--bands B] [--level L]\n"
    "                       [--incoming N | --level-in Li] [--input-format f32|u16|i32|sed]\n"
    "                       [--lossless | --max-error E | --bytes N | --ratio R]\n"
    "                       [--basis haar|53|97|pred|auto] [--scale S] [--relative]\n"
    "                       [--coder range|rice] [-q]\n"
    "                       [--symmetry auto|mirror|reciprocal|both|none]\n"
    "\n"
    "Compresses a measurement. Raw input is little-endian, row-major\n"
    "[incoming][outgoing][band], directions in 'brdfwave grid' order.\n"
    "  --bands B         bands per spectrum (sed: taken from the file)\n"
    "  --level L         outgoing geodesic level 0..6; without it the input is a\n"
    "                    set of spectra [spectrum][band]\n"
    "  --incoming N      N incoming directions, outgoing transform only (isotropic BRDF)\n"
    "  --level-in Li     full BRDF: incoming hemisphere at level Li\n"
    "  --input-format F  f32 (default), u16, i32, or sed (Spectral Evolution; several\n"
    "                    -i files make a set of spectra, reflectance in units of 1e-5)\n"
    "  --lossless        bit-exact (default); float input must be integer multiples of\n"
    "                    --scale (default 1)\n"
    "  --max-error E     every decoded value within E of the input (value units)\n"
    "  --bytes N         the payload is at most N bytes, best quality that fits\n"
    "  --ratio R         the payload is at most 4*samples/R bytes (R:1 against float32)\n"
    "  --basis B         spectral wavelet (default auto: the smallest payload); pred:\n"
    "                    prediction instead, for spectra with --lossless or --max-error\n"
    "  --scale S         float input: value of one integer step\n"
    "  --device D        where to encode: host (default); qemu, the emulated\n"
    "                    Cortex-M4 co-processor (its payload comes back over the\n"
    "                    UART link and is checked on the host); or linux, the same\n"
    "                    device application as a host process\n"
    "  --firmware IMAGE  device image (default: $BW_FIRMWARE for qemu, $BW_FIRMWARE_LINUX\n"
    "                    for linux, else the build's: ../qemu/brdfwave-fw.elf or\n"
    "                    brdfwave-fw-linux beside this program)\n"
    "  --stream          code in the order a streaming encoder produces (the device\n"
    "                    then encodes spectrum by spectrum in bounded RAM; needs\n"
    "                    --lossless, --max-error or a fixed --basis; not --level-in)\n"
    "  --relative        with --bytes or --ratio, float input > 0: code log(value),\n"
    "                    so the budget buys relative rather than absolute accuracy\n"
    "  --coder C         entropy coder: range (default, the smallest payload) or rice\n"
    "                    (adaptive Rice strips: a few times fewer instructions per\n"
    "                    sample on the device, a few percent more bytes)\n"
    "  --symmetry S      directional data: mirror codes the half y < 0 of each\n"
    "                    hemisphere as differences from its mirror image (x, -y, z),\n"
    "                    for BRDFs symmetric about the incidence plane x-z;\n"
    "                    reciprocal (a full BRDF, --level-in equal to --level) codes\n"
    "                    f(wi, wo) as its difference from f(wo, wi) where that comes\n"
    "                    first, for reciprocal BRDFs; both; none; or auto (default:\n"
    "                    every one that applies, on the host, and the smallest\n"
    "                    payload, or for a byte budget the smallest error)\n"
    "  -q, --quiet       no summary line\n"
    "\n"
    "Ends with one line on standard error, measured on the payload decoded again:\n"
    "  OUT: N samples -> B bytes, X bits/sample, R:1 against float32, max error E,\n"
    "  relative L2 P %\n"
    "(the ratio against the input's own sample size: uint16 for u16, int32 for i32,\n"
    "float32 for f32 and sed; the errors in the values' units). On a terminal a\n"
    "progress line shows while the work takes more than a second.\n";

static int parse_basis(const char *v, void *dest)
{
    int b = bwh_basis_from_name(v);
    if (b < 0)
        return -1;
    *(unsigned *)dest = (unsigned)b;
    return 0;
}

static int parse_symmetry(const char *v, void *dest)
{
    int f = bwh_symmetry_from_name(v);
    if (f < 0)
        return -1;
    *(unsigned *)dest = (unsigned)f;
    return 0;
}

static int parse_coder(const char *v, void *dest)
{
    int f = bwh_coder_from_name(v);
    if (f < 0)
        return -1;
    *(unsigned *)dest = (unsigned)f;
    return 0;
}

/* The summary line: the payload decoded again and compared with the input
 * values (floats, or ints of value iscale * sample). 0, or -1. */
static int summary(const char *outp, const uint8_t *payload, size_t plen, size_t count,
                   const float *floats, const int32_t *ints, float iscale, int fmt)
{
    static const char *const own[] = {"float32", "uint16", "int32", "float32"};
    static const size_t own_bytes[] = {4, 2, 4, 4};
    bw_header_t h;
    float *dec = NULL, *ref = NULL;
    const char *name = strcmp(outp, "-") ? outp : "(stdout)";
    double bps = 8.0 * (double)plen / (double)count;
    double ratio = (double)own_bytes[fmt] * (double)count / (double)plen;
    if (bwh_decode_limit(payload, plen, count, &h, NULL, &dec) != 0) {
        /* a valid payload whose values float32 cannot hold (decode says so) */
        cli_progress_end();
        fprintf(stderr,
                "%s: %zu samples -> %zu bytes, %.4f bits/sample, %.2f:1 against %s, "
                "errors not measured: %s\n",
                name, count, plen, bps, ratio, own[fmt], bwh_last_error());
        return 0;
    }
    if (!floats) {
        ref = malloc(count * sizeof *ref);
        if (!ref) {
            free(dec);
            return bwh_fail("out of memory");
        }
        bwh_value_map_t m = bwh_value_map(iscale, 0.0f, bwh_decimal_exponent(iscale)
                                                            ? BW_FLAG_DECIMAL_SCALE
                                                            : 0u);
        for (size_t i = 0; i < count; i++)
            ref[i] = bwh_value_of(&m, ints[i]);
    }
    bwh_metrics_t m;
    bwh_metrics(floats ? floats : ref, dec, count, &m);
    cli_progress_end();
    fprintf(stderr,
            "%s: %zu samples -> %zu bytes, %.4f bits/sample, %.2f:1 against %s, "
            "max error %.6g, relative L2 %.6g %%\n",
            name, count, plen, bps, ratio, own[fmt], m.max_abs, m.rel_l2);
    free(dec);
    free(ref);
    return 0;
}

enum { DEV_HOST, DEV_QEMU, DEV_LINUX };
static const char *const devices[] = {"host", "qemu", "linux", NULL};
static const char *const formats[] = {"f32", "u16", "i32", "sed", NULL};
enum { FMT_SED = 3 };

int bw_cmd_encode(int argc, char **argv)
{
    const char *inputs[4096];
    cli_list_t in = {inputs, 0, (int)(sizeof inputs / sizeof *inputs)};
    const char *outp = NULL;
    cli_shape_t sh = {0};
    int fmt = BWH_FMT_F32, device = DEV_HOST, lossless = 0, stream = 0, relative = 0;
    int n_lossless = 0, n_max_error = 0, n_bytes = 0, n_ratio = 0, has_symmetry = 0;
    double max_error = 0, ratio = 0, scale = 0;
    uint32_t bytes = 0, drop = 0;
    int has_drop = 0, quiet = 0;
    unsigned basis = BW_BASIS_AUTO, symmetry = 0, coder = 0;
    const char *firmware = NULL;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_LIST, .dest = &in},
        {"output", 'o', CLI_STRING, .dest = &outp},
        CLI_SHAPE_BANDS(&sh),
        CLI_SHAPE_LEVELS(&sh),
        CLI_SHAPE_INCOMING(&sh),
        {"input-format", 0, CLI_CHOICE, .dest = &fmt, .choices = formats},
        {"lossless", 0, CLI_FLAG, .dest = &lossless, .seen = &n_lossless},
        {"max-error", 0, CLI_POSITIVE, .dest = &max_error, .seen = &n_max_error},
        {"bytes", 0, CLI_U32, .dest = &bytes, .lo = 1, .hi = UINT32_MAX, .seen = &n_bytes},
        {"ratio", 0, CLI_POSITIVE, .dest = &ratio, .seen = &n_ratio},
        {"basis", 0, CLI_CALL, .dest = &basis, .parse = parse_basis,
         .what = "--basis must be haar, 53, 97, pred or auto"},
        {"scale", 0, CLI_POSITIVE, .dest = &scale},
        {"device", 0, CLI_CHOICE, .dest = &device, .choices = devices},
        {"firmware", 0, CLI_STRING, .dest = &firmware},
        {"drop-chunk", 0, CLI_U32, .dest = &drop, .lo = 0, .hi = 65535, .seen = &has_drop},
        {"stream", 0, CLI_FLAG, .dest = &stream},
        {"relative", 0, CLI_FLAG, .dest = &relative},
        {"coder", 0, CLI_CALL, .dest = &coder, .parse = parse_coder,
         .what = "--coder must be range or rice"},
        {"symmetry", 0, CLI_CALL, .dest = &symmetry, .parse = parse_symmetry, .seen = &has_symmetry,
         .what = "--symmetry must be auto, mirror, reciprocal, both or none"},
        {"quiet", 'q', CLI_FLAG, .dest = &quiet},
        {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, encode_help, &first, &st))
        return st;
    while (first < argc && in.n < in.cap)
        in.item[in.n++] = argv[first++];
    if (first < argc)
        return cli_usage("too many inputs");
    bwh_shape_t shape;
    if ((st = cli_shape_get(&sh, &shape)) != 0)
        return st;
    if (!in.n || !outp)
        return cli_usage("needs -i INPUT and -o OUTPUT");
    if (n_lossless + n_max_error + n_bytes + n_ratio > 1)
        return cli_usage("give only one of --lossless, --max-error, --bytes, --ratio");
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = n_max_error ? BW_MODE_MAX_ERROR : n_bytes || n_ratio ? BW_MODE_BYTES
                                                                  : BW_MODE_LOSSLESS;
    o.max_error = max_error;
    o.byte_budget = bytes;
    o.basis = basis;
    o.scale = scale;
    o.flags = symmetry | coder | (stream ? BW_FLAG_STREAM_ORDER : 0u) |
              (relative ? BW_FLAG_LOG_VALUE : 0u);
    uint64_t device_instructions = 0;
    struct bwh_device_job job = {devices[device], firmware, 0, has_drop ? (int)drop : -1,
                                 &device_instructions};
    o.device = device == DEV_HOST ? NULL : &job;
    if (o.basis == BW_BASIS_PRED &&
        (sh.has_level || o.mode > BW_MODE_MAX_ERROR || (o.flags & BW_FLAG_STREAM_ORDER)))
        return cli_usage("--basis pred codes sets of spectra (no --level) with --lossless "
                         "or --max-error, not --stream");
    if (fmt != FMT_SED && in.n > 1)
        return cli_usage("several inputs are only for --input-format sed");
    if (fmt != FMT_SED && !sh.has_bands)
        return cli_usage("--bands is required for raw input");
    if (relative && fmt != BWH_FMT_F32)
        return cli_usage("--relative is for float input (--input-format f32)");

    /* the samples: floats (f32), or integers of value scale * sample */
    int32_t *ints = NULL;
    float *floats = NULL, iscale = 1.0f;
    size_t count = 0;
    uint8_t *payload = NULL;
    size_t plen = 0;
    int rc = CLI_EXIT_FAIL;
    bw_dims_t d;
    if (fmt == FMT_SED) {
        if (bwh_sed_read_set(in.item, in.n, &ints, &shape.bands, &count) != 0)
            goto fail;
        iscale = (float)BWH_SED_SCALE;
    } else {
        if (bwh_raw_read(in.item[0], (bwh_format_t)fmt, fmt == BWH_FMT_F32 ? &floats : NULL,
                         &ints, &count) != 0)
            goto fail;
        if (fmt == BWH_FMT_I32 && scale > 0)
            iscale = (float)scale;
    }
    if (bwh_shape_dims(&shape, count, &d) != 0)
        goto fail;
    if (n_ratio) {
        double b = 4.0 * (double)count / ratio;
        if (b < 1)
            b = 1;
        o.byte_budget = b > (double)UINT32_MAX ? UINT32_MAX : (size_t)floor(b);
    }
    cli_progress_start("%zu samples", count);
    if ((floats ? bwh_encode_f32(&d, floats, &o, &payload, &plen)
                : bwh_encode_scaled(&d, ints, &o, iscale, &payload, &plen)) != 0 ||
        bwh_write_file(outp, payload, plen) != 0)
        goto fail;
    cli_progress_text("%zu samples, measuring the payload", count);
    if (!quiet && summary(outp, payload, plen, count, floats, ints, iscale, fmt) != 0)
        goto fail;
    cli_progress_end();
    if (o.device)
        printf("device %s: %zu samples -> %zu bytes, %llu %s (%.1f per sample)\n", job.device,
               count, plen, (unsigned long long)device_instructions,
               device == DEV_LINUX ? "ns" : "instructions",
               (double)device_instructions / (double)count);
    rc = CLI_EXIT_OK;
    goto out;
fail:
    cli_progress_end();
    cli_fail("%s", bwh_last_error());
out:
    free(ints);
    free(floats);
    free(payload);
    return rc;
}
