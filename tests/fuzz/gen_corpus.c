/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Seed corpus for the fuzz targets:
 *   gen_corpus DIR   writes DIR/decode/<name>.bwv    valid payloads (every shape,
 *                                                     mode and basis, small sizes)
 *                           DIR/roundtrip/<name>.bin inputs in fuzz_roundtrip.c's
 *                                                     layout
 * Deterministic: the same core writes the same files. tests/fuzz/corpus holds
 * a committed copy; tests/fuzz/run.sh also regenerates the seeds from the
 * current core before every run.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bw_codec.h"

static void write_file(const char *dir, const char *name, const void *p, size_t len)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(p, 1, len, f) != len || fclose(f) != 0) {
        perror(path);
        exit(1);
    }
}

static void make_dir(const char *path)
{
    if (mkdir(path, 0755) != 0 && errno != EEXIST) {
        perror(path);
        exit(1);
    }
}

typedef struct {
    const char *name;
    uint8_t shape, level_out, level_in;
    uint32_t n_in, bands;
    uint8_t mode, basis;
    uint32_t param;
    uint8_t flags; /* BW_FLAG_MIRROR, BW_FLAG_RICE, BW_FLAG_MS (both: the static tables, which
                    * the round-trip input asks for as BW_CODER_AUTO) */
    uint32_t seg;  /* vectors per segment (0: one body); a name ending in
                    * _embed: embedded segments */
} seed_t;

