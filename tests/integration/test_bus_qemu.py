#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""A QEMU board and a host-simulated slave on one line (issue 15 item 3):

    tools/run-qemu mps2-an385            -> slave 5 (the image's default.ini) on MODBUS_TTY
    modcp-sim default.ini --set protocol.slave_address=6 --qemu-member MODBUS_TTY

 - both answer FC03 by address through the one pty (bytes checked);
 - a broadcast FC06 lands in both (read back from each);
 - the trace names the emulated board's replies (@qemu (external));
 - --capture: tshark decodes the board's replies as Modbus RTU (unit 5, FC03, 0x8765
   0x4321) from the board's source port (2: the members are @default = 1, @qemu = 2),
   slave direction, with its DE records "DE on (qemu)" / "DE off (qemu)" around them;
   --vcd: the board's signals qemu_tx and qemu_de.
Exit 77 (skipped) when the image is missing (tools/build-arm builds it).

    test_bus_qemu.py --sim PATH/modcp-sim --root SOURCE_DIR [--board mps2-an385]
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
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
    if shutil.which("tshark") is None:
        print("tshark missing: tools/install-deps installs it")
        return 1
    t = Checks()
    tmp = tempfile.mkdtemp(prefix="modcp-busqemu-")
    pcap = os.path.join(tmp, "qemu.pcap")
    vcd = os.path.join(tmp, "qemu.vcd")
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
                  extra=["--qemu-member", tty, "--capture", pcap, "--vcd", vcd]).start()
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
    finally:
        if sim is not None:
            sim.stop()
        os.killpg(q.pid, signal.SIGTERM)
        q.wait(timeout=20)
    try:
        if sim is not None:
            tr = "\n".join(sim.trace_lines())  # complete: the simulator has stopped
            t.ok("@qemu (external) 05 03 04 87 65 43 21" in tr, "trace: the board's reply named @qemu")
            t.ok("@default slave 6 06 03 04 87 65 43 21" in tr, "trace: the host slave's reply named")
            captured(t, pcap, vcd)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return t.done()


def captured(t, pcap, vcd):
    """The QEMU member's frames in the capture and the waveform."""
    out = subprocess.run(["tshark", "-r", pcap, "-T", "fields", "-E", "separator=|",
                          "-e", "exported_pdu.prot_name", "-e", "exported_pdu.p2p_dir",
                          "-e", "exported_pdu.src_port", "-e", "mbrtu.unit_id",
                          "-e", "modbus.func_code", "-e", "modbus.regval_uint16", "-e", "text"],
                         capture_output=True, text=True, timeout=60)
    rows = [l.split("|") for l in out.stdout.splitlines()]
    board = [r for r in rows if r[0] == "mbrtu" and r[2] == "2"]
    fc03 = [r for r in board if r[1] == "1" and r[3] == "5" and r[4] == "3" and r[5] == "34661,17185"]
    t.ok(len(fc03) == 3, "capture: the board's 3 FC03 replies decoded as Modbus RTU, unit 5, "
         "0x8765 0x4321, from source port 2, slave direction (%d of %d)" % (len(fc03), len(board)))
    t.ok(len(board) == 4, "capture: the board's 4 replies, none else from its port (%d)"
         % len(board))
    de = [r[6] for r in rows if r[2] == "2" and r[0] == "data-text-lines"]
    t.ok(de.count("DE on (qemu)\\n") == len(board) and de.count("DE off (qemu)\\n") == len(board),
         "capture: DE on / off (qemu) around each of its replies (%s)" % de[:4])
    host = [r for r in rows if r[0] == "mbrtu" and r[2] == "1" and r[3] == "6"]
    t.ok(len(host) == 4, "capture: the host slave's 4 replies from source port 1 (%d)" % len(host))
    with open(vcd) as f:
        head = f.read(4000)
    for sig in ("qemu_tx", "qemu_de"):
        t.ok(re.search(r"\$var wire 1 \S+ %s \$end" % sig, head) is not None,
             "waveform declares %s" % sig)


if __name__ == "__main__":
    sys.exit(main())
