#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Faults (docs/diagnostics.md, §6; issue 3 item 7) against modcp-sim with configs/default.ini:

 - a frame for another address: silence, no event, the next good request is served;
 - a CRC-corrupted frame for us: silence, event (08)36H, CRC counter; next request served;
 - a CRC-corrupted frame for another address: silence, no event;
 - a broadcast FC03: silence, event (08)30H;
 - a paused user program: exception 04 after the CPU job timeout with (0E)31H (read)
   and (0E)3BH (FC05), the timed-out FC05 is never executed later; a second request
   while the first is pending gives (08)37H; after resume the next request is served;
 - the --trace output names what happened ("not for us", "CRC error", exception 04);
 - SIGTERM and SIGINT stop the simulator cleanly and remove the pty link.

    test_faults.py --sim PATH/modcp-sim --config configs/default.ini
"""
import argparse
import os
import signal
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402

GOOD_REQ = with_crc("05 03 00 50 00 02")
GOOD_RSP = bytes.fromhex("05 03 04 87 65 43 21 76 70")


def events_since(sim, before_total):
    st = sim.status()
    return int(st["events"]) - before_total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    t = Checks()
    t0 = time.monotonic()

    sim = Sim(a.sim, a.config, trace=True).start()
    line = RawLine(sim.device)
    cpu_timeout = 1.0  # [cpu] timeout_ms of configs/default.ini
    try:
        t.ok(line.xfer(GOOD_REQ, len(GOOD_RSP)) == GOOD_RSP, "baseline FC03 request answered")
        st0 = sim.status()
        ev0 = int(st0["events"])

        # another address
        rsp = line.xfer(with_crc("07 03 00 50 00 02"), 100, timeout=0.4)
        t.ok(rsp == b"", "frame for slave 7: no reply (got %s)" % rsp.hex(" "))
        st = sim.status()
        t.ok(int(st["events"]) == ev0, "frame for slave 7: no event")
        t.ok(int(st["slave_msg"]) == int(st0["slave_msg"]), "frame for slave 7: not counted as ours")
        t.ok(line.xfer(GOOD_REQ, len(GOOD_RSP)) == GOOD_RSP, "next good request after slave 7 served")

        # CRC error for us
        st1 = sim.status()
        bad = bytearray(GOOD_REQ)
        bad[-1] ^= 0x01
        rsp = line.xfer(bytes(bad), 100, timeout=0.4)
        t.ok(rsp == b"", "CRC-corrupted request: no reply (got %s)" % rsp.hex(" "))
        d = sim.diag()
        t.ok(d[:1] == ["0836"], "CRC-corrupted request: event (08)36H newest (diag %s)" % d[:3])
        st = sim.status()
        t.ok(int(st["bus_crc"]) == int(st1["bus_crc"]) + 1,
             "CRC-corrupted request: CRC counter %s -> %s" % (st1["bus_crc"], st["bus_crc"]))
        t.ok(line.xfer(GOOD_REQ, len(GOOD_RSP)) == GOOD_RSP, "next good request after CRC error served")

        # CRC error for another address: not checked
        ev1 = int(sim.status()["events"])
        bad = bytearray(with_crc("07 03 00 50 00 02"))
        bad[-2] ^= 0x40
        rsp = line.xfer(bytes(bad), 100, timeout=0.4)
        t.ok(rsp == b"", "CRC-corrupted frame for slave 7: no reply")
        t.ok(int(sim.status()["events"]) == ev1, "CRC-corrupted frame for slave 7: no event")

        # broadcast of a read
        rsp = line.xfer(with_crc("00 03 00 50 00 02"), 100, timeout=0.4)
        t.ok(rsp == b"", "broadcast FC03: no reply")
        t.ok(sim.diag()[:1] == ["0830"], "broadcast FC03: event (08)30H")

        # paused user program
        t.ok(sim.cmd("set Q257.3 0") == ["Q257.3 = 0"], "console: Q257.3 cleared")
        t.ok(sim.cmd("pause") == ["user program paused"], "console: pause")
        line.flush()
        t1 = time.monotonic()
        rsp = line.xfer(GOOD_REQ, 5, timeout=cpu_timeout + 2.0)
        dt = time.monotonic() - t1
        t.ok(rsp == with_crc("05 83 04"), "paused: FC03 -> exception 04 (%s)" % rsp.hex(" "))
        t.ok(0.9 * cpu_timeout <= dt <= cpu_timeout + 1.0,
             "paused: exception after %.0f ms (CPU job timeout %.0f ms)" % (dt * 1000, cpu_timeout * 1000))
        t.ok(sim.diag()[:1] == ["0E31"], "paused: event (0E)31H (timeout of the transfer to the CPU)")
        t1 = time.monotonic()
        rsp = line.xfer(with_crc("05 05 08 0B FF 00"), 5, timeout=cpu_timeout + 2.0)
        dt = time.monotonic() - t1
        t.ok(rsp == with_crc("05 85 04"), "paused: FC05 -> exception 04 (%s)" % rsp.hex(" "))
        t.ok(0.9 * cpu_timeout <= dt <= cpu_timeout + 1.0, "paused: FC05 exception after %.0f ms" % (dt * 1000))
        t.ok(sim.diag()[:1] == ["0E3B"], "paused: event (0E)3BH (timeout of the FB's write job)")

        # a second request while the first one is pending
        line.flush()
        line.send(GOOD_REQ)
        time.sleep(0.2)
        line.send(with_crc("05 03 00 51 00 01"))
        rsp = line.recv(100, cpu_timeout + 1.5)
        t.ok(rsp == with_crc("05 83 04"),
             "paused: two requests: one exception 04 for the first, nothing for the second (%s)" % rsp.hex(" "))
        d = sim.diag()
        t.ok("0837" in d[:3], "paused: second request while one is pending: event (08)37H (diag %s)" % d[:3])

        t.ok(sim.cmd("resume") == ["user program running"], "console: resume")
        time.sleep(0.1)
        t.ok(line.xfer(GOOD_REQ, len(GOOD_RSP)) == GOOD_RSP, "resumed: next good request served")
        t.ok(sim.get("Q257.3") == 0, "resumed: the timed-out FC05 was not executed later")
        rsp = line.xfer(with_crc("05 05 08 0B FF 00"), 8)
        t.ok(rsp == with_crc("05 05 08 0B FF 00"), "resumed: FC05 Q257.3 works again")
        t.ok(sim.get("Q257.3") == 1, "resumed: Q257.3 = 1 in the controller memory")
        st = sim.status()
        t.ok(st.get("fb") == "RUN" and st.get("cp") == "ready", "status: fb=RUN cp=ready")

        # trace
        tr = "\n".join(sim.trace_lines())
        t.ok("not for us (slave 7)" in tr, "trace: 'not for us (slave 7)'")
        t.ok("CRC error" in tr, "trace: 'CRC error'")
        t.ok("FC03 exception 04 (slave device failure)" in tr, "trace: 'FC03 exception 04'")
        t.ok("event (08)36H" in tr and "event (0E)31H" in tr, "trace: events (08)36H, (0E)31H")
        t.ok("slave 5 FC03 read holding registers addr 0x0050 (80) qty 2" in tr,
             "trace: request decoded")
    finally:
        line.close()
        rc, gone = sim.stop()
    t.ok(rc == 0, "SIGTERM: modcp-sim exit code %s" % rc)
    t.ok(gone, "SIGTERM: pty link removed")
    t.ok(any("stopped (SIGTERM)" in l for l in sim.lines), "SIGTERM: 'stopped (SIGTERM)'")

    sim = Sim(a.sim, a.config, control=False).start()
    link = sim.device
    sim.proc.send_signal(signal.SIGINT)
    try:
        rc = sim.proc.wait(timeout=5)
    except Exception:
        rc = None
    t.ok(rc == 0, "SIGINT: modcp-sim exit code %s" % rc)
    t.ok(not os.path.lexists(link), "SIGINT: pty link removed")
    sim.stop()
    print("test_faults: %.1f s" % (time.monotonic() - t0))
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
