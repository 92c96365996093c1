/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave plot: PNG pictures of a user's own data (host-tools/plot/plot.h):
 * a BRDF or reflectance as a hemisphere map, spectra before and after
 * compression with the error below, and a rate-distortion curve of one
 * file. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "cli_progress.h"
#include "cli_shape.h"
#include "commands.h"
#include "plot.h"

static const char plot_help[] =
    "usage: brdfwave plot hemisphere -i IN -o OUT.png [options]\n"
    "       brdfwave plot spectra -i ORIGINAL --payload IN.bwv -o OUT.png [options]\n"
    "       brdfwave plot rd -i IN -o OUT.png [options]\n"
    "\n"
    "Pictures of measurements as PNG (brdfwave plot KIND --help for each):\n"
    "  hemisphere  a BRDF or a reflectance over the outgoing hemisphere, one incoming\n"
    "              direction and one band (or their mean), as a polar map of the\n"
    "              geodesic triangles\n"
    "  spectra     spectra of a measurement and of its payload, the error below\n"
    "  rd          the rate-distortion curve of one file: bits/sample against\n"
    "              relative L2 and max error, the encoder run over a range of budgets\n";

/* the input options every kind takes */
#define INPUT_HELP                                                                             \
    "  -i IN              a payload (.bwv), or raw samples (--bands and the shape\n"           \
    "                     options as for encode), or .sed files (--input-format sed,\n"        \
    "                     several -i make a set of spectra)\n"                                 \
    "  --input-format F   f32 (default), u16, i32 or sed\n"                                    \
    "  --scale S          i32: the value of one integer step\n"                                \
    "  --bands B, --level L, --incoming N, --level-in Li   the shape of raw input\n"

static const char hemi_help[] =
    "usage: brdfwave plot hemisphere -i IN -o OUT.png [--in K | --theta-in DEG]\n"
    "                                [--band B] [--log] [--range LO,HI] [--edges]\n"
    "                                [--title TEXT] [shape and input options]\n"
    "\n"
    "A BRDF or a spectral reflectance as a disc: the outgoing hemisphere seen from\n"
    "above, polar projection (the zenith angle theta linear in the radius, 90 degrees\n"
    "at the rim; the azimuth phi counter-clockwise from the right), each geodesic\n"
    "triangle in the colour of its value, with a colour bar. The incoming direction\n"
    "is marked 'in' (an isotropic BRDF's incoming directions lie at phi = 0, so its\n"
    "mirror direction is on the left).\n" INPUT_HELP
    "  --in K             incoming direction K (0-based; default: the one nearest\n"
    "                     --theta-in)\n"
    "  --theta-in DEG     the incoming direction nearest this zenith angle at phi = 0\n"
    "                     (default 45)\n"
    "  --band B           one band (0-based; default: band 0 of monochrome data, else\n"
    "                     the mean of the bands)\n"
    "  --log              colours by log10 of the value (values <= 0 at the bottom)\n"
    "  --range LO,HI      the colour scale's ends (default: the values' min and max)\n"
    "  --edges            the triangles' outlines\n"
    "  --title TEXT       the picture's title (default: the file and the slice)\n"
    "  -o OUT.png         the picture\n";

static const char spectra_help[] =
    "usage: brdfwave plot spectra -i ORIGINAL --payload IN.bwv -o OUT.png\n"
    "                             [--spectrum K]... [--title TEXT] [input options]\n"
    "\n"
    "Spectra of a measurement (solid) and of its payload decoded (dashed), one colour\n"
    "per spectrum, and below them the error, decoded minus original. The x axis is\n"
    "the wavelength in nm for .sed input, else the band.\n" INPUT_HELP
    "  --payload IN.bwv   the payload of ORIGINAL\n"
    "  --spectrum K       a spectrum (0-based: spectrum K of a set, or incoming K / n_out\n"
    "                     and outgoing K %% n_out of a BRDF); up to 6; default 0\n"
    "  --title TEXT       the picture's title\n"
    "  -o OUT.png         the picture\n";

