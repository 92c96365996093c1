/* SPDX-License-Identifier: BSD-2-Clause */
#include "bw_error.h"

#include "bw_config.h"

const char *bw_strerror(int status)
{
#if BW_CFG_STATUS_TEXT
    switch (status) {
#define BW_X_CASE(name, value, msg) \
    case value:                     \
        return msg;
        BW_STATUS_LIST(BW_X_CASE)
#undef BW_X_CASE
    default:
        return "unknown status";
    }
#else
    (void)status;
    return "status";
#endif
}
