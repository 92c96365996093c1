# SPDX-License-Identifier: BSD-2-Clause
# QEMU mps2-an386 (Cortex-M4F): the codec core as a static library.
CROSS_COMPILE ?= arm-none-eabi-
CC := $(CROSS_COMPILE)gcc
AR := $(CROSS_COMPILE)ar
CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
OPT ?= -O2
CFLAGS := $(WARN) $(OPT) $(CPU) -ffreestanding -ffunction-sections -fdata-sections $(CORE_INC)
LINKER_SCRIPT := linker/mps2-an386.ld

FW_SRC := firmware/link/bw_frame.c firmware/app/app.c firmware/app/main.c \
          hal/cortex-m/startup.c hal/qemu-mps2/board.c hal/file_sensor.c
FW_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(FW_SRC))
FW_ELF := $(BUILD)/brdfwave-fw.elf
$(FW_OBJ): CFLAGS += -Ihal -Ifirmware/link -Ifirmware/app

all: $(BUILD)/libbwcore.a $(FW_ELF)

# the firmware image: the application on the codec core
$(FW_ELF): $(CORE_OBJ) $(FW_OBJ) $(LINKER_SCRIPT) linker/cortex-m.ld
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CPU) --specs=rdimon.specs -nostartfiles -Llinker -T $(LINKER_SCRIPT) \
	    -Wl,--gc-sections -Wl,-Map,$(BUILD)/brdfwave-fw.map $(CORE_OBJ) $(FW_OBJ) -o $@

$(BUILD)/libbwcore.a: $(CORE_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^

# target tests: the core on the emulated board, semihosting for I/O and exit
TT_SRC := hal/cortex-m/startup.c hal/qemu-mps2/board.c hal/file_sensor.c tests/target/test_target.c
TT_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(TT_SRC))
TT_ELF := $(BUILD)/tests/test_target.elf
$(TT_OBJ): CFLAGS += -Ihal -Itests

target-tests: $(TT_ELF)

$(TT_ELF): $(CORE_OBJ) $(TT_OBJ) $(LINKER_SCRIPT) linker/cortex-m.ld
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CPU) --specs=rdimon.specs -nostartfiles -Llinker -T $(LINKER_SCRIPT) \
	    -Wl,--gc-sections $(CORE_OBJ) $(TT_OBJ) -o $@
