/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libFuzzer target: encode then decode, and check the mode's guarantee.
 *
 * The input is read as
 *   byte 0     shape                          b % 4; bit 6 embedded segments
 *                                             (transform bases); bit 7 the
 *                                             device's effort
 *   byte 1     levels                         level_out = b % 4, level_in = (b >> 2) % 3
 *   bytes 2-3  bands (little-endian)          1 + v % 2151, then cut so that
 *                                             n <= FUZZ_MAX_SAMPLES
 *   byte 4     n_in (spectra, BRDF_ISO)       1 + b % 32; bits 5-6 segments: none,
 *                                             1 or 3 vectors each, or about 4
 *                                             segments; bit 7 the mirror
 *   byte 5     mode, basis                    b % 4, (b >> 2) % 4 (3 = AUTO); bit 4:
 *                                             prediction instead, where it applies
 *                                             (spectra, lossless or max-error)
 *   bytes 6-7  parameter p (little-endian)    MAX_ERROR: E = 1 + p % 1000, or for
 *                                               p >= 0xF000 up to BW_SAMPLE_MAX
 *                                             BYTES: budget = 2p bytes
 *                                             STEP: step_q8 = 256 + 8p
 *   byte 8     sample style, vector threshold b % 4, (b >> 2) * 16 (0: default)
 *   bytes 9..  samples, by style: 0 four bytes each, anywhere in the range;
 *              1 a walk with steps of 16 * (int8)b; 2 sparse spikes; 3 small
 *              values (int8)b. When the input runs out a generator seeded
 *              from it supplies the rest.
 * The target aborts when a valid input is refused (other than BW_ERR_BUDGET
 * in byte-budget mode), the encoder's own verify fails, the payload exceeds
 * bw_payload_bound() or the byte budget, the payloads encoded with and
 * without the verify buffer differ (except AUTO in byte-budget mode, which
 * ranks the bases differently when it can decode), the header does not
 * describe the input, or the decoded samples break the guarantee (bit-exact;
 * within E; bit-exact when a budget allowed step 1). A segmented payload is
 * then damaged (a byte changed) and cut where the input says, and decoded
 * in part: a known status, and every direction pair marked exact holds the
 * samples of the whole payload.
 *
 * Built like fuzz_decode.c (see tests/fuzz/run.sh), including the replay
 * main under BW_FUZZ_REPLAY.
 */
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bw_config.h"

#define FUZZ_MAX_SAMPLES ((size_t)1 << 12)
#define SMAX ((int32_t)BW_SAMPLE_MAX)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int cond, const char *what, int st)
{
    if (!cond) {
        fprintf(stderr, "fuzz_roundtrip: %s (status %d: %s)\n", what, st, bw_strerror(st));
        abort();
    }
}

typedef struct {
    const uint8_t *p;
    size_t len, pos;
    uint64_t s;
} src_t;

static uint8_t next_byte(src_t *src)
{
    if (src->pos < src->len)
        return src->p[src->pos++];
    src->s ^= src->s >> 12;
    src->s ^= src->s << 25;
    src->s ^= src->s >> 27;
    return (uint8_t)((src->s * 0x2545F4914F6CDD1Du) >> 56);
}

static int32_t clamp_sample(int64_t v) { return v > SMAX ? SMAX : v < -SMAX ? -SMAX : (int32_t)v; }

static int known(int st) { return st <= BW_OK && st >= BW_ERR_INCOMPLETE; }

/* A segmented payload damaged (a byte changed) and cut, where the input
 * says: the salvage decode ends in a known status, and every direction
 * pair it marks exact holds the whole payload's samples y. */
