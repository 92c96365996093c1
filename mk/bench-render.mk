# SPDX-License-Identifier: BSD-2-Clause
# `make bench-render`: the paper's path-tracing comparison (sec. 6.2) with
# brdfwave render, and the sampling throughput of the hierarchy against a
# linear scan. Writes build/bench/render.md with the images beside it in
# build/bench/render/. Included by mk/render.mk (host build).
BR_DIR := build/bench/render
BR_SAMPLING := $(BR_DIR)/bench_sampling

$(BR_SAMPLING): tests/bench/render/bench_sampling.c $(LIB)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS) -Itests/unit $< $(LIB) -lm -o $@

.PHONY: bench-render
bench-render: $(BW_CLI) $(BR_SAMPLING)
	$(Q)tests/deps.sh check
	$(Q)BW=$(BW_CLI) BENCH_SAMPLING=$(BR_SAMPLING) /usr/bin/python3 tests/bench/render/run_render_bench.py
