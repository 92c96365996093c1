# SPDX-License-Identifier: BSD-2-Clause
"""VM tests of the acquirers against the kernel's i2c-stub and gpio-sim
(run by tests/hw/init inside the VM that tests/hw/run.sh boots).

The test plays the co-processor (stubdev.py): it loads a real payload into
the stub's register pages and raises data-ready; the real acquirers
(python3 -m brdfwave.acquire and brdfwave acquire) run as processes against
/dev/i2c-N and /dev/gpiochipN. Prints one line per case and
"RESULT: N passed, M failed".
"""
import glob
import os
import signal
import struct
import subprocess
import sys
import time
import traceback
import zlib

ROOT = sys.argv[1]
sys.path[:0] = [os.path.join(ROOT, "host-tools", "python"), os.path.join(ROOT, "tests", "hw"),
                "/usr/lib/python3/dist-packages"]
BUILD = os.path.join(ROOT, "build", "host")
BW = os.path.join(BUILD, "brdfwave")
DATA = os.path.join(BUILD, "hw")  # payloads made on the host by run.sh

import numpy as np  # noqa: E402
import smbus2  # noqa: E402

import brdfwave  # noqa: E402
from brdfwave import i2cmap as M  # noqa: E402
from stubdev import StubDevice  # noqa: E402

LINE = 3
passed = failed = 0


def setup():
    bus = None
    for d in sorted(glob.glob("/sys/bus/i2c/devices/i2c-*")):
        with open(d + "/name") as f:
            if f.read().strip() == "SMBus stub driver":
                bus = int(d.rsplit("-", 1)[1])
    assert bus is not None, "no i2c-stub bus"
    cfg = "/sys/kernel/config/gpio-sim/bw"
    os.mkdir(cfg)
    os.mkdir(cfg + "/bank0")
    with open(cfg + "/bank0/num_lines", "w") as f:
        f.write("8")
    with open(cfg + "/live", "w") as f:
        f.write("1")
    chip = open(cfg + "/bank0/chip_name").read().strip()
    dev = open(cfg + "/dev_name").read().strip()
    pull = "/sys/devices/platform/%s/%s/sim_gpio%d/pull" % (dev, chip, LINE)
    return bus, chip, pull


BUS, CHIP, PULL = setup()
print("hw: i2c-stub on /dev/i2c-%d, data-ready on %s line %d" % (BUS, CHIP, LINE), flush=True)
DEV = StubDevice(smbus2.SMBus(BUS), M.ADDR, PULL)
DEV.start()
ENV = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "host-tools", "python") +
           ":/usr/lib/python3/dist-packages")


def payload(name):
    with open(os.path.join(DATA, name), "rb") as f:
        return f.read()


def outdir(name):
    d = "/tmp/out-" + name
    os.mkdir(d)
    return d


def py_cmd(out, *extra, addr=M.ADDR):
    return ["/usr/bin/python3", "-S", "-m", "brdfwave.acquire", "--bus", str(BUS),
            "--addr", hex(addr), "--chip", CHIP, "--line", str(LINE), "--out", out] + list(extra)


def c_cmd(out, *extra, addr=M.ADDR):
    return [BW, "acquire", "--bus", str(BUS), "--addr", hex(addr), "--chip", CHIP,
            "--line", str(LINE), "--out", out] + list(extra)


def run(cmd, timeout=60):
    t0 = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=timeout)
    return r.returncode, r.stdout, r.stderr, time.monotonic() - t0


def case(fn):
    global passed, failed
    DEV.withdraw()
    DEV.reset_log()
    t0 = time.monotonic()
    try:
        fn()
        print("ok     %-48s (%.1f s)" % (fn.__name__, time.monotonic() - t0), flush=True)
        passed += 1
    except Exception:
        print("FAIL   %s" % fn.__name__, flush=True)
        traceback.print_exc(file=sys.stdout)
        failed += 1
    return fn


def expect(cond, what, r=None):
    if not cond:
        raise AssertionError(what + ("" if r is None else "\n  rc %r\n  stdout %r\n  stderr %r"
                                     % (r[0], r[1], r[2])))


def stored(out):
    return sorted(os.listdir(out))


def name(pid, data):
    """The file a payload is stored as: its id and its CRC-32 field."""
    return "payload-%d-%08x.bwv" % (pid, struct.unpack("<I", data[-4:])[0])


