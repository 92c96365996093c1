#define _GNU_SOURCE
#include "link.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "bw_crc32.h"
#include "bw_frame.h"
#include "bwhost.h"

int bwh_fail(const char *fmt, ...);

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

/* ---- the emulated co-processor ------------------------------------------- */

static char *default_firmware(int linux_process)
{
    const char *env = getenv("BW_FIRMWARE");
    if (env && *env && !linux_process)
        return strdup(env);
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 64);
    if (n <= 0)
        return strdup("build/qemu/brdfwave-fw.elf");
    exe[n] = 0;
    char *slash = strrchr(exe, '/');
    if (slash)
        *slash = 0;
    char *path = malloc(strlen(exe) + 64);
    if (path)
        sprintf(path, linux_process ? "%s/brdfwave-fw-linux" : "%s/../qemu/brdfwave-fw.elf", exe);
    return path;
}

/* Reads QEMU's output until it names the pseudo-terminal of the link. */
static int find_pty(int out_fd, char *pty, size_t cap, double timeout_s)
{
    char acc[4096];
    size_t have = 0;
    double end = bwh_now() + timeout_s;
    while (bwh_now() < end) {
        struct pollfd pf = {out_fd, POLLIN, 0};
        if (poll(&pf, 1, 100) <= 0)
            continue;
        ssize_t r = read(out_fd, acc + have, sizeof acc - 1 - have);
        if (r <= 0)
            return bwh_fail("the emulator exited before opening the link: %.*s", (int)have, acc);
        have += (size_t)r;
        acc[have] = 0;
        char *p = strstr(acc, "redirected to ");
        if (p) {
            p += strlen("redirected to ");
            char *e = p;
            while (*e && *e != ' ' && *e != '\n' && *e != '(')
                e++;
            if (*e) {
                size_t l = (size_t)(e - p);
                if (l + 1 > cap)
                    return bwh_fail("pty path too long");
                memcpy(pty, p, l);
                pty[l] = 0;
                return 0;
            }
        }
        if (have == sizeof acc - 1)
            have = 0;
    }
    return bwh_fail("the emulator did not open its link within %.0f s", timeout_s);
}

/* Replaces the last error of a device-side failure by one that says what
 * the device can take and what to do instead. */
static void explain_device_error(const bw_dims_t *d, int32_t st, const bw_limits_t *lim)
{
    size_t n = bw_dims_samples(d);
    if (st == BW_ERR_WORK && lim->max_samples) {
        char advice[300];
        if (d->shape == BW_SHAPE_BRDF_FULL)
            snprintf(advice, sizeof advice,
                     "a full BRDF (--level-in) is not streamed: encode it on the host, or as "
                     "blocks of incoming directions (--incoming)");
        else if (d->bands <= lim->stream_bands && d->level_out <= lim->stream_level)
            snprintf(advice, sizeof advice,
                     "encode it with --stream (a fixed --basis, --lossless or --max-error): the "
                     "device then holds one spectrum at a time");
        else
            snprintf(advice, sizeof advice,
                     "streamed jobs take up to %u bands at levels up to %u: encode it on the "
                     "host or split it", lim->stream_bands, lim->stream_level);
        bwh_fail("the device cannot hold this job: %zu samples of %u bands, it holds at most %u "
                 "samples of up to %u bands; %s",
                 n, d->bands, lim->max_samples, lim->max_bands, advice);
    } else if (st == BW_ERR_OUTPUT_FULL && lim->payload_cap) {
        bwh_fail("the device reports: the payload would exceed its %u-byte buffer; use a byte "
                 "budget (--bytes, --ratio), a larger --max-error, or a smaller job",
                 lim->payload_cap);
    } else if (st == -100) {
        bwh_fail("the device reports: its sensor could not deliver the %zu samples", n);
    } else {
        bwh_fail("the device reports: %s", bw_strerror(st));
    }
}

/* Starts the application as a host process on one end of a socket pair. */
static pid_t start_linux(const char *fw, int *fd)
{
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
        return bwh_fail("socketpair: %s", strerror(errno)), -1;
    pid_t pid = fork();
    if (pid < 0) {
        close(sv[0]);
        close(sv[1]);
        return bwh_fail("fork: %s", strerror(errno)), -1;
    }
    if (pid == 0) {
        dup2(sv[1], 0);
        dup2(sv[1], 1);
        execl(fw, fw, (char *)NULL);
        fprintf(stderr, "cannot run %s: %s\n", fw, strerror(errno));
        _exit(127);
    }
    close(sv[1]);
    fcntl(sv[0], F_SETFL, fcntl(sv[0], F_GETFL) | O_NONBLOCK);
    *fd = sv[0];
    return pid;
}

