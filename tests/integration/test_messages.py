#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp-sim's messages a person reads (issue 14 item 3), asserted word for word:

 - --pty-link PATH held by a running instance: refused, the PID named, the link kept;
   a link to a device nobody holds: refused; a stale link (its pty gone): replaced;
 - --device that is not a serial port: "not a serial device";
 - an option without its value (--cycle-ms): "needs a value";
 - a bad --set value is blamed on the option, not on the config file;
 - the trace names the sender of every frame, is in time order, and in ASCII shows a
   byte that is not printable in hex (<E9>) and an odd number of hex digits as such.

    test_messages.py --sim PATH/modcp-sim --config configs/default.ini
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402


def run(args, timeout=10):
    p = subprocess.run(args, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                       timeout=timeout)
    return p.returncode, p.stdout, p.stderr.splitlines()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    t = Checks()
    tmp = tempfile.mkdtemp(prefix="modcp-msg-")

    # a second instance on the link of a running one
    sim = Sim(a.sim, a.config).start()
    try:
        rc, out, err = run([a.sim, a.config, "--pty-link", sim.device])
        want = ("modcp-sim: --pty-link %s is in use: it points at %s, held by PID %d (modcp-sim); "
                "not replaced (stop that instance or choose another path)"
                % (sim.device, sim.pty, sim.proc.pid))
        t.ok(rc == 1 and err == [want], "link of a running instance: refused, PID named (%r)" % err)
        t.ok(os.path.islink(sim.device) and os.readlink(sim.device) == sim.pty,
             "link of a running instance: still points at its pty")
        t.ok(sim.cmd("status")[0].startswith("fb=RUN") or sim.status().get("fb") == "RUN",
             "the running instance is untouched")
    finally:
        sim.stop()

    link = os.path.join(tmp, "tty")
    target = os.path.join(tmp, "not-a-pty")
    open(target, "w").close()
    os.symlink(target, link)
    rc, out, err = run([a.sim, a.config, "--pty-link", link])
    t.ok(rc == 1 and err == ["modcp-sim: --pty-link %s exists and points at %s, which no "
                             "process holds; not replaced (remove it or choose another path)"
                             % (link, target)],
         "link to a device nobody holds: refused (%r)" % err)
    os.unlink(link)
    with open(link, "w") as f:
        f.write("x")
    rc, out, err = run([a.sim, a.config, "--pty-link", link])
    t.ok(rc == 1 and err == ["modcp-sim: --pty-link %s exists and is not a symbolic link; "
                             "not replaced" % link], "regular file: refused (%r)" % err)
    os.unlink(link)
    os.symlink("/dev/pts/999999", link)  # a stale link: its pty is gone
    sim = Sim(a.sim, a.config, extra=())
    sim.link = link
    sim.args[sim.args.index("--pty-link") + 1] = link
    sim.start()
    t.ok(os.readlink(link) == sim.pty, "stale link: replaced by the new pty")
    sim.stop()

    # --device
    for dev in ("/dev/null", os.path.abspath(__file__)):
        rc, out, err = run([a.sim, a.config, "--device", dev])
        t.ok(rc == 1 and err == ["modcp-sim: --device %s: not a serial device" % dev],
             "--device %s: 'not a serial device' (%r)" % (dev, err))

    # options without a value
    rc, out, err = run([a.sim, a.config, "--cycle-ms"])
    t.ok(rc == 1 and err == ["modcp-sim: --cycle-ms needs a value (the user program's cycle in ms, "
                             "1..60000)"], "--cycle-ms without a value (%r)" % err)
    rc, out, err = run([a.sim, a.config, "--set", "--trace"])
    t.ok(rc == 1 and err == ["modcp-sim: --set needs a value (section.key=value)"],
         "--set followed by another option (%r)" % err)

    # a bad --set value
    rc, out, err = run([a.sim, a.config, "--set", "serial.baud=7"])
    t.ok(rc == 2 and len(err) == 2 and err[0].startswith("--set serial.baud=7: must be one of 300,")
         and err[1] == "modcp-sim: --set: 1 problem, not started",
         "--set serial.baud=7 blamed on the option (%r)" % err)
    rc, out, err = run([a.sim, a.config, "--set", "serial.parity=odd", "--set", "cpu.cycle_ms=x"])
    t.ok(rc == 2 and err[-1] == "modcp-sim: --set: 1 problem, not started"
         and any(l.startswith("--set cpu.cycle_ms=x: ") for l in err),
         "second --set named (%r)" % err)

    # trace: senders, time order (RTU)
    sim = Sim(a.sim, a.config, trace=True).start()
    line = RawLine(sim.device)
    try:
        req = with_crc("05 03 00 50 00 02")
        t.ok(len(line.xfer(req, 9)) == 9, "RTU: request answered")
        bad = bytearray(req)
        bad[-1] ^= 1
        line.xfer(bytes(bad), 100, timeout=0.3)
        time.sleep(0.1)
        tr = sim.trace_lines()
        t.ok(any(re.match(r"\[\s*\d+\.\d{6}\] master 05 03 00 50 00 02 \S\S \S\S \| slave 5 FC03", l)
                 for l in tr), "RTU trace: the request marked 'master'")
        t.ok(any(re.match(r"\[\s*\d+\.\d{6}\] slave 5 05 03 04 ", l) for l in tr),
             "RTU trace: the reply marked 'slave 5'")
        ts = [float(re.match(r"\[\s*(\d+\.\d{6})\]", l).group(1)) for l in tr]
        t.ok(ts == sorted(ts), "RTU trace: lines in time order (%s)" % ts)
    finally:
        line.close()
        sim.stop()

    # trace: ASCII
    sim = Sim(a.sim, a.config, trace=True,
              sets=["protocol.framing=ascii", "serial.data_bits=7"]).start()
    line = RawLine(sim.device)
    try:
        line.xfer(b":05\xe90300500002A6\r\n", 100, timeout=0.4)
        line.xfer(b":0503005000002A6\r\n", 100, timeout=0.4)
        time.sleep(0.1)
        tr = "\n".join(sim.trace_lines())
        t.ok("master :05<E9>0300500002A6\\r\\n | " in tr,
             "ASCII trace: a byte that is not printable shown as <E9>")
        t.ok("master :0503005000002A6\\r\\n | not an ASCII frame: odd number of hex digits (15)" in tr,
             "ASCII trace: odd number of hex digits named")
        t.ok("?" not in "".join(l.split(" | ")[0] for l in sim.trace_lines()), "ASCII trace: no '?'")
    finally:
        line.close()
        sim.stop()
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
