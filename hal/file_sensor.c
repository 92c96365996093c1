/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * A sensor that replays a file of little-endian int32 samples through the C
 * library: the emulated board (semihosting) and the Linux process use it.
 */
#include "file_sensor.h"

#include <stdio.h>

#include "bw_le.h"

static FILE *sensor;

int bw_file_sensor_open(const char *source)
{
    if (sensor)
        fclose(sensor);
    sensor = fopen(source, "rb");
    return sensor ? 0 : -BW_HAL_EIO;
}

int bw_file_sensor_read(int32_t *samples, size_t cap)
{
    if (!sensor)
        return -BW_HAL_EIO;
    size_t n = 0;
    uint8_t b[4];
    while (n < cap && fread(b, 1, 4, sensor) == 4)
        samples[n++] = (int32_t)bw_get_u32(b);
    return (int)n;
}
