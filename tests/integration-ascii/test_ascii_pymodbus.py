#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Modbus ASCII ([ASCII-32] §2) against modcp-sim, with pymodbus's ASCII framer (Debian's
/usr/bin/python3, python3-pymodbus) and, for what pymodbus cannot send, raw frames
through the same pty.

    test_ascii_pymodbus.py --sim modcp-sim --simlib DIR --configs DIR

1. configs/ascii.ini (9600 7E1 ASCII): every function of the manual's set through
   pymodbus with the values of [ASCII-32] §9 (initial memory of the config), writes checked
   from the controller side (console `get`), exceptions 01 / 02 / 03, the ASCII limits
   ([ASCII-32] §5: bits 2008 / 1976, registers 125 / 123), broadcast.
2. The same pty, raw text: the [ASCII-32] §2 vectors byte for byte, and every receive error
   with its event in the diagnostic buffer: LRC (08)36H, ':' restart (08)39H, non-hex
   (08)3AH, wrong start (08)38H, character delay time (08)06H (100 ms via --set).
3. configs/regs32.ini switched to ASCII (--set protocol.framing=ascii, data_bits=7):
   32-bit registers through pymodbus (FC03 with 4 bytes per register, floats as
   IEEE-754 big-endian) and the 32-bit vectors of [ASCII-32] §2 as raw text; limits 62 / 61.
