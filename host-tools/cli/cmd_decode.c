/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave decode: a payload to samples, with its metadata where the output
 * format holds it. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_meta.h"
#include "bwh_output.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_num.h"
#include "cli_progress.h"
#include "commands.h"

static const char decode_help[] =
    "usage: brdfwave decode -i IN.bwv -o OUT [--output-format F] [--max-samples N]\n"
    "                       [--mask MASK.u8] [--incoming K | --rows LIST |\n"
    "                       --region THETA,PHI,RADIUS | [--level L] [--level-in Li]]\n"
    "                       [--bands LIST | --wavelengths LO,HI]\n"
    "\n"
    "Decodes a payload in the encoder's layout, [incoming][outgoing][band], with\n"
    "its metadata (wavelengths, units, incidence angles, ...: 'brdfwave info').\n"
    "'-' is standard input or output; an OUT that is a device or a pipe is\n"
    "written to directly.\n"
    "  --output-format F  f32: float32 values (the default, and for a name ending\n"
    "                     in none of the below); i32: the codec's int32 samples;\n"
    "                     u16: those as uint16; raw: the type the input came in as;\n"
    "                     npy: a numpy array of that type (.npy); csv: a wavelength\n"
    "                     column and a column per spectrum, or a row per direction\n"
    "                     (.csv); envi: an ENVI header OUT.hdr beside the data (.img,\n"
    "                     .sli). f32, i32, u16, raw and npy keep the metadata in\n"
    "                     OUT.json (not on standard output)\n"
    "  --max-samples N    refuse payloads that decode to more than N samples\n"
    "                     (default 67108864, 256 MiB of float32): a small payload\n"
    "                     can describe gigabytes\n"
    "  --mask FILE        write the state of every sample, one byte each in the\n"
    "                     output's layout: 0 exact, 1 approximate (rebuilt from\n"
    "                     coarser levels: segments lost; or a float payload's\n"
    "                     value without the low bits its lost tail held), 2 missing\n"
    "  --incoming K       decode only incoming direction K of a BRDF (or spectrum K\n"
    "                     of a set of spectra), as a reflectance (one spectrum): only\n"
    "                     what it depends on is decoded (with --segments, only the\n"
    "                     segments that hold it)\n"
    "  --rows LIST        decode only the incoming directions (or spectra) listed,\n"
    "                     K or A-B (both included), comma-separated: a BRDF of those\n"
    "                     directions (or those spectra) in ascending order; what they\n"
    "                     share is decoded once\n"
    "  --region THETA,PHI,RADIUS\n"
    "                     decode only the incoming directions of a full BRDF whose\n"
    "                     triangles' centres lie within RADIUS degrees of the direction\n"
    "                     THETA (from the normal), PHI (from the x axis): a region of\n"
    "                     the incoming hemisphere; of an isotropic BRDF, the incidences\n"
    "                     within RADIUS of THETA (the payload's incidence angles; PHI\n"
    "                     plays no part); the rows chosen are named on standard error\n"
    "                     (as --rows takes them)\n"
    "  --level L          decode at a coarser outgoing level L (level of detail):\n"
    "                     each triangle's value is the mean of the samples below it\n"
    "                     (its Bio-Haar scaling value); only the coarser levels'\n"
    "                     coefficients are decoded (with --segments, only the\n"
    "                     segments that hold them)\n"    "  --level-in Li      a full BRDF at a coarser incoming level Li (with --level,\n"
    "                     both): each value the mean over the incoming triangle too;\n"
    "                     only the coarser incoming blocks are decoded\n"
    "  --bands LIST       keep only the bands listed (K or A-B, from 0, both\n"
    "                     included, comma-separated), in order, with their\n"
    "                     wavelengths, bandwidths and names; with any of the above\n"
    "                     and with --mask (the payload is decoded as without it,\n"
    "                     then the bands are kept; a payload coded with\n"
    "                     --band-access, alone, decodes only the bands from the\n"
    "                     first listed to the last)\n"
    "  --wavelengths LO,HI\n"
    "                     keep only the bands whose wavelength lies in [LO, HI], in\n"
    "                     the payload's wavelength unit ('brdfwave info'), as --bands\n"
    "--incoming, --rows and --region decode what the rows need alone, with\n"
    "segments only the segments that hold it.\n"
    "A payload coded in segments (encode --segments) that arrives damaged or cut\n"
    "still decodes: every whole segment is decoded, the rest is rebuilt from the\n"
    "coarser levels it has, and decode says how many samples that touched and\n"
    "exits with status 3 (the output is written).\n"
    "On a terminal a progress line shows while the work takes more than a second.\n";

