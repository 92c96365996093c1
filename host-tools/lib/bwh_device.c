/* SPDX-License-Identifier: BSD-2-Clause */
/* Encoding on a device: the emulated co-processor or its application as a
 * host process (bwh_device.h). */
#define _GNU_SOURCE
#include "bwh_device.h"

#include <dlfcn.h>
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
#include <unistd.h>

#include "bwh_error.h"
#include "bwh_ext.h"

static char *program_dir;

void bwh_device_set_program_dir(const char *dir)
{
    free(program_dir);
    program_dir = dir ? strdup(dir) : NULL;
}

/* DIR/brdfwave-fw-linux or DIR/../qemu/brdfwave-fw.elf, allocated */
static char *image_in(const char *dir, int linux_process)
{
    const char *rel = linux_process ? "brdfwave-fw-linux" : "../qemu/brdfwave-fw.elf";
    size_t n = strlen(dir) + strlen(rel) + 2;
    char *path = malloc(n);
    if (path)
        snprintf(path, n, "%s/%s", dir, rel);
    return path;
}

/* the directory of the file this library's code was loaded from: the
 * shared library, or the program it is linked into */
static char *library_dir(void)
{
    Dl_info info;
    if (!dladdr((void *)bwh_device_firmware, &info) || !info.dli_fname)
        return NULL;
    char *real = realpath(info.dli_fname, NULL);
    if (!real)
        return NULL;
    char *slash = strrchr(real, '/');
    if (slash)
        *slash = 0;
    return real;
}

