#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp integration test: a whole Modbus line, 247 slaves (every address) in one modcp-sim.

    test_line247.py --sim PATH/modcp-sim --master-bus PATH/master_bus --config configs/default.ini
                    [--members 247] [--ops 2000] [--baud 115200]

Copies of the config at addresses 1..N on one bus (115200 baud); every member prints
its "ready" line; a libmodbus master (master_bus --same-start) sends --ops mixed requests
(FC01/03/05/06/15/16) to addresses chosen at random among all N, checks every read
against its shadow of that slave's memory and at the end reads back every slave's whole
memory: 0 mismatches and 0 errors pass. The console still reaches the last member. The
start-up time (start to "modcp-sim: ready") is printed, not asserted. ctest runs 2,000
requests (integration.line247); the issue's 10,000: --ops 10000.
"""
import atexit
import shutil
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, Sim, member_configs  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--master-bus", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--members", type=int, default=247)
    ap.add_argument("--ops", type=int, default=2000)
    ap.add_argument("--baud", type=int, default=115200)
    a = ap.parse_args()
    t = Checks()
    tmp = tempfile.mkdtemp(prefix="modcp-line247-")
    atexit.register(shutil.rmtree, tmp, True)  # the 247 configs go however the run ends
    cfgs = member_configs(a.config, tmp, [("s%d" % k, k) for k in range(1, a.members + 1)])
    t0 = time.monotonic()
    sim = Sim(a.sim, cfgs[0], sets=["serial.baud=%d" % a.baud], cycle_ms=10,
              extra=cfgs[1:], start_timeout=60.0).start()
    print("start-up: %d members ready in %.2f s" % (a.members, time.monotonic() - t0), flush=True)
    try:
        ready = [l for l in sim.lines if re.match(r"modcp-sim: @s\d+ ready$", l)]
        t.ok(len(ready) == a.members, "%d members ready (%d)" % (a.members, len(ready)))
        last = sim.cmd("@s%d status" % a.members)
        t.ok(any(l.startswith("faults:") for l in last),
             "@s%d answers on the console: %r" % (a.members, last[:1]))
        r = subprocess.run([a.master_bus, "--device", sim.device, "--baud", str(a.baud),
                            "--slaves", "1-%d" % a.members, "--ops", str(a.ops), "--same-start",
                            "--max-regs", "60", "--max-coils", "200", "--timeout-ms", "5000",
                            "--recover-ms", "100"],
                           capture_output=True, text=True, timeout=3600)
        mixed = [l for l in r.stdout.splitlines() if l.startswith("mixed:")]
        print(mixed[0] if mixed else r.stdout[-2000:], flush=True)
        bad = [l for l in r.stdout.splitlines() if l.startswith("FAIL") or "differs" in l]
        for line in bad[:10]:
            print(line)
        t.ok(r.returncode == 0 and re.search(r" 0 mismatches, 0 errors", mixed[0] if mixed else ""),
             "master_bus: %d requests over addresses 1..%d, 0 mismatches, 0 errors, every "
             "slave's memory its own writes (%s)" % (a.ops, a.members,
                                                      (r.stdout.strip().splitlines() or
                                                       [r.stderr.strip()])[-1]))
    finally:
        rc, gone = sim.stop()
    t.ok(rc == 0 and gone, "modcp-sim stopped cleanly (exit %r, pty link removed %r)" % (rc, gone))
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
