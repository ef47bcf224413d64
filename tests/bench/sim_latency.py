#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp — the simulator's slave time, measured as a raw master on its pty.

    tests/bench/sim_latency.py [--sim build/host/tools/sim/modcp-sim]
                               [--config configs/default.ini] [--baud 115200]
                               [--cycle-ms 1] [--n 1000] [--qty 10] [--seed 1]
                               [--hist] [--stages]

Starts modcp-sim (RTU, the configuration with --set serial.baud=BAUD and --cycle-ms),
sends N requests FC03 (slave 5, holding register 80, QTY registers) one at a time and
prints, as key=value lines (BAUD as suffix):

    sim_slave_time_p50_us_BAUD=   median slave time
    sim_slave_time_p90_us_BAUD=   90th percentile
    sim_slave_time_p99_us_BAUD=   99th percentile
    sim_slave_time_model_us_BAUD= t3.5 + 1/2 cycle + 1 character
    sim_slave_time_n_BAUD=        requests measured (all replies checked byte for byte)

Slave time: from the moment the master's single write() of the whole request (8 bytes)
has returned to the moment poll() reports the first reply byte readable (CLOCK_MONOTONIC,
time.monotonic_ns). A pseudo-terminal does not pace bytes: the request arrives in one
piece, so the end of the write is the end of the request's last character on the
simulated line (the CP time-stamps the bytes when it reads them and measures t3.5 from
there). On the way out the simulator's HAL paces: byte k of the reply is written when its
last stop bit would have left a real line, t0 + (k+1) character times after the CP
handed the reply to the UART; the first reply byte therefore shows up one character
time after the reply is ready.

Model (what an ideal slave on this line would do): the CP detects the end of the frame
t3.5 after the last byte, hands the job to the CPU side, which runs it at its next FB
call (the request's phase against the CPU cycle is uniform: on average half a cycle;
the master waits a random pause between requests so that the phase does not lock), and
the first reply character takes one character time. t3.5 and the character time come
from the same rules as the core (firmware/src/timing.c: eof_timing = manual, f_mul 1,
8E1): 9600 -> 4000 us + 1146 us; 115200 -> 335 us + 96 us.

The pty's own delay is in the measurement: the request's bytes reach the simulator, and
the reply's bytes the master, through the kernel's tty buffer work (a few tens of us per
direction on a loaded machine); sim_pty_hop_p50_us= is one such hop measured on a pty
pair of the script's own. A sample whose write() took longer than 100 us (the master was
preempted between writing and reading the clock) is not counted and the request is
repeated (sim_slave_time_repeated_BAUD=).

--stages splits the slave time into the simulator's stages (pty hop in, t3.5, timer
lateness, the wait for the FB call, its lateness, the CP taking the reply, one
character, the first byte's lateness, pty hop out: p50, mean, p90 and how many samples
each delayed by over 100 us more than its median), from time stamps the simulator
writes with MODCP_SIM_LATLOG (tools/sim/latlog.h) joined with the master's own.

