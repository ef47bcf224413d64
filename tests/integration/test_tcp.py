#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""RTU over TCP (issue 22 item 7): modcp-sim --tcp [ADDR:]PORT with Debian's pymodbus
(its TCP client with the RTU framer, as "RTU over TCP" masters and serial device servers
carry the frames), configs/default.ini (slave 5):

 - a first client reads DB800.DBW160/162 (FC03 addr 80: 0x8765 0x4321), writes FC06 addr
   100 = 0x1234 and reads it back; it leaves;
 - a second client, after it, reads the value the first one wrote;
 - a client that disconnects in the middle of a frame (3 bytes of a request): the slave
   drops that frame at t3.5 ((08)36H), and a third client is served at once;
 - the pty keeps working beside the TCP clients;
 - a bad --tcp value is refused with the option named.

    test_tcp.py --sim PATH/modcp-sim --config configs/default.ini
"""
import argparse
import os
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def client(port):
    from pymodbus.client import ModbusTcpClient
    from pymodbus.framer.rtu_framer import ModbusRtuFramer
    c = ModbusTcpClient("127.0.0.1", port=port, framer=ModbusRtuFramer, timeout=2)
    if not c.connect():
        raise RuntimeError("cannot connect to 127.0.0.1:%d" % port)
    return c


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    t = Checks()
    port = free_port()
    sim = Sim(a.sim, a.config, extra=["--tcp", str(port)]).start()
    try:
        t.ok(any(l == "modcp-sim: RTU over TCP on 127.0.0.1:%d" % port for l in sim.lines),
             "start-up names the TCP address")
        c = client(port)
        rr = c.read_holding_registers(80, 2, slave=5)
        t.ok(not rr.isError() and rr.registers == [0x8765, 0x4321],
             "client 1: FC03 addr 80 -> 0x8765 0x4321 (%s)" % rr)
        wr = c.write_register(100, 0x1234, slave=5)
        t.ok(not wr.isError(), "client 1: FC06 addr 100 = 0x1234 (%s)" % wr)
        rr = c.read_holding_registers(100, 1, slave=5)
        t.ok(not rr.isError() and rr.registers == [0x1234], "client 1: read back 0x1234")
        c.close()

        c = client(port)
        rr = c.read_holding_registers(100, 1, slave=5)
        t.ok(not rr.isError() and rr.registers == [0x1234],
             "client 2 (after client 1 left): reads 0x1234 (%s)" % rr)
        c.close()

        bus_crc0 = int(sim.status()["bus_crc"])
        raw = socket.create_connection(("127.0.0.1", port))
        raw.sendall(with_crc("05 03 00 50 00 02")[:3])
        raw.close()
        time.sleep(0.1)
        c = client(port)
        rr = c.read_holding_registers(80, 2, slave=5)
        t.ok(not rr.isError() and rr.registers == [0x8765, 0x4321],
             "client 3 after one that left mid-frame: served (%s)" % rr)
        c.close()
        st = sim.status()
        t.ok(int(st["bus_crc"]) == bus_crc0 + 1 and sim.diag()[:1] == ["0836"],
             "the cut frame dropped at t3.5: (08)36H, bus_crc %d -> %s" % (bus_crc0, st["bus_crc"]))

        line = RawLine(sim.device)
        rsp = line.xfer(with_crc("05 03 00 64 00 01"), 7)
        line.close()
        t.ok(rsp[3:5] == b"\x12\x34", "the pty beside TCP: reads 0x1234 (%s)" % rsp.hex(" "))
    finally:
        rc, gone = sim.stop()
    t.ok(rc == 0, "stopped cleanly with the TCP thread")
    p = subprocess.run([a.sim, a.config, "--tcp", "localhost:x"], stdin=subprocess.DEVNULL,
                       capture_output=True, text=True, timeout=30)
    t.ok(p.returncode != 0 and "--tcp localhost:x: expected [ADDR:]PORT" in p.stderr,
         "a bad --tcp refused, named (%s)" % p.stderr.strip())
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
