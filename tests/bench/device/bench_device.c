/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Device benchmark image: the codec core on the emulated Cortex-M4 (QEMU
 * mps2-an386, semihosting I/O), instructions counted with -icount shift=0
 * through the board's SysTick counter (bw_board()->counter()).
 *
 * One run measures one data set. The semihosting command line is
 *   bench_device NAME FILE SHAPE LEVEL_OUT LEVEL_IN N_IN BANDS
 * where FILE (relative to the working directory, the repository root) holds
 * the samples as little-endian uint16 in the codec's [incoming][outgoing][band]
 * order. The image prints, one per line, space-separated key=value records:
 *   SET     the data set and its dimensions
 *   FLOOR   reference loops over the same 16-bit samples: memcpy, first
 *           difference, table CRC-32 (256 entries, a byte at a time), and the
 *           core's own CRC-32 (nibble table)
 *   ROW     one coding mode: payload bytes, encode without and with the
 *           verify buffer, decode, the error after decoding
 *   PHASE   the transforms alone on the same data (basis the encoder chose)
 *   PROF    a PC-sampling profile of one call (lossless encode, decode,
 *           ratio-8 encode), followed by "P ADDRESS COUNT" lines
 *   STACK   stack high-water marks of bw_encode_ctx / bw_decode_ctx (painted
 *           stack; the coder's state is the static ctx below)
 *   MEM     the arena layout
 *   END     status
 * Instruction counts are totals for the whole buffer; the host divides.
 * Exit status 0 if every measurement ran and every guarantee held.
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_biohaar.h"
#include "bw_codec.h"
#include "bw_crc32.h"
#include "bw_hal.h"
#include "bw_spectral.h"

/* ---- memory --------------------------------------------------------------
 * One arena for every buffer, carved at run time from the data set's size.
 * The rest of the 4 MiB RAM holds the stack (linker/mps2-an386.ld), the
 * C library's heap (semihosting FILE buffers) and small statics. */
#define ARENA_BYTES (4u * 1024u * 1024u - 192u * 1024u)
static uint8_t arena[ARENA_BYTES] __attribute__((aligned(8)));

extern uint32_t _sstack, _estack;

static const bw_hal_t *hal;
static bw_ctx_t ctx; /* the coder's state, off the stack as on a device */
static unsigned failures;

static uint64_t now(void) { return bw_hal_counter(hal); }

/* ---- semihosting command line -------------------------------------------- */

static int semihost(int op, void *arg)
{
    register int r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

#define SYS_GET_CMDLINE 0x15

static char cmdline[512];

static int get_args(char **argv, int cap)
{
    struct {
        char *buf;
        int len;
    } blk = {cmdline, (int)sizeof cmdline - 1};
    if (semihost(SYS_GET_CMDLINE, &blk) != 0)
        return 0;
    cmdline[sizeof cmdline - 1] = '\0';
    int argc = 0;
    char *p = cmdline;
    while (*p && argc < cap) {
        while (*p == ' ')
            p++;
        if (!*p)
            break;
        argv[argc++] = p;
        while (*p && *p != ' ')
            p++;
        if (*p)
            *p++ = '\0';
    }
    return argc;
}

/* ---- floors ---------------------------------------------------------------- */

static uint32_t crc_table[256];

static void crc_table_init(void)
{
    for (uint32_t i = 0; i < 256u; i++) {
        uint32_t c = i;
        for (int k = 0; k < 8; k++)
            c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
        crc_table[i] = c;
    }
}

__attribute__((noinline)) static uint32_t crc32_table(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    while (n--)
        c = crc_table[(c ^ *p++) & 0xFFu] ^ (c >> 8);
    return ~c;
}

__attribute__((noinline)) static void first_diff(const uint16_t *x, int32_t *d, size_t n)
{
    int32_t prev = 0;
    for (size_t i = 0; i < n; i++) {
        int32_t v = x[i];
        d[i] = v - prev;
        prev = v;
    }
}

/* ---- stack high-water mark ----------------------------------------------- */

#define PAINT 0xA5C3E17Bu

static inline __attribute__((always_inline)) uint32_t stack_pointer(void)
{
    uint32_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

/* Paints the free stack below the caller's frame (always inlined, so "sp" is
 * the measuring function's). */
static inline __attribute__((always_inline)) void stack_paint(void)
{
    volatile uint32_t *p = &_sstack, *lim = (volatile uint32_t *)(stack_pointer() - 64u);
    while (p < lim)
        *p++ = PAINT;
}

/* Lowest address written since the paint. */
static uint32_t stack_low(void)
{
    const volatile uint32_t *p = &_sstack;
    while (p < &_estack && *p == PAINT)
        p++;
    return (uint32_t)(uintptr_t)p;
}

static uint32_t stack_enc_max, stack_dec_max, stack_encv_max;

/* ---- the data set ---------------------------------------------------------- */

typedef struct {
    const char *name;
    bw_dims_t d;
    size_t n, wb;
    uint16_t *raw;   /* the 16-bit samples (in the verify area until coding) */
    int32_t *x;      /* samples as int32                                      */
    int32_t *work;   /* bw_work_bound                                         */
    int32_t *verify; /* bw_work_bound                                         */
    uint8_t *out;
    size_t out_cap;
} set_t;

static void *carve(uint8_t **p, size_t bytes)
{
    void *r = *p;
    *p += (bytes + 7u) & ~(size_t)7u;
    return r;
}

static int set_load(set_t *s, const char *path)
{
    s->n = bw_dims_samples(&s->d);
    s->wb = bw_work_bound(s->n, s->d.bands);
    uint8_t *p = arena;
    s->x = carve(&p, s->n * sizeof(int32_t));
    s->work = carve(&p, s->wb * sizeof(int32_t));
    s->verify = carve(&p, s->wb * sizeof(int32_t));
    if (p > arena + ARENA_BYTES) {
        printf("ERROR set=%s what=arena need=%lu have=%lu\n", s->name,
               (unsigned long)(p - arena), (unsigned long)ARENA_BYTES);
        return -1;
    }
    s->out = p;
    s->out_cap = (size_t)(arena + ARENA_BYTES - p);
    if (s->out_cap > bw_payload_bound(s->n))
        s->out_cap = bw_payload_bound(s->n);
    s->raw = (uint16_t *)(void *)s->verify;
    printf("MEM arena=%lu ctx=%lu x=%lu work=%lu verify=%lu out_cap=%lu\n",
           (unsigned long)ARENA_BYTES, (unsigned long)sizeof ctx,
           (unsigned long)(s->n * 4u), (unsigned long)(s->wb * 4u), (unsigned long)(s->wb * 4u),
           (unsigned long)s->out_cap);

    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("ERROR set=%s what=open file=%s\n", s->name, path);
        return -1;
    }
    size_t got = fread(s->raw, sizeof(uint16_t), s->n, f);
    int extra = fgetc(f);
    fclose(f);
    if (got != s->n || extra != EOF) {
        printf("ERROR set=%s what=size file=%s samples=%lu expected=%lu\n", s->name, path,
               (unsigned long)got, (unsigned long)s->n);
        return -1;
    }
    return 0;
}

static volatile uint32_t sink;

static void floors(set_t *s)
{
    size_t n = s->n, bytes = n * sizeof(uint16_t);
    uint8_t *dst = (uint8_t *)s->work;
    uint64_t t0, t1;

    t0 = now();
    memcpy(dst, s->raw, bytes);
    t1 = now();
    sink = dst[bytes - 1];
    printf("FLOOR name=memcpy samples=%lu instr=%llu\n", (unsigned long)n, t1 - t0);

    t0 = now();
    first_diff(s->raw, s->work, n);
    t1 = now();
    sink = (uint32_t)s->work[n - 1];
    printf("FLOOR name=diff samples=%lu instr=%llu\n", (unsigned long)n, t1 - t0);

    t0 = now();
    uint32_t c = crc32_table((const uint8_t *)s->raw, bytes);
    t1 = now();
    printf("FLOOR name=crc32_table samples=%lu instr=%llu crc=%08lx\n",
           (unsigned long)n, t1 - t0, c);

    t0 = now();
    uint32_t c2 = bw_crc32((const uint8_t *)s->raw, bytes);
    t1 = now();
    printf("FLOOR name=crc32_core samples=%lu instr=%llu crc=%08lx\n",
           (unsigned long)n, t1 - t0, c2);
    if (c != c2) {
        printf("ERROR what=crc_mismatch\n");
        failures++;
    }
}

/* ---- one coding mode ------------------------------------------------------- */

typedef struct {
    const char *name;
    uint8_t mode;
    uint32_t max_error;
    uint32_t ratio; /* BYTES: budget = 2 * samples / ratio */
} bench_mode_t;

static const bench_mode_t modes[] = {
    {"lossless", BW_MODE_LOSSLESS, 0, 0}, {"maxerr1", BW_MODE_MAX_ERROR, 1, 0},
    {"maxerr4", BW_MODE_MAX_ERROR, 4, 0}, {"maxerr16", BW_MODE_MAX_ERROR, 16, 0},
    {"ratio8", BW_MODE_BYTES, 0, 8},      {"ratio32", BW_MODE_BYTES, 0, 32},
};

static bw_params_t params_of(const bench_mode_t *m, const set_t *s, uint8_t basis)
{
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = m->mode;
    p.basis = basis;
    p.max_error = m->max_error;
    if (m->mode == BW_MODE_BYTES)
        p.byte_budget = (uint32_t)(2u * s->n / m->ratio);
    p.scale_bits = 0x3F800000u; /* 1.0f: integer samples */
    return p;
}

/* encode, stack painted; returns instructions */
static __attribute__((noinline)) uint64_t timed_encode(set_t *s, const bw_params_t *p,
                                                        int32_t *verify, size_t *len,
                                                        bw_status_t *st, uint32_t *stack)
{
    stack_paint();
    uint32_t sp = stack_pointer();
    uint64_t t0 = now();
    *st = bw_encode_ctx(&ctx, &s->d, p, s->x, s->work, verify, s->out, s->out_cap, len);
    uint64_t t1 = now();
    *stack = sp - stack_low();
    return t1 - t0;
}

static __attribute__((noinline)) uint64_t timed_decode(set_t *s, size_t len, bw_header_t *h,
                                                        bw_status_t *st, uint32_t *stack)
{
    stack_paint();
    uint32_t sp = stack_pointer();
    uint64_t t0 = now();
    *st = bw_decode_ctx(&ctx, s->out, len, s->verify, s->wb, s->verify, s->wb, h);
    uint64_t t1 = now();
    *stack = sp - stack_low();
    return t1 - t0;
}

/* Largest absolute error of the decoded samples (in verify) against the
 * input, and their squared error in *sse. */
static uint32_t decoded_error(const set_t *s, uint64_t *sse)
{
    uint32_t worst = 0;
    *sse = 0;
    for (size_t i = 0; i < s->n; i++) {
        int64_t e = (int64_t)s->verify[i] - s->x[i];
        uint64_t a = (uint64_t)(e < 0 ? -e : e);
        if (a > worst)
            worst = (uint32_t)a;
        *sse += a * a;
    }
    return worst;
}

/* The mode's guarantee: lossless exact, max-error within its bound. */
static int bound_held(uint8_t mode, uint32_t max_error, uint32_t worst)
{
    return !(mode == BW_MODE_LOSSLESS && worst != 0) &&
           !(mode == BW_MODE_MAX_ERROR && worst > max_error);
}

static void max_stack(uint32_t *m, uint32_t v)
{
    if (v > *m)
        *m = v;
}

static int lossless_basis = -1;

/* The basis of the transforms' measurements: the lossless encode's, or 5/3
 * where that chose prediction (no transform, and no quantiser step). */
static unsigned transform_basis(void)
{
    return lossless_basis == BW_BASIS_PRED ? BW_BASIS_53 : (unsigned)lossless_basis;
}

/* A payload of len bytes from an encode of status st: decoded, within the
 * mode's bound and p's budget; its basis in *basis, its squared error in
 * *sse. */
static int coded_ok(set_t *s, const bench_mode_t *m, const bw_params_t *p, size_t len,
                    bw_status_t st, unsigned *basis, uint64_t *sse)
{
    bw_header_t h;
    bw_status_t st_d;
    uint32_t stk;
    if (st != BW_OK)
        return 0;
    (void)timed_decode(s, len, &h, &st_d, &stk);
    max_stack(&stack_dec_max, stk);
    uint32_t worst = st_d == BW_OK ? decoded_error(s, sse) : 0u;
    *basis = h.basis;
    return st_d == BW_OK && bound_held(m->mode, m->max_error, worst) &&
           !(m->mode == BW_MODE_BYTES && len > p->byte_budget);
}

/* A byte budget: the fast encode (p's coder) with each transform basis
 * named, decoded: the smallest squared error in *sse, its basis in *basis
 * (BW_BASIS_AUTO: none). 0: one of them failed. */
static int every_basis_fast(set_t *s, const bench_mode_t *m, bw_params_t p, uint64_t *sse,
                            unsigned *basis)
{
    int ok = 1;
    *sse = 0;
    *basis = BW_BASIS_AUTO;
    p.effort = BW_EFFORT_FAST;
    for (unsigned b = 0; b < BW_BASIS_COUNT; b++) {
        size_t len = 0;
        bw_status_t st;
        uint32_t stk;
        unsigned got = 0;
        uint64_t e = 0;
        p.basis = (uint8_t)b;
        (void)timed_encode(s, &p, NULL, &len, &st, &stk);
        if (!coded_ok(s, m, &p, len, st, &got, &e) || got != b)
            ok = 0;
        else if (*basis == BW_BASIS_AUTO || e < *sse) {
            *sse = e;
            *basis = b;
        }
    }
    return ok;
}

static void run_mode(set_t *s, const bench_mode_t *m)
{
    bw_params_t p = params_of(m, s, BW_BASIS_AUTO);
    size_t len = 0, len_v = 0, len_f = 0;
    bw_status_t st, st_v, st_d, st_f = BW_OK;
    uint32_t stk_e, stk_v, stk_d, stk_f;

    /* with verify first (the payload is then overwritten by the device path) */
    uint64_t t_encv = timed_encode(s, &p, s->verify, &len_v, &st_v, &stk_v);
    uint32_t crc_v = st_v == BW_OK ? bw_crc32(s->out, len_v) : 0u;
    max_stack(&stack_encv_max, stk_v);

    uint64_t t_enc = timed_encode(s, &p, NULL, &len, &st, &stk_e);
    max_stack(&stack_enc_max, stk_e);
    if (st != BW_OK) {
        printf("ROW mode=%s status=%d error=\"%s\" encv_status=%d\n", m->name, (int)st,
               bw_strerror(st), (int)st_v);
        failures++;
        return;
    }
    uint32_t crc_e = bw_crc32(s->out, len);

    bw_header_t h;
    uint64_t t_dec = timed_decode(s, len, &h, &st_d, &stk_d);
    unsigned basis = h.basis, levels = h.spectral_levels;
    max_stack(&stack_dec_max, stk_d);
    uint64_t sse = 0;
    uint32_t worst = st_d == BW_OK ? decoded_error(s, &sse) : 0u;
    int ok = st_v == BW_OK && st_d == BW_OK && bound_held(m->mode, m->max_error, worst);
    if (m->mode == BW_MODE_BYTES && (len > p.byte_budget || len_v > p.byte_budget))
        ok = 0;

    /* the same encode with the basis fixed to the one chosen (one pass per
     * step instead of one per basis); only where there is a spectral axis */
    uint64_t t_encf = 0;
    if (levels > 0u || basis == BW_BASIS_PRED) {
        bw_params_t pf = params_of(m, s, (uint8_t)basis);
        t_encf = timed_encode(s, &pf, NULL, &len_f, &st_f, &stk_f);
        max_stack(&stack_enc_max, stk_f);
        if (st_f != BW_OK || len_f != len || bw_crc32(s->out, len_f) != crc_e)
            ok = 0; /* the fixed-basis payload must be the same payload */
    }
    if (m->mode == BW_MODE_LOSSLESS)
        lossless_basis = (int)basis;

    /* BW_EFFORT_FAST: the basis chosen on parts of the measurement, then one
     * encode (a byte budget: its step estimated and corrected by each
     * encode); its payload decoded and checked, and the same with the basis
     * it chose named (for a byte budget always: the figure of its search) */
    uint64_t t_encq = 0, t_encqf = t_encf, sse_q = 0;
    size_t len_q = 0, len_qf = 0;
    unsigned basis_q = basis;
    uint32_t worst_q = 0;
    if (levels > 0u || basis == BW_BASIS_PRED || m->mode == BW_MODE_BYTES) {
        bw_params_t pq = params_of(m, s, BW_BASIS_AUTO);
        pq.effort = BW_EFFORT_FAST;
        bw_status_t st_q, st_qd;
        uint32_t stk_q;
        bw_header_t hq;
        t_encq = timed_encode(s, &pq, NULL, &len_q, &st_q, &stk_q);
        max_stack(&stack_enc_max, stk_q);
        if (st_q == BW_OK) {
            (void)timed_decode(s, len_q, &hq, &st_qd, &stk_q);
            basis_q = hq.basis;
            worst_q = st_qd == BW_OK ? decoded_error(s, &sse_q) : 0u;
            if (st_qd != BW_OK || !bound_held(m->mode, m->max_error, worst_q) ||
                (m->mode == BW_MODE_BYTES && len_q > p.byte_budget))
                ok = 0;
            if (basis_q != basis || m->mode == BW_MODE_BYTES) {
                bw_params_t pf = params_of(m, s, (uint8_t)basis_q);
                pf.effort = BW_EFFORT_FAST;
                t_encqf = timed_encode(s, &pf, NULL, &len_qf, &st_q, &stk_q);
                if (st_q != BW_OK || len_qf != len_q)
                    ok = 0;
            }
        } else {
            ok = 0;
        }
    }

    /* a byte budget with a spectral axis: the same fast encode with each
     * transform basis named, decoded: the smallest squared error is what
     * trying every basis with the same encode gives */
    uint64_t sse_every = 0;
    unsigned basis_every = BW_BASIS_AUTO;
    if (m->mode == BW_MODE_BYTES && levels > 0u &&
        !every_basis_fast(s, m, p, &sse_every, &basis_every))
        ok = 0;

    printf("ROW mode=%s max_error=%lu budget=%lu samples=%lu bytes=%lu "
           "bytes_verify=%lu same_payload=%d basis=%u step_q8=%lu enc=%llu"
           " enc_verify=%llu enc_fixed=%llu dec=%llu worst=%lu"
           " sse=%llu enc_quick=%llu enc_quick_fixed=%llu bytes_quick=%lu basis_quick=%u"
           " worst_quick=%lu sse_quick=%llu sse_every_fast=%llu basis_every_fast=%u status=%s\n",
           m->name, m->max_error, p.byte_budget, (unsigned long)s->n, (unsigned long)len,
           (unsigned long)len_v, len == len_v && crc_e == crc_v, basis, h.step_q8, t_enc, t_encv,
           t_encf, t_dec, worst, sse, t_encq, t_encqf, (unsigned long)len_q, basis_q,
           (unsigned long)worst_q, sse_q, sse_every, basis_every, ok ? "ok" : "FAIL");
    if (!ok) {
        printf("ERROR mode=%s encv=%d dec=%d fixed=%d\n", m->name, (int)st_v, (int)st_d,
               (int)st_f);
        failures++;
    }
}

/* ---- the basis choice with the device's coder ------------------------------
 * BW_EFFORT_FAST with BW_BASIS_AUTO and BW_CODER_AUTO (the device's
 * defaults) against the same encode with the basis it chose named, and
 * against trying every basis (BW_EFFORT_BEST, the same coder): its payload
 * or, for a byte budget, whose payloads all fill it, the smallest squared
 * error of the fast encode with each transform basis named. Every payload
 * decoded and checked. Only where there is a spectral axis. */
static void run_choice(set_t *s, const bench_mode_t *m)
{
    if (bw_spec_levels(s->d.bands) == 0u)
        return;
    bw_params_t pq = params_of(m, s, BW_BASIS_AUTO);
    pq.coder = BW_CODER_AUTO;
    pq.effort = BW_EFFORT_FAST;
    bw_status_t st;
    uint32_t stk;
    size_t len_q = 0, len_f = 0, len_e = 0;
    unsigned basis_q = 0, basis_e = 0;
    uint64_t sse_q = 0, sse_e = 0;
    uint64_t t_q = timed_encode(s, &pq, NULL, &len_q, &st, &stk);
    max_stack(&stack_enc_max, stk);
    int ok = coded_ok(s, m, &pq, len_q, st, &basis_q, &sse_q);
    uint32_t crc_q = ok ? bw_crc32(s->out, len_q) : 0u;
    bw_params_t pf = pq;
    pf.basis = (uint8_t)basis_q;
    uint64_t t_f = timed_encode(s, &pf, NULL, &len_f, &st, &stk);
    if (!ok || st != BW_OK || len_f != len_q || bw_crc32(s->out, len_f) != crc_q)
        ok = 0; /* the basis named gives the same payload */
    bw_params_t pe = pq;
    pe.effort = BW_EFFORT_BEST;
    uint64_t t_e = timed_encode(s, &pe, NULL, &len_e, &st, &stk);
    max_stack(&stack_enc_max, stk);
    if (!coded_ok(s, m, &pe, len_e, st, &basis_e, &sse_e))
        ok = 0;
    uint64_t sse_every = 0;
    unsigned basis_every = BW_BASIS_AUTO;
    if (m->mode == BW_MODE_BYTES && !every_basis_fast(s, m, pq, &sse_every, &basis_every))
        ok = 0;
    printf("CHOICE coder=auto mode=%s samples=%lu bytes_quick=%lu basis_quick=%u enc_quick=%llu"
           " enc_quick_fixed=%llu sse_quick=%llu bytes_every=%lu basis_every=%u enc_every=%llu"
           " sse_every=%llu sse_every_fast=%llu basis_every_fast=%u status=%s\n",
           m->name, (unsigned long)s->n, (unsigned long)len_q, basis_q, t_q, t_f, sse_q,
           (unsigned long)len_e, basis_e, t_e, sse_e, sse_every, basis_every,
           ok ? "ok" : "FAIL");
    if (!ok)
        failures++;
}

/* ---- the Rice strip coder ------------------------------------------------
 * The device configuration for speed: BW_FLAG_RICE with a fixed basis, one
 * pass per encode. Modes: lossless, max-error 1/4/16 and a fixed quantiser
 * step (BW_MODE_STEP, step in sample units). Each row is checked: decoded
 * within its bound (lossless exact, max-error within E), and the payload
 * decodes to what the encoder with its verify buffer accepts. */
typedef struct {
    const char *name;
    uint8_t mode;
    uint32_t max_error;
    uint32_t step; /* STEP: sample units */
} fast_mode_t;

static const fast_mode_t fast_modes[] = {
    {"lossless", BW_MODE_LOSSLESS, 0, 0}, {"maxerr1", BW_MODE_MAX_ERROR, 1, 0},
    {"maxerr4", BW_MODE_MAX_ERROR, 4, 0}, {"maxerr16", BW_MODE_MAX_ERROR, 16, 0},
    {"step8", BW_MODE_STEP, 0, 8},        {"step64", BW_MODE_STEP, 0, 64},
};

/* the coders: by their flag, or BW_CODER_AUTO (the device's: for
 * prediction Rice strips or the multi-symbol coder, for a set of spectra
 * transformed the static tables or the multi-symbol coder, else the
 * multi-symbol coder) */
static const struct {
    const char *name;
    uint8_t flag, automatic;
} fast_coders[] = {
    {"rice", BW_FLAG_RICE, 0},
    {"ms", BW_FLAG_MS, 0},
    {"tab", BW_FLAG_RICE | BW_FLAG_MS, 0},
    {"range", 0, 0},
    {"auto", 0, 1}};

static void run_fast(set_t *s)
{
    unsigned levels = bw_spec_levels(s->d.bands);
    bool pred = s->d.shape == BW_SHAPE_SPECTRA;
    for (size_t c = 0; c < sizeof fast_coders / sizeof *fast_coders; c++)
    for (unsigned basis = 0; basis <= BW_BASIS_PRED; basis++) {
        if (basis < BW_BASIS_COUNT && !levels && basis != BW_BASIS_53)
            continue; /* no spectral axis: one row per mode */
        if (basis == BW_BASIS_PRED && !pred)
            continue;
        for (size_t i = 0; i < sizeof fast_modes / sizeof *fast_modes; i++) {
            const fast_mode_t *m = &fast_modes[i];
            if (basis == BW_BASIS_PRED && m->mode > BW_MODE_MAX_ERROR)
                continue;
            bw_params_t p;
            memset(&p, 0, sizeof p);
            p.mode = m->mode;
            p.basis = (uint8_t)basis;
            p.max_error = m->max_error;
            p.step_q8 = m->step * 256u;
            p.flags = fast_coders[c].flag;
            p.coder = fast_coders[c].automatic ? BW_CODER_AUTO : BW_CODER_BY_FLAGS;
            p.scale_bits = 0x3F800000u;
            size_t len = 0;
            bw_status_t st, st_d;
            uint32_t stk;
            uint64_t t_enc = timed_encode(s, &p, NULL, &len, &st, &stk);
            max_stack(&stack_enc_max, stk);
            if (st != BW_OK) {
                printf("ERROR what=fast mode=%s basis=%u status=%d\n", m->name, basis, (int)st);
                failures++;
                continue;
            }
            bw_header_t h;
            uint64_t t_dec = timed_decode(s, len, &h, &st_d, &stk);
            max_stack(&stack_dec_max, stk);
            uint64_t sse = 0;
            uint32_t worst = st_d == BW_OK ? decoded_error(s, &sse) : 0u;
            unsigned got = h.flags & (BW_FLAG_RICE | BW_FLAG_MS);
            int ok = st_d == BW_OK && bound_held(m->mode, m->max_error, worst) &&
                     (fast_coders[c].automatic || got == fast_coders[c].flag);
            printf("FAST coder=%s basis=%u mode=%s samples=%lu bytes=%lu enc=%llu dec=%llu"
                   " worst=%lu sse=%llu chosen=%s status=%s\n",
                   fast_coders[c].name, basis, m->name, (unsigned long)s->n, (unsigned long)len,
                   t_enc, t_dec, (unsigned long)worst, sse,
                   got == (BW_FLAG_RICE | BW_FLAG_MS) ? "tab"
                   : got == BW_FLAG_RICE              ? "rice"
                   : got == BW_FLAG_MS                ? "ms"
                                                      : "range",
                   ok ? "ok" : "FAIL");
            if (!ok)
                failures++;
        }
    }
}

/* ---- the transforms alone ------------------------------------------------ */

static void phases(set_t *s)
{
    const bw_dims_t *d = &s->d;
    if (lossless_basis < 0)
        return;
    unsigned basis = transform_basis(), levels = bw_spec_levels(d->bands);
    size_t vectors = (size_t)d->n_in * d->n_out;
    int32_t *w = s->work, *tmp = s->work + s->n;
    uint64_t t0, t1;

    t0 = now();
    memcpy(w, s->x, s->n * sizeof *w);
    t1 = now();
    printf("PHASE name=copy_int32 instr=%llu\n", t1 - t0);

    if (levels) {
        t0 = now();
        for (size_t v = 0; v < vectors; v++)
            bw_spec_fwd(w + v * d->bands, d->bands, basis, levels, tmp);
        t1 = now();
        printf("PHASE name=spectral_fwd basis=%u levels=%u instr=%llu\n", basis, levels,
               t1 - t0);
    }
    if (d->shape != BW_SHAPE_SPECTRA) {
        t0 = now();
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_fwd(w + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
        t1 = now();
        printf("PHASE name=biohaar_out_fwd level=%u instr=%llu\n", d->level_out, t1 - t0);
    }
    if (d->shape == BW_SHAPE_BRDF_FULL) {
        t0 = now();
        bw_biohaar_fwd(w, d->level_in, (size_t)d->n_out * d->bands);
        t1 = now();
        printf("PHASE name=biohaar_in_fwd level=%u instr=%llu\n", d->level_in, t1 - t0);
        t0 = now();
        bw_biohaar_inv(w, d->level_in, (size_t)d->n_out * d->bands);
        t1 = now();
        printf("PHASE name=biohaar_in_inv level=%u instr=%llu\n", d->level_in, t1 - t0);
    }
    if (d->shape != BW_SHAPE_SPECTRA) {
        t0 = now();
        for (uint32_t i = 0; i < d->n_in; i++)
            bw_biohaar_inv(w + (size_t)i * d->n_out * d->bands, d->level_out, d->bands);
        t1 = now();
        printf("PHASE name=biohaar_out_inv level=%u instr=%llu\n", d->level_out, t1 - t0);
    }
    if (levels) {
        t0 = now();
        for (size_t v = 0; v < vectors; v++)
            bw_spec_inv(w + v * d->bands, d->bands, basis, levels, tmp);
        t1 = now();
        printf("PHASE name=spectral_inv basis=%u levels=%u instr=%llu\n", basis, levels,
               t1 - t0);
    }
    if (memcmp(w, s->x, s->n * sizeof *w) != 0) {
        printf("ERROR what=transform_round_trip\n");
        failures++;
    }

    /* everything but the coding of values: a step so large that every
     * coefficient quantises to zero (load, range check, transform, tables,
     * quantiser, one presence flag per strip, header, CRC), and its decode */
    bw_params_t pz = params_of(&modes[0], s, (uint8_t)basis);
    pz.mode = BW_MODE_STEP;
    pz.step_q8 = UINT32_MAX;
    size_t lz = 0;
    t0 = now();
    bw_status_t stz = bw_encode_ctx(&ctx, d, &pz, s->x, s->work, NULL, s->out, s->out_cap, &lz);
    t1 = now();
    if (stz == BW_OK) {
        printf("PHASE name=encode_all_zero bytes=%lu instr=%llu\n", (unsigned long)lz, t1 - t0);
        t0 = now();
        stz = bw_decode_ctx(&ctx, s->out, lz, s->verify, s->wb, s->verify, s->wb, NULL);
        t1 = now();
        if (stz == BW_OK)
            printf("PHASE name=decode_all_zero bytes=%lu instr=%llu\n", (unsigned long)lz,
                   t1 - t0);
    }
    if (stz != BW_OK) {
        printf("ERROR what=all_zero status=%d\n", (int)stz);
        failures++;
    }

    /* the payload CRC of the lossless payload, as the encoder computes it */
    bw_params_t p = params_of(&modes[0], s, (uint8_t)lossless_basis);
    size_t len = 0;
    if (bw_encode_ctx(&ctx, d, &p, s->x, s->work, NULL, s->out, s->out_cap, &len) == BW_OK) {
        t0 = now();
        sink = bw_crc32(s->out, len - BW_TRAILER_SIZE);
        t1 = now();
        printf("PHASE name=payload_crc bytes=%lu instr=%llu\n", (unsigned long)len,
               t1 - t0);
    }
}

/* ---- where the instructions go: PC sampling --------------------------------
 * CMSDK APB timer 0 (IRQ 8 on mps2-an386, 25 MHz like SysTick) interrupts
 * every PROF_TICKS ticks (40 instructions a tick under -icount shift=0) and
 * the handler counts the interrupted PC in 4-byte bins. The vector table is
 * copied to RAM with the timer's entry added. Profiled runs are separate from
 * the measured ones (the handler's own instructions would count there). */
#define TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)
#define TIMER0_INTCLEAR (*(volatile uint32_t *)0x4000000Cu)
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define NVIC_ICER0 (*(volatile uint32_t *)0xE000E180u)
#define SCB_VTOR (*(volatile uint32_t *)0xE000ED08u)
#define TIMER0_IRQ 8u
#define PROF_TICKS 23u
#define PROF_BINS 32768u /* 128 KiB of code in 4-byte bins (the image's text is below) */

static uint32_t prof_hist[PROF_BINS];
static uint32_t prof_outside, prof_total;
static void (*ram_vectors[48])(void) __attribute__((aligned(256)));

__attribute__((used)) void bench_prof_sample(const uint32_t *frame);
void bench_prof_sample(const uint32_t *frame)
{
    TIMER0_INTCLEAR = 1u;
    uint32_t pc = frame[6] >> 2;
    prof_total++;
    if (pc < PROF_BINS)
        prof_hist[pc]++;
    else
        prof_outside++;
}

/* the exception frame is at sp on entry: r0 r1 r2 r3 r12 lr pc xpsr */
__attribute__((naked)) static void prof_irq(void)
{
    __asm__ volatile("mov r0, sp\n\tb bench_prof_sample\n");
}

static void prof_start(void)
{
    void (*const *cur)(void) = (void (*const *)(void))(uintptr_t)SCB_VTOR;
    for (unsigned i = 0; i < 16u; i++)
        ram_vectors[i] = cur[i];
    ram_vectors[16u + TIMER0_IRQ] = prof_irq;
    __asm__ volatile("dsb" ::: "memory");
    SCB_VTOR = (uint32_t)(uintptr_t)ram_vectors;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    memset(prof_hist, 0, sizeof prof_hist);
    prof_outside = prof_total = 0;
    TIMER0_RELOAD = PROF_TICKS;
    TIMER0_VALUE = PROF_TICKS;
    TIMER0_INTCLEAR = 1u;
    NVIC_ISER0 = 1u << TIMER0_IRQ;
    TIMER0_CTRL = 0x9u; /* enable, interrupt enable */
}

static void prof_stop(const char *what)
{
    TIMER0_CTRL = 0u;
    NVIC_ICER0 = 1u << TIMER0_IRQ;
    TIMER0_INTCLEAR = 1u;
    printf("PROF what=%s period_instr=%lu samples=%lu outside=%lu\n", what,
           (unsigned long)(PROF_TICKS * 40u), (unsigned long)prof_total,
           (unsigned long)prof_outside);
    for (uint32_t b = 0; b < PROF_BINS; b++)
        if (prof_hist[b])
            printf("P %lx %lu\n", (unsigned long)(b << 2), (unsigned long)prof_hist[b]);
}

static void profile(set_t *s)
{
    if (lossless_basis < 0)
        return;
    bw_params_t p = params_of(&modes[0], s, (uint8_t)lossless_basis);
    size_t len = 0;
    prof_start();
    bw_status_t st = bw_encode_ctx(&ctx, &s->d, &p, s->x, s->work, NULL, s->out, s->out_cap, &len);
    prof_stop("encode_lossless");
    if (st == BW_OK) {
        prof_start();
        st = bw_decode_ctx(&ctx, s->out, len, s->verify, s->wb, s->verify, s->wb, NULL);
        prof_stop("decode_lossless");
    }
    bw_params_t pb = params_of(&modes[4], s, (uint8_t)transform_basis());
    if (st == BW_OK) {
        prof_start();
        st = bw_encode_ctx(&ctx, &s->d, &pb, s->x, s->work, NULL, s->out, s->out_cap, &len);
        prof_stop("encode_ratio8");
    }
    /* the Rice, the multi-symbol and the static-table coders, 5/3: lossless
     * and max-error 4 */
    static const char *const what[] = {"encode_rice_lossless", "encode_rice_maxerr4",
                                       "encode_ms_lossless",   "encode_ms_maxerr4",
                                       "encode_tab_lossless",  "encode_tab_maxerr4"};
    static const uint8_t flag[] = {BW_FLAG_RICE, BW_FLAG_MS, BW_FLAG_RICE | BW_FLAG_MS};
    for (unsigned i = 0; i < 6u && st == BW_OK; i++) {
        bw_params_t pr = params_of(&modes[i & 1u ? 2 : 0], s, BW_BASIS_53);
        pr.flags = flag[i / 2u];
        prof_start();
        st = bw_encode_ctx(&ctx, &s->d, &pr, s->x, s->work, NULL, s->out, s->out_cap, &len);
        prof_stop(what[i]);
    }
    if (st != BW_OK) {
        printf("ERROR what=profile status=%d\n", (int)st);
        failures++;
    }
}

/* ---- main ------------------------------------------------------------------ */

int main(void)
{
    hal = bw_board();
    char *argv[12];
    int argc = get_args(argv, 12);
    /* a ninth argument "fast": the one-pass rows only (FAST) */
    if (argc != 8 && !(argc == 9 && !strcmp(argv[8], "fast"))) {
        printf("ERROR what=usage argc=%d (bench_device NAME FILE SHAPE LEVEL_OUT LEVEL_IN N_IN "
               "BANDS [fast])\n",
               argc);
        return 2;
    }
    set_t s;
    memset(&s, 0, sizeof s);
    s.name = argv[1];
    bw_status_t st =
        bw_dims_make(&s.d, (bw_shape_t)atoi(argv[3]), (unsigned)atoi(argv[4]),
                     (unsigned)atoi(argv[5]), (uint32_t)atol(argv[6]), (uint32_t)atol(argv[7]));
    if (st != BW_OK) {
        printf("ERROR what=dims status=%d\n", (int)st);
        return 2;
    }
    printf("SET name=%s shape=%u level_out=%u level_in=%u n_in=%lu n_out=%lu bands=%lu "
           "samples=%lu\n",
           s.name, s.d.shape, s.d.level_out, s.d.level_in, (unsigned long)s.d.n_in,
           (unsigned long)s.d.n_out, (unsigned long)s.d.bands,
           (unsigned long)bw_dims_samples(&s.d));
    if (set_load(&s, argv[2]) != 0)
        return 2;
    crc_table_init();

    /* the empty interval: what a measurement costs by itself */
    uint64_t t0 = now(), t1 = now();
    printf("FLOOR name=empty samples=%lu instr=%llu\n", (unsigned long)s.n, t1 - t0);
    floors(&s);

    for (size_t i = 0; i < s.n; i++)
        s.x[i] = s.raw[i];
    if (argc == 9) {
        run_fast(&s);
        /* where the one-pass coders spend them: the multi-symbol and the
         * static-table coder, 5/3 lossless, 9/7 lossless and step 8 */
        static const char *const what[] = {"encode_ms_lossless",  "encode_ms_97_lossless",
                                           "encode_ms_97_step8",  "encode_tab_lossless",
                                           "encode_tab_97_lossless", "encode_tab_97_step8"};
        for (unsigned i = 0; i < 6u; i++) {
            bw_params_t pm;
            memset(&pm, 0, sizeof pm);
            pm.mode = i % 3u == 2u ? BW_MODE_STEP : BW_MODE_LOSSLESS;
            pm.step_q8 = 8u * 256u;
            pm.basis = i % 3u ? BW_BASIS_97 : BW_BASIS_53;
            pm.flags = i < 3u ? BW_FLAG_MS : BW_FLAG_MS | BW_FLAG_RICE;
            pm.scale_bits = 0x3F800000u;
            size_t len = 0;
            prof_start();
            bw_encode_ctx(&ctx, &s.d, &pm, s.x, s.work, NULL, s.out, s.out_cap, &len);
            prof_stop(what[i]);
        }
        printf("END status=%s failures=%u\n", failures ? "FAIL" : "ok", failures);
        return failures ? 1 : 0;
    }
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++)
        run_mode(&s, &modes[m]);
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++)
        run_choice(&s, &modes[m]);
    run_fast(&s);
    phases(&s);
    profile(&s);

    printf("STACK encode=%lu encode_verify=%lu decode=%lu"
           " stack_region=%lu\n",
           stack_enc_max, stack_encv_max, stack_dec_max,
           (unsigned long)((uintptr_t)&_estack - (uintptr_t)&_sstack));
    printf("END status=%s failures=%u\n", failures ? "FAIL" : "ok", failures);
    return failures ? 1 : 0;
}
