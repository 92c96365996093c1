# SPDX-License-Identifier: BSD-2-Clause
"""The co-processor's side of docs/I2C.md, played on Linux's i2c-stub and gpio-sim.

i2c-stub (bank_reg=0x10 bank_mask=0xff bank_start=0x40 bank_end=0x53) holds
the registers: bank p is page p of the window. gpio-sim's pull attribute
drives the data-ready line. A thread answers the host's RETRY and ACK the
way the board does: it clears RETRY (rewriting the page first, unless told
to leave it corrupted) and on ACK releases the payload (STATUS.ready and
DRDY low) if the id matches.

While the host reads a page only the host selects banks; the thread switches
banks only while the host waits for RETRY to clear (the host then selects the
page again).
"""
import threading
import time
import zlib

from brdfwave import i2cmap as M


class StubDevice:
    def __init__(self, bus, addr, pull_path):
        self.bus, self.addr, self.pull_path = bus, addr, pull_path
        self.lock = threading.Lock()
        self.acked, self.retries, self.naks = [], [], 0
        self.fix_on_retry = True
        self.good_pages = {}
        self.pid = None
        self.queue = []  # (pid, payload, kwargs) offered after the next ACK
        self.status = 0
        self._stop = False
        self._thread = None

    # ---- registers -------------------------------------------------------
    def w(self, reg, v):
        self.bus.write_word_data(self.addr, reg, v & 0xFFFF)

    def r(self, reg):
        return self.bus.read_word_data(self.addr, reg)

    def select(self, p):
        self.bus.write_byte_data(self.addr, M.PAGE, p)

    def write_page(self, p, data, pcrc):
        self.select(p)
        padded = data + b"\xff" * (M.PAGE_SIZE - len(data))
        for k in range(M.PAGE_SIZE // 2):
            self.w(M.DATA + k, padded[2 * k] | padded[2 * k + 1] << 8)
        self.w(M.PNUM, p)
        self.w(M.PLEN, len(data))
        self.w(M.PCRC_LO, pcrc & 0xFFFF)
        self.w(M.PCRC_HI, pcrc >> 16)
        self.select(0)

    def drdy(self, level):
        with open(self.pull_path, "w") as f:
            f.write("pull-up" if level else "pull-down")

    def set_status(self, v):
        self.status = v
        self.w(M.STATUS, v)

    # ---- offering a payload ------------------------------------------------
    def offer(self, pid, payload, corrupt=(), announce_crc=None, fix_on_retry=True):
        """Loads payload as page windows and raises DRDY. corrupt: pages whose
        bytes are served flipped (with the good page CRC); announce_crc: a
        payload CRC other than the true one."""
        with self.lock:
            self.drdy(0)
            self.set_status(0)
            self.fix_on_retry = fix_on_retry
            n = len(payload)
            pages = (n + M.PAGE_SIZE - 1) // M.PAGE_SIZE
            assert pages <= 255, "i2c-stub has 255 banks: payload too long for the test"
            self.w(M.MAGIC, M.MAGIC_VALUE)
            self.w(M.VERSION, M.PAGE_SIZE << 8 | M.MAP_VERSION)
            for reg, v in ((M.ID_LO, pid), (M.LEN_LO, n),
                           (M.CRC_LO, zlib.crc32(payload) if announce_crc is None
                            else announce_crc)):
                self.w(reg, v & 0xFFFF)
                self.w(reg + 1, v >> 16)
            self.w(M.PAGES, pages)
            self.w(M.RETRY, 0)
            self.w(M.CMD, 0)
            self.good_pages = {}
            for p in range(1, pages + 1):
                data = payload[(p - 1) * M.PAGE_SIZE:p * M.PAGE_SIZE]
                crc = zlib.crc32(data)
                self.good_pages[p] = (data, crc)
                if p in corrupt:
                    data = bytes([data[0] ^ 0x5A]) + data[1:]
                self.write_page(p, data, crc)
            self.pid = pid
            self.set_status(M.ST_READY)
            self.drdy(1)

    def withdraw(self):
        with self.lock:
            self.set_status(0)
            self.drdy(0)
            self.pid = None
            self.queue = []

    # ---- the board's answers ----------------------------------------------
    def _serve(self):
        while not self._stop:
            with self.lock:
                retry = self.r(M.RETRY)
                if retry:
                    self.retries.append(retry)
                    if self.fix_on_retry and retry in self.good_pages:
                        data, crc = self.good_pages[retry]
                        self.write_page(retry, data, crc)
                    self.w(M.RETRY, 0)
                cmd = self.r(M.CMD) & 0xFF
                nxt = None
                if cmd == M.CMD_ACK:
                    ack = self.r(M.ACK_LO) | self.r(M.ACK_HI) << 16
                    if self.pid is not None and ack == self.pid and self.status & M.ST_READY:
                        self.acked.append(ack)
                        self.set_status(0)
                        self.drdy(0)
                        self.pid = None
                        if self.queue:
                            nxt = self.queue.pop(0)
                    else:
                        self.naks += 1
                        self.set_status(self.status | M.ST_NAK)
                    self.w(M.CMD, 0)
            if nxt:
                time.sleep(0.05)
                self.offer(nxt[0], nxt[1], **nxt[2])
            time.sleep(0.002)

    def start(self):
        self._stop = False
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def stop(self):
        self._stop = True
        if self._thread:
            self._thread.join()

    def reset_log(self):
        self.acked, self.retries, self.naks = [], [], 0
