#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# `make check`: the fuzz targets rebuilt as ordinary programs (gcc, ASan + UBSan)
# and run once on every corpus input. See tests/fuzz/run.sh.
set -eu
exec "$(dirname "$0")/run.sh" --replay