int bwh_device_encode(const char *device, const char *firmware, const bw_dims_t *dims,
                      const bw_params_t *p, const int32_t *samples, const bwh_rx_opts_t *o,
                      bwh_received_t *r)
{
    memset(r, 0, sizeof *r);
    int rc = -1, fd = -1, pipefd[2] = {-1, -1};
    pid_t pid = -1;
    int linux_process = !strcmp(device, "linux");
    char *fw = firmware ? strdup(firmware) : default_firmware(linux_process);
    char input[] = "/tmp/brdfwave-sensor-XXXXXX";
    int in_fd = mkstemp(input);
    if (!fw || in_fd < 0) {
        bwh_fail("cannot prepare the device input: %s", strerror(errno));
        goto out;
    }
    struct stat sb;
    if (stat(fw, &sb) != 0) {
        bwh_fail("firmware image %s: %s (build it with '%s')", fw, strerror(errno),
                 linux_process ? "make" : "make TARGET=qemu");
        goto out;
    }
    size_t n = bw_dims_samples(dims);
    uint8_t *raw = malloc(n * 4 + 1);
    if (!raw) {
        bwh_fail("out of memory");
        goto out;
    }
    for (size_t i = 0; i < n; i++)
        bw_put_u32(raw + 4 * i, (uint32_t)samples[i]);
    ssize_t w = write(in_fd, raw, n * 4);
    free(raw);
    if (w != (ssize_t)(n * 4)) {
        bwh_fail("cannot write the device input: %s", strerror(errno));
        goto out;
    }
    close(in_fd);
    in_fd = -1;

    if (linux_process) {
        pid = start_linux(fw, &fd);
        if (pid < 0)
            goto out;
        goto connected;
    }
    if (pipe2(pipefd, O_CLOEXEC) != 0) {
        bwh_fail("pipe: %s", strerror(errno));
        goto out;
    }
    pid = fork();
    if (pid < 0) {
        bwh_fail("fork: %s", strerror(errno));
        goto out;
    }
    if (pid == 0) {
        dup2(pipefd[1], 1);
        dup2(pipefd[1], 2);
        execlp("qemu-system-arm", "qemu-system-arm", "-M", "mps2-an386", "-display", "none",
               "-monitor", "none", "-icount", "shift=0", "-semihosting-config",
               "enable=on,target=native", "-chardev", "pty,id=link", "-serial", "chardev:link",
               "-kernel", fw, (char *)NULL);
        fprintf(stderr, "cannot run qemu-system-arm: %s\n", strerror(errno));
        _exit(127);
    }
    close(pipefd[1]);
    pipefd[1] = -1;
    char pty[256];
    if (find_pty(pipefd[0], pty, sizeof pty, 30) != 0)
        goto out;
    fd = bwh_port_open(pty);
    if (fd < 0)
        goto out;
connected:;

    bw_job_t job;
    memset(&job, 0, sizeof job);
    job.shape = dims->shape;
    job.level_out = dims->level_out;
    job.level_in = dims->level_in;
    job.n_in = dims->n_in;
    job.bands = dims->bands;
    job.mode = p->mode;
    job.basis = p->basis;
    job.flags = p->flags;
    job.max_error = p->max_error;
    job.byte_budget = p->byte_budget;
    job.scale_bits = p->scale_bits;
    job.offset_bits = p->offset_bits;
    if (strlen(input) >= sizeof job.source) {
        bwh_fail("input path too long");
        goto out;
    }
    strcpy(job.source, input);
    uint8_t jb[BW_JOB_SIZE];
    bw_job_pack(&job, jb);
    if (bwh_send_frame(fd, BW_FT_JOB, 0, jb, BW_JOB_SIZE) != 0)
        goto out;
    bwh_link_t link;
    bwh_link_init(&link, fd);
    if (bwh_receive_payload(&link, o, r) != 0) {
        if (r->device_error)
            explain_device_error(dims, r->device_status, &r->limits);
        goto out;
    }
    if (bwh_acknowledge(&link, r->id) != 0) {
        free(r->payload);
        r->payload = NULL;
        goto out;
    }
    rc = 0;
out:
    if (pid > 0) {
        /* the session ends now, whatever happened: the device exits on QUIT;
         * one that does not within a few seconds is stopped */
        if (fd >= 0)
            bwh_send_frame(fd, BW_FT_QUIT, 0, NULL, 0);
        int status;
        double end = bwh_now() + 3;
        while (waitpid(pid, &status, WNOHANG) == 0) {
            if (bwh_now() > end) {
                kill(pid, SIGKILL);
                waitpid(pid, &status, 0);
                break;
            }
            usleep(2000);
        }
    }
    if (fd >= 0)
        close(fd);
    if (pipefd[0] >= 0)
        close(pipefd[0]);
    if (pipefd[1] >= 0)
        close(pipefd[1]);
    if (in_fd >= 0)
        close(in_fd);
    unlink(input);
    free(fw);
    return rc;
}
