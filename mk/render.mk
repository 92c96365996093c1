# SPDX-License-Identifier: BSD-2-Clause
# `brdfwave render` (librender, mk/host.mk): its libraries, the mesh test,
# the sampling unit test (it reads a measured RGL BRDF with the reference
# model's loader, so it links libbwref too) and `make bench-render`
# (mk/bench-render.mk).
$(BW_CLI): LDLIBS += -lz -lpthread

$(BUILD)/tests/test_mesh: tests/unit/test_mesh.c $(RENDER_LIB) $(LIB)
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(TEST_CFLAGS) -Ihost-tools/render -MMD -MP $< $(RENDER_LIB) $(LIB) $(TEST_LIBS) -o $@

$(BUILD)/tests/test_sample: tests/unit/test_sample.c $(LIB) $(BUILD)/libbwref.a
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(TEST_CFLAGS) -Ihost-tools/ref -MMD -MP $< $(LIB) $(BUILD)/libbwref.a $(TEST_LIBS) -o $@

include mk/bench-render.mk
