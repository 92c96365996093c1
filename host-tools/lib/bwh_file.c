/* SPDX-License-Identifier: BSD-2-Clause */
/* Whole files in and out (bwh_file.h). */
#define _DEFAULT_SOURCE
#include "bwh_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bwh_error.h"

int bwh_read_file(const char *path, uint8_t **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    int std = !strcmp(path, "-");
    FILE *f = std ? stdin : fopen(path, "rb");
    if (!f)
        return bwh_fail("%s: %s", path, strerror(errno));
    if (std)
        path = "standard input";
    size_t cap = 1 << 16, n = 0;
    uint8_t *b = malloc(cap);
    if (!b) {
        if (!std)
            fclose(f);
        return bwh_fail("%s: out of memory", path);
    }
    for (;;) {
        if (n == cap) {
            uint8_t *nb = cap > SIZE_MAX / 2 ? NULL : realloc(b, cap * 2);
            if (!nb) {
                free(b);
                if (!std)
                    fclose(f);
                return bwh_fail("%s: out of memory", path);
            }
            b = nb;
            cap *= 2;
        }
        size_t r = fread(b + n, 1, cap - n, f);
        n += r;
        if (r == 0)
            break;
    }
    int err = ferror(f);
    if (!std)
        fclose(f);
    if (err) {
        free(b);
        return bwh_fail("%s: read error", path);
    }
    *buf = b;
    *len = n;
    return 0;
}

int bwh_write_fd(int fd, const void *buf, size_t len)
{
    const uint8_t *p = buf;
    while (len) {
        ssize_t w = write(fd, p, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        len -= (size_t)w;
    }
    return 0;
}

/* A new file beside `path` (same directory), created exclusively with the
 * mode a new file would get; its name goes to tmp[cap]. */
static int temp_beside(const char *path, char *tmp, size_t cap)
{
    const char *slash = strrchr(path, '/');
    int dl = slash ? (int)(slash - path + 1) : 0;
    if (snprintf(tmp, cap, "%.*s.%s.XXXXXX", dl, path, slash ? slash + 1 : path) >= (int)cap) {
        errno = ENAMETOOLONG;
        return -1;
    }
    int fd = mkstemp(tmp);
    if (fd < 0)
        return -1;
    mode_t um = umask(0);
    umask(um);
    if (fchmod(fd, 0666 & ~um) != 0) {
        close(fd);
        unlink(tmp);
        return -1;
    }
    return fd;
}

int bwh_write_file(const char *path, const void *buf, size_t len)
{
    if (!strcmp(path, "-")) {
        if (bwh_write_fd(1, buf, len) != 0)
            return bwh_fail("standard output: %s", strerror(errno));
        return 0;
    }
    struct stat st, lst;
    int exists = stat(path, &st) == 0;
    if (!exists && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode))
        return bwh_fail("%s: a symbolic link to a missing file; not replaced", path);
    if (exists && !S_ISREG(st.st_mode)) {
        /* a device, a pipe, a socket: written to as it is, never replaced */
        if (S_ISDIR(st.st_mode))
            return bwh_fail("%s: is a directory", path);
        int fd = open(path, O_WRONLY | O_CLOEXEC);
        if (fd < 0)
            return bwh_fail("%s: %s", path, strerror(errno));
        int bad = bwh_write_fd(fd, buf, len) != 0;
        int e = errno;
        if (close(fd) != 0 && !bad) {
            bad = 1;
            e = errno;
        }
        return bad ? bwh_fail("%s: write failed: %s", path, strerror(e)) : 0;
    }
    /* a regular file (a symbolic link to one is followed): written beside
     * its target and renamed over it, so a failure leaves the old file */
    char *real = NULL;
    if (exists && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        real = realpath(path, NULL);
        if (!real)
            return bwh_fail("%s: %s", path, strerror(errno));
        path = real;
    }
    char tmp[4096];
    int fd = temp_beside(path, tmp, sizeof tmp);
    if (fd < 0) {
        bwh_fail("%s: %s", path, strerror(errno));
        free(real);
        return -1;
    }
    int ok = bwh_write_fd(fd, buf, len) == 0;
    if (ok && exists)
        ok = fchmod(fd, st.st_mode & 07777) == 0;
    ok = (close(fd) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) {
        bwh_fail("%s: write failed: %s", path, strerror(errno));
        unlink(tmp);
        free(real);
        return -1;
    }
    free(real);
    return 0;
}
