/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libFuzzer target: the payload decoder on arbitrary bytes.
 *
 * Calls bw_header_read, bw_decode and bw_decode_unchecked on the input and
 * aborts if any of them returns a status outside bw_error.h, if bw_decode
 * accepts a payload whose header bw_header_read refused, or if the checked
 * and unchecked decoders disagree on a payload the checked one accepts.
 * Memory stays small: a header declaring more than FUZZ_MAX_SAMPLES samples
 * is only offered buffers far too small (the decoders must refuse them)
 * instead of being allocated for.
 *
 * Built by tests/fuzz/run.sh: with clang -fsanitize=fuzzer,address,undefined
 * for fuzzing, or with -DBW_FUZZ_REPLAY (any C11 compiler plus sanitizers)
 * as a program that runs the target once on every file named on its command
 * line (directories: every file in them).
 */
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bw_config.h"

#define FUZZ_MAX_SAMPLES ((size_t)1 << 20)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int cond, const char *what, int st)
{
    if (!cond) {
        fprintf(stderr, "fuzz_decode: %s (status %d: %s)\n", what, st, bw_strerror(st));
        abort();
    }
}

static int known(int st) { return st <= BW_OK && st >= BW_ERR_INCOMPLETE; }

static int same_dims(const bw_dims_t *a, const bw_dims_t *b)
{
    return a->shape == b->shape && a->level_out == b->level_out && a->level_in == b->level_in &&
           a->n_in == b->n_in && a->n_out == b->n_out && a->bands == b->bands;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int32_t tiny[64];
    bw_header_t hr, hf, hd;
    int st_read = bw_header_read(data, size, &hr);
    require(known(st_read), "bw_header_read: unknown status", st_read);

    /* the sample count the header declares, if its fields are valid */
    size_t n = 0;
    int st_fields = BW_ERR_TRUNCATED;
    if (size >= BW_HEADER_FIXED + BW_TRAILER_SIZE) {
        memset(&hf, 0, sizeof hf);
        st_fields = bw_header_parse_fields(data, size, &hf);
        require(known(st_fields), "bw_header_parse_fields: unknown status", st_fields);
        if (st_fields == BW_OK)
            n = bw_dims_samples(&hf.dims);
    }
    if (st_read == BW_OK)
        require(st_fields == BW_OK && same_dims(&hr.dims, &hf.dims),
                "bw_header_read accepts fields that bw_header_parse_fields refuses", st_fields);

    if (n == 0 || n > FUZZ_MAX_SAMPLES) {
        /* invalid or too large to allocate for: both decoders must fail
         * before writing beyond these buffers */
        int st = bw_decode(data, size, tiny, 64, tiny, 64, &hd);
        require(known(st) && (st != BW_OK || n <= 64), "bw_decode on small buffers", st);
        st = bw_decode_unchecked(data, size, tiny, 64, tiny, 64);
        require(known(st) && (st != BW_OK || n <= 64), "bw_decode_unchecked on small buffers",
                st);
        return 0;
    }

    size_t wb = bw_work_bound(n, hf.dims.bands);
    int32_t *s1 = malloc(n * sizeof *s1), *w1 = malloc(wb * sizeof *w1);
    int32_t *s2 = malloc(n * sizeof *s2), *w2 = malloc(wb * sizeof *w2);
    if (!s1 || !w1 || !s2 || !w2)
        abort();

    int st1 = bw_decode(data, size, s1, n, w1, wb, &hd);
    require(known(st1), "bw_decode: unknown status", st1);
    int st2 = bw_decode_unchecked(data, size, s2, n, w2, wb);
    require(known(st2), "bw_decode_unchecked: unknown status", st2);

    if (st1 == BW_OK) {
        require(st_read == BW_OK, "bw_decode accepts a payload bw_header_read refuses", st_read);
        require(same_dims(&hd.dims, &hf.dims), "bw_decode reports other dims", st1);
        require(st2 == BW_OK, "bw_decode_unchecked refuses what bw_decode accepts", st2);
        require(memcmp(s1, s2, n * sizeof *s1) == 0, "the two decoders disagree", st2);
        /* samples may be the work array itself */
        int st3 = bw_decode(data, size, w2, wb, w2, wb, NULL);
        require(st3 == BW_OK && memcmp(s1, w2, n * sizeof *s1) == 0,
                "decoding into the work array differs", st3);
    } else if (st_read == BW_OK) {
        /* a valid header and CRC: only the body can be wrong */
        require(st1 == BW_ERR_CORRUPT, "valid header, but an error other than CORRUPT", st1);
    }
    /* the salvage decode: a known status; on a whole payload the same
     * samples, every segment whole and nothing lost */
    if (BW_CFG_SALVAGE) {
        size_t nv = (size_t)hf.dims.n_in * hf.dims.n_out;
        uint8_t *lost = malloc(nv ? nv : 1), ok[64], *mask = malloc(nv ? nv : 1);
        static bw_ctx_t ctx;
        bw_header_t hs;
        if (!lost || !mask)
            abort();
        int st = bw_decode_salvage(&ctx, data, size, s2, n, w2, wb, &hs, ok, sizeof ok, lost);
        require(known(st), "bw_decode_salvage: unknown status", st);
        if (st1 == BW_OK) {
            require(st == BW_OK && memcmp(s1, s2, n * sizeof *s1) == 0,
                    "bw_decode_salvage differs from bw_decode on a whole payload", st);
            for (size_t v = 0; v < nv; v++)
                require(!lost[v], "a whole payload with a lost vector", st);
        }
        if (st == BW_OK || st == BW_ERR_INCOMPLETE) {
            int32_t *tmp = malloc((nv ? nv : 1) * sizeof *tmp);
            if (!tmp)
                abort();
            bw_salvage_mask(&hs, lost, mask, tmp);
            free(tmp);
        }
        free(lost);
        free(mask);
    }
    /* one incoming direction (row) alone: a known status; on a whole
     * payload, the row of the whole decode (or a refusal it documents) */
    if (hf.dims.n_in && hf.dims.shape != BW_SHAPE_REFLECTANCE) {
        static bw_ctx_t rctx;
        uint32_t in = (uint32_t)(size * 2654435761u) % hf.dims.n_in;
        size_t row = (size_t)hf.dims.n_out * hf.dims.bands;
        int st = bw_decode_incoming(&rctx, data, size, in, s2, n, w2, wb, NULL);
        require(known(st), "bw_decode_incoming: unknown status", st);
        if (st1 == BW_OK)
            require((st == BW_OK && memcmp(s2, s1 + (size_t)in * row, row * sizeof *s1) == 0) ||
                        (st == BW_ERR_ARG && (hf.flags & BW_FLAG_RECIPROCAL)),
                    "bw_decode_incoming differs from the whole decode's row", st);
    }
    /* a set of rows (every third from one the input picks): a known
     * status; on a whole payload, those rows of the whole decode (or a
     * refusal it documents) */
    if (hf.dims.n_in && hf.dims.shape != BW_SHAPE_REFLECTANCE && hf.dims.n_in <= n) {
        static bw_ctx_t sctx;
        uint8_t *marks = calloc(hf.dims.n_in, 1);
        if (!marks)
            abort();
        size_t row = (size_t)hf.dims.n_out * hf.dims.bands, k = 0;
        for (uint32_t t = (uint32_t)(size % 3u); t < hf.dims.n_in; t += 3u)
            marks[t] = 1;
        int st = bw_decode_rows(&sctx, data, size, marks, s2, n, w2, wb, NULL);
        require(known(st), "bw_decode_rows: unknown status", st);
        if (st1 == BW_OK && st == BW_OK)
            for (uint32_t t = 0; t < hf.dims.n_in; t++)
                if (marks[t])
                    require(memcmp(s2 + k++ * row, s1 + (size_t)t * row, row * sizeof *s1) == 0,
                            "bw_decode_rows differs from the whole decode's rows", st);
        if (st1 == BW_OK)
            require(st == BW_OK || (st == BW_ERR_ARG && (hf.flags & BW_FLAG_RECIPROCAL)),
                    "bw_decode_rows refuses a whole payload", st);
        free(marks);
    }
    /* a coarser level (of both hemispheres of a full BRDF): a known
     * status, and on a whole payload it decodes
     * (or is refused as documented) */
    if (hf.dims.shape != BW_SHAPE_SPECTRA && hf.dims.level_out <= BW_MAX_LEVEL) {
        static bw_ctx_t lctx;
        unsigned lv = (unsigned)(size % (hf.dims.level_out + 1u));
        unsigned li = hf.dims.shape == BW_SHAPE_BRDF_FULL && hf.dims.level_in <= BW_MAX_LEVEL
                          ? (unsigned)(size / 7u % (hf.dims.level_in + 1u))
                          : BW_LEVEL_OWN;
        int st = bw_decode_lod(&lctx, data, size, lv, li, s2, n, w2, wb, NULL);
        require(known(st), "bw_decode_lod: unknown status", st);
        if (st1 == BW_OK)
            require(st == BW_OK || (st == BW_ERR_ARG && (hf.flags & BW_FLAG_RECIPROCAL)),
                    "bw_decode_level refuses a whole payload", st);
    }
    /* a band range of a payload with band access: a known status; on a
     * whole payload, those bands of the whole decode */
    if (BW_CFG_BANDS && hf.band_access && hf.dims.bands) {
        uint32_t B = hf.dims.bands, b0 = (uint32_t)(size * 2654435761u) % B;
        uint32_t b1 = b0 + 1u + (uint32_t)(size / 5u) % (B - b0), R = b1 - b0;
        size_t rw = bw_band_range_work(hf.dims.n_in, R);
        int32_t *o = malloc((size_t)hf.dims.n_in * R * sizeof *o), *w = malloc(rw * sizeof *w);
        if (!o || !w)
            abort();
        int st = bw_decode_band_range(data, size, b0, b1, o, (size_t)hf.dims.n_in * R, w, rw,
                                      NULL);
        require(known(st), "bw_decode_band_range: unknown status", st);
        if (st1 == BW_OK) {
            require(st == BW_OK, "bw_decode_band_range refuses a whole payload", st);
            for (uint32_t s = 0; s < hf.dims.n_in; s++)
                require(memcmp(o + (size_t)s * R, s1 + (size_t)s * B + b0, R * sizeof *o) == 0,
                        "bw_decode_band_range differs from the whole decode's bands", st);
        }
        free(o);
        free(w);
    }
    /* undersized buffers are refused */
    if (st1 == BW_OK) {
        int st = bw_decode(data, size, s1, n - 1, w1, wb, NULL);
        require(st == BW_ERR_WORK, "samples_cap n-1 not refused", st);
        st = bw_decode(data, size, s1, n, w1, wb - 1, NULL);
        require(st == BW_ERR_WORK, "work_cap too small not refused", st);
    }
    free(s1);
    free(w1);
    free(s2);
    free(w2);
    return 0;
}

#ifdef BW_FUZZ_REPLAY
#define BW_FUZZ_NAME "fuzz_decode"
#include "replay_main.h"
#endif
