#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""One version everywhere (issue 23): the version set once by project(modcp VERSION ...)
in the top-level CMakeLists.txt, handed to this test by CMake, is what

 - `modcp-sim --version` and `modcp-conf --version` print ("modcp-sim 0.2.0", exit 0),
 - the console's `status` ends with (`version=0.2.0`), and
 - FC43/14 object 02 and the FC17 reply carry, configs/default.ini leaving
   `[identification] revision` empty; with `--set identification.revision=V7` they
   carry V7 instead.

    test_version.py --sim modcp-sim --conf modcp-conf --config configs/default.ini \
                    --version 0.2.0
"""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, RawLine, Sim, with_crc  # noqa: E402


def tool_version(t, path, name, want):
    p = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=10)
    t.ok(p.returncode == 0 and p.stdout == "%s %s\n" % (name, want) and p.stderr == "",
         "%s --version: %r, exit %d (expected '%s %s', exit 0)" % (name, p.stdout, p.returncode,
                                                                    name, want))


def fc43_frame(rev):
    """The FC43/14 basic stream reply of configs/default.ini's slave 5 (vendor modcp,
    product CP341-MODBUS) with revision rev."""
    objs = b"\x00\x05modcp\x01\x0cCP341-MODBUS" + bytes([2, len(rev)]) + rev
    return with_crc((bytes.fromhex("05 2B 0E 01 82 00 00 03") + objs).hex(" "))


def fc17_frame(rev):
    """Its FC17 reply: slave id 5, run indicator FF, "modcp CP341-MODBUS rev"."""
    data = b"modcp CP341-MODBUS " + rev
    return with_crc((bytes([5, 0x11, 2 + len(data), 5, 0xFF]) + data).hex(" "))


def identification(t, line, rev, what):
    want = fc43_frame(rev)
    got = line.xfer(with_crc("05 2B 0E 01 00"), len(want))
    t.ok(got == want, "%s: FC43/14 basic stream, object 02 = %r (%s)" % (what, rev, got.hex(" ")))
    want = fc17_frame(rev)
    got = line.xfer(with_crc("05 11"), len(want))
    t.ok(got == want, "%s: FC17 reply ends with %r (%s)" % (what, rev, got.hex(" ")))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--conf", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--version", required=True, help="project(modcp VERSION ...)")
    a = ap.parse_args()
    t = Checks()
    want = a.version
    tool_version(t, a.sim, "modcp-sim", want)
    tool_version(t, a.conf, "modcp-conf", want)

    with Sim(a.sim, a.config, sets=["serial.baud=115200"], cycle_ms=1) as sim:
        ans = sim.cmd("status")
        t.ok(len(ans) == 1 and ans[0].endswith(" version=" + want),
             "console status ends with version=%s (%r)" % (want, ans[-1:]))
        line = RawLine(sim.device)
        try:
            identification(t, line, want.encode(), "revision left empty")
        finally:
            line.close()

    with Sim(a.sim, a.config, sets=["serial.baud=115200", "identification.revision=V7"],
             cycle_ms=1) as sim:
        line = RawLine(sim.device)
        try:
            identification(t, line, b"V7", "revision = V7")
        finally:
            line.close()
        ans = sim.cmd("status")
        t.ok(len(ans) == 1 and ans[0].endswith(" version=" + want),
             "console status: still version=%s with revision = V7" % want)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