static void salvage_check(const uint8_t *pl, size_t len, const bw_header_t *h, const int32_t *y,
                          const uint8_t *data, size_t size)
{
    size_t n = bw_dims_samples(&h->dims), wb = bw_work_bound(n, h->dims.bands);
    size_t nv = (size_t)h->dims.n_in * h->dims.n_out;
    uint8_t *q = malloc(len), *lost = malloc(nv), *mask = malloc(nv), *ok = malloc(h->segments);
    int32_t *s = malloc(n * sizeof *s), *w = malloc(wb * sizeof *w), *tmp = malloc(nv * 4);
    static bw_ctx_t ctx;
    if (!q || !lost || !mask || !ok || !s || !w || !tmp)
        abort();
    uint32_t r = (uint32_t)size * 2654435761u ^ data[size - 1];
    for (int k = 0; k < 2; k++) {
        memcpy(q, pl, len);
        size_t ql = len;
        if (k == 0)
            q[h->header_len + r % (len - h->header_len)] ^= (uint8_t)(1u + r % 255u);
        else
            ql = h->header_len + (r >> 8) % (len - h->header_len);
        bw_header_t hh;
        int st = bw_decode_salvage(&ctx, q, ql, s, n, w, wb, &hh, ok, h->segments, lost);
        require(known(st), "bw_decode_salvage: unknown status", st);
        if (st != BW_OK && st != BW_ERR_INCOMPLETE)
            continue;
        bw_salvage_mask(&hh, lost, mask, tmp);
        uint32_t b = h->dims.bands;
        for (size_t v = 0; v < nv; v++)
            if (mask[v] == BW_SAMPLE_EXACT)
                require(memcmp(s + v * b, y + v * b, b * sizeof *s) == 0,
                        "a salvaged pair marked exact differs", st);
    }
    free(q);
    free(lost);
    free(mask);
    free(ok);
    free(s);
    free(w);
    free(tmp);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 9)
        return 0;
    unsigned shape = data[0] % 4u, level_out = data[1] % 4u, level_in = (data[1] >> 2) % 3u;
    uint32_t bands = 1u + (uint32_t)(data[2] | data[3] << 8) % 2151u;
    uint32_t n_in = 1u + data[4] % 32u;
    unsigned mode = data[5] % 4u, basis = (data[5] >> 2) % 4u;
    uint32_t p = (uint32_t)(data[6] | data[7] << 8);
    unsigned style = data[8] % 4u;
    if (basis == 3u)
        basis = BW_BASIS_AUTO;
    /* where prediction applies (bw_codec.h) */
    int embed = (data[0] & 0x40u) != 0;
    int pred = shape == BW_SHAPE_SPECTRA && mode <= BW_MODE_MAX_ERROR && !embed;
    if ((data[5] & 0x10u) && pred)
        basis = BW_BASIS_PRED;

    bw_dims_t d;
    int st = bw_dims_make(&d, (bw_shape_t)shape, level_out, level_in, n_in, bands);
    require(st == BW_OK, "bw_dims_make refuses valid dims", st);
    size_t vectors = (size_t)d.n_in * d.n_out;
    if (vectors > FUZZ_MAX_SAMPLES)
        return 0;
    if (vectors * d.bands > FUZZ_MAX_SAMPLES) {
        st = bw_dims_make(&d, (bw_shape_t)shape, level_out, level_in, n_in,
                          (uint32_t)(FUZZ_MAX_SAMPLES / vectors));
        require(st == BW_OK, "bw_dims_make refuses valid dims", st);
    }
    size_t n = bw_dims_samples(&d);

    bw_params_t pa;
    memset(&pa, 0, sizeof pa);
    pa.mode = (uint8_t)mode;
    pa.basis = (uint8_t)basis;
    /* the device's cheap choices: the basis on parts, the budget's step
     * estimated */
    pa.effort = (data[0] & 0x80u) ? BW_EFFORT_FAST : BW_EFFORT_BEST;
    pa.vec_thresh_q8 = (uint32_t)(data[8] >> 2) * 16u;
    pa.scale_bits = 0x3F800000u;
    /* the mirror of directional data (bit 7 of the n_in byte) */
    int mirror = (data[4] & 0x80u) && d.shape != BW_SHAPE_SPECTRA;
    if (mirror)
        pa.flags = BW_FLAG_MIRROR;
    /* the coder (bits 5-6 of the mode byte): range, Rice, multi-symbol, or
     * the encoder's choice (BW_CODER_AUTO: the static tables for a set of
     * spectra transformed) */
    static const uint8_t coder_flags[4] = {0u, BW_FLAG_RICE, BW_FLAG_MS, 0u};
    pa.flags |= coder_flags[(data[5] >> 5) & 3u];
    if (((data[5] >> 5) & 3u) == 3u)
        pa.coder = BW_CODER_AUTO;
    /* segments (bits 5-6 of the n_in byte): none, one vector each, three,
     * or about four segments */
    size_t nvec = (size_t)d.n_in * d.n_out;
    unsigned seg_sel = (data[4] >> 5) & 3u;
    pa.segment_vectors = seg_sel == 1u ? 1u : seg_sel == 2u ? 3u
                         : seg_sel == 3u ? (uint32_t)(nvec / 4u + 1u) : 0u;
    pa.progressive = (uint32_t)embed;
    /* band access (bit 7 of the level byte) where prediction is asked for:
     * one body, the flags naming no coder */
    int bands_acc = BW_CFG_BANDS && basis == BW_BASIS_PRED && (data[1] & 0x80u);
    if (bands_acc) {
        pa.band_access = 1u;
        pa.segment_vectors = 0;
        pa.flags &= (uint8_t)~(BW_FLAG_RICE | BW_FLAG_MS);
        pa.coder = BW_CODER_BY_FLAGS;
    }
    if (mode == BW_MODE_MAX_ERROR)
        pa.max_error = p < 0xF000u ? 1u + p % 1000u
                                   : 1u + (uint32_t)(((uint64_t)p * 2654435761u) % (uint32_t)SMAX);
    else if (mode == BW_MODE_BYTES)
        pa.byte_budget = 2u * p;
    else if (mode == BW_MODE_STEP)
        pa.step_q8 = 256u + 8u * p;

    int32_t *x = malloc(n * sizeof *x);
    if (!x)
        abort();
    src_t src = {data, size, 9, 0x9E3779B97F4A7C15u ^ size};
    int64_t acc = 30000;
    for (size_t i = 0; i < n; i++) {
        switch (style) {
        case 0: {
            uint32_t u = 0;
            for (int k = 0; k < 4; k++)
                u = u << 8 | next_byte(&src);
            x[i] = (int32_t)(u % (2u * (uint32_t)SMAX + 1u)) - SMAX;
            break;
        }
        case 1:
            acc = clamp_sample(acc + 16 * (int8_t)next_byte(&src));
            x[i] = (int32_t)acc;
            break;
        case 2: {
            uint8_t b = next_byte(&src);
            x[i] = b % 8u ? 0 : clamp_sample((int64_t)(int8_t)b * 131072);
            break;
        }
        default:
            x[i] = (int8_t)next_byte(&src);
            break;
        }
    }

    size_t wb = bw_work_bound(n, d.bands),
           cap = bw_payload_bound(n) + BW_SEGMENT_OVERHEAD(nvec) + BW_BANDS_OVERHEAD;
    int32_t *work = malloc(wb * sizeof *work), *ver = malloc(wb * sizeof *ver);
    uint8_t *out = malloc(cap), *out2 = malloc(cap);
    int32_t *y = malloc(n * sizeof *y);
    if (!work || !ver || !out || !out2 || !y)
        abort();

    size_t len = 0, len2 = 0;
    st = bw_encode(&d, &pa, x, work, ver, out, cap, &len);
    int st2 = bw_encode(&d, &pa, x, work, NULL, out2, cap, &len2);
    require(st == st2, "encoding with and without verify differ in status", st2);
    if (st == BW_ERR_BUDGET && mode == BW_MODE_BYTES)
        goto done;
    if (st == BW_ERR_RANGE && mirror) {
        /* a difference left the range: only possible with samples beyond
         * half of it */
        int32_t big = 0;
        for (size_t i = 0; i < n; i++)
            big |= x[i] > SMAX / 2 || x[i] < -(SMAX / 2);
        require(big, "the mirror refuses samples within half the range", st);
        goto done;
    }
    require(st == BW_OK, "valid input refused (or its verify failed)", st);
    /* the same bytes with and without the verify buffer, except for AUTO in
     * byte-budget mode, which ranks the bases by decoded error when it can
     * decode and by step otherwise */
    if (!(mode == BW_MODE_BYTES && basis == BW_BASIS_AUTO))
        require(len == len2 && memcmp(out, out2, len) == 0,
                "encoding with and without verify differ", st);
    for (int pass = 0; pass < 2; pass++) {
        const uint8_t *pl = pass ? out2 : out;
        size_t pl_len = pass ? len2 : len;
        require(pl_len >= BW_HEADER_FIXED + BW_TRAILER_SIZE && pl_len <= cap,
                "payload size out of bounds", st);
        if (mode == BW_MODE_BYTES)
            require(pl_len <= pa.byte_budget, "payload exceeds the byte budget", st);

        bw_header_t h;
        st = bw_decode(pl, pl_len, y, n, work, wb, &h);
        require(st == BW_OK, "own payload does not decode", st);
        require(h.dims.shape == d.shape && h.dims.level_out == d.level_out &&
                    h.dims.level_in == d.level_in && h.dims.n_in == d.n_in &&
                    h.dims.n_out == d.n_out && h.dims.bands == d.bands,
                "header dims differ from the input's", st);
        /* a byte budget that the exact coding fits gives the lossless payload */
        require(h.mode == mode || (mode == BW_MODE_BYTES && h.mode == BW_MODE_LOSSLESS),
                "header mode differs", st);
        require(basis == BW_BASIS_AUTO
                    ? h.basis < BW_BASIS_COUNT || (h.basis == BW_BASIS_PRED && pred)
                    : h.basis == basis,
                "header basis differs", st);
        if (mode == BW_MODE_STEP)
            require(h.step_q8 == pa.step_q8, "header step differs", st);

        require((h.embedded != 0u) == (embed != 0) && (!embed || h.segment_vectors),
                "header embedding differs", st);
        /* (an embedded budget is a cut: exact only if it holds everything) */
        int exact = h.mode == BW_MODE_LOSSLESS ||
                    (mode == BW_MODE_BYTES && h.step_q8 == 256u && !embed);
        for (size_t i = 0; i < n; i++) {
            int64_t err = (int64_t)y[i] - x[i];
            if (err < 0)
                err = -err;
            if (exact)
                require(err == 0, "decoded sample differs", st);
            else if (mode == BW_MODE_MAX_ERROR)
                require(err <= (int64_t)pa.max_error, "decoded sample beyond the max error", st);
        }
        require((h.band_access != 0u) == (bands_acc != 0), "header band access differs", st);
        if (h.band_access) { /* a band range: those bands of the whole decode */
            uint32_t B = d.bands, b0 = (uint32_t)(size * 2654435761u) % B, R = B - b0;
            size_t rw = bw_band_range_work(d.n_in, R);
            int32_t *o = malloc((size_t)d.n_in * R * sizeof *o), *rwk = malloc(rw * sizeof *rwk);
            if (!o || !rwk)
                abort();
            st = bw_decode_band_range(pl, pl_len, b0, B, o, (size_t)d.n_in * R, rwk, rw, NULL);
            require(st == BW_OK, "own payload's band range does not decode", st);
            for (uint32_t s = 0; s < d.n_in; s++)
                require(memcmp(o + (size_t)s * R, y + (size_t)s * B + b0, R * sizeof *o) == 0,
                        "a band range differs from the whole decode", st);
            free(o);
            free(rwk);
        }
        st = bw_decode_unchecked(pl, pl_len, work, wb, work, wb);
        require(st == BW_OK && memcmp(work, y, n * sizeof *y) == 0,
                "bw_decode_unchecked differs from bw_decode", st);
        if (pass == 0 && h.segment_vectors)
            salvage_check(pl, pl_len, &h, y, data, size);
    }

done:
    free(x);
    free(work);
    free(ver);
    free(out);
    free(out2);
    free(y);
    return 0;
}

#ifdef BW_FUZZ_REPLAY
#define BW_FUZZ_NAME "fuzz_roundtrip"
#include "replay_main.h"
#endif
