/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave encode: a measurement file to a payload. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_device.h"
#include "bwh_input.h"
#include "bwh_meta.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_progress.h"
#include "cli_shape.h"
#include "commands.h"

static const char encode_help[] =
    "usage: brdfwave encode -i IN [-i IN2 ...] -o OUT.bwv [--bands B] [--level L]\n"
    "                       [--incoming N | --level-in Li] [--input-format F]\n"
    "                       [--lossless | --max-error E | --bytes N | --ratio R]\n"
    "                       [--max-rel-error R [--rel-floor F]]\n"
    "                       [--basis haar|53|97|pred|auto] [--effort best|fast]\n"
    "                       [--scale S] [--relative]\n"
    "                       [--coder range|ms|tab|rice|auto] [--segments N] [--progressive]\n"
    "                       [--band-access]\n"
    "                       [-q]\n"
    "                       [--symmetry auto|mirror|reciprocal|both|none]\n"
    "                       [--metadata FILE.json] [--field KEY=VALUE ...] [--no-metadata]\n"
    "\n"
    "Compresses a measurement with its metadata (wavelengths, units, incidence\n"
    "angles, instrument, time, location, free fields: 'brdfwave info'). Raw input\n"
    "is little-endian, row-major [incoming][outgoing][band], directions in\n"
    "'brdfwave grid' order, with the metadata of its sidecar IN.json if there is one.\n"
    "  --bands B         bands per spectrum (raw input; the other formats say)\n"
    "  --level L         outgoing geodesic level 0..6; without it the input is a\n"
    "                    set of spectra [spectrum][band]\n"
    "  --incoming N      N incoming directions, outgoing transform only (isotropic BRDF)\n"
    "  --level-in Li     full BRDF: incoming hemisphere at level Li\n"
    "  --input-format F  auto (default: from the content and the name), f32, u16, i32,\n"
    "                    sed (Spectral Evolution), sig (Spectra Vista), asd (ASD, every\n"
    "                    version), usgs (USGS ASCII spectrum; its wavelength table is\n"
    "                    found beside it), envi (header and library or image), csv\n"
    "                    (a wavelength column and a column per spectrum, or angle\n"
    "                    columns), npy, bsdf (an RGL BRDF sampled on the grid at\n"
    "                    --level, default 4, at its measured incidence angles) or\n"
    "                    gonio (a goniometer's scattered directions projected onto\n"
    "                    the grid); several -i files make one set of spectra\n"
    "  --channel C       bsdf: rgb (default), r, g or b\n"
    "  --column C        sed, sig, asd: reflectance (default), target or reference\n"
    "  --ignore-value V  samples equal to V are missing (ENVI files name theirs):\n"
    "                    coded as their neighbours, given back as V\n"
    "  --wavelength-table FILE  usgs: the wavelength table to use\n"
    "  --metadata FILE   JSON metadata (info --json's \"metadata\" object) to add to\n"
    "                    or replace the input's\n"
    "  --field KEY=VALUE a free field to add (repeatable)\n"
    "  --no-metadata     no metadata record in the payload\n"
    "  --lossless        bit-exact (default); float32 input comes back bit for bit\n"
    "                    (NaN, infinities, -0.0 and subnormals too); with --scale\n"
    "                    every value must be an integer multiple of it\n"
    "  --max-error E     every decoded value within E of the input (value units)\n"
    "  --max-rel-error R every decoded value x' within R |x| of its input x (0 < R < 1;\n"
    "                    zeros stay zero); with --max-error E too, within the tighter\n"
    "                    of the two: min(E, R |x|), as CCSDS 123.0-B-2 combines them\n"
    "  --rel-floor F     with --max-rel-error: within max(R |x|, F), so values below\n"
    "                    F / R need only be within F\n"
    "  --bytes N         the payload is at most N bytes, best quality that fits\n"
    "  --ratio R         the payload is at most 4*samples/R bytes (R:1 against float32)\n"
    "  --basis B         spectral wavelet (default auto: the smallest payload); pred:\n"
    "                    prediction instead, for spectra with --lossless or --max-error\n"
    "  --effort E        best (the default on the host): auto codes the data with\n"
    "                    each basis, --bytes searches the step; fast (the default\n"
    "                    with --device): auto ranks the wavelets on an eighth of it,\n"
    "                    codes it with the first and prediction, then the whole\n"
    "                    once with the best, --bytes is met in one encode\n"
    "                    that steers a step per chunk as it codes (else the step is\n"
    "                    estimated and corrected by each encode's size)\n"
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
    "  --segments N      split the body into N segments (about; whole coefficient\n"
    "                    vectors in coding order, coarse levels first), each with\n"
    "                    its length and CRC-32 and decodable alone: a damaged or\n"
    "                    missing segment costs its own coefficients only (decode\n"
    "                    rebuilds the rest and reports what was lost); format 7\n"
    "  --progressive     embedded segments (one without --segments): bit planes, the\n"
    "                    most significant first, so that any prefix decodes to an\n"
    "                    approximation (decode of a cut payload); with --bytes or\n"
    "                    --ratio the exact coding cut at the budget, no search;\n"
    "                    transform bases; format 7\n"
    "  --band-access     a set of spectra (--lossless or --max-error) coded so that\n"
    "                    any band or band range decodes alone (decode --bands),\n"
    "                    at a cost that follows the bands asked for: prediction\n"
    "                    along the bands, coarse to fine, coded by columns; format 7\n"
    "  --coder C         entropy coder: range (the default on the host: the smallest\n"
    "                    payload); ms (multi-symbol range coder, format 7: about a\n"
    "                    third fewer instructions per sample on the device, about\n"
    "                    the same bytes); tab (static tables, counted over part of\n"
    "                    the body and sent ahead of it, format 7: fewer instructions\n"
    "                    still on sets of spectra; not with --progressive, nor with\n"
    "                    --stream on a device); rice (adaptive Rice strips: several\n"
    "                    times fewer instructions, more bytes where most\n"
    "                    coefficients are zero); or auto (the default with\n"
    "                    --device): rice for prediction errors of a bit or more a\n"
    "                    sample, tab for spectra transformed (not the sparsest),\n"
    "                    else ms\n"
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

