/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Frames of the host link (UART or I2C), shared by the device and the host.
 * Freestanding, no heap. See docs/LINK.md.
 *
 *   offset  size  field
 *   0       2     sync 0xB5 0x57
 *   2       1     type (bw_frame_type_t)
 *   3       1     flags (0)
 *   4       2     seq, little-endian
 *   6       2     len of data, little-endian, <= BW_FRAME_MAX_DATA
 *   8       len   data
 *   8+len   4     CRC-32 of bytes 2 .. 8+len-1 (type to the end of data)
 *
 * A receiver that loses sync, or sees a bad CRC, drops bytes up to the next
 * sync pair and tries again, so a corrupted or truncated frame costs only
 * itself.
 */
#ifndef BW_FRAME_H
#define BW_FRAME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"
#include "bw_le.h"

#define BW_FRAME_SYNC0 0xB5u
#define BW_FRAME_SYNC1 0x57u
#define BW_FRAME_HEADER 8u
#define BW_FRAME_MAX_DATA 1024u
#define BW_FRAME_OVERHEAD (BW_FRAME_HEADER + 4u)
#define BW_FRAME_MAX (BW_FRAME_OVERHEAD + BW_FRAME_MAX_DATA)

typedef enum {
    BW_FT_HELLO = 0x01,   /* host -> device: who are you (no data); device ->
                           * host: link version u8, then its limits
                           * (bw_limits_t)                                    */
    BW_FT_JOB = 0x02,     /* host -> device: encode request (bw_job_t)         */
    BW_FT_QUIT = 0x03,    /* host -> device: stop                              */
    BW_FT_JOB_EXT = 0x04, /* host -> device: extension records for the next JOB,
                           * more than its frame holds (appended in order)   */
    BW_FT_START = 0x10,   /* device -> host: payload id u32, length u32,
                           * chunks u16, CRC-32 of the payload u32, then
                           * instructions spent encoding u64                   */
    BW_FT_DATA = 0x11,    /* device -> host: chunk `seq` of the payload        */
    BW_FT_END = 0x12,     /* device -> host: payload id u32                    */
    BW_FT_ACK = 0x20,     /* host -> device: payload id u32, verified          */
    BW_FT_RESEND = 0x21,  /* host -> device: payload id u32, then chunk
                           * numbers u16 (none: everything)                   */
    BW_FT_ERROR = 0x30    /* device -> host: status i32 (bw_status_t), then
                           * the device's limits (bw_limits_t)               */
} bw_frame_type_t;

typedef struct {
    uint8_t type;
    uint8_t flags;
    uint16_t seq;
    uint16_t len;
    uint8_t data[BW_FRAME_MAX_DATA];
} bw_frame_t;

/* Writes a frame into out (BW_FRAME_OVERHEAD + len bytes); returns its size,
 * 0 if len is too large. */
size_t bw_frame_pack(uint8_t *out, uint8_t type, uint16_t seq, const uint8_t *data, uint16_t len);

/* Byte-at-a-time receiver with resynchronisation. */
typedef struct {
    uint8_t buf[BW_FRAME_MAX];
    size_t have;
    uint32_t dropped; /* bytes skipped while hunting for a frame */
    uint32_t bad_crc; /* frames rejected by their CRC            */
} bw_frame_rx_t;

void bw_frame_rx_init(bw_frame_rx_t *rx);

/* Takes bytes from in[len] until a frame is complete and returns how many
 * it took; *got says whether *out now holds a complete, valid frame. The
 * receiver keeps its state between calls, and after a frame the caller
 * keeps in[used..len): call again with the rest (or with len 0, which
 * only looks at the bytes already buffered) until a call takes no bytes
 * and gives no frame. After a resynchronisation the buffer can hold
 * more than one frame, which is why a call may return a frame and take
 * nothing. */
size_t bw_frame_rx_feed(bw_frame_rx_t *rx, const uint8_t *in, size_t len, bw_frame_t *out,
                        bool *got);

/* Feeds one byte; returns true when a complete, valid frame is in *out. */
bool bw_frame_rx_byte(bw_frame_rx_t *rx, uint8_t byte, bw_frame_t *out);

/* The encode request of a BW_FT_JOB frame. */
typedef struct {
    uint8_t shape, level_out, level_in, mode, basis, flags, effort, coder;
    uint32_t n_in, bands, max_error, byte_budget, scale_bits, offset_bits;
    char source[128]; /* the sensor's input (QEMU: a file by semihosting) */
    /* the payload's extension records (bw_params_t.ext: the host's
     * metadata), sent after the fixed part of the frame: they point into
     * the frame's data and hold while it does. NULL and 0: none. */
    const uint8_t *ext;
    uint32_t ext_len;
} bw_job_t;

#define BW_JOB_SIZE 160u /* the fixed part; a JOB frame is this plus ext_len */
#define BW_JOB_EXT_MAX (BW_FRAME_MAX_DATA - BW_JOB_SIZE)

/* What a device can take, sent after the status in an ERROR frame so that
 * the host can say what to do instead: jobs held whole in memory have at
 * most max_samples samples and max_bands bands; streamed jobs (stream order,
 * a fixed basis, LOSSLESS, MAX_ERROR or STEP, not BRDF_FULL) have any number
 * of directions at levels up to stream_level with up to stream_bands bands;
 * no payload is longer than payload_cap bytes. 0: not said. */
typedef struct {
    uint32_t max_samples, max_bands, stream_bands, payload_cap;
    uint8_t stream_level;
} bw_limits_t;

#define BW_ERROR_SIZE 21u /* status, then the limits */
size_t bw_error_pack(int32_t status, const bw_limits_t *lim, uint8_t *out); /* BW_ERROR_SIZE */
/* The status of an ERROR frame's data and, where the device sent them, its
 * limits (else zeros); false if the data is too short for a status. */
bool bw_error_unpack(const uint8_t *in, size_t len, int32_t *status, bw_limits_t *lim);

/* The device's answer to HELLO: the link version and its limits. */
#define BW_LINK_VERSION 1u
#define BW_HELLO_SIZE 18u
size_t bw_hello_pack(const bw_limits_t *lim, uint8_t *out); /* BW_HELLO_SIZE */
bool bw_hello_unpack(const uint8_t *in, size_t len, uint8_t *version, bw_limits_t *lim);

/* Whether a device with these limits takes the job: BW_OK (and *streamed
 * when it encodes it spectrum by spectrum) or BW_ERR_WORK; BW_ERR_ARG for
 * embedded segments in stream order. The device application and the host
 * both decide with this one rule. */
bw_status_t bw_limits_admit(const bw_limits_t *lim, const bw_dims_t *d, const bw_params_t *p,
                            bool *streamed);
/* BW_JOB_SIZE + job->ext_len bytes (at most BW_FRAME_MAX_DATA); the
 * records beyond BW_JOB_EXT_MAX are not packed: check ext_len first */
size_t bw_job_pack(const bw_job_t *job, uint8_t *out);
bool bw_job_unpack(const uint8_t *in, size_t len, bw_job_t *job);

/* The job of encoding samples of these dimensions with these parameters
 * (the host's side; source empty), and the parameters of a job (the
 * device's side). Segments (bw_params_t.segment_vectors) travel as the
 * job's first extension record, BW_EXT_SEGMENTS: the host puts it in
 * front of p->ext (bw_job_make does not), bw_job_params takes it out. */
void bw_job_make(bw_job_t *job, const bw_dims_t *dims, const bw_params_t *p);
void bw_job_params(const bw_job_t *job, bw_params_t *p);

#endif
