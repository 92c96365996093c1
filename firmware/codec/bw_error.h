/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave: one list of status codes. Success is >= 0, errors are < 0. */
#ifndef BW_ERROR_H
#define BW_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

/* X(name, value, message) */
#define BW_STATUS_LIST(X)                                                          \
    X(BW_OK, 0, "ok")                                                              \
    X(BW_ERR_ARG, -1, "invalid argument")                                          \
    X(BW_ERR_SHAPE, -2, "unsupported shape or dimensions")                         \
    X(BW_ERR_RANGE, -3, "sample out of range")                                     \
    X(BW_ERR_OUTPUT_FULL, -4, "output buffer too small")                           \
    X(BW_ERR_BUDGET, -5, "byte budget too small for this measurement")             \
    X(BW_ERR_TRUNCATED, -6, "payload truncated")                                   \
    X(BW_ERR_MAGIC, -7, "not a brdfwave payload (bad magic)")                      \
    X(BW_ERR_VERSION, -8, "unsupported payload version")                           \
    X(BW_ERR_HEADER, -9, "invalid payload header field")                           \
    X(BW_ERR_CRC, -10, "payload CRC mismatch (corrupted)")                         \
    X(BW_ERR_CORRUPT, -11, "corrupted payload body")                               \
    X(BW_ERR_WORK, -12, "work buffer too small")                                   \
    X(BW_ERR_VERIFY, -13, "encoder self-check failed (guarantee not met)")         \
    X(BW_ERR_MISMATCH, -14, "operands have different sizes")                        \
    X(BW_ERR_TRAILING, -15, "payload length does not match its header")                    \
    X(BW_ERR_EXTENSION, -16, "payload needs an extension this decoder does not know") \
    X(BW_ERR_NOT_BUILT, -17, "this build leaves out the coder the payload or request needs") \
    X(BW_ERR_INCOMPLETE, -18, "payload damaged or cut: segments lost, the rest decoded")

typedef enum {
#define BW_X_ENUM(name, value, msg) name = value,
    BW_STATUS_LIST(BW_X_ENUM)
#undef BW_X_ENUM
} bw_status_t;

const char *bw_strerror(int status);

#ifdef __cplusplus
}
#endif

#endif
