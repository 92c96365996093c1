/*
 * bwref ratios: compress a data set with the reference model at given
 * compression ratios (coefficients kept, the paper's r_c) or byte budgets
 * and print one CSV row per point: errors (eq. 7-8) and memory (Table 4).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_compress.h"
#include "bwr_model.h"
#include "bwref.h"

#define MAX_POINTS 256

static int parse_list(const char *s, double *out, size_t *n)
{
    size_t k = 0;
    const char *p = s;
    while (*p != '\0') {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno != 0 || !(v > 0.0) || k == MAX_POINTS)
            return -1;
        out[k++] = v;
        p = end;
        if (*p == ',')
            p++;
        else if (*p != '\0')
            return -1;
    }
    *n = k;
    return k ? 0 : -1;
}

static int parse_size(const char *s, size_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (s[0] < '0' || s[0] > '9' || *end != '\0' || errno != 0)
        return -1;
    *out = (size_t)v;
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

static void usage(void)
{
    puts("usage: bwref ratios -i FILE [--format f32|f64|text] [--bands B]\n"
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
         "with target 'initial' gives the uncompressed memory.");
}

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
    const char *in = NULL, *fmt = "f32", *basis = "db4", *in_basis = NULL;
    size_t bands = 1, incoming = 0, value_bytes = 8;
    int level = -1, level_in = -1, spec_levels = -1, in_levels = -1;
    bwr_ext_t ext = BWR_EXT_PERIODIZATION;
    double pts[MAX_POINTS] = {1, 2, 8, 16, 64, 128, 256};
    size_t npts = 7;
    int by_bytes = 0;
    job_t j;
    memset(&j, 0, sizeof j);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        size_t z;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage();
            return 0;
        }
        if (v == NULL)
            return bwref_fail("ratios", "option '%s' needs a value (or is unknown)", a);
        i++;
        if (strcmp(a, "-i") == 0)
            in = v;
        else if (strcmp(a, "--format") == 0)
            fmt = v;
        else if (strcmp(a, "--basis") == 0)
            basis = v;
        else if (strcmp(a, "--in-basis") == 0)
            in_basis = v;
        else if (strcmp(a, "--extension") == 0 &&
                 (strcmp(v, "periodization") == 0 || strcmp(v, "symmetric") == 0))
            ext = strcmp(v, "symmetric") == 0 ? BWR_EXT_SYMMETRIC : BWR_EXT_PERIODIZATION;
        else if (strcmp(a, "--bands") == 0 && parse_size(v, &bands) == 0 && bands > 0)
            ;
        else if (strcmp(a, "--level") == 0 && parse_size(v, &z) == 0 && z <= 6)
            level = (int)z;
        else if (strcmp(a, "--level-in") == 0 && parse_size(v, &z) == 0 && z <= 6)
            level_in = (int)z;
        else if (strcmp(a, "--incoming") == 0 && parse_size(v, &incoming) == 0 && incoming > 0)
            ;
        else if (strcmp(a, "--spec-levels") == 0 && strcmp(v, "deep") == 0)
            spec_levels = BWR_DWT_DEEP;
        else if (strcmp(a, "--spec-levels") == 0 && parse_size(v, &z) == 0 && z <= 24)
            spec_levels = (int)z;
        else if (strcmp(a, "--in-levels") == 0 && strcmp(v, "deep") == 0)
            in_levels = BWR_DWT_DEEP;
        else if (strcmp(a, "--in-levels") == 0 && parse_size(v, &z) == 0 && z <= 24)
            in_levels = (int)z;
        else if (strcmp(a, "--value-bytes") == 0 && parse_size(v, &value_bytes) == 0 &&
                 (value_bytes == 4 || value_bytes == 8))
            ;
        else if (strcmp(a, "--ratios") == 0 && parse_list(v, pts, &npts) == 0)
            by_bytes = 0;
        else if (strcmp(a, "--bytes") == 0 && parse_list(v, pts, &npts) == 0)
            by_bytes = 1;
        else if (strcmp(a, "--eps-in") == 0)
            j.th0.eps_in = atof(v);
        else if (strcmp(a, "--eps-vec") == 0)
            j.th0.eps_vec = atof(v);
        else if (strcmp(a, "--per-object") == 0 && (strcmp(v, "0") == 0 || strcmp(v, "1") == 0))
            j.th0.per_in = v[0] == '1';
        else if (strcmp(a, "--keep-coarse") == 0 && (strcmp(v, "0") == 0 || strcmp(v, "1") == 0))
            j.th0.keep_coarse = v[0] == '1';
        else if (strcmp(a, "--magnitude") == 0 && (strcmp(v, "l2") == 0 || strcmp(v, "raw") == 0))
            j.th0.raw = strcmp(v, "raw") == 0;
        else
            return bwref_fail("ratios", "bad option or value: %s %s", a, v);
    }
    if (in == NULL)
        return bwref_fail("ratios", "-i FILE is required");
    size_t n;
    int rr = strcmp(fmt, "f32") == 0   ? bwref_read_f32(in, &j.x, &n)
             : strcmp(fmt, "f64") == 0 ? read_f64(in, &j.x, &n)
             : strcmp(fmt, "text") == 0 ? bwref_read_text(in, &j.x, &n)
                                        : -2;
    if (rr == -2)
        return bwref_fail("ratios", "unknown --format '%s'", fmt);
    if (rr != 0 || n == 0)
        return bwref_fail("ratios", "cannot read '%s' as %s", in, fmt);
    const bwr_filter_t *f = NULL;
    if (strcmp(basis, "best") != 0) {
        f = bwr_filter_find(basis);
        if (f == NULL) {
            free(j.x);
            return bwref_fail("ratios", "unknown basis '%s'", basis);
        }
    }
    const bwr_filter_t *f0 = f ? f : bwr_filter_find("haar");
    if (level < 0) {
        if (n % bands != 0) {
            free(j.x);
            return bwref_fail("ratios", "%zu values are not a whole number of %zu-band spectra", n,
                              bands);
        }
        j.shape = bwr_shape_spectra(n / bands, bands, f0);
    } else {
        size_t no = (size_t)4 << (2 * level);
        size_t ni = level_in >= 0 ? (size_t)4 << (2 * level_in) : incoming ? incoming : 1;
        if (n != ni * no * bands) {
            free(j.x);
            return bwref_fail("ratios", "%zu values, the shape needs %zu", n, ni * no * bands);
        }
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
    j.shape.spec_ext = ext;
    if (in_basis != NULL) {
        if (level_in >= 0 || (level >= 0 && incoming == 0)) {
            free(j.x);
            return bwref_fail("ratios", "--in-basis applies to sets (spectra or --incoming N)");
        }
        j.shape.in_basis = bwr_filter_find(in_basis);
        j.shape.in_levels = in_levels;
        if (j.shape.in_basis == NULL) {
            free(j.x);
            return bwref_fail("ratios", "unknown basis '%s'", in_basis);
        }
    }
    j.value_bytes = value_bytes;

    bwr_model_t m;
    if (bwr_model_init(&m, &j.shape) != 0) {
        free(j.x);
        return bwref_fail("ratios", "cannot build the model (too few bands for the basis?)");
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
    for (size_t p = 0; p < npts && rc == 0; p++) {
        bwr_error_t e;
        bwr_memory_t fl, ne;
        size_t kept = 0;
        const bwr_filter_t *used = f;
        size_t keep;
        if (!by_bytes) {
            /* 1:1 keeps every coefficient (the odd-length extension of a
             * periodized 1-D transform may give a few more than samples) */
            keep = pts[p] <= 1.0 ? nc : (size_t)llround((double)ns / pts[p]);
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
                if ((double)fl.total_bytes <= pts[p]) {
                    best = mid;
                    lo = mid + 1;
                } else {
                    hi = mid - 1;
                }
            }
            if (rc == 0 && best == 0) {
                printf("%.0f,0,,,,,,,,,,,\n", pts[p]);
                continue;
            }
            if (rc == 0)
                rc = best_point(&j, f, best, &e, &fl, &ne, &kept, &used);
        }
        if (rc != 0)
            break;
        printf("%.6g,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%zu,%zu,%zu,%zu,%zu\n", pts[p], kept,
               (double)ns / (double)(kept ? kept : 1), e.rel_l1, e.rel_l2, e.rmse, e.max_abs,
               used ? used->name : "-", fl.values, fl.strips, fl.total_bytes, ne.strips,
               ne.total_bytes);
    }
    free(j.x);
    if (rc != 0)
        return bwref_fail("ratios", "compression failed (out of memory?)");
    return 0;
}
