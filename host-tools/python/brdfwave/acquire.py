"""Acquisition service: payloads from the co-processor over I2C/SMBus.

    python3 -m brdfwave.acquire --bus 1 --addr 0x42 --chip gpiochip0 --line 17 --out DIR

Waits for a rising edge of the data-ready line (libgpiod 1.6 edge events, with
a timeout), reads the offered payload page by page through the register
window of docs/I2C.md (smbus2), checks every page's CRC-32 (a bad page is
asked for again, RETRY), the whole payload's CRC-32 and header, and decodes it
(libbrdfwave), stores it as DIR/payload-ID-CRC.bwv through a temporary file,
fsync and a link that never replaces a file, and only then acknowledges it. A
payload that never verifies or does not decode is not acknowledged and not
stored. SIGTERM or SIGINT stop the service between two transfers.
"""
import argparse
import errno
import os
import signal
import sys
import time
import zlib

from . import i2cmap as M

NAK_ERRNOS = (errno.ENXIO, errno.ENODEV, errno.EREMOTEIO, errno.EIO, errno.ETIMEDOUT,
              errno.EAGAIN)


class AcquireError(Exception):
    """The offered payload could not be read and verified (not acknowledged)."""


class Stopped(Exception):
    """SIGTERM or SIGINT arrived while a payload was being read."""


def _nak(addr, bus_name, e):
    if e.errno in NAK_ERRNOS:
        return AcquireError("no answer from the device at 0x%02x on %s (NAK: %s)"
                            % (addr, bus_name, os.strerror(e.errno)))
    return AcquireError("I2C transfer to 0x%02x on %s failed: %s" % (addr, bus_name, e))


class Device:
    """The register map of docs/I2C.md on an SMBus (smbus2.SMBus or alike)."""

    def __init__(self, bus, addr, bus_name="the bus"):
        self.bus, self.addr, self.bus_name = bus, addr, bus_name

    def word(self, reg):
        try:
            return self.bus.read_word_data(self.addr, reg)
        except OSError as e:
            raise _nak(self.addr, self.bus_name, e) from None

    def u32(self, lo):
        return self.word(lo) | self.word(lo + 1) << 16

    def write_byte(self, reg, v):
        try:
            self.bus.write_byte_data(self.addr, reg, v)
        except OSError as e:
            raise _nak(self.addr, self.bus_name, e) from None

    def write_word(self, reg, v):
        try:
            self.bus.write_word_data(self.addr, reg, v)
        except OSError as e:
            raise _nak(self.addr, self.bus_name, e) from None

    def wait_zero(self, reg, timeout):
        t_end = time.monotonic() + timeout
        while True:
            if self.word(reg) == 0:
                return True
            if time.monotonic() > t_end:
                return False
            time.sleep(0.005)


