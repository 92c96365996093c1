#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""add_ext.py IN.bwv OUT.bwv TYPE HEXDATA: IN (version 6) as a version-7
payload with one extension record of TYPE and those bytes after the
header's fields (docs/FORMAT.md, Extensions); the body is unchanged and the
CRC-32 is computed again. For the conformance vectors and their check."""
import struct
import sys
import zlib


def varint(v):
    out = bytearray()
    while True:
        b = v & 0x7F
        v >>= 7
        out.append(b | (0x80 if v else 0))
        if not v:
            return bytes(out)


def skip_varint(p, k):
    while p[k] & 0x80:
        k += 1
    return k + 1


def header_len(p):
    k = 7
    k = skip_varint(p, k)  # n_in
    k = skip_varint(p, k)  # bands
    if (p[3] >> 2) & 3:  # the parameter: not in lossless mode
        k = skip_varint(p, k)
    if p[3] & 0x40:  # scale
        k += 4
    if p[3] & 0x80:  # offset
        k += 4
    return k


def with_ext(p, typ, data):
    assert p[:2] == b"BW" and p[2] == 6 and not p[5] & 0x40, "not a version-6 payload"
    n = header_len(p)
    rec = bytes([typ]) + varint(len(data)) + data
    head = bytearray(p[:n])
    head[2] = 7
    head[5] |= 0x40
    body = bytes(head) + varint(len(rec)) + rec + p[n:-4]
    return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)


if __name__ == "__main__":
    src, dst, typ, hexdata = sys.argv[1:]
    out = with_ext(open(src, "rb").read(), int(typ, 0), bytes.fromhex(hexdata))
    open(dst, "wb").write(out)
