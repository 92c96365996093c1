#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""A scripted device on a pseudo-terminal, for `brdfwave receive`.

    fake_device.py PAYLOAD PTY_FILE LOG_FILE [MODE [PAYLOAD2]]

Writes the pty's path to PTY_FILE and a log of what it saw to LOG_FILE.
Modes:
  damaged     (default) the payload as id 7 after some line noise, with one
              chunk corrupted and one left out; answers the resend request;
              exit 0 once acknowledged.
  one-write   every frame of the payload (id 8) in a single write, so that
              the receiver gets them all in one read; exit 0 once acknowledged.
  stall       announces the payload (id 9), sends half of its chunks and then
              nothing new: it answers every request by repeating START and
              sending frames of an unknown type, which bring no progress.
              Exits 0 when the receiver has gone (the pty closed) within 60 s.
  later       the payload (id 10) without its chunk 2, deaf to requests while
              the receiver asks (it gives up and keeps what arrived); after a
              second of silence from the host it answers RESEND as a device
              that kept the payload does (`receive --resume`); exit 0 once
              acknowledged.
  twice       two payloads with the same id 1 (PAYLOAD, then PAYLOAD2), as a
              device counting from 1 again after a reboot would send them;
              exit 0 once both are acknowledged.
"""
import os, select, struct, sys, time, tty, zlib

SYNC = b'\xb5\x57'
MAXD = 1024


def frame(ftype, seq, data=b''):
    body = struct.pack('<BBHH', ftype, 0, seq, len(data)) + data
    return SYNC + body + struct.pack('<I', zlib.crc32(body) & 0xFFFFFFFF)


def start_frame(pid, payload, chunks):
    return frame(0x10, 0, struct.pack('<IIHIII', pid, len(payload), len(chunks),
                                      zlib.crc32(payload) & 0xFFFFFFFF, 123, 0))


class Host:
    """Frames from the receiver."""

    def __init__(self, fd, log):
        self.fd, self.log, self.buf = fd, log, b''

    def frames(self, wait):
        r, _, _ = select.select([self.fd], [], [], wait)
        if not r:
            return []
        self.buf += os.read(self.fd, 4096)
        out = []
        while True:
            i = self.buf.find(SYNC)
            if i < 0 or len(self.buf) < i + 8:
                break
            ftype, _, seq, n = struct.unpack('<BBHH', self.buf[i + 2:i + 8])
            if len(self.buf) < i + 12 + n:
                break
            data = self.buf[i + 8:i + 8 + n]
            crc, = struct.unpack('<I', self.buf[i + 8 + n:i + 12 + n])
            self.buf = self.buf[i + 12 + n:]
            if zlib.crc32(struct.pack('<BBHH', ftype, 0, seq, n) + data) & 0xFFFFFFFF != crc:
                self.log.write('bad frame from the host\n')
                continue
            out.append((ftype, data))
        return out


def serve(master, host, log, pid, payload, first_write, deadline=20):
    """Sends first_write, then answers RESEND until the payload is acknowledged."""
    chunks = [payload[i:i + MAXD] for i in range(0, len(payload), MAXD)]
    os.write(master, first_write)
    t_end = time.time() + deadline
    while time.time() < t_end:
        for ftype, data in host.frames(0.2):
            if ftype == 0x21:
                asked = [struct.unpack('<H', data[k:k + 2])[0] for k in range(4, len(data), 2)]
                log.write('RESEND %s\n' % asked)
                for c in (asked or range(len(chunks))):
                    os.write(master, frame(0x11, c, chunks[c]))
                os.write(master, frame(0x12, 0, struct.pack('<I', pid)))
            elif ftype == 0x20:
                log.write('ACK %d\n' % struct.unpack('<I', data)[0])
                return True
    log.write('no acknowledgement\n')
    return False


def main():
    payload = open(sys.argv[1], 'rb').read()
    mode = sys.argv[4] if len(sys.argv) > 4 else 'damaged'
    log = open(sys.argv[3], 'w', buffering=1)
    master, slave = os.openpty()
    tty.setraw(slave)
    open(sys.argv[2], 'w').write(os.ttyname(slave))
    host = Host(master, log)
    chunks = [payload[i:i + MAXD] for i in range(0, len(payload), MAXD)]
    assert len(chunks) >= 3, 'payload too small for this script'
    time.sleep(0.3)  # let the receiver open the port

    if mode == 'damaged':
        pid = 7
        w = b'\x00\xb5\x13noise\xb5' + start_frame(pid, payload, chunks)
        for c in range(len(chunks)):
            if c == 2:
                continue  # lost
            f = bytearray(frame(0x11, c, chunks[c]))
            if c == 1:
                f[20] ^= 0x40  # inside the data: the frame CRC no longer matches
            w += bytes(f)
        w += frame(0x12, 0, struct.pack('<I', pid))
        return 0 if serve(master, host, log, pid, payload, w) else 1

    if mode == 'one-write':
        pid = 8
        w = start_frame(pid, payload, chunks)
        w += b''.join(frame(0x11, c, chunks[c]) for c in range(len(chunks)))
        w += frame(0x12, 0, struct.pack('<I', pid))
        return 0 if serve(master, host, log, pid, payload, w) else 1

    if mode == 'later':
        pid = 10
        w = start_frame(pid, payload, chunks)
        w += b''.join(frame(0x11, c, chunks[c]) for c in range(len(chunks)) if c != 2)
        os.write(master, w + frame(0x12, 0, struct.pack('<I', pid)))
        quiet = time.time()
        while time.time() - quiet < 1.0:
            for ftype, data in host.frames(0.1):
                log.write('deaf to %s\n' % {0x21: 'RESEND', 0x20: 'ACK'}.get(ftype, hex(ftype)))
                quiet = time.time()
        log.write('listening again\n')
        return 0 if serve(master, host, log, pid, payload, b'', deadline=40) else 1

    if mode == 'twice':
        second = open(sys.argv[5], 'rb').read()
        for p in (payload, second):
            ch = [p[i:i + MAXD] for i in range(0, len(p), MAXD)]
            w = start_frame(1, p, ch) + b''.join(frame(0x11, c, ch[c]) for c in range(len(ch)))
            w += frame(0x12, 0, struct.pack('<I', 1))
            if not serve(master, host, log, 1, p, w):
                return 1
        return 0

    if mode == 'stall':
        pid = 9
        w = start_frame(pid, payload, chunks)
        w += b''.join(frame(0x11, c, chunks[c]) for c in range(len(chunks) // 2))
        os.write(master, w)
        t_end = time.time() + 60
        while time.time() < t_end:
            for ftype, data in host.frames(0.2) or []:
                log.write('%s\n' % {0x21: 'RESEND', 0x20: 'ACK'}.get(ftype, hex(ftype)))
            # frames that make no progress, several times a second
            os.write(master, start_frame(pid, payload, chunks) + frame(0x7F, 0, b'?'))
        return 0

    log.write('unknown mode %s\n' % mode)
    return 2


sys.exit(main())
