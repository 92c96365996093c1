/* SPDX-License-Identifier: BSD-2-Clause */
/* Scattered directions onto the grid (bwh_project.h). */
#include "bwh_project.h"

#include "bwh_error.h"
#include "bwr_project.h"

int bwh_project(const double (*dir)[3], const double *values, size_t n, size_t bands,
                unsigned level, double *out)
{
    if (bwr_project(dir, values, n, bands, level, 0, out) != 0)
        return bwh_fail("cannot project %zu directions onto level %u (a direction below the "
                        "horizon, a value not finite, or no directions)",
                        n, level);
    return 0;
}
