/* SPDX-License-Identifier: BSD-2-Clause */
/* The host end of the device link (bwh_link.h). */
#define _GNU_SOURCE
#include "bwh_link.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "bw_crc32.h"
#include "bwh_decode.h"
#include "bwh_error.h"

int bwh_port_open(const char *path)
{
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return bwh_fail("%s: %s", path, strerror(errno));
    struct termios t;
    if (tcgetattr(fd, &t) == 0) {
        cfmakeraw(&t);
        cfsetispeed(&t, B115200);
        cfsetospeed(&t, B115200);
        t.c_cflag |= CLOCAL | CREAD;
        t.c_cc[VMIN] = 0;
        t.c_cc[VTIME] = 0;
        if (tcsetattr(fd, TCSANOW, &t) != 0) {
            close(fd);
            return bwh_fail("%s: cannot configure: %s", path, strerror(errno));
        }
    } /* not a terminal (a pipe or file in tests): use it as it is */
    return fd;
}

static int write_all(int fd, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && (errno == EAGAIN || errno == EINTR)) {
            struct pollfd pf = {fd, POLLOUT, 0};
            poll(&pf, 1, 100);
            continue;
        }
        if (w <= 0)
            return bwh_fail("link write: %s", strerror(errno));
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

int bwh_send_frame(int fd, uint8_t type, uint16_t seq, const uint8_t *data, uint16_t len)
{
    uint8_t buf[BW_FRAME_MAX];
    size_t n = bw_frame_pack(buf, type, seq, data, len);
    if (!n)
        return bwh_fail("frame too large");
    return write_all(fd, buf, n);
}

double bwh_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

void bwh_link_init(bwh_link_t *l, int fd)
{
    l->fd = fd;
    l->is_tty = isatty(fd);
    bw_frame_rx_init(&l->rx);
    l->pos = l->len = 0;
}

int bwh_link_next(bwh_link_t *l, bw_frame_t *f, double deadline)
{
    for (;;) {
        bool got;
        l->pos += bw_frame_rx_feed(&l->rx, l->in + l->pos, l->len - l->pos, f, &got);
        if (got)
            return 1;
        ssize_t r = read(l->fd, l->in, sizeof l->in);
        l->pos = 0;
        l->len = r > 0 ? (size_t)r : 0u;
        if (r > 0)
            continue;
        /* a raw terminal with VMIN = 0 reads 0 when it has nothing yet */
        if (r == 0 && !l->is_tty)
            return bwh_fail("link closed"), -1;
        if (r < 0 && errno != EAGAIN && errno != EINTR) {
            if (errno == EIO) /* pty without a peer any more */
                return bwh_fail("link closed (device gone)"), -1;
            return bwh_fail("link read: %s", strerror(errno)), -1;
        }
        double left = deadline - bwh_now();
        if (left <= 0)
            return 0;
        struct pollfd pf = {l->fd, POLLIN, 0};
        int ms = left > 0.2 ? 200 : (int)(left * 1000) + 1;
        if (poll(&pf, 1, ms) < 0 && errno != EINTR)
            return bwh_fail("poll: %s", strerror(errno)), -1;
    }
}

int bwh_acknowledge(bwh_link_t *l, uint32_t id)
{
    uint8_t d[4];
    bw_put_u32(d, id);
    return bwh_send_frame(l->fd, BW_FT_ACK, 0, d, 4);
}

/* Asks for the chunks of payload id that have not arrived, as many as fit
 * in one frame (none missing, or all: the whole payload). */
static int ask_missing(int fd, uint32_t id, const uint8_t *have, uint16_t chunks)
{
    uint8_t d[BW_FRAME_MAX_DATA];
    uint16_t n = 4, missing = 0;
    bw_put_u32(d, id);
    for (uint16_t c = 0; c < chunks; c++)
        if (!have[c]) {
            missing++;
            if (n + 2u <= sizeof d) {
                bw_put_u16(d + n, c);
                n += 2;
            }
        }
    if (missing == chunks)
        n = 4; /* everything: the short form */
    return bwh_send_frame(fd, BW_FT_RESEND, 0, d, n);
}

