/* brdfwave encode / decode / info / compare */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_le.h"
#include "bwhost.h"
#include "commands.h"

static int err(const char *cmd, const char *msg)
{
    fprintf(stderr, "brdfwave %s: %s\n", cmd, msg);
    return 1;
}

static int usage_err(const char *cmd, const char *msg)
{
    fprintf(stderr, "brdfwave %s: %s (see 'brdfwave %s --help')\n", cmd, msg, cmd);
    return 2;
}

/* Strict number parsing: the whole string, finite, in range. */
static int parse_u32(const char *s, uint32_t max, uint32_t *out)
{
    char *e;
    errno = 0;
    if (!s || !*s || *s == '-')
        return -1;
    unsigned long long v = strtoull(s, &e, 10);
    if (errno || *e || v > max)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int parse_pos_double(const char *s, double *out)
{
    char *e;
    errno = 0;
    if (!s || !*s)
        return -1;
    double v = strtod(s, &e);
    if (errno || *e || !isfinite(v) || !(v > 0))
        return -1;
    *out = v;
    return 0;
}

static const char encode_help[] =
    "usage: brdfwave encode -i IN [-i IN2 ...] -o OUT.bwv [--bands B] [--level L]\n"
    "                       [--incoming N | --level-in Li] [--input-format f32|u16|i32|sed]\n"
    "                       [--lossless | --max-error E | --bytes N | --ratio R]\n"
    "                       [--basis haar|53|97|pred|auto] [--scale S] [--relative]\n"
    "                       [--coder range|rice]\n"
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
    "  --firmware ELF    device image (default: build/qemu/brdfwave-fw.elf)\n"
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
    "                    payload, or for a byte budget the smallest error)\n";

int bw_cmd_encode(int argc, char **argv)
{
    static const struct option opts[] = {
        {"input", required_argument, 0, 'i'},      {"output", required_argument, 0, 'o'},
        {"bands", required_argument, 0, 'b'},      {"level", required_argument, 0, 'l'},
        {"incoming", required_argument, 0, 'n'},   {"level-in", required_argument, 0, 'L'},
        {"input-format", required_argument, 0, 'f'}, {"lossless", no_argument, 0, 'x'},
        {"max-error", required_argument, 0, 'e'},  {"bytes", required_argument, 0, 'B'},
        {"ratio", required_argument, 0, 'r'},      {"basis", required_argument, 0, 'w'},
        {"scale", required_argument, 0, 's'},      {"help", no_argument, 0, 'h'},
        {"device", required_argument, 0, 'D'},     {"firmware", required_argument, 0, 'F'},
        {"drop-chunk", required_argument, 0, 'K'}, {"stream", no_argument, 0, 'S'},
        {"relative", no_argument, 0, 'R'},         {"coder", required_argument, 0, 'C'},
        {"symmetry", required_argument, 0, 'Y'},   {0, 0, 0, 0}};
    const char *C = "encode";
    const char *in[4096];
    int nin = 0;
    const char *outp = NULL, *fmt = "f32";
    uint32_t bands = 0, level = UINT32_MAX, incoming = 0, level_in = UINT32_MAX;
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.mode = BW_MODE_LOSSLESS;
    o.basis = BW_BASIS_AUTO;
    o.drop_chunk = -1;
    uint64_t device_instructions = 0;
    o.device_instructions = &device_instructions;
    int modes = 0;
    double ratio = 0;
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "i:o:h", opts, NULL)) != -1) {
        switch (c) {
        case 'i':
            if (nin == (int)(sizeof in / sizeof *in))
                return usage_err(C, "too many inputs");
            in[nin++] = optarg;
            break;
        case 'o': outp = optarg; break;
        case 'b':
            if (parse_u32(optarg, BW_MAX_BANDS, &bands) || !bands)
                return usage_err(C, "--bands must be 1..65535");
            break;
        case 'l':
            if (parse_u32(optarg, BW_MAX_LEVEL, &level))
                return usage_err(C, "--level must be 0..6");
            break;
        case 'n':
            if (parse_u32(optarg, BW_MAX_N_IN, &incoming) || !incoming)
                return usage_err(C, "--incoming must be a positive count");
            break;
        case 'L':
            if (parse_u32(optarg, BW_MAX_LEVEL, &level_in))
                return usage_err(C, "--level-in must be 0..6");
            break;
        case 'f': fmt = optarg; break;
        case 'x': o.mode = BW_MODE_LOSSLESS; modes++; break;
        case 'e':
            if (parse_pos_double(optarg, &o.max_error))
                return usage_err(C, "--max-error must be a positive number");
            o.mode = BW_MODE_MAX_ERROR;
            modes++;
            break;
        case 'B': {
            uint32_t b;
            if (parse_u32(optarg, UINT32_MAX, &b) || !b)
                return usage_err(C, "--bytes must be a positive byte count");
            o.byte_budget = b;
            o.mode = BW_MODE_BYTES;
            modes++;
            break;
        }
        case 'r':
            if (parse_pos_double(optarg, &ratio))
                return usage_err(C, "--ratio must be a positive number");
            o.mode = BW_MODE_BYTES;
            modes++;
            break;
        case 'w':
            if (!strcmp(optarg, "haar")) o.basis = BW_BASIS_HAAR;
            else if (!strcmp(optarg, "53")) o.basis = BW_BASIS_53;
            else if (!strcmp(optarg, "97")) o.basis = BW_BASIS_97;
            else if (!strcmp(optarg, "pred")) o.basis = BW_BASIS_PRED;
            else if (!strcmp(optarg, "auto")) o.basis = BW_BASIS_AUTO;
            else return usage_err(C, "--basis must be haar, 53, 97, pred or auto");
            break;
        case 's':
            if (parse_pos_double(optarg, &o.scale))
                return usage_err(C, "--scale must be a positive number");
            break;
        case 'D': o.device = optarg; break;
        case 'S': o.flags |= BW_FLAG_STREAM_ORDER; break;
        case 'C':
            if (!strcmp(optarg, "rice")) o.flags |= BW_FLAG_RICE;
            else if (!strcmp(optarg, "range")) o.flags &= ~BW_FLAG_RICE;
            else return usage_err(C, "--coder must be range or rice");
            break;
        case 'R': o.flags |= BW_FLAG_LOG_VALUE; break;
        case 'Y':
            o.flags &= ~(BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL | BWH_NO_MIRROR);
            if (!strcmp(optarg, "mirror")) o.flags |= BW_FLAG_MIRROR | BWH_NO_MIRROR;
            else if (!strcmp(optarg, "reciprocal")) o.flags |= BW_FLAG_RECIPROCAL | BWH_NO_MIRROR;
            else if (!strcmp(optarg, "both"))
                o.flags |= BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL | BWH_NO_MIRROR;
            else if (!strcmp(optarg, "none")) o.flags |= BWH_NO_MIRROR;
            else if (strcmp(optarg, "auto"))
                return usage_err(C, "--symmetry must be auto, mirror, reciprocal, both or none");
            break;
        case 'F': o.firmware = optarg; break;
        case 'K': {
            uint32_t k;
            if (parse_u32(optarg, 65535, &k))
                return usage_err(C, "--drop-chunk must be a chunk number");
            o.drop_chunk = (int)k;
            break;
        }
        case 'h': fputs(encode_help, stdout); return 0;
        default: return usage_err(C, "unknown option or missing argument");
        }
    }
    if (o.device && strcmp(o.device, "qemu") && strcmp(o.device, "linux") &&
        strcmp(o.device, "host"))
        return usage_err(C, "--device must be host, qemu or linux");
    if (o.device && !strcmp(o.device, "host"))
        o.device = NULL;
    while (optind < argc && nin < (int)(sizeof in / sizeof *in))
        in[nin++] = argv[optind++];
    if (!nin || !outp)
        return usage_err(C, "needs -i INPUT and -o OUTPUT");
    if (modes > 1)
        return usage_err(C, "give only one of --lossless, --max-error, --bytes, --ratio");
    if (incoming && level_in != UINT32_MAX)
        return usage_err(C, "--incoming and --level-in exclude each other");
    if ((incoming || level_in != UINT32_MAX) && level == UINT32_MAX)
        return usage_err(C, "--incoming / --level-in need --level");
    if (o.basis == BW_BASIS_PRED &&
        (level != UINT32_MAX || o.mode > BW_MODE_MAX_ERROR || (o.flags & BW_FLAG_STREAM_ORDER)))
        return usage_err(C, "--basis pred codes sets of spectra (no --level) with --lossless "
                            "or --max-error, not --stream");
    int is_sed = !strcmp(fmt, "sed");
    bwh_format_t f = BWH_FMT_F32;
    if (!strcmp(fmt, "u16")) f = BWH_FMT_U16;
    else if (!strcmp(fmt, "i32")) f = BWH_FMT_I32;
    else if (strcmp(fmt, "f32") && !is_sed)
        return usage_err(C, "--input-format must be f32, u16, i32 or sed");
    if (!is_sed && nin > 1)
        return usage_err(C, "several inputs are only for --input-format sed");

    int32_t *ints = NULL;
    float *floats = NULL;
    size_t count = 0; /* samples read */
    float scale = 1.0f;
    int rc = 1;
    uint8_t *payload = NULL;
    size_t plen = 0;
    if (is_sed) {
        for (int k = 0; k < nin; k++) {
            int32_t *v;
            uint32_t b;
            if (bwh_sed_read(in[k], &v, &b, NULL) != 0) {
                err(C, bwh_last_error());
                goto out;
            }
            if (!bands)
                bands = b;
            if (b != bands) {
                free(v);
                fprintf(stderr, "brdfwave %s: %s has %u channels, expected %u\n", C, in[k], b, bands);
                goto out;
            }
            int32_t *grown = realloc(ints, (count + b) * sizeof *ints);
            if (!grown) {
                free(v);
                err(C, "out of memory");
                goto out;
            }
            ints = grown;
            memcpy(ints + count, v, b * sizeof *v);
            count += b;
            free(v);
        }
        scale = (float)BWH_SED_SCALE;
        f = BWH_FMT_I32;
    } else {
        uint8_t *raw;
        size_t len;
        if (!bands) {
            usage_err(C, "--bands is required for raw input");
            rc = 2;
            goto out;
        }
        if (bwh_read_file(in[0], &raw, &len) != 0) {
            err(C, bwh_last_error());
            goto out;
        }
        size_t es = f == BWH_FMT_U16 ? 2 : 4;
        if (len % es) {
            fprintf(stderr, "brdfwave %s: %s: %zu bytes is not a whole number of %zu-byte samples\n",
                    C, in[0], len, es);
            free(raw);
            goto out;
        }
        count = len / es;
        if (f == BWH_FMT_F32) {
            floats = malloc((count ? count : 1) * sizeof *floats);
            for (size_t i = 0; floats && i < count; i++) {
                floats[i] = bwh_bits_to_float(bw_get_u32(raw + 4 * i));
            }
        } else {
            ints = malloc((count ? count : 1) * sizeof *ints);
            for (size_t i = 0; ints && i < count; i++)
                ints[i] = f == BWH_FMT_U16 ? (int32_t)bw_get_u16(raw + 2 * i)
                                           : (int32_t)bw_get_u32(raw + 4 * i);
        }
        free(raw);
        if (!floats && !ints) {
            err(C, "out of memory");
            goto out;
        }
    }

    bw_dims_t d;
    int st;
    if (level == UINT32_MAX) {
        if (count % bands || count == 0) {
            fprintf(stderr, "brdfwave %s: %zu samples is not a whole number of %u-band spectra\n", C,
                    count, bands);
            goto out;
        }
        st = bw_dims_make(&d, BW_SHAPE_SPECTRA, 0, 0, (uint32_t)(count / bands), bands);
    } else if (level_in != UINT32_MAX) {
        st = bw_dims_make(&d, BW_SHAPE_BRDF_FULL, level, level_in, 0, bands);
    } else if (incoming) {
        st = bw_dims_make(&d, BW_SHAPE_BRDF_ISO, level, 0, incoming, bands);
    } else {
        st = bw_dims_make(&d, BW_SHAPE_REFLECTANCE, level, 0, 1, bands);
    }
    if (st != BW_OK) {
        fprintf(stderr, "brdfwave %s: %s\n", C, bw_strerror(st));
        goto out;
    }
    size_t need = bw_dims_samples(&d);
    if (need != count) {
        fprintf(stderr,
                "brdfwave %s: input has %zu samples, the shape needs %zu "
                "(%u incoming x %u outgoing x %u bands)\n",
                C, count, need, d.n_in, d.n_out, d.bands);
        goto out;
    }
    if (ratio > 0) {
        double b = 4.0 * (double)need / ratio;
        if (b < 1)
            b = 1;
        o.byte_budget = b > (double)UINT32_MAX ? UINT32_MAX : (size_t)floor(b);
    }
    if (!floats && (o.flags & BW_FLAG_LOG_VALUE)) {
        usage_err(C, "--relative is for float input (--input-format f32)");
        rc = 2;
        goto out;
    }
    if (floats)
        st = bwh_encode_f32(&d, floats, &o, &payload, &plen);
    else {
        if (f == BWH_FMT_I32 && !is_sed && o.scale > 0)
            scale = (float)o.scale;
        bwh_encode_opts_t io = o;
        if (o.mode == BW_MODE_MAX_ERROR) {
            /* value units -> sample units. Values scaled by a non-unit step
             * are rounded to float32 when decoded: keep one ulp of the
             * largest value in hand for that rounding. */
            double margin = 0;
            if (scale != 1.0f) {
                double maxabs = 0;
                for (size_t i = 0; i < count; i++)
                    maxabs = fmax(maxabs, fabs((double)ints[i] * scale));
                float top = (float)(maxabs + o.max_error);
                margin = (double)nextafterf(top, INFINITY) - (double)top;
            }
            io.max_error = floor((o.max_error - margin) / scale);
            /* a bound finer than the integer grid: only exact coding meets it */
            if (io.max_error < 1 && o.max_error > 0)
                io.mode = BW_MODE_LOSSLESS;
        }
        if (bwh_decimal_exponent(scale))
            io.flags |= BW_FLAG_DECIMAL_SCALE;
        st = bwh_encode_i32(&d, ints, &io, scale, 0.0f, &payload, &plen);
    }
    if (st != 0) {
        err(C, bwh_last_error());
        goto out;
    }
    if (bwh_write_file(outp, payload, plen) != 0) {
        err(C, bwh_last_error());
        goto out;
    }
    if (o.device)
        printf("device %s: %zu samples -> %zu bytes, %llu %s (%.1f per sample)\n", o.device,
               need, plen, (unsigned long long)device_instructions,
               strcmp(o.device, "linux") ? "instructions" : "ns",
               (double)device_instructions / (double)need);
    rc = 0;
