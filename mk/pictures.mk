# SPDX-License-Identifier: BSD-2-Clause
# make pictures: the README's pictures of `brdfwave plot`, from the shared
# data (writes the tracked docs/img/plot_*.png; the work in build/pictures): a BRDF,
# an incidence of it in 8 segments whole and cut, and embedded and cut, field
# spectra, their curve
PIC_DIR := $(BUILD)/pictures
FIELD_SED := $(sort $(wildcard tests/data/field_psr3500/*.sed))

pictures: $(BW_CLI)
	@mkdir -p $(PIC_DIR) docs/img
	$(Q)$(BW_CLI) import-rgl -i tests/data/rgl/satin_rosaline_rgb.bsdf -o $(PIC_DIR)/satin.f32 \
	    --channel g --incoming 16 >/dev/null
	$(Q)$(BW_CLI) encode -q -i $(PIC_DIR)/satin.f32 -o $(PIC_DIR)/satin.bwv --bands 1 --level 4 \
	    --incoming 16 --ratio 20
	$(Q)$(BW_CLI) plot hemisphere -i $(PIC_DIR)/satin.bwv --theta-in 45 --log \
	    --title "RGL satin_rosaline (green), ratio 20: incoming theta 42.2 deg" \
	    -o docs/img/plot_hemisphere.png
	$(Q)$(BW_CLI) import-rgl -i tests/data/rgl/satin_rosaline_rgb.bsdf -o $(PIC_DIR)/satin6.f32 \
	    --channel g --incoming 16 --level 6 >/dev/null
	$(Q)tail -c +$$((7 * 65536 + 1)) $(PIC_DIR)/satin6.f32 | head -c 65536 >$(PIC_DIR)/theta42.f32
	$(Q)$(BW_CLI) encode -q -i $(PIC_DIR)/theta42.f32 -o $(PIC_DIR)/theta42.bwv --bands 1 \
	    --level 6 --max-error 0.001 --segments 8
	$(Q)head -c 1464 $(PIC_DIR)/theta42.bwv >$(PIC_DIR)/cut.bwv
	$(Q)$(BW_CLI) plot hemisphere -i $(PIC_DIR)/theta42.bwv --log \
	    --title "satin, theta_i 42.2 deg, level 6: 8 segments, whole" \
	    -o docs/img/plot_segments_whole.png
	$(Q)$(BW_CLI) plot hemisphere -i $(PIC_DIR)/cut.bwv --log \
	    --title "the same cut to 1464 bytes (40 %): coarser levels" \
	    -o docs/img/plot_segments_cut.png 2>/dev/null
	$(Q)$(BW_CLI) encode -q -i $(PIC_DIR)/theta42.f32 -o $(PIC_DIR)/theta42e.bwv --bands 1 \
	    --level 6 --max-error 0.001 --progressive
	$(Q)head -c 1464 $(PIC_DIR)/theta42e.bwv >$(PIC_DIR)/cute.bwv
	$(Q)$(BW_CLI) plot hemisphere -i $(PIC_DIR)/cute.bwv --log \
	    --title "the same, embedded (--progressive), cut to 1464 bytes" \
	    -o docs/img/plot_embedded_cut.png 2>/dev/null
	$(Q)$(BW_CLI) encode -q --input-format sed -i $(FIELD_SED) -o $(PIC_DIR)/field.bwv \
	    --max-error 0.0005
	$(Q)$(BW_CLI) plot spectra --input-format sed -i $(FIELD_SED) --payload $(PIC_DIR)/field.bwv \
	    --spectrum 0 --spectrum 30 -o docs/img/plot_spectra.png
	$(Q)$(BW_CLI) plot rd --input-format sed -i $(FIELD_SED) \
	    --title "60 field spectra (PSR-3500), 1024 bands: byte budgets of ratio 2 to 256" \
	    -o docs/img/plot_rd.png >$(PIC_DIR)/rd.csv

.PHONY: pictures
