# QEMU mps2-an386 (Cortex-M4F): the codec core as a static library.
CROSS_COMPILE ?= arm-none-eabi-
CC := $(CROSS_COMPILE)gcc
AR := $(CROSS_COMPILE)ar
CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
OPT ?= -O2
CFLAGS := $(WARN) $(OPT) $(CPU) -ffreestanding -ffunction-sections -fdata-sections $(CORE_INC)
LINKER_SCRIPT := linker/mps2-an386.ld

all: $(BUILD)/libbwcore.a

$(BUILD)/libbwcore.a: $(CORE_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^
