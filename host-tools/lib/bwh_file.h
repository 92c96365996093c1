/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Whole files in and out. "-" is standard input or output; a path that is
 * not a regular file (a device, a pipe) is written to directly; a regular
 * file is replaced only once the new one is complete.
 */
#ifndef BWH_FILE_H
#define BWH_FILE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Reads all of path into *buf (allocated: free() it). 0, or -1
 * (bwh_last_error()). */
int bwh_read_file(const char *path, uint8_t **buf, size_t *len);

/* Writes "-" to standard output, and a path that is not a regular file (a
 * device, a pipe) directly; a regular file (or a symbolic link to one,
 * followed) is written beside it and renamed over it, so that a failure
 * leaves the old file; a symbolic link to nothing is refused. 0, or -1. */
int bwh_write_file(const char *path, const void *buf, size_t len);

/* Writes all of buf to a blocking descriptor (EINTR retried). 0, or -1 with
 * errno set. */
int bwh_write_fd(int fd, const void *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif
