#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The line made visible (issue 22 items 1 and 2): modcp-sim --capture FILE.pcap and
--vcd FILE.vcd, read back with Debian's tshark and sigrok-cli, no setting of theirs.

 - one slave (configs/default.ini, 9600 8E1, slave 5): FC03, FC06, FC03, FC16 by a raw
   RTU master; tshark decodes every record as Modbus RTU (dissector mbrtu) with unit 5,
   the function codes in order, the register values of the FC03 replies, the sender
   (P2P direction 0 = master, 1 = slave; source port 0 = master, 1 = member @1), and a
   reply's first start bit at least t3.5 after the end of its request's last stop bit;
 - the same run's waveform: sigrok-cli's uart + modbus decoders find the requests and
   replies (slave 5, the functions, the values, CRC correct, none incorrect);
 - ASCII framing: each frame a record of its own with the protocol column MODBUS/ASCII
   and the frame as its line of text;
 - a bus at 9600 (@a and @b at address 1, @b's replies 3 ms late, so that the two
   overlap; @c at 2 with the noise fault): each colliding reply is a COLLISION record of
   its own (its member's source port), the noise a NOISE record, @c's reply a Modbus RTU
   record from source port 3; the waveform has the members' TX and DE signals.

    test_capture.py --sim PATH/modcp-sim --config configs/default.ini
"""
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import run_checks, RawLine, Sim, member_configs, with_crc  # noqa: E402

T35_9600_US = 4010  # 3.5 characters of 11 bits at 9600 baud (timing.c: 3.5 * 1146 us)


def tshark(path, *fields):
    args = ["tshark", "-r", path, "-T", "fields", "-E", "separator=|"]
    for f in fields:
        args += ["-e", f]
    out = subprocess.run(args, capture_output=True, text=True, timeout=60)
    if out.returncode != 0:
        raise RuntimeError("tshark failed: " + out.stderr)
    return [l.split("|") for l in out.stdout.splitlines()]


def one_slave(a, t, tmp):
    pcap = os.path.join(tmp, "one.pcap")
    vcd = os.path.join(tmp, "one.vcd")
    sim = Sim(a.sim, a.config, extra=["--capture", pcap, "--vcd", vcd]).start()
    line = RawLine(sim.device)
    # a pause after each reply: a request written on a pty arrives at once, and the line
    # model ends its last stop bit then only when the line was free for it
    try:
        t.ok(line.xfer(with_crc("05 03 00 50 00 02"), 9).hex() == "050304876543217670",
             "FC03 answered")
        time.sleep(0.05)
        t.ok(len(line.xfer(with_crc("05 06 00 64 12 34"), 8)) == 8, "FC06 answered")
        time.sleep(0.05)
        t.ok(line.xfer(with_crc("05 03 00 64 00 01"), 7)[3:5].hex() == "1234", "FC03 answered 0x1234")
        time.sleep(0.05)
        t.ok(len(line.xfer(with_crc("05 10 00 64 00 02 04 AB CD 00 01"), 8)) == 8, "FC16 answered")
        time.sleep(0.05)
    finally:
        line.close()
        rc, _ = sim.stop()
    t.ok(rc == 0, "simulator stopped cleanly")
    t.ok(any(re.match(r"modcp-sim: capture .*: 16 records", l) for l in sim.lines),
         "16 records reported: 8 frames, DE on and off around each reply (%s)"
         % [l for l in sim.lines if "capture" in l])
    every = tshark(pcap, "exported_pdu.prot_name", "exported_pdu.p2p_dir", "exported_pdu.src_port",
                   "mbrtu.unit_id", "modbus.func_code", "modbus.regval_uint16",
                   "frame.time_epoch", "frame.len", "text")
    rows = [r for r in every if r[0] == "mbrtu"]
    de = [r for r in every if r[0] == "data-text-lines"]
    t.ok([r[8] for r in de] == ["DE on (default)\\n", "DE off (default)\\n"] * 4,
         "DE on / off records around each reply (%s)" % [r[8] for r in de])
    for k in range(4):
        on_t, off_t = float(de[2 * k][6]), float(de[2 * k + 1][6])
        rsp_t = float(rows[2 * k + 1][6])
        rsp_len = (9, 8, 7, 8)[k]
        t.ok(abs(on_t - rsp_t) < 1e-6 and abs(off_t - rsp_t - rsp_len * 11 / 9600) < 2e-5,
             "reply %d: DE on at its first start bit, off at the end of its last stop bit" % (k + 1))
    t.ok(len(rows) == 8, "tshark: 8 frames (got %d)" % len(rows))
    t.ok(len(every) == 16, "16 records (%d)" % len(every))
    t.ok([r[1] for r in rows] == ["0", "1"] * 4, "directions: master, slave, ... (%s)" %
         [r[1] for r in rows])
    t.ok([r[2] for r in rows] == ["0", "1"] * 4, "source ports: master 0, member 1")
    t.ok(all(r[3] == "5" for r in rows), "unit id 5 in every frame (%s)" % [r[3] for r in rows])
    t.ok([r[4] for r in rows] == ["3", "3", "6", "6", "3", "3", "16", "16"],
         "function codes (%s)" % [r[4] for r in rows])
    t.ok(rows[1][5] == "34661,17185", "FC03 reply values 0x8765 0x4321 (%s)" % rows[1][5])
    t.ok(rows[5][5] == "4660", "FC03 reply value 0x1234 after the FC06 (%s)" % rows[5][5])
    char_us = 11 * 1e6 / 9600
    for i in (0, 2, 4, 6):
        req_t, rsp_t = float(rows[i][6]), float(rows[i + 1][6])
        req_len = {0: 8, 2: 8, 4: 8, 6: 13}[i]
        gap_us = (rsp_t - req_t) * 1e6 - req_len * char_us
        t.ok(gap_us >= T35_9600_US - 2, "reply %d starts %.0f us after its request's end "
             "(>= t3.5 %d)" % (i // 2 + 1, gap_us, T35_9600_US))

    out = subprocess.run(["sigrok-cli", "-I", "vcd", "-i", vcd, "-P",
                          "uart:baudrate=9600:parity=even:rx=slaves:tx=master_tx,modbus",
                          "-A", "modbus"], capture_output=True, text=True, timeout=120)
    ann = out.stdout
    t.ok(out.returncode == 0, "sigrok-cli decoded the VCD (%s)" % out.stderr.strip()[:200])
    t.ok(ann.count("Slave ID: 5") == 8, "sigrok: 8 frames of slave 5 (got %d)" %
         ann.count("Slave ID: 5"))
    t.ok(ann.count("CRC correct") == 8 and "CRC incorrect" not in ann,
         "sigrok: 8 CRCs correct, none incorrect")
    for want in ("Function 3: Read Holding Registers", "Function 6: Write Single Register",
                 "Function 16: Write Multiple Registers", "0x8765 / 34661", "0x4321 / 17185",
                 "Register Value 0x1234 / 4660"):
        t.ok(want in ann, "sigrok: '%s'" % want)


def bus(a, t, tmp):
    cfgs = member_configs(a.config, tmp, [("a", 1), ("b", 1), ("c", 2)])
    pcap = os.path.join(tmp, "bus.pcap")
    vcd = os.path.join(tmp, "bus.vcd")
    # 9600 baud: a reply of 9 bytes is on the line for 10.3 ms; @b, at @a's address,
    # answers 3 ms after @a: the two replies overlap whatever the threads' timing
    sim = Sim(a.sim, cfgs[0], cycle_ms=1, trace=True,
              extra=cfgs[1:] + ["--fault", "@b:delay=3", "--fault", "@c:noise=3",
                                "--capture", pcap, "--vcd", vcd]).start()
    line = RawLine(sim.device)
    try:
        rsp = line.xfer(with_crc("01 03 00 50 00 02"), 9, timeout=0.5)
        t.ok(rsp != with_crc("01 03 04 87 65 43 21"), "two members at address 1: no clean reply")
        time.sleep(0.2)
        line.recv(1024, 0.1)
        rsp = line.xfer(with_crc("02 03 00 50 00 02"), 9, timeout=1.0)
        t.ok(rsp == with_crc("02 03 04 87 65 43 21"), "member @c (address 2) answered")
        time.sleep(0.1)
    finally:
        line.close()
        sim.stop()
    rows = tshark(pcap, "_ws.col.Protocol", "exported_pdu.src_port", "mbrtu.unit_id",
                  "modbus.func_code", "data.data")
    protos = [r[0] for r in rows]
    if "COLLISION" not in protos:
        print("\n".join(sim.lines[-40:]))
    coll = sorted(r[1] for r in rows if r[0] == "COLLISION")
    t.ok(coll == ["1", "2"], "bus: the colliding replies of @a and @b are COLLISION records "
         "from source ports 1 and 2 (%s)" % protos)
    noise = [r for r in rows if r[0] == "NOISE"]
    t.ok(len(noise) == 1 and noise[0][1] == "65535" and len(noise[0][4]) == 6,
         "bus: a NOISE record of 3 bytes from source port 65535 (%s)" % noise)
    c_reply = [r for r in rows if r[0] == "Modbus RTU" and r[1] == "3" and r[2] == "2" and r[3] == "3"]
    t.ok(len(c_reply) == 1, "bus: member @c's reply from source port 3 decoded as Modbus RTU")
    with open(vcd) as f:
        head = f.read(2000)
    for sig in ("line", "master_tx", "slaves", "noise_tx", "a_tx", "a_de", "b_tx", "c_de"):
        t.ok(re.search(r"\$var wire 1 \S+ %s \$end" % sig, head) is not None,
             "waveform declares %s" % sig)


def ascii_frames(a, t, tmp):
    pcap = os.path.join(tmp, "ascii.pcap")
    sim = Sim(a.sim, a.config, sets=["protocol.framing=ascii", "serial.data_bits=7"],
              extra=["--capture", pcap]).start()
    line = RawLine(sim.device)
    try:
        rsp = line.xfer(b":050300500002A6\r\n", 19, timeout=2.0)
        t.ok(rsp == b":05030487654321A4\r\n", "ASCII: FC03 answered (%r)" % rsp)
    finally:
        line.close()
        sim.stop()
    rows = [r for r in tshark(pcap, "exported_pdu.p2p_dir", "_ws.col.Protocol", "text")
            if r[1] != "LINE"]
    t.ok([r[:2] for r in rows] == [["0", "MODBUS/ASCII"], ["1", "MODBUS/ASCII"]],
         "ASCII: a request and a reply, protocol column MODBUS/ASCII (%s)" % rows)
    t.ok(len(rows) == 2 and rows[0][2] == ":050300500002A6\\r\\n" and
         rows[1][2] == ":05030487654321A4\\r\\n", "ASCII: each frame as its line of text")


def main():
    return run_checks("modcp-capture-", ("tshark", "sigrok-cli"), [one_slave, bus, ascii_frames])


if __name__ == "__main__":
    sys.exit(main())