static const char rd_help[] =
    "usage: brdfwave plot rd -i IN -o OUT.png [--ratios R,R,...] [--relative]\n"
    "                        [--title TEXT] [shape and input options]\n"
    "\n"
    "Encodes IN with byte budgets of 4 * samples / R bytes (as encode --ratio R) for\n"
    "each R, decodes every payload and plots bits/sample against the relative L2\n"
    "error in percent (left) and the max absolute error (right). Prints the points\n"
    "as CSV on standard output: ratio,bytes,bits_per_sample,relative_l2_percent,\n"
    "max_abs_error (and coding, with --relative). A budget too small for the data\n"
    "is left out.\n" INPUT_HELP
    "  --ratios LIST      the ratios against float32 (default\n"
    "                     2,3,4,6,8,12,16,24,32,48,64,96,128,192,256)\n"
    "  --relative         also the same budgets spent on relative accuracy (encode\n"
    "                     --relative: log(value) coded; positive float input)\n"
    "  --title TEXT       the picture's title\n"
    "  -o OUT.png         the picture\n";

static const char *const formats[] = {"f32", "u16", "i32", "sed", NULL};
enum { FMT_SED = 3 };

/* a measurement: float values in [incoming][outgoing][band] */
typedef struct {
    float *v;
    size_t n;
    bw_dims_t d;
    int32_t *ints;  /* integer input, for the encoder (rd) */
    float iscale;   /* their value: iscale * sample */
    double *wl;     /* .sed: the wavelengths of the bands (nm), else NULL */
    int payload;    /* read from a payload */
    bw_header_t h;  /* its header */
    const char *name;
} data_t;

