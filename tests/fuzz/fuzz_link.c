/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libFuzzer target: the link's frame receiver and the frames' contents
 * (firmware/link/bw_frame.c, docs/LINK.md) on arbitrary bytes, as a UART
 * delivers them.
 *
 * The input is a byte stream, fed to one receiver a byte at a time
 * (bw_frame_rx_byte) and to another in chunks whose sizes the input picks
 * (bw_frame_rx_feed): both must give the same frames, each one that its
 * type, seq and data packed again (bw_frame_pack) make whole, found in the
 * stream as it arrived. Then a frame of our own follows the stream, and
 * enough bytes to end any frame the stream left begun: it must arrive
 * (a damaged frame costs only itself). Every frame's data is read as a
 * JOB, HELLO and ERROR; a JOB read, packed and read again is the same job,
 * and its parameters go through the admission rule.
 */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_crc32.h"
#include "bw_frame.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int cond, const char *what)
{
    if (!cond) {
        fprintf(stderr, "fuzz_link: %s\n", what);
        abort();
    }
}

/* whether needle[n] occurs in hay[len] */
static bool occurs(const uint8_t *hay, size_t len, const uint8_t *needle, size_t n)
{
    for (size_t i = 0; i + n <= len; i++)
        if (!memcmp(hay + i, needle, n))
            return true;
    return false;
}

static void contents(const bw_frame_t *f)
{
    bw_job_t job;
    if (bw_job_unpack(f->data, f->len, &job)) {
        static uint8_t again[BW_FRAME_MAX_DATA];
        require(job.ext_len <= BW_JOB_EXT_MAX, "a JOB with more records than its frame holds");
        size_t n = bw_job_pack(&job, again);
        bw_job_t back;
        require(n == BW_JOB_SIZE + job.ext_len && n == f->len && bw_job_unpack(again, n, &back),
                "a JOB read does not pack to a JOB");
        /* the same job (the bytes after the source's NUL are not the job's) */
        require(back.shape == job.shape && back.level_out == job.level_out &&
                    back.level_in == job.level_in && back.mode == job.mode &&
                    back.basis == job.basis && back.flags == job.flags &&
                    back.effort == job.effort && back.coder == job.coder &&
                    back.n_in == job.n_in && back.bands == job.bands &&
                    back.max_error == job.max_error && back.byte_budget == job.byte_budget &&
                    back.scale_bits == job.scale_bits && back.offset_bits == job.offset_bits &&
                    !strcmp(back.source, job.source) && back.ext_len == job.ext_len &&
                    (!job.ext_len || !memcmp(back.ext, job.ext, job.ext_len)),
                "a JOB packed and read again differs");
        bw_params_t p;
        bw_dims_t d;
        bw_job_params(&job, &p);
        if (bw_dims_make(&d, (bw_shape_t)job.shape, job.level_out, job.level_in, job.n_in,
                         job.bands) == BW_OK) {
            bw_limits_t lim;
            memset(&lim, 0, sizeof lim);
            lim.max_samples = 1u << 16;
            lim.max_bands = 256;
            bool streamed;
            bw_status_t st = bw_limits_admit(&lim, &d, &p, &streamed);
            require(st == BW_OK || st == BW_ERR_WORK || st == BW_ERR_ARG,
                    "the admission rule's status");
        }
    }
    uint8_t version;
    bw_limits_t lim;
    int32_t status;
    (void)bw_hello_unpack(f->data, f->len, &version, &lim);
    (void)bw_error_unpack(f->data, f->len, &status, &lim);
}

/* a frame's fields and its data's CRC */
typedef struct {
    uint8_t type, flags;
    uint16_t seq, len;
    uint32_t crc;
} seen_t;

#define MAX_SEEN 2048u /* more than a stream of 8 KiB + 2 KiB holds (12 bytes a frame) */

