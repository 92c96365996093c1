/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libbrdfwave: the public interface of the host library.
 *
 *   #include <brdfwave/brdfwave.h>      cc prog.c $(pkg-config --cflags --libs brdfwave)
 *
 * The codec core (brdfwave/codec.h) works on integer samples; the library
 * maps float measurements to integers and back (value = offset + scale *
 * sample, both recorded in the payload header), reads and writes files and
 * the input formats, stores received payloads, computes the error metrics
 * the command line reports and gives the geodesic grid of the directions.
 * Evaluation and importance sampling of decoded BRDFs are in brdfwave/brdf.h.
 *
 * Every failing bwh_* call returns -1 (or NULL) and leaves one line of text
 * in bwh_last_error(). Buffers the library allocates are released with
 * free().
 *
 * The headers this one includes are the library's own, installed beside it;
 * the library's sources include them through it, so what is installed is
 * what the library is built from. The serial link, the device encode and
 * the I2C client are not part of this interface.
 */
#ifndef BRDFWAVE_BRDFWAVE_H
#define BRDFWAVE_BRDFWAVE_H

/* the release: the shared library's SONAME is libbrdfwave.so.MAJOR */
#define BRDFWAVE_VERSION_MAJOR 1
#define BRDFWAVE_VERSION_MINOR 0
#define BRDFWAVE_VERSION_PATCH 0
#define BRDFWAVE_VERSION_STRING "1.0.0"
#define BRDFWAVE_VERSION_NUMBER \
    (BRDFWAVE_VERSION_MAJOR * 10000 + BRDFWAVE_VERSION_MINOR * 100 + BRDFWAVE_VERSION_PATCH)

#include "codec.h"

#include "bwh_decode.h"
#include "bwh_encode.h"
#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_metrics.h"
#include "bwh_names.h"
#include "bwh_raw.h"
#include "bwh_sed.h"
#include "bwh_shape.h"
#include "bwh_store.h"
#include "bwh_values.h"
#include "geodesic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the library the program runs with ("1.0.0"), which may be
 * newer than the BRDFWAVE_VERSION_STRING it was compiled with. */
const char *bwh_version(void);
/* the same as BRDFWAVE_VERSION_NUMBER */
int bwh_version_number(void);

#ifdef __cplusplus
}
#endif

#endif
