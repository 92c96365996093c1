/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The codec core's interface: dimensions, parameters, bw_encode, bw_decode,
 * bw_header_read, the streaming encoder bw_stream_* and the caller-owned
 * coder context bw_ctx_t. Freestanding C11: no allocation; every buffer
 * belongs to the caller and has a worst-case size (BW_PAYLOAD_BOUND,
 * BW_WORK_BOUND, ...). The core's own header, installed beside this one.
 */
#ifndef BRDFWAVE_CODEC_H
#define BRDFWAVE_CODEC_H

#include "bw_codec.h"

#endif