char *bwh_device_firmware(const char *device, const char *explicit_path)
{
    int linux_process = device && !strcmp(device, "linux");
    if (explicit_path)
        return strdup(explicit_path);
    const char *env = getenv(linux_process ? "BW_FIRMWARE_LINUX" : "BW_FIRMWARE");
    if (env && *env)
        return strdup(env);
    char *lib = library_dir(), *first = NULL;
    const char *dirs[2] = {program_dir, lib};
    for (int k = 0; k < 2; k++) {
        if (!dirs[k])
            continue;
        char *path = image_in(dirs[k], linux_process);
        struct stat sb;
        if (path && stat(path, &sb) == 0) {
            free(first);
            free(lib);
            return path;
        }
        if (!first)
            first = path;
        else
            free(path);
    }
    free(lib);
    if (!first) /* neither directory known */
        first = strdup(linux_process ? "brdfwave-fw-linux" : "brdfwave-fw.elf");
    return first;
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

int bwh_device_open(bwh_device_t *dv, const char *device, const char *firmware)
{
    memset(dv, 0, sizeof *dv);
    dv->fd = dv->pipefd = -1;
    dv->pid = -1;
    int linux_process = !strcmp(device, "linux");
    if (!linux_process && strcmp(device, "qemu") != 0)
        return bwh_fail("unknown device '%s' (known: qemu, linux)", device);
    char *fw = bwh_device_firmware(device, firmware);
    if (!fw)
        return bwh_fail("out of memory");
    struct stat sb;
    if (stat(fw, &sb) != 0) {
        bwh_fail("firmware image %s: %s (build it with '%s')", fw, strerror(errno),
                 linux_process ? "make" : "make TARGET=qemu");
        free(fw);
        return -1;
    }
    if (linux_process) {
        dv->pid = start_linux(fw, &dv->fd);
        free(fw);
        if (dv->pid < 0)
            return -1;
    } else {
        int pipefd[2];
        if (pipe2(pipefd, O_CLOEXEC) != 0) {
            free(fw);
            return bwh_fail("pipe: %s", strerror(errno));
        }
        dv->pid = fork();
        if (dv->pid < 0) {
            free(fw);
            close(pipefd[0]);
            close(pipefd[1]);
            return bwh_fail("fork: %s", strerror(errno));
        }
        if (dv->pid == 0) {
            dup2(pipefd[1], 1);
            dup2(pipefd[1], 2);
            execlp("qemu-system-arm", "qemu-system-arm", "-M", "mps2-an386", "-display", "none",
                   "-monitor", "none", "-icount", "shift=0", "-semihosting-config",
                   "enable=on,target=native", "-chardev", "pty,id=link", "-serial",
                   "chardev:link", "-kernel", fw, (char *)NULL);
            fprintf(stderr, "cannot run qemu-system-arm: %s\n", strerror(errno));
            _exit(127);
        }
        free(fw);
        close(pipefd[1]);
        dv->pipefd = pipefd[0];
        char pty[256];
        if (find_pty(dv->pipefd, pty, sizeof pty, 30) != 0 ||
            (dv->fd = bwh_port_open(pty)) < 0) {
            bwh_device_close(dv);
            return -1;
        }
    }
    bwh_link_init(&dv->link, dv->fd);
    /* the device's limits, so that a job it cannot take is refused before
     * any work; a device that does not answer is asked nothing more */
    if (bwh_send_frame(dv->fd, BW_FT_HELLO, 0, NULL, 0) != 0) {
        bwh_device_close(dv);
        return -1;
    }
    double end = bwh_now() + 10;
    bw_frame_t f;
    for (;;) {
        int k = bwh_link_next(&dv->link, &f, end);
        if (k < 0) {
            bwh_device_close(dv);
            return -1;
        }
        if (k == 0)
            break;
        uint8_t version;
        if (f.type == BW_FT_HELLO && bw_hello_unpack(f.data, f.len, &version, &dv->limits)) {
            dv->have_limits = 1;
            break;
        }
    }
    return 0;
}

int bwh_device_admit(const bwh_device_t *dv, const bw_dims_t *dims, const bw_params_t *p)
{
    bool streamed;
    bw_status_t st = dv->have_limits ? bw_limits_admit(&dv->limits, dims, p, &streamed) : BW_OK;
    if (st == BW_OK)
        return 0;
    if (st == BW_ERR_ARG)
        return bwh_fail("embedded segments (--progressive) are coded in coarse-to-fine order, "
                        "not in stream order");
    explain_device_error(dims, BW_ERR_WORK, &dv->limits);
    return -1;
}

int bwh_device_run(bwh_device_t *dv, const bw_dims_t *dims, const bw_params_t *p,
                   const int32_t *samples, const bwh_rx_opts_t *o, bwh_received_t *r)
{
    memset(r, 0, sizeof *r);
    int rc = -1;
    uint8_t *seg_ext = NULL;
    char input[] = "/tmp/brdfwave-sensor-XXXXXX";
    int in_fd = mkstemp(input);
    if (in_fd < 0)
        return bwh_fail("cannot prepare the device input: %s", strerror(errno));
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
    bw_job_t job;
    bw_job_make(&job, dims, p);
    /* segments: the job's first record, embedded segments a record 0x04
     * without data after it (bw_job_params); embedded without segments is
     * one segment of every vector */
    if (p->segment_vectors || p->progressive) {
        seg_ext = malloc(p->ext_len + 9u);
        if (!seg_ext) {
            bwh_fail("out of memory");
            goto out;
        }
        uint32_t nv = dims->n_in * dims->n_out;
        size_t k = bwh_varint_put(seg_ext + 2, p->segment_vectors ? p->segment_vectors : nv);
        seg_ext[0] = BW_EXT_SEGMENTS;
        seg_ext[1] = (uint8_t)k;
        k += 2u;
        if (p->progressive) {
            seg_ext[k++] = BW_EXT_EMBEDDED;
            seg_ext[k++] = 0;
        }
        if (p->ext_len)
            memcpy(seg_ext + k, p->ext, p->ext_len);
        job.ext = seg_ext;
        job.ext_len = p->ext_len + (uint32_t)k;
    }
    strcpy(job.source, input); /* shorter than the field */
    if (job.ext_len > BW_JOB_EXT_MAX) {
        /* more records than the JOB frame holds: JOB_EXT frames first */
        for (uint32_t at = 0; at < job.ext_len; at += BW_FRAME_MAX_DATA) {
            uint32_t k = job.ext_len - at < BW_FRAME_MAX_DATA ? job.ext_len - at
                                                              : BW_FRAME_MAX_DATA;
            if (bwh_send_frame(dv->fd, BW_FT_JOB_EXT, 0, job.ext + at, (uint16_t)k) != 0)
                goto out;
        }
        job.ext = NULL;
        job.ext_len = 0;
    }
    uint8_t jb[BW_FRAME_MAX_DATA];
    size_t jn = bw_job_pack(&job, jb);
    if (bwh_send_frame(dv->fd, BW_FT_JOB, 0, jb, (uint16_t)jn) != 0)
        goto out;
    if (bwh_receive_payload(&dv->link, o, r) != 0) {
        if (r->device_error && r->device_status == BW_ERR_ARG && p->ext_len > BW_JOB_EXT_MAX)
            bwh_fail("the device refused the job's %u bytes of metadata (more than it holds): "
                     "encode with --no-metadata, or on the host", (unsigned)p->ext_len);
        else if (r->device_error)
            explain_device_error(dims, r->device_status, &r->limits);
        goto out;
    }
    if (bwh_acknowledge(&dv->link, r->id) != 0) {
        free(r->payload);
        r->payload = NULL;
        goto out;
    }
    rc = 0;
out:
    free(seg_ext);
    close(in_fd);
    unlink(input);
    return rc;
}

void bwh_device_close(bwh_device_t *dv)
{
    if (dv->pid > 0) {
        /* the session ends now, whatever happened: the device exits on QUIT;
         * one that does not within a few seconds is stopped */
        if (dv->fd >= 0)
            bwh_send_frame(dv->fd, BW_FT_QUIT, 0, NULL, 0);
        int status;
        double end = bwh_now() + 3;
        while (waitpid(dv->pid, &status, WNOHANG) == 0) {
            if (bwh_now() > end) {
                kill(dv->pid, SIGKILL);
                waitpid(dv->pid, &status, 0);
                break;
            }
            usleep(2000);
        }
    }
    if (dv->fd >= 0)
        close(dv->fd);
    if (dv->pipefd >= 0)
        close(dv->pipefd);
    dv->fd = dv->pipefd = -1;
    dv->pid = -1;
}

int bwh_device_encode(const char *device, const char *firmware, const bw_dims_t *dims,
                      const bw_params_t *p, const int32_t *samples, const bwh_rx_opts_t *o,
                      bwh_received_t *r)
{
    memset(r, 0, sizeof *r);
    bwh_device_t dv;
    if (bwh_device_open(&dv, device, firmware) != 0)
        return -1;
    int rc = bwh_device_admit(&dv, dims, p);
    if (rc == 0)
        rc = bwh_device_run(&dv, dims, p, samples, o, r);
    bwh_device_close(&dv);
    return rc;
}
