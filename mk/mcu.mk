# SPDX-License-Identifier: BSD-2-Clause
# A real MCU: STM32L476RG (Cortex-M4F, 1 MiB flash, 96 KiB SRAM1), build only:
# the codec core as a static library and the firmware image on the
# register-level board backend (hal/stm32l4).
CROSS_COMPILE ?= arm-none-eabi-
CC := $(CROSS_COMPILE)gcc
AR := $(CROSS_COMPILE)ar
SIZE := $(CROSS_COMPILE)size
CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
OPT ?= -Os
CFLAGS := $(WARN) $(OPT) $(CPU) -ffreestanding -ffunction-sections -fdata-sections $(CORE_INC)
LINKER_SCRIPT := linker/stm32l476.ld

# the core with the switches for the device's flash (mk/core-device.mk) and
# link-time optimisation (fat objects: libbwcore.a links without it too)
include mk/core-device.mk
$(CORE_OBJ): CFLAGS += $(BW_DEVICE_CFG) -flto -ffat-lto-objects

# startup.c before vectors.c: both put their table in .isr_vector, which the
# linker keeps in link order (the 16 system vectors, then IRQ 0..81)
FW_SRC := firmware/link/bw_frame.c firmware/link/bw_i2cwin.c firmware/app/app.c \
          firmware/app/main.c hal/cortex-m/startup.c hal/stm32l4/vectors.c hal/stm32l4/board.c
FW_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(FW_SRC))
FW_ELF := $(BUILD)/brdfwave-fw.elf
$(FW_OBJ): CFLAGS += -Ihal -Ifirmware/link -Ifirmware/app
$(FW_OBJ): mk/mcu.mk

# The application's buffers in 96 KiB of SRAM1: a whole measurement of up to
# 4096 samples and 1024 bands encoded at once (4 spectra of 1024 bands, or a
# level-4 reflectance of 4 bands), a streamed job of up to level 4 and 128
# bands encoded spectrum by spectrum, payloads of up to 16 KiB, the
# coder's state (bw_ctx_t, 7.5 KiB) and 2 KiB of a job's extension records
# (the host's metadata, APP_EXT_MAX). That leaves about 7 KiB below .bss for
# the stack: linker/stm32l476.ld reserves 4 KiB, and the deepest call chain
# with the application's frames takes about 1.7 KiB (-fstack-usage;
# build/bench/device.md).
APP_SIZES := -DAPP_MAX_SAMPLES=4096u -DAPP_MAX_BANDS=1024u -DAPP_PAYLOAD_CAP=16384u \
             -DAPP_STREAM_LEVEL=4u -DAPP_STREAM_BANDS=128u
$(BUILD)/firmware/app/app.o: CFLAGS += $(APP_SIZES)

all: $(BUILD)/libbwcore.a $(FW_ELF)

$(BUILD)/libbwcore.a: $(CORE_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^

# the firmware image; the linker script asserts that .data + .bss + stack fit
$(FW_ELF): $(CORE_OBJ) $(FW_OBJ) $(LINKER_SCRIPT) linker/cortex-m.ld
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CPU) $(OPT) -flto -T $(LINKER_SCRIPT) -Llinker -nostartfiles --specs=nano.specs \
	    --specs=nosys.specs -Wl,--gc-sections -Wl,-Map,$(BUILD)/brdfwave-fw.map \
	    $(CORE_OBJ) $(FW_OBJ) -o $@
	$(Q)$(SIZE) $@
