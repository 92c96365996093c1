/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The host end of the device link (docs/LINK.md): serial ports, frames, and
 * payload reception with resend requests and the receiver's checks.
 */
#ifndef BWH_LINK_H
#define BWH_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"
#include "bw_frame.h"
#include "bwh_store.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Opens a serial device (or pty) raw, 8N1, non-blocking reads. -1 on error. */
int bwh_port_open(const char *path);

/* One end of a link: the frame receiver and the bytes read from fd that it
 * has not taken yet, kept from one frame (and one payload) to the next. */
typedef struct {
    int fd;
    int is_tty;
    bw_frame_rx_t rx;
    uint8_t in[4096];
    size_t pos, len;
} bwh_link_t;

void bwh_link_init(bwh_link_t *l, int fd);

/* Waits for the next valid frame until the CLOCK_MONOTONIC time `deadline`
 * (seconds, bwh_now()); 1 = frame, 0 = deadline passed, -1 = error or the
 * link closed (bwh_last_error() set). */
int bwh_link_next(bwh_link_t *l, bw_frame_t *f, double deadline);

/* Seconds on CLOCK_MONOTONIC. */
double bwh_now(void);

typedef struct {
    double timeout_s;   /* give up after this long without progress: a new
                         * payload announced, a chunk not had before, or a
                         * payload completed; frames that bring none of these
                         * do not extend it */
    int drop_chunk;     /* >= 0: ignore the first copy of this chunk (tests resend) */
    int verbose;
    size_t max_samples; /* refuse payloads that decode to more samples (0: the default) */
    int keep_partial;   /* on giving up after a START: what arrived into r->partial */
    const bwh_partial_t *resume; /* may be NULL: a payload that arrived in part
                                  * before, whose missing chunks are asked for
                                  * first (its id, length and CRC must match
                                  * a START the device sends again) */
} bwh_rx_opts_t;

typedef struct {
    uint32_t id;
    uint8_t *payload; /* allocated */
    size_t len;
    uint64_t instructions; /* the device's count for the encode */
    unsigned resends;      /* resend requests made */
    uint32_t bad_frames;   /* frames dropped for CRC or sync */
    /* a device-side error (an ERROR frame): its status and limits */
    int device_error;
    int32_t device_status;
    bw_limits_t limits;
    /* with keep_partial: the payload given up on, its chunks that arrived
     * (partial.payload non-NULL; bwh_partial_free) */
    bwh_partial_t partial;
} bwh_received_t;

/* Receives one payload over l: checks every frame, asks for missing or
 * corrupted chunks, checks the payload's CRC and header and decodes it
 * (bwh_payload_check). 0 on success; -1 with bwh_last_error() set (and
 * r->device_error when the device sent ERROR). The device keeps the payload
 * until the caller, once it has stored it, calls bwh_acknowledge. */
int bwh_receive_payload(bwh_link_t *l, const bwh_rx_opts_t *o, bwh_received_t *r);
int bwh_acknowledge(bwh_link_t *l, uint32_t id);

/* Sends one frame. */
int bwh_send_frame(int fd, uint8_t type, uint16_t seq, const uint8_t *data, uint16_t len);

#ifdef __cplusplus
}
#endif

#endif
