# SPDX-License-Identifier: BSD-2-Clause
# make conformance: writes the conformance vectors of tests/conformance/
# (payloads, their samples and headers; docs/FORMAT.md) with this build's
# encoder. They are committed; make check decodes them (check.py).
conformance: $(BW_CLI)
	$(Q)BW=$(BW_CLI) tests/conformance/gen.sh >/dev/null

.PHONY: conformance
