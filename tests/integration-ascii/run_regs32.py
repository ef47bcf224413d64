#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""32-bit registers over RTU ([ASCII-32] §4.5): modcp-sim with configs/regs32.ini on its pty,
master_regs32 (libmodbus, raw requests) runs its checks over the line, then the values
it wrote are verified from the controller side through the simulator's console
(`get DBn.DBDm [float]`: DBD as int32 and as IEEE-754 float), and the diagnostic
buffer holds the events of the refused requests.

    run_regs32.py --sim modcp-sim --simlib DIR --config configs/regs32.ini --master master_regs32
"""
import argparse
import re
import subprocess
import sys

passed = 0
failed = 0


def ok(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL  " + what, flush=True)


def get(sim, operand, as_float=False):
    ans = sim.cmd("get %s%s" % (operand, " float" if as_float else ""))
    m = re.match(r"\S+ = (\S+) \((\S+)\)", ans[0]) if ans else None
    if not m:
        raise RuntimeError("get %s: %r" % (operand, ans))
    if as_float:
        return float(m.group(1)), int(m.group(2), 16)
    return int(m.group(1), 16), int(m.group(2))  # hex, signed / unsigned decimal


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--simlib", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--master", required=True)
    a = ap.parse_args()
    sys.path.insert(0, a.simlib)
    from simlib import Sim  # noqa: E402

    with Sim(a.sim, a.config) as sim:
        ok(sim.settings == "9600 8E1 RTU", "settings %r" % sim.settings)
        rc = subprocess.call([a.master, "--device", sim.device], timeout=300)
        ok(rc == 0, "master_regs32 exit code %d" % rc)

        # what the master wrote, seen by the controller (big-endian as stored)
        ok(get(sim, "DB2.DBW766")[0] == 0x2B1A, "DB2.DBW766 = 2B1A ([ASCII-32] §4.5 FC06 int16)")
        ok(get(sim, "DB2.DBW200")[0] == 0xCD09, "DB2.DBW200 = CD09 ([ASCII-32] §4.5 FC16 int16)")
        ok(get(sim, "DB2.DBW204")[0] == 0xEF2B, "DB2.DBW204 = EF2B")
        ok(get(sim, "DB4.DBD8")[0] == 0x12233445, "DB4.DBD8 = 12233445 ([ASCII-32] §9.8 FC06 float)")
        ok(get(sim, "DB3.DBD12")[0] == 0x3A09DE1A, "DB3.DBD12 = 3A09DE1A ([ASCII-32] §9.12)")
        ok(get(sim, "DB3.DBD16")[0] == 0x01020304, "DB3.DBD16 = 01020304 ([ASCII-32] §9.12)")
        ok(get(sim, "DB4.DBD800", True) == (0.001, 0x3A83126F), "DB4.DBD800 = 0.001")
        ok(get(sim, "DB4.DBD804", True) == (-123.5, 0xC2F70000), "DB4.DBD804 = -123.5")
        ok(get(sim, "DB4.DBD36", True)[1] == 0xC2F6E979, "DB4.DBD36 = -123.456 (FC06, 4 bytes)")
        ok(get(sim, "DB3.DBD200") == (0x80000000, -2147483648), "DB3.DBD200 = int32 min")
        ok(get(sim, "DB3.DBD208") == (0xFFFF0000, -65536), "DB3.DBD208 = -65536")
        ok(get(sim, "DB4.DBD4000", True)[0] == -7.0, "DB4.DBD4000 (8000) = -7.0")
        ok(get(sim, "DB4.DBD4248", True)[0] == 24.0, "DB4.DBD4248 (8062) = 24.0")
        ok(get(sim, "DB4.DBD4252")[0] == 0, "DB4.DBD4252 (8063) untouched")

        events = sim.diag()
        for ev, what in (("0E54", "past the range end"), ("0E51", "no range"),
                         ("0832", "quantity"), ("0833", "byte count")):
            ok(ev in events, "diagnostic buffer holds (%s)%sH %s: %r" % (ev[:2], ev[2:], what, events))
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
