/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The on-device application: wait for a job from the host, read the
 * measurement from the sensor, encode it with the codec core, send the
 * payload in frames, and keep it until the host acknowledges it.
 *
 *   idle --JOB--> read --> encode --> send --+--ACK--> idle
 *                                    ^      |
 *                                    +------+ RESEND (chunks), or silence
 *                                             for ACK_WAIT instructions
 *   idle --RESEND (the payload kept)--> send --> ...
 *   idle --QUIT--> exit
 *
 * A job in stream order with a fixed basis and an exact or bounded-error
 * mode is encoded spectrum by spectrum (bw_stream_*): its RAM does not grow
 * with the number of directions (APP_STREAM_* bound the level and bands).
 * Other jobs hold the whole measurement (APP_MAX_SAMPLES). See docs/LINK.md.
 *
 * The payload kept for the host is also offered to the board
 * (bw_hal_offer), which may serve it on a second link (the I2C register
 * window of docs/I2C.md); an ACK over that link reaches the application as an
 * ACK frame, like one over the UART.
 */
#include "app.h"

#include <string.h>

#include "bw_codec.h"
#include "bw_crc32.h"
#include "bw_frame.h"

#ifndef APP_MAX_SAMPLES
#define APP_MAX_SAMPLES 131072u
#endif
#ifndef APP_MAX_BANDS
#define APP_MAX_BANDS 4096u
#endif
#ifndef APP_PAYLOAD_CAP
#define APP_PAYLOAD_CAP (1024u * 1024u)
#endif
/* instructions without an answer before the payload is sent again */
#define ACK_WAIT 4000000000ull
#define MAX_SENDS 8u

/* the extension records (the host's metadata) a job can bring in JOB_EXT
 * frames before its JOB, beyond what the JOB frame holds */
#ifndef APP_EXT_MAX
#define APP_EXT_MAX 2048u
#endif

#ifndef APP_STREAM_LEVEL
#define APP_STREAM_LEVEL 6u
#endif
#ifndef APP_STREAM_BANDS
#define APP_STREAM_BANDS 2151u
#endif

static bw_stream_t stream;
static int32_t stream_mem[BW_STREAM_MEM_BOUND(APP_STREAM_LEVEL, APP_STREAM_BANDS)];
static int32_t spectrum[APP_STREAM_BANDS];
static int32_t samples[APP_MAX_SAMPLES];
static int32_t work[BW_WORK_BOUND(APP_MAX_SAMPLES, APP_MAX_BANDS)];
static bw_ctx_t ctx; /* the coder's state, off the stack */
static uint8_t payload[APP_PAYLOAD_CAP];
static uint8_t job_ext[APP_EXT_MAX];
static uint32_t job_ext_len;
static bool job_ext_over; /* more JOB_EXT bytes came than job_ext holds */
static uint8_t txbuf[BW_FRAME_MAX];
static bw_frame_rx_t rx;
static bw_frame_t frame;

static void send(const bw_hal_t *hal, uint8_t type, uint16_t seq, const uint8_t *d, uint16_t len)
{
    size_t n = bw_frame_pack(txbuf, type, seq, d, len);
    bw_hal_link_write(hal, txbuf, n);
}

static const bw_limits_t limits = {APP_MAX_SAMPLES, APP_MAX_BANDS, APP_STREAM_BANDS,
                                   APP_PAYLOAD_CAP, APP_STREAM_LEVEL};

static void send_error(const bw_hal_t *hal, int status)
{
    uint8_t d[BW_ERROR_SIZE];
    send(hal, BW_FT_ERROR, 0, d, (uint16_t)bw_error_pack(status, &limits, d));
    bw_hal_offer(hal, 0, NULL, 0, status);
}

/* Bytes read from the link and not yet given to the frame receiver: a read
 * can bring several frames (an ACK and a QUIT back to back), and every one
 * of them is kept for the next call. */
static uint8_t rxbuf[64];
static size_t rx_pos, rx_len;

/* Next frame from the host, or false after `wait` instructions (0: forever). */
static bool receive(const bw_hal_t *hal, uint64_t wait)
{
    uint64_t t0 = bw_hal_counter(hal);
    for (;;) {
        bool got;
        rx_pos += bw_frame_rx_feed(&rx, rxbuf + rx_pos, rx_len - rx_pos, &frame, &got);
        if (got)
            return true;
        int n = bw_hal_link_read(hal, rxbuf, sizeof rxbuf);
        rx_pos = 0;
        rx_len = n > 0 ? (size_t)n : 0u;
        if (n <= 0 && wait && bw_hal_counter(hal) - t0 > wait)
            return false;
    }
}

