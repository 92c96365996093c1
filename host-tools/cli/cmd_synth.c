/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * brdfwave synth: virtual goniometer data sets from analytic BRDF models.
 *
 * Output: raw little-endian float32, layout [incoming][outgoing][band] with
 * one band. Outgoing directions are the centres of the geodesic triangles at
 * --level, in grid index order; incoming directions those of the shape
 * (bwh_shape.h): N directions in the plane phi = 0 (--incoming N) or the
 * geodesic centres at --level-in. Models: modified Phong and Ward,
 * brdf_models.h.
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdf_models.h"
#include "bw_le.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_shape.h"
#include "commands.h"
#include "geodesic.h"

static const char synth_help[] =
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
    "  Ward:   --model ward --ax 0.35 --ay 0.05 --kd 0.75 --ks 0.25 --level 4 --level-in 4\n";

enum { MODEL_PHONG, MODEL_WARD };

/* rows of the data set to out, one incoming direction at a time */
static int write_set(const char *out, int model, const bwh_brdf_params_t *p, const bw_dims_t *d,
                     const double (*wi)[3], const double (*wo)[3])
{
    uint8_t *row = malloc((size_t)d->n_out * 4);
    FILE *f = row ? fopen(out, "wb") : NULL;
    if (!row) {
        return cli_fail("out of memory");
    }
    if (!f) {
        free(row);
        return cli_fail("cannot create '%s': %s", out, strerror(errno));
    }
    int rc = CLI_EXIT_OK;
    for (size_t i = 0; i < d->n_in && !rc; i++) {
        for (size_t j = 0; j < d->n_out && !rc; j++) {
            double v = model == MODEL_PHONG ? bwh_brdf_phong(p, wi[i], wo[j])
                                            : bwh_brdf_ward(p, wi[i], wo[j]);
            if (!isfinite(v) || v > FLT_MAX)
                rc = cli_fail("BRDF value not representable as float32 (incoming %zu, "
                              "outgoing %zu)",
                              i, j);
            float fv = (float)v;
            uint32_t u;
            memcpy(&u, &fv, sizeof u);
            bw_put_u32(row + 4 * j, u);
        }
        if (!rc && fwrite(row, 4, d->n_out, f) != d->n_out)
            rc = cli_fail("write to '%s' failed: %s", out, strerror(errno));
    }
    free(row);
    if (fclose(f) != 0 && !rc)
        rc = cli_fail("write to '%s' failed: %s", out, strerror(errno));
    if (rc)
        remove(out);
    return rc;
}

int bw_cmd_synth(int argc, char **argv)
{
    static const char *const models[] = {"phong", "ward", NULL};
    int model = -1, has_n = 0, has_ax = 0, has_ay = 0;
    bwh_brdf_params_t p = {.kd = 0.75, .ks = 0.25, .n = 20.0, .ax = 0.35, .ay = 0.05};
    cli_shape_t sh = {.level = 4, .has_level = 1, .bands = 1, .has_bands = 1};
    const char *out = NULL;
    const cli_opt_t opts[] = {
        {"model", 0, CLI_CHOICE, .dest = &model, .choices = models},
        {"kd", 0, CLI_REAL, .dest = &p.kd, .lo = 0, .hi = DBL_MAX},
        {"ks", 0, CLI_REAL, .dest = &p.ks, .lo = 0, .hi = DBL_MAX},
        {"n", 0, CLI_REAL, .dest = &p.n, .lo = 0, .hi = DBL_MAX, .seen = &has_n},
        {"ax", 0, CLI_POSITIVE, .dest = &p.ax, .seen = &has_ax},
        {"ay", 0, CLI_POSITIVE, .dest = &p.ay, .seen = &has_ay},
        CLI_SHAPE_LEVELS(&sh),
        CLI_SHAPE_INCOMING(&sh),
        {"output", 'o', CLI_STRING, .dest = &out},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, synth_help, NULL, &st))
        return st;
    if (model < 0)
        return cli_usage("--model phong|ward is required");
    if (model == MODEL_WARD && has_n)
        return cli_usage("--n applies to the phong model only");
    if (model == MODEL_PHONG && (has_ax || has_ay))
        return cli_usage("--ax/--ay apply to the ward model only");
    bwh_shape_t shape;
    if ((st = cli_shape_get(&sh, &shape)) != 0)
        return st;
    if (!sh.has_incoming && !sh.has_level_in)
        return cli_usage("one of --incoming N or --level-in Li is required");
    if (out == NULL || !*out)
        return cli_usage("-o OUT is required");

    bw_dims_t d;
    if (bwh_shape_dims(&shape, 0, &d) != 0)
        return cli_fail("%s", bwh_last_error());
    double(*wo)[3] = malloc(d.n_out * sizeof *wo), (*wi)[3] = malloc(d.n_in * sizeof *wi);
    int rc;
    if (!wo || !wi || bwh_grid_centres(d.level_out, wo, NULL) != 0 ||
        bwh_shape_incoming(&d, wi) != 0)
        rc = cli_fail("out of memory");
    else
        rc = write_set(out, model, &p, &d, (const double(*)[3])wi, (const double(*)[3])wo);
    free(wo);
    free(wi);
    return rc;
}