out:
    free(ints);
    free(floats);
    free(payload);
    return rc;
}

static const char decode_help[] =
    "usage: brdfwave decode -i IN.bwv -o OUT [--output-format f32|i32] [--max-samples N]\n"
    "\n"
    "Decodes a payload to raw little-endian samples in the encoder's layout:\n"
    "float32 values (default) or the codec's int32 samples. '-' is standard input\n"
    "or output; an OUT that is a device or a pipe is written to directly.\n"
    "  --max-samples N  refuse payloads that decode to more than N samples\n"
    "                   (default 67108864, 256 MiB of float32): a small payload\n"
    "                   can describe gigabytes\n";

int bw_cmd_decode(int argc, char **argv)
{
    static const struct option opts[] = {{"input", required_argument, 0, 'i'},
                                         {"output", required_argument, 0, 'o'},
                                         {"output-format", required_argument, 0, 'f'},
                                         {"max-samples", required_argument, 0, 'M'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *C = "decode", *inp = NULL, *outp = NULL, *fmt = "f32";
    uint32_t max_samples = 0;
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "i:o:h", opts, NULL)) != -1) {
        switch (c) {
        case 'i': inp = optarg; break;
        case 'o': outp = optarg; break;
        case 'f': fmt = optarg; break;
        case 'M':
            if (parse_u32(optarg, BW_MAX_SAMPLES, &max_samples) || !max_samples)
                return usage_err(C, "--max-samples must be 1..268435456");
            break;
        case 'h': fputs(decode_help, stdout); return 0;
        default: return usage_err(C, "unknown option or missing argument");
        }
    }
    if (!inp || !outp || optind != argc)
        return usage_err(C, "needs -i IN.bwv and -o OUT");
    int as_int = !strcmp(fmt, "i32");
    if (!as_int && strcmp(fmt, "f32"))
        return usage_err(C, "--output-format must be f32 or i32");
    uint8_t *p;
    size_t len;
    if (bwh_read_file(inp, &p, &len) != 0)
        return err(C, bwh_last_error());
    bw_header_t h;
    int32_t *s = NULL;
    float *v = NULL;
    /* one array: the integers, or the values in their place */
    if (bwh_decode_limit(p, len, max_samples, &h, as_int ? &s : NULL, as_int ? NULL : &v) != 0) {
        fprintf(stderr, "brdfwave %s: %s: %s\n", C, inp, bwh_last_error());
        free(p);
        return 1;
    }
    free(p);
    size_t n = bw_dims_samples(&h.dims);
    /* little-endian in place */
    uint8_t *raw = as_int ? (uint8_t *)s : (uint8_t *)v;
    for (size_t i = 0; i < n; i++)
        bw_put_u32(raw + 4 * i, as_int ? (uint32_t)s[i] : bwh_float_to_bits(v[i]));
    int rc = bwh_write_file(outp, raw, n * 4);
    free(raw);
    return rc ? err(C, bwh_last_error()) : 0;
}

