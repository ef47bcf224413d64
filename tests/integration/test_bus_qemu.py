#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""A QEMU board and a host-simulated slave on one line (issue 15 item 3):

    tools/run-qemu mps2-an385            -> slave 5 (the image's default.ini) on MODBUS_TTY
    modcp-sim default.ini --set protocol.slave_address=6 --qemu-member MODBUS_TTY

 - both answer FC03 by address through the one pty (bytes checked);
 - a broadcast FC06 lands in both (read back from each);
 - the trace names the emulated board's replies (@qemu (external)).
Exit 77 (skipped) when the image is missing (tools/build-arm builds it).

    test_bus_qemu.py --sim PATH/modcp-sim --root SOURCE_DIR [--board mps2-an385]
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("--board", default="mps2-an385")
    a = ap.parse_args()
    # the QEMU test twin (f_mul = 4: a 16 ms end of frame, tools/build-arm): the bus paces
    # the bytes it forwards in host time, so a busy host must not split a frame
    elf = os.path.join(a.root, "build", a.board, "modcp-%s-qemu.elf" % a.board)
    if not os.path.exists(elf):
        print("skipped: no image %s (tools/build-arm builds it)" % elf)
        return 77
    t = Checks()
    q = subprocess.Popen([os.path.join(a.root, "tools", "run-qemu"), a.board, "--elf", elf], cwd=a.root,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         start_new_session=True)
    tty = None
    end = time.monotonic() + 20
    while time.monotonic() < end and tty is None:
        line = q.stdout.readline()
        m = re.match(r"MODBUS_TTY=(\S+)", line)
        if m:
            tty = m.group(1)
    sim = None
    try:
        t.ok(tty is not None, "tools/run-qemu %s: Modbus pty %s" % (a.board, tty))
        time.sleep(1.0)  # the image initialises its FB
        sim = Sim(a.sim, os.path.join(a.root, "configs", "default.ini"),
                  sets=["protocol.slave_address=6"], trace=True,
                  extra=["--qemu-member", tty]).start()
        line = RawLine(sim.device)
        for rnd in range(3):
            for addr in (5, 6):
                time.sleep(0.05)
                want = with_crc("%02X 03 04 87 65 43 21" % addr)
                got = line.xfer(with_crc("%02X 03 00 50 00 02" % addr), len(want), timeout=2.0)
                t.ok(got == want, "round %d: slave %d (%s) answers FC03 (%s)"
                     % (rnd, addr, "QEMU" if addr == 5 else "host", got.hex(" ")))
        time.sleep(0.05)
        line.send(with_crc("00 06 00 64 5A 3C"))
        time.sleep(0.5)
        for addr in (5, 6):
            want = with_crc("%02X 03 02 5A 3C" % addr)
            got = line.xfer(with_crc("%02X 03 00 64 00 01" % addr), len(want), timeout=2.0)
            t.ok(got == want, "broadcast FC06 landed in slave %d (%s)" % (addr, got.hex(" ")))
            time.sleep(0.05)
        line.close()
        tr = "\n".join(sim.trace_lines())
        t.ok("@qemu (external) 05 03 04 87 65 43 21" in tr, "trace: the board's reply named @qemu")
        t.ok("@default slave 6 06 03 04 87 65 43 21" in tr, "trace: the host slave's reply named")
    finally:
        if sim is not None:
            sim.stop()
        os.killpg(q.pid, signal.SIGTERM)
        q.wait(timeout=20)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