def read_page(dev, p, pages, page_size):
    """One page: (bytes, page CRC as served) after selecting it."""
    if pages > 255:
        dev.write_byte(M.PAGE_HI, p >> 8)
    dev.write_byte(M.PAGE, p & 0xFF)
    pnum = dev.word(M.PNUM)
    if pnum != p:
        raise AcquireError("page %d: the window shows page %d" % (p, pnum))
    plen = dev.word(M.PLEN)
    if not 1 <= plen <= page_size:
        raise AcquireError("page %d: length %d out of range" % (p, plen))
    crc = dev.u32(M.PCRC_LO)
    data = bytearray()
    for k in range((plen + 1) // 2):
        w = dev.word(M.DATA + k)
        data += bytes((w & 0xFF, w >> 8))
    return bytes(data[:plen]), crc


def read_payload(dev, retries=3, retry_wait=1.0, log=None, stop=None, max_samples=0):
    """Reads and verifies the offered payload; returns (id, bytes, page retries).
    Raises AcquireError when it is not offered or never verifies."""
    log = log or (lambda msg: None)
    magic = dev.word(M.MAGIC)
    if magic != M.MAGIC_VALUE:
        raise AcquireError("device at 0x%02x is not a brdfwave co-processor (MAGIC 0x%04x)"
                           % (dev.addr, magic))
    version = dev.word(M.VERSION)
    page_size = version >> 8
    if version & 0xFF != M.MAP_VERSION or not 2 <= page_size <= 32 or page_size % 2:
        raise AcquireError("unsupported register map (VERSION 0x%04x)" % version)
    status = dev.word(M.STATUS)
    if not status & M.ST_READY:
        err = ""
        if status & M.ST_ERROR:
            code = dev.word(M.ERRCODE)
            err = ": the last job failed with status %d" % (code - 0x10000 if code & 0x8000
                                                            else code)
        raise AcquireError("no payload offered (STATUS 0x%02x)%s" % (status, err))
    pid = dev.u32(M.ID_LO)
    length = dev.u32(M.LEN_LO)
    pages = dev.word(M.PAGES)
    crc = dev.u32(M.CRC_LO)
    if length == 0 or pages != (length + page_size - 1) // page_size:
        raise AcquireError("payload %d: length %d does not match %d pages" % (pid, length, pages))
    out = bytearray()
    bad_pages = 0
    try:
        for p in range(1, pages + 1):
            for attempt in range(retries + 1):
                if stop and stop():
                    raise Stopped()
                data, pcrc = read_page(dev, p, pages, page_size)
                want = page_size if p < pages else length - page_size * (pages - 1)
                if len(data) == want and zlib.crc32(data) == pcrc:
                    break
                bad_pages += 1
                if attempt == retries:
                    raise AcquireError("payload %d: page %d failed its CRC-32 %d times; "
                                       "payload not acknowledged" % (pid, p, retries + 1))
                log("payload %d: page %d failed its CRC-32, asking again (%d/%d)"
                    % (pid, p, attempt + 1, retries))
                dev.write_word(M.RETRY, p)
                if not dev.wait_zero(M.RETRY, retry_wait):
                    raise AcquireError("payload %d: the device did not answer RETRY of page %d"
                                       % (pid, p))
            out += data
    finally:
        try:
            dev.write_byte(M.PAGE, 0)
        except AcquireError:
            pass
    payload = bytes(out)
    if zlib.crc32(payload) != crc:
        raise AcquireError("payload %d: CRC-32 0x%08x, the device announced 0x%08x; "
                           "payload not acknowledged" % (pid, zlib.crc32(payload), crc))
    from ._lib import BrdfwaveError, payload_check
    try:
        payload_check(payload, max_samples)
    except BrdfwaveError as e:
        raise AcquireError("payload %d does not decode: %s; payload not acknowledged"
                           % (pid, e)) from None
    return pid, payload, bad_pages


def store(outdir, pid, payload):
    """Stores the payload as DIR/payload-ID-CRC.bwv (a temporary file, fsync,
    then a link that never replaces a file); returns (path, stored before)."""
    from ._lib import BrdfwaveError, store_payload
    try:
        return store_payload(outdir, pid, payload)
    except BrdfwaveError as e:
        raise AcquireError("%s; payload %d not acknowledged" % (e, pid)) from None


def acknowledge(dev, pid, timeout=1.0):
    """ACK for payload pid; True when the device released it."""
    dev.write_word(M.ACK_LO, pid & 0xFFFF)
    dev.write_word(M.ACK_HI, pid >> 16)
    dev.write_byte(M.CMD, M.CMD_ACK)
    if not dev.wait_zero(M.CMD, timeout):
        return False
    st = dev.word(M.STATUS)
    if st & M.ST_NAK:
        return False
    return not st & M.ST_READY or dev.u32(M.ID_LO) != pid


class DataReady:
    """The data-ready input: rising-edge events through libgpiod 1.6."""

    def __init__(self, chip, line):
        import gpiod
        self.gpiod = gpiod
        try:
            self.chip = gpiod.Chip(chip)
        except (OSError, FileNotFoundError) as e:
            raise AcquireError("cannot open GPIO chip %s: %s" % (chip, e)) from None
        try:
            self.line = self.chip.get_line(line)
            self.line.request(consumer="brdfwave-acquire",
                              type=gpiod.LINE_REQ_EV_RISING_EDGE)
        except (OSError, ValueError) as e:
            raise AcquireError("cannot request line %d of %s: %s" % (line, chip, e)) from None

    def high(self):
        return self.line.get_value() == 1

    def wait(self, seconds):
        """True if a rising edge arrived within seconds (pending events drained)."""
        sec = int(seconds)
        try:
            if not self.line.event_wait(sec=sec, nsec=int((seconds - sec) * 1e9)):
                return False
        except InterruptedError:  # a signal: the caller looks at its flag
            return False
        self.line.event_read()
        return True

    def close(self):
        self.line.release()
        self.chip.close()


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m brdfwave.acquire",
                                 description="Stores payloads the co-processor offers over "
                                             "I2C (docs/I2C.md) when its data-ready line rises.")
    ap.add_argument("--bus", type=int, required=True, help="I2C bus number N (/dev/i2c-N)")
    ap.add_argument("--addr", type=lambda s: int(s, 0), default=M.ADDR,
                    help="7-bit device address (default 0x42)")
    ap.add_argument("--chip", required=True, help="GPIO chip of the data-ready line "
                                                  "(gpiochipN, or a path)")
    ap.add_argument("--line", type=int, required=True, help="line offset on that chip")
    ap.add_argument("--out", required=True, help="directory for payload-ID-CRC.bwv files")
    ap.add_argument("--once", action="store_true",
                    help="store one payload, then exit (status 1 if it fails)")
    ap.add_argument("--timeout", type=float, default=0,
                    help="with --once: seconds to wait for data-ready (default: forever)")
    ap.add_argument("--retries", type=int, default=3, help="reads of a bad page after the "
                                                           "first (default 3)")
    ap.add_argument("--retry-interval", type=float, default=5.0,
                    help="seconds before a failed payload is tried again (default 5)")
    ap.add_argument("--max-samples", type=int, default=0,
                    help="refuse payloads that decode to more samples (default 67108864)")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.out):
        print("acquire: %s is not a directory" % a.out, file=sys.stderr)
        return 2
    if not 0x03 <= a.addr <= 0x77 or a.retries < 0 or a.timeout < 0 or a.max_samples < 0:
        print("acquire: --addr must be 0x03..0x77, --retries, --timeout and --max-samples "
              ">= 0", file=sys.stderr)
        return 2

    def log(msg):
        print("acquire: " + msg, file=sys.stderr, flush=True)

    stop = {"now": False}

    def on_signal(signum, frame):
        stop["now"] = True

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)

    import smbus2
    bus_name = "/dev/i2c-%d" % a.bus
    try:
        bus = smbus2.SMBus(a.bus)
    except OSError as e:
        log("cannot open %s: %s" % (bus_name, e.strerror))
        return 1
    try:
        drdy = DataReady(a.chip, a.line)
    except AcquireError as e:
        log(str(e))
        bus.close()
        return 1
    dev = Device(bus, a.addr, bus_name)
    t_end = time.monotonic() + a.timeout if a.once and a.timeout > 0 else None
    stored = 0
    rc = 0
    holdoff = 0.0  # after a failure: wait for an edge or this time
    try:
        while not stop["now"]:
            if not drdy.high() or time.monotonic() < holdoff:
                step = 0.2
                if t_end is not None:
                    left = t_end - time.monotonic()
                    if left <= 0:
                        log("no data-ready edge on %s line %d within %g s"
                            % (a.chip, a.line, a.timeout))
                        rc = 1
                        break
                    step = min(step, left)
                if drdy.wait(step):
                    holdoff = 0.0
                continue
            try:
                pid, payload, bad = read_payload(dev, a.retries, log=log,
                                                 stop=lambda: stop["now"],
                                                 max_samples=a.max_samples)
                path, before = store(a.out, pid, payload)
                if not acknowledge(dev, pid):
                    log("payload %d stored, but the device did not confirm the ACK" % pid)
                print("stored %s%s: %d bytes, %d page retries"
                      % (path, " (already stored)" if before else "", len(payload), bad),
                      flush=True)
                stored += 1
                if a.once:
                    break
            except Stopped:
                break
            except (AcquireError, OSError) as e:
                log(str(e))
                if a.once:
                    rc = 1
                    break
                holdoff = time.monotonic() + a.retry_interval
    finally:
        drdy.close()
        bus.close()
    if stop["now"]:
        log("stopped after %d payload(s)" % stored)
    return rc


if __name__ == "__main__":
    sys.exit(main())