static const char info_help[] = "usage: brdfwave info IN.bwv\n"
                                "\n"
                                "Prints the payload header as 'key: value' lines.\n";

int bw_cmd_info(int argc, char **argv)
{
    const char *C = "info";
    if (argc == 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) {
        fputs(info_help, stdout);
        return 0;
    }
    if (argc != 2 || argv[1][0] == '-')
        return usage_err(C, "needs one payload file");
    uint8_t *p;
    size_t len;
    if (bwh_read_file(argv[1], &p, &len) != 0)
        return err(C, bwh_last_error());
    bw_header_t h;
    int st = bw_header_read(p, len, &h);
    free(p);
    if (st != BW_OK) {
        fprintf(stderr, "brdfwave %s: %s: %s\n", C, argv[1], bw_strerror(st));
        return 1;
    }
    size_t n = bw_dims_samples(&h.dims);
    double scale = bwh_bits_to_float(h.scale_bits);
    printf("version: %u\n", h.version);
    printf("shape: %s\n", bwh_shape_name(h.dims.shape));
    printf("level_out: %u\n", h.dims.level_out);
    printf("level_in: %u\n", h.dims.level_in);
    printf("incoming: %u\n", h.dims.n_in);
    printf("outgoing: %u\n", h.dims.n_out);
    printf("bands: %u\n", h.dims.bands);
    printf("samples: %zu\n", n);
    printf("basis: %s\n", bwh_basis_name(h.basis));
    printf("spectral_levels: %u\n", h.spectral_levels);
    printf("mode: %s\n", bwh_mode_name(h.mode));
    printf("order: %s\n", h.flags & BW_FLAG_STREAM_ORDER ? "streamed" : "coarse-to-fine");
    printf("coder: %s\n", h.flags & BW_FLAG_RICE ? "rice" : "range");
    static const char *const sym[4] = {"none", "mirror", "reciprocal", "both"};
    printf("symmetry: %s\n", sym[(h.flags & BW_FLAG_MIRROR ? 1 : 0) +
                                 (h.flags & BW_FLAG_RECIPROCAL ? 2 : 0)]);
    printf("values: %s\n", h.flags & BW_FLAG_LOG_VALUE ? "exp(offset + scale * sample)"
                                                       : "offset + scale * sample");
    printf("max_error: %.9g\n", h.mode == BW_MODE_MAX_ERROR ? h.max_error * scale : 0.0);
    printf("prequant: %u\n", h.prequant);
    printf("step: %.4f\n", h.step_q8 / 256.0);
    printf("scale: %.9g\n", scale);
    printf("offset: %.9g\n", (double)bwh_bits_to_float(h.offset_bits));
    printf("payload_bytes: %u\n", h.payload_len);
    printf("bits_per_sample: %.6f\n", 8.0 * h.payload_len / (double)n);
    printf("ratio_vs_float32: %.3f\n", 4.0 * (double)n / h.payload_len);
    printf("crc32: 0x%08x\n", h.crc);
    return 0;
}

