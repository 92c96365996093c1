/*
 * brdfwave synth: virtual goniometer data sets from analytic BRDF models.
 *
 * Output: raw little-endian float32, layout [incoming][outgoing][band] with
 * one band. Outgoing directions are the centres of the geodesic triangles at
 * --level, in grid index order. Incoming directions are either N directions
 * in the plane phi = 0 (isotropic case, theta_k = (k + 0.5) * 90 / N deg) or
 * the geodesic centres at --level-in (full case).
 *
 * Models: modified Phong and Ward, brdf_models.h.
 */
#include <errno.h>
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdf_models.h"
#include "commands.h"
#include "geodesic.h"

#define SYNTH_PI 3.14159265358979323846
#define SYNTH_MAX_INCOMING 1048576ul

enum synth_model { MODEL_NONE, MODEL_PHONG, MODEL_WARD };

enum {
    OPT_MODEL = 256,
    OPT_KD,
    OPT_KS,
    OPT_N,
    OPT_AX,
    OPT_AY,
    OPT_LEVEL,
    OPT_INCOMING,
    OPT_LEVEL_IN
};

typedef struct {
    enum synth_model model;
    bwh_brdf_params_t p;
    int have_n, have_ax, have_ay;
    unsigned level;
    unsigned long incoming;  /* 0 = not given */
    int have_level_in;
    unsigned level_in;
    const char *out;
} synth_opts_t;

static void synth_usage(FILE *f)
{
    fputs(
        "usage: brdfwave synth --model phong|ward [model parameters]\n"
        "                      [--level L] (--incoming N | --level-in Li) -o OUT\n"
        "\n"
        "Writes a virtual goniometer data set as raw little-endian float32,\n"
        "layout [incoming][outgoing][band] with 1 band. Outgoing directions are\n"
        "the centres of the geodesic triangles at level L (4*4^L of them), in\n"
        "the codec's index order.\n"
        "\n"
        "  --model phong|ward  modified Phong (Lafortune & Willems) or Ward\n"
        "                      anisotropic\n"
        "  --kd X              diffuse albedo (default 0.75)\n"
        "  --ks X              specular albedo (default 0.25)\n"
        "  --n X               Phong exponent (phong only, default 20)\n"
        "  --ax X, --ay X      Ward roughness along x and y (ward only,\n"
        "                      defaults 0.35 and 0.05)\n"
        "  --level L           outgoing geodesic level (default 4)\n"
        "  --incoming N        isotropic case: N incoming directions at phi = 0,\n"
        "                      theta_k = (k + 0.5) * 90 / N degrees\n"
        "  --level-in Li       full case: incoming directions = the geodesic\n"
        "                      centres at level Li\n"
        "  -o, --output OUT    output file\n"
        "  -h, --help          this text\n"
        "\n"
        "Paper data sets:\n"
        "  Phong1: --model phong --kd 0.75 --ks 0.25 --n 20 --level 4 --incoming 16\n"
        "  Phong2: --model phong --kd 0.5 --ks 0.5 --n 50 --level 4 --incoming 16\n"
        "  Ward:   --model ward --ax 0.35 --ay 0.05 --kd 0.75 --ks 0.25 --level 4 --level-in 4\n",
        f);
}