static void note(seen_t *list, size_t *n, const bw_frame_t *f)
{
    require(*n < MAX_SEEN, "more frames than the stream can hold");
    seen_t *e = &list[(*n)++];
    e->type = f->type;
    e->flags = f->flags;
    e->seq = f->seq;
    e->len = f->len;
    e->crc = bw_crc32(f->data, f->len);
}

/* the frames of the stream, one receiver a byte at a time (then asked for
 * what it still holds), the other in chunks: the same ones, in the same
 * order, each whole in the stream as it had arrived */
static void frames(const uint8_t *s, size_t n, const uint8_t *sizes, size_t ns,
                   const uint8_t *mine, size_t mine_len)
{
    static bw_frame_rx_t a, b;
    static bw_frame_t f;
    static uint8_t packed[BW_FRAME_MAX];
    static seen_t la[MAX_SEEN], lb[MAX_SEEN];
    size_t na = 0, nb = 0, found_mine = 0;
    bw_frame_rx_init(&a);
    bw_frame_rx_init(&b);
    for (size_t i = 0; i <= n; i++) {
        bool got = false;
        if (i < n)
            got = bw_frame_rx_byte(&a, s[i], &f);
        else
            bw_frame_rx_feed(&a, NULL, 0, &f, &got);
        if (!got)
            continue;
        size_t len = bw_frame_pack(packed, f.type, f.seq, f.data, f.len);
        require(len == BW_FRAME_OVERHEAD + f.len, "a frame does not pack");
        /* (with the flags it came with) */
        packed[3] = f.flags;
        bw_put_u32(packed + len - 4u, bw_crc32(packed + 2u, len - 6u));
        require(occurs(s, i < n ? i + 1u : n, packed, len), "a frame that is not in the stream");
        if (mine && len == mine_len && !memcmp(packed, mine, len))
            found_mine++;
        contents(&f);
        note(la, &na, &f);
        if (i == n)
            i--; /* ask again: it may hold more */
    }
    for (size_t at = 0, k = 0;;) {
        bool got = false;
        size_t chunk = ns ? (size_t)sizes[k++ % ns] + 1u : n;
        if (chunk > n - at)
            chunk = n - at;
        size_t used = bw_frame_rx_feed(&b, s + at, chunk, &f, &got);
        require(used <= chunk, "the chunked receiver took more than it was given");
        at += used;
        if (got)
            note(lb, &nb, &f);
        else if (at == n && !used)
            break;
    }
    require(na == nb, "the two receivers give different numbers of frames");
    for (size_t k = 0; k < na; k++)
        require(la[k].type == lb[k].type && la[k].flags == lb[k].flags && la[k].seq == lb[k].seq &&
                    la[k].len == lb[k].len && la[k].crc == lb[k].crc,
                "the two receivers disagree");
    require(!mine || found_mine, "a frame after damaged bytes is lost");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* the first bytes pick the chunk sizes, the rest is the stream */
    size_t ns = size ? data[0] % 8u : 0u;
    if (ns + 1u > size)
        ns = size ? size - 1u : 0u;
    const uint8_t *sizes = data + (size ? 1u : 0u), *s = sizes + ns;
    size_t n = size - (size ? 1u : 0u) - ns;
    frames(s, n, sizes, ns, NULL, 0);

    /* the stream, a frame of ours, and bytes to end a frame it began */
    static uint8_t mine[BW_FRAME_OVERHEAD + 16u];
    const uint8_t payload[16] = "brdfwave frame!";
    size_t ml = bw_frame_pack(mine, BW_FT_END, 0x5A5Au, payload, sizeof payload);
    size_t total = n + ml + BW_FRAME_MAX;
    uint8_t *t = calloc(total, 1);
    require(t != NULL, "out of memory");
    if (n)
        memcpy(t, s, n);
    memcpy(t + n, mine, ml);
    frames(t, total, sizes, ns, mine, ml);
    free(t);
    return 0;
}

#ifdef BW_FUZZ_REPLAY
#define BW_FUZZ_NAME "fuzz_link"
#include "replay_main.h"
#endif
