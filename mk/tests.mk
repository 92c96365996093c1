# SPDX-License-Identifier: BSD-2-Clause
# Tests (host). `make check` runs them all and ends with one summary line.
TEST_CFLAGS := $(CFLAGS) -Itests/unit
TEST_LIBS := -lcmocka -lm

UNIT_TESTS := $(patsubst tests/unit/%.c,%,$(wildcard tests/unit/test_*.c))
UNIT_BIN := $(addprefix $(BUILD)/tests/,$(UNIT_TESTS))

# tests that need host-tools sources besides the library
$(BUILD)/tests/%: tests/unit/%.c $(LIB)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(TEST_CFLAGS) -MMD -MP $< $(LIB) $(TEST_LIBS) -o $@

# the device application against a scripted link (it includes app.c)
$(BUILD)/tests/test_app: TEST_CFLAGS += -Ihal -Ifirmware/app

# the firmware's I2C register window read by the host's I2C client
$(BUILD)/tests/test_i2cwin: tests/unit/test_i2cwin.c firmware/link/bw_i2cwin.c $(LIB)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(TEST_CFLAGS) $< firmware/link/bw_i2cwin.c $(LIB) $(TEST_LIBS) -o $@

tests: $(UNIT_BIN)

deps:
	$(Q)tests/deps.sh

check: deps
	$(Q)$(MAKE) --no-print-directory all tests
	$(Q)tests/run.sh

# coverage-guided fuzzing of the decoder and the round trip (clang, libFuzzer)
fuzz:
	$(Q)tests/deps.sh fuzz
	$(Q)tests/fuzz/run.sh
