/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The codec core on the emulated Cortex-M4 (QEMU mps2-an386, semihosting):
 * every golden case encodes to the very payload the host produces (CRC and
 * length from tests/golden/payload_crc.txt), decodes within its guarantee,
 * and reports the instructions it took (-icount shift=0: deterministic).
 * The encoder (with its self-check, which decodes) and the decoder run with
 * the coder's state in a static bw_ctx_t, and their stack stays within
 * BW_CTX_STACK_MAX (bw_codec.h).
 * Ends with "RESULT: N passed, M failed"; the exit status is non-zero on a
 * failure.
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_codec.h"
#include "bw_crc32.h"
#include "bw_hal.h"
#include "golden/golden_cases.h"

#define MAX_SAMPLES 82944u /* the largest golden case: level 4 x 81 bands */
#define MAX_BANDS 2151u

static int32_t x[MAX_SAMPLES];
static int32_t work[BW_WORK_BOUND(MAX_SAMPLES, MAX_BANDS)];
static int32_t verify[BW_WORK_BOUND(MAX_SAMPLES, MAX_BANDS)];
static uint8_t payload[BW_PAYLOAD_BOUND(MAX_SAMPLES)];

static unsigned passed, failed;
static const bw_hal_t *hal;

/* the coder's state, off the stack */
static bw_ctx_t ctx;

/* the streaming encoder's whole state: context, caller memory, one spectrum */
static bw_stream_t stream;
static int32_t stream_mem[BW_STREAM_MEM_BOUND(0, 1024)]; /* >= BW_STREAM_MEM_BOUND(4, 81) */
static int32_t spectrum[1024];

/* Stack high-water mark of fn(): paint below the current stack pointer,
 * run, and find the deepest word overwritten. */
#define PAINT_WORDS 3072u
static size_t stack_used(void (*fn)(void))
{
    volatile uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    volatile uint32_t *low = sp - PAINT_WORDS;
    for (volatile uint32_t *p = low; p < sp - 16; p++)
        *p = 0xC0DEFACEu;
    fn();
    volatile uint32_t *p = low;
    while (p < sp && *p == 0xC0DEFACEu)
        p++;
    return (size_t)(sp - p) * 4u;
}

/* one encode (with verify) and one decode, each run under stack_used() */
static struct {
    const bw_dims_t *d;
    const bw_params_t *p;
    size_t len;
    bw_status_t st;
    bw_header_t h;
    uint64_t instr;
} job;

static void run_encode(void)
{
    uint64_t t0 = bw_hal_counter(hal);
    job.st = bw_encode_ctx(&ctx, job.d, job.p, x, work, verify, payload, sizeof payload, &job.len);
    job.instr = bw_hal_counter(hal) - t0;
}

static void run_decode(void)
{
    uint64_t t0 = bw_hal_counter(hal);
    job.st = bw_decode_ctx(&ctx, payload, job.len, verify, MAX_SAMPLES, work,
                           sizeof work / sizeof *work, &job.h);
    job.instr = bw_hal_counter(hal) - t0;
}

static const golden_case_t *stream_case;
static size_t stream_len;
static bw_status_t stream_status;

static void run_stream(void)
{
    const golden_case_t *g = stream_case;
    bw_dims_t d;
    bw_dims_make(&d, (bw_shape_t)g->shape, g->level_out, g->level_in, g->n_in, g->bands);
    bw_params_t p = golden_params(g);
    stream_status = bw_stream_init(&stream, &d, &p, stream_mem, sizeof stream_mem / 4, payload,
                                   sizeof payload);
    for (size_t v = 0; stream_status == BW_OK && v < (size_t)d.n_in * d.n_out; v++) {
        /* the sensor delivers one spectrum at a time */
        memcpy(spectrum, x + v * d.bands, d.bands * sizeof *spectrum);
        stream_status = bw_stream_push(&stream, spectrum);
    }
    if (stream_status == BW_OK)
        stream_status = bw_stream_finish(&stream, &stream_len);
}

static void check(int ok, const char *what, const char *name)
{
    if (ok) {
        passed++;
    } else {
        failed++;
        printf("FAIL: %s: %s\n", name, what);
    }
}

/* Looks a case up in the golden file (run from the repository root). */
static int golden_lookup(const char *name, uint32_t *crc, size_t *len)
{
    FILE *f = fopen("tests/golden/payload_crc.txt", "r");
    if (!f)
        return -1;
    char line[256], n[128];
    unsigned long c, l;
    int found = -1;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (sscanf(line, "%127s %lx %lu", n, &c, &l) == 3 && !strcmp(n, name)) {
            *crc = (uint32_t)c;
            *len = (size_t)l;
            found = 0;
            break;
        }
    }
    fclose(f);
    return found;
}

