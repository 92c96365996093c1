# brdfwave: one entry point.
#   make                 host library and CLI (build/host)
#   make check           every test (installs missing Debian packages first)
#   make run             the main job end to end (see README)
#   make bench           benchmark report build/bench/codec.md
#   make TARGET=qemu     the codec core for the emulated Cortex-M4 board
#   make TARGET=mcu      the codec core for the real MCU (build only)
# V=1 shows the commands.

TARGET ?= host
ifeq ($(filter $(TARGET),host qemu mcu),)
$(error TARGET must be host, qemu or mcu)
endif

BUILD := build/$(TARGET)
Q := $(if $(filter 1,$(V)),,@)

CORE_SRC := $(wildcard firmware/codec/*.c)
CORE_INC := -Ifirmware/codec
WARN := -std=c11 -Wall -Wextra -Wshadow -Wstrict-prototypes -Werror

CORE_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(CORE_SRC))

include mk/$(TARGET).mk

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -MD -MP -c $< -o $@

-include $(shell find build -name '*.d' 2>/dev/null)

.PHONY: all clean check run bench deps deps-run fuzz tests tables target-tests help spdx
.DEFAULT_GOAL := all

clean:
	rm -rf build

# adds the licence's SPDX line to source files without one (scripts/spdx-check)
spdx:
	$(Q)scripts/spdx-check --add

help:
	@sed -n '2,9p' Makefile
