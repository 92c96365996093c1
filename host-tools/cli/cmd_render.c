/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave render: the path tracer's options (host-tools/render/render.h). */
#define _POSIX_C_SOURCE 200809L /* sysconf */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bwh_error.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "cli_progress.h"
#include "commands.h"
#include "render.h"

#define MAX_SPP 1000000u

static const char render_help[] =
    "usage: brdfwave render [--scene sphereflake|room] [--material SPEC]...\n"
    "                       [--sampling uniform|cosine|analytic|wavelet] [--level J]\n"
    "                       [--spp N | --time SECONDS] [--size WxH] [--threads T]\n"
    "                       [--depth D] [--direct off|mis] [--seed S] [--exposure E]\n"
    "                       -o OUT.png\n"
    "\n"
    "Path-traces a closed room with diffuse walls and a light panel under the\n"
    "ceiling, and writes a PNG. Objects take the --material options in order\n"
    "(repeated when fewer are given):\n"
    "  sphereflake  one sphereflake (91 spheres) on the floor\n"
    "  room         a table (box), a sphere, a torus (6,144 triangles) on the\n"
    "               table, a sphereflake\n"
    "\n"
    "  --material SPEC    phong:KD,KS,N       modified Phong (default phong:0.05,0.9,60)\n"
    "                     ward:KD,KS,AX,AY    Ward anisotropic\n"
    "                     payload:FILE.bwv    a decoded BRDF payload (isotropic or full,\n"
    "                                         1 band or 3 bands read as R, G, B), e.g.\n"
    "                                         from brdfwave import-rgl + encode\n"
    "  --sampling S[,S]   next direction at the material's hits: uniform hemisphere,\n"
    "                     cosine, the analytic lobe (Phong, Ward; cosine for\n"
    "                     payloads) or the wavelet hierarchy (default wavelet); a\n"
    "                     comma list renders each in turn, side by side in one PNG\n"
    "  --level J          level of accuracy of the hierarchy, 0..6 (default 4)\n"
    "  --tables N         incoming tables for analytic models: isotropic, every 90/N\n"
    "                     degrees from the normal (default 32); anisotropic Ward,\n"
    "                     one per incoming triangle, at least N (default: the grid\n"
    "                     level whose triangles are no wider than the lobe, up to\n"
    "                     1024 triangles)\n"
    "  --supersample S    leaf integrals from 4^S points per leaf, 0..3 (default 1)\n"
    "  --mix M            weight of the cosine lobe in the hierarchy's pdf (default 0.05)\n"
    "  --spp N            paths per pixel (default 16)\n"
    "  --time SECONDS     instead: passes of one path per pixel until the process has\n"
    "                     spent SECONDS of CPU time rendering (equal-time runs)\n"
    "  --size WxH         image size (default 160x120)\n"
    "  --threads T        worker threads (default: the online CPUs)\n"
    "  --depth D          bounces (default 5)\n"
    "  --direct off|mis   off (default): paths reach the light only along the\n"
    "                     strategies' directions, as in sec. 6.2; mis: at every hit\n"
    "                     also one point drawn on the light panel, both weighted by\n"
    "                     the power heuristic with the strategy's pdf (multiple\n"
    "                     importance sampling: the same mean, less noise)\n"
    "  --seed S           random seed (default 1); images do not depend on --threads\n"
    "  --exposure E       scale before display (default 1)\n"
    "  -o, --output FILE  the PNG\n"
    "\n"
    "Prints key: value lines: material (with tables, the incoming tables of its\n"
    "hierarchy), build_seconds (the sampling structures), then per\n"
    "strategy: sampling, spp, cpu_seconds, wall_seconds, samples (directions drawn),\n"
    "samples_per_second (per CPU second), radiance (mean over the image and the\n"
    "channels, unclamped: the same for every strategy up to noise), mean (displayed\n"
    "intensity), and\n"
    "variance: the image variance of sec. 6.2 (per pixel the variance over its\n"
    "3 x 3 block of displayed intensities, mean of R, G, B clamped to [0, 1];\n"
    "averaged over the interior pixels). On a terminal a progress line shows while\n"
    "the work takes more than a second.\n";

/* comma-separated numbers in [0, 1e6]; exactly n of them */
static int number_list(const char *s, double *v, size_t n)
{
    size_t k;
    return cli_real_list(s, 0.0, 1e6, v, n, &k) != 0 || k != n ? -1 : 0;
}

/* --material phong:KD,KS,N | ward:KD,KS,AX,AY | payload:FILE */
static int material_spec(const char *spec, render_material_spec_t *m)
{
    memset(m, 0, sizeof *m);
    m->spec = spec;
    double v[4];
    if (!strncmp(spec, "phong:", 6)) {
        if (number_list(spec + 6, v, 3) != 0 || v[2] < 0.0)
            return cli_usage("--material phong:KD,KS,N needs three numbers >= 0");
        m->kind = MAT_PHONG;
        m->p.kd = v[0];
        m->p.ks = v[1];
        m->p.n = v[2];
    } else if (!strncmp(spec, "ward:", 5)) {
        if (number_list(spec + 5, v, 4) != 0 || !(v[2] > 0.0) || !(v[3] > 0.0))
            return cli_usage("--material ward:KD,KS,AX,AY needs four numbers, AX, AY > 0");
        m->kind = MAT_WARD;
        m->p.kd = v[0];
        m->p.ks = v[1];
        m->p.ax = v[2];
        m->p.ay = v[3];
    } else if (!strncmp(spec, "payload:", 8)) {
        m->kind = MAT_DATA;
        m->path = spec + 8;
    } else {
        return cli_usage("unknown material '%s' (phong:..., ward:..., payload:FILE)", spec);
    }
    return 0;
}

