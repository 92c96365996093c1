#!/usr/bin/python3
"""A scripted device on a pseudo-terminal, for `brdfwave receive`.

Sends a payload (argv[1]) as id 7 in link frames, after some line noise,
with one chunk corrupted and one left out, answers the receiver's resend
request, and waits for its acknowledgement. Writes the pty's path to argv[2]
and a log of what it saw to argv[3]. Exit 0 once acknowledged.
"""
import os, select, struct, sys, time, tty, zlib

SYNC = b'\xb5\x57'
MAXD = 1024


def frame(ftype, seq, data=b''):
    body = struct.pack('<BBHH', ftype, 0, seq, len(data)) + data
    return SYNC + body + struct.pack('<I', zlib.crc32(body) & 0xFFFFFFFF)


def main():
    payload = open(sys.argv[1], 'rb').read()
    log = open(sys.argv[3], 'w')
    master, slave = os.openpty()
    tty.setraw(slave)
    open(sys.argv[2], 'w').write(os.ttyname(slave))
    chunks = [payload[i:i + MAXD] for i in range(0, len(payload), MAXD)]
    assert len(chunks) >= 3, 'payload too small for this script'
    pid = 7

    def send_chunk(c, corrupt=False):
        f = bytearray(frame(0x11, c, chunks[c]))
        if corrupt:
            f[20] ^= 0x40  # inside the data: the frame CRC no longer matches
        os.write(master, bytes(f))

    time.sleep(0.3)  # let the receiver open the port
    os.write(master, b'\x00\xb5\x13noise\xb5')
    start = struct.pack('<IIHIII', pid, len(payload), len(chunks), zlib.crc32(payload) & 0xFFFFFFFF, 123, 0)
    os.write(master, frame(0x10, 0, start))
    for c in range(len(chunks)):
        if c == 2:
            continue  # lost
        send_chunk(c, corrupt=(c == 1))
    os.write(master, frame(0x12, 0, struct.pack('<I', pid)))

    buf = b''
    deadline = time.time() + 20
    while time.time() < deadline:
        r, _, _ = select.select([master], [], [], 0.2)
        if not r:
            continue
        buf += os.read(master, 4096)
        while True:
            i = buf.find(SYNC)
            if i < 0 or len(buf) < i + 8:
                break
            ftype, _, seq, n = struct.unpack('<BBHH', buf[i + 2:i + 8])
            if len(buf) < i + 12 + n:
                break
            data = buf[i + 8:i + 8 + n]
            crc, = struct.unpack('<I', buf[i + 8 + n:i + 12 + n])
            buf = buf[i + 12 + n:]
            if zlib.crc32(struct.pack('<BBHH', ftype, 0, seq, n) + data) & 0xFFFFFFFF != crc:
                log.write('bad frame from the host\n')
                continue
            if ftype == 0x21:
                asked = [struct.unpack('<H', data[k:k + 2])[0] for k in range(4, len(data), 2)]
                log.write('RESEND %s\n' % asked)
                for c in (asked or range(len(chunks))):
                    send_chunk(c)
                os.write(master, frame(0x12, 0, struct.pack('<I', pid)))
            elif ftype == 0x20:
                log.write('ACK %d\n' % struct.unpack('<I', data)[0])
                log.close()
                return 0
    log.write('no acknowledgement\n')
    return 1


sys.exit(main())