Nothing is asserted (the machine is shared): the script fails only when the simulator
does not start or a reply is wrong or missing.
"""
import argparse
import atexit
import os
import random
import select
import sys
import tempfile
import time
import tty

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests", "integration"))
import simlib  # noqa: E402

# firmware/src/timing.c, eof_timing = manual (the manual's TIME_OUT table), f_mul = 1
T35_TABLE_US = {300: 128000, 600: 64000, 1200: 32000, 2400: 16000, 4800: 8000, 9600: 4000,
                19200: 2000, 38400: 1000, 76800: 500}


def div_ceil(a, b):
    return -(-a // b)


def t35_us(baud):
    return T35_TABLE_US.get(baud, div_ceil(385 * 100000, baud))


def char_us(baud, bits=11):
    return div_ceil(bits * 1000000, baud)


def percentile(sorted_vals, p):
    """Nearest-rank percentile."""
    k = max(1, div_ceil(p * len(sorted_vals), 100))
    return sorted_vals[k - 1]


WRITE_SLOW_US = 100  # a write() that took longer: the master was preempted, not counted


def measure(line, n, qty, t35, cycle_us, rng, samples=None):
    """n slave times in us; and how many samples were repeated (slow write). samples,
    if given, gets (t_end_ns, t_first_ns, counted) of every request, in order."""
    req = simlib.with_crc("050300%02X%04X" % (0x50, qty))
    want = 5 + 2 * qty
    times = []
    repeated = 0
    i = 0
    while len(times) < n:
        i += 1
        # a pause of at least t3.5 plus a random part of one cycle, so the request's
        # phase against the CPU cycle is uniform
        pause_s = (2 * t35 + 200 + rng.uniform(0, cycle_us)) / 1e6
        time.sleep(pause_s)
        t_start = time.monotonic_ns()
        os.write(line.fd, req)
        t_end = time.monotonic_ns()
        r, _, _ = select.select([line.fd], [], [], 2.0)
        t_first = time.monotonic_ns()
        if not r:
            raise SystemExit("sim_latency: no reply to request %d" % i)
        rep = line.recv(want, 2.0)
        if len(rep) != want or rep[:3] != bytes([5, 3, 2 * qty]) or \
                simlib.crc16(rep[:-2]) != rep[-2:]:
            raise SystemExit("sim_latency: bad reply to request %d: %s" % (i, rep.hex()))
        slow = (t_end - t_start) / 1000.0 > WRITE_SLOW_US
        if samples is not None:
            samples.append((t_end, t_first, not slow))
        if slow:
            repeated += 1
            continue
        times.append((t_first - t_end) / 1000.0)
    return times, repeated


# The simulator's stage log (MODCP_SIM_LATLOG, tools/sim/latlog.h): one line per reply.
LATLOG_FIELDS = ("seq rx timer_due timer_seen job fb_due fb_start fb_end take tx_t0 "
                 "first_due first").split()
# (name, from, to): consecutive stages from the master's write to its poll(); their sum
# is the slave time. "end" / "poll" are the master's own time stamps.
STAGES = (("pty hop in (write -> CP read)", "end", "rx"),
          ("t3.5 (CP read -> timer due)", "rx", "timer_due"),
          ("timer late", "timer_due", "timer_seen"),
          ("request onto backplane", "timer_seen", "job"),
          ("wait for the FB call (cycle phase)", "job", "fb_due"),
          ("FB call late", "fb_due", "fb_start"),
          ("FB call runs", "fb_start", "fb_end"),
          ("CP takes the reply", "fb_end", "take"),
          ("reply to UART", "take", "tx_t0"),
          ("1 character", "tx_t0", "first_due"),
          ("first byte late", "first_due", "first"),
          ("pty hop out (write -> master poll)", "first", "poll"))


def stages_report(samples, log_path):
    """Median and mean of every stage over the counted samples, as '#' lines."""
    with open(log_path) as f:
        rows = [dict(zip(LATLOG_FIELDS, map(int, ln.split()))) for ln in f if ln.strip()]
    if len(rows) != len(samples):
        print("# stages: %d log lines for %d requests: not joined" % (len(rows), len(samples)))
        return
    per = {name: [] for name, _, _ in STAGES}
    for (t_end, t_first, counted), r in zip(samples, rows):
        if not counted:
            continue
        r = dict(r)
        r["end"] = (t_end // 1000) & 0xFFFFFFFF
        r["poll"] = (t_first // 1000) & 0xFFFFFFFF
        for name, a, b in STAGES:
            d = (r[b] - r[a]) & 0xFFFFFFFF
            if d >= 0x80000000:
                d -= 0x100000000
            per[name].append(d)
    # late: how many samples this stage delayed by over 100 us more than its median (a
    # thread that did not get a core in time); each percent of them moves the slave
    # time's median by about 5 us (the cycle phase spreads the samples over one cycle)
    print("# stage                                   p50      mean     p90   late")
    tot50 = totm = 0.0
    for name, _, _ in STAGES:
        v = sorted(per[name])
        mean = sum(v) / len(v)
        p50 = percentile(v, 50)
        tot50 += p50
        totm += mean
        late = sum(1 for x in v if x > p50 + 100) if "cycle" not in name else 0
        print("# %-38s %6.0f  %8.1f  %6.0f  %5d" % (name, p50, mean, percentile(v, 90), late))
    print("# %-38s %6.0f  %8.1f" % ("sum", tot50, totm))


def pty_hop_us(n=500):
    """Median time from write() on one side of a fresh pty pair until poll() sees the
    bytes on the other side, in this process: what the pty itself adds to each
    direction (the request in, the reply out) on this machine, now."""
    m, s = os.openpty()
    try:
        tty.setraw(m)
        tty.setraw(s)
        ts = []
        for _ in range(n):
            os.write(s, b"\x05\x03\x00\x50\x00\x0a\x00\x00")
            t0 = time.monotonic_ns()
            select.select([m], [], [], 1.0)
            ts.append((time.monotonic_ns() - t0) / 1000.0)
            os.read(m, 64)
            time.sleep(0.0003)
        ts.sort()
        return percentile(ts, 50)
    finally:
        os.close(m)
        os.close(s)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sim", default=os.path.join(ROOT, "build", "host", "tools", "sim",
                                                  "modcp-sim"))
    ap.add_argument("--config", default=os.path.join(ROOT, "configs", "default.ini"))
    ap.add_argument("--baud", type=int, default=115200)
    ap.add_argument("--cycle-ms", type=int, default=1)
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--qty", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--hist", action="store_true", help="also print a histogram")
    ap.add_argument("--stages", action="store_true",
                    help="also print where the time goes, stage by stage (the simulator's "
                         "MODCP_SIM_LATLOG)")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    t35 = t35_us(a.baud)
    ch = char_us(a.baud)
    cycle_us = a.cycle_ms * 1000
    sets = ["serial.baud=%d" % a.baud, "serial.parity=even", "serial.data_bits=8",
            "serial.stop_bits=1", "protocol.framing=rtu", "protocol.eof_timing=manual",
            "protocol.f_mul=1"]
    samples = [] if a.stages else None
    log_path = None
    if a.stages:
        fd, log_path = tempfile.mkstemp(prefix="modcp-latlog-")
        os.close(fd)
        # removed however the run ends (a bad reply exits, Ctrl-C, a failed start)
        atexit.register(lambda: os.path.exists(log_path) and os.unlink(log_path))
        os.environ["MODCP_SIM_LATLOG"] = log_path
    try:
        with simlib.Sim(a.sim, a.config, sets=sets, cycle_ms=a.cycle_ms, control=False) as sim:
            line = simlib.RawLine(sim.device)
            try:
                measure(line, 20, a.qty, t35, cycle_us, rng, samples)  # warm-up, not counted
                times, repeated = measure(line, a.n, a.qty, t35, cycle_us, rng, samples)
                times.sort()
            finally:
                line.close()
        if a.stages:
            stages = (samples, log_path)
    finally:
        os.environ.pop("MODCP_SIM_LATLOG", None)
    model = t35 + cycle_us / 2 + ch
    sfx = "_%d" % a.baud
    print("sim_slave_time_p50_us%s=%.0f" % (sfx, percentile(times, 50)))
    print("sim_slave_time_p90_us%s=%.0f" % (sfx, percentile(times, 90)))
    print("sim_slave_time_p99_us%s=%.0f" % (sfx, percentile(times, 99)))
    print("sim_slave_time_model_us%s=%.0f" % (sfx, model))
    print("sim_slave_time_min_us%s=%.0f" % (sfx, times[0]))
    print("sim_slave_time_n%s=%d" % (sfx, len(times)))
    print("sim_slave_time_repeated%s=%d" % (sfx, repeated))
    print("sim_pty_hop_p50_us=%.0f" % pty_hop_us())
    print("# baud %d cycle %d ms: t3.5 %d us + cycle/2 %d us + 1 character %d us"
          % (a.baud, a.cycle_ms, t35, cycle_us // 2, ch))
    if a.stages:
        stages_report(*stages)
    if a.hist:
        lo = times[0]
        step = max(1.0, (times[-1] - lo) / 20)
        for k in range(20):
            c = sum(1 for t in times if lo + k * step <= t < lo + (k + 1) * step)
            print("# %8.0f %s" % (lo + k * step, "#" * (c * 60 // len(times))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
