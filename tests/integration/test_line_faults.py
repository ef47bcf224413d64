#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Serial-layer faults (issue 22 item 3): one slave (configs/default.ini, 9600 8E1, slave
5) as it runs by default (no --bus: a line of one member), faults in the master's direction
(@master) and in its replies, from the console and from --fault, each off by default and
counted in `status` (its faults line once it had one); for each, what the manuals require of the slave (CP 341 / CP 441-2 manual,
"Diagnostic messages of the MODBUS slave driver", and the Modbus serial line spec):

 - parity error in a request byte: event (08)0CH, char_errors + 1, the request dropped;
 - framing error: (08)0CH likewise;
 - BREAK inside a request: (08)0DH, breaks + 1, the request dropped;
 - a pause t1.5 < X < t3.5 inside a request (2300 us: its character ends 3446 us after
   the one before, 581 us past t1.5 + 1 character and 564 us before t3.5): with t15_check on (08)06H, t15 + 1, dropped;
   with t15_check off (the default) the request is answered;
 - a pause X > t3.5 inside a request: two frames, the first with a wrong CRC: (08)36H,
   bus_crc + 1, nothing answered;
 - DE released early: the last stop bit cut (1 bit): the character is whole, answered;
   5 bits cut: the CRC's high bits read as 1, (08)36H, dropped;
 - a master that starts its next request 500 us (< t3.5) after a reply: answered (the
   slave's receiver is idle once its reply is out);
 - a reply delayed past the master's timeout: the master sees nothing in time, the late
   reply arrives afterwards, and the next request is answered;
 - in the member's replies: a parity error, a BREAK, DE cut 5 bits: the master reads a 0
   byte in place of the erroneous character (termios with INPCK, no PARMRK), an extra 0
   for the BREAK, the last byte with its high bits 1; counted in the member's faults;
 - --fault @master:parity=2 from the command line; the capture shows the line events as
   LINE records (tshark).

    test_line_faults.py --sim PATH/modcp-sim --config configs/default.ini
"""
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import run_checks, RawLine, Sim, with_crc  # noqa: E402

REQ = with_crc("05 03 00 50 00 02")
RSP = bytes.fromhex("05 03 04 87 65 43 21 76 70")


def kv(line):
    return dict(p.split("=", 1) for p in line.split() if "=" in p)


def master_faults(sim):
    ans = sim.cmd("@master fault")
    return kv(ans[0].split("|", 1)[1]) if ans and "|" in ans[0] else {}


def member_faults(sim):
    ans = sim.cmd("status")
    line = [l for l in ans if l.startswith("faults:")]
    return kv(line[0].split("|", 1)[1]) if line else {}


def status_shows_master(sim):
    return any(l.startswith("@master master faults:") for l in sim.cmd("status"))


class Case:
    def __init__(self, sim, line, t):
        self.sim, self.line, self.t = sim, line, t

    def clean(self, what):
        self.line.recv(64, 0.05)
        rsp = self.line.xfer(REQ, len(RSP), timeout=1.0)
        self.t.ok(rsp == RSP, "%s: the next clean request is answered (%s)" % (what, rsp.hex(" ")))

    def dropped(self, fault, event, counter, what, sim_counter, frames=1):
        st0 = self.sim.status()
        mf0 = master_faults(self.sim)
        ans = self.sim.cmd("@master fault " + fault)
        self.t.ok(ans and ans[0].startswith("@master master faults: serial:"), "%s: set (%s)" % (what, ans))
        rsp = self.line.xfer(REQ, len(RSP), timeout=0.5)
        self.sim.cmd("@master fault off")
        self.t.ok(rsp == b"", "%s: not answered (got %s)" % (what, rsp.hex(" ")))
        d = self.sim.diag()
        self.t.ok(d[:1] == [event], "%s: event (%s)%sH newest (diag %s)" % (what, event[:2], event[2:], d[:3]))
        st = self.sim.status()
        self.t.ok(int(st[counter]) == int(st0[counter]) + frames,
                  "%s: %s %s -> %s" % (what, counter, st0[counter], st[counter]))
        mf = master_faults(self.sim)
        self.t.ok(int(mf[sim_counter]) == int(mf0[sim_counter]) + 1,
                  "%s: counted in the master's faults (%s %s -> %s)" % (what, sim_counter,
                                                                        mf0[sim_counter], mf[sim_counter]))
        self.clean(what)

    def answered(self, fault, what, sim_counter):
        mf0 = master_faults(self.sim)
        ev0 = int(self.sim.status()["events"])
        self.sim.cmd("@master fault " + fault)
        rsp = self.line.xfer(REQ, len(RSP), timeout=1.0)
        rsp2 = self.line.xfer(REQ, len(RSP), timeout=1.0)  # at once after a reply
        self.sim.cmd("@master fault off")
        self.t.ok(rsp == RSP and rsp2 == RSP, "%s: answered (%s / %s)" % (what, rsp.hex(" "), rsp2.hex(" ")))
        self.t.ok(int(self.sim.status()["events"]) == ev0, "%s: no event" % what)
        mf = master_faults(self.sim)
        self.t.ok(int(mf[sim_counter]) > int(mf0[sim_counter]), "%s: counted (%s %s -> %s)"
                  % (what, sim_counter, mf0[sim_counter], mf[sim_counter]))


def master_direction(a, t, tmp):
    pcap = os.path.join(tmp, "faults.pcap")
    sim = Sim(a.sim, a.config, extra=["--capture", pcap]).start()
    line = RawLine(sim.device)
    try:
        mf = master_faults(sim)
        t.ok(mf and all(v == "0" for v in mf.values()), "master faults off and zero by default (%s)" % mf)
        t.ok(not status_shows_master(sim), "status: no line for the master's direction while it "
             "never had a fault")
        c = Case(sim, line, t)
        c.clean("baseline")
        c.dropped("parity=3", "080C", "char_errors", "parity error on byte 3", "parity_errors")
        c.dropped("framing=2", "080C", "char_errors", "framing error on byte 2", "framing_errors")
        c.dropped("break=10", "080D", "breaks", "BREAK of 10 ms", "breaks")
        # two frames, both with a wrong CRC (the second begins 00 02: a broadcast)
        c.dropped("gap=4:8000", "0836", "bus_crc", "gap of 8000 us (> t3.5) after byte 4", "gaps",
                  frames=2)
        c.dropped("de_cut=5", "0836", "bus_crc", "DE released 5 bits early", "de_cuts")
        c.answered("gap=4:2300", "gap of 2300 us (t1.5 = 1719 < X < t3.5 = 4010), t15_check off", "gaps")
        c.answered("de_cut=1", "DE released in the last stop bit", "de_cuts")
        c.answered("early=500", "next request 500 us after the reply (< t3.5 = 4010 us)", "early")
        t.ok(status_shows_master(sim), "status: the master's direction's faults and counters")
        member_direction(sim, line, t)
        delayed_reply(sim, line, t)
    finally:
        line.close()
        sim.stop()
    rows = subprocess.run(["tshark", "-r", pcap, "-Y", 'exported_pdu.col_proto_str == "LINE"',
                           "-T", "fields", "-e", "text"], capture_output=True, text=True,
                          timeout=60).stdout
    for want in ("parity error on byte 2", "framing error on byte 1", "BREAK 10.000 ms",
                 "DE released"):
        t.ok(want in rows, "capture: a LINE record '%s'" % want)


def member_direction(sim, line, t):
    t.ok(member_faults(sim) == {}, "status: no faults line while the slave never had a fault")
    sim.cmd("fault off")
    f0 = member_faults(sim)
    t.ok(f0 and all(f0[k] == "0" for k in ("parity_errors", "breaks", "de_cuts")),
         "status: its faults line, zero, once a fault was set (%s)" % f0)
    sim.cmd("fault parity=3")
    rsp = line.xfer(REQ, len(RSP), timeout=1.0)
    sim.cmd("fault off")
    t.ok(rsp == RSP[:2] + b"\x00" + RSP[3:], "reply byte 3 with a parity error: the master reads "
         "0x00 there (%s)" % rsp.hex(" "))
    sim.cmd("fault break=5")
    rsp = line.xfer(REQ, len(RSP) + 1, timeout=1.0)
    sim.cmd("fault off")
    t.ok(rsp == RSP[:1] + b"\x00" + RSP[1:], "reply with a BREAK after byte 1: a 0x00 between "
         "bytes 1 and 2 (%s)" % rsp.hex(" "))
    sim.cmd("fault de_cut=5")
    rsp = line.xfer(REQ, len(RSP), timeout=1.0)
    sim.cmd("fault off")
    # 8E1: bits 6..8 of the data, the parity and the stop bit idle at 1: 0x70 becomes 0xF0,
    # whose even parity bit would be 0: a parity error, read as 0x00
    t.ok(rsp == RSP[:-1] + b"\x00", "reply with DE off 5 bits early: the last byte 0x70 arrives "
         "as 0xF0 with a parity error, read as 0x00 (%s)" % rsp.hex(" "))
    f = member_faults(sim)
    for k in ("parity_errors", "breaks", "de_cuts"):
        t.ok(int(f[k]) == int(f0[k]) + 1, "member's faults: %s %s -> %s" % (k, f0[k], f[k]))
    line.recv(64, 0.05)


def delayed_reply(sim, line, t):
    sim.cmd("fault delay=400")
    t0 = time.monotonic()
    rsp = line.xfer(REQ, len(RSP), timeout=0.2)
    t.ok(rsp == b"", "reply delayed 400 ms: nothing within the master's 200 ms timeout")
    late = line.recv(len(RSP), 1.0)
    t.ok(late == RSP and time.monotonic() - t0 >= 0.39, "the late reply arrives after 400 ms")
    sim.cmd("fault off")
    rsp = line.xfer(REQ, len(RSP), timeout=1.0)
    t.ok(rsp == RSP, "after the late reply the next request is answered")


def t15_on(a, t):
    sim = Sim(a.sim, a.config, sets=["protocol.t15_check=on"],
              extra=["--fault", "@master:parity=2"]).start()
    line = RawLine(sim.device)
    try:
        rsp = line.xfer(REQ, len(RSP), timeout=0.5)
        t.ok(rsp == b"" and sim.diag()[:1] == ["080C"],
             "--fault @master:parity=2 from the command line: dropped, (08)0CH")
        sim.cmd("@master fault off")
        c = Case(sim, line, t)
        c.clean("--fault @master:parity=2 off")
        c.dropped("gap=4:2300", "0806", "t15", "gap of 2300 us with t15_check on", "gaps")
    finally:
        line.close()
        sim.stop()


def main():
    return run_checks("modcp-linefaults-", ("tshark",), [master_direction, lambda a, t, tmp: t15_on(a, t)])


if __name__ == "__main__":
    sys.exit(main())