int bwh_receive_payload(bwh_link_t *l, const bwh_rx_opts_t *o, bwh_received_t *r)
{
    memset(r, 0, sizeof *r);
    bw_frame_t f;
    uint8_t *buf = NULL, *have = NULL;
    uint32_t id = 0, crc = 0, bad0 = l->rx.bad_crc, dropped0 = l->rx.dropped;
    size_t len = 0, arrived = 0;
    uint16_t chunks = 0;
    int started = 0, dropped_once = 0;
    unsigned verify_failures = 0;
    /* silence after a start: ask again at this interval, within the timeout */
    double quiet = o->timeout_s / 8 < 0.2 ? 0.2 : o->timeout_s / 8 > 2.0 ? 2.0 : o->timeout_s / 8;
    double progress = bwh_now(), last = progress;
    for (;;) {
        double deadline = progress + o->timeout_s;
        double wake = started && last + quiet < deadline ? last + quiet : deadline;
        int k = bwh_link_next(l, &f, wake);
        if (k < 0)
            goto fail;
        double t = bwh_now();
        if (k == 0) {
            if (t >= deadline) {
                if (!started)
                    bwh_fail("no payload from the device within %g s", o->timeout_s);
                else
                    bwh_fail("payload %u: nothing new from the device for %g s (%zu of %u "
                             "chunks in); not acknowledged",
                             id, o->timeout_s, arrived, chunks);
                goto fail;
            }
            r->resends++;
            if (ask_missing(l->fd, id, have, chunks) != 0)
                goto fail;
            last = t;
            continue;
        }
        last = t;
        int complete = 0;
        switch (f.type) {
        case BW_FT_ERROR: {
            int32_t st = 0;
            bw_error_unpack(f.data, f.len, &st, &r->limits);
            r->device_error = 1;
            r->device_status = st;
            bwh_fail("the device reports: %s",
                     st == -100 ? "sensor input unavailable" : bw_strerror(st));
            goto fail;
        }
        case BW_FT_START: {
            if (f.len < 22 || (started && bw_get_u32(f.data) == id))
                break; /* short, or a resend of the same payload: no progress */
            uint32_t nid = bw_get_u32(f.data);
            size_t nlen = bw_get_u32(f.data + 4);
            uint16_t nchunks = bw_get_u16(f.data + 8);
            if (nlen == 0 || nlen > ((size_t)1 << 31) ||
                nchunks != (nlen + BW_FRAME_MAX_DATA - 1) / BW_FRAME_MAX_DATA) {
                bwh_fail("the device announced an inconsistent payload (%zu bytes, %u chunks)",
                         nlen, nchunks);
                goto fail;
            }
            free(buf);
            free(have);
            id = nid;
            len = nlen;
            chunks = nchunks;
            crc = bw_get_u32(f.data + 10);
            r->instructions = bw_get_u32(f.data + 14) | (uint64_t)bw_get_u32(f.data + 18) << 32;
            buf = malloc(len);
            have = calloc(chunks, 1);
            arrived = 0;
            if (!buf || !have) {
                bwh_fail("out of memory");
                goto fail;
            }
            started = 1;
            progress = t;
            break;
        }
        case BW_FT_DATA: {
            if (!started || f.seq >= chunks || have[f.seq])
                break;
            if (o->drop_chunk == (int)f.seq && !dropped_once) {
                dropped_once = 1; /* simulated loss */
                break;
            }
            size_t off = (size_t)f.seq * BW_FRAME_MAX_DATA;
            size_t want = len - off < BW_FRAME_MAX_DATA ? len - off : BW_FRAME_MAX_DATA;
            if (f.len != want)
                break;
            memcpy(buf + off, f.data, want);
            have[f.seq] = 1;
            progress = t;
            complete = ++arrived == chunks;
            break;
        }
        case BW_FT_END:
            if (!started || f.len < 4 || bw_get_u32(f.data) != id)
                break;
            if (arrived < chunks) {
                r->resends++;
                if (ask_missing(l->fd, id, have, chunks) != 0)
                    goto fail;
            }
            break;
        default:
            break;
        }
        if (!complete)
            continue;
        uint8_t d[4];
        bw_put_u32(d, id);
        if (bw_crc32(buf, len) != crc) {
            /* every chunk arrived but the whole does not match: ask again */
            if (++verify_failures > 3) {
                bwh_fail("payload %u: CRC-32 mismatch after %u complete transfers; not "
                         "acknowledged", id, verify_failures);
                goto fail;
            }
            memset(have, 0, chunks);
            arrived = 0;
            r->resends++;
            if (bwh_send_frame(l->fd, BW_FT_RESEND, 0, d, 4) != 0)
                goto fail;
            continue;
        }
        /* the transfer is intact; a payload that does not decode would not
         * come out better by sending it again */
        bw_header_t h;
        if (bwh_payload_check(buf, len, o->max_samples, &h) != 0) {
            char why[400];
            snprintf(why, sizeof why, "%s", bwh_last_error());
            bwh_fail("payload %u does not decode: %s; not acknowledged", id, why);
            goto fail;
        }
        free(have);
        r->id = id;
        r->payload = buf;
        r->len = len;
        r->bad_frames = (l->rx.bad_crc - bad0) + (l->rx.dropped != dropped0 ? 1u : 0u);
        return 0;
    }
fail:
    free(buf);
    free(have);
    return -1;
}
