#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""master_pymodbus.py — pymodbus (Debian's python3-pymodbus, 3.0 API) against a modcp
slave configured with configs/default.ini, on any serial device.

    /usr/bin/python3 master_pymodbus.py --device PATH [--baud 9600] [--parity E|O|N]
                                        [--framing rtu|ascii] [--data-bits 8|7] [--slave 5]
                                        [--random 300] [--seed N] [--timeout 2]

Its own checks, written with pymodbus's API (not the byte-level ones of
master_libmodbus): the manual's read examples as values, writes and read-backs of
every writable FC, exceptions as pymodbus reports them, FC08 loopback, and random
write-then-read operations (memory restored afterwards). Last line "N passed, M
failed"; exit code 0 only if nothing failed.

Pseudo-terminals have no parity: Debian's glibc then refuses tcsetattr() with parity
(pyserial issue #196), so on a pty the script falls back to parity N (the slave on a
pty does not see parity either)."""
import argparse
import random
import sys
import time

import debpkg

try:
    import pymodbus
    from pymodbus import diag_message
    from pymodbus.client import ModbusSerialClient
    from pymodbus.framer.ascii_framer import ModbusAsciiFramer
    from pymodbus.pdu import ExceptionResponse
except ImportError as e:
    debpkg.missing(e)

passed = 0
failed = 0
verbose = False


def ok(cond, what):
    global passed, failed
    if cond:
        passed += 1
        if verbose:
            print("ok - " + what)
    else:
        failed += 1
        print("FAIL - " + what)
    sys.stdout.flush()


def connect(a):
    for parity in ([a.parity, "N"] if a.parity != "N" else ["N"]):
        if a.framing == "ascii":
            c = ModbusSerialClient(port=a.device, framer=ModbusAsciiFramer, baudrate=a.baud,
                                   parity=parity, stopbits=a.stop_bits, bytesize=a.data_bits or 7,
                                   timeout=a.timeout)
        else:
            c = ModbusSerialClient(port=a.device, baudrate=a.baud, parity=parity, stopbits=a.stop_bits,
                                   bytesize=a.data_bits or 8, timeout=a.timeout)
        try:
            if c.connect():
                if parity != a.parity:
                    print("note: %s refuses parity %s (a pty); using N" % (a.device, a.parity))
                return c
        except Exception as e:  # termios.error on a pty with parity
            print("note: connect with parity %s: %s" % (parity, e))
            try:
                c.close()
            except Exception:
                pass
    return None


def regs(c, addr, n, s):
    rr = c.read_holding_registers(addr, n, slave=s)
    return None if rr.isError() else list(rr.registers)


def bits(c, addr, n, s):
    rr = c.read_coils(addr, n, slave=s)
    return None if rr.isError() else list(rr.bits[:n])


def regs_range(c, addr, n, s):
    out = []
    while n > 0:
        k = min(n, 125, 512 - addr % 512)
        r = regs(c, addr, k, s)
        if r is None:
            return None
        out += r
        addr += k
        n -= k
    return out


def write_regs_range(c, addr, vals, s):
    i = 0
    while i < len(vals):
        k = min(len(vals) - i, 123, 512 - (addr + i) % 512)
        c.write_registers(addr + i, vals[i:i + k], slave=s)
        i += k


def exc_code(rr):
    return rr.exception_code if isinstance(rr, ExceptionResponse) else None


def byte_bits(values):
    out = []
    for v in values:
        out += [bool((v >> i) & 1) for i in range(8)]
    return out


def main():
    global verbose
    ap = argparse.ArgumentParser()
    ap.add_argument("--device", required=True)
    ap.add_argument("--baud", type=int, default=9600)
    ap.add_argument("--parity", default="E", choices=["E", "O", "N"])
    ap.add_argument("--stop-bits", type=int, default=1)
    ap.add_argument("--data-bits", type=int, default=0, help="default 8 (RTU) / 7 (ASCII)")
    ap.add_argument("--framing", default="rtu", choices=["rtu", "ascii"])
    ap.add_argument("--slave", type=int, default=5)
    ap.add_argument("--random", type=int, default=300)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--timeout", type=float, default=2.0)
    ap.add_argument("--verbose", action="store_true")
    a = ap.parse_args()
    verbose = a.verbose
    s = a.slave
    seed = a.seed if a.seed is not None else int(time.time())
    rnd = random.Random(seed)
    print("master_pymodbus: pymodbus %s, %s %d %s, slave %d, seed %d" %
          (pymodbus.__version__, a.device, a.baud, a.framing.upper(), s, seed))
    c = connect(a)
    if c is None:
        print("0 passed, 1 failed")
        return 1
    t0 = time.monotonic()

    # the manual's read examples ([RTU-2003] §6), as values
    ok(bits(c, 0x40, 32, s) == byte_bits([0x01, 0x17, 0x02, 0x18]),
       "FC01 M1008.0..M1011.7 = 01 17 02 18")
    rr = c.read_discrete_inputs(0x1030, 24, slave=s)
    ok(not rr.isError() and list(rr.bits[:24]) == byte_bits([0x12, 0x34, 0x56]),
       "FC02 I134.0..I136.7 = 12 34 56")
    ok(regs(c, 0x50, 2, s) == [0x8765, 0x4321], "FC03 DB800.DBW160/162 = 8765 4321")
    rr = c.read_input_registers(0x2C0, 3, slave=s)
    ok(not rr.isError() and list(rr.registers) == [0xA1A2, 0xA3A4, 0xA5A6],
       "FC04 DB901.DBW384..388 = A1A2 A3A4 A5A6")
    ok(bits(c, 4096, 32, s) == byte_bits([0x12, 0x34, 0x56, 0x78]),
       "FC01 T100, T101 = 1234 5678 (high byte first)")

    # FC08 loopback
    rr = c.execute(diag_message.ReturnQueryDataRequest(message=0xA5C3, unit=s))
    msg = getattr(rr, "message", None)
    ok(not rr.isError() and msg in (b"\xa5\xc3", [0xA5C3], (0xA5C3,), 0xA5C3),
       "FC08 sub 0000 echo A5C3 (got %r)" % (msg,))

    # writes and read-backs
    rr = c.write_register(0x180, 0x2B1A, slave=s)
    ok(not rr.isError() and regs(c, 0x180, 1, s) == [0x2B1A], "FC06 DB800.DBW768 = 2B1A")
    rr = c.write_registers(0x32, [0xCD09, 0xDE1A, 0xEF2B], slave=s)
    ok(not rr.isError() and regs(c, 0x32, 3, s) == [0xCD09, 0xDE1A, 0xEF2B],
       "FC16 DB800.DBW100..104")
    rr = c.write_coil(2057, True, slave=s)
    ok(not rr.isError() and bits(c, 2057, 1, s) == [True], "FC05 Q257.1 on")
    rr = c.write_coil(2057, False, slave=s)
    ok(not rr.isError() and bits(c, 2057, 1, s) == [False], "FC05 Q257.1 off")
    c.write_coils(1160, [True] * 8, slave=s)  # MB1145 = FF
    rr = c.write_coils(1152, byte_bits([0xCD])[:8] + [True, False, False, True], slave=s)
    ok(not rr.isError() and bits(c, 1152, 16, s) == byte_bits([0xCD, 0xF9]),
       "FC15 MB1144 = CD, M1145.0..3 = 9, M1145.4..7 untouched")

    # exceptions as pymodbus reports them
    qmax = 125 if a.framing == "ascii" else 127  # FC03 limit: 127 (RTU), 125 (ASCII, [ASCII-32])
    rr = c.read_holding_registers(0, qmax, slave=s)
    ok(not rr.isError() and len(rr.registers) == qmax, "FC03 %d registers accepted" % qmax)
    ok(exc_code(c.read_holding_registers(0, qmax + 1, slave=s)) == 3,
       "FC03 %d registers -> exception 3" % (qmax + 1))
    ok(exc_code(c.read_coils(3000, 8, slave=s)) == 2, "FC01 address 3000 (gap) -> exception 2")
    ok(exc_code(c.write_register(51200, 1, slave=s)) == 2, "FC06 DB900 (write limit) -> exception 2")
    ok(exc_code(c.write_coil(4096, True, slave=s)) == 2, "FC05 on a timer -> exception 2")
    ok(exc_code(c.read_holding_registers(0x600, 1, slave=s)) == 4, "FC03 DB803 missing -> exception 4")
    ok(exc_code(c.read_holding_registers(510, 4, slave=s)) == 2, "FC03 across a DB -> exception 2")
    ok(regs(c, 0x50, 2, s) == [0x8765, 0x4321], "good request after exceptions")

    # random write-then-read; memory restored afterwards
    saved_c = bits(c, 0, 2000, s) + bits(c, 2000, 48, s)
    saved_q = bits(c, 2048, 512, s)
    saved_r = regs_range(c, 0, 1536, s)
    ok(None not in (saved_c, saved_q, saved_r), "random: snapshot")
    mism = 0
    for i in range(a.random):
        k = rnd.randrange(4)
        if k == 0:
            addr = rnd.choice([rnd.randrange(0, 2048), rnd.randrange(2048, 2560)])
            v = rnd.random() < 0.5
            c.write_coil(addr, v, slave=s)
            good = bits(c, addr, 1, s) == [v]
        elif k == 1:
            lo, hi = rnd.choice([(0, 2048), (2048, 2560)])
            n = rnd.randrange(1, 65)
            addr = rnd.randrange(lo, hi - n + 1)
            v = [rnd.random() < 0.5 for _ in range(n)]
            c.write_coils(addr, v, slave=s)
            good = bits(c, addr, n, s) == v
        elif k == 2:
            addr = rnd.randrange(0, 1536)
            v = rnd.randrange(65536)
            c.write_register(addr, v, slave=s)
            good = regs(c, addr, 1, s) == [v]
        else:
            addr = rnd.randrange(0, 1536)
            n = min(rnd.randrange(1, 33), 512 - addr % 512)
            v = [rnd.randrange(65536) for _ in range(n)]
            c.write_registers(addr, v, slave=s)
            good = regs(c, addr, n, s) == v
        if not good:
            mism += 1
            if mism <= 5:
                print("random op %d (kind %d) mismatch" % (i, k))
    ok(mism == 0, "random: %d write-then-read operations, %d mismatches" % (a.random, mism))
    c.write_coils(0, saved_c[:1968], slave=s)
    c.write_coils(1968, saved_c[1968:], slave=s)
    c.write_coils(2048, saved_q, slave=s)
    write_regs_range(c, 0, saved_r, s)
    ok(bits(c, 0, 2000, s) + bits(c, 2000, 48, s) == saved_c and bits(c, 2048, 512, s) == saved_q
       and regs_range(c, 0, 1536, s) == saved_r, "random: memory restored")

    c.close()
    print("master_pymodbus: %.1f s" % (time.monotonic() - t0))
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