static int parse_format(const char *v, void *dest)
{
    int f = bwh_output_format_from_name(v);
    if (f < 0)
        return -1;
    *(int *)dest = f;
    return 0;
}

/* the format a name asks for by its ending, f32 otherwise */
static int format_of_name(const char *path)
{
    static const struct {
        const char *end;
        int f;
    } ends[] = {{".npy", BWH_OUT_NPY}, {".csv", BWH_OUT_CSV}, {".img", BWH_OUT_ENVI},
                {".sli", BWH_OUT_ENVI}, {".bsq", BWH_OUT_ENVI}, {".bip", BWH_OUT_ENVI}};
    size_t n = strlen(path);
    for (size_t i = 0; i < sizeof ends / sizeof *ends; i++) {
        size_t e = strlen(ends[i].end);
        if (n > e && !strcmp(path + n - e, ends[i].end))
            return ends[i].f;
    }
    return BWH_OUT_F32;
}

/* "K" or "A-B" items, comma-separated, into marks[n] (marked 1), for the
 * option opt ("rows", "bands") of items called what. 0, or a usage
 * error. */
static int parse_marks(const char *opt, const char *what, const char *list, uint32_t n,
                       uint8_t *marks)
{
    memset(marks, 0, n);
    const char *q = list;
    for (;;) {
        const char *end = strchr(q, ','), *dash;
        size_t l = end ? (size_t)(end - q) : strlen(q);
        char item[32];
        uint32_t a, b;
        if (!l || l >= sizeof item)
            return cli_usage("--%s %s: K or A-B items, comma-separated", opt, list);
        memcpy(item, q, l);
        item[l] = 0;
        dash = strchr(item, '-');
        if (dash)
            item[dash - item] = 0;
        if (cli_u32(item, 0, UINT32_MAX - 1u, 0, &a) != 0 ||
            (dash ? cli_u32(dash + 1, a, UINT32_MAX - 1u, 0, &b) : (b = a, 0)) != 0)
            return cli_usage("--%s %s: K or A-B items (A <= B), comma-separated", opt, list);
        if (b >= n)
            return cli_usage("--%s %s: %s %u is past the last (%u)", opt, list, what, b, n - 1u);
        memset(marks + a, 1, (size_t)b - a + 1u);
        if (!end)
            return 0;
        q = end + 1;
    }
}

/* The rows marked, as --rows takes them: runs as A-B. */
static void print_rows(FILE *f, const uint8_t *rows, uint32_t n)
{
    const char *sep = "";
    for (uint32_t t = 0; t < n; t++) {
        if (!rows[t])
            continue;
        uint32_t e = t;
        while (e + 1u < n && rows[e + 1u])
            e++;
        if (e > t)
            fprintf(f, "%s%u-%u", sep, t, e);
        else
            fprintf(f, "%s%u", sep, t);
        sep = ",";
        t = e;
    }
}

/* Marks in marks[bands] the bands --bands lists (list) or whose
 * wavelengths (meta's) lie in wl[2]. 0, or an exit status. */
static int band_marks(const char *inp, const char *list, const double *wl, uint32_t bands,
                      const bwh_meta_t *meta, uint8_t *marks)
{
    if (list)
        return parse_marks("bands", "band", list, bands, marks);
    int k = bwh_bands_of_wavelengths(meta, bands, wl[0], wl[1], marks);
    if (k < 0)
        return cli_fail("%s: %s", inp, bwh_last_error());
    if (!k)
        return cli_fail("%s: no band's wavelength lies in [%g, %g] %s", inp, wl[0], wl[1],
                        bwh_wl_unit_name(meta->wl_unit));
    return 0;
}

