#include "bw_error.h"

const char *bw_strerror(int status)
{
    switch (status) {
#define BW_X_CASE(name, value, msg) \
    case value:                     \
        return msg;
        BW_STATUS_LIST(BW_X_CASE)
#undef BW_X_CASE
    default:
        return "unknown status";
    }
}