def check_stored(out, pid, original):
    path = os.path.join(out, name(pid, original))
    with open(path, "rb") as f:
        got = f.read()
    expect(got == original, "stored payload differs from the offered one")
    m = brdfwave.decode(path)
    ref = brdfwave.decode_bytes(original)
    expect(m.shape == ref.shape and np.array_equal(m.view(np.uint32), ref.view(np.uint32)),
           "stored payload decodes differently")
    cli = os.path.join(out, "cli.f32")
    subprocess.run([BW, "decode", "-i", path, "-o", cli], check=True)
    expect(np.array_equal(np.fromfile(cli, "<u4"), m.view(np.uint32).ravel()),
           "CLI decode differs from the Python decode")
    os.unlink(cli)


A = payload("a.bwv")
B = payload("b.bwv")
print("hw: payloads of %d and %d bytes (%d and %d pages)" % (
    len(A), len(B), -(-len(A) // 32), -(-len(B) // 32)), flush=True)


def acquire_once_stores_the_offered_payload_and_acknowledges_it(cmd):
    out = outdir(cmd.__name__ + "-good")
    DEV.offer(7, A)
    r = run(cmd(out, "--once", "--timeout", "20"))
    expect(r[0] == 0 and "stored" in r[1], "acquire failed", r)
    expect(stored(out) == [name(7, A)], "stored files %r" % stored(out), r)
    check_stored(out, 7, A)
    expect(DEV.acked == [7] and DEV.retries == [], "device saw acks %r retries %r"
           % (DEV.acked, DEV.retries), r)


def no_edge_times_out_with_a_clear_error(cmd):
    out = outdir(cmd.__name__ + "-timeout")
    r = run(cmd(out, "--once", "--timeout", "1.5"))
    expect(r[0] == 1 and "no data-ready edge" in r[2] and r[3] >= 1.5, "no timeout", r)
    expect(stored(out) == [] and DEV.acked == [], "stored %r acked %r" % (stored(out), DEV.acked))


def a_device_that_naks_is_a_clear_error(cmd):
    out = outdir(cmd.__name__ + "-nak")
    DEV.offer(8, A)
    r = run(cmd(out, "--once", "--timeout", "10", addr=0x43))
    expect(r[0] == 1 and "no answer from the device at 0x43" in r[2] and "NAK" in r[2],
           "NAK not reported", r)
    expect(stored(out) == [] and DEV.acked == [], "stored %r acked %r" % (stored(out), DEV.acked))


def a_corrupted_page_is_read_again(cmd):
    out = outdir(cmd.__name__ + "-retry")
    DEV.offer(9, A, corrupt=(3,))
    r = run(cmd(out, "--once", "--timeout", "20"))
    expect(r[0] == 0 and "page 3 failed its CRC-32, asking again (1/3)" in r[2],
           "retry not reported", r)
    expect("1 page retries" in r[1], "retry count not reported", r)
    check_stored(out, 9, A)
    expect(DEV.retries == [3] and DEV.acked == [9], "device saw retries %r acks %r"
           % (DEV.retries, DEV.acked))


def a_page_that_never_verifies_is_not_acknowledged(cmd):
    out = outdir(cmd.__name__ + "-badpage")
    DEV.offer(10, A, corrupt=(2,), fix_on_retry=False)
    r = run(cmd(out, "--once", "--timeout", "20", "--retries", "2"))
    expect(r[0] == 3 and "page 2 failed its CRC-32 3 times; payload not acknowledged" in r[2],
           "no clear error", r)
    # what arrived is kept as incomplete, not acknowledged
    part = "payload-10-%08x.part" % zlib.crc32(A)
    expect(stored(out) == [part, part + ".bwv"] and DEV.acked == [] and DEV.retries == [2, 2],
           "stored %r acked %r retries %r" % (stored(out), DEV.acked, DEV.retries), r)
    with open(os.path.join(out, part + ".bwv"), "rb") as f:
        held = f.read()
    expect(held == A[:32] + bytes(32) + A[64:], "the kept bytes are not the payload's")
    # later, the page served right: --resume reads it and completes the payload
    DEV.offer(10, A)
    r = run(cmd(out, "--once", "--timeout", "20", "--resume", os.path.join(out, part)))
    expect(r[0] == 0 and "stored" in r[1], "resume failed", r)
    expect(stored(out) == [name(10, A)], "stored files %r" % stored(out), r)
    check_stored(out, 10, A)
    expect(DEV.acked == [10], "acked %r" % DEV.acked, r)


def a_payload_crc_mismatch_is_not_acknowledged(cmd):
    out = outdir(cmd.__name__ + "-badcrc")
    DEV.offer(11, A, announce_crc=0x12345678)
    r = run(cmd(out, "--once", "--timeout", "20"))
    expect(r[0] == 1 and "announced 0x12345678; payload not acknowledged" in r[2],
           "no clear error", r)
    expect(stored(out) == [] and DEV.acked == [], "stored %r acked %r" % (stored(out), DEV.acked))


def a_payload_with_a_bad_header_is_not_acknowledged(cmd):
    out = outdir(cmd.__name__ + "-badhdr")
    bad = bytearray(A)
    bad[0:4] = b"XXXX"  # page and payload CRCs are computed over these bytes: only the header check sees it
    DEV.offer(12, bytes(bad))
    r = run(cmd(out, "--once", "--timeout", "20"))
    expect(r[0] == 1 and "magic" in r[2] and "not acknowledged" in r[2], "no clear error", r)
    expect(stored(out) == [] and DEV.acked == [], "stored %r acked %r" % (stored(out), DEV.acked))


def a_payload_that_does_not_decode_is_not_acknowledged(cmd):
    out = outdir(cmd.__name__ + "-nodecode")
    body = A[:-4 - 16]  # the body cut short, the payload's own CRC made to match it
    DEV.offer(13, body + struct.pack("<I", zlib.crc32(body)))
    r = run(cmd(out, "--once", "--timeout", "20"))
    expect(r[0] == 1 and "does not decode" in r[2] and "not acknowledged" in r[2],
           "no clear error", r)
    expect(stored(out) == [] and DEV.acked == [], "stored %r acked %r" % (stored(out), DEV.acked))


def ids_repeated_after_a_reboot_never_replace_a_stored_payload(cmd):
    out = outdir(cmd.__name__ + "-reboot")
    for data in (A, B, A):  # id 1 from three boots; the third repeats the first's payload
        DEV.offer(1, data)
        r = run(cmd(out, "--once", "--timeout", "20"))
        expect(r[0] == 0 and "stored" in r[1], "acquire failed", r)
    expect("already stored" in r[1], "the repeat is not reported", r)
    expect(stored(out) == sorted([name(1, A), name(1, B)]), "stored %r" % stored(out), r)
    check_stored(out, 1, A)
    check_stored(out, 1, B)
    expect(DEV.acked == [1, 1, 1], "acked %r" % DEV.acked)


def the_service_stores_payloads_until_sigterm(cmd):
    out = outdir(cmd.__name__ + "-service")
    p = subprocess.Popen(cmd(out, "--retry-interval", "0.5"), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=ENV)
    time.sleep(1.0)  # the service is waiting for an edge
    DEV.queue = [(21, B, {})]
    DEV.offer(20, A)
    t_end = time.monotonic() + 40
    while len(DEV.acked) < 2 and time.monotonic() < t_end and p.poll() is None:
        time.sleep(0.1)
    p.send_signal(signal.SIGTERM)
    try:
        so, se = p.communicate(timeout=5)
    except subprocess.TimeoutExpired:
        p.kill()
        so, se = p.communicate()
        raise AssertionError("no clean exit on SIGTERM: " + se)
    r = (p.returncode, so, se)
    expect(p.returncode == 0 and "stopped after 2 payload(s)" in se, "no clean shutdown", r)
    expect(stored(out) == sorted([name(20, A), name(21, B)]), "stored %r" % stored(out), r)
    check_stored(out, 20, A)
    check_stored(out, 21, B)
    expect(DEV.acked == [20, 21], "acked %r" % DEV.acked, r)


def py(fn):
    def t():
        fn(py_cmd)
    t.__name__ = "python: " + fn.__name__
    return t


def c(fn):
    def t():
        fn(c_cmd)
    t.__name__ = "C: " + fn.__name__
    return t


py_cmd.__name__, c_cmd.__name__ = "py", "c"
ALL = (acquire_once_stores_the_offered_payload_and_acknowledges_it,
       no_edge_times_out_with_a_clear_error, a_device_that_naks_is_a_clear_error,
       a_corrupted_page_is_read_again, a_page_that_never_verifies_is_not_acknowledged,
       a_payload_crc_mismatch_is_not_acknowledged,
       a_payload_with_a_bad_header_is_not_acknowledged,
       a_payload_that_does_not_decode_is_not_acknowledged,
       ids_repeated_after_a_reboot_never_replace_a_stored_payload,
       the_service_stores_payloads_until_sigterm)
for f in ALL:
    case(py(f))
for f in ALL:
    case(c(f))
DEV.stop()
print("RESULT: %d passed, %d failed" % (passed, failed), flush=True)
