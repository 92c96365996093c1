# SPDX-License-Identifier: BSD-2-Clause
# Rate-distortion benchmark with targets: brdfwave against JPEG-LS (CharLS),
# OpenJPEG, ZFP, libaec, xz and zstd on the synthetic, field, Spectralon and
# RGL sets. Writes build/bench/rd.md, rd.csv and one rd_<set>.png per set.
# Uses BW_CLI (mk/host.mk) and the JPEG-LS helper of mk/bench.mk.

.PHONY: bench-rd bench-rd-deps
bench-rd-deps:
	$(Q)tests/deps.sh bench

bench-rd: bench-rd-deps $(BW_CLI)
	$(Q)$(MAKE) --no-print-directory $(BENCH_JPEGLS)
	BW=$(BW_CLI) PEER_JPEGLS=$(BENCH_JPEGLS) $(BENCH_PYTHON) tests/bench/run_rd_bench.py

# The per-sample guarantees of float input (lossless bit for bit, the
# relative bound) against ZFP: build/bench/guarantee.md. Runs alone in
# seconds; bench-rd runs it too.
.PHONY: bench-guarantee
bench-guarantee: bench-rd-deps $(BW_CLI)
	BW=$(BW_CLI) $(BENCH_PYTHON) tests/bench/run_guarantee_bench.py

bench-rd: bench-guarantee

# Payloads in segments: their cost in bytes, what a lost segment or 1 KiB
# chunk costs in samples, and what they cost the emulated board's streaming
# encoder (build/bench/progressive.md; QEMU from deps-run).
.PHONY: bench-progressive
bench-progressive: deps-run $(BW_CLI) $(PYLIB)
	$(Q)$(MAKE) --no-print-directory TARGET=qemu all
	BW=$(BW_CLI) $(BENCH_PYTHON) tests/bench/run_progressive_bench.py
