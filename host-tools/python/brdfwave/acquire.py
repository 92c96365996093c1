# SPDX-License-Identifier: BSD-2-Clause
"""Acquisition service: payloads from the co-processor over I2C/SMBus.

    python3 -m brdfwave.acquire --bus 1 --addr 0x42 --chip gpiochip0 --line 17 --out DIR

Waits for a rising edge of the data-ready line (libgpiod 1.6 edge events, with
a timeout), reads the offered payload page by page through the register
window of docs/I2C.md, checks every page's CRC-32 (a bad page is asked for
again, RETRY), the whole payload's CRC-32 and header, and decodes it, stores it
as DIR/payload-ID-CRC.bwv through a temporary file, fsync and a link that
never replaces a file, and only then acknowledges it. A payload that does not
decode is not acknowledged and not stored. A page that never verifies leaves
the payload incomplete: what arrived is kept as DIR/payload-ID-CRC.part.bwv
and DIR/payload-ID-CRC.part (which pages are missing) and the next attempt
reads only the missing pages (--resume FILE after a restart); once whole, the
payload is stored and both files removed. SIGTERM or SIGINT stop the service
between two transfers.

The protocol is libbrdfwave's I2C client (bwh_i2c.h, through ctypes: the same
code as `brdfwave acquire`); smbus2 provides its SMBus transfers.
"""
import argparse
import ctypes
import errno
import os
import signal
import sys
import time

from . import i2cmap as M


class AcquireError(Exception):
    """The offered payload could not be read and verified (not acknowledged)."""


class Incomplete(AcquireError):
    """The offered payload arrived in part (pages that never verified); the
    client keeps what arrived (Client.keep stores it) and reads only the
    missing pages next time."""

    def __init__(self, msg, pid, missing, pages):
        super().__init__(msg)
        self.pid, self.missing, self.pages = pid, missing, pages


class Stopped(Exception):
    """SIGTERM or SIGINT arrived while a payload was being read."""


class Client:
    """The library's I2C client (bwh_i2c.h: the same code as `brdfwave acquire`)
    over an SMBus (smbus2.SMBus or alike): the window of docs/I2C.md read page
    by page with CRC checks and retries, and the ACK."""

    def __init__(self, bus, addr, bus_name="the bus", log=None, stop=None):
        from . import _lib
        self._lib = _lib
        self.bus, self.addr = bus, addr
        self.log = log or (lambda msg: None)
        self.stop = stop or (lambda: False)

        def transfer(fn):
            def call(ctx, *args):
                try:
                    return fn(*args)
                except OSError as e:
                    return -(e.errno or errno.EIO)
                except Exception:  # noqa: BLE001 - a failure must not unwind through C
                    return -errno.EIO
            return call

        def read_word(reg, out):
            out[0] = bus.read_word_data(addr, reg)
            return 0

        def write_byte(reg, v):
            bus.write_byte_data(addr, reg, v)
            return 0

        def write_word(reg, v):
            bus.write_word_data(addr, reg, v)
            return 0

        # the callbacks live as long as the client: C holds their addresses
        self._part = _lib.Partial()  # what arrived of a payload not yet whole
        self._c = _lib.I2C(_lib.I2C_READ_WORD(transfer(read_word)),
                           _lib.I2C_WRITE_BYTE(transfer(write_byte)),
                           _lib.I2C_WRITE_WORD(transfer(write_word)),
                           _lib.I2C_LOG(lambda ctx, line: self.log(line.decode())),
                           _lib.I2C_STOP(lambda ctx: 1 if self.stop() else 0),
                           None, addr, bus_name.encode())

    def read_payload(self, retries=3, max_samples=0):
        """Reads and verifies the offered payload; returns (id, bytes, page retries).
        Raises Incomplete when pages never verified (what arrived is kept, and
        the next call reads only the missing pages of the same payload),
        AcquireError when it is not offered or never verifies, Stopped when
        stop() asked for it."""
        L = self._lib.lib()
        got = self._lib.I2CPayload()
        rc = L.bwh_i2c_read_partial(ctypes.byref(self._c), retries, max_samples,
                                    ctypes.byref(self._part), ctypes.byref(got))
        if rc == self._lib.I2C_STOPPED:
            raise Stopped()
        if rc == 1:
            raise Incomplete(self._lib.last_error(), self._part.id,
                             L.bwh_partial_missing(ctypes.byref(self._part)), self._part.parts)
        if rc != 0:
            raise AcquireError(self._lib.last_error())
        try:
            return got.id, ctypes.string_at(got.payload, got.len), got.bad_pages
        finally:
            self._lib.free(got.payload)

    def keep(self, outdir):
        """Stores what arrived of an incomplete payload as
        OUTDIR/payload-ID-CRC.part(.bwv); returns the record's path."""
        L = self._lib.lib()
        path = ctypes.create_string_buffer(4096)
        if L.bwh_partial_store(os.fsencode(outdir), ctypes.byref(self._part), path,
                               len(path)) != 0:
            raise AcquireError(self._lib.last_error())
        return os.fsdecode(path.value)

    def resume(self, path):
        """Takes up an incomplete payload kept before (its .part or .part.bwv):
        if the device still offers it, only its missing pages are read."""
        L = self._lib.lib()
        L.bwh_partial_free(ctypes.byref(self._part))
        if L.bwh_partial_load(os.fsencode(path), ctypes.byref(self._part)) != 0:
            raise AcquireError(self._lib.last_error())

    def close(self):
        """Frees what is kept of an incomplete payload."""
        self._lib.lib().bwh_partial_free(ctypes.byref(self._part))

    def acknowledge(self, pid, timeout=1.0):
        """ACK for payload pid; True when the device released it, False when
        it did not confirm. Raises AcquireError on a bus error."""
        rc = self._lib.lib().bwh_i2c_acknowledge(ctypes.byref(self._c), pid, timeout)
        if rc < 0:
            raise AcquireError(self._lib.last_error())
        return rc == 1


