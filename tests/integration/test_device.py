#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp-sim --device: the serial-device path of the POSIX HAL (termios from the
parameters, PARMRK decoding of the received stream). The "device" is the slave side of
a pseudo-terminal pair made here; the test is the master on the other side. Frames
carry 0xFF bytes (escaped as FF FF by PARMRK) and must come through unchanged; replies
must be complete before the next request, so no (08)37H.

    test_device.py --sim PATH/modcp-sim --config configs/default.ini
"""
import argparse
import os
import pty
import select
import subprocess
import sys
import time
import tty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, with_crc  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    t = Checks()
    master, slave = pty.openpty()
    tty.setraw(master)
    dev = os.ttyname(slave)
    p = subprocess.Popen([a.sim, a.config, "--device", dev, "--set", "serial.baud=38400"],
                         stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True)
    lines = []
    end = time.monotonic() + 10
    while time.monotonic() < end:
        line = p.stdout.readline()
        if not line:
            break
        lines.append(line.rstrip())
        if line.strip() == "modcp-sim: ready":
            break
    t.ok(lines and lines[0] == "modcp-sim: slave 5 on %s (38400 8E1 RTU)" % dev,
         "modcp-sim on the device %s: %r" % (dev, lines[:1]))
    t.ok("modcp-sim: ready" in lines, "ready")

    def xfer(hexreq, want, timeout=1.5):
        os.write(master, with_crc(hexreq))
        out = b""
        stop = time.monotonic() + timeout
        while len(out) < want and time.monotonic() < stop:
            r, _, _ = select.select([master], [], [], stop - time.monotonic())
            if r:
                out += os.read(master, want - len(out))
        return out

    for i in range(3):  # back to back: the next request right after the reply
        rsp = xfer("05 03 00 50 00 02", 9)
        t.ok(rsp == bytes.fromhex("05 03 04 87 65 43 21 76 70"), "FC03 example #%d: %s" % (i, rsp.hex(" ")))
        rsp = xfer("05 05 08 09 FF 00", 8)
        t.ok(rsp == with_crc("05 05 08 09 FF 00"), "FC05 with an FF byte #%d: %s" % (i, rsp.hex(" ")))
    rsp = xfer("05 06 00 64 FF FF", 8)
    t.ok(rsp == with_crc("05 06 00 64 FF FF"), "FC06 value FFFF: %s" % rsp.hex(" "))
    rsp = xfer("05 10 00 65 00 02 04 FF 00 00 FF", 8)
    t.ok(rsp == with_crc("05 10 00 65 00 02"), "FC16 FF00 00FF: %s" % rsp.hex(" "))
    rsp = xfer("05 03 00 64 00 03", 11)
    t.ok(rsp == with_crc("05 03 06 FF FF FF 00 00 FF"), "FC03 reads FFFF FF00 00FF back: %s" % rsp.hex(" "))
    p.stdin.write("diag\necho __end__\n")
    p.stdin.flush()
    diag = []
    while True:
        line = p.stdout.readline()
        if not line or line.strip() == "__end__":
            break
        diag.append(line.rstrip())
    events = [ln for ln in diag if ln.startswith("event ")]
    t.ok(diag and all("(00)03H" in ln for ln in events),
         "no events but the start-up's (00)03H (no (08)37H, no CRC error): %s" % diag[:3])
    p.terminate()
    t.ok(p.wait(timeout=5) == 0, "SIGTERM: exit 0")
    os.close(master)
    os.close(slave)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