static const seed_t seeds[] = {
    {"spectra_1x1_lossless_haar", 0, 0, 0, 1, 1, 0, 0, 0, 0, 0},
    {"spectra_3x17_maxerr2_97", 0, 0, 0, 3, 17, 1, 2, 2, 0, 0},
    {"spectra_2x81_bytes_53", 0, 0, 0, 2, 81, 2, 1, 300, 0, 0},
    {"spectra_4x9_step_haar", 0, 0, 0, 4, 9, 3, 0, 2048, 0, 0},
    {"refl_l0x5_lossless_53", 1, 0, 0, 1, 5, 0, 1, 0, 0, 0},
    {"refl_l1x3_maxerr1_haar", 1, 1, 0, 1, 3, 1, 0, 1, 0, 0},
    {"refl_l2x1_lossless_97", 1, 2, 0, 1, 1, 0, 2, 0, 0, 0},
    {"refl_l1x12_bytes_97", 1, 1, 0, 1, 12, 2, 2, 400, 0, 0},
    {"refl_l1x8_auto", 1, 1, 0, 1, 8, 0, 255, 0, 0, 0},
    {"iso_2xl1x4_step_53", 2, 1, 0, 2, 4, 3, 1, 4096, 0, 0},
    {"iso_3xl0x7_maxerr16_97", 2, 0, 0, 3, 7, 1, 2, 16, 0, 0},
    {"full_l0l0x3_lossless_haar", 3, 0, 0, 0, 3, 0, 0, 0, 0, 0},
    {"full_l1l0x2_bytes_53", 3, 1, 0, 0, 2, 2, 1, 250, 0, 0},
    {"full_l0l1x2_maxerr4_97", 3, 0, 1, 0, 2, 1, 2, 4, 0, 0},
    {"iso_3xl2x5_mirror_lossless_53", 2, 2, 0, 3, 5, 0, 1, 0, BW_FLAG_MIRROR, 0},
    {"full_l1l1x2_mirror_maxerr2_haar", 3, 1, 1, 0, 2, 1, 0, 2, BW_FLAG_MIRROR, 0},
    {"spectra_3x40_lossless_pred", 0, 0, 0, 3, 40, 0, BW_BASIS_PRED, 0, 0, 0},
    {"spectra_2x33_maxerr5_pred", 0, 0, 0, 2, 33, 1, BW_BASIS_PRED, 5, 0, 0},
    {"refl_l1x12_maxerr2_53_rice", 1, 1, 0, 1, 12, 1, 1, 2, BW_FLAG_RICE, 0},
    {"refl_l1x12_lossless_97_ms", 1, 1, 0, 1, 12, 0, 2, 0, BW_FLAG_MS, 0},
    {"iso_3xl2x5_mirror_maxerr3_haar_ms", 2, 2, 0, 3, 5, 1, 0, 3, BW_FLAG_MIRROR | BW_FLAG_MS, 0},
    {"spectra_3x40_lossless_pred_ms", 0, 0, 0, 3, 40, 0, BW_BASIS_PRED, 0, BW_FLAG_MS, 0},
    {"spectra_6x17_maxerr2_53_seg1", 0, 0, 0, 6, 17, 1, 1, 2, 0, 1},
    {"refl_l2x3_lossless_haar_seg3_rice", 1, 2, 0, 1, 3, 0, 0, 0, BW_FLAG_RICE, 3},
    {"full_l1l1x2_mirror_maxerr2_haar_seg17_ms", 3, 1, 1, 0, 2, 1, 0, 2,
     BW_FLAG_MIRROR | BW_FLAG_MS, 17},
    {"spectra_5x24_lossless_pred_seg1", 0, 0, 0, 5, 24, 0, BW_BASIS_PRED, 0, 0, 1},
    {"spectra_4x40_lossless_53_embed", 0, 0, 0, 4, 40, 0, 1, 0, 0, 0},
    {"iso_3xl2x1_maxerr3_haar_seg7_embed", 2, 2, 0, 3, 1, 1, 0, 3, 0, 7},
    {"full_l1l1x2_mirror_bytes_97_embed", 3, 1, 1, 0, 2, 2, 2, 300, BW_FLAG_MIRROR, 0},
    {"spectra_20x64_lossless_97_tab", 0, 0, 0, 20, 64, 0, 2, 0, BW_FLAG_RICE | BW_FLAG_MS, 0},
    {"spectra_6x40_maxerr3_haar_tab", 0, 0, 0, 6, 40, 1, 0, 3, BW_FLAG_RICE | BW_FLAG_MS, 0},
    {"refl_l2x3_maxerr2_53_tab_seg5", 1, 2, 0, 1, 3, 1, 1, 2, BW_FLAG_RICE | BW_FLAG_MS, 5},
    {"iso_3xl2x5_mirror_lossless_haar_tab", 2, 2, 0, 3, 5, 0, 0, 0,
     BW_FLAG_MIRROR | BW_FLAG_RICE | BW_FLAG_MS, 0},
};

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen_corpus DIR\n");
        return 2;
    }
    char dec[1024], rt[1024];
    snprintf(dec, sizeof dec, "%s/decode", argv[1]);
    snprintf(rt, sizeof rt, "%s/roundtrip", argv[1]);
    make_dir(argv[1]);
    make_dir(dec);
    make_dir(rt);

    unsigned written = 0;
    for (size_t s = 0; s < sizeof seeds / sizeof seeds[0]; s++) {
        const seed_t *sd = &seeds[s];
        bw_dims_t d;
        int st = bw_dims_make(&d, (bw_shape_t)sd->shape, sd->level_out, sd->level_in, sd->n_in,
                              sd->bands);
        if (st != BW_OK) {
            fprintf(stderr, "%s: %s\n", sd->name, bw_strerror(st));
            return 1;
        }
        size_t n = bw_dims_samples(&d), wb = bw_work_bound(n, d.bands),
               cap = bw_payload_bound(n) + BW_SEGMENT_OVERHEAD((size_t)d.n_in * d.n_out);
        int32_t *x = malloc(n * sizeof *x), *work = malloc(wb * sizeof *work);
        uint8_t *out = malloc(cap);
        if (!x || !work || !out)
            return 1;
        uint32_t r = 12345u + (uint32_t)s;
        for (size_t i = 0; i < n; i++) {
            r ^= r << 13;
            r ^= r >> 17;
            r ^= r << 5;
            x[i] = 20000 + (int32_t)(i % d.bands) * 150 + (int32_t)(r % 401u) - 200;
        }
        bw_params_t p;
        memset(&p, 0, sizeof p);
        p.mode = sd->mode;
        p.basis = sd->basis;
        p.max_error = sd->mode == BW_MODE_MAX_ERROR ? sd->param : 0u;
        p.byte_budget = sd->mode == BW_MODE_BYTES ? sd->param : 0u;
        p.step_q8 = sd->mode == BW_MODE_STEP ? sd->param : 0u;
        p.scale_bits = 0x3727C5ACu;
        p.flags = sd->flags;
        p.segment_vectors = sd->seg;
        size_t nl = strlen(sd->name);
        bool embed = nl > 6 && !strcmp(sd->name + nl - 6, "_embed");
        p.progressive = embed;
        size_t len;
        st = bw_encode(&d, &p, x, work, NULL, out, cap, &len);
        if (st != BW_OK) {
            fprintf(stderr, "%s: %s\n", sd->name, bw_strerror(st));
            return 1;
        }
        char name[128];
        snprintf(name, sizeof name, "%s.bwv", sd->name);
        write_file(dec, name, out, len);

        /* the same case as a round-trip input: 9 bytes of settings and
         * walk-style samples (style 1) */
        uint8_t in[9 + 64];
        uint32_t bands_field = sd->bands - 1u;
        uint32_t param = sd->mode == BW_MODE_MAX_ERROR ? sd->param - 1u
                         : sd->mode == BW_MODE_BYTES   ? sd->param / 2u
                         : sd->mode == BW_MODE_STEP    ? (sd->param - 256u) / 8u
                                                       : 0u;
        in[0] = (uint8_t)(sd->shape | (embed ? 0x40u : 0u));
        in[1] = (uint8_t)(sd->level_out | sd->level_in << 2);
        in[2] = (uint8_t)bands_field;
        in[3] = (uint8_t)(bands_field >> 8);
        in[4] = (uint8_t)((sd->n_in ? sd->n_in - 1u : 0u) | (sd->flags & BW_FLAG_MIRROR ? 0x80u : 0u) |
                          (sd->seg == 1u ? 0x20u : sd->seg == 3u ? 0x40u : sd->seg ? 0x60u : 0u));
        in[5] = (uint8_t)(sd->mode |
                          (sd->basis == BW_BASIS_PRED ? 0x10u
                                                      : (sd->basis == 255 ? 3u : sd->basis) << 2) |
                          ((sd->flags & (BW_FLAG_RICE | BW_FLAG_MS)) == (BW_FLAG_RICE | BW_FLAG_MS)
                               ? 0x60u
                           : sd->flags & BW_FLAG_RICE ? 0x20u
                           : sd->flags & BW_FLAG_MS   ? 0x40u
                                                      : 0u));
        in[6] = (uint8_t)param;
        in[7] = (uint8_t)(param >> 8);
        in[8] = (uint8_t)(s % 4u);
        for (size_t i = 9; i < sizeof in; i++)
            in[i] = (uint8_t)(r >> (i % 24u)) ^ (uint8_t)(i * 37u);
        snprintf(name, sizeof name, "%s.bin", sd->name);
        write_file(rt, name, in, sizeof in);
        written += 2;
        free(x);
        free(work);
        free(out);
    }
    printf("gen_corpus: %u seeds in %s\n", written, argv[1]);
    return 0;
}