def store(outdir, pid, payload):
    """Stores the payload as DIR/payload-ID-CRC.bwv (a temporary file, fsync,
    then a link that never replaces a file); returns (path, stored before).
    What was kept of it while it was incomplete is removed."""
    from ._lib import BrdfwaveError, lib, store_payload
    try:
        stored = store_payload(outdir, pid, payload)
    except BrdfwaveError as e:
        raise AcquireError("%s; payload %d not acknowledged" % (e, pid)) from None
    lib().bwh_partial_forget(os.fsencode(outdir), pid, payload, len(payload))
    return stored


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
                    help="store one payload, then exit (status 1 if it fails, 3 if it stays "
                         "incomplete)")
    ap.add_argument("--timeout", type=float, default=0,
                    help="with --once: seconds to wait for data-ready (default: forever)")
    ap.add_argument("--retries", type=int, default=3, help="reads of a bad page after the "
                                                           "first (default 3)")
    ap.add_argument("--retry-interval", type=float, default=5.0,
                    help="seconds before a failed payload is tried again (default 5)")
    ap.add_argument("--max-samples", type=int, default=0,
                    help="refuse payloads that decode to more samples (default 67108864)")
    ap.add_argument("--resume", metavar="FILE",
                    help="an incomplete payload kept before (its .part or .part.bwv): if the "
                         "device still offers it, only its missing pages are read")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.out):
        print("acquire: %s is not a directory" % a.out, file=sys.stderr)
        return 1
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
    dev = Client(bus, a.addr, bus_name, log=log, stop=lambda: stop["now"])
    if a.resume:
        try:
            dev.resume(a.resume)
        except AcquireError as e:
            log(str(e))
            dev.close()
            drdy.close()
            bus.close()
            return 1
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
                pid, payload, bad = dev.read_payload(a.retries, a.max_samples)
                path, before = store(a.out, pid, payload)
                if a.resume:
                    from ._lib import lib
                    lib().bwh_partial_remove(os.fsencode(a.resume))
                try:
                    if not dev.acknowledge(pid):
                        log("payload %d stored, but the device did not confirm the ACK" % pid)
                except AcquireError as e:
                    log("payload %d stored, ACK failed: %s" % (pid, e))
                print("stored %s%s: %d bytes, %d page retries"
                      % (path, " (already stored)" if before else "", len(payload), bad),
                      flush=True)
                stored += 1
                if a.once:
                    break
            except Stopped:
                break
            except Incomplete as e:
                try:
                    kept = dev.keep(a.out)
                    log("%s; kept as %s.bwv, %d of %d pages missing%s"
                        % (e, kept, e.missing, e.pages,
                           "" if a.once else "; they are read again next"))
                except AcquireError as k:
                    log("%s; what arrived could not be kept: %s" % (e, k))
                if a.once:
                    rc = 3
                    break
                holdoff = time.monotonic() + a.retry_interval
            except (AcquireError, OSError) as e:
                log(str(e))
                if a.once:
                    rc = 1
                    break
                holdoff = time.monotonic() + a.retry_interval
    finally:
        dev.close()
        drdy.close()
        bus.close()
    if stop["now"]:
        log("stopped after %d payload(s)" % stored)
    return rc


if __name__ == "__main__":
    sys.exit(main())
