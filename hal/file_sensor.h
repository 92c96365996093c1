/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef BW_FILE_SENSOR_H
#define BW_FILE_SENSOR_H

#include <stddef.h>
#include <stdint.h>

#include "bw_hal.h"

/* bw_hal_t.sensor_open / sensor_read over a file of little-endian int32. */
int bw_file_sensor_open(const char *source);
int bw_file_sensor_read(int32_t *samples, size_t cap);

#endif
