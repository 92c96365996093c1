# SPDX-License-Identifier: BSD-2-Clause
"""The package's version; the payload format it writes is 7 (docs/FORMAT.md)."""
__version__ = "0.7.0"
FORMAT_VERSION = 7
