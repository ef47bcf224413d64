#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Replay of a capture (issue 22 item 4): modcp-sim --replay FILE.pcap [--speed F].

 - capture: configs/default.ini (9600 8E1, slave 5), six requests by a raw RTU master
   (FC03, FC06, FC03, FC16, FC03, and one for slave 7 that nobody answers) with
   --capture;
 - replay against the same configuration: 6 requests, 0 differ, exit code 0; the same at
   --speed 4;
 - replay after the user program changed one register (DB800.DBW160 = 0x1111, --script):
   exactly one request differs, the first FC03, at its value bytes 4 and 5 (87 65 -> 11
   11) and its CRC (bytes 8 and 9); exit code 3;
 - a file that is not a capture of modcp-sim is refused with a message naming it.

    test_replay.py --sim PATH/modcp-sim --config configs/default.ini
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402

REQUESTS = [
    ("05 03 00 50 00 02", 9),
    ("05 06 00 64 12 34", 8),
    ("05 03 00 64 00 01", 7),
    ("05 10 00 64 00 02 04 AB CD 00 01", 8),
    ("07 03 00 50 00 02", 0),
    ("05 03 00 64 00 02", 9),
]


def capture(a, t, pcap):
    sim = Sim(a.sim, a.config, extra=["--capture", pcap]).start()
    line = RawLine(sim.device)
    try:
        for req, want in REQUESTS:
            rsp = line.xfer(with_crc(req), want, timeout=0.3 if want == 0 else 1.0)
            t.ok(len(rsp) == want, "capture: %s answered with %d bytes" % (req, len(rsp)))
            time.sleep(0.03)
    finally:
        line.close()
        sim.stop()


def replay(a, pcap, *extra):
    p = subprocess.run([a.sim, a.config, "--replay", pcap] + list(extra), stdin=subprocess.DEVNULL,
                       capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    t = Checks()
    tmp = tempfile.mkdtemp(prefix="modcp-replay-")
    try:
        pcap = os.path.join(tmp, "line.pcap")
        capture(a, t, pcap)

        rc, out = replay(a, pcap)
        t.ok(rc == 0 and re.search(r"replay .*: 6 requests, 0 differ", out) is not None,
             "replay: 6 requests, 0 differ, exit 0 (rc %d: %s)" % (rc, out.strip()[-300:]))
        rc, out = replay(a, pcap, "--speed", "4")
        t.ok(rc == 0 and re.search(r"replay .*: 6 requests, 0 differ", out) is not None,
             "replay --speed 4: 0 differ (rc %d: %s)" % (rc, out.strip()[-300:]))

        script = os.path.join(tmp, "change.txt")
        with open(script, "w") as f:
            f.write("set DB800.DBW160 0x1111\n")
        rc, out = replay(a, pcap, "--script", script)
        t.ok(rc == 3 and re.search(r"replay .*: 6 requests, 1 differ", out) is not None,
             "one register changed: 1 request differs, exit 3 (rc %d: %s)" % (rc, out.strip()[-300:]))
        diffs = [l for l in out.splitlines() if l.startswith("replay: request")]
        t.ok(len(diffs) == 2 and all(l.startswith("replay: request 1") for l in diffs),
             "only request 1 reported (%s)" % diffs)
        t.ok(any("recorded [05 03 04 87 65 43 21 76 70]" in l for l in diffs),
             "the recorded reply named")
        byte_lines = [l for l in diffs if ": bytes " in l]
        pos = re.findall(r" (\d+): (\S\S) -> (\S\S)", byte_lines[0]) if byte_lines else []
        t.ok([p[0] for p in pos] == ["4", "5", "8", "9"] and pos[0][1:] == ("87", "11") and
             pos[1][1:] == ("65", "11"),
             "the differing bytes: the value 87 65 -> 11 11 and the CRC (%s)" % byte_lines)

        bad = os.path.join(tmp, "bad.pcap")
        with open(bad, "wb") as f:
            f.write(b"not a capture at all, longer than 24 bytes")
        rc, out = replay(a, bad)
        t.ok(rc != 0 and "--replay %s: not a classic pcap file" % bad in out,
             "a file that is not a pcap refused, named (%s)" % out.strip()[-200:])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
