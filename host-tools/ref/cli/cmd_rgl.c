/*
 * bwref import-rgl: samples a measured RGL BRDF (RGB tensor file) on the
 * geodesic grid, as raw float32 [incoming][outgoing][band] like
 * `brdfwave synth`, by inverting Dupuy and Jakob's warp (bwr_rgl.h).
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwr_rgl.h"
#include "bwref.h"
#include "bwr_geodesic.h"

#define RGL_PI 3.14159265358979323846

static void usage(void)
{
    printf("usage: %s import-rgl -i FILE.bsdf -o OUT.f32 [--level L]\n"
           "          [--incoming measured|N | --level-in Li]\n"
           "          [--channel rgb|r|g|b] [--times-cos] [--clamp]\n"
           "\n", bwref_progname);
    puts("Samples a measured BRDF of the RGL database (RGB tensor file) at the\n"
         "centres of the geodesic triangles of level L (default 4) and writes raw\n"
         "little-endian float32, layout [incoming][outgoing][band] (bands: 3 for\n"
         "rgb, else 1), the layout of `brdfwave synth` and `bwref ratios`.\n"
         "\n"
         "  --incoming measured  the file's own incidence angles below 89 degrees,\n"
         "                       in the plane phi = 0 (default)\n"
         "  --incoming N         N directions at phi = 0, theta_k = (k + 1/2) 90/N deg\n"
         "  --level-in Li        full BRDF: incoming directions = geodesic centres\n"
         "  --times-cos          write f cos(theta_o) (the loader's value) instead of f\n"
         "  --clamp              negative measured values (noise) become 0\n"
         "\n"
         "Prints the incidence angles used and the value range.");
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

int bwref_cmd_import_rgl(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *channel = "rgb", *incoming = "measured";
    int level = 4, level_in = -1, times_cos = 0, clamp = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage();
            return 0;
        }
        if (strcmp(a, "--times-cos") == 0) {
            times_cos = 1;
            continue;
        }
        if (strcmp(a, "--clamp") == 0) {
            clamp = 1;
            continue;
        }
        if (i + 1 >= argc)
            return bwref_fail("import-rgl", "option '%s' needs a value (or is unknown)", a);
        const char *v = argv[++i];
        char *end;
        if (strcmp(a, "-i") == 0) {
            in = v;
        } else if (strcmp(a, "-o") == 0) {
            out = v;
        } else if (strcmp(a, "--channel") == 0) {
            if (strcmp(v, "rgb") && strcmp(v, "r") && strcmp(v, "g") && strcmp(v, "b"))
                return bwref_fail("import-rgl", "--channel needs rgb, r, g or b");
            channel = v;
        } else if (strcmp(a, "--incoming") == 0) {
            incoming = v;
        } else if (strcmp(a, "--level") == 0 || strcmp(a, "--level-in") == 0) {
            long l = strtol(v, &end, 10);
            if (*end != '\0' || l < 0 || l > (long)BWR_GRID_MAX_LEVEL)
                return bwref_fail("import-rgl", "%s needs 0..%u", a, BWR_GRID_MAX_LEVEL);
            if (a[7] == '\0')
                level = (int)l;
            else
                level_in = (int)l;
        } else {
            return bwref_fail("import-rgl", "unknown option '%s'", a);
        }
    }
    if (in == NULL || out == NULL)
        return bwref_fail("import-rgl", "-i FILE.bsdf and -o OUT.f32 are required");
    unsigned long n_fixed = 0;
    if (strcmp(incoming, "measured") != 0) {
        char *end;
        errno = 0;
        n_fixed = strtoul(incoming, &end, 10);
        if (*end != '\0' || errno || n_fixed == 0 || n_fixed > 4096 || incoming[0] == '-')
            return bwref_fail("import-rgl", "--incoming needs 'measured' or 1..4096");
    }
    char err[512];
    bwr_rgl_t b;
    if (bwr_rgl_load(&b, in, err, sizeof err) != 0)
        return bwref_fail("import-rgl", "%s", err);

    size_t n_out = bwr_grid_count((unsigned)level), n_in = 0;
    double(*wo)[3] = malloc(n_out * sizeof *wo), (*wi)[3] = NULL;
    int rc = 2;
    if (wo == NULL || bwr_grid_centres((unsigned)level, wo, NULL) != 0) {
        rc = bwref_fail("import-rgl", "out of memory");
        goto done;
    }
    if (level_in >= 0) {
        n_in = bwr_grid_count((unsigned)level_in);
        wi = malloc(n_in * sizeof *wi);
        if (wi == NULL || bwr_grid_centres((unsigned)level_in, wi, NULL) != 0) {
            rc = bwref_fail("import-rgl", "out of memory");
            goto done;
        }
    } else {
        size_t cap = n_fixed ? n_fixed : b.n_theta;
        wi = malloc(cap * sizeof *wi);
        if (wi == NULL) {
            rc = bwref_fail("import-rgl", "out of memory");
            goto done;
        }
        for (size_t k = 0; k < cap; k++) {
            double th = n_fixed ? ((double)k + 0.5) * (RGL_PI / 2.0) / (double)n_fixed
                                : b.theta_i[k];
            if (!n_fixed && th >= 89.0 * RGL_PI / 180.0)
                continue; /* grazing incidence: no reflected light on the grid */
            wi[n_in][0] = sin(th);
            wi[n_in][1] = 0.0;
            wi[n_in][2] = cos(th);
            n_in++;
        }
    }
    int c0 = 0, nb = 3;
    if (strcmp(channel, "rgb") != 0) {
        nb = 1;
        c0 = channel[0] == 'r' ? 0 : channel[0] == 'g' ? 1 : 2;
    }
    FILE *f = fopen(out, "wb");
    if (f == NULL) {
        rc = bwref_fail("import-rgl", "cannot create '%s': %s", out, strerror(errno));
        goto done;
    }
    unsigned char *row = malloc(n_out * (size_t)nb * 4);
    double vmin = INFINITY, vmax = -INFINITY;
    size_t negatives = 0;
    for (size_t i = 0; row != NULL && i < n_in; i++) {
        for (size_t o = 0; o < n_out; o++) {
            double v[3];
            if (times_cos)
                bwr_rgl_eval_cos(&b, wi[i], wo[o], v);
            else
                bwr_rgl_eval(&b, wi[i], wo[o], v);
            for (int c = 0; c < nb; c++) {
                double x = v[c0 + c];
                if (x < 0.0) {
                    negatives++;
                    if (clamp)
                        x = 0.0;
                }
                vmin = fmin(vmin, x);
                vmax = fmax(vmax, x);
                put_f32le(row + 4 * (o * (size_t)nb + (size_t)c), (float)x);
            }
        }
        if (fwrite(row, 4, n_out * (size_t)nb, f) != n_out * (size_t)nb) {
            free(row);
            row = NULL;
        }
    }
    if (row == NULL || fclose(f) != 0) {
        if (row != NULL)
            free(row);
        else
            fclose(f);
        remove(out);
        rc = bwref_fail("import-rgl", "write to '%s' failed", out);
        goto done;
    }
    free(row);
    printf("material: %s\n", b.description);
    printf("incoming: %zu", n_in);
    if (level_in >= 0) {
        printf(" (geodesic level %d)\n", level_in);
    } else {
        printf(" (theta_i deg:");
        for (size_t i = 0; i < n_in; i++)
            printf(" %.2f", acos(wi[i][2]) * 180.0 / RGL_PI);
        printf(")\n");
    }
    printf("outgoing: %zu (level %d)\nbands: %d (%s)\nvalues: %s, min %.6g, max %.6g, "
           "negative %zu%s\n",
           n_out, level, nb, channel, times_cos ? "f cos(theta_o)" : "f (1/sr)", vmin, vmax,
           negatives, clamp && negatives ? " (clamped to 0)" : "");
    rc = 0;
done:
    free(wo);
    free(wi);
    bwr_rgl_free(&b);
    return rc;
}
