/* SPDX-License-Identifier: BSD-2-Clause */
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

#include "bwh_meta.h"
#include "bwh_output.h"
#include "bwhost.h"
#include "bwr_rgl.h"
#include "bwref.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "cli_shape.h"
#include "geodesic.h"

#define RGL_PI 3.14159265358979323846

static const char rgl_help[] =
    "usage: PROG import-rgl -i FILE.bsdf -o OUT.f32 [--level L]\n"
    "          [--incoming measured|N | --level-in Li]\n"
    "          [--channel rgb|r|g|b] [--times-cos] [--clamp]\n"
    "\n"
    "Samples a measured BRDF of the RGL database (RGB tensor file) at the\n"
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
    "Prints the incidence angles used and the value range. The sidecar OUT.json\n"
    "(docs/FORMAT.md, Metadata) keeps the quantity, the channels and, for the\n"
    "measured angles, the incidence angles, so that 'brdfwave encode -i OUT.f32'\n"
    "carries them into the payload.\n";

/* --incoming measured|N: 0 for the file's own angles */
static int parse_incoming(const char *v, void *dest)
{
    if (!strcmp(v, "measured")) {
        *(uint32_t *)dest = 0;
        return 0;
    }
    return cli_u32(v, 1, 4096, 0, dest);
}

/* OUT.json: the quantity, the channels and, for the file's own incidence
 * angles, those (radians as the file gives them, like the encoder's .bsdf
 * reader); for a full BRDF the layout alone */
static int sidecar(const char *out, const bwr_rgl_t *b, size_t n_in, int measured, int full,
                   int times_cos, int channel, int nb)
{
    static const char *const names[] = {"red", "green", "blue"};
    bwh_meta_t m;
    bwh_meta_init(&m);
    m.quantity = times_cos ? BWH_Q_OTHER : BWH_Q_BRDF;
    m.present |= BWH_M_QUANTITY;
    int rc = times_cos ? bwh_meta_set_string(&m.unit, "sr^-1 (times cos theta_o)") : 0;
    rc = rc || bwh_meta_set_strings(&m.band_names, names + (channel ? channel - 1 : 0),
                                    (size_t)nb);
    if (!rc && b->description[0])
        rc = bwh_meta_add_field(&m, "description", b->description);
    if (!rc && measured) {
        double *th = malloc((n_in ? n_in : 1) * sizeof *th);
        size_t k = 0;
        for (size_t i = 0; th && i < b->n_theta && k < n_in; i++)
            if (b->theta_i[i] < 89.0 * RGL_PI / 180.0)
                th[k++] = b->theta_i[i];
        m.inc_unit = BWH_ANGLE_RAD;
        rc = !th || k != n_in || bwh_meta_set_numbers(&m.incidence, th, n_in);
        free(th);
    }
    if (!rc)
        rc = bwh_sidecar_write(out, &m, full ? BW_SHAPE_BRDF_FULL : BW_SHAPE_BRDF_ISO);
    bwh_meta_free(&m);
    return rc ? -1 : 0;
}

int bwref_cmd_import_rgl(int argc, char **argv)
{
    static const char *const channels[] = {"rgb", "r", "g", "b", NULL};
    const char *in = NULL, *out = NULL;
    int channel = 0, times_cos = 0, clamp = 0;
    uint32_t n_fixed = 0;
    cli_shape_t sh = {.level = 4, .has_level = 1};
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &in},
        {"output", 'o', CLI_STRING, .dest = &out},
        CLI_SHAPE_LEVELS(&sh),
        {"incoming", 0, CLI_CALL, .dest = &n_fixed, .parse = parse_incoming,
         .seen = &sh.has_incoming, .what = "--incoming needs 'measured' or 1..4096"},
        {"channel", 0, CLI_CHOICE, .dest = &channel, .choices = channels},
        {"times-cos", 0, CLI_FLAG, .dest = &times_cos},
        {"clamp", 0, CLI_FLAG, .dest = &clamp},
        {NULL}};
    char help[sizeof rgl_help + 16];
    const char *prog = cli_prog();
    snprintf(help, sizeof help, "usage: %s%s", prog, rgl_help + strlen("usage: PROG"));
    int st;
    if (!cli_parse(argc, argv, opts, help, NULL, &st))
        return st;
    if (in == NULL || out == NULL)
        return cli_usage("-i FILE.bsdf and -o OUT.f32 are required");
    int nb = channel == 0 ? 3 : 1;
    sh.incoming = n_fixed;
    sh.has_incoming = n_fixed > 0;
    sh.bands = (uint32_t)nb;
    sh.has_bands = 1;
    bwh_shape_t shape;
    if ((st = cli_shape_get(&sh, &shape)) != 0)
        return st;
    char err[512];
    bwr_rgl_t b;
    if (bwr_rgl_load(&b, in, err, sizeof err) != 0)
        return cli_fail("%s", err);

    unsigned level = sh.level;
    int level_in = sh.has_level_in ? (int)sh.level_in : -1;
    size_t n_out = bwh_grid_count(level), n_in = 0;
    double(*wo)[3] = malloc(n_out * sizeof *wo), (*wi)[3] = NULL;
    int rc = CLI_EXIT_FAIL;
    if (wo == NULL || bwh_grid_centres(level, wo, NULL) != 0) {
        rc = cli_fail("out of memory");
        goto done;
    }
    if (sh.has_level_in || n_fixed) {
        /* the shape's own incoming directions */
        bw_dims_t d;
        if (bwh_shape_dims(&shape, 0, &d) != 0) {
            rc = cli_fail("%s", bwh_last_error());
            goto done;
        }
        n_in = d.n_in;
        wi = malloc(n_in * sizeof *wi);
        if (wi == NULL || bwh_shape_incoming(&d, wi) != 0) {
            rc = cli_fail("out of memory");
            goto done;
        }
    } else {
        wi = malloc(b.n_theta * sizeof *wi);
        if (wi == NULL) {
            rc = cli_fail("out of memory");
            goto done;
        }
        for (size_t k = 0; k < b.n_theta; k++) {
            double th = b.theta_i[k];
            if (th >= 89.0 * RGL_PI / 180.0)
                continue; /* grazing incidence: no reflected light on the grid */
            wi[n_in][0] = sin(th);
            wi[n_in][1] = 0.0;
            wi[n_in][2] = cos(th);
            n_in++;
        }
    }
    int c0 = channel == 0 ? 0 : channel - 1;
    FILE *f = fopen(out, "wb");
    if (f == NULL) {
        rc = cli_fail("cannot create '%s': %s", out, strerror(errno));
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
                bwref_put_f32(row + 4 * (o * (size_t)nb + (size_t)c), (float)x);
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
        rc = cli_fail("write to '%s' failed", out);
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
    printf("outgoing: %zu (level %u)\nbands: %d (%s)\nvalues: %s, min %.6g, max %.6g, "
           "negative %zu%s\n",
           n_out, level, nb, channels[channel], times_cos ? "f cos(theta_o)" : "f (1/sr)", vmin,
           vmax,
           negatives, clamp && negatives ? " (clamped to 0)" : "");
    if (sidecar(out, &b, n_in, level_in < 0 && !n_fixed, level_in >= 0, times_cos, channel,
                nb) != 0) {
        remove(out);
        rc = cli_fail("%s", bwh_last_error());
        goto done;
    }
    rc = 0;
done:
    free(wo);
    free(wi);
    bwr_rgl_free(&b);
    return rc;
}
