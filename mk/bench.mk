# SPDX-License-Identifier: BSD-2-Clause
# Codec benchmark: brdfwave against JPEG-LS (CharLS), OpenJPEG, ZFP, libaec,
# xz and zstd on the field spectra and the paper's synthetic BRDF sets.
# Writes build/bench/codec.md and build/bench/codec.csv.
#
# Included by the top-level Makefile, which sets BW_CLI (the brdfwave host
# tool, build/host/brdfwave) and its build rule.

BENCH_DIR      ?= build/bench
BENCH_HOST_CC  ?= gcc
BENCH_PYTHON   ?= /usr/bin/python3
BENCH_JPEGLS   := $(BENCH_DIR)/peer_jpegls

$(BENCH_JPEGLS): tests/bench/peer_jpegls.c
	@mkdir -p $(dir $@)
	$(BENCH_HOST_CC) -O2 -std=c11 -Wall -Wextra tests/bench/peer_jpegls.c -lcharls -o $@ || \
	  { rm -f $@; echo "bench: cannot build $@ (CharLS missing? apt-get install libcharls-dev);" \
	    "the JPEG-LS peer will be skipped" >&2; }

.PHONY: bench
bench: $(BW_CLI) $(BENCH_JPEGLS)
	BW=$(BW_CLI) PEER_JPEGLS=$(BENCH_JPEGLS) $(BENCH_PYTHON) tests/bench/run_codec_bench.py

include mk/bench-device.mk
