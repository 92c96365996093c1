/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Encoding on a device (`brdfwave encode --device`): "qemu" starts the
 * emulated co-processor (QEMU mps2-an386) with its firmware image and talks
 * to it over its UART (a pseudo-terminal); "linux" runs the same device
 * application as a host process on a socket pair. The samples become the
 * device's sensor input, the job goes over the link, and the payload comes
 * back through bwh_receive_payload.
 */
#ifndef BWH_DEVICE_H
#define BWH_DEVICE_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "bw_codec.h"
#include "bwh_link.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An encode on a device (bwh_encode_opts_t.device): where, and what the
 * command line wants to know of it. */
struct bwh_device_job {
    const char *device;     /* "qemu" (the emulated co-processor) or "linux"
                             * (its application as a host process) */
    const char *firmware;   /* NULL: bwh_device_firmware's search */
    double timeout;         /* seconds, 0: 120 */
    int drop_chunk;         /* tests: lose the first copy of a chunk, -1: none */
    uint64_t *instructions; /* out (may be NULL): the device's count for the encode */
};

/* The directory of the program that uses the library (the command line
 * passes its own): device images are looked for beside it. NULL: none. The
 * string is copied. */
void bwh_device_set_program_dir(const char *dir);

/* The device image for `device`, allocated (free() it), NULL when out of
 * memory. The first of:
 *   explicit        when not NULL;
 *   $BW_FIRMWARE    (qemu) or $BW_FIRMWARE_LINUX (linux), when set;
 *   beside the program (bwh_device_set_program_dir) and then beside the
 *                   library itself (found with dladdr, so a Python process
 *                   that loaded libbrdfwave.so finds the images of its
 *                   build): DIR/brdfwave-fw-linux (linux) or
 *                   DIR/../qemu/brdfwave-fw.elf (qemu), the first that
 *                   exists; if none does, the first of these paths. */
char *bwh_device_firmware(const char *device, const char *explicit_path);

/* A session with a device: started by bwh_device_open, which also asks the
 * device for its limits (HELLO); ended by bwh_device_close (QUIT, and the
 * device stopped if it does not exit within 3 s). */
typedef struct {
    pid_t pid;
    int fd, pipefd;
    bwh_link_t link;
    int have_limits;
    bw_limits_t limits;
} bwh_device_t;

int bwh_device_open(bwh_device_t *dv, const char *device, const char *firmware);
/* 0 when the device takes the job (or did not say what it takes); -1 with a
 * message that says what it holds and what to do instead. */
int bwh_device_admit(const bwh_device_t *dv, const bw_dims_t *dims, const bw_params_t *p);
int bwh_device_run(bwh_device_t *dv, const bw_dims_t *dims, const bw_params_t *p,
                   const int32_t *samples, const bwh_rx_opts_t *o, bwh_received_t *r);
void bwh_device_close(bwh_device_t *dv);

/* Encodes dims/p/samples on `device` ("qemu" or "linux") with the image
 * `firmware` (NULL: bwh_device_firmware's choice). The session ends (QUIT)
 * as soon as the payload is in or the device reports an error; a device
 * error becomes a message that says what the device holds and what to do
 * instead. 0, or -1 (bwh_last_error()). */
int bwh_device_encode(const char *device, const char *firmware, const bw_dims_t *dims,
                      const bw_params_t *p, const int32_t *samples, const bwh_rx_opts_t *o,
                      bwh_received_t *r);

#ifdef __cplusplus
}
#endif

#endif
