/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Entry of the freestanding test images (tests/freestanding/check.sh).
 *
 * Encodes and decodes a small reflectance measurement on static buffers in
 * every mode and basis, so that the link keeps the codec's real code paths,
 * and provides the string.h routines the core and the compiler call, as the
 * images are linked without a C library. Never run: the script only links
 * the image and inspects its symbols.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bw_codec.h"

#define LEVEL 1u
#define BANDS 8u
#define N (4u * 4u * BANDS) /* 4 * 4^LEVEL directions */

static int32_t samples[N];
static int32_t work[BW_WORK_BOUND(N, BANDS)];
static int32_t check[BW_WORK_BOUND(N, BANDS)];
static uint8_t payload[BW_PAYLOAD_BOUND(N)];
static bw_ctx_t ctx; /* the coder's state, off the stack as on the device */
volatile int32_t bw_entry_result;

void _start(void);
int bw_entry(void);

void *memcpy(void *restrict dst, const void *restrict src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    while (n--)
        *d++ = *s++;
    return dst;
}

void *memmove(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (d < s)
        while (n--)
            *d++ = *s++;
    else
        while (n--)
            d[n] = s[n];
    return dst;
}

void *memset(void *dst, int c, size_t n)
{
    unsigned char *d = dst;
    while (n--)
        *d++ = (unsigned char)c;
    return dst;
}

int memcmp(const void *a, const void *b, size_t n)
{
    const unsigned char *p = a, *q = b;
    for (; n--; p++, q++)
        if (*p != *q)
            return *p < *q ? -1 : 1;
    return 0;
}

int bw_entry(void)
{
    static const uint8_t modes[] = {BW_MODE_LOSSLESS, BW_MODE_MAX_ERROR, BW_MODE_BYTES,
                                    BW_MODE_STEP};
    static const uint8_t bases[] = {BW_BASIS_HAAR, BW_BASIS_53, BW_BASIS_97, BW_BASIS_AUTO};
    bw_dims_t d;
    int32_t acc = 0;
    if (bw_dims_make(&d, BW_SHAPE_REFLECTANCE, LEVEL, 0, 1, BANDS) != BW_OK)
        return -1;
    for (uint32_t i = 0; i < N; i++)
        samples[i] = (int32_t)((i * 37u) % 1000u) + 20000;
    for (unsigned m = 0; m < sizeof modes; m++) {
        for (unsigned b = 0; b < sizeof bases; b++) {
            bw_params_t p;
            memset(&p, 0, sizeof p);
            p.mode = modes[m];
            p.basis = bases[b];
            p.max_error = 2;
            p.byte_budget = 200;
            p.step_q8 = 1024;
            size_t len = 0;
            bw_header_t h;
            int st = bw_encode_ctx(&ctx, &d, &p, samples, work, check, payload, sizeof payload,
                                   &len);
            acc += st;
            acc += bw_decode_ctx(&ctx, payload, len, check, N, work, BW_WORK_BOUND(N, BANDS), &h);
            acc += bw_decode_unchecked(payload, len, check, N, work, BW_WORK_BOUND(N, BANDS));
            acc += bw_header_read(payload, len, &h) + (int32_t)h.body_len;
        }
    }
    /* the streaming encoder, spectrum by spectrum */
    static bw_stream_t stream;
    static int32_t mem[BW_STREAM_MEM_BOUND(LEVEL, BANDS)];
    bw_params_t sp;
    memset(&sp, 0, sizeof sp);
    sp.mode = BW_MODE_MAX_ERROR;
    sp.basis = BW_BASIS_97;
    sp.max_error = 1;
    size_t slen = 0;
    int st = bw_stream_init(&stream, &d, &sp, mem, sizeof mem / sizeof *mem, payload, sizeof payload);
    for (uint32_t v = 0; st == BW_OK && v < d.n_out; v++)
        st = bw_stream_push(&stream, samples + v * BANDS);
    if (st == BW_OK)
        st = bw_stream_finish(&stream, &slen);
    acc += st + (int32_t)slen;
    return acc + (int32_t)bw_strerror(acc)[0];
}

void _start(void)
{
    bw_entry_result = bw_entry();
    for (;;) {
    }
}