/* Keeps the bands marked in marks[] (those of the payload, whose dimensions
 * are *full; the samples hold bands from `first` on) of the decoded samples
 * s, values v and mask (any NULL) of dimensions *d, and of the metadata.
 * 0, or an exit status. */
static int keep_marked(const char *inp, const uint8_t *marks, const bw_dims_t *full,
                       uint32_t first, bw_dims_t *d, bwh_meta_t *meta, int32_t *s, float *v,
                       uint8_t *mask)
{
    if (bwh_meta_bands(meta, full, marks) != 0 || bwh_keep_bands(d, marks + first, s, v, mask) != 0)
        return cli_fail("%s: %s", inp, bwh_last_error());
    return 0;
}

/* Keeps the bands --bands lists (list) or whose wavelengths lie in wl[2]
 * of the decoded samples s, values v and mask (any NULL) of dimensions *d,
 * and of the metadata. 0, or an exit status. */
static int keep_bands(const char *inp, const char *list, const double *wl, bw_dims_t *d,
                      bwh_meta_t *meta, int32_t *s, float *v, uint8_t *mask)
{
    uint8_t *marks = malloc(d->bands);
    if (!marks)
        return cli_fail("out of memory");
    bw_dims_t full = *d;
    int bad = band_marks(inp, list, wl, d->bands, meta, marks);
    if (!bad)
        bad = keep_marked(inp, marks, &full, 0, d, meta, s, v, mask);
    free(marks);
    return bad;
}

