#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""modcp — real masters against the firmware images running in QEMU.

    qemu_test.py --root ROOT --board BOARD --suite SUITE [options]

BOARD is an in-tree board (mps2-an385, stm32f405, microbit, lm3s6965evb) or a board
folder anywhere: tools/board-env reads its board.env (QEMU machine, UARTs, whether it
has a console) and the images are BOARD_BUILD/modcp-<name>[-qemu].elf.

Suites
  smoke      the image exactly as tools/build-arm built it from configs/default.ini
             boots, is configured and answers (FC03 / FC06 manual examples, console)
  libmodbus  tests/integration/master_libmodbus (every FC of the manual with the exact
             reply bytes, T/C, exceptions 01..04, broadcast, the largest frames, the
             paused user program via the console, N random write-then-read operations)
  pymodbus   tests/integration/master_pymodbus.py (pymodbus client, same configuration)
  firmware   what is particular to the image, from raw frames: the end-of-frame timer
             (a frame written in pieces with short gaps is one frame, a long gap splits
             it), the console and the Modbus side seeing one controller memory,
             broadcast, exceptions, the extended function set (FC08 counters, FC11,
             FC12, FC17, FC22, FC23, FC43/14)

Except smoke, the suites run the QEMU test image modcp-<board>-qemu.elf (the same
configuration with f_mul = 4: a 16 ms end of frame, see tools/build-arm). Host load
cannot cut a frame inside QEMU (the ports confirm every end-of-frame expiry with quiet
rounds, docs/porting.md section 4), so nothing is retried: every suite ends with
    qemu_test: sent=N answered=N failed=N
(firmware / smoke: the script's own requests and the replies it got; libmodbus /
pymodbus: the frames the slave took or found damaged and the replies it sent, from its
status counters; master_libmodbus clears them with FC08 sub 0A, so there they count from
that clear) and fails on a failed check or on any frame the slave counts as damaged
(CRC, too long, character error, overrun) that the suite did not damage on purpose. The image is
started with tools/run-qemu (Modbus line and console on ptys). The
script keeps both ptys open for the whole run (QEMU polls a pty it considers
disconnected only once a second and drops output meanwhile), waits until the console
prompt and an FC08 echo answer, then runs the suite. The master's --control FIFO is
bridged to the console (`pause` / `resume` stop and restart the cyclic user program).

A board without a console (QEMU_CONSOLE_UART empty in its board.env; microbit: its only
UART is the Modbus line) runs every check
that needs no console; the ones that read or write through the console (console get /
set / status / board, the paused user program) are reported as "n/a", counted apart,
never as passed. Its bus counters are read with FC08 diagnostics instead (sub 0B..0F,
12: messages, CRC errors, exceptions, slave messages, no response, overruns).

