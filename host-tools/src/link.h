/*
 * The host side of the device link: serial ports, payload reception with
 * resend requests, and the emulated co-processor (QEMU mps2-an386).
 */
#ifndef BW_LINK_H
#define BW_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "bw_codec.h"

/* Opens a serial device (or pty) raw, 8N1, non-blocking reads. -1 on error. */
int bwh_port_open(const char *path);

typedef struct {
    double timeout_s;   /* give up after this long without a frame */
    int drop_chunk;     /* >= 0: ignore the first copy of this chunk (tests resend) */
    int verbose;
} bwh_rx_opts_t;

typedef struct {
    uint32_t id;
    uint8_t *payload; /* allocated */
    size_t len;
    uint64_t instructions; /* the device's count for the encode */
    unsigned resends;      /* resend requests made */
    uint32_t bad_frames;   /* frames dropped for CRC or sync */
} bwh_received_t;

/* Receives one payload from fd: checks every frame, asks for missing or
 * corrupted chunks, checks the payload's CRC and header, then acknowledges
 * it. 0 on success; -1 with bwh_last_error() set. */
int bwh_receive_payload(int fd, const bwh_rx_opts_t *o, bwh_received_t *r);

/* Sends one frame. */
int bwh_send_frame(int fd, uint8_t type, uint16_t seq, const uint8_t *data, uint16_t len);

/* Encodes on a device: "qemu" starts the emulated co-processor with the
 * firmware image (firmware = NULL: ../qemu/brdfwave-fw.elf beside this
 * program, or $BW_FIRMWARE) and talks to it over its UART (a
 * pseudo-terminal); "linux" runs the same application as a host process
 * (brdfwave-fw-linux beside this program) on a socket pair. The samples
 * become the device's sensor input, the job goes over the link, and the
 * payload comes back through bwh_receive_payload. */
int bwh_device_encode(const char *device, const char *firmware, const bw_dims_t *dims,
                      const bw_params_t *p, const int32_t *samples, const bwh_rx_opts_t *o,
                      bwh_received_t *r);

#endif
