/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * bwref ratios: compress a data set with the reference model at given
 * compression ratios (coefficients kept, the paper's r_c) or byte budgets
 * and print one CSV row per point: errors (eq. 7-8) and memory (Table 4).
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwhost.h"
#include "bwr_compress.h"
#include "bwr_model.h"
#include "bwref.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "cli_shape.h"

#define MAX_POINTS 256

/* --ratios R1,R2,... or --bytes B1,B2,...: the points, the last option given */
typedef struct {
    double v[MAX_POINTS];
    size_t n;
    int by_bytes;
} points_t;

static int parse_points(const char *v, points_t *p, int by_bytes)
{
    points_t q;
    if (cli_real_list(v, DBL_TRUE_MIN, DBL_MAX, q.v, MAX_POINTS, &q.n) != 0)
        return -1;
    q.by_bytes = by_bytes;
    *p = q;
    return 0;
}

static int parse_ratios(const char *v, void *dest) { return parse_points(v, dest, 0); }

static int parse_bytes(const char *v, void *dest) { return parse_points(v, dest, 1); }

/* --spec-levels / --in-levels J|deep */
static int parse_levels(const char *v, void *dest)
{
    uint32_t z;
    if (!strcmp(v, "deep")) {
        *(int *)dest = BWR_DWT_DEEP;
        return 0;
    }
    if (cli_u32(v, 0, 24, 0, &z) != 0)
        return -1;
    *(int *)dest = (int)z;
    return 0;
}

static int read_f64(const char *path, double **out, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return -1;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    rewind(f);
    if (len <= 0 || len % 8 != 0) {
        fclose(f);
        return -1;
    }
    size_t cnt = (size_t)len / 8;
    double *v = malloc(cnt * sizeof *v);
    if (v == NULL || fread(v, 8, cnt, f) != cnt) {
        free(v);
        fclose(f);
        return -1;
    }
    fclose(f);
    *out = v;
    *n = cnt;
    return 0;
}

static const char ratios_help[] =
    "usage: bwref ratios -i FILE [--format f32|f64|text] [--bands B]\n"
    "                    [--level L [--incoming N | --level-in Li]]\n"
    "                    [--basis NAME|best] [--spec-levels J|deep]\n"
    "                    [--in-basis NAME] [--in-levels J|deep]\n"
    "                    [--extension periodization|symmetric]\n"
    "                    [--ratios R1,R2,... | --bytes B1,B2,...] [--value-bytes 4|8]\n"
    "                    [--eps-in X] [--eps-vec X] [--magnitude l2|raw]\n"
    "                    [--keep-coarse 0|1] [--per-object 0|1]\n"
    "\n"
    "Shape: without --level a set of spectra of B bands; with --level L a\n"
    "(spectral) reflectance, with --incoming N an isotropic BRDF (N incoming\n"
    "directions, outgoing transform only), with --level-in Li a full BRDF.\n"
    "Data layout [incoming][outgoing][band]. --in-basis: a 1-D wavelet across\n"
    "the set (the spectra, or the N incoming directions) as well. Levels:\n"
    "default PyWavelets' dwt_max_level, deep: down to 2 coefficients.\n"
    "--extension: PyWavelets' mode of the 1-D transforms (default\n"
    "periodization).\n"
    "\n"
    "--ratios: keep n_samples / R coefficients (the paper's r_c; default\n"
    "1,2,8,16,64,128,256). --bytes: the most coefficients whose flat sparse\n"
    "storage (value-bytes per value + 8 bytes per strip) fits in B bytes.\n"
    "--eps-in / --eps-vec: thresholds per space applied first (normalised\n"
    "norms of incoming objects / spectral vectors). --basis best: the\n"
    "spectral basis of lowest relative L2 error at each point (54 bases).\n"
    "--magnitude: rank coefficients by |c| times the L2 norm of their basis\n"
    "function (l2, default) or by |c| alone (raw). --keep-coarse 1: the\n"
    "scaling coefficients of the coarsest level are always kept.\n"
    "--per-object 1: every object of the set (spectrum, incoming direction)\n"
    "keeps its share of the coefficients (compressed one by one).\n"
    "\n"
    "Output CSV: target,kept,ratio,rel_l1,rel_l2,rmse,max_abs,basis,\n"
    "values,strips_flat,bytes_flat,strips_nested,bytes_nested; a first row\n"
    "with target 'initial' gives the uncompressed memory.\n";

typedef struct {
    double *x;
    bwr_shape_t shape;
    size_t value_bytes;
    bwr_thresholds_t th0;
} job_t;

/* compress with keep coefficients using basis f; fills the error and memory */
static int run_point(const job_t *j, const bwr_filter_t *f, size_t keep, bwr_error_t *e,
                     bwr_memory_t *flat, bwr_memory_t *nested, size_t *kept)
{
    bwr_shape_t s = j->shape;
    if (s.bands > 1)
        s.basis = f;
    bwr_model_t m;
    if (bwr_model_init(&m, &s) != 0)
        return -1;
    double *c = malloc(m.n_coefs * sizeof *c), *y = malloc(m.n_samples * sizeof *y);
    double *k = malloc(m.n_coefs * sizeof *k);
    int rc = -1;
    if (c == NULL || y == NULL || k == NULL || bwr_model_forward(&m, j->x, c) != 0)
        goto done;
    bwr_thresholds_t th = j->th0;
    th.keep = keep;
    bwr_compress_info_t inf;
    if (bwr_compress(&m, c, &th, k, &inf) != 0 || bwr_model_inverse(&m, k, y) != 0)
        goto done;
    bwr_error(j->x, y, m.n_samples, e);
    bwr_coef_memory(&m, k, j->value_bytes, flat, nested);
    *kept = inf.kept;
    rc = 0;
done:
    free(c);
    free(y);
    free(k);
    bwr_model_free(&m);
    return rc;
}

static int best_point(const job_t *j, const bwr_filter_t *fixed, size_t keep, bwr_error_t *e,
                      bwr_memory_t *flat, bwr_memory_t *nested, size_t *kept,
                      const bwr_filter_t **used)
{
    if (fixed != NULL || j->shape.bands == 1) {
        *used = j->shape.bands == 1 ? NULL : fixed;
        return run_point(j, fixed, keep, e, flat, nested, kept);
    }
    int found = 0;
    for (size_t b = 0; b < BWR_NUM_FILTERS; b++) {
        bwr_error_t eb;
        bwr_memory_t fb, nb;
        size_t kb;
        if (run_point(j, &bwr_filters[b], keep, &eb, &fb, &nb, &kb) != 0)
            continue; /* too few bands for this filter */
        if (!found || eb.rel_l2 < e->rel_l2) {
            *e = eb;
            *flat = fb;
            *nested = nb;
            *kept = kb;
            *used = &bwr_filters[b];
            found = 1;
        }
    }
    return found ? 0 : -1;
}

int bwref_cmd_ratios(int argc, char **argv)
{
    static const char *const formats[] = {"f32", "f64", "text", NULL};
    static const char *const extensions[] = {"periodization", "symmetric", NULL};
    static const char *const value_sizes[] = {"4", "8", NULL};
    static const char *const zero_one[] = {"0", "1", NULL};
    static const char *const magnitudes[] = {"l2", "raw", NULL};
    const char *in = NULL, *basis = "db4", *in_basis = NULL;
    int fmt = 0, ext = 0, value_size = 1, per_object = 0, keep_coarse = 0, raw = 0;
    int spec_levels = -1, in_levels = -1;
    cli_shape_t sh = {.bands = 1, .has_bands = 1};
    points_t pts = {{1, 2, 8, 16, 64, 128, 256}, 7, 0};
    job_t j;
    memset(&j, 0, sizeof j);
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &in},
        {"format", 0, CLI_CHOICE, .dest = &fmt, .choices = formats},
        {"basis", 0, CLI_STRING, .dest = &basis},
        {"in-basis", 0, CLI_STRING, .dest = &in_basis},
        {"extension", 0, CLI_CHOICE, .dest = &ext, .choices = extensions},
        CLI_SHAPE_BANDS(&sh),
        CLI_SHAPE_LEVELS(&sh),
        CLI_SHAPE_INCOMING(&sh),
        {"spec-levels", 0, CLI_CALL, .dest = &spec_levels, .parse = parse_levels,
         .what = "--spec-levels needs 0..24 or deep"},
        {"in-levels", 0, CLI_CALL, .dest = &in_levels, .parse = parse_levels,
         .what = "--in-levels needs 0..24 or deep"},
        {"value-bytes", 0, CLI_CHOICE, .dest = &value_size, .choices = value_sizes},
        {"ratios", 0, CLI_CALL, .dest = &pts, .parse = parse_ratios,
         .what = "--ratios needs numbers > 0, comma-separated"},
        {"bytes", 0, CLI_CALL, .dest = &pts, .parse = parse_bytes,
         .what = "--bytes needs numbers > 0, comma-separated"},
        {"eps-in", 0, CLI_REAL, .dest = &j.th0.eps_in, .lo = 0, .hi = DBL_MAX},
        {"eps-vec", 0, CLI_REAL, .dest = &j.th0.eps_vec, .lo = 0, .hi = DBL_MAX},
        {"per-object", 0, CLI_CHOICE, .dest = &per_object, .choices = zero_one},
        {"keep-coarse", 0, CLI_CHOICE, .dest = &keep_coarse, .choices = zero_one},
        {"magnitude", 0, CLI_CHOICE, .dest = &raw, .choices = magnitudes},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, ratios_help, NULL, &st))
        return st;
    if (in == NULL)
        return cli_usage("-i FILE is required");
    bwh_shape_t shape;
    if ((st = cli_shape_get(&sh, &shape)) != 0)
        return st;
    j.th0.per_in = per_object;
    j.th0.keep_coarse = keep_coarse;
    j.th0.raw = raw;
    size_t value_bytes = value_size ? 8 : 4, bands = sh.bands;
    int by_bytes = pts.by_bytes;
    size_t n;
    int rr = fmt == 0 ? bwref_read_f32(in, &j.x, &n)
             : fmt == 1 ? read_f64(in, &j.x, &n)
                        : bwref_read_text(in, &j.x, &n);
    if (rr != 0 || n == 0)
        return cli_fail("cannot read '%s' as %s", in, formats[fmt]);
    const bwr_filter_t *f = NULL;
    if (strcmp(basis, "best") != 0) {
        f = bwr_filter_find(basis);
        if (f == NULL) {
            free(j.x);
            return cli_usage("unknown basis '%s'", basis);
        }
    }
    const bwr_filter_t *f0 = f ? f : bwr_filter_find("haar");
    /* the shape's dimensions by the codec's rule, as a shape of the model */
    bw_dims_t d;
    if (bwh_shape_dims(&shape, n, &d) != 0) {
        free(j.x);
        return cli_fail("%s", bwh_last_error());
    }
    int level = shape.level, level_in = shape.level_in;
    size_t incoming = shape.incoming;
    if (d.shape == BW_SHAPE_SPECTRA) {
        j.shape = bwr_shape_spectra(d.n_in, bands, f0);
    } else {
        if (level_in >= 0)
            j.shape = bwr_shape_spectral_brdf(level_in, 0, (unsigned)level, bands, f0);
        else if (incoming)
            j.shape = bwr_shape_spectral_brdf(-1, incoming, (unsigned)level, bands, f0);
        else
            j.shape = bwr_shape_spectral_reflectance((unsigned)level, bands, f0);
        if (bands == 1)
            j.shape.kind = level_in >= 0 || incoming ? BWR_BRDF : BWR_REFLECTANCE;
    }
    if (bands == 1)
        j.shape.basis = NULL;
    j.shape.spec_levels = spec_levels;
    j.shape.spec_ext = ext ? BWR_EXT_SYMMETRIC : BWR_EXT_PERIODIZATION;
    if (in_basis != NULL) {
        if (level_in >= 0 || (level >= 0 && incoming == 0)) {
            free(j.x);
            return cli_usage("--in-basis applies to sets (spectra or --incoming N)");
        }
        j.shape.in_basis = bwr_filter_find(in_basis);
        j.shape.in_levels = in_levels;
        if (j.shape.in_basis == NULL) {
            free(j.x);
            return cli_usage("unknown basis '%s'", in_basis);
        }
    }
    j.value_bytes = value_bytes;

    bwr_model_t m;
    if (bwr_model_init(&m, &j.shape) != 0) {
        free(j.x);
        return cli_fail("cannot build the model (too few bands for the basis?)");
    }
    size_t ns = m.n_samples, nc = m.n_coefs;
    /* initial memory: every sample stored */
    {
        bwr_memory_t fl, ne;
        bwr_sample_memory(&m, value_bytes, &fl, &ne);
        printf("target,kept,ratio,rel_l1,rel_l2,rmse,max_abs,basis,values,strips_flat,bytes_flat,"
               "strips_nested,bytes_nested\n");
        printf("initial,%zu,1,0,0,0,0,%s,%zu,%zu,%zu,%zu,%zu\n", ns, "-", fl.values, fl.strips,
               fl.total_bytes, ne.strips, ne.total_bytes);
    }
    bwr_model_free(&m);
    int rc = 0;
    for (size_t p = 0; p < pts.n && rc == 0; p++) {
        bwr_error_t e;
        bwr_memory_t fl, ne;
        size_t kept = 0;
        const bwr_filter_t *used = f;
        size_t keep;
        if (!by_bytes) {
            /* 1:1 keeps every coefficient (the odd-length extension of a
             * periodized 1-D transform may give a few more than samples) */
            keep = pts.v[p] <= 1.0 ? nc : (size_t)llround((double)ns / pts.v[p]);
            if (keep < 1)
                keep = 1;
            if (keep > nc)
                keep = nc;
            rc = best_point(&j, f, keep, &e, &fl, &ne, &kept, &used);
        } else {
            /* largest keep whose flat storage fits: binary search */
            size_t lo = 1, hi = nc, best = 0;
            while (lo <= hi && rc == 0) {
                size_t mid = lo + (hi - lo) / 2;
                rc = run_point(&j, f ? f : f0, mid, &e, &fl, &ne, &kept);
                if (rc != 0)
                    break;
                if ((double)fl.total_bytes <= pts.v[p]) {
                    best = mid;
                    lo = mid + 1;
                } else {
                    hi = mid - 1;
                }
            }
            if (rc == 0 && best == 0) {
                printf("%.0f,0,,,,,,,,,,,\n", pts.v[p]);
                continue;
            }
            if (rc == 0)
                rc = best_point(&j, f, best, &e, &fl, &ne, &kept, &used);
        }
        if (rc != 0)
            break;
        printf("%.6g,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%zu,%zu,%zu,%zu,%zu\n", pts.v[p], kept,
               (double)ns / (double)(kept ? kept : 1), e.rel_l1, e.rel_l2, e.rmse, e.max_abs,
               used ? used->name : "-", fl.values, fl.strips, fl.total_bytes, ne.strips,
               ne.total_bytes);
    }
    free(j.x);
    if (rc != 0)
        return cli_fail("compression failed (out of memory?)");
    return 0;
}
