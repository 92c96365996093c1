# SPDX-License-Identifier: BSD-2-Clause
# Device benchmark: instructions per sample of the codec core on the emulated
# Cortex-M4 (QEMU mps2-an386, -icount shift=0), next to memcpy, first
# difference and table CRC-32 floors measured in the same image; flash, RAM
# and stack of the core. Writes build/bench/device.md.
#
# Included by mk/bench.mk (host build): BW_CLI and BENCH_PYTHON come from
# there. The image is compiled here with its own flags into
# build/bench/device/, independent of TARGET.

include mk/core-device.mk

BD_DIR   := build/bench/device
BD_CC    := arm-none-eabi-gcc
BD_CPU   := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
BD_WARN  := -std=c11 -Wall -Wextra -Wshadow -Wstrict-prototypes -Werror
BD_CORE_CFLAGS = $(BD_WARN) $(BD_CPU) -ffreestanding -ffunction-sections -fdata-sections \
                 -Ifirmware/codec -g -fstack-usage -fcallgraph-info=su
BD_CORE_SRC := $(wildcard firmware/codec/*.c)
BD_CORE_HDR := $(wildcard firmware/codec/*.h)
# -O2 with the default switches: linked into the image; -Os with the
# device's switches (mk/core-device.mk): stack frames only (as the MCU build)
BD_OBJ_O2 := $(patsubst firmware/codec/%.c,$(BD_DIR)/obj-O2/%.o,$(BD_CORE_SRC))
BD_OBJ_OS := $(patsubst firmware/codec/%.c,$(BD_DIR)/obj-Os/%.o,$(BD_CORE_SRC))
BD_IMG_SRC := tests/bench/device/bench_device.c hal/cortex-m/startup.c hal/qemu-mps2/board.c \
              hal/file_sensor.c
BD_IMG_OBJ := $(patsubst %.c,$(BD_DIR)/obj-img/%.o,$(BD_IMG_SRC))
BD_ELF := $(BD_DIR)/bench_device.elf

$(BD_DIR)/obj-O2/%.o: firmware/codec/%.c $(BD_CORE_HDR) mk/bench-device.mk mk/core-device.mk
	@mkdir -p $(dir $@)
	$(BD_CC) $(BD_CORE_CFLAGS) -O2 -c $< -o $@

$(BD_DIR)/obj-Os/%.o: firmware/codec/%.c $(BD_CORE_HDR) mk/bench-device.mk mk/core-device.mk
	@mkdir -p $(dir $@)
	$(BD_CC) $(BD_CORE_CFLAGS) -Os $(BW_DEVICE_CFG) -c $< -o $@

$(BD_DIR)/obj-img/%.o: %.c $(BD_CORE_HDR) hal/bw_hal.h mk/bench-device.mk
	@mkdir -p $(dir $@)
	$(BD_CC) $(BD_WARN) $(BD_CPU) -O2 -g -ffunction-sections -fdata-sections \
	    -Ifirmware/codec -Ihal -c $< -o $@

$(BD_ELF): $(BD_OBJ_O2) $(BD_IMG_OBJ) linker/mps2-an386.ld linker/cortex-m.ld
	$(BD_CC) $(BD_CPU) --specs=rdimon.specs -nostartfiles -Llinker -T linker/mps2-an386.ld \
	    -Wl,--gc-sections -Wl,-Map=$(BD_DIR)/bench_device.map $(BD_IMG_OBJ) $(BD_OBJ_O2) -o $@

.PHONY: bench-device bench-device-image bench-device-deps
bench-device-deps:
	$(Q)tests/deps.sh device

bench-device-image: $(BD_ELF) $(BD_OBJ_OS)

bench-device: bench-device-deps bench-device-image $(BW_CLI)
	$(MAKE) --no-print-directory TARGET=mcu build/mcu/libbwcore.a
	$(MAKE) --no-print-directory TARGET=qemu build/qemu/libbwcore.a
	BW=$(BW_CLI) $(BENCH_PYTHON) tests/bench/device/run_device_bench.py

bench: bench-device
