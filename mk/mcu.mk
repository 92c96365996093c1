# A real MCU: STM32L476 (Cortex-M4F, 1 MiB flash, 128 KiB SRAM), build only.
CROSS_COMPILE ?= arm-none-eabi-
CC := $(CROSS_COMPILE)gcc
AR := $(CROSS_COMPILE)ar
CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
OPT ?= -Os
CFLAGS := $(WARN) $(OPT) $(CPU) -ffreestanding -ffunction-sections -fdata-sections $(CORE_INC)
LINKER_SCRIPT := linker/stm32l476.ld

all: $(BUILD)/libbwcore.a

$(BUILD)/libbwcore.a: $(CORE_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^
