/* SPDX-License-Identifier: BSD-2-Clause */
/* Storing received payloads (bwh_store.h). */
#define _DEFAULT_SOURCE
#include "bwh_store.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bw_codec.h"
#include "bw_crc32.h"
#include "bwh_error.h"
#include "bwh_file.h"

/* fsync of the directory that holds path, so that a rename or link in it
 * survives a power loss */
static void sync_dir(const char *dir)
{
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        fsync(dfd);
        close(dfd);
    }
}

/* 1 when the file at path holds exactly p[n], else 0 */
static int same_content(const char *path, const uint8_t *p, size_t n)
{
    uint8_t *b;
    size_t bl;
    if (bwh_read_file(path, &b, &bl) != 0)
        return 0;
    int same = bl == n && !memcmp(b, p, n);
    free(b);
    return same;
}

int bwh_store_payload(const char *dir, uint32_t id, const uint8_t *p, size_t n, char *path,
                      size_t cap)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s/.payload-%u.XXXXXX", dir, id);
    int fd = mkstemp(tmp);
    if (fd < 0)
        return bwh_fail("cannot store payload %u in %s: %s", id, dir, strerror(errno));
    int ok = fchmod(fd, 0644) == 0 && bwh_write_fd(fd, p, n) == 0 && fsync(fd) == 0;
    int e = errno;
    ok = close(fd) == 0 && ok;
    if (!ok) {
        unlink(tmp);
        return bwh_fail("cannot store payload %u in %s: %s", id, dir, strerror(e));
    }
    /* the payload's own CRC-32 (of header and body; the CRC of a whole
     * payload, its CRC included, is the same constant for every payload) */
    uint32_t crc = bw_crc32(p, n >= BW_TRAILER_SIZE ? n - BW_TRAILER_SIZE : n);
    int rc = -1, reported = 0;
    for (unsigned k = 1; k < 1000; k++) {
        if (k == 1)
            snprintf(path, cap, "%s/payload-%u-%08x.bwv", dir, id, crc);
        else
            snprintf(path, cap, "%s/payload-%u-%08x-%u.bwv", dir, id, crc, k);
        if (link(tmp, path) == 0) {
            rc = 0;
            break;
        }
        if (errno != EEXIST) {
            bwh_fail("cannot store payload %u as %s: %s", id, path, strerror(errno));
            reported = 1;
            break;
        }
        if (same_content(path, p, n)) {
            rc = 1; /* the same payload again (its ACK was lost): kept once */
            break;
        }
    }
    if (rc < 0 && !reported)
        bwh_fail("cannot store payload %u in %s: too many files of that name", id, dir);
    unlink(tmp);
    if (rc >= 0)
        sync_dir(dir);
    return rc;
}