static uint16_t chunks_of(size_t len) { return (uint16_t)((len + BW_FRAME_MAX_DATA - 1u) / BW_FRAME_MAX_DATA); }

static void send_chunk(const bw_hal_t *hal, size_t len, uint16_t c)
{
    size_t off = (size_t)c * BW_FRAME_MAX_DATA;
    size_t n = len - off < BW_FRAME_MAX_DATA ? len - off : BW_FRAME_MAX_DATA;
    send(hal, BW_FT_DATA, c, payload + off, (uint16_t)n);
}

static void send_payload(const bw_hal_t *hal, uint32_t id, size_t len, uint64_t instructions)
{
    uint8_t d[22];
    bw_put_u32(d, id);
    bw_put_u32(d + 4, (uint32_t)len);
    bw_put_u16(d + 8, chunks_of(len));
    bw_put_u32(d + 10, bw_crc32(payload, len));
    bw_put_u32(d + 14, (uint32_t)instructions);
    bw_put_u32(d + 18, (uint32_t)(instructions >> 32));
    send(hal, BW_FT_START, 0, d, sizeof d);
    for (uint16_t c = 0; c < chunks_of(len); c++)
        send_chunk(hal, len, c);
    bw_put_u32(d, id);
    send(hal, BW_FT_END, 0, d, 4);
}

static int deliver(const bw_hal_t *hal, uint32_t id, size_t len, uint64_t spent);

/* The payload in the buffer that the host has not acknowledged (id 0:
 * none): after MAX_SENDS sends it stays until the next job, and a RESEND
 * or ACK for it is still answered (the host may come back for the chunks
 * it missed, docs/LINK.md). */
static struct {
    uint32_t id;
    size_t len;
    uint64_t spent;
} kept;

/* Reads exactly n samples from the sensor; false if it delivers fewer. */
static bool read_samples(const bw_hal_t *hal, int32_t *dst, size_t n)
{
    size_t got = 0;
    while (got < n) {
        int r = bw_hal_sensor_read(hal, dst + got, n - got);
        if (r <= 0)
            return false;
        got += (size_t)r;
    }
    return true;
}

/* Runs one job; returns 0 when the host acknowledged the payload. */
static int run_job(const bw_hal_t *hal, const bw_job_t *job, uint32_t id)
{
    bw_hal_offer(hal, 0, NULL, 0, 0); /* the payload buffer is about to be reused */
    kept.id = 0;
    bw_dims_t d;
    bw_status_t st = bw_dims_make(&d, (bw_shape_t)job->shape, job->level_out, job->level_in,
                                  job->n_in, job->bands);
    bw_params_t p;
    bw_job_params(job, &p);
    bool streaming = false;
    if (st == BW_OK)
        st = bw_limits_admit(&limits, &d, &p, &streaming);
    if (st != BW_OK) {
        send_error(hal, st);
        return -1;
    }
    size_t n = bw_dims_samples(&d);
    if (bw_hal_sensor_open(hal, job->source) < 0) {
        send_error(hal, APP_ERR_SENSOR);
        return -1;
    }
    size_t len = 0;
    if (streaming) {
        uint64_t t0 = bw_hal_counter(hal);
        st = bw_stream_init(&stream, &d, &p, stream_mem, sizeof stream_mem / sizeof *stream_mem,
                            payload, sizeof payload);
        for (size_t v = 0; st == BW_OK && v < (size_t)d.n_in * d.n_out; v++) {
            if (!read_samples(hal, spectrum, d.bands)) {
                send_error(hal, APP_ERR_SENSOR);
                return -1;
            }
            st = bw_stream_push(&stream, spectrum);
        }
        if (st == BW_OK)
            st = bw_stream_finish(&stream, &len);
        uint64_t spent = bw_hal_counter(hal) - t0;
        if (st != BW_OK) {
            send_error(hal, st);
            return -1;
        }
        return deliver(hal, id, len, spent);
    }
    if (!read_samples(hal, samples, n)) {
        send_error(hal, APP_ERR_SENSOR);
        return -1;
    }
    uint64_t t0 = bw_hal_counter(hal);
    st = bw_encode_ctx(&ctx, &d, &p, samples, work, NULL, payload, sizeof payload, &len);
    uint64_t spent = bw_hal_counter(hal) - t0;
    if (st != BW_OK) {
        send_error(hal, st);
        return -1;
    }
    return deliver(hal, id, len, spent);
}

