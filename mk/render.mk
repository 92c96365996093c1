# Importance sampling (bw_sample.c), BRDF evaluation of decoded data
# (brdf_eval.c, which uses the reference model's interpolants) and
# `brdfwave render`: extra flags and libraries, the sampling unit test (it
# links libbwref too) and `make bench-render` (mk/bench-render.mk).
$(BUILD)/host-tools/src/brdf_eval.o $(BUILD)/host-tools/src/cmd_render.o: CFLAGS += -Ihost-tools/ref
$(BW_CLI): LDLIBS += $(BUILD)/libbwref.a -lz -lpthread

$(BUILD)/tests/test_sample: tests/unit/test_sample.c $(LIB) $(BUILD)/libbwref.a
	@mkdir -p $(dir $@)
	$(if $(Q),@echo "  TEST-CC $@")
	$(Q)$(CC) $(TEST_CFLAGS) -Ihost-tools/ref -MMD -MP $< $(LIB) $(BUILD)/libbwref.a $(TEST_LIBS) -o $@

include mk/bench-render.mk
