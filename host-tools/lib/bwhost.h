/*
 * libbrdfwave: the host side of the codec, one header for the whole of it.
 *
 * The codec core (firmware/codec) works on integer samples. The library maps
 * float measurements to integers and back (value = offset + scale * sample,
 * both recorded in the payload header), reads and writes files and the input
 * formats, stores received payloads, and computes the error metrics the
 * tools report. Each part has its own header; this one includes them all.
 * The geodesic grid, the BRDF models and their evaluation, the sampler, the
 * device link and the I2C client have their own headers too (not included
 * here: see docs/ARCHITECTURE.md).
 */
#ifndef BWHOST_H
#define BWHOST_H

#include "bw_codec.h"
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

#endif