Prints "N passed, M failed"; exit code 0 only when nothing failed.
"""
import argparse
import os
import select
import struct
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
import debpkg  # noqa: E402

try:
    from pymodbus.client import ModbusSerialClient
    from pymodbus.diag_message import ReturnQueryDataRequest
    from pymodbus.framer.ascii_framer import ModbusAsciiFramer
    from pymodbus.register_read_message import ReadHoldingRegistersRequest
    from pymodbus.register_write_message import WriteMultipleRegistersRequest
except ImportError as e:
    debpkg.missing(e)

passed = 0
failed = 0
SLAVE = 5


def ok(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL  " + what, flush=True)


def lrc(b):
    return (-sum(b)) & 0xFF


def frame(hexstr):
    b = bytes.fromhex(hexstr)
    return b":" + b.hex().upper().encode() + b"%02X\r\n" % lrc(b)


def client(sim):
    c = ModbusSerialClient(sim.device, framer=ModbusAsciiFramer, baudrate=9600, bytesize=7,
                           parity="E", stopbits=1, timeout=2, retries=0)
    ok(c.connect(), "pymodbus connects to %s" % sim.device)
    return c


class RawPort:
    """The pty opened a second time without pyserial: re-opening it with pyserial in 7E1
    after pymodbus closed it fails with EINVAL in tcsetattr (the simulator's pty); the
    line settings do not matter on a pty, the raw mode is already set."""

    def __init__(self, device):
        self.fd = os.open(device, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)

    def drain(self):
        while select.select([self.fd], [], [], 0)[0]:
            if not os.read(self.fd, 4096):
                break

    def write(self, data):
        while data:
            n = os.write(self.fd, data)
            data = data[n:]

    def read_some(self, timeout):
        if select.select([self.fd], [], [], max(timeout, 0))[0]:
            return os.read(self.fd, 4096)
        return b""

    def close(self):
        os.close(self.fd)


def raw(port, text, wait=0.3):
    """Send raw characters; return everything answered within `wait` after the last."""
    port.drain()
    port.write(text)
    out = b""
    deadline = time.monotonic() + wait
    while time.monotonic() < deadline and not out.endswith(b"\r\n"):
        out += port.read_some(deadline - time.monotonic())
    return out


def exc(r):
    return getattr(r, "exception_code", None) if r is not None and r.isError() else None


def no_reply(call):
    """True when the request is not answered (pymodbus reports no response)."""
    try:
        r = call()
    except Exception:  # ModbusIOException: no response received
        return True
    return r is None or (r.isError() and getattr(r, "exception_code", None) is None)


def get(sim, operand):
    return sim.get(operand)


class Read32Request(ReadHoldingRegistersRequest):
    """FC03 for the 32-bit ranges: the reply carries 4 bytes per register ([ASCII-32] §4.5);
    pymodbus must expect byte count 4 x count (it decodes them as 2 x count words)."""

    def __init__(self, address, count, slave=SLAVE):
        ReadHoldingRegistersRequest.__init__(self, address, count, unit=slave)

    def get_response_pdu_size(self):
        return 1 + 1 + 4 * self.count


def read32(c, address, count):
    return c.execute(Read32Request(address, count))


class Write32Request(WriteMultipleRegistersRequest):
    """FC16 for the 32-bit ranges: the quantity counts 4-byte registers ([ASCII-32] §4.5)."""

    def __init__(self, address, values32, slave=SLAVE):
        WriteMultipleRegistersRequest.__init__(self, address, [0], unit=slave)
        self.values32 = list(values32)

    def encode(self):
        n = len(self.values32)
        return struct.pack(">HHB", self.address, n, 4 * n) + b"".join(
            struct.pack(">I", v) for v in self.values32)


# ---- 1 + 2: configs/ascii.ini --------------------------------------------------------

def part_standard(Sim, sim_bin, configs):
    with Sim(sim_bin, os.path.join(configs, "ascii.ini"),
             sets=["protocol.ascii_timeout_ms=100"]) as sim:
        ok(sim.settings == "9600 7E1 ASCII", "settings %r" % sim.settings)
        c = client(sim)
        # [ASCII-32] §9.1 FC01: 64 -> M1008.0, 32 bits = 01 17 02 18
        r = c.read_coils(64, 32, slave=SLAVE)
        want = [bool((b >> k) & 1) for b in (0x01, 0x17, 0x02, 0x18) for k in range(8)]
        ok(not r.isError() and r.bits[:32] == want, "FC01 64 x 32 -> 01 17 02 18: %r" % r)
        # [ASCII-32] §9.2 FC02: 4144 -> I134.0, 24 bits = 12 34 56
        r = c.read_discrete_inputs(4144, 24, slave=SLAVE)
        want = [bool((b >> k) & 1) for b in (0x12, 0x34, 0x56) for k in range(8)]
        ok(not r.isError() and r.bits[:24] == want, "FC02 4144 x 24 -> 12 34 56: %r" % r)
        # [ASCII-32] §9.3 FC03: 0050H -> DB800.DBW160 = 8765 4321
        r = c.read_holding_registers(0x50, 2, slave=SLAVE)
        ok(not r.isError() and r.registers == [0x8765, 0x4321], "FC03 0050H x 2: %r" % r)
        # [ASCII-32] §9.5 FC04: 02C0H -> DB901.DBW384
        r = c.read_input_registers(0x2C0, 3, slave=SLAVE)
        ok(not r.isError() and r.registers == [0xA1A2, 0xA3A4, 0xA5A6], "FC04 02C0H x 3: %r" % r)
        # [ASCII-32] §9.6 FC05: 2057 -> Q257.1
        r = c.write_coil(2057, True, slave=SLAVE)
        ok(not r.isError() and get(sim, "Q257.1") == 1, "FC05 2057 -> Q257.1 = 1")
        # [ASCII-32] §9.7 FC06: 0180H -> DB800.DBW768
        r = c.write_register(0x180, 0x2B1A, slave=SLAVE)
        ok(not r.isError() and get(sim, "DB800.DBW768") == 0x2B1A, "FC06 0180H -> DB800.DBW768")
        # [ASCII-32] §9.10 FC15: 1153 -> M1144.1 .. M1145.4 = CD 09 (12 bits)
        bits = [bool((0x09CD >> k) & 1) for k in range(12)]
        before = get(sim, "MB1144"), get(sim, "MB1145")
        r = c.write_coils(1153, bits, slave=SLAVE)
        ok(not r.isError(), "FC15 1153 x 12: %r" % r)
        ok(get(sim, "MB1144") == ((before[0] & 0x01) | ((0xCD << 1) & 0xFE)) and
           get(sim, "MB1145") == ((before[1] & 0xE0) | (0xCD >> 7) | (0x09 << 1)),
           "FC15 bits M1144.1 .. M1145.4, neighbours kept")
        # [ASCII-32] §9.12 FC16: 0A32H -> DB805.DBW100..104
        r = c.write_registers(0x0A32, [0xCD09, 0xDE1A, 0xEF2B], slave=SLAVE)
        ok(not r.isError() and [get(sim, "DB805.DBW%d" % a) for a in (100, 102, 104)] ==
           [0xCD09, 0xDE1A, 0xEF2B], "FC16 0A32H -> DB805.DBW100..104")
        # [ASCII-32] §8.1 FC08 echo
        r = c.execute(ReturnQueryDataRequest(0xA5C3, unit=SLAVE))
        ok(not r.isError() and list(r.message) == [0xA5C3], "FC08 echo A5C3: %r" % r)
        # exceptions
        ok(exc(c.write_coil(3000, True, slave=SLAVE)) == 2, "FC05 coil 3000: exception 02")
        ok(exc(c.read_holding_registers(0x1FF, 2, slave=SLAVE)) == 2, "FC03 crossing a DB: 02")
        # ASCII limits ([ASCII-32] §5, §8.5 (08)32H)
        ok(not c.read_coils(0, 2008, slave=SLAVE).isError(), "FC01 2008 bits")
        ok(exc(c.read_coils(0, 2009, slave=SLAVE)) == 3, "FC01 2009 bits: exception 03")
        ok(not c.read_discrete_inputs(0, 2008, slave=SLAVE).isError(), "FC02 2008 bits")
        ok(exc(c.read_discrete_inputs(0, 2009, slave=SLAVE)) == 3, "FC02 2009: exception 03")
        ok(not c.write_coils(0, [False] * 1976, slave=SLAVE).isError(), "FC15 1976 bits")
        ok(len(getattr(c.read_holding_registers(0, 125, slave=SLAVE), "registers", [])) == 125,
           "FC03 125 registers")
        ok(exc(c.read_holding_registers(0, 126, slave=SLAVE)) == 3, "FC03 126: exception 03")
        ok(exc(c.read_input_registers(0, 126, slave=SLAVE)) == 3, "FC04 126: exception 03")
        ok(not c.write_registers(0x400, list(range(123)), slave=SLAVE).isError(), "FC16 123")
        ok(get(sim, "DB802.DBW244") == 122, "FC16 123 registers: the last one DB802.DBW244")
        ok("0832" in sim.diag(), "(08)32H in the diagnostic buffer")
        # 1977 bits need 253 data bytes: more than 2 x 252 characters ([ASCII-32] §8.1), an
        # over-long frame, (08)16H, not answered (last: pymodbus drops the port after it;
        # FC16 with 124 registers likewise, test_ascii.c test_limits_registers)
        ok(no_reply(lambda: c.write_coils(0, [False] * 1977, slave=SLAVE)),
           "FC15 1977: over-long, no reply")
        ok(sim.diag()[:1] == ["0816"], "(08)16H in the diagnostic buffer")
        sim.cmd("set MD1008 0x01170218")  # FC15 1976 bits cleared M1000..M1246
        c.close()

        port = RawPort(sim.device)
        # the [ASCII-32] §2 vectors, byte for byte
        for req, rsp in ((b":05080000A5C38B\r\n", b":05080000A5C38B\r\n"),
                         (b":050300500002A6\r\n", b":05030487654321A4\r\n"),
                         (b":0501004000209A\r\n", b":05010401170218C4\r\n"),
                         (b":050402C0000332\r\n", b":050406A1A2A3A4A5A61C\r\n"),
                         (b":05050809FF00E6\r\n", b":05050809FF00E6\r\n"),
                         (b":050F0481000C02CD0983\r\n", b":050F0481000C5B\r\n"),
                         (frame("05050BB8FF00"), b":05850274\r\n")):  # [ASCII-32] §8.2
            got = raw(port, req)
            ok(got == rsp, "[ASCII-32] §2 %r -> %r, got %r" % (req, rsp, got))
        # broadcast: executed, no reply
        got = raw(port, frame("000601802B2B"))
        ok(got == b"" and get(sim, "DB800.DBW768") == 0x2B2B, "broadcast FC06: no reply, written")
        # receive errors: no reply, the event in the buffer
        for text, ev, what in ((b":05080000A5C38C\r\n", "0836", "LRC incorrect"),
                               (b":0503005:05080000A5C38B\r\n", "0839", "':' restarts"),
                               (b":0508G000A5C38B\r\n", "083A", "non-hex character"),
                               (b"\x05\x03\x00\x50\x00\x02\xC5\x9E", "0838", "RTU frame")):
            got = raw(port, text)
            if ev == "0839":
                ok(got == b":05080000A5C38B\r\n", "%s: the second frame answered, got %r" % (what, got))
            else:
                ok(got == b"", "%s: no reply, got %r" % (what, got))
            ok(sim.diag()[:1] == [ev], "%s: event (%s)%sH newest, %r" % (what, ev[:2], ev[2:], sim.diag()))
        time.sleep(0.3)  # the stray RTU bytes end with the character delay time
        got = raw(port, b":050800", wait=0.4)  # then silence > 100 ms
        ok(got == b"" and sim.diag()[:1] == ["0806"], "character delay time: (08)06H, %r" % sim.diag())
        got = raw(port, b":05080000A5C38B\r\n")
        ok(got == b":05080000A5C38B\r\n", "served again after the errors")
        st = sim.status()
        ok(int(st.get("bus_crc", "0")) >= 1, "bus_crc counted: %r" % st.get("bus_crc"))
        port.close()


# ---- 3: configs/regs32.ini in ASCII -------------------------------------------------

def part_regs32(Sim, sim_bin, configs):
    with Sim(sim_bin, os.path.join(configs, "regs32.ini"),
             sets=["protocol.framing=ascii", "serial.data_bits=7"]) as sim:
        ok(sim.settings == "9600 7E1 ASCII", "settings %r" % sim.settings)
        c = client(sim)
        # [ASCII-32] §9.4: 7001 x 2 -> DB4.DBD4, DBD8; pymodbus sees 4 words (byte count 8)
        r = read32(c, 7001, 2)
        ok(not r.isError() and r.registers == [0xCDDC, 0xABBA, 0x1122, 0x3344],
           "FC03 7001 x 2 (32-bit) -> CDDC ABBA 1122 3344: %r" % r)
        # floats, IEEE-754 big-endian as stored (DB4.DBD0 = 1.5, DBD400 = 3.14159274)
        r = read32(c, 7000, 1)
        f = struct.unpack(">f", struct.pack(">HH", *r.registers))[0] if not r.isError() else None
        ok(f == 1.5, "float 7000 = 1.5: %r" % f)
        r = read32(c, 7100, 1)
        f = struct.unpack(">f", struct.pack(">HH", *r.registers))[0] if not r.isError() else None
        ok(f is not None and abs(f - 3.14159274) < 1e-6, "float 7100 = 3.14159274: %r" % f)
        r = read32(c, 5000, 2)
        iv = struct.unpack(">ii", struct.pack(">HHHH", *r.registers)) if not r.isError() else None
        ok(iv == (-2, 2147483647), "int32 5000, 5001 = -2, 2147483647: %r" % (iv,))
        # 16-bit range: 3050 -> DB2.DBW100
        r = c.read_holding_registers(3050, 2, slave=SLAVE)
        ok(not r.isError() and r.registers == [0x8765, 0x4321], "FC03 3050 x 2 (int16): %r" % r)
        # FC16 with 4-byte registers ([ASCII-32] §9.12) through pymodbus's framer
        r = c.execute(Write32Request(5003, [0x3A09DE1A, 0x01020304]))
        ok(not r.isError() and (r.address, r.count) == (5003, 2), "FC16 32-bit 5003 x 2: %r" % r)
        ok(get(sim, "DB3.DBD12") == 0x3A09DE1A and get(sim, "DB3.DBD16") == 0x01020304,
           "DB3.DBD12, 16 = 3A09DE1A 01020304")
        fl = [0.1, -2.5e-8, 65504.0]
        r = c.execute(Write32Request(7300, [struct.unpack(">I", struct.pack(">f", v))[0] for v in fl]))
        ok(not r.isError(), "FC16 three floats to 7300: %r" % r)
        r = read32(c, 7300, 3)
        back = list(struct.unpack(">fff", struct.pack(">6H", *r.registers))) if not r.isError() else None
        ok(back == [struct.unpack(">f", struct.pack(">f", v))[0] for v in fl],
           "floats read back: %r" % back)
        # ASCII 32-bit limits: read 62 / write 61
        r = read32(c, 7000, 62)
        ok(not r.isError() and len(r.registers) == 124, "FC03 62 floats (248 bytes)")
        ok(exc(read32(c, 7000, 63)) == 3, "FC03 63 floats: 03")
        ok(not c.execute(Write32Request(8000, range(61))).isError(), "FC16 61 floats")
        ok(exc(c.read_holding_registers(4999, 2, slave=SLAVE)) == 2, "straddling int16/int32: 02")
        # 62 floats are 248 data bytes, 253 with start, quantity and byte count: more than
        # 2 x 252 characters ([ASCII-32] §8.1), over-long, not answered (last: pymodbus drops the
        # port after it)
        ok(no_reply(lambda: c.execute(Write32Request(8000, range(62)))),
           "FC16 62 floats: over-long, no reply")
        c.close()

        port = RawPort(sim.device)
        for req, rsp in ((b":05031B59000282\r\n", b":050308CDDCABBA1122334438\r\n"),
                         (b":05061B5A12233445D2\r\n", b":05061B5A12233445D2\r\n"),
                         (b":0510138B0002083A09DE1A01020304FE\r\n", b":0510138B00024B\r\n")):
            got = raw(port, req)
            ok(got == rsp, "[ASCII-32] §2 %r -> %r, got %r" % (req, rsp, got))
        ok(get(sim, "DB4.DBD8") == 0x12233445, "FC06 4 data bytes: DB4.DBD8 = 12233445")
        port.close()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--simlib", required=True)
    ap.add_argument("--configs", required=True)
    a = ap.parse_args()
    sys.path.insert(0, a.simlib)
    from simlib import Sim  # noqa: E402
    part_standard(Sim, a.sim, a.configs)
    part_regs32(Sim, a.sim, a.configs)
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
