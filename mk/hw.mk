# SPDX-License-Identifier: BSD-2-Clause
# Acquisition over I2C with a data-ready line (docs/I2C.md): `brdfwave
# acquire` (libgpiod + i2c-dev), the Python package's tests (it loads
# libbrdfwave.so, mk/host.mk) and the VM tests against the kernel's i2c-stub
# and gpio-sim drivers (`make check-hw`, tests/hw/run.sh).
#
# Included by mk/host.mk before the CLI's link rule.

# brdfwave acquire: needs libgpiod 1.6 (libgpiod-dev); without it the command
# says so and fails.
#
# What the build probes is recorded in $(FEATURES_H), rewritten only when an
# answer changes; the objects that include it depend on it, so installing or
# removing an optional library rebuilds what it affects on the next make.
CLI_OBJ += $(BUILD)/host-tools/cli/cmd_acquire.o
FEATURES_H := $(BUILD)/gen/bw_features.h
HAVE_GPIOD := $(shell pkg-config --exists 'libgpiod >= 1.6' 'libgpiod < 2' 2>/dev/null && echo 1 || echo 0)
FEATURES := /* made by the build (mk/hw.mk): what it found on this machine */\n$\
            \#define BW_HAVE_GPIOD $(HAVE_GPIOD)
$(shell mkdir -p $(BUILD)/gen && printf '$(FEATURES)\n' >$(FEATURES_H).new && \
        { cmp -s $(FEATURES_H).new $(FEATURES_H) && rm -f $(FEATURES_H).new || \
          mv -f $(FEATURES_H).new $(FEATURES_H); })
$(BUILD)/host-tools/cli/cmd_acquire.o: $(FEATURES_H)
$(BUILD)/host-tools/cli/cmd_acquire.o: CFLAGS += -I$(BUILD)/gen
ifeq ($(HAVE_GPIOD),1)
$(BUILD)/brdfwave: LDLIBS += -lgpiod
else
all: features-note
endif

.PHONY: features-note
features-note: $(BUILD)/brdfwave
	@echo "brdfwave: 'brdfwave acquire' left out: libgpiod 1.6 not found (apt-get install libgpiod-dev, then make)"

.PHONY: pylib check-hw check-py
pylib: $(PYLIB)

check-py: $(PYLIB) $(BUILD)/brdfwave
	$(Q)/usr/bin/python3 tests/python/test_package.py

check-hw: all
	$(Q)tests/deps.sh hw
	$(Q)tests/hw/run.sh