Exit status: 0 passed, 1 failed, 77 skipped (no qemu-system-arm or no image: build the
images with tools/build-arm).
"""
import argparse
import os
import queue
import re
import select
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import threading
import time
import tty

SKIP = 77
SLAVE = 5


def crc16(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return bytes([crc & 0xFF, crc >> 8])


def adu(pdu, addr=SLAVE):
    frame = bytes([addr]) + bytes(pdu)
    return frame + crc16(frame)


class Fail(Exception):
    pass


# Host-time limits. They only bound how long a test waits for something that should
# come; none of them makes anything happen twice. A loaded host stalls QEMU's threads
# (seen: over a second at load average ~10 on 2 cores), so they are generous.
REPLY_TIMEOUT_S = 5.0     # a request that must be answered
CONSOLE_TIMEOUT_S = 10.0  # a console command
START_TIMEOUT_S = 40.0    # QEMU up, console prompt, first FC08 echo
VERSION = ""              # --version: what the smoke suite's board / status must show
WATCHDOG_S = 590          # the whole test (ctest's TIMEOUT is 600): never leave QEMU behind


class Target:
    """One firmware image in QEMU, its Modbus pty and its console pty."""

    def __init__(self, root, board, env, elf, log):
        self.root, self.board_arg, self.elf, self.log = root, board, elf, log
        self.board = env["BOARD_NAME"]
        self.in_tree = os.path.dirname(env["BOARD_DIR"]) == os.path.join(root, "boards")
        self.proc = None
        self.mfd = self.cfd = None
        self.modbus_tty = self.console_tty = None
        self.has_console = env["QEMU_CONSOLE_UART"] != ""
        self.counting = False  # count requests once the image is up
        self.sent = self.replied = 0

    def start(self):
        cmd = [os.path.join(self.root, "tools", "run-qemu"), self.board_arg, "--elf", self.elf]
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, start_new_session=True)
        self.lines = queue.Queue()
        threading.Thread(target=self._drain, daemon=True).start()
        deadline = time.time() + START_TIMEOUT_S
        while time.time() < deadline and not (self.modbus_tty and self.console_tty):
            try:
                line = self.lines.get(timeout=max(0.1, deadline - time.time()))
            except queue.Empty:
                break
            if line is None:
                raise Fail("tools/run-qemu ended: %s" % self.proc.poll())
            if line.startswith("MODBUS_TTY="):
                self.modbus_tty = line.strip().split("=", 1)[1]
            elif line.startswith("CONSOLE_TTY="):
                self.console_tty = line.strip().split("=", 1)[1]
        if not (self.modbus_tty and self.console_tty):
            raise Fail("no ptys from tools/run-qemu")
        if self.has_console:
            self.cfd = self._open(self.console_tty)
        self.mfd = self._open(self.modbus_tty)
        if self.has_console:
            self._wait_console()
        self._wait_modbus()
        self.counting = True

    def _drain(self):
        for line in self.proc.stdout:
            self.log(("qemu: " if self.modbus_tty and self.console_tty else "") + line.rstrip())
            self.lines.put(line)
        self.lines.put(None)

    @staticmethod
    def _open(path):
        fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(fd)
        return fd

    def stop(self):
        for fd in (self.mfd, self.cfd):
            if fd is not None:
                os.close(fd)
        if self.proc and self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()

    # ---- console ----
    def _read(self, fd, timeout):
        r, _, _ = select.select([fd], [], [], max(0.0, timeout))
        return os.read(fd, 4096) if r else b""

    def _wait_console(self):
        deadline = time.time() + START_TIMEOUT_S
        buf = b""
        while time.time() < deadline:
            os.write(self.cfd, b"\r")
            end = time.time() + 2.0
            while time.time() < end:
                buf += self._read(self.cfd, end - time.time())
                if b"> " in buf:
                    self._flush(self.cfd)
                    return
        raise Fail("the console did not answer (%r)" % buf[-200:])

    def _flush(self, fd):
        while self._read(fd, 0.05):
            pass

    def console(self, cmd, timeout=CONSOLE_TIMEOUT_S):
        """Run one console command; returns its answer (without echo and prompt)."""
        if not self.has_console:
            raise Fail("console: %s has no console (%r)" % (self.board, cmd))
        self._flush(self.cfd)
        os.write(self.cfd, cmd.encode() + b"\r")
        buf = b""
        end = time.time() + timeout
        while time.time() < end:
            buf += self._read(self.cfd, end - time.time())
            text = buf.decode(errors="replace")
            if text.endswith("\r\n> ") or text.endswith("\n> "):
                lines = text.replace("\r\n", "\n").split("\n")
                return "\n".join(l for l in lines[1:-1])  # drop the echo and the prompt
        raise Fail("console: no answer to %r (%r)" % (cmd, buf[-200:]))

    # ---- Modbus, raw frames ----
    def _wait_modbus(self):
        """Until an FC08 echo is answered. Each attempt waits long enough for a slow
        host (an echo written while the previous one is still on its way would join it
        into one damaged frame), and the line is quiet before the suite starts."""
        deadline = time.time() + START_TIMEOUT_S
        req = adu([0x08, 0x00, 0x00, 0xA5, 0x5A])
        while time.time() < deadline:
            if self.transact(req, timeout=2.0, expect_len=len(req)) == req:
                while self._read(self.mfd, 0.3):
                    pass
                return
        raise Fail("no answer to an FC08 echo on %s" % self.modbus_tty)

    def transact(self, req, timeout=REPLY_TIMEOUT_S, expect_len=None, pieces=None, gap_s=0.0):
        """Send req (optionally in pieces with gap_s between them) and return the
        reply: complete when expect_len bytes are in or, without expect_len, when the
        bytes received form a frame with a valid CRC; otherwise what came until the
        timeout. A pause inside the reply never ends it early: QEMU writes a reply byte
        by byte from the vCPU thread, and a loaded host deschedules that thread for tens
        of milliseconds, so a reply cut at a silence would leave its tail to be taken as
        the next reply. The timeout is host time and generous: it costs nothing when
        the reply comes, and a request that gets none fails just the same (nothing is
        sent twice). self.max_gap_s is the longest pause the host actually made between
        two pieces (from the end of one write to the end of the next)."""
        self._flush(self.mfd)
        self.max_gap_s = 0.0
        if pieces:
            pos = 0
            last = None
            for n in pieces + [len(req)]:
                if pos >= len(req):
                    break
                os.write(self.mfd, req[pos:pos + n])
                now = time.monotonic()
                if last is not None:
                    self.max_gap_s = max(self.max_gap_s, now - last)
                last = now
                pos += n
                if pos < len(req):
                    time.sleep(gap_s)
        else:
            os.write(self.mfd, req)
        if self.counting:
            self.sent += 1
        out = b""
        end = time.time() + timeout
        while time.time() < end:
            data = self._read(self.mfd, end - time.time())
            if data:
                out += data
                if expect_len is not None:
                    if len(out) >= expect_len:
                        break
                elif len(out) >= 4 and crc16(out[:-2]) == out[-2:]:
                    break
        if self.counting and out:
            self.replied += 1
        return out

    def wait_taken(self, before, n=1):
        """Until the slave has ended n more frames than the counters `before` show. QEMU
        reads the pty only while its threads run: a frame the slave does not answer
        must have been taken before the next one is written, or a host stall makes
        both reach the UART back to back, as one frame (measured at load average ~7:
        2-3 % of "request for slave 6, 0.3 s, request for slave 5" pairs on every
        board). Through the console; without one a pause of 1 s is all there is."""
        if not self.has_console:
            time.sleep(1.0)
            return
        end = time.time() + REPLY_TIMEOUT_S
        while time.time() < end:
            if frames(self.counters()) - frames(before) >= n:
                return
            time.sleep(0.02)
        raise Fail("the slave did not end %d frame(s) within %.0f s" % (n, REPLY_TIMEOUT_S))

    def counters(self):
        """The slave's bus counters: from the console's status line, or, on a board
        whose only UART is the Modbus line, from FC08 diagnostics (FC08_COUNTERS, one
        request each, not counted as the script's own requests). FC08 values are taken
        as they stood before these queries: a query counts itself and the ones before
        it in bus_msg and slave_msg."""
        if self.has_console:
            text = self.console("status")
            return {k: int(v) for k, v in re.findall(r"(\w+)=(\d+)\b", text)}
        counting, self.counting = self.counting, False
        out = {}
        try:
            for i, (sub, name) in enumerate(FC08_COUNTERS):
                req = adu([0x08, 0x00, sub, 0x00, 0x00])
                rep = self.transact(req, expect_len=8)
                if len(rep) != 8 or rep[:4] != req[:4] or crc16(rep[:6]) != rep[6:]:
                    raise Fail("FC08 sub %02X (%s): reply %s" % (sub, name, rep.hex(" ")))
                v = struct.unpack(">H", rep[4:6])[0]
                if name in ("bus_msg", "slave_msg"):
                    v -= i + 1
                out[name] = v
        finally:
            self.counting = counting
        return out


# ---- the firmware suite -----------------------------------------------------------------


class Checks:
    def __init__(self, log):
        self.log = log
        self.passed = 0
        self.failed = 0
        self.na = 0
        self.expected_damage = 0  # frames the suite damages on purpose
        self.discarded = 0

    def ok(self, cond, what):
        if cond:
            self.passed += 1
            self.log("ok - " + what)
        else:
            self.failed += 1
            self.log("FAIL - " + what)
        return cond

    def console(self, t, what):
        """True when target t has a console for the check `what`; otherwise the check
        is counted and logged as not applicable."""
        if t.has_console:
            return True
        self.na += 1
        self.log("n/a - %s (%s has no console)" % (what, t.board))
        return False


def reply_ok(rep, fc):
    return len(rep) >= 4 and rep[0] == SLAVE and rep[1] == fc and crc16(rep[:-2]) == rep[-2:]


def exc_of(rep):
    if len(rep) == 5 and rep[1] & 0x80 and crc16(rep[:3]) == rep[3:]:
        return rep[2]
    return None


# status counters of frames the slave could not take: a cut frame shows up here
DAMAGE = ("bus_crc", "too_long", "char_errors", "breaks", "overrun", "t15")
# the same through FC08 diagnostics (no console; 16-bit counters): a frame with a
# character error, BREAK or t1.5 violation counts in bus_crc there too
FC08_COUNTERS = ((0x0B, "bus_msg"), (0x0C, "bus_crc"), (0x0D, "exceptions"),
                 (0x0E, "slave_msg"), (0x0F, "no_response"), (0x12, "overrun"))


def damage(before, after):
    return sum(after.get(k, 0) - before.get(k, 0) for k in DAMAGE)


def frames(cnt):
    """Frames the slave ended: each counts once, as a message, a CRC error or too long."""
    return sum(cnt.get(k, 0) for k in ("bus_msg", "bus_crc", "too_long"))


def console_value(text):
    m = re.search(r"=\s*(0x[0-9A-Fa-f]+|-?\d+)", text)
    return int(m.group(1), 0) if m else None


def suite_firmware(t, c):
    # end-of-frame timing on the chip: t3.5 at 9600 baud = 4 ms (manual table), times
    # f_mul = 4 in the QEMU test image: 16 ms
    t35_s = 0.016 if "-qemu" in t.elf else 0.004
    req = adu([0x03, 0x00, 0x50, 0x00, 0x02])
    want = bytes.fromhex("05 03 04 87 65 43 21 76 70")
    c.ok(t.transact(req, expect_len=9) == want, "FC03 manual example in one write")
    # Byte by byte with 0.5 ms gaps (< t3.5): one frame. The pauses are the host's; a
    # sample in which the host itself paused >= t3.5 / 2 between two writes (this
    # script descheduled) does not test a short gap: it is reported and taken again,
    # up to 5 samples; its bus counters are set aside (c.expected_damage).
    for attempt in range(5):
        before = t.counters()
        rep = t.transact(req, expect_len=9, pieces=[1, 1, 1, 1, 1, 1, 1], gap_s=0.0005)
        gap = t.max_gap_s
        if gap < t35_s / 2:
            c.ok(rep == want and damage(before, t.counters()) == 0,
                 "FC03 written byte by byte, 0.5 ms gaps (< t3.5; longest %.1f ms): one frame"
                 % (gap * 1000))
            break
        c.expected_damage += damage(before, t.counters())
        c.discarded += 1
        t.log("sample not counted: the host paused %.1f ms between two writes (>= t3.5/2)"
              % (gap * 1000))
    else:
        c.ok(False, "FC03 byte by byte: the host never kept its pauses below t3.5/2")
    before = t.counters()
    if t.has_console:
        # the second piece only once the slave has ended the first (a host stall could
        # otherwise hand QEMU both pieces at once: see Target.wait_taken)
        t._flush(t.mfd)
        os.write(t.mfd, req[:4])
        t.wait_taken(before, 1)
        rep = t.transact(req[4:], timeout=0.8)
        t.wait_taken(before, 2)
    else:
        rep = t.transact(req, timeout=0.8, pieces=[4], gap_s=0.300)
    c.ok(rep == b"", "FC03 split by a gap > t3.5: two fragments, no reply")
    after = t.counters()
    if c.console(t, "both fragments counted as CRC errors"):
        c.ok(after.get("bus_crc", 0) - before.get("bus_crc", 0) == 2,
             "both fragments counted as CRC errors (%s -> %s)"
             % (before.get("bus_crc"), after.get("bus_crc")))
    c.expected_damage += damage(before, after)
    c.ok(t.transact(req, expect_len=9) == want, "next request after the split frame is served")

    # the console and the master see one controller memory
    rep = t.transact(adu([0x06, 0x01, 0x80, 0x2B, 0x1A]), expect_len=8)
    c.ok(rep == adu([0x06, 0x01, 0x80, 0x2B, 0x1A]), "[RTU-2003] §6.6 FC06 DB800.DBW768 = 2B1A")
    if c.console(t, "console: get DB800.DBW768 = 0x2B1A after FC06"):
        v = console_value(t.console("get DB800.DBW768"))
        c.ok(v == 0x2B1A, "console: get DB800.DBW768 = 0x2B1A after FC06 (got %s)" % v)
    if c.console(t, "console set DB800.DBW770 0x4242, FC03 reads it"):
        t.console("set DB800.DBW770 0x4242")
        rep = t.transact(adu([0x03, 0x01, 0x81, 0x00, 0x01]), expect_len=7)
        c.ok(rep == adu([0x03, 0x02, 0x42, 0x42]), "console set DB800.DBW770 0x4242, FC03 reads it")
    if c.console(t, "console set M1150.5, FC01 coil 1205 reads 1"):
        t.console("set M1150.5 1")
        rep = t.transact(adu([0x01, 0x04, 0xB5, 0x00, 0x01]), expect_len=6)
        c.ok(rep == adu([0x01, 0x01, 0x01]), "console set M1150.5, FC01 coil 1205 reads 1")

    # broadcast: executed, never answered
    before = t.counters()
    rep = t.transact(adu([0x06, 0x01, 0x82, 0x77, 0x88], addr=0), timeout=0.3)
    c.ok(rep == b"", "broadcast FC06: no reply")
    t.wait_taken(before)
    if c.console(t, "broadcast FC06 executed: console get DB800.DBW772 = 0x7788"):
        # executed once the slave's end of frame and the next FB cycle have passed: read
        # back until then (the request itself is sent once)
        end = time.time() + REPLY_TIMEOUT_S
        while True:
            v = console_value(t.console("get DB800.DBW772"))
            if v == 0x7788 or time.time() > end:
                break
            time.sleep(0.05)
        c.ok(v == 0x7788, "broadcast FC06 executed: DB800.DBW772 = 0x7788 (got %s)" % v)
    before = t.counters()
    rep = t.transact(adu([0x03, 0x00, 0x50, 0x00, 0x02], addr=0), timeout=0.3)
    c.ok(rep == b"", "broadcast FC03: dropped, no reply")
    t.wait_taken(before)
    before = t.counters()
    rep = t.transact(adu([0x03, 0x00, 0x50, 0x00, 0x02], addr=6), timeout=0.3)
    c.ok(rep == b"", "request for slave 6: ignored")
    t.wait_taken(before)

    # exceptions
    for name, pdu, code in (
        ("FC 0x41 -> 01", [0x41, 0, 0, 0, 1], 1),
        ("FC03 across a DB boundary -> 02", [0x03, 0x01, 0xFE, 0x00, 0x04], 2),
        ("FC03 0 registers -> 03", [0x03, 0x00, 0x00, 0x00, 0x00], 3),
        ("FC03 DB803 missing -> 04", [0x03, 0x06, 0x00, 0x00, 0x01], 4),
    ):
        rep = t.transact(adu(pdu), expect_len=5)
        c.ok(exc_of(rep) == code and rep[1] == (pdu[0] | 0x80),
             "exception %s (got %s)" % (name, rep.hex(" ")))

    # extended function set
    rep = t.transact(adu([0x08, 0x00, 0x0B, 0x00, 0x00]), expect_len=8)
    c.ok(reply_ok(rep, 0x08) and struct.unpack(">H", rep[4:6])[0] > 0,
         "FC08 sub 0B bus message count > 0 (%s)" % rep.hex(" "))
    rep = t.transact(adu([0x08, 0x00, 0x0C, 0x00, 0x00]), expect_len=8)
    c.ok(reply_ok(rep, 0x08) and struct.unpack(">H", rep[4:6])[0] >= 2,
         "FC08 sub 0C CRC error count >= 2 (%s)" % rep.hex(" "))
    rep = t.transact(adu([0x0B]), expect_len=8)
    c.ok(reply_ok(rep, 0x0B) and len(rep) == 8, "FC11 comm event counter (%s)" % rep.hex(" "))
    rep = t.transact(adu([0x0C]))
    c.ok(reply_ok(rep, 0x0C) and rep[2] == len(rep) - 5 and rep[2] >= 6,
         "FC12 comm event log (%d bytes)" % len(rep))
    rep = t.transact(adu([0x11]))
    c.ok(reply_ok(rep, 0x11) and rep[2] == len(rep) - 5, "FC17 report slave ID (%r)" % rep[3:-2])
    # FC22: DB800.DBW774 = 0x1234, AND 0xF0F0, OR 0x0505 -> (0x1234 & F0F0) | (0505 & ~F0F0)
    t.transact(adu([0x06, 0x01, 0x83, 0x12, 0x34]), expect_len=8)
    rep = t.transact(adu([0x16, 0x01, 0x83, 0xF0, 0xF0, 0x05, 0x05]), expect_len=10)
    c.ok(rep == adu([0x16, 0x01, 0x83, 0xF0, 0xF0, 0x05, 0x05]), "FC22 mask write echo")
    want22 = (0x1234 & 0xF0F0) | (0x0505 & ~0xF0F0 & 0xFFFF)
    if c.console(t, "FC22 result: console get DB800.DBW774 = 0x%04X" % want22):
        v = console_value(t.console("get DB800.DBW774"))
        c.ok(v == want22, "FC22 result DB800.DBW774 = 0x%04X (got %s)" % (want22, v))
    # FC23: write 2 registers at 0x0190 first, then read 3 from 0x018F
    rep = t.transact(adu([0x17, 0x01, 0x8F, 0x00, 0x03, 0x01, 0x90, 0x00, 0x02, 0x04,
                          0xAA, 0xBB, 0xCC, 0xDD]), expect_len=11)
    c.ok(reply_ok(rep, 0x17) and rep[2] == 6 and rep[5:9] == bytes([0xAA, 0xBB, 0xCC, 0xDD]),
         "FC23 write then read (%s)" % rep.hex(" "))
    rep = t.transact(adu([0x2B, 0x0E, 0x01, 0x00]))
    c.ok(reply_ok(rep, 0x2B) and rep[2] == 0x0E and len(rep) > 12,
         "FC43/14 basic device identification (%r)" % rep[3:-2])

    # the image itself
    if c.console(t, "console: board command"):
        text = t.console("board")
        # an out-of-tree board names itself in board_name(), not necessarily by its folder
        named = t.board in text if t.in_tree else "board " in text
        c.ok(named and "cycles" in text, "console: board command (%s)" % text.split("\n")[0])


def suite_smoke(t, c):
    """The image exactly as built from the configuration (not the QEMU twin): it boots,
    takes its parameters and answers (also 100 requests back to back with its 4 ms end
    of frame). Every request is sent once (the end of frame
    does not depend on host load: see the ports' end-of-frame confirmation, docs/porting.md)."""
    if c.console(t, "console: board shows the image's own configuration"):
        text = t.console("board")
        c.ok("config " in text and "-qemu" not in text and "qemu-test" not in text,
             "console: board shows the image's own configuration (%s)" % text.replace("\n", " | "))
        if VERSION:  # the image's modcp/version.h (boards/common/app.c: banner and board)
            c.ok("\nversion %s\n" % VERSION in text,
                 "console: board shows version %s (project(modcp VERSION))" % VERSION)
    c.ok(t.transact(adu([0x03, 0x00, 0x50, 0x00, 0x02]), expect_len=9) ==
         bytes.fromhex("05 03 04 87 65 43 21 76 70"), "[RTU-2003] §6.3 FC03 manual example")
    c.ok(t.transact(adu([0x06, 0x01, 0x80, 0x2B, 0x1A]), expect_len=8) == adu([0x06, 0x01, 0x80, 0x2B, 0x1A]),
         "[RTU-2003] §6.6 FC06 DB800.DBW768 = 2B1A")
    if c.console(t, "console: get DB800.DBW768 = 0x2B1A"):
        v = console_value(t.console("get DB800.DBW768"))
        c.ok(v == 0x2B1A, "console: get DB800.DBW768 = 0x2B1A (got %s)" % v)
    # the image's own 4 ms end of frame under whatever load the host has: 100 requests
    # in a row, each answered exactly
    want = bytes.fromhex("05 03 04 87 65 43 21 76 70")
    good = sum(t.transact(adu([0x03, 0x00, 0x50, 0x00, 0x02]), expect_len=9) == want
               for _ in range(100))
    c.ok(good == 100, "100 x FC03 manual example back to back: %d answered exactly" % good)
    if c.console(t, "status: FB running, CP ready"):
        status = t.console("status")
        c.ok("fb=RUN" in status and "cp=ready" in status, "status: FB running, CP ready")
        if VERSION:
            c.ok(status.endswith(" version=" + VERSION),
                 "status: version=%s (project(modcp VERSION)) (%s)" % (VERSION, status[-30:]))


# ---- masters ----------------------------------------------------------------------------


def bridge_fifo(path, target, stop):
    """Forward the master's control lines (pause / resume) to the console. The FIFO is
    opened read-write so that it never reports end-of-file between two writers."""
    fd = os.open(path, os.O_RDWR | os.O_NONBLOCK)
    buf = b""
    try:
        while not stop.is_set():
            r, _, _ = select.select([fd], [], [], 0.1)
            if not r:
                continue
            buf += os.read(fd, 256)
            while b"\n" in buf:
                line, buf = buf.split(b"\n", 1)
                cmd = line.decode().strip()
                if cmd:
                    target.log("control: %s -> %s" % (cmd, target.console(cmd)))
    finally:
        os.close(fd)


masters = []


def run_master(cmd, log, timeout):
    log("$ " + " ".join(cmd))
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    masters.append(p)
    last = ""
    try:
        for line in p.stdout:
            log(line.rstrip())
            if line.strip():
                last = line.strip()
        rc = p.wait(timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        raise Fail("master timed out")
    m = re.match(r"(\d+) passed, (\d+) failed", last)
    if not m:
        raise Fail("master ended without 'N passed, M failed' (rc %s)" % rc)
    return int(m.group(1)), int(m.group(2)), rc


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", required=True)
    ap.add_argument("--board", required=True, help="in-tree board name or board folder")
    ap.add_argument("--suite", required=True,
                    choices=["libmodbus", "pymodbus", "firmware", "smoke"])
    ap.add_argument("--master", help="master_libmodbus executable or master_pymodbus.py")
    ap.add_argument("--python", default=sys.executable, help="interpreter for pymodbus")
    ap.add_argument("--random", type=int, default=2000)
    ap.add_argument("--version", default="",
                    help="project(modcp VERSION): the smoke suite's board / status must show it")
    ap.add_argument("--elf", help="image to run (default: the QEMU test image, else the plain one)")
    args = ap.parse_args()
    global VERSION
    VERSION = args.version

    t_start = time.time()

    def log(msg):
        print("[%6.2f] %s" % (time.time() - t_start, msg), flush=True)

    if shutil.which("qemu-system-arm") is None:
        print("SKIP: qemu-system-arm is not installed (Debian package qemu-system-arm)")
        return SKIP
    # The QEMU test image (tools/build-arm): configs/default.ini with f_mul = 4, i.e. a
    # 16 ms end of frame (margin for this script's own pauses between pieces). Without
    # it, the plain image.
    info = subprocess.run([os.path.join(args.root, "tools", "board-env"), args.board],
                          capture_output=True, text=True)
    if info.returncode != 0:
        print(info.stderr.strip())
        return 1
    env = dict(line.split("=", 1) for line in info.stdout.splitlines() if "=" in line)
    if not env.get("QEMU_MACHINE"):
        print("SKIP: board %s has no QEMU machine (QEMU_MACHINE in its board.env)" % env["BOARD_NAME"])
        return SKIP
    name = env["BOARD_NAME"]
    plain = os.path.join(env["BOARD_BUILD"], "modcp-%s.elf" % name)
    if args.suite == "smoke":
        elf = args.elf or plain
    else:
        elf = args.elf or os.path.join(env["BOARD_BUILD"], "modcp-%s-qemu.elf" % name)
        if not os.path.exists(elf):
            elf = plain
    if not os.path.exists(elf):
        print("SKIP: no firmware image %s (build it with tools/build-arm or tools/build-board)" % elf)
        return SKIP
    if args.suite in ("libmodbus", "pymodbus") and (not args.master or not os.path.exists(args.master)):
        print("SKIP: master %s not available" % args.master)
        return SKIP

    def on_signal(signum, frame):
        raise Fail("stopped by signal %d" % signum)

    signal.signal(signal.SIGTERM, on_signal)  # ctest's timeout: stop QEMU too
    signal.signal(signal.SIGHUP, on_signal)
    signal.signal(signal.SIGALRM, on_signal)
    signal.alarm(WATCHDOG_S)  # a watchdog below ctest's TIMEOUT: never leave QEMU behind
    log("image %s" % elf)
    target = Target(args.root, args.board, env, elf, log)
    stop = threading.Event()
    tmpdir = tempfile.mkdtemp(prefix="modcp-qemu-")
    try:
        target.start()
        log("%s up: Modbus %s, console %s (%.1f s)" % (args.board, target.modbus_tty,
                                                      target.console_tty, time.time() - t_start))
        start = target.counters()
        checks = Checks(log)
        if args.suite in ("firmware", "smoke"):
            (suite_firmware if args.suite == "firmware" else suite_smoke)(target, checks)
            passed, failed, rc = checks.passed, checks.failed, 0
        else:
            fifo = os.path.join(tmpdir, "control")
            os.mkfifo(fifo)
            threading.Thread(target=bridge_fifo, args=(fifo, target, stop), daemon=True).start()
            if args.suite == "libmodbus":
                cmd = [args.master, "--device", target.modbus_tty, "--baud", "9600",
                       "--parity", "E", "--slave", str(SLAVE), "--random", str(args.random),
                       "--timeout-ms", str(int(REPLY_TIMEOUT_S * 1000))]
                # the paused user program is driven through the console: without one
                # the master leaves its pause group out
                if checks.console(target, "pause: user program paused / resumed via the console"):
                    cmd += ["--control", fifo]
            else:
                cmd = [args.python, args.master, "--device", target.modbus_tty, "--baud",
                       "9600", "--parity", "E", "--slave", str(SLAVE), "--random",
                       str(args.random), "--timeout", str(REPLY_TIMEOUT_S)]
            passed, failed, rc = run_master(cmd, log, timeout=WATCHDOG_S - 10)
        if target.has_console:
            status = target.console("status")
            log("console status: " + status)
            end = {k: int(v) for k, v in re.findall(r"(\w+)=(\d+)\b", status)}
        else:
            end = target.counters()
            log("FC08 counters: " + " ".join("%s=%d" % kv for kv in end.items()))
        if args.suite == "libmodbus":
            # master_libmodbus clears the slave's counters (FC08 sub 0A) before its random
            # operations: the end values count from there (a frame damaged before the
            # clear shows as a failed check of the master)
            start = {}
        d = {k: end.get(k, 0) - start.get(k, 0) for k in end}
        if start and not target.has_console:
            # the FC08 queries that read `start` are frames on the bus too
            for k in ("bus_msg", "slave_msg"):
                d[k] = d.get(k, 0) - len(FC08_COUNTERS)
        damaged = damage(start, end) - checks.expected_damage
        if args.suite in ("firmware", "smoke"):
            # the script's own requests: answered = a reply came (a request that must
            # stay unanswered is checked by the suite and counts as sent only)
            sent, answered = target.sent, target.replied
        else:
            # the master's requests as the slave saw them (libmodbus: since its counter
            # clear): every frame taken (bus_msg) or damaged; answered = replies sent
            # (slave_msg - no_response)
            sent = d.get("bus_msg", 0) + damage(start, end)
            answered = d.get("slave_msg", 0) - d.get("no_response", 0)
        failures = failed + max(damaged, 0)
        log("qemu_test: sent=%d answered=%d failed=%d (checks %d passed %d failed; frames "
            "damaged by the line %d, on purpose %d; samples not counted %d)"
            % (sent, answered, failures, passed, failed, damaged, checks.expected_damage,
               checks.discarded))
        ok = failures == 0 and passed > 0 and rc == 0
        if not ok and target.has_console:
            log("console diag:\n" + target.console("diag"))
        na = ", %d n/a (no console)" % checks.na if checks.na else ""
        log("%s %s: %d passed, %d failed%s, %.1f s -> %s" % (args.board, args.suite, passed, failed,
                                                            na, time.time() - t_start,
                                                            "PASS" if ok else "FAIL"))
        return 0 if ok else 1
    except Fail as e:
        log("FAIL: %s" % e)
        return 1
    finally:
        signal.alarm(0)
        for p in masters:
            if p.poll() is None:
                p.kill()
                p.wait()
        stop.set()
        target.stop()
        shutil.rmtree(tmpdir, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
