/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave info: a payload's header as key: value lines. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwh_decode.h"
#include "bwh_exact.h"
#include "bwh_ext.h"
#include "bwh_guarantee.h"
#include "bwh_meta.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_kv.h"
#include "commands.h"

static const char info_help[] =
    "usage: brdfwave info [--json] IN.bwv\n"
    "\n"
    "Prints the payload header as 'key: value' lines, then its guarantee and\n"
    "metadata (wavelengths, quantity and unit, incidence angles, instrument,\n"
    "time, location, free fields) and the bytes it takes. '-' is standard input.\n"
    "  --json  as one JSON object instead (the same keys; the metadata as the\n"
    "          object \"metadata\", what 'encode --metadata' reads)\n";

/* The bytes the payload would be smaller without its metadata: the record
 * and, when it is the only one, the extension area's length field. */
static size_t metadata_bytes(const uint8_t *p, const bw_header_t *h)
{
    size_t pos = 0, at = 0, bytes = 0, records = 0;
    uint8_t type;
    const uint8_t *d;
    uint32_t dl;
    while (bw_ext_next(p + h->ext_off, h->ext_len, &pos, &type, &d, &dl)) {
        records++;
        if (type == BW_EXT_METADATA)
            bytes += pos - at;
        at = pos;
    }
    if (bytes && records == 1)
        for (uint32_t n = h->ext_len; n; n >>= 7)
            bytes++;
    return bytes;
}