/* --sampling S[,S...]: up to 4 strategies */
static int parse_strategies(const char *v, void *dest)
{
    render_opts_t *o = dest;
    char buf[128];
    if (strlen(v) >= sizeof buf)
        return -1;
    strcpy(buf, v);
    o->n_strategies = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k;
        for (k = 0; k < 4 && strcmp(tok, render_strategy_names[k]); k++)
            ;
        if (k == 4 || o->n_strategies == 4)
            return -1;
        o->strategies[o->n_strategies++] = (enum strategy)k;
    }
    return o->n_strategies ? 0 : -1;
}

/* --size WxH */
static int parse_size(const char *v, void *dest)
{
    uint32_t *wh = dest;
    return cli_size2(v, 3, 8192, &wh[0], &wh[1]);
}

static void progress(void *ctx, const char *what, double done, double total)
{
    (void)ctx;
    cli_progress_text("%s", what);
    cli_progress_set(done, total);
}

int bw_cmd_render(int argc, char **argv)
{
    static const char *const scenes[] = {"sphereflake", "room", NULL};
    static const char *const direct_modes[] = {"off", "mis", NULL};
    const char *spec_text[RENDER_MAX_MATERIALS];
    cli_list_t specs = {spec_text, 0, RENDER_MAX_MATERIALS};
    render_opts_t o = {.scene = RENDER_SPHEREFLAKE, .strategies = {S_WAVELET}, .n_strategies = 1,
                       .sampler = {4, 1, 0, 0.05}, .exposure = 1.0};
    uint32_t spp = 16, size[2] = {160, 120}, depth = 5, threads = 0, seed = 1, tables = 0;
    const cli_opt_t opts[] = {
        {"scene", 0, CLI_CHOICE, .dest = &o.scene, .choices = scenes},
        {"material", 0, CLI_LIST, .dest = &specs},
        {"sampling", 0, CLI_CALL, .dest = &o, .parse = parse_strategies,
         .what = "--sampling needs uniform, cosine, analytic or wavelet (or up to 4 of them, "
                 "comma-separated)"},
        {"level", 0, CLI_U32, .dest = &o.sampler.level, .hi = BWH_SAMPLER_MAX_LEVEL},
        {"tables", 0, CLI_U32, .dest = &tables, .lo = 1, .hi = 1024},
        {"supersample", 0, CLI_U32, .dest = &o.sampler.supersample,
         .hi = BWH_SAMPLER_MAX_SUPERSAMPLE},
        {"mix", 0, CLI_REAL, .dest = &o.sampler.mix, .lo = 0, .hi = 1},
        {"spp", 0, CLI_U32, .dest = &spp, .lo = 1, .hi = MAX_SPP},
        {"time", 0, CLI_REAL, .dest = &o.time_budget, .lo = 1e-3, .hi = 1e6},
        {"size", 0, CLI_CALL, .dest = size, .parse = parse_size,
         .what = "--size needs WxH, 3..8192 each"},
        {"threads", 0, CLI_U32, .dest = &threads, .lo = 1, .hi = 256},
        {"depth", 0, CLI_U32, .dest = &depth, .lo = 1, .hi = 64},
        {"direct", 0, CLI_CHOICE, .dest = &o.direct, .choices = direct_modes},
        {"seed", 0, CLI_U32, .dest = &seed, .hi = UINT32_MAX},
        {"exposure", 0, CLI_REAL, .dest = &o.exposure, .lo = 1e-6, .hi = 1e6},
        {"output", 'o', CLI_STRING, .dest = &o.output},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, render_help, NULL, &st))
        return st;
    if (!o.output)
        return cli_usage("no output (-o OUT.png)");
    render_material_spec_t mats[RENDER_MAX_MATERIALS];
    if (specs.n == 0)
        specs.item[specs.n++] = "phong:0.05,0.9,60";
    for (int k = 0; k < specs.n; k++)
        if ((st = material_spec(specs.item[k], &mats[k])) != 0)
            return st;
    o.materials = mats;
    o.n_materials = specs.n;
    o.sampler.tables = tables;
    o.spp = spp;
    o.width = size[0];
    o.height = size[1];
    o.depth = depth;
    o.threads = threads ? threads : (unsigned)sysconf(_SC_NPROCESSORS_ONLN);
    o.seed = seed;
    o.progress = progress;
    /* the report is held until the progress line is gone, so that the two
     * never share a terminal line */
    char *report = NULL;
    size_t report_len = 0;
    FILE *rf = cli_progress_enabled() ? open_memstream(&report, &report_len) : NULL;
    cli_progress_start("building the materials");
    int rc = render_run(&o, rf ? rf : stdout);
    cli_progress_end();
    if (rf) {
        fclose(rf);
        fwrite(report, 1, report_len, stdout);
        free(report);
    }
    return rc != 0 ? cli_fail("%s", bwh_last_error()) : CLI_EXIT_OK;
}