int bw_cmd_decode(int argc, char **argv)
{
    const char *inp = NULL, *outp = NULL, *maskp = NULL, *rowsp = NULL, *regionp = NULL;
    const char *bandsp = NULL, *wlp = NULL;
    int fmt = -1;
    uint32_t max_samples = 0, incoming = 0, lod = 0, lodin = 0;
    int has_incoming = 0, has_lod = 0, has_lodin = 0;
    const cli_opt_t opts[] = {
        {"input", 'i', CLI_STRING, .dest = &inp},
        {"output", 'o', CLI_STRING, .dest = &outp},
        {"output-format", 0, CLI_CALL, .dest = &fmt, .parse = parse_format,
         .what = "--output-format must be f32, i32, u16, raw, npy, csv or envi"},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = BW_MAX_SAMPLES},
        {"mask", 0, CLI_STRING, .dest = &maskp},
        {"incoming", 0, CLI_U32, .dest = &incoming, .lo = 0, .hi = UINT32_MAX - 1u,
         .seen = &has_incoming},
        {"level", 0, CLI_U32, .dest = &lod, .lo = 0, .hi = BW_MAX_LEVEL, .seen = &has_lod},
        {"level-in", 0, CLI_U32, .dest = &lodin, .lo = 0, .hi = BW_MAX_LEVEL, .seen = &has_lodin},
        {"rows", 0, CLI_STRING, .dest = &rowsp},
        {"region", 0, CLI_STRING, .dest = &regionp},
        {"bands", 0, CLI_STRING, .dest = &bandsp},
        {"wavelengths", 0, CLI_STRING, .dest = &wlp},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, decode_help, NULL, &st))
        return st;
    if (!inp || !outp)
        return cli_usage("needs -i IN.bwv and -o OUT");
    if (fmt < 0)
        fmt = format_of_name(outp);
    int has_lodout = has_lod;
    has_lod = has_lod || has_lodin;
    int parts = has_incoming + has_lod + !!rowsp + !!regionp;
    if (parts && maskp)
        return cli_usage("--mask is for a whole decode, not with --incoming, --rows, --region or "
                         "--level");
    if (parts > 1)
        return cli_usage("give one of --incoming, --rows, --region and --level (or --level-in)");
    double reg[3];
    size_t nreg = 0;
    if (regionp && (cli_real_list(regionp, -360, 360, reg, 3, &nreg) != 0 || nreg != 3))
        return cli_usage("--region THETA,PHI,RADIUS: three numbers, in degrees");
    double wl[2];
    size_t nwl = 0;
    if (bandsp && wlp)
        return cli_usage("give --bands or --wavelengths, not both");
    if (wlp && (cli_real_list(wlp, -1e12, 1e12, wl, 2, &nwl) != 0 || nwl != 2 || wl[0] > wl[1]))
        return cli_usage("--wavelengths LO,HI: two numbers, LO <= HI");
    if (fmt == BWH_OUT_ENVI && !strcmp(outp, "-"))
        return cli_usage("--output-format envi writes a header beside its data: not to '-'");
    uint8_t *p;
    size_t len;
    if (bwh_read_file(inp, &p, &len) != 0)
        return cli_fail("%s", bwh_last_error());
    bw_header_t h;
    int32_t *s = NULL;
    float *v = NULL;
    bwh_meta_t meta;
    bwh_meta_init(&meta);
    /* the integer formats need no values (a scale can take the values
     * beyond float32 where the integers are fine) */
    int ints_only = fmt == BWH_OUT_I32 || fmt == BWH_OUT_U16;
    cli_progress_start("%zu bytes", len);
    uint8_t *mask = NULL;
    bwh_salvage_t sv;
    bw_dims_t rowd;
    uint8_t *rows = NULL;
    if (rowsp || regionp) {
        bw_header_t f;
        int bad = 0;
        if (bwh_header_salvage(p, len, &f) != BW_OK) {
            bad = cli_fail("%s: %s", inp, bw_strerror(bw_header_read(p, len, &f)));
        } else if (!(rows = malloc(f.dims.n_in))) {
            bad = cli_fail("out of memory");
        } else if (rowsp) {
            bad = parse_marks("rows", "row", rowsp, f.dims.n_in, rows);
        } else {
            /* an isotropic BRDF's incidences: the payload's metadata's */
            bwh_meta_t rm;
            bwh_meta_init(&rm);
            double *inc = NULL;
            if (f.dims.shape == BW_SHAPE_BRDF_ISO && bwh_meta_of_payload(p, len, &f, &rm) == 0 &&
                rm.incidence.n == f.dims.n_in && (inc = malloc(rm.incidence.n * sizeof *inc)))
                for (size_t i = 0; i < rm.incidence.n; i++)
                    inc[i] = rm.inc_unit == BWH_ANGLE_RAD
                                 ? rm.incidence.v[i] * 180.0 / 3.14159265358979323846
                                 : rm.incidence.v[i];
            bwh_meta_free(&rm);
            int k = bwh_region_rows(&f, inc, reg[0], reg[1], reg[2], rows);
            free(inc);
            if (k < 0) {
                bad = cli_fail("%s: %s", inp, bwh_last_error());
            } else if (!k) {
                bad = cli_fail("%s: no incoming direction lies within %g degrees of (%g, %g)",
                               inp, reg[2], reg[0], reg[1]);
            } else {
                fprintf(stderr, "decode: %d of %u incoming directions: rows ", k, f.dims.n_in);
                print_rows(stderr, rows, f.dims.n_in);
                fputc('\n', stderr);
            }
        }
        if (bad) {
            free(rows);
            free(p);
            return bad;
        }
    }
    /* bands of a payload with band access: only those from the first
     * marked to the last decode */
    uint8_t *bmarks = NULL;
    uint32_t b_lo = 0, b_hi = 0;
    if ((bandsp || wlp) && !parts && !maskp) {
        bw_header_t f;
        if (bw_header_parse_fields(p, len, &f) == BW_OK && f.band_access) {
            bwh_meta_t bm;
            bwh_meta_init(&bm);
            int bad = !(bmarks = malloc(f.dims.bands)) ? cli_fail("out of memory")
                      : wlp && bwh_meta_of_payload(p, len, &f, &bm) != 0
                          ? cli_fail("%s: %s", inp, bwh_last_error())
                          : band_marks(inp, bandsp, wl, f.dims.bands, &bm, bmarks);
            bwh_meta_free(&bm);
            if (bad) {
                free(bmarks);
                free(p);
                cli_progress_end();
                return bad;
            }
            for (b_lo = 0; !bmarks[b_lo]; b_lo++)
                ;
            for (b_hi = f.dims.bands - 1u; !bmarks[b_hi]; b_hi--)
                ;
        }
    }
    int got = bmarks ? bwh_decode_bands(p, len, b_lo, b_hi + 1u, &h, &rowd, &s,
                                        ints_only ? NULL : &v)
              : rows         ? bwh_decode_rows(p, len, rows, &h, &rowd, &s, ints_only ? NULL : &v)
              : has_incoming ? bwh_decode_incoming(p, len, incoming, &h, &rowd, &s,
                                                   ints_only ? NULL : &v)
              : has_lod    ? bwh_decode_levels(p, len, has_lodout ? (int)lod : -1,
                                               has_lodin ? (int)lodin : -1, &h, &rowd, &s,
                                               ints_only ? NULL : &v)
                           : bwh_decode_salvage(p, len, max_samples, &h, &s,
                                                ints_only ? NULL : &v, maskp ? &mask : NULL, &sv);
    if (got < 0 || bwh_meta_of_payload(p, len, &h, &meta) != 0 ||
        (has_incoming && bwh_meta_row(&meta, &h.dims, incoming) != 0) ||
        (rows && bwh_meta_rows(&meta, &h.dims, rows) != 0)) {
        free(rows);
        free(bmarks);
        free(p);
        free(s);
        free(v);
        free(mask);
        cli_progress_end();
        return cli_fail("%s: %s", inp, bwh_last_error());
    }
    free(p);
    free(rows);
    if (parts)
        h.dims = rowd;
    if (has_lod) { /* the source's missing samples are at its own level */
        free(meta.missing);
        meta.missing = NULL;
        meta.n_missing = 0;
        meta.present &= ~BWH_M_MISSING;
    }
    int kb = 0;
    if (bmarks) {
        bw_dims_t full = h.dims;
        h.dims = rowd;
        kb = keep_marked(inp, bmarks, &full, b_lo, &h.dims, &meta, s, v, mask);
        free(bmarks);
    } else if (bandsp || wlp) {
        kb = keep_bands(inp, bandsp, wlp ? wl : NULL, &h.dims, &meta, s, v, mask);
    }
    if (kb) {
        free(s);
        free(v);
        free(mask);
        bwh_meta_free(&meta);
        cli_progress_end();
        return kb;
    }
    size_t n = bw_dims_samples(&h.dims);
    if (v)
        bwh_meta_put_missing(&meta, v, n);
    bwh_decoded_t d;
    d.dims = h.dims;
    d.values = v;
    d.ints = s;
    /* the integer samples are the values themselves */
    d.ints_are_values = h.scale_bits == 0x3F800000u && (h.offset_bits & 0x7FFFFFFFu) == 0 &&
                        !(h.flags & (BW_FLAG_LOG_VALUE | BW_FLAG_DECIMAL_SCALE)) &&
                        !(meta.present & BWH_M_MISSING);
    d.meta = &meta;
    cli_progress_text("%zu samples, writing", n);
    int rc = bwh_output_write(outp, fmt, &d);
    if (!rc && maskp)
        rc = bwh_write_file(maskp, mask, n);
    free(s);
    free(v);
    free(mask);
    bwh_meta_free(&meta);
    cli_progress_end();
    if (rc)
        return cli_fail("%s", bwh_last_error());
    if (got == 1) {
        cli_fail("%s: damaged or cut: %u of %u segments lost%s; %zu of %zu samples (%.2f %%) "
                 "%s, %zu (%.2f %%) missing%s",
                 inp, sv.lost_segments, sv.segments,
                 sv.tail_lost ? ", and the float tail (the values' low bits and exceptions)" : "",
                 sv.approx, n, n ? 100.0 * (double)sv.approx / (double)n : 0.0,
                 sv.tail_lost ? "approximate" : "rebuilt from coarser levels", sv.missing,
                 n ? 100.0 * (double)sv.missing / (double)n : 0.0,
                 maskp ? "" : " (--mask FILE marks them)");
        return CLI_EXIT_INCOMPLETE;
    }
    return CLI_EXIT_OK;
}