int main(void)
{
    size_t stack_enc = 0, stack_dec = 0;
    hal = bw_board();
    printf("codec core on %s\n", "mps2-an386 (Cortex-M4)");
    for (size_t c = 0; c < GOLDEN_CASES; c++) {
        const golden_case_t *g = &golden_cases[c];
        bw_dims_t d;
        if (bw_dims_make(&d, (bw_shape_t)g->shape, g->level_out, g->level_in, g->n_in, g->bands) !=
                BW_OK ||
            bw_dims_samples(&d) > MAX_SAMPLES || d.bands > MAX_BANDS) {
            check(0, "dims", g->name);
            continue;
        }
        size_t n = bw_dims_samples(&d);
        golden_input(&d, x);
        bw_params_t p = golden_params(g);
        job.d = &d;
        job.p = &p;
        size_t stack = stack_used(run_encode);
        size_t len = job.len;
        uint64_t enc_instr = job.instr;
        bw_status_t st = job.st;
        if (stack > stack_enc)
            stack_enc = stack;
        check(stack <= BW_CTX_STACK_MAX, "encoder's stack above BW_CTX_STACK_MAX", g->name);
        check(st == BW_OK, bw_strerror(st), g->name);
        if (st != BW_OK)
            continue;

        uint32_t want_crc = 0;
        size_t want_len = 0;
        uint32_t crc = bw_crc32(payload, len - BW_TRAILER_SIZE);
        if (golden_lookup(g->name, &want_crc, &want_len) != 0)
            check(0, "not in tests/golden/payload_crc.txt", g->name);
        else
            check(crc == want_crc && len == want_len, "payload differs from the host's", g->name);

        /* decode alone, then the guarantee */
        stack = stack_used(run_decode);
        st = job.st;
        if (stack > stack_dec)
            stack_dec = stack;
        check(stack <= BW_CTX_STACK_MAX, "decoder's stack above BW_CTX_STACK_MAX", g->name);
        check(st == BW_OK, bw_strerror(st), g->name);
        uint32_t worst = 0;
        for (size_t i = 0; st == BW_OK && i < n; i++) {
            int64_t e = (int64_t)verify[i] - x[i];
            uint32_t a = (uint32_t)(e < 0 ? -e : e);
            if (a > worst)
                worst = a;
        }
        if (g->mode == BW_MODE_LOSSLESS)
            check(worst == 0, "lossless decode not exact", g->name);
        if (g->mode == BW_MODE_MAX_ERROR)
            check(worst <= g->param, "max error exceeded", g->name);
        printf("  %-32s %6lu samples %6lu bytes  encode+verify %8.1f instr/sample  decode %6.1f\n",
               g->name, (unsigned long)n, (unsigned long)len, (double)enc_instr / (double)n,
               (double)job.instr / (double)n);

        if (g->flags & BW_FLAG_STREAM_ORDER) {
            /* the streaming encoder, spectrum by spectrum, makes the same payload */
            if (d.bands > sizeof spectrum / sizeof *spectrum ||
                bw_stream_mem_bound(d.level_out, d.bands) > sizeof stream_mem / sizeof *stream_mem) {
                check(0, "streaming buffers too small for this case", g->name);
                continue;
            }
            stream_case = g;
            uint64_t s0 = bw_hal_counter(hal);
            stack = stack_used(run_stream);
            uint64_t s1 = bw_hal_counter(hal);
            check(stream_status == BW_OK, bw_strerror(stream_status), g->name);
            check(stream_status == BW_OK && stream_len == want_len &&
                      bw_crc32(payload, stream_len - BW_TRAILER_SIZE) == want_crc,
                  "streamed payload differs from the host's", g->name);
            size_t mem = bw_stream_mem_bound(d.level_out, d.bands) * 4u;
            printf("  %-32s streaming: %8.1f instr/sample, RAM %lu = context %lu + memory %lu + "
                   "spectrum %lu + stack %lu bytes\n",
                   "", (double)(s1 - s0) / (double)n,
                   (unsigned long)(sizeof stream + mem + d.bands * 4u + stack),
                   (unsigned long)sizeof stream, (unsigned long)mem,
                   (unsigned long)(d.bands * 4u), (unsigned long)stack);
        }
    }
    printf("stack: encode with verify %lu bytes, decode %lu bytes (BW_CTX_STACK_MAX %lu; the "
           "coder's state, bw_ctx_t, %lu bytes, is static)\n",
           (unsigned long)stack_enc, (unsigned long)stack_dec, (unsigned long)BW_CTX_STACK_MAX,
           (unsigned long)sizeof ctx);
    printf("RESULT: %u passed, %u failed\n", passed, failed);
    return failed ? 1 : 0;
}
