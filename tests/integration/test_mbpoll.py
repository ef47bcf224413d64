#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""mbpoll against modcp-sim (configs/default.ini): reads and writes registers and
coils; mbpoll's output is parsed and the values asserted, writes are checked through
the simulator's console (the controller memory) and by reading back with mbpoll.

    test_mbpoll.py --sim PATH/modcp-sim --config configs/default.ini [--mbpoll mbpoll]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, Sim  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--mbpoll", default="mbpoll")
    a = ap.parse_args()
    if shutil.which(a.mbpoll) is None:
        print("%s not found: install Debian's mbpoll (tools/install-deps does)" % a.mbpoll)
        print("0 passed, 1 failed")
        return 1
    t = Checks()
    t0 = time.monotonic()
    with Sim(a.sim, a.config) as sim:
        base = [a.mbpoll, "-m", "rtu", "-a", "5", "-b", "9600", "-P", "even", "-q"]

        def mb(*args):
            p = subprocess.run(base + list(args[:-1]) + [sim.device] + ([] if args[-1] is None else
                                                                         [str(v) for v in args[-1]]),
                               capture_output=True, text=True, timeout=20)
            return p.returncode, p.stdout + p.stderr

        def values(out):
            return {int(m.group(1)): m.group(2) for m in re.finditer(r"^\[(\d+)\]:\s+(\S+)", out, re.M)}

        # the manual's FC03 example: registers 0x50..0x51 (references 81, 82)
        rc, out = mb("-t", "4:hex", "-r", "81", "-c", "2", "-1", None)
        t.ok(rc == 0 and values(out) == {81: "0x8765", 82: "0x4321"},
             "mbpoll FC03 refs 81..82 = 0x8765 0x4321 (%s)" % values(out))
        # FC04 example: DB901.DBW384.. (register 0x2C0 -> reference 705)
        rc, out = mb("-t", "3:hex", "-r", "705", "-c", "3", "-1", None)
        t.ok(rc == 0 and values(out) == {705: "0xA1A2", 706: "0xA3A4", 707: "0xA5A6"},
             "mbpoll FC04 refs 705..707 = A1A2 A3A4 A5A6 (%s)" % values(out))
        # FC02 example: I134 = 12h (reference 4145 = address 4144)
        rc, out = mb("-t", "1", "-r", "4145", "-c", "8", "-1", None)
        t.ok(rc == 0 and [values(out).get(4145 + i) for i in range(8)] == list("01001000"),
             "mbpoll FC02 I134.0..7 = 0 1 0 0 1 0 0 0")
        # FC01 example: M1008 = 01
        rc, out = mb("-t", "0", "-r", "65", "-c", "8", "-1", None)
        t.ok(rc == 0 and [values(out).get(65 + i) for i in range(8)] == list("10000000"),
             "mbpoll FC01 M1008.0..7 = 1 0 0 0 0 0 0 0")

        # write a register (FC06) and several (FC16), check memory and read back
        rc, out = mb("-t", "4", "-r", "101", [4660])
        t.ok(rc == 0 and "Written 1 references" in out, "mbpoll FC06 ref 101 = 4660")
        t.ok(sim.get("DB800.DBW200") == 0x1234, "console: DB800.DBW200 = 0x1234")
        rc, out = mb("-t", "4", "-r", "51", [52489, 56858, 61227])
        t.ok(rc == 0 and "Written 3 references" in out, "mbpoll FC16 refs 51..53")
        t.ok([sim.get("DB800.DBW%d" % o) for o in (100, 102, 104)] == [0xCD09, 0xDE1A, 0xEF2B],
             "console: DB800.DBW100..104 = CD09 DE1A EF2B")
        rc, out = mb("-t", "4:hex", "-r", "51", "-c", "3", "-1", None)
        t.ok(values(out) == {51: "0xCD09", 52: "0xDE1A", 53: "0xEF2B"}, "mbpoll reads them back")

        # write a coil (FC05) and several (FC15)
        t.ok(sim.cmd("set Q257.1 0") == ["Q257.1 = 0"], "console: Q257.1 = 0")
        rc, out = mb("-t", "0", "-r", "2058", [1])
        t.ok(rc == 0 and "Written 1 references" in out, "mbpoll FC05 coil ref 2058 (Q257.1) = 1")
        t.ok(sim.get("Q257.1") == 1, "console: Q257.1 = 1")
        rc, out = mb("-t", "0", "-r", "2058", "-c", "1", "-1", None)
        t.ok(values(out) == {2058: "1"}, "mbpoll reads Q257.1 back = 1")
        rc, out = mb("-t", "0", "-r", "1153", [1, 0, 1, 1, 0, 0, 1, 1])
        t.ok(rc == 0 and "Written 8 references" in out, "mbpoll FC15 coil refs 1153..1160")
        t.ok(sim.get("MB1144") == 0xCD, "console: MB1144 = 0xCD")

        # an exception as mbpoll reports it
        rc, out = mb("-t", "4:hex", "-r", "1537", "-c", "1", "-1", None)
        t.ok(rc != 0 and "Slave device or server failure" in out,
             "mbpoll FC03 in the missing DB803 -> exception 04")
    print("test_mbpoll: %.1f s" % (time.monotonic() - t0))
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
