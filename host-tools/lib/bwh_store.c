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

/* ---- incomplete payloads ---------------------------------------------------- */

int bwh_partial_init(bwh_partial_t *p, uint32_t id, uint32_t crc, size_t len, unsigned unit)
{
    memset(p, 0, sizeof *p);
    if (len == 0 || unit == 0 || (len + unit - 1u) / unit > UINT32_MAX)
        return bwh_fail("an incomplete payload of %zu bytes in parts of %u", len, unit);
    p->id = id;
    p->crc = crc;
    p->len = len;
    p->unit = unit;
    p->parts = (uint32_t)((len + unit - 1u) / unit);
    p->payload = calloc(len, 1);
    p->have = calloc(p->parts, 1);
    if (!p->payload || !p->have) {
        bwh_partial_free(p);
        return bwh_fail("out of memory");
    }
    return 0;
}

void bwh_partial_free(bwh_partial_t *p)
{
    free(p->payload);
    free(p->have);
    p->payload = p->have = NULL;
}

uint32_t bwh_partial_missing(const bwh_partial_t *p)
{
    uint32_t n = 0;
    for (uint32_t k = 0; k < p->parts; k++)
        n += !p->have[k];
    return n;
}

/* data[n] to path through a temporary file beside it, fsync and a rename */
static int replace_file(const char *dir, const char *path, const void *data, size_t n)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.XXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0)
        return bwh_fail("cannot write %s: %s", path, strerror(errno));
    int ok = fchmod(fd, 0644) == 0 && bwh_write_fd(fd, data, n) == 0 && fsync(fd) == 0;
    int e = errno;
    ok = close(fd) == 0 && ok;
    if (!ok || rename(tmp, path) != 0) {
        e = ok ? errno : e;
        unlink(tmp);
        return bwh_fail("cannot write %s: %s", path, strerror(e));
    }
    sync_dir(dir);
    return 0;
}

#define PART_MAGIC "brdfwave incomplete payload 1\n"

/* The record's name of payload id whose whole bytes have CRC-32 crc. */
static void partial_path(const char *dir, uint32_t id, uint32_t crc, char *path, size_t cap)
{
    snprintf(path, cap, "%s/payload-%u-%08x.part", dir, id, crc);
}

int bwh_partial_store(const char *dir, const bwh_partial_t *p, char *path, size_t cap)
{
    char bytes[4096];
    partial_path(dir, p->id, p->crc, path, cap);
    snprintf(bytes, sizeof bytes, "%s.bwv", path);
    /* the record: a few fixed lines, then the missing parts */
    size_t cap_t = 256u + 11u * (size_t)p->parts, n = 0;
    char *t = malloc(cap_t);
    if (!t)
        return bwh_fail("out of memory");
    n += (size_t)snprintf(t + n, cap_t - n,
                          PART_MAGIC "id %u\nlength %zu\ncrc %08x\nunit %u\nmissing", p->id,
                          p->len, p->crc, p->unit);
    for (uint32_t k = 0; k < p->parts; k++)
        if (!p->have[k])
            n += (size_t)snprintf(t + n, cap_t - n, " %u", k);
    n += (size_t)snprintf(t + n, cap_t - n, "\n");
    /* the bytes first: a record names bytes that are there */
    int rc = replace_file(dir, bytes, p->payload, p->len) == 0 &&
                     replace_file(dir, path, t, n) == 0
                 ? 0
                 : -1;
    free(t);
    return rc;
}

/* the record's path of a .part or .part.bwv path */
static void record_path(const char *path, char *rec, size_t cap)
{
    size_t n = strlen(path);
    snprintf(rec, cap, "%s", path);
    if (n > 9 && !strcmp(path + n - 9, ".part.bwv") && n - 4 < cap)
        rec[n - 4] = '\0';
}

int bwh_partial_load(const char *path, bwh_partial_t *p)
{
    char rec[4096], bytes[4104];
    memset(p, 0, sizeof *p);
    record_path(path, rec, sizeof rec);
    snprintf(bytes, sizeof bytes, "%s.bwv", rec);
    uint8_t *t;
    size_t tl;
    if (bwh_read_file(rec, &t, &tl) != 0)
        return -1;
    char *s = malloc(tl + 1u);
    if (!s) {
        free(t);
        return bwh_fail("out of memory");
    }
    memcpy(s, t, tl);
    s[tl] = '\0';
    free(t);
    unsigned id, crc, unit;
    size_t len;
    int used = 0, rc = -1;
    if (strncmp(s, PART_MAGIC, strlen(PART_MAGIC)) != 0 ||
        sscanf(s + strlen(PART_MAGIC), "id %u length %zu crc %x unit %u missing%n", &id, &len,
               &crc, &unit, &used) != 4 ||
        !used) {
        bwh_fail("%s is not a record of an incomplete payload", rec);
        goto out;
    }
    if (bwh_partial_init(p, id, crc, len, unit) != 0)
        goto out;
    memset(p->have, 1, p->parts);
    for (const char *c = s + strlen(PART_MAGIC) + used;;) {
        char *end;
        while (*c == ' ')
            c++;
        if (*c == '\n' && !c[1])
            break;
        unsigned long k = strtoul(c, &end, 10);
        if (end == c || k >= p->parts || !p->have[k]) {
            bwh_fail("%s: a malformed list of missing parts", rec);
            goto out;
        }
        p->have[k] = 0;
        c = end;
    }
    uint8_t *b;
    size_t bl;
    if (bwh_read_file(bytes, &b, &bl) != 0)
        goto out;
    if (bl != len) {
        free(b);
        bwh_fail("%s holds %zu bytes, its record %zu", bytes, bl, len);
        goto out;
    }
    memcpy(p->payload, b, len);
    free(b);
    rc = 0;
out:
    free(s);
    if (rc != 0)
        bwh_partial_free(p);
    return rc;
}

void bwh_partial_forget(const char *dir, uint32_t id, const uint8_t *payload, size_t len)
{
    char path[4096];
    partial_path(dir, id, bw_crc32(payload, len), path, sizeof path);
    bwh_partial_remove(path);
}

void bwh_partial_remove(const char *path)
{
    char rec[4096], bytes[4104];
    record_path(path, rec, sizeof rec);
    snprintf(bytes, sizeof bytes, "%s.bwv", rec);
    unlink(rec);
    unlink(bytes);
}
