/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Linux backend: the device application as a host process, for tests.
 * The host link is the process's standard input and output (the host runs
 * it on one end of a socket pair), the sensor is a file of little-endian
 * int32 samples, and the counter is CLOCK_MONOTONIC in nanoseconds.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "bw_hal.h"
#include "file_sensor.h"

static uint64_t counter(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static int link_write(const uint8_t *buf, size_t len)
{
    size_t done = 0;
    while (done < len) {
        ssize_t w = write(1, buf + done, len - done);
        if (w < 0 && (errno == EINTR || errno == EAGAIN)) {
            struct pollfd pf = {1, POLLOUT, 0};
            poll(&pf, 1, 10);
            continue;
        }
        if (w <= 0)
            return -BW_HAL_EIO;
        done += (size_t)w;
    }
    return (int)len;
}

/* Waits up to a millisecond for bytes, so that the application's polling
 * loop does not spin a core. */
static int link_read(uint8_t *buf, size_t cap)
{
    struct pollfd pf = {0, POLLIN, 0};
    if (poll(&pf, 1, 1) <= 0)
        return 0;
    ssize_t r = read(0, buf, cap);
    if (r == 0) /* the host went away: nothing will come any more */
        exit(3);
    return r < 0 ? 0 : (int)r;
}

static void fault(uint32_t code)
{
    fprintf(stderr, "brdfwave-fw: fault %lu\n", (unsigned long)code);
    exit(128);
}

static const bw_hal_t board = {
    .counter = counter,
    .link_write = link_write,
    .link_read = link_read,
    .sensor_open = bw_file_sensor_open,
    .sensor_read = bw_file_sensor_read,
    .fault = fault,
};

const bw_hal_t *bw_board(void) { return &board; }
