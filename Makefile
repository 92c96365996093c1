# SPDX-License-Identifier: BSD-2-Clause
# brdfwave: one entry point (`make help` lists every goal).
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
# -Werror in the project's own checks (`make check`, CI), not in a user's
# build: `make check` sets it for itself, its sub-makes and its scripts
WERROR ?= $(if $(filter check,$(MAKECMDGOALS)),-Werror)
export WERROR
WARN := -std=c11 -Wall -Wextra -Wshadow -Wstrict-prototypes $(WERROR)

CORE_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(CORE_SRC))

# the objects are rebuilt when -Werror comes or goes (a dry run, make -n,
# leaves the stamp alone)
FLAGS_STAMP := $(BUILD)/gen/werror
ifeq ($(findstring n,$(firstword -$(MAKEFLAGS))),)
$(shell mkdir -p $(BUILD)/gen && { [ -f $(FLAGS_STAMP) ] && [ "$$(cat $(FLAGS_STAMP))" = "$(WERROR)" ] || \
        echo "$(WERROR)" >$(FLAGS_STAMP); })
endif

include mk/$(TARGET).mk

$(BUILD)/%.o: %.c $(FLAGS_STAMP)
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
	@cat mk/help.txt