int bw_cmd_info(int argc, char **argv)
{
    int json = 0;
    const cli_opt_t opts[] = {{"json", 0, CLI_FLAG, .dest = &json}, {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, info_help, &first, &st))
        return st;
    if (argc - first != 1)
        return cli_usage("needs one payload file");
    const char *path = argv[first];
    uint8_t *p;
    size_t len;
    if (bwh_read_file(path, &p, &len) != 0)
        return cli_fail("%s", bwh_last_error());
    bw_header_t h;
    int whole = bw_header_read(p, len, &h) == BW_OK;
    int hs = whole ? BW_OK : bwh_header_salvage(p, len, &h);
    if (hs != BW_OK) {
        free(p);
        return cli_fail("%s: %s", path, bw_strerror(hs));
    }
    /* the guarantee, and the records that map samples to values */
    bwh_guarantee_t g;
    const uint8_t *xd, *ld;
    uint32_t xl, ll, n_exc = 0;
    int map = -1;
    unsigned low = 0;
    int fx = bwh_ext_find(p, &h, BW_EXT_FLOAT_EXACT, &xd, &xl);
    int fl = bwh_ext_find(p, &h, BW_EXT_LOG_MAP, &ld, &ll);
    int gs = bwh_guarantee_of(p, &h, &g);
    if (gs != 0 || fx < 0 || fl < 0 || (fx == 1 && bwh_exact_fields(xd, xl, &map, &low, &n_exc) != 0)) {
        free(p);
        return cli_fail("%s: %s", path, gs != 0 ? bwh_last_error() : "malformed value records");
    }
    /* a step per chunk (record 0x05): K, the chunks, their step changes */
    const uint8_t *cd;
    uint32_t cl, chunk_k = 0, chunks = 0;
    int dmin = 0, dmax = 0;
    if (bwh_ext_find(p, &h, BW_EXT_CHUNK_STEPS, &cd, &cl) == 1) {
        const uint8_t *q = cd, *end = cd + cl;
        if (bwh_varint_get(&q, end, &chunk_k) != 0)
            chunk_k = 0; /* (the header's read vouched for it) */
        for (chunks = 0; chunk_k && q < end; q++, chunks++) {
            int dv = (int)(int8_t)*q;
            dmin = chunks == 0u || dv < dmin ? dv : dmin;
            dmax = chunks == 0u || dv > dmax ? dv : dmax;
        }
    }
    bwh_meta_t meta;
    int ms = bwh_meta_of_payload(p, len, &h, &meta);
    size_t meta_bytes = metadata_bytes(p, &h);
    /* each segment's length, from the table (its CRC vouched for it) */
    char *seg_lens = h.segment_vectors ? malloc((size_t)h.segments * 11u + 1u) : NULL;
    if (seg_lens) {
        size_t k = 0;
        for (uint32_t sg = 0; sg < h.segments; sg++) {
            const uint8_t *e = p + h.header_len + (size_t)sg * 8u;
            k += (size_t)sprintf(seg_lens + k, "%s%u", sg ? "," : "",
                                 (unsigned)e[0] | (unsigned)e[1] << 8 | (unsigned)e[2] << 16 |
                                     (unsigned)e[3] << 24);
        }
        seg_lens[k] = 0;
    }
    free(p);
    if (ms != 0) {
        free(seg_lens);
        return cli_fail("%s: %s", path, bwh_last_error());
    }
    char *mj = NULL;
    if (json && bwh_meta_to_json(&meta, &mj) != 0) {
        bwh_meta_free(&meta);
        free(seg_lens);
        return cli_fail("%s", bwh_last_error());
    }
    size_t n = bw_dims_samples(&h.dims);
    double scale = bwh_bits_to_float(h.scale_bits);
    cli_kv_t kv;
    char crc[16];
    snprintf(crc, sizeof crc, "0x%08x", h.crc);
    cli_kv_begin(&kv, stdout, json);
    cli_kv_uint(&kv, "version", h.version);
    cli_kv_str(&kv, "shape", bwh_shape_name(h.dims.shape));
    cli_kv_uint(&kv, "level_out", h.dims.level_out);
    cli_kv_uint(&kv, "level_in", h.dims.level_in);
    cli_kv_uint(&kv, "incoming", h.dims.n_in);
    cli_kv_uint(&kv, "outgoing", h.dims.n_out);
    cli_kv_uint(&kv, "bands", h.dims.bands);
    cli_kv_uint(&kv, "samples", n);
    cli_kv_str(&kv, "basis", h.band_access ? "pred (coarse to fine along the bands)"
                                           : bwh_basis_name(h.basis));
    cli_kv_uint(&kv, "spectral_levels", h.spectral_levels);
    cli_kv_str(&kv, "mode", bwh_mode_name(h.mode));
    cli_kv_str(&kv, "order", h.flags & BW_FLAG_STREAM_ORDER ? "streamed"
                             : h.embedded                  ? "embedded (bit planes)"
                                                           : "coarse-to-fine");
    cli_kv_str(&kv, "coder", h.band_access ? "columns (band access: record 0x06)"
                                           : bwh_coder_name(h.flags));
    if (h.segment_vectors) {
        cli_kv_uint(&kv, "segments", h.segments);
        cli_kv_uint(&kv, "segment_vectors", h.segment_vectors);
        /* where the segment table lies, and each segment's length (the
         * table's CRC vouched for them) */
        cli_kv_uint(&kv, "segment_table_offset", h.header_len);
        if (seg_lens)
            cli_kv_str(&kv, "segment_bytes", seg_lens);
    }
    if (chunk_k) {
        /* the byte budget's one encode: each chunk's step, step_q8 2^(d / 32) */
        char steps[64];
        snprintf(steps, sizeof steps, "%d to %d (1/32 octave)", dmin, dmax);
        cli_kv_uint(&kv, "chunks", chunks);
        cli_kv_uint(&kv, "chunk_vectors", chunk_k);
        cli_kv_str(&kv, "chunk_steps", steps);
    }
    if (!whole)
        cli_kv_str(&kv, "damaged", "yes: not whole (cut or changed); decode rebuilds what the "
                                   "whole segments hold");
    cli_kv_str(&kv, "symmetry", bwh_symmetry_name(h.flags));
    char values[96];
    if (map == BWH_EXACT_PLANES)
        snprintf(values, sizeof values,
                 "float32 bits: the samples their high plane, %u low bits raw", low);
    else
        snprintf(values, sizeof values, "%s",
                 fl == 1                        ? "the signed log map of record 0x02"
                 : h.flags & BW_FLAG_LOG_VALUE ? "exp(offset + scale * sample)"
                                               : "offset + scale * sample");
    cli_kv_str(&kv, "values", values);
    if (fx == 1)
        cli_kv_uint(&kv, "exceptions", n_exc);
    cli_kv_num(&kv, "max_error", "%.9g", h.mode == BW_MODE_MAX_ERROR ? h.max_error * scale : 0.0);
    cli_kv_uint(&kv, "prequant", h.prequant);
    cli_kv_num(&kv, "step", "%.4f", h.step_q8 / 256.0);
    cli_kv_num(&kv, "scale", "%.9g", scale);
    cli_kv_num(&kv, "offset", "%.9g", (double)bwh_bits_to_float(h.offset_bits));
    cli_kv_uint(&kv, "payload_bytes", h.payload_len);
    cli_kv_num(&kv, "bits_per_sample", "%.6f", 8.0 * h.payload_len / (double)n);
    cli_kv_num(&kv, "ratio_vs_float32", "%.3f", 4.0 * (double)n / h.payload_len);
    cli_kv_str(&kv, "crc32", crc);
    char rule[160], num[32];
    bwh_guarantee_rule(&g, rule, sizeof rule);
    cli_kv_str(&kv, "guarantee", bwh_guarantee_name(g.kind));
    cli_kv_str(&kv, "guarantee_rule", rule);
    cli_kv_str(&kv, "guarantee_recorded", g.recorded ? "yes" : "no (from the header)");
    bwh_shortest(g.max_error, num, sizeof num);
    cli_kv_numtext(&kv, "guarantee_max_error", num);
    bwh_shortest(g.max_rel_error, num, sizeof num);
    cli_kv_numtext(&kv, "guarantee_max_rel_error", num);
    bwh_shortest(g.rel_floor, num, sizeof num);
    cli_kv_numtext(&kv, "guarantee_rel_floor", num);
    cli_kv_uint(&kv, "metadata_bytes", meta_bytes);
    if (json) {
        cli_kv_json(&kv, "metadata", mj);
        free(mj);
    }
    cli_kv_end(&kv);
    if (!json)
        bwh_meta_print(&meta, stdout);
    bwh_meta_free(&meta);
    free(seg_lens);
    return CLI_EXIT_OK;
}
