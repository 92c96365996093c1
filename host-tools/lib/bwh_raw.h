/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Raw sample files: little-endian float32, uint16 or int32, row-major
 * [incoming][outgoing][band], the layout `brdfwave encode` reads and
 * `decode` writes.
 */
#ifndef BWH_RAW_H
#define BWH_RAW_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { BWH_FMT_F32 = 0, BWH_FMT_U16 = 1, BWH_FMT_I32 = 2 } bwh_format_t;

/* "f32", "u16", "i32": the format, else -1 */
int bwh_format_from_name(const char *name);
/* bytes per sample */
size_t bwh_format_size(bwh_format_t f);

/* Reads path ("-": standard input) as samples of format f: *floats
 * (allocated) gets their values, u16 and i32 converted to float; or, with
 * floats NULL, *ints (allocated) the integers (f32 is refused). A size that
 * is not a whole number of samples is refused. 0, or -1 (bwh_last_error()). */
int bwh_raw_read(const char *path, bwh_format_t f, float **floats, int32_t **ints, size_t *n);

/* Writes n int32 (as_int) or float32 samples to path (bwh_write_file),
 * turning them into their little-endian bytes in place: afterwards the
 * buffer holds the file's bytes. */
int bwh_raw_write(const char *path, void *samples, size_t n, int as_int);

#ifdef __cplusplus
}
#endif

#endif
