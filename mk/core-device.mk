# SPDX-License-Identifier: BSD-2-Clause
# The codec core's switches (firmware/codec/bw_config.h) for the device's
# 16 KiB of flash: the small code forms (the same bytes), and the encoder
# without prediction, without the byte budget's half-step search, without
# the fast basis choice and byte budget, without segments (it decodes them),
# without steps per chunk (it refuses them) and the decode of damaged
# payloads, and without the multi-symbol coder; status texts are left to the
# host (the device sends status numbers). Used by the MCU build
# (mk/mcu.mk), the benchmark's -Os figures (mk/bench-device.mk), the
# freestanding check's -Os image and the sanitizer's first pass (which read
# this line).
BW_DEVICE_CFG := -DBW_CFG_SPEED=0 -DBW_CFG_ENCODE_PRED=0 -DBW_CFG_BUDGET_FILL_HALF=0 -DBW_CFG_FAST_BASIS=0 -DBW_CFG_FAST_BUDGET=0 -DBW_CFG_SEGMENTS=0 -DBW_CFG_CHUNK_STEPS=0 -DBW_CFG_SALVAGE=0 -DBW_CFG_EMBED=0 -DBW_CFG_BANDS=0 -DBW_CFG_STATUS_TEXT=0 -DBW_CFG_CODER_MS=0