/* Answers a RESEND for the kept payload: the chunks it names, then END;
 * none named, the whole payload. */
static void resend(const bw_hal_t *hal)
{
    if (frame.len == 4) {
        send_payload(hal, kept.id, kept.len, kept.spent);
        return;
    }
    for (uint16_t i = 4; i + 1u < frame.len; i += 2) {
        uint16_t c = bw_get_u16(frame.data + i);
        if (c < chunks_of(kept.len))
            send_chunk(hal, kept.len, c);
    }
    uint8_t e[4];
    bw_put_u32(e, kept.id);
    send(hal, BW_FT_END, 0, e, 4);
}

/* Whether the frame is a RESEND or an ACK of the kept payload. */
static bool for_kept(uint8_t type)
{
    return kept.id && frame.type == type && frame.len >= 4 && bw_get_u32(frame.data) == kept.id &&
           (type != BW_FT_ACK || frame.len == 4);
}

/* Sends a payload and keeps it until the host acknowledges it, answering
 * RESEND, and sends it again after ACK_WAIT instructions of silence; 0
 * when acknowledged, 1 when the host said QUIT instead, -1 after MAX_SENDS
 * sends (the payload stays kept: bw_app_run still answers for it). */
static int deliver(const bw_hal_t *hal, uint32_t id, size_t len, uint64_t spent)
{
    kept.id = id;
    kept.len = len;
    kept.spent = spent;
    bw_hal_offer(hal, id, payload, len, 0);
    send_payload(hal, id, len, spent);
    for (unsigned sends = 1;;) {
        if (!receive(hal, ACK_WAIT)) {
            if (++sends > MAX_SENDS)
                return -1;
            send_payload(hal, kept.id, kept.len, kept.spent);
            continue;
        }
        if (for_kept(BW_FT_ACK)) {
            bw_hal_offer(hal, 0, NULL, 0, 0);
            kept.id = 0;
            return 0;
        }
        if (for_kept(BW_FT_RESEND))
            resend(hal);
        if (frame.type == BW_FT_QUIT)
            return 1;
    }
}

int bw_app_run(const bw_hal_t *hal)
{
    bw_frame_rx_init(&rx);
    rx_pos = rx_len = 0;
    uint32_t id = 0;
    for (;;) {
        receive(hal, 0);
        if (frame.type == BW_FT_QUIT)
            return 0;
        if (for_kept(BW_FT_RESEND) || for_kept(BW_FT_ACK)) {
            /* the host back for the payload it did not finish */
            if (frame.type == BW_FT_RESEND) {
                resend(hal);
            } else {
                bw_hal_offer(hal, 0, NULL, 0, 0);
                kept.id = 0;
            }
            continue;
        }
        if (frame.type == BW_FT_HELLO) {
            uint8_t d[BW_HELLO_SIZE];
            send(hal, BW_FT_HELLO, 0, d, (uint16_t)bw_hello_pack(&limits, d));
            continue;
        }
        if (frame.type == BW_FT_JOB_EXT) {
            if (frame.len > APP_EXT_MAX - job_ext_len)
                job_ext_over = true;
            else
                memcpy(job_ext + job_ext_len, frame.data, frame.len);
            job_ext_len += job_ext_over ? 0u : frame.len;
            continue;
        }
        if (frame.type != BW_FT_JOB)
            continue;
        bw_job_t job;
        bool ok = bw_job_unpack(frame.data, frame.len, &job);
        /* records from JOB_EXT frames come first, the JOB's own after them */
        if (ok && (job_ext_len || job_ext_over)) {
            ok = !job_ext_over && job.ext_len <= APP_EXT_MAX - job_ext_len;
            if (ok && job.ext_len)
                memcpy(job_ext + job_ext_len, job.ext, job.ext_len);
            job.ext = job_ext;
            job.ext_len += job_ext_len;
        }
        job_ext_len = 0;
        job_ext_over = false;
        if (!ok) {
            send_error(hal, BW_ERR_ARG);
            continue;
        }
        if (run_job(hal, &job, ++id) == 1)
            return 0;
    }
}