#define CODER_AUTO 0x100u /* --coder auto: BW_CODER_AUTO */
#define CODER_UNSET 0x200u /* no --coder: auto on a device, else range */

static int parse_coder(const char *v, void *dest)
{
    if (strcmp(v, "auto") == 0) {
        *(unsigned *)dest = CODER_AUTO;
        return 0;
    }
    int f = bwh_coder_from_name(v);
    if (f < 0)
        return -1;
    *(unsigned *)dest = (unsigned)f;
    return 0;
}

/* The summary line: the payload decoded again and compared with the input
 * values (floats, or ints of value iscale * sample). 0, or -1. */
static int summary(const char *outp, const uint8_t *payload, size_t plen, size_t count,
                   const float *floats, const int32_t *ints, float iscale, unsigned st)
{
    /* against the input's own sample type: integers as they came, else float32 */
    static const char *const own[BWH_ST_COUNT] = {"float32", "uint8", "int16", "uint16",
                                                  "int32", "float32", "float32"};
    static const size_t own_bytes[BWH_ST_COUNT] = {4, 1, 2, 2, 4, 4, 4};
    unsigned fmt = st < BWH_ST_COUNT ? st : 0u;
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
static const char *const efforts[] = {"best", "fast", NULL}; /* bw_effort_t */
static const char *const channels[] = {"rgb", "r", "g", "b", NULL};
static const char *const columns[] = {"reflectance", "target", "reference", NULL};

static int parse_format(const char *v, void *dest)
{
    int f = bwh_input_format_from_name(v);
    if (f < 0)
        return -1;
    *(int *)dest = f;
    return 0;
}

/* the measurement's metadata with --metadata FILE and --field KEY=VALUE */
static int metadata_options(bwh_meta_t *m, const char *file, const cli_list_t *fields)
{
    if (file) {
        uint8_t *b;
        size_t n;
        if (bwh_read_file(file, &b, &n) != 0)
            return -1;
        char *s = realloc(b, n + 1);
        if (!s) {
            free(b);
            return bwh_fail("out of memory");
        }
        s[n] = 0;
        bwh_meta_t x;
        int rc = bwh_meta_from_json(s, &x);
        free(s);
        if (rc)
            return bwh_fail("%s: %s", file, bwh_last_error());
        rc = bwh_meta_merge(m, &x);
        bwh_meta_free(&x);
        if (rc)
            return -1;
    }
    for (int i = 0; i < fields->n; i++) {
        const char *eq = strchr(fields->item[i], '=');
        if (!eq || eq == fields->item[i])
            return bwh_fail("--field needs KEY=VALUE, got '%s'", fields->item[i]);
        char key[256];
        snprintf(key, sizeof key, "%.*s", (int)(eq - fields->item[i]), fields->item[i]);
        bwh_meta_t x;
        bwh_meta_init(&x);
        int rc = bwh_meta_add_field(&x, key, eq + 1) || bwh_meta_merge(m, &x);
        bwh_meta_free(&x);
        if (rc)
            return -1;
    }
    return 0;
}

/* The dimensions: the file's shape, or the shape options (which must agree
 * with what the file says) */
static int dims_of(const bwh_measure_t *m, const cli_shape_t *sh, bwh_shape_t *shape,
                   bw_dims_t *d)
{
    int given = sh->has_level || sh->has_incoming || sh->has_level_in;
    if (m->bands && sh->has_bands && shape->bands != m->bands)
        return bwh_fail("the input has %u bands, --bands says %u", m->bands, shape->bands);
    if (m->bands)
        shape->bands = m->bands;
    if (m->shape < 0 || (m->shape == BW_SHAPE_SPECTRA && given))
        return bwh_shape_dims(shape, m->count, d);
    /* the options given must say what the file says (--level also picks
     * the grid of the formats sampled onto it, and the reader used it) */
    if ((sh->has_level && sh->level != m->level_out) ||
        (sh->has_incoming && (m->shape != BW_SHAPE_BRDF_ISO || sh->incoming != m->n_in)) ||
        (sh->has_level_in && (m->shape != BW_SHAPE_BRDF_FULL || sh->level_in != m->level_in)))
        return bwh_fail("the input holds a %s at level %u with %u incoming directions; the "
                        "shape options say otherwise",
                        bwh_shape_name((unsigned)m->shape), m->level_out,
                        m->shape == BW_SHAPE_REFLECTANCE ? 1u : m->n_in);
    unsigned n_in = m->shape == BW_SHAPE_REFLECTANCE ? 1u : m->n_in;
    if (bw_dims_make(d, (bw_shape_t)m->shape, m->level_out, m->level_in, n_in, m->bands) != BW_OK ||
        bw_dims_samples(d) != m->count)
        return bwh_fail("the input's shape (%s, %u by %u directions, %u bands) does not make "
                        "its %zu samples",
                        bwh_shape_name((unsigned)m->shape), n_in, m->level_out, m->bands,
                        m->count);
    return 0;
}

int bw_cmd_encode(int argc, char **argv)
{
    const char *inputs[4096];
    cli_list_t in = {inputs, 0, (int)(sizeof inputs / sizeof *inputs)};
    const char *outp = NULL;
    cli_shape_t sh = {0};
    int fmt = BWH_IN_AUTO, device = DEV_HOST, lossless = 0, stream = 0, relative = 0;
    int channel = 0, column = 0, no_meta = 0, has_ignore = 0;
    double ignore = 0;
    const char *meta_file = NULL, *wl_table = NULL;
    const char *field_items[256];
    cli_list_t fields = {field_items, 0, 256};
    int n_lossless = 0, n_max_error = 0, n_bytes = 0, n_ratio = 0, has_symmetry = 0;
    double max_error = 0, ratio = 0, scale = 0, max_rel = 0, rel_floor = 0;
    int n_max_rel = 0, n_rel_floor = 0;
    uint32_t bytes = 0, drop = 0;
    int has_drop = 0, quiet = 0, has_effort = 0, effort = 0;
    uint32_t segments = 0;
    int progressive = 0, band_access = 0;
    unsigned basis = BW_BASIS_AUTO, symmetry = 0, coder = CODER_UNSET;
    const char *firmware = NULL;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_LIST, .dest = &in},
        {"output", 'o', CLI_STRING, .dest = &outp},
        CLI_SHAPE_BANDS(&sh),
        CLI_SHAPE_LEVELS(&sh),
        CLI_SHAPE_INCOMING(&sh),
        {"input-format", 0, CLI_CALL, .dest = &fmt, .parse = parse_format,
         .what = "--input-format must be auto, f32, u16, i32, sed, sig, asd, usgs, envi, csv, "
                 "npy, bsdf or gonio"},
        {"channel", 0, CLI_CHOICE, .dest = &channel, .choices = channels},
        {"column", 0, CLI_CHOICE, .dest = &column, .choices = columns},
        {"ignore-value", 0, CLI_REAL, .dest = &ignore, .lo = -3.4e38, .hi = 3.4e38,
         .seen = &has_ignore},
        {"wavelength-table", 0, CLI_STRING, .dest = &wl_table},
        {"metadata", 0, CLI_STRING, .dest = &meta_file},
        {"field", 0, CLI_LIST, .dest = &fields},
        {"no-metadata", 0, CLI_FLAG, .dest = &no_meta},
        {"lossless", 0, CLI_FLAG, .dest = &lossless, .seen = &n_lossless},
        {"max-error", 0, CLI_POSITIVE, .dest = &max_error, .seen = &n_max_error},
        {"max-rel-error", 0, CLI_POSITIVE, .dest = &max_rel, .seen = &n_max_rel},
        {"rel-floor", 0, CLI_POSITIVE, .dest = &rel_floor, .seen = &n_rel_floor},
        {"bytes", 0, CLI_U32, .dest = &bytes, .lo = 1, .hi = UINT32_MAX, .seen = &n_bytes},
        {"ratio", 0, CLI_POSITIVE, .dest = &ratio, .seen = &n_ratio},
        {"basis", 0, CLI_CALL, .dest = &basis, .parse = parse_basis,
         .what = "--basis must be haar, 53, 97, pred or auto"},
        {"effort", 0, CLI_CHOICE, .dest = &effort, .choices = efforts, .seen = &has_effort},
        {"scale", 0, CLI_POSITIVE, .dest = &scale},
        {"device", 0, CLI_CHOICE, .dest = &device, .choices = devices},
        {"firmware", 0, CLI_STRING, .dest = &firmware},
        {"drop-chunk", 0, CLI_U32, .dest = &drop, .lo = 0, .hi = 65535, .seen = &has_drop},
        {"stream", 0, CLI_FLAG, .dest = &stream},
        {"segments", 0, CLI_U32, .dest = &segments, .lo = 1, .hi = 1u << 28},
        {"progressive", 0, CLI_FLAG, .dest = &progressive},
        {"band-access", 0, CLI_FLAG, .dest = &band_access},
        {"relative", 0, CLI_FLAG, .dest = &relative},
        {"coder", 0, CLI_CALL, .dest = &coder, .parse = parse_coder,
         .what = "--coder must be range, ms, tab, rice or auto"},
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
    if (n_max_rel && !(max_rel < 1))
        return cli_usage("--max-rel-error must lie between 0 and 1");
    if (n_max_rel && (n_lossless || n_bytes || n_ratio || relative))
        return cli_usage("--max-rel-error goes alone or with --max-error, not with --lossless, "
                         "--bytes, --ratio or --relative");
    if (n_rel_floor && !n_max_rel)
        return cli_usage("--rel-floor needs --max-rel-error");
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = n_max_error ? BW_MODE_MAX_ERROR : n_bytes || n_ratio ? BW_MODE_BYTES
                                                                  : BW_MODE_LOSSLESS;
    o.max_error = max_error;
    o.max_rel_error = max_rel;
    o.rel_floor = rel_floor;
    o.byte_budget = bytes;
    o.basis = basis;
    /* on a device every try costs an encode */
    o.effort = has_effort ? (unsigned)effort : device != DEV_HOST ? BW_EFFORT_FAST
                                                                  : BW_EFFORT_BEST;
    o.scale = scale;
    /* on a device the coder that keeps up with the sensor */
    if (coder == CODER_UNSET)
        coder = device != DEV_HOST ? CODER_AUTO : 0u;
    o.coder = coder == CODER_AUTO ? BW_CODER_AUTO : BW_CODER_BY_FLAGS;
    coder = coder == CODER_AUTO ? 0u : coder;
    o.segments = segments;
    o.progressive = (uint32_t)progressive;
    o.band_access = (uint32_t)band_access;
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
    if (progressive && (stream || o.basis == BW_BASIS_PRED))
        return cli_usage("--progressive codes transform coefficients coarse to fine: not with "
                         "--stream or --basis pred");
    if (band_access && (sh.has_level || o.mode > BW_MODE_MAX_ERROR || stream || progressive ||
                        segments || coder || o.coder != BW_CODER_BY_FLAGS ||
                        device != DEV_HOST ||
                        (o.basis != BW_BASIS_PRED && o.basis != BW_BASIS_AUTO)))
        return cli_usage("--band-access codes a set of spectra (no --level) on the host with "
                         "--lossless or --max-error: not with --stream, --segments, "
                         "--progressive, --coder, --device or a transform basis");
    if (in.n > 1 && fmt >= BWH_IN_F32 && fmt <= BWH_IN_I32)
        return cli_usage("several inputs make a set of spectra: not for raw input");
    if ((fmt == BWH_IN_F32 || fmt == BWH_IN_U16 || fmt == BWH_IN_I32) && !sh.has_bands)
        return cli_usage("--bands is required for raw input");
    if (relative && (fmt == BWH_IN_U16 || fmt == BWH_IN_I32))
        return cli_usage("--relative is for float input");
    if (no_meta && (meta_file || fields.n))
        return cli_usage("--no-metadata with --metadata or --field");

    /* the samples: floats, or integers of value scale * sample */
    int32_t *ints = NULL;
    float *floats = NULL, iscale = 1.0f;
    size_t count = 0;
    uint8_t *payload = NULL, *ext = NULL;
    size_t plen = 0, ext_len = 0;
    int rc = CLI_EXIT_FAIL;
    bw_dims_t d;
    bwh_measure_t m;
    bwh_read_opts_t ro = BWH_READ_OPTS_INIT;
    ro.level = sh.has_level ? (int)sh.level : -1;
    ro.channel = channel;
    ro.column = column;
    ro.has_ignore = has_ignore;
    ro.ignore = ignore;
    ro.wavelengths = wl_table;
    if (bwh_measure_read(in.item, in.n, fmt, &ro, &m) != 0) {
        bwh_measure_init(&m);
        goto fail;
    }
    if (!m.bands && !sh.has_bands) {
        cli_fail("%s: raw samples: give --bands (or a sidecar %s.json with the wavelengths)",
                 in.item[0], in.item[0]);
        goto out;
    }
    if (dims_of(&m, &sh, &shape, &d) != 0 || metadata_options(&m.meta, meta_file, &fields) != 0)
        goto fail;
    if (!no_meta && (bwh_meta_check(&m.meta, &d) != 0 ||
                     bwh_meta_encode(&m.meta, &ext, &ext_len) != 0))
        goto fail;
    o.ext = ext;
    o.ext_len = ext_len;
    count = m.count;
    if (m.values || relative) {
        floats = m.values ? m.values : bwh_measure_floats(&m);
        if (!floats)
            goto fail;
        if (m.values)
            m.values = NULL;
    } else {
        ints = m.ints;
        m.ints = NULL;
        iscale = (float)m.scale;
        if (m.scale == 1.0 && scale > 0)
            iscale = (float)scale;
    }
    if (n_ratio) {
        double b = 4.0 * (double)count / ratio;
        if (b < 1)
            b = 1;
        o.byte_budget = b > (double)UINT32_MAX ? UINT32_MAX : (size_t)floor(b);
    }
    if (n_max_rel && !floats) {
        /* a relative bound is a bound on the values: integer input as its values */
        floats = malloc((count ? count : 1) * sizeof *floats);
        if (!floats) {
            bwh_fail("out of memory");
            goto fail;
        }
        bwh_value_map_t vm = bwh_value_map(iscale, 0.0f,
                                           bwh_decimal_exponent(iscale) ? BW_FLAG_DECIMAL_SCALE : 0u);
        for (size_t i = 0; i < count; i++)
            floats[i] = bwh_value_of(&vm, ints[i]);
    }
    cli_progress_start("%zu samples", count);
    if ((floats ? bwh_encode_f32(&d, floats, &o, &payload, &plen)
                : bwh_encode_scaled(&d, ints, &o, iscale, &payload, &plen)) != 0 ||
        bwh_write_file(outp, payload, plen) != 0)
        goto fail;
    cli_progress_text("%zu samples, measuring the payload", count);
    if (!quiet && summary(outp, payload, plen, count, floats, ints, iscale,
                          (m.meta.present & BWH_M_SAMPLE_TYPE) ? (unsigned)m.meta.sample_type : 0u) != 0)
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
    free(ext);
    bwh_measure_free(&m);
    return rc;
}