static int synth_fail(const char *fmt, ...)
{
    va_list ap;
    fputs("brdfwave synth: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 2;
}

static int parse_double(const char *s, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_ulong(const char *s, unsigned long max, unsigned long *out)
{
    char *end;
    unsigned long v;
    if (s[0] < '0' || s[0] > '9')
        return -1;
    errno = 0;
    v = strtoul(s, &end, 10);
    if (*end != '\0' || errno == ERANGE || v > max)
        return -1;
    *out = v;
    return 0;
}

static void put_f32le(unsigned char *p, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    p[0] = (unsigned char)(u & 0xffu);
    p[1] = (unsigned char)((u >> 8) & 0xffu);
    p[2] = (unsigned char)((u >> 16) & 0xffu);
    p[3] = (unsigned char)((u >> 24) & 0xffu);
}

static int synth_parse(int argc, char **argv, synth_opts_t *o, int *help)
{
    static const struct option longopts[] = {
        {"model", required_argument, NULL, OPT_MODEL},
        {"kd", required_argument, NULL, OPT_KD},
        {"ks", required_argument, NULL, OPT_KS},
        {"n", required_argument, NULL, OPT_N},
        {"ax", required_argument, NULL, OPT_AX},
        {"ay", required_argument, NULL, OPT_AY},
        {"level", required_argument, NULL, OPT_LEVEL},
        {"incoming", required_argument, NULL, OPT_INCOMING},
        {"level-in", required_argument, NULL, OPT_LEVEL_IN},
        {"output", required_argument, NULL, 'o'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    int c;
    unsigned long ul;

    memset(o, 0, sizeof *o);
    o->p.kd = 0.75;
    o->p.ks = 0.25;
    o->p.n = 20.0;
    o->p.ax = 0.35;
    o->p.ay = 0.05;
    o->level = 4;
    *help = 0;

#ifdef __GLIBC__
    optind = 0; /* full re-initialisation of getopt's state */
#else
    optind = 1;
#endif
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":o:h", longopts, NULL)) != -1) {
        const char *opt = (optind > 0 && optind <= argc) ? argv[optind - 1] : "?";
        switch (c) {
        case OPT_MODEL:
            if (strcmp(optarg, "phong") == 0)
                o->model = MODEL_PHONG;
            else if (strcmp(optarg, "ward") == 0)
                o->model = MODEL_WARD;
            else
                return synth_fail("unknown model '%s' (expected phong or ward)",
                                  optarg);
            break;
        case OPT_KD:
            if (parse_double(optarg, &o->p.kd) != 0 || o->p.kd < 0.0)
                return synth_fail("--kd needs a finite value >= 0, got '%s'", optarg);
            break;
        case OPT_KS:
            if (parse_double(optarg, &o->p.ks) != 0 || o->p.ks < 0.0)
                return synth_fail("--ks needs a finite value >= 0, got '%s'", optarg);
            break;
        case OPT_N:
            if (parse_double(optarg, &o->p.n) != 0 || o->p.n < 0.0)
                return synth_fail("--n needs a finite value >= 0, got '%s'", optarg);
            o->have_n = 1;
            break;
        case OPT_AX:
            if (parse_double(optarg, &o->p.ax) != 0 || !(o->p.ax > 0.0))
                return synth_fail("--ax needs a finite value > 0, got '%s'", optarg);
            o->have_ax = 1;
            break;
        case OPT_AY:
            if (parse_double(optarg, &o->p.ay) != 0 || !(o->p.ay > 0.0))
                return synth_fail("--ay needs a finite value > 0, got '%s'", optarg);
            o->have_ay = 1;
            break;
        case OPT_LEVEL:
            if (parse_ulong(optarg, BWH_GRID_MAX_LEVEL, &ul) != 0)
                return synth_fail("--level needs an integer 0..%u, got '%s'",
                                  BWH_GRID_MAX_LEVEL, optarg);
            o->level = (unsigned)ul;
            break;
        case OPT_INCOMING:
            if (parse_ulong(optarg, SYNTH_MAX_INCOMING, &ul) != 0 || ul == 0)
                return synth_fail("--incoming needs an integer 1..%lu, got '%s'",
                                  SYNTH_MAX_INCOMING, optarg);
            o->incoming = ul;
            break;
        case OPT_LEVEL_IN:
            if (parse_ulong(optarg, BWH_GRID_MAX_LEVEL, &ul) != 0)
                return synth_fail("--level-in needs an integer 0..%u, got '%s'",
                                  BWH_GRID_MAX_LEVEL, optarg);
            o->level_in = (unsigned)ul;
            o->have_level_in = 1;
            break;
        case 'o':
            if (optarg[0] == '\0')
                return synth_fail("-o needs a file name");
            o->out = optarg;
            break;
        case 'h':
            *help = 1;
            return 0;
        case ':':
            return synth_fail("option '%s' needs a value", opt);
        default:
            if (optopt > 0 && optopt < 256)
                return synth_fail("unknown option '-%c' (see --help)", optopt);
            return synth_fail("unknown option '%s' (see --help)", opt);
        }
    }
    if (optind < argc)
        return synth_fail("unexpected argument '%s'", argv[optind]);
    if (o->model == MODEL_NONE)
        return synth_fail("--model phong|ward is required");
    if (o->model == MODEL_WARD && o->have_n)
        return synth_fail("--n applies to the phong model only");
    if (o->model == MODEL_PHONG && (o->have_ax || o->have_ay))
        return synth_fail("--ax/--ay apply to the ward model only");
    if (o->incoming != 0 && o->have_level_in)
        return synth_fail("give either --incoming or --level-in, not both");
    if (o->incoming == 0 && !o->have_level_in)
        return synth_fail("one of --incoming N or --level-in Li is required");
    if (o->out == NULL)
        return synth_fail("-o OUT is required");
    return 0;
}

int bw_cmd_synth(int argc, char **argv)
{
    synth_opts_t o;
    int help = 0, rc;
    size_t n_out, n_in, i, j;
    double (*out_dirs)[3] = NULL;
    double (*in_dirs)[3] = NULL;
    unsigned char *row = NULL;
    FILE *f = NULL;

    rc = synth_parse(argc, argv, &o, &help);
    if (rc != 0)
        return rc;
    if (help) {
        synth_usage(stdout);
        return 0;
    }

    n_out = bwh_grid_count(o.level);
    if (n_out == 0)
        return synth_fail("unsupported --level %u", o.level);
    n_in = o.have_level_in ? bwh_grid_count(o.level_in) : (size_t)o.incoming;
    if (n_in == 0)
        return synth_fail("unsupported --level-in %u", o.level_in);
    if (n_out > ((size_t)-1) / 4 / n_in)
        return synth_fail("data set too large");

    out_dirs = malloc(n_out * sizeof *out_dirs);
    in_dirs = malloc(n_in * sizeof *in_dirs);
    row = malloc(n_out * 4);
    if (out_dirs == NULL || in_dirs == NULL || row == NULL) {
        rc = synth_fail("out of memory");
        goto done;
    }
    if (bwh_grid_centres(o.level, out_dirs, NULL) != 0) {
        rc = synth_fail("geodesic grid at level %u failed", o.level);
        goto done;
    }
    if (o.have_level_in) {
        if (bwh_grid_centres(o.level_in, in_dirs, NULL) != 0) {
            rc = synth_fail("geodesic grid at level %u failed", o.level_in);
            goto done;
        }
    } else {
        for (i = 0; i < n_in; i++) {
            double th = ((double)i + 0.5) * (SYNTH_PI / 2.0) / (double)n_in;
            in_dirs[i][0] = sin(th);
            in_dirs[i][1] = 0.0;
            in_dirs[i][2] = cos(th);
        }
    }

    f = fopen(o.out, "wb");
    if (f == NULL) {
        rc = synth_fail("cannot create '%s': %s", o.out, strerror(errno));
        goto done;
    }
    for (i = 0; i < n_in; i++) {
        for (j = 0; j < n_out; j++) {
            double v = o.model == MODEL_PHONG ? bwh_brdf_phong(&o.p, in_dirs[i], out_dirs[j])
                                              : bwh_brdf_ward(&o.p, in_dirs[i], out_dirs[j]);
            if (!isfinite(v) || v > FLT_MAX) {
                rc = synth_fail("BRDF value not representable as float32 "
                                "(incoming %zu, outgoing %zu)", i, j);
                goto fail_file;
            }
            put_f32le(row + 4 * j, (float)v);
        }
        if (fwrite(row, 4, n_out, f) != n_out) {
            rc = synth_fail("write to '%s' failed: %s", o.out, strerror(errno));
            goto fail_file;
        }
    }
    if (fclose(f) != 0) {
        f = NULL;
        rc = synth_fail("write to '%s' failed: %s", o.out, strerror(errno));
        remove(o.out);
        goto done;
    }
    f = NULL;
    rc = 0;
    goto done;

fail_file:
    fclose(f);
    f = NULL;
    remove(o.out);
done:
    free(row);
    free(in_dirs);
    free(out_dirs);
    return rc;
}
