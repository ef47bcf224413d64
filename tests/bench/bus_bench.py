#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp — transactions per second on a line with three slaves vs one slave.

    tests/bench/bus_bench.py [--sim build/host/tools/sim/modcp-sim]
                             [--master-bus build/host/tests/integration/master_bus]
                             [--config configs/default.ini] [--seconds 5] [--cycle-ms 1]
                             [--bauds 19200,115200]

For each baud rate: modcp-sim with one config (slave 5, its own pty), then modcp-sim with
three copies of the config at addresses 1, 2, 3 (one line, the bus); master_bus --bench
reads 10 holding registers (FC03) from the slaves in turn for SECONDS, keeping t3.5 of
silence before each request, and the rate is printed. Not a test: nothing is asserted.
Prints one line per run and key=value lines:

    bus_tps_single_BAUD=   transactions/s, one slave
    bus_tps_three_BAUD=    transactions/s, three slaves on one line
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "integration"))
from simlib import Sim  # noqa: E402


def run(a, cfgs, baud, slaves):
    sim = Sim(a.sim, cfgs[0], sets=["serial.baud=%d" % baud], cycle_ms=a.cycle_ms,
              extra=list(cfgs[1:])).start()
    try:
        r = subprocess.run([a.master_bus, "--device", sim.device, "--baud", str(baud), "--slaves",
                            slaves, "--bench", str(a.seconds), "--timeout-ms", "2000"],
                           capture_output=True, text=True, timeout=a.seconds + 60)
    finally:
        sim.stop()
    m = re.search(r"bench: .*: ([\d.]+) transactions/s, (\d+) errors", r.stdout)
    line = [l for l in r.stdout.splitlines() if l.startswith("bench:")]
    return (float(m.group(1)) if m else 0.0), (line[0] if line else r.stdout.strip())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", default=os.path.join(ROOT, "build/host/tools/sim/modcp-sim"))
    ap.add_argument("--master-bus", default=os.path.join(ROOT, "build/host/tests/integration/master_bus"))
    ap.add_argument("--config", default=os.path.join(ROOT, "configs/default.ini"))
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--cycle-ms", type=int, default=1)
    ap.add_argument("--bauds", default="19200,115200")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="modcp-busbench-")
    with open(a.config) as f:
        text = f.read()
    three = []
    for addr in (1, 2, 3):
        p = os.path.join(tmp, "s%d.ini" % addr)
        with open(p, "w") as f:
            f.write(re.sub(r"(?m)^slave_address = \d+", "slave_address = %d" % addr, text))
        three.append(p)
    out = []
    for baud in [int(b) for b in a.bauds.split(",")]:
        single, l1 = run(a, [a.config], baud, "5")
        print("%6d baud, one slave:    %s" % (baud, l1), flush=True)
        bus, l3 = run(a, three, baud, "1,2,3")
        print("%6d baud, three slaves: %s" % (baud, l3), flush=True)
        out += ["bus_tps_single_%d=%.1f" % (baud, single), "bus_tps_three_%d=%.1f" % (baud, bus)]
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