static void data_free(data_t *m)
{
    free(m->v);
    free(m->ints);
    free(m->wl);
    memset(m, 0, sizeof *m);
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* a payload: decoded. 1 when path holds one, 0 when it does not, -1 when
 * it does and it does not decode */
static int load_payload(const char *path, data_t *m)
{
    uint8_t *p;
    size_t len;
    if (bwh_read_file(path, &p, &len) != 0)
        return -1;
    if (len < 2 || p[0] != 'B' || p[1] != 'W' || bwh_header_salvage(p, len, &m->h) != BW_OK) {
        free(p);
        return 0;
    }
    /* a damaged or cut payload in segments: what its whole segments hold */
    bwh_salvage_t sv;
    int rc = bwh_decode_salvage(p, len, 0, &m->h, NULL, &m->v, NULL, &sv);
    free(p);
    if (rc < 0)
        return bwh_fail("%s: %s", path, bwh_last_error());
    if (rc == 1)
        fprintf(stderr, "brdfwave plot: %s: damaged or cut: %u of %u segments lost%s; the "
                        "picture shows what the rest rebuilds (%zu samples approximate, %zu "
                        "missing)\n",
                path, sv.lost_segments, sv.segments, sv.tail_lost ? ", and the float tail" : "",
                sv.approx, sv.missing);
    m->d = m->h.dims;
    m->n = bw_dims_samples(&m->d);
    m->payload = 1;
    m->name = path;
    return 1;
}

/* The input of a kind: a payload, raw samples or .sed files. need_shape:
 * raw input must have a shape that gives dimensions (else bands alone). 0,
 * or -1 (bwh_last_error()), or CLI_EXIT_USAGE after a usage error (*usage
 * set). */
static int load(const cli_list_t *in, int fmt, int fmt_given, double scale, const cli_shape_t *sh,
                data_t *m, int *usage)
{
    memset(m, 0, sizeof *m);
    *usage = 0;
    m->iscale = 1.0f;
    if (in->n == 1 && !fmt_given) {
        int r = load_payload(in->item[0], m);
        if (r != 0)
            return r < 0 ? -1 : 0;
    }
    m->name = in->item[0];
    if (fmt != FMT_SED && in->n > 1) {
        *usage = 1;
        return cli_usage("several inputs are only for --input-format sed");
    }
    bwh_shape_t shape;
    int st = cli_shape_get(sh, &shape);
    if (st != 0) {
        *usage = 1;
        return st;
    }
    if (fmt != FMT_SED && !sh->has_bands) {
        *usage = 1;
        return cli_usage("--bands is required for raw input");
    }
    size_t count = 0;
    if (fmt == FMT_SED) {
        uint32_t bands = 0;
        int32_t *first = NULL;
        if (bwh_sed_read(in->item[0], &first, &bands, &m->wl) != 0)
            return -1;
        free(first);
        if (bwh_sed_read_set(in->item, in->n, &m->ints, &shape.bands, &count) != 0)
            return -1;
        m->iscale = (float)BWH_SED_SCALE;
    } else {
        if (bwh_raw_read(in->item[0], (bwh_format_t)fmt, fmt == BWH_FMT_F32 ? &m->v : NULL,
                         &m->ints, &count) != 0)
            return -1;
        if (fmt == BWH_FMT_I32 && scale > 0)
            m->iscale = (float)scale;
    }
    if (bwh_shape_dims(&shape, count, &m->d) != 0)
        return -1;
    m->n = count;
    if (!m->v) {
        m->v = malloc(count * sizeof *m->v);
        if (!m->v)
            return bwh_fail("out of memory");
        bwh_value_map_t vm = bwh_value_map(m->iscale, 0.0f,
                                           bwh_decimal_exponent(m->iscale) ? BW_FLAG_DECIMAL_SCALE
                                                                           : 0u);
        for (size_t i = 0; i < count; i++)
            m->v[i] = bwh_value_of(&vm, m->ints[i]);
    }
    return 0;
}

/* the options every kind takes */
typedef struct {
    const char *in_text[4096];
    cli_list_t in;
    int fmt, n_fmt;
    double scale;
    cli_shape_t sh;
    const char *out, *title;
} common_t;

#define COMMON_OPTS(c)                                                                         \
    {"input", 'i', CLI_LIST, .dest = &(c)->in},                                                \
    {"input-format", 0, CLI_CHOICE, .dest = &(c)->fmt, .choices = formats,                     \
     .seen = &(c)->n_fmt},                                                                     \
    {"scale", 0, CLI_POSITIVE, .dest = &(c)->scale}, CLI_SHAPE_BANDS(&(c)->sh),                \
    CLI_SHAPE_LEVELS(&(c)->sh), CLI_SHAPE_INCOMING(&(c)->sh),                                  \
    {"output", 'o', CLI_STRING, .dest = &(c)->out},                                            \
    {"title", 0, CLI_STRING, .dest = &(c)->title}

static void common_init(common_t *c)
{
    memset(c, 0, sizeof *c);
    c->in = (cli_list_t){c->in_text, 0, (int)(sizeof c->in_text / sizeof *c->in_text)};
}

/* --range LO,HI */
static int parse_range(const char *v, void *dest)
{
    double *r = dest;
    size_t k;
    if (cli_real_list(v, -1e30, 1e30, r, 2, &k) != 0 || k != 2 || !(r[1] > r[0]))
        return -1;
    return 0;
}

/* ---- hemisphere ------------------------------------------------------------ */

static int plot_hemi(int argc, char **argv)
{
    common_t c;
    common_init(&c);
    uint32_t in_k = 0, band = 0;
    int has_in = 0, has_band = 0, log = 0, edges = 0, has_range = 0;
    double theta_in = 45, range[2] = {0, 1};
    const cli_opt_t opts[] = {
        COMMON_OPTS(&c),
        {"in", 0, CLI_U32, .dest = &in_k, .hi = BW_MAX_N_IN, .seen = &has_in},
        {"theta-in", 0, CLI_REAL, .dest = &theta_in, .lo = 0, .hi = 90},
        {"band", 0, CLI_U32, .dest = &band, .hi = BW_MAX_BANDS, .seen = &has_band},
        {"log", 0, CLI_FLAG, .dest = &log},
        {"edges", 0, CLI_FLAG, .dest = &edges},
        {"range", 0, CLI_CALL, .dest = range, .parse = parse_range, .seen = &has_range,
         .what = "--range needs LO,HI with LO < HI"},
        {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, hemi_help, &first, &st))
        return st;
    while (first < argc && c.in.n < c.in.cap)
        c.in.item[c.in.n++] = argv[first++];
    if (!c.in.n || !c.out)
        return cli_usage("needs -i IN and -o OUT.png");
    data_t m;
    int usage;
    if (load(&c.in, c.fmt, c.n_fmt, c.scale, &c.sh, &m, &usage) != 0) {
        data_free(&m);
        return usage ? CLI_EXIT_USAGE : cli_fail("%s", bwh_last_error());
    }
    const bw_dims_t *d = &m.d;
    int rc = CLI_EXIT_FAIL;
    double *vals = NULL, (*wi)[3] = NULL;
    plot_canvas_t cv = {0};
    if (d->shape == BW_SHAPE_SPECTRA) {
        rc = cli_fail("%s: a set of spectra has no directions (brdfwave plot spectra shows it)",
                      m.name);
        goto out;
    }
    if (has_band && band >= d->bands) {
        rc = cli_usage("--band %u: the data have %u bands", band, d->bands);
        goto out;
    }
    if (has_in && in_k >= d->n_in) {
        rc = cli_usage("--in %u: the data have %u incoming directions", in_k, d->n_in);
        goto out;
    }
    vals = malloc(d->n_out * sizeof *vals);
    wi = malloc(d->n_in * sizeof *wi);
    if (!vals || !wi || bwh_shape_incoming(d, wi) != 0) {
        rc = cli_fail("out of memory");
        goto out;
    }
    if (!has_in) { /* the incoming direction nearest theta_in at phi = 0 */
        double t = theta_in * 3.14159265358979323846 / 180;
        double want[3] = {sin(t), 0, cos(t)}, best = -2;
        for (uint32_t k = 0; k < d->n_in; k++) {
            double dot = bwg_dot3(want, wi[k]);
            if (dot > best) {
                best = dot;
                in_k = k;
            }
        }
    }
    int mean = !has_band && d->bands > 1;
    double lo = INFINITY, hi = -INFINITY, lo_pos = INFINITY;
    for (uint32_t j = 0; j < d->n_out; j++) {
        const float *s = m.v + ((size_t)in_k * d->n_out + j) * d->bands;
        double v = 0;
        if (mean) {
            for (uint32_t b = 0; b < d->bands; b++)
                v += s[b];
            v /= d->bands;
        } else {
            v = s[has_band ? band : 0];
        }
        vals[j] = v;
        lo = fmin(lo, v);
        hi = fmax(hi, v);
        if (v > 0)
            lo_pos = fmin(lo_pos, v);
    }
    if (log) {
        if (!(hi > 0)) {
            rc = cli_fail("--log: no value above 0");
            goto out;
        }
        lo = lo_pos;
    }
    if (has_range) {
        lo = range[0];
        hi = range[1];
        if (log && !(lo > 0)) {
            rc = cli_usage("--log needs --range LO > 0");
            goto out;
        }
    }
    if (!(hi > lo)) { /* a constant map */
        double e = lo != 0 ? fabs(lo) * 0.05 : 1;
        hi = lo + e;
        lo -= log ? 0 : e;
        if (log)
            lo = hi / 10;
    }

    if (plot_canvas_init(&cv, 780, 640) != 0)
        goto fail;
    const int cx = 300, cy = 350, r = 240;
    if (plot_hemisphere(&cv, cx, cy, r, d->level_out, vals, lo, hi, log, edges) != 0)
        goto fail;
    if (d->shape != BW_SHAPE_REFLECTANCE) { /* the incoming direction */
        double x, y;
        plot_hemisphere_xy(cx, cy, r, wi[in_k], &x, &y);
        plot_circle(&cv, x + 0.5, y + 0.5, 7, 4, PLOT_BLACK);
        plot_circle(&cv, x + 0.5, y + 0.5, 7, 2, PLOT_WHITE);
        plot_text_halo(&cv, (int)x + 12, (int)y - 20, "in", 2, PLOT_LEFT);
    }
    char label[96];
    if (mean)
        snprintf(label, sizeof label, "value, mean of %u bands%s", d->bands,
                 log ? " (log scale)" : "");
    else
        snprintf(label, sizeof label, "value, band %u%s", has_band ? band : 0,
                 log ? " (log scale)" : "");
    plot_colour_bar(&cv, 600, cy - r, 630, cy + r, lo, hi, log, label);
    char title[512];
    if (c.title) {
        snprintf(title, sizeof title, "%s", c.title);
    } else {
        double th = acos(wi[in_k][2] > 1 ? 1 : wi[in_k][2]) * 180 / 3.14159265358979323846;
        double ph = atan2(wi[in_k][1], wi[in_k][0]) * 180 / 3.14159265358979323846;
        if (d->shape == BW_SHAPE_REFLECTANCE)
            snprintf(title, sizeof title, "%s: reflectance, level %u", base_name(m.name),
                     d->level_out);
        else
            snprintf(title, sizeof title, "%s: in %u of %u (theta %.1f\xb0, phi %.0f\xb0)",
                     base_name(m.name), in_k, d->n_in, th, ph < 0 ? ph + 360 : ph);
    }
    plot_text(&cv, 390, 22, title, 2, PLOT_CENTRE, PLOT_BLACK);
    if (plot_canvas_png(&cv, c.out) != 0)
        goto fail;
    rc = CLI_EXIT_OK;
    goto out;
fail:
    rc = cli_fail("%s", bwh_last_error());
out:
    plot_canvas_free(&cv);
    free(vals);
    free(wi);
    data_free(&m);
    return rc;
}

/* ---- spectra --------------------------------------------------------------- */

#define MAX_SPECTRA 6

static int plot_spectra(int argc, char **argv)
{
    common_t c;
    common_init(&c);
    const char *payload = NULL, *spec_text[MAX_SPECTRA];
    cli_list_t specs = {spec_text, 0, MAX_SPECTRA};
    const cli_opt_t opts[] = {COMMON_OPTS(&c),
                              {"payload", 0, CLI_STRING, .dest = &payload},
                              {"spectrum", 0, CLI_LIST, .dest = &specs},
                              {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, spectra_help, &first, &st))
        return st;
    while (first < argc && c.in.n < c.in.cap)
        c.in.item[c.in.n++] = argv[first++];
    if (!c.in.n || !payload || !c.out)
        return cli_usage("needs -i ORIGINAL, --payload IN.bwv and -o OUT.png");
    size_t idx[MAX_SPECTRA] = {0}, n_idx = specs.n ? (size_t)specs.n : 1;
    for (int k = 0; k < specs.n; k++) {
        uint32_t v;
        if (cli_u32(specs.item[k], 0, UINT32_MAX, 0, &v) != 0)
            return cli_usage("--spectrum needs an integer >= 0, got '%s'", specs.item[k]);
        idx[k] = v;
    }
    data_t dec, orig;
    memset(&orig, 0, sizeof orig);
    int usage, rc = CLI_EXIT_FAIL;
    double *x = NULL, *y = NULL;
    plot_canvas_t cv = {0};
    int r = load_payload(payload, &dec);
    if (r <= 0) {
        if (r == 0)
            bwh_fail("%s is not a payload", payload);
        data_free(&dec);
        return cli_fail("%s", bwh_last_error());
    }
    /* the original: its bands from the payload unless given */
    cli_shape_t sh = c.sh;
    if (!sh.has_bands && c.fmt != FMT_SED) {
        sh.has_bands = 1;
        sh.bands = dec.d.bands;
    }
    if (load(&c.in, c.fmt, c.n_fmt, c.scale, &sh, &orig, &usage) != 0) {
        rc = usage ? CLI_EXIT_USAGE : cli_fail("%s", bwh_last_error());
        goto out;
    }
    if (orig.payload) {
        rc = cli_fail("%s is a payload: -i takes the original measurement", orig.name);
        goto out;
    }
    uint32_t bands = dec.d.bands;
    if (orig.n != dec.n || orig.d.bands != bands) {
        rc = cli_fail("%s has %zu samples of %u bands, the payload %zu of %u", orig.name, orig.n,
                      orig.d.bands, dec.n, bands);
        goto out;
    }
    size_t n_spec = dec.n / bands;
    for (size_t k = 0; k < n_idx; k++)
        if (idx[k] >= n_spec) {
            rc = cli_usage("--spectrum %zu: there are %zu spectra", idx[k], n_spec);
            goto out;
        }
    x = malloc(bands * sizeof *x);
    y = malloc(bands * sizeof *y);
    if (!x || !y) {
        rc = cli_fail("out of memory");
        goto out;
    }
    for (uint32_t b = 0; b < bands; b++)
        x[b] = orig.wl ? orig.wl[b] : b;
    /* the ranges */
    double vlo = INFINITY, vhi = -INFINITY, elo = INFINITY, ehi = -INFINITY, emax = 0;
    for (size_t k = 0; k < n_idx; k++)
        for (uint32_t b = 0; b < bands; b++) {
            size_t i = idx[k] * bands + b;
            double o = orig.v[i], e = (double)dec.v[i] - o;
            vlo = fmin(vlo, fmin(o, dec.v[i]));
            vhi = fmax(vhi, fmax(o, dec.v[i]));
            elo = fmin(elo, e);
            ehi = fmax(ehi, e);
            emax = fmax(emax, fabs(e));
        }
    if (emax == 0) {
        elo = -1;
        ehi = 1;
    } else {
        ehi = fmax(fabs(elo), fabs(ehi));
        elo = -ehi;
    }
    plot_nice_range(&vlo, &vhi, 0);
    plot_nice_range(&elo, &ehi, 0);
    double xlo = x[0], xhi = x[bands - 1];
    if (!(xhi > xlo)) { /* one band: its point in the middle */
        xlo -= 0.5;
        xhi += 0.5;
    }
    /* a few bands: their points are marked (one band would be no line at all) */
    double mark = bands < 24 ? 4.0 : 0.0;
    if (plot_canvas_init(&cv, 960, 760) != 0)
        goto fail;
    plot_axes_t top = {130, 80, 920, 440, xlo, xhi, vlo, vhi, 0, 0};
    plot_axes_t bot = {130, 530, 920, 680, xlo, xhi, elo, ehi, 0, 0};
    char title[512], etitle[128];
    if (c.title)
        snprintf(title, sizeof title, "%s", c.title);
    else
        snprintf(title, sizeof title, "%s%s and %s (%s, %.3f bits/sample)",
                 base_name(orig.name), c.in.n > 1 ? " ..." : "", base_name(payload),
                 bwh_mode_name(dec.h.mode), 8.0 * dec.h.payload_len / (double)dec.n);
    snprintf(etitle, sizeof etitle, "decoded - original (max |error| %.4g over these)", emax);
    const char *xl = orig.wl ? "wavelength (nm)" : "band";
    plot_axes_draw(&cv, &top, NULL, "value", title);
    plot_axes_draw(&cv, &bot, xl, "error", etitle);
    plot_line(&cv, bot.x0, plot_py(&bot, 0), bot.x1, plot_py(&bot, 0), 1, PLOT_GREY, 0);
    /* the legend: the spectra, then one entry for every decoded line */
    const char *names[MAX_SPECTRA + 1];
    char name_buf[MAX_SPECTRA][48];
    plot_rgb_t cols[MAX_SPECTRA + 1];
    double dashes[MAX_SPECTRA + 1];
    for (size_t k = 0; k < n_idx; k++) {
        plot_rgb_t col = plot_series_colour((unsigned)k);
        const float *o = orig.v + idx[k] * bands, *dv = dec.v + idx[k] * bands;
        for (uint32_t b = 0; b < bands; b++)
            y[b] = o[b];
        plot_series(&cv, &top, x, y, bands, col, 3.0, 0, mark);
        for (uint32_t b = 0; b < bands; b++)
            y[b] = dv[b];
        plot_series(&cv, &top, x, y, bands, PLOT_BLACK, 1.0, 5, mark / 2);
        for (uint32_t b = 0; b < bands; b++)
            y[b] = (double)dv[b] - o[b];
        plot_series(&cv, &bot, x, y, bands, col, 1.2, 0, mark);
        snprintf(name_buf[k], sizeof name_buf[k], "spectrum %zu", idx[k]);
        names[k] = name_buf[k];
        cols[k] = col;
        dashes[k] = 0;
    }
    names[n_idx] = "decoded";
    cols[n_idx] = PLOT_BLACK;
    dashes[n_idx] = 5;
    plot_legend(&cv, &top, names, cols, dashes, n_idx + 1, PLOT_TOP_RIGHT);
    if (plot_canvas_png(&cv, c.out) != 0)
        goto fail;
    rc = CLI_EXIT_OK;
    goto out;
fail:
    rc = cli_fail("%s", bwh_last_error());
out:
    plot_canvas_free(&cv);
    free(x);
    free(y);
    data_free(&dec);
    data_free(&orig);
    return rc;
}

/* ---- rate-distortion --------------------------------------------------------- */

#define MAX_RATIOS 64

static int plot_rd(int argc, char **argv)
{
    common_t c;
    common_init(&c);
    const char *ratio_text = "2,3,4,6,8,12,16,24,32,48,64,96,128,192,256";
    int relative = 0;
    const cli_opt_t opts[] = {COMMON_OPTS(&c),
                              {"ratios", 0, CLI_STRING, .dest = &ratio_text},
                              {"relative", 0, CLI_FLAG, .dest = &relative},
                              {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, rd_help, &first, &st))
        return st;
    while (first < argc && c.in.n < c.in.cap)
        c.in.item[c.in.n++] = argv[first++];
    if (!c.in.n || !c.out)
        return cli_usage("needs -i IN and -o OUT.png");
    double ratios[MAX_RATIOS];
    size_t n_r;
    if (cli_real_list(ratio_text, 1e-3, 1e9, ratios, MAX_RATIOS, &n_r) != 0 || n_r == 0)
        return cli_usage("--ratios needs a list of numbers > 0, e.g. 4,8,16");
    data_t m;
    int usage;
    if (load(&c.in, c.fmt, c.n_fmt, c.scale, &c.sh, &m, &usage) != 0) {
        data_free(&m);
        return usage ? CLI_EXIT_USAGE : cli_fail("%s", bwh_last_error());
    }
    int rc = CLI_EXIT_FAIL;
    plot_canvas_t cv = {0};
    if (relative && (m.ints || m.payload)) {
        data_free(&m);
        return cli_usage("--relative is for float input (--input-format f32)");
    }
    /* one series per coding: [0] plain, [1] relative */
    int n_series = relative ? 2 : 1;
    double bps[2][MAX_RATIOS], l2[2][MAX_RATIOS], mx[2][MAX_RATIOS];
    size_t pts[2] = {0, 0};
    double exact_bps = 0; /* the smallest payload that decoded exactly */
    printf("ratio,bytes,bits_per_sample,relative_l2_percent,max_abs_error%s\n",
           relative ? ",coding" : "");
    cli_progress_start("%zu samples, %zu budgets", m.n, n_r * (size_t)n_series);
    for (int s = 0; s < n_series; s++)
        for (size_t k = 0; k < n_r; k++) {
            cli_progress_set((double)(s * n_r + k), (double)(n_r * (size_t)n_series));
            bwh_encode_opts_t o;
            memset(&o, 0, sizeof o);
            o.mode = BW_MODE_BYTES;
            o.basis = BW_BASIS_AUTO;
            o.flags = s ? BW_FLAG_LOG_VALUE : 0u;
            double b = floor(4.0 * (double)m.n / ratios[k]);
            o.byte_budget = b < 1 ? 1 : b > (double)UINT32_MAX ? UINT32_MAX : (size_t)b;
            uint8_t *p = NULL;
            size_t len = 0;
            int er = m.ints ? bwh_encode_scaled(&m.d, m.ints, &o, m.iscale, &p, &len)
                            : bwh_encode_f32(&m.d, m.v, &o, &p, &len);
            if (er != 0)
                continue; /* a budget too small for these data */
            bw_header_t h;
            float *dv = NULL;
            if (bwh_decode_limit(p, len, m.n, &h, NULL, &dv) != 0) {
                free(p);
                cli_progress_end();
                rc = cli_fail("a payload that does not decode: %s", bwh_last_error());
                goto out;
            }
            free(p);
            bwh_metrics_t mt;
            bwh_metrics(m.v, dv, m.n, &mt);
            free(dv);
            if (mt.max_abs == 0 && (exact_bps == 0 || 8.0 * (double)len / (double)m.n < exact_bps))
                exact_bps = 8.0 * (double)len / (double)m.n;
            size_t i = pts[s]++;
            bps[s][i] = 8.0 * (double)len / (double)m.n;
            l2[s][i] = mt.rel_l2;
            mx[s][i] = mt.max_abs;
            printf("%g,%zu,%.6f,%.6g,%.6g%s\n", ratios[k], len, bps[s][i], mt.rel_l2, mt.max_abs,
                   relative ? (s ? ",relative" : ",absolute") : "");
        }
    cli_progress_end();
    if (pts[0] + pts[1] == 0) {
        rc = cli_fail("every budget is too small for these data (try smaller --ratios)");
        goto out;
    }
    double xlo = INFINITY, xhi = 0, llo = INFINITY, lhi = 0, mlo = INFINITY, mhi = 0;
    for (int s = 0; s < n_series; s++)
        for (size_t i = 0; i < pts[s]; i++) {
            xlo = fmin(xlo, bps[s][i]);
            xhi = fmax(xhi, bps[s][i]);
            if (l2[s][i] > 0) {
                llo = fmin(llo, l2[s][i]);
                lhi = fmax(lhi, l2[s][i]);
            }
            if (mx[s][i] > 0) {
                mlo = fmin(mlo, mx[s][i]);
                mhi = fmax(mhi, mx[s][i]);
            }
        }
    plot_nice_range(&xlo, &xhi, 1);
    plot_nice_range(&llo, &lhi, 1);
    plot_nice_range(&mlo, &mhi, 1);
    if (plot_canvas_init(&cv, 1100, 560) != 0)
        goto fail;
    plot_axes_t left = {120, 90, 520, 460, xlo, xhi, llo, lhi, 1, 1};
    plot_axes_t right = {660, 90, 1060, 460, xlo, xhi, mlo, mhi, 1, 1};
    plot_axes_draw(&cv, &left, "bits/sample", "relative L2 error (%)", NULL);
    plot_axes_draw(&cv, &right, "bits/sample", "max absolute error", NULL);
    const char *names[2] = {"absolute", "relative (log coded)"};
    plot_rgb_t cols[2] = {plot_series_colour(0), plot_series_colour(1)};
    for (int s = 0; s < n_series; s++) {
        plot_series(&cv, &left, bps[s], l2[s], pts[s], cols[s], 2, 0, 4);
        plot_series(&cv, &right, bps[s], mx[s], pts[s], cols[s], 2, 0, 4);
    }
    if (n_series > 1) {
        plot_legend(&cv, &left, names, cols, NULL, 2, PLOT_BOTTOM_LEFT);
        plot_legend(&cv, &right, names, cols, NULL, 2, PLOT_BOTTOM_LEFT);
    }
    if (exact_bps > 0) { /* a log axis has no 0 */
        char note[96];
        snprintf(note, sizeof note, "exact (error 0, not drawn) at %.3f bits/sample", exact_bps);
        plot_text(&cv, 550, 520, note, 2, PLOT_CENTRE, PLOT_GREY);
    }
    char title[512];
    if (c.title)
        snprintf(title, sizeof title, "%s", c.title);
    else
        snprintf(title, sizeof title, "%s%s: %zu samples, byte budgets of ratio %g to %g",
                 base_name(m.name), c.in.n > 1 ? " ..." : "", m.n, ratios[0], ratios[n_r - 1]);
    plot_text(&cv, 550, 24, title, 2, PLOT_CENTRE, PLOT_BLACK);
    if (plot_canvas_png(&cv, c.out) != 0)
        goto fail;
    rc = CLI_EXIT_OK;
    goto out;
fail:
    rc = cli_fail("%s", bwh_last_error());
out:
    plot_canvas_free(&cv);
    data_free(&m);
    return rc;
}

int bw_cmd_plot(int argc, char **argv)
{
    static const struct {
        const char *kind, *name;
        int (*run)(int argc, char **argv);
    } kinds[] = {{"hemisphere", "plot hemisphere", plot_hemi},
                 {"spectra", "plot spectra", plot_spectra},
                 {"rd", "plot rd", plot_rd}};
    if (argc < 2)
        return cli_usage("needs the kind of picture: hemisphere, spectra or rd");
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
        fputs(plot_help, stdout);
        return CLI_EXIT_OK;
    }
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++)
        if (!strcmp(argv[1], kinds[k].kind)) {
            cli_set_name(cli_prog(), kinds[k].name);
            return kinds[k].run(argc - 1, argv + 1);
        }
    if (argv[1][0] == '-')
        return cli_usage("the first argument is the kind of picture: hemisphere, spectra or rd "
                         "(before '%s')",
                         argv[1]);
    return cli_usage("unknown kind '%s' (hemisphere, spectra or rd)", argv[1]);
}
