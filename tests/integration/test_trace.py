#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The text trace reads the line (issue 22): modcp-sim --trace --capture FILE.pcap prints
the frames the capture records, at the same times (the first start bit of each frame), in
the same order, and the events and console answers in time order with them.

 - one slave (configs/default.ini, 9600 8E1, slave 5): FC03, a request with a wrong CRC,
   one for slave 7, `echo` on the console, FC06. The trace's frame lines and the
   capture's Modbus RTU records: the same 6 frames, the same senders (master / slave 5
   by the P2P direction), units and function codes, and every trace time equal to its
   record's time less one offset (the simulator's start); event (08)36H follows the
   request with the wrong CRC, before the next frame; the console answer comes after the
   frames before it and before the frames after it; "not for us (slave 7)".
 - a bus (@a at 1, @b at 2): FC03 to each; "@a slave 1" and "@b slave 2" with the times
   of the capture's records from source ports 1 and 2.

    test_trace.py --sim PATH/modcp-sim --config configs/default.ini
"""
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import run_checks, RawLine, Sim, member_configs, with_crc  # noqa: E402

FRAME = re.compile(r"\[\s*(\d+)\.(\d{6})\] (master|slave \d+|@\w+ slave \d+) ((?:[0-9A-F]{2} )*[0-9A-F]{2}) \| (.*)")


def tshark(path, *fields):
    args = ["tshark", "-r", path, "-Y", "mbrtu", "-T", "fields", "-E", "separator=|"]
    for f in fields:
        args += ["-e", f]
    out = subprocess.run(args, capture_output=True, text=True, timeout=60)
    if out.returncode != 0:
        raise RuntimeError("tshark failed: " + out.stderr)
    return [l.split("|") for l in out.stdout.splitlines()]


def frames_of(lines):
    """(us since start, sender, unit, function, index in lines) of every frame line."""
    out = []
    for i, l in enumerate(lines):
        m = FRAME.match(l)
        if m:
            b = m.group(4).split()
            out.append((int(m.group(1)) * 1000000 + int(m.group(2)), m.group(3), int(b[0], 16),
                        int(b[1], 16), i))
    return out


def same_times(t, what, trace, records):
    """Every trace time is its record's time (us since the epoch) less one offset."""
    offs = [rec - tr for tr, rec in zip(trace, records)]
    t.ok(len(trace) == len(records) and len(offs) > 0 and max(offs) - min(offs) <= 1,
         "%s: trace times = capture times - one offset (offsets %s us)" % (what, offs))


def one_slave(a, t, tmp):
    pcap = os.path.join(tmp, "one.pcap")
    sim = Sim(a.sim, a.config, trace=True, extra=["--capture", pcap]).start()
    line = RawLine(sim.device)
    try:
        t.ok(line.xfer(with_crc("05 03 00 50 00 02"), 9).hex() == "050304876543217670",
             "FC03 answered")
        time.sleep(0.05)
        bad = bytearray(with_crc("05 03 00 50 00 02"))
        bad[-1] ^= 0x01
        line.send(bytes(bad))
        time.sleep(0.1)
        line.send(with_crc("07 03 00 50 00 02"))
        time.sleep(0.1)
        ans = sim.cmd("echo MARK-1")
        t.ok(ans == ["MARK-1"], "console answer (%s)" % ans)
        t.ok(len(line.xfer(with_crc("05 06 00 64 12 34"), 8)) == 8, "FC06 answered")
        time.sleep(0.05)
        line.send(with_crc("05 06 00 64 00 00"))  # memory as it was
        line.recv(8, 1.0)
    finally:
        line.close()
        rc, _ = sim.stop()
    t.ok(rc == 0, "simulator stopped cleanly")
    lines = sim.lines
    fr = frames_of(lines)
    recs = tshark(pcap, "frame.time_epoch", "exported_pdu.p2p_dir", "mbrtu.unit_id",
                  "modbus.func_code")
    t.ok(len(fr) == 8 and len(recs) == 8, "8 frames in the trace and in the capture (%d, %d)"
         % (len(fr), len(recs)))
    t.ok([f[1] for f in fr] == ["master", "slave 5", "master", "master", "master", "slave 5",
                                "master", "slave 5"],
         "trace senders in order (%s)" % [f[1] for f in fr])
    t.ok(["0" if f[1] == "master" else "1" for f in fr] == [r[1] for r in recs],
         "the capture's directions in the same order (%s)" % [r[1] for r in recs])
    t.ok([(str(f[2]), str(f[3])) for f in fr] == [(r[2], r[3]) for r in recs],
         "the same units and function codes in the same order (%s)" % [(r[2], r[3]) for r in recs])
    same_times(t, "one slave", [f[0] for f in fr],
               [int(round(float(r[0]) * 1e6)) for r in recs])
    ev = [i for i, l in enumerate(lines) if "event (08)36H" in l]
    bad_i = fr[2][4]
    t.ok(len(ev) == 1 and bad_i < ev[0] < fr[3][4],
         "event (08)36H after the request with the wrong CRC, before the next frame")
    if ev:
        ev_t = re.match(r"\[\s*(\d+)\.(\d{6})\]", lines[ev[0]])
        ev_us = int(ev_t.group(1)) * 1000000 + int(ev_t.group(2))
        t.ok(ev_us >= fr[2][0] + 8 * 1146, "the event's time (%d) after the request's end (%d)"
             % (ev_us, fr[2][0] + 8 * 1146))
    mark = lines.index("MARK-1") if "MARK-1" in lines else -1
    t.ok(fr[3][4] < mark < fr[4][4],
         "the console answer after the frames before it, before the FC06 after it")
    t.ok("not for us (slave 7)" in lines[fr[3][4]], "slave 7's request: not for us")
    t.ok("CRC error, slave 5 FC03" in lines[fr[2][4]], "the wrong CRC named")


def bus(a, t, tmp):
    cfgs = member_configs(a.config, tmp, [("a", 1), ("b", 2)])
    pcap = os.path.join(tmp, "bus.pcap")
    sim = Sim(a.sim, cfgs[0], trace=True, extra=cfgs[1:] + ["--capture", pcap]).start()
    line = RawLine(sim.device)
    try:
        for addr in (1, 2):
            want = with_crc("%02X 03 04 87 65 43 21" % addr)
            t.ok(line.xfer(with_crc("%02X 03 00 50 00 02" % addr), 9) == want,
                 "bus: slave %d answered" % addr)
            time.sleep(0.05)
    finally:
        line.close()
        sim.stop()
    fr = frames_of(sim.lines)
    recs = tshark(pcap, "frame.time_epoch", "exported_pdu.src_port", "mbrtu.unit_id")
    t.ok([f[1] for f in fr] == ["master", "@a slave 1", "master", "@b slave 2"],
         "bus: the trace names the members (%s)" % [f[1] for f in fr])
    t.ok([r[1] for r in recs] == ["0", "1", "0", "2"],
         "bus: the capture's source ports (%s)" % [r[1] for r in recs])
    same_times(t, "bus", [f[0] for f in fr], [int(round(float(r[0]) * 1e6)) for r in recs])


def main():
    return run_checks("modcp-trace-", ("tshark",), [one_slave, bus])


if __name__ == "__main__":
    sys.exit(main())
