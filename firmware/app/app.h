/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef BW_APP_H
#define BW_APP_H

#include "bw_hal.h"

/* status sent in an ERROR frame when the sensor cannot deliver the samples */
#define APP_ERR_SENSOR (-100)

/* Serves jobs from the host until it says QUIT; returns the exit status. */
int bw_app_run(const bw_hal_t *hal);

#endif
