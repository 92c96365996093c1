/* SPDX-License-Identifier: BSD-2-Clause */
/* The library's version (brdfwave/brdfwave.h). */
#include "brdfwave/brdfwave.h"

const char *bwh_version(void) { return BRDFWAVE_VERSION_STRING; }

int bwh_version_number(void) { return BRDFWAVE_VERSION_NUMBER; }
