/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave info: a payload's header as key: value lines. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_kv.h"
#include "commands.h"

static const char info_help[] = "usage: brdfwave info [--json] IN.bwv\n"
                                "\n"
                                "Prints the payload header as 'key: value' lines.\n"
                                "  --json  as one JSON object instead (the same keys)\n";

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
    free(p);
    if (hs != BW_OK)
        return cli_fail("%s: %s", path, bw_strerror(hs));
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
    cli_kv_str(&kv, "basis", bwh_basis_name(h.basis));
    cli_kv_uint(&kv, "spectral_levels", h.spectral_levels);
    cli_kv_str(&kv, "mode", bwh_mode_name(h.mode));
    cli_kv_str(&kv, "order", h.flags & BW_FLAG_STREAM_ORDER ? "streamed" : "coarse-to-fine");
    cli_kv_str(&kv, "coder", bwh_coder_name(h.flags));
    cli_kv_str(&kv, "symmetry", bwh_symmetry_name(h.flags));
    cli_kv_str(&kv, "values", h.flags & BW_FLAG_LOG_VALUE ? "exp(offset + scale * sample)"
                                                          : "offset + scale * sample");
    cli_kv_num(&kv, "max_error", "%.9g", h.mode == BW_MODE_MAX_ERROR ? h.max_error * scale : 0.0);
    cli_kv_uint(&kv, "prequant", h.prequant);
    cli_kv_num(&kv, "step", "%.4f", h.step_q8 / 256.0);
    cli_kv_num(&kv, "scale", "%.9g", scale);
    cli_kv_num(&kv, "offset", "%.9g", (double)bwh_bits_to_float(h.offset_bits));
    cli_kv_uint(&kv, "payload_bytes", h.payload_len);
    cli_kv_num(&kv, "bits_per_sample", "%.6f", 8.0 * h.payload_len / (double)n);
    cli_kv_num(&kv, "ratio_vs_float32", "%.3f", 4.0 * (double)n / h.payload_len);
    cli_kv_str(&kv, "crc32", crc);
    cli_kv_end(&kv);
    return CLI_EXIT_OK;
}