static const char compare_help[] =
    "usage: brdfwave compare [--format f32|u16|i32] REFERENCE TEST\n"
    "\n"
    "Compares two raw sample files of equal size: relative L1 and L2 in percent\n"
    "(the paper's eq. 7 and 8; samples whose reference is 0 are counted and left\n"
    "out of those two), RMSE, max absolute error and PSNR (peak = max |reference|).\n";

static int load_as_float(const char *path, const char *fmt, float **out, size_t *n)
{
    uint8_t *raw;
    size_t len;
    if (bwh_read_file(path, &raw, &len) != 0)
        return -1;
    size_t es = !strcmp(fmt, "u16") ? 2 : 4;
    if (len % es) {
        free(raw);
        fprintf(stderr, "brdfwave compare: %s: %zu bytes is not a whole number of samples\n", path,
                len);
        return -2;
    }
    *n = len / es;
    float *v = malloc((*n ? *n : 1) * sizeof *v);
    if (!v) {
        free(raw);
        return -1;
    }
    for (size_t i = 0; i < *n; i++) {
        if (es == 2) {
            v[i] = (float)bw_get_u16(raw + 2 * i);
            continue;
        }
        uint32_t b = bw_get_u32(raw + 4 * i);
        v[i] = !strcmp(fmt, "i32") ? (float)(int32_t)b : bwh_bits_to_float(b);
    }
    free(raw);
    *out = v;
    return 0;
}

