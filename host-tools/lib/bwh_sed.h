/* SPDX-License-Identifier: BSD-2-Clause */
/* Spectral Evolution .sed files (PSR-3500 and alike) as codec samples. */
#ifndef BWH_SED_H
#define BWH_SED_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Reads the reflectance column, parsed exactly as decimal text into
 * integers of 10^-5 (the files print 5 decimals). *values is allocated;
 * *bands receives the channel count; wavelengths (optional, allocated) in
 * nm. A row cut short, a row too many or too few are refused. 0, or -1. */
int bwh_sed_read(const char *path, int32_t **values, uint32_t *bands, double **wavelengths);

/* Several files as one set of spectra: their samples one after the other
 * in *values (allocated), *count of them. Every file must have *bands
 * channels (0 on entry: as many as the first). 0, or -1. */
int bwh_sed_read_set(const char *const *paths, int n, int32_t **values, uint32_t *bands,
                     size_t *count);

/* A decimal with at most `decimals` fraction digits, exactly, in units of
 * 10^-decimals (within the codec's sample range); *end after it. 0, or -1
 * (not such a number). */
int bwh_parse_fixed(const char *s, int decimals, const char **end, int32_t *out);

/* the value of one integer unit of bwh_sed_read's samples */
#define BWH_SED_SCALE 1e-5

#ifdef __cplusplus
}
#endif

#endif
