/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libbrdfwave: the host side of the codec, one header for the whole of it.
 *
 * The library's public interface is include/brdfwave/brdfwave.h (installed
 * as <brdfwave/brdfwave.h>): this header is that one, so that the library
 * and its tools are built against what is installed. The geodesic grid is
 * part of it; the BRDF models, their evaluation and the sampler are in
 * brdfwave/brdf.h; the device link and the I2C client have their own
 * headers, not installed (see docs/ARCHITECTURE.md).
 */
#ifndef BWHOST_H
#define BWHOST_H

#include "brdfwave/brdfwave.h"

#endif
