/* brdfwave info: a payload's header as key: value lines. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwh_exact.h"
#include "bwh_ext.h"
#include "bwh_guarantee.h"
#include "bwh_meta.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "commands.h"

static const char info_help[] =
    "usage: brdfwave info IN.bwv [--json]\n"
    "\n"
    "Prints the payload header as 'key: value' lines, then its metadata\n"
    "(wavelengths, quantity and unit, incidence angles, instrument, time,\n"
    "location, free fields) and the bytes it takes. '-' is standard input.\n"
    "  --json  the metadata alone as JSON (what 'encode --metadata' reads)\n";

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
    int hs = bw_header_read(p, len, &h);
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
    bwh_meta_t meta;
    int ms = bwh_meta_of_payload(p, len, &h, &meta);
    size_t meta_bytes = metadata_bytes(p, &h);
    free(p);
    if (ms != 0)
        return cli_fail("%s: %s", path, bwh_last_error());
    if (json) {
        char *j;
        if (bwh_meta_to_json(&meta, &j) != 0) {
            bwh_meta_free(&meta);
            return cli_fail("%s", bwh_last_error());
        }
        printf("%s\n", j);
        free(j);
        bwh_meta_free(&meta);
        return CLI_EXIT_OK;
    }
    size_t n = bw_dims_samples(&h.dims);
    double scale = bwh_bits_to_float(h.scale_bits);
    printf("version: %u\n", h.version);
    printf("shape: %s\n", bwh_shape_name(h.dims.shape));
    printf("level_out: %u\n", h.dims.level_out);
    printf("level_in: %u\n", h.dims.level_in);
    printf("incoming: %u\n", h.dims.n_in);
    printf("outgoing: %u\n", h.dims.n_out);
    printf("bands: %u\n", h.dims.bands);
    printf("samples: %zu\n", n);
    printf("basis: %s\n", bwh_basis_name(h.basis));
    printf("spectral_levels: %u\n", h.spectral_levels);
    printf("mode: %s\n", bwh_mode_name(h.mode));
    printf("order: %s\n", h.flags & BW_FLAG_STREAM_ORDER ? "streamed" : "coarse-to-fine");
    printf("coder: %s\n", bwh_coder_name(h.flags));
    printf("symmetry: %s\n", bwh_symmetry_name(h.flags));
    if (map == BWH_EXACT_PLANES)
        printf("values: float32 bits: the samples their high plane, %u low bits raw\n", low);
    else if (fl == 1)
        printf("values: the signed log map of record 0x02\n");
    else
        printf("values: %s\n", h.flags & BW_FLAG_LOG_VALUE ? "exp(offset + scale * sample)"
                                                           : "offset + scale * sample");
    if (fx == 1)
        printf("exceptions: %u\n", n_exc);
    printf("max_error: %.9g\n", h.mode == BW_MODE_MAX_ERROR ? h.max_error * scale : 0.0);
    printf("prequant: %u\n", h.prequant);
    printf("step: %.4f\n", h.step_q8 / 256.0);
    printf("scale: %.9g\n", scale);
    printf("offset: %.9g\n", (double)bwh_bits_to_float(h.offset_bits));
    printf("payload_bytes: %u\n", h.payload_len);
    printf("bits_per_sample: %.6f\n", 8.0 * h.payload_len / (double)n);
    printf("ratio_vs_float32: %.3f\n", 4.0 * (double)n / h.payload_len);
    printf("crc32: 0x%08x\n", h.crc);
    char rule[160];
    bwh_guarantee_rule(&g, rule, sizeof rule);
    printf("guarantee: %s\n", bwh_guarantee_name(g.kind));
    printf("guarantee_rule: %s\n", rule);
    printf("guarantee_recorded: %s\n", g.recorded ? "yes" : "no (from the header)");
    char num[32];
    bwh_shortest(g.max_error, num, sizeof num);
    printf("guarantee_max_error: %s\n", num);
    bwh_shortest(g.max_rel_error, num, sizeof num);
    printf("guarantee_max_rel_error: %s\n", num);
    bwh_shortest(g.rel_floor, num, sizeof num);
    printf("guarantee_rel_floor: %s\n", num);
    printf("metadata_bytes: %zu\n", meta_bytes);
    bwh_meta_print(&meta, stdout);
    bwh_meta_free(&meta);
    return CLI_EXIT_OK;
}
