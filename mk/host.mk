# SPDX-License-Identifier: BSD-2-Clause
# Linux host: the codec core, libbrdfwave and the brdfwave CLI.
CC ?= cc
OPT ?= -O2 -g
CFLAGS := $(WARN) $(OPT) $(CORE_INC) -Ifirmware/link -Ihost-tools/lib -Iinclude $(EXTRA_CFLAGS)
LDLIBS := -lm

# libbrdfwave: the codec core, the link frames and host-tools/lib, one list
# of sources for both libraries: its objects make libbrdfwave.a (the tools
# and tests link it), the same compiled position independent (build/host/pic)
# libbrdfwave.so (the Python package loads it). The static library's objects
# are not position independent: that costs the core about 2 % more
# instructions.
LIB_SRC := $(CORE_SRC) firmware/link/bw_frame.c $(wildcard host-tools/lib/*.c)
# the reference model's RGL loader and its projection of scattered
# directions onto the grid, for the library's readers of RGL and goniometer
# files (bwh_rgl.c, bwh_project.c): the same objects as libbwref's
LIB_REF_SRC := host-tools/ref/bwr_rgl.c host-tools/ref/bwr_project.c host-tools/ref/bwr_geodesic.c
LIB_SRC += $(LIB_REF_SRC)
LIB_REF_USERS := host-tools/lib/bwh_project.c host-tools/lib/bwh_rgl.c host-tools/lib/bwh_decode.c
$(patsubst %.c,$(BUILD)/%.o,$(LIB_REF_USERS)) $(patsubst %.c,$(BUILD)/pic/%.o,$(LIB_REF_USERS)): \
    CFLAGS += -Ihost-tools/ref
LIB_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(LIB_SRC))
LIB_PIC_OBJ := $(patsubst %.c,$(BUILD)/pic/%.o,$(LIB_SRC))
LIB := $(BUILD)/libbrdfwave.a
# the shared library: libbrdfwave.so.MAJOR (its SONAME) and the link
# libbrdfwave.so beside it, both from the version in include/brdfwave/brdfwave.h
VERSION := $(shell sed -n 's/^\#define BRDFWAVE_VERSION_STRING "\(.*\)"/\1/p' include/brdfwave/brdfwave.h)
SOVERSION := $(firstword $(subst ., ,$(VERSION)))
SONAME := libbrdfwave.so.$(SOVERSION)
SOLIB := $(BUILD)/$(SONAME)
PYLIB := $(BUILD)/libbrdfwave.so

$(BUILD)/pic/%.o: %.c $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  CC-PIC  $<")
	$(Q)$(CC) $(CFLAGS) -fPIC -MD -MP -c $< -o $@

# the command line's own modules: options, numbers, exit statuses, shape
# options (also linked into bwref)
CLIKIT_SRC := host-tools/cli/cli_args.c host-tools/cli/cli_num.c host-tools/cli/cli_errors.c \
              host-tools/cli/cli_shape.c host-tools/cli/cli_progress.c host-tools/cli/cli_kv.c
CLIKIT := $(BUILD)/libbwcli.a

# the renderer of `brdfwave render` (scene, tracer, materials, meshes,
# image, PNG): librender
RENDER_SRC := $(wildcard host-tools/render/*.c)
RENDER_LIB := $(BUILD)/librender.a

# the pictures of `brdfwave plot` (canvas, font, axes, hemisphere; the
# renderer's PNG writer): libplot
PLOT_SRC := $(wildcard host-tools/plot/*.c)
PLOT_LIB := $(BUILD)/libplot.a
$(patsubst %.c,$(BUILD)/%.o,$(PLOT_SRC)): CFLAGS += -Ihost-tools/render

$(PLOT_LIB): $(patsubst %.c,$(BUILD)/%.o,$(PLOT_SRC))
	$(Q)rm -f $@ && $(AR) rcs $@ $^

# brdfwave: main.c and one file per command (cmd_acquire.c: mk/hw.mk)
CLI_SRC := host-tools/cli/main.c host-tools/cli/cmd_encode.c host-tools/cli/cmd_decode.c \
           host-tools/cli/cmd_info.c host-tools/cli/cmd_compare.c host-tools/cli/cmd_grid.c \
           host-tools/cli/cmd_synth.c host-tools/cli/cmd_receive.c host-tools/cli/cmd_render.c \
           host-tools/cli/cmd_plot.c host-tools/cli/cmd_eval.c
CLI_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(CLI_SRC))
include mk/hw.mk
$(CLI_OBJ) $(patsubst %.c,$(BUILD)/%.o,$(CLIKIT_SRC)): CFLAGS += -Ihost-tools/cli -Ihost-tools/ref/cli
$(CLI_OBJ): CFLAGS += -Ihost-tools/render -Ihost-tools/plot
$(BUILD)/host-tools/cli/cmd_eval.o: CFLAGS += -Ihost-tools/ref

BW_CLI := $(BUILD)/brdfwave

# the device application as a host process (hal/linux), for tests
FWL_SRC := firmware/app/app.c firmware/app/main.c hal/linux/board.c hal/file_sensor.c
FWL_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(FWL_SRC))
FWL := $(BUILD)/brdfwave-fw-linux
$(FWL_OBJ): CFLAGS += -Ihal -Ifirmware/app

all: $(LIB) $(PYLIB) $(BW_CLI) $(FWL)

$(FWL): $(FWL_OBJ) $(LIB)
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CFLAGS) $(FWL_OBJ) $(LIB) $(LDLIBS) -o $@

$(LIB): $(LIB_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $^

$(SOLIB): $(LIB_PIC_OBJ)
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS) $^ -lm -o $@

$(PYLIB): $(SOLIB)
	$(Q)ln -sf $(SONAME) $@

$(CLIKIT): $(patsubst %.c,$(BUILD)/%.o,$(CLIKIT_SRC))
	$(Q)rm -f $@ && $(AR) rcs $@ $^

$(RENDER_LIB): $(patsubst %.c,$(BUILD)/%.o,$(RENDER_SRC))
	$(Q)rm -f $@ && $(AR) rcs $@ $^

# `brdfwave import-rgl` runs the reference model's importer (mk/ref.mk)
CLI_REF_OBJ := $(BUILD)/host-tools/ref/cli/cmd_rgl.o $(BUILD)/host-tools/ref/cli/bwref_io.o

$(BW_CLI): $(CLI_OBJ) $(CLI_REF_OBJ) $(CLIKIT) $(PLOT_LIB) $(RENDER_LIB) $(BUILD)/libbwref.a $(LIB)
	$(if $(Q),@echo "  LD      $@")
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) $(CLI_OBJ) $(CLI_REF_OBJ) $(CLIKIT) $(PLOT_LIB) $(RENDER_LIB) \
	    $(BUILD)/libbwref.a $(LIB) $(LDLIBS) -o $@

include mk/tests.mk
include mk/install.mk
include mk/pictures.mk
include mk/conformance.mk
include mk/deb.mk
include mk/ref.mk
-include mk/bench.mk
include mk/render.mk
-include mk/bench-rd.mk

run: deps-run all
	$(Q)$(MAKE) --no-print-directory TARGET=qemu all
	$(Q)host-tools/scripts/run.sh

deps-run:
	$(Q)tests/deps.sh run

# regenerate the committed geodesic tables of the core
$(BUILD)/gen_geodesic_tables: host-tools/gen/gen_geodesic_tables.c host-tools/lib/geodesic.c
	$(Q)$(CC) $(WARN) -O2 -Ihost-tools/lib $^ -lm -o $@

tables: $(BUILD)/gen_geodesic_tables
	$(Q)$< > firmware/codec/bw_geodesic_tables.c
	$(Q)$< --areas > firmware/codec/bw_geodesic_areas.c
