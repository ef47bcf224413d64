#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp — a line of 1, 16 and 247 slaves: start-up, idle CPU and transactions per second.

    tests/bench/bus_bench.py [--sim build/host/tools/sim/modcp-sim]
                             [--master-bus build/host/tests/integration/master_bus]
                             [--config configs/default.ini] [--members 1,16,247]
                             [--baud 115200] [--cycle-ms 10] [--idle-seconds 3] [--seconds 5]

For each member count N: modcp-sim with N copies of the config at addresses 1..N (N = 1:
one slave on its own pty; else one bus); the start-up time (start to "modcp-sim: ready");
the process's CPU while idle (utime + stime from /proc/PID/stat over --idle-seconds, in %
of one core); then master_bus --bench reads 10 holding registers (FC03) from the
addresses in turn for --seconds (t3.5 of silence before each request) and the rate is
printed. Not a test: nothing is asserted (ctest's bench.bus_bench only checks that it
runs: exit 1 when a run carried no transaction at all). Prints one line per run and key=value lines:

    line_startup_s_N=   seconds to "ready"
    line_idle_cpu_N=    % of one core, idle
    line_tps_N=         transactions/s
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

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "integration"))
from simlib import Sim, member_configs  # noqa: E402


def cpu_ticks(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime, stime (fields 14, 15)


def run(a, cfgs):
    n = len(cfgs)
    t0 = time.monotonic()
    sim = Sim(a.sim, cfgs[0], sets=["serial.baud=%d" % a.baud], cycle_ms=a.cycle_ms,
              extra=list(cfgs[1:]), start_timeout=120.0).start()
    startup = time.monotonic() - t0
    try:
        time.sleep(1.0)  # the members' start-up settles
        hz = os.sysconf("SC_CLK_TCK")
        c0, w0 = cpu_ticks(sim.proc.pid), time.monotonic()
        time.sleep(a.idle_seconds)
        c1, w1 = cpu_ticks(sim.proc.pid), time.monotonic()
        idle = 100.0 * (c1 - c0) / hz / (w1 - w0)
        r = subprocess.run([a.master_bus, "--device", sim.device, "--baud", str(a.baud),
                            "--slaves", "1-%d" % n, "--bench", str(a.seconds),
                            "--timeout-ms", "2000"],
                           capture_output=True, text=True, timeout=a.seconds + 120)
    finally:
        sim.stop()
    m = re.search(r"bench: .*: ([\d.]+) transactions/s, (\d+) errors", r.stdout)
    line = [l for l in r.stdout.splitlines() if l.startswith("bench:")]
    return startup, idle, (float(m.group(1)) if m else 0.0), (line[0] if line else r.stdout.strip())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", default=os.path.join(ROOT, "build/host/tools/sim/modcp-sim"))
    ap.add_argument("--master-bus", default=os.path.join(ROOT, "build/host/tests/integration/master_bus"))
    ap.add_argument("--config", default=os.path.join(ROOT, "configs/default.ini"))
    ap.add_argument("--members", default="1,16,247")
    ap.add_argument("--baud", type=int, default=115200)
    ap.add_argument("--cycle-ms", type=int, default=10)
    ap.add_argument("--idle-seconds", type=float, default=3.0)
    ap.add_argument("--seconds", type=float, default=5.0)
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="modcp-busbench-")
    atexit.register(shutil.rmtree, tmp, True)  # the 247 configs go however the run ends
    out = []
    for n in [int(x) for x in a.members.split(",")]:
        startup, idle, tps, line = run(a, member_configs(a.config, tmp, [("b%d" % k, k) for k in range(1, n + 1)]))
        print("%3d member%s, %d baud, cycle %d ms: start-up %.2f s, idle %.1f %% of a core; %s"
              % (n, " " if n == 1 else "s", a.baud, a.cycle_ms, startup, idle, line), flush=True)
        out += ["line_startup_s_%d=%.2f" % (n, startup), "line_idle_cpu_%d=%.1f" % (n, idle),
                "line_tps_%d=%.1f" % (n, tps)]
    print("\n".join(out))
    return 1 if any(l.startswith("line_tps_") and l.endswith("=0.0") for l in out) else 0


if __name__ == "__main__":
    sys.exit(main())
