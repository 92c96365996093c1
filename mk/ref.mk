# SPDX-License-Identifier: BSD-2-Clause
# Float reference model of the paper (host-tools/ref): libbwref, the bwref
# tool, its tests and `make reproduce` (build/report/paper.md).
# The model shares no code with firmware/codec or libbrdfwave, only the
# numbering of the triangles: its objects are compiled without their include
# paths. The bwref tool is a command line like brdfwave's: it uses the
# command line's modules (libbwcli) and the shape rule of libbrdfwave.
REF_SRC := $(wildcard host-tools/ref/bwr_*.c)
REF_CLI_SRC := $(wildcard host-tools/ref/cli/*.c)
REF_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(REF_SRC))
REF_CLI_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(REF_CLI_SRC))
REF_LIB := $(BUILD)/libbwref.a
REF_CLI := $(BUILD)/bwref
REF_INC := -Ihost-tools/ref

$(REF_OBJ): CFLAGS := $(WARN) $(OPT) $(EXTRA_CFLAGS) $(REF_INC)
$(REF_CLI_OBJ): CFLAGS += $(REF_INC) -Ihost-tools/cli

all: $(REF_LIB) $(REF_CLI)

$(REF_LIB): $(REF_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^

$(REF_CLI): $(REF_CLI_OBJ) $(REF_LIB) $(CLIKIT) $(LIB)
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CFLAGS) $(REF_CLI_OBJ) $(REF_LIB) $(CLIKIT) $(LIB) -lm -o $@

REF_TESTS := $(patsubst tests/ref/%.c,$(BUILD)/tests/%,$(wildcard tests/ref/test_ref_*.c))

$(REF_TESTS): $(BUILD)/tests/%: tests/ref/%.c $(REF_LIB)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(CFLAGS) $(REF_INC) $< $(REF_LIB) -lcmocka -lm -o $@

# the codec core's integer transforms, its host grid and the product's
# interpolation against the reference: these tests link both (the reference
# library itself does not)
REF_CORE_TESTS := $(BUILD)/tests/test_fixed_vs_ref $(BUILD)/tests/test_grid_vs_ref \
                  $(BUILD)/tests/test_interp_vs_ref

$(REF_CORE_TESTS): $(BUILD)/tests/%: tests/ref/%.c $(REF_LIB) $(LIB)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(CFLAGS) $(REF_INC) $< $(REF_LIB) $(LIB) -lcmocka -lm -o $@

tests: $(REF_TESTS) $(REF_CORE_TESTS) $(REF_CLI)

# regenerate the committed filter tables
ref-filters:
	$(Q)/usr/bin/python3 host-tools/ref/gen/gen_filters.py > host-tools/ref/bwr_filters.c

# the paper's results, build/report/paper.md
reproduce: all
	$(Q)tests/deps.sh reproduce
	$(Q)BW=$(BW_CLI) BWREF=$(REF_CLI) /usr/bin/python3 host-tools/ref/report.py

.PHONY: ref-filters reproduce
