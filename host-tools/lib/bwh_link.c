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

/* Asks for the chunks of a payload that have not arrived, as many as fit
 * in one frame (none missing, or all: the whole payload). */
static int ask_missing(int fd, const bwh_partial_t *c)
{
    uint8_t d[BW_FRAME_MAX_DATA];
    uint16_t n = 4;
    uint32_t missing = 0;
    bw_put_u32(d, c->id);
    for (uint32_t k = 0; k < c->parts; k++)
        if (!c->have[k]) {
            missing++;
            if (n + 2u <= sizeof d) {
                bw_put_u16(d + n, (uint16_t)k);
                n += 2;
            }
        }
    if (missing == c->parts)
        n = 4; /* everything: the short form */
    return bwh_send_frame(fd, BW_FT_RESEND, 0, d, n);
}

int bwh_receive_payload(bwh_link_t *l, const bwh_rx_opts_t *o, bwh_received_t *r)
{
    memset(r, 0, sizeof *r);
    bw_frame_t f;
    bwh_partial_t cur; /* the payload being received */
    memset(&cur, 0, sizeof cur);
    uint32_t bad0 = l->rx.bad_crc, dropped0 = l->rx.dropped, arrived = 0;
    int started = 0, dropped_once = 0;
    unsigned verify_failures = 0;
    /* silence after a start: ask again at this interval, within the timeout */
    double quiet = o->timeout_s / 8 < 0.2 ? 0.2 : o->timeout_s / 8 > 2.0 ? 2.0 : o->timeout_s / 8;
    double progress = bwh_now(), last = progress;
    if (o->resume) { /* what arrived before; the rest asked for at once */
        const bwh_partial_t *p = o->resume;
        if (p->unit != BW_FRAME_MAX_DATA)
            return bwh_fail("payload %u arrived in parts of %u bytes, not the link's %u", p->id,
                            p->unit, (unsigned)BW_FRAME_MAX_DATA);
        if (bwh_partial_init(&cur, p->id, p->crc, p->len, p->unit) != 0)
            return -1;
        memcpy(cur.payload, p->payload, p->len);
        memcpy(cur.have, p->have, p->parts);
        arrived = cur.parts - bwh_partial_missing(&cur);
        started = 1;
        r->resends++;
        if (ask_missing(l->fd, &cur) != 0)
            goto fail;
    }
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
                    bwh_fail("payload %u: nothing new from the device for %g s (%u of %u "
                             "chunks in); not acknowledged",
                             cur.id, o->timeout_s, arrived, cur.parts);
                if (started && o->keep_partial) {
                    r->partial = cur; /* the caller's now */
                    memset(&cur, 0, sizeof cur);
                }
                goto fail;
            }
            r->resends++;
            if (ask_missing(l->fd, &cur) != 0)
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
            if (f.len < 22)
                break;
            uint32_t nid = bw_get_u32(f.data), ncrc = bw_get_u32(f.data + 10);
            size_t nlen = bw_get_u32(f.data + 4);
            uint16_t nchunks = bw_get_u16(f.data + 8);
            if (started && nid == cur.id && nlen == cur.len && ncrc == cur.crc)
                break; /* a resend of the same payload: no progress */
            if (nlen == 0 || nlen > ((size_t)1 << 31) ||
                nchunks != (nlen + BW_FRAME_MAX_DATA - 1) / BW_FRAME_MAX_DATA) {
                bwh_fail("the device announced an inconsistent payload (%zu bytes, %u chunks)",
                         nlen, nchunks);
                goto fail;
            }
            if (o->resume) { /* only the payload asked for */
                bwh_fail("the device sends payload %u, not payload %u (which it no longer "
                         "holds, or holds under another id); nothing stored",
                         nid, o->resume->id);
                goto fail;
            }
            bwh_partial_free(&cur);
            if (bwh_partial_init(&cur, nid, ncrc, nlen, BW_FRAME_MAX_DATA) != 0)
                goto fail;
            r->instructions = bw_get_u32(f.data + 14) | (uint64_t)bw_get_u32(f.data + 18) << 32;
            arrived = 0;
            started = 1;
            progress = t;
            break;
        }
        case BW_FT_DATA: {
            if (!started || f.seq >= cur.parts || cur.have[f.seq])
                break;
            if (o->drop_chunk == (int)f.seq && !dropped_once) {
                dropped_once = 1; /* simulated loss */
                break;
            }
            size_t off = (size_t)f.seq * BW_FRAME_MAX_DATA;
            size_t want = cur.len - off < BW_FRAME_MAX_DATA ? cur.len - off : BW_FRAME_MAX_DATA;
            if (f.len != want)
                break;
            memcpy(cur.payload + off, f.data, want);
            cur.have[f.seq] = 1;
            progress = t;
            complete = ++arrived == cur.parts;
            break;
        }
        case BW_FT_END:
            if (!started || f.len < 4 || bw_get_u32(f.data) != cur.id)
                break;
            if (arrived < cur.parts) {
                r->resends++;
                if (ask_missing(l->fd, &cur) != 0)
                    goto fail;
            }
            break;
        default:
            break;
        }
        if (!complete)
            continue;
        uint8_t d[4];
        bw_put_u32(d, cur.id);
        if (bw_crc32(cur.payload, cur.len) != cur.crc) {
            /* every chunk arrived but the whole does not match: ask again */
            if (++verify_failures > 3) {
                bwh_fail("payload %u: CRC-32 mismatch after %u complete transfers; not "
                         "acknowledged", cur.id, verify_failures);
                goto fail;
            }
            memset(cur.have, 0, cur.parts);
            arrived = 0;
            r->resends++;
            if (bwh_send_frame(l->fd, BW_FT_RESEND, 0, d, 4) != 0)
                goto fail;
            continue;
        }
        /* the transfer is intact; a payload that does not decode would not
         * come out better by sending it again */
        bw_header_t h;
        if (bwh_payload_check(cur.payload, cur.len, o->max_samples, &h) != 0) {
            char why[400];
            snprintf(why, sizeof why, "%s", bwh_last_error());
            bwh_fail("payload %u does not decode: %s; not acknowledged", cur.id, why);
            goto fail;
        }
        free(cur.have);
        r->id = cur.id;
        r->payload = cur.payload;
        r->len = cur.len;
        r->bad_frames = (l->rx.bad_crc - bad0) + (l->rx.dropped != dropped0 ? 1u : 0u);
        return 0;
    }
fail:
    bwh_partial_free(&cur);
    return -1;
}