int bw_cmd_compare(int argc, char **argv)
{
    static const struct option opts[] = {
        {"format", required_argument, 0, 'f'}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
    const char *C = "compare", *fmt = "f32";
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (c) {
        case 'f': fmt = optarg; break;
        case 'h': fputs(compare_help, stdout); return 0;
        default: return usage_err(C, "unknown option or missing argument");
        }
    }
    if (strcmp(fmt, "f32") && strcmp(fmt, "u16") && strcmp(fmt, "i32"))
        return usage_err(C, "--format must be f32, u16 or i32");
    if (argc - optind != 2)
        return usage_err(C, "needs two files: REFERENCE TEST");
    float *a = NULL, *b = NULL;
    size_t na, nb;
    int r = load_as_float(argv[optind], fmt, &a, &na);
    if (r == 0)
        r = load_as_float(argv[optind + 1], fmt, &b, &nb);
    if (r != 0) {
        if (r == -1)
            err(C, bwh_last_error());
        free(a);
        return 1;
    }
    int rc = 0;
    if (na != nb) {
        fprintf(stderr, "brdfwave %s: sizes differ (%zu and %zu samples)\n", C, na, nb);
        rc = 1;
    } else {
        for (size_t i = 0; i < na && !rc; i++)
            if (!isfinite(a[i]) || !isfinite(b[i])) {
                fprintf(stderr, "brdfwave %s: sample %zu is not finite\n", C, i);
                rc = 1;
            }
    }
    if (!rc) {
        bwh_metrics_t m;
        bwh_metrics(a, b, na, &m);
        printf("samples: %zu\n", m.n);
        printf("zero_reference_samples: %zu\n", m.zero_ref);
        printf("relative_l1_percent: %.6g\n", m.rel_l1);
        printf("relative_l2_percent: %.6g\n", m.rel_l2);
        printf("rmse: %.9g\n", m.rmse);
        printf("max_abs_error: %.9g\n", m.max_abs);
        if (isinf(m.psnr))
            printf("psnr_db: inf\n");
        else
            printf("psnr_db: %.4f\n", m.psnr);
    }
    free(a);
    free(b);
    return rc;
}
