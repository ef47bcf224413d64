#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp integration tests: start modcp-sim on its own pty, talk to its console, stop it.

As a module:
    with Sim(sim_bin, config, sets=["serial.baud=115200"], cycle_ms=1) as sim:
        sim.device            # the pty a master opens (a symlink made by --pty-link)
        sim.cmd("get MB1008") # console answer lines
        sim.diag()            # [(class, number), ...] newest first

As a runner (ctest): start the simulator, run a command with {dev} / {ctl} replaced
by the pty link and the console FIFO, stop the simulator with SIGTERM and check that
the pty link is gone:
    simlib.py --sim modcp-sim --config configs/default.ini [--set S.K=V] [--cycle-ms N]
              [--timeout S] -- master_libmodbus --device {dev} --control {ctl}
"""
import argparse
import atexit
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

_counter = 0


class SimError(Exception):
    pass


def _die_with_parent():
    """In the child: SIGTERM when the test process dies (e.g. killed by a ctest TIMEOUT),
    so no simulator is left behind holding a pty. Linux only; ignored elsewhere."""
    try:
        import ctypes
        ctypes.CDLL(None).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except Exception:
        pass


class Sim:
    def __init__(self, sim_bin, config, sets=(), cycle_ms=None, trace=False, control=True,
                 extra=(), start_timeout=15.0):
        global _counter
        _counter += 1
        self.tmp = tempfile.mkdtemp(prefix="modcp-it-")
        atexit.register(self._cleanup)
        self.link = os.path.join(self.tmp, "tty")
        self.control = os.path.join(self.tmp, "ctl") if control else None
        args = [sim_bin, config, "--pty-link", self.link]
        for s in sets:
            args += ["--set", s]
        if cycle_ms is not None:
            args += ["--cycle-ms", str(cycle_ms)]
        if trace:
            args.append("--trace")
        if self.control:
            args += ["--control", self.control]
        args += list(extra)
        self.args = args
        self.start_timeout = start_timeout
        self.proc = None
        self.lines = []          # everything the simulator printed
        self.q = queue.Queue()
        self.pty = None
        self.slave = None
        self.settings = None
        self._marker = 0

    # -- life cycle -------------------------------------------------------------
    def start(self):
        self.proc = subprocess.Popen(self.args, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True, bufsize=1,
                                     preexec_fn=_die_with_parent)
        self.reader = threading.Thread(target=self._reader, daemon=True)
        self.reader.start()
        deadline = time.monotonic() + self.start_timeout
        ready = False
        while time.monotonic() < deadline:
            try:
                line = self.q.get(timeout=0.1)
            except queue.Empty:
                if self.proc.poll() is not None:
                    break
                continue
            m = re.match(r"modcp-sim: slave (\d+) on (\S+) \((.*)\)", line)
            if m:
                self.slave, self.pty, self.settings = int(m.group(1)), m.group(2), m.group(3)
            if line.strip() == "modcp-sim: ready":
                ready = True
                break
        if not ready:
            out = "\n".join(self.lines)
            self.kill()
            raise SimError("modcp-sim did not become ready:\n" + out)
        if not os.path.islink(self.link) or os.readlink(self.link) != self.pty:
            raise SimError("pty link %s missing or wrong" % self.link)
        return self

    def _reader(self):
        for line in self.proc.stdout:
            line = line.rstrip("\n")
            self.lines.append(line)
            self.q.put(line)
        self.q.put(None)

    @property
    def device(self):
        return self.link

    def stop(self, timeout=10.0):
        """SIGTERM; returns (exit code, link removed)."""
        if self.proc is None:
            return None, True
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            rc = self.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        # the process has ended, but what it printed last may still be in the pipe: the
        # reader has read all of it when it reaches the end of the output
        self.reader.join(timeout=timeout)
        gone = not os.path.lexists(self.link)
        self._cleanup()
        return rc, gone

    def _cleanup(self):
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def kill(self):
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()
        return False

    # -- console ----------------------------------------------------------------------
    def cmd(self, line, timeout=10.0):
        """Run one console command; returns its answer lines (trace lines filtered out)."""
        self._marker += 1
        mark = "__end_%d__" % self._marker
        self.proc.stdin.write(line + "\n" + "echo " + mark + "\n")
        self.proc.stdin.flush()
        out = []
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise SimError("no answer to %r" % line)
            try:
                got = self.q.get(timeout=left)
            except queue.Empty:
                continue
            if got is None:
                raise SimError("modcp-sim ended while answering %r" % line)
            if got == mark:
                return out
            if re.match(r"\[\s*\d+\.\d{6}\] ", got):
                continue  # trace line
            out.append(got)

    def get(self, operand):
        """Value of an operand via the console (int; floats with 'float')."""
        ans = self.cmd("get " + operand)
        m = re.match(r"\S+ = (0x[0-9A-F]+|\d+)", ans[0]) if ans else None
        if not m:
            raise SimError("get %s: %r" % (operand, ans))
        return int(m.group(1), 0)

    def diag(self):
        """Events of the diagnostic buffer, newest first, as 'CCNN' hex strings."""
        ans = self.cmd("diag")
        return [m.group(1) + m.group(2) for m in
                (re.match(r"event \d+: \(([0-9A-F]{2})\)([0-9A-F]{2})H", a) for a in ans) if m]

    def status(self):
        ans = self.cmd("status")
        return dict(kv.split("=", 1) for kv in ans[0].split()[1:] if "=" in kv)

    def trace_lines(self):
        return [l for l in self.lines if re.match(r"\[\s*\d+\.\d{6}\] ", l)]


class Checks:
    """ok()/done() with the same output as the C master: 'N passed, M failed'."""

    def __init__(self, verbose=True):
        self.passed = 0
        self.failed = 0
        self.verbose = verbose

    def ok(self, cond, what):
        if cond:
            self.passed += 1
            if self.verbose:
                print("ok - " + what, flush=True)
        else:
            self.failed += 1
            print("FAIL - " + what, flush=True)
        return cond

    def done(self):
        print("%d passed, %d failed" % (self.passed, self.failed), flush=True)
        return 0 if self.failed == 0 else 1


def run_checks(prefix, tools, steps):
    """The main() of a test that needs the simulator (--sim) and a configuration
    (--config), the line tools `tools` and a scratch folder: each step(a, t, tmp) in turn,
    the folder removed after; exit status of Checks.done() (1 when a tool is missing)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    a = ap.parse_args()
    for tool in tools:
        if shutil.which(tool) is None:
            print("%s missing: tools/install-deps installs it" % tool)
            return 1
    t = Checks()
    tmp = tempfile.mkdtemp(prefix=prefix)
    try:
        for step in steps:
            step(a, t, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return t.done()


def crc16(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return bytes([crc & 0xFF, crc >> 8])


def with_crc(hexstr):
    b = bytes.fromhex(hexstr)
    return b + crc16(b)


def member_configs(src, tmp, specs):
    """Copies of the configuration src in tmp, one per member: specs is a list of
    (name, slave address) or (name, slave address, {key: value}) -> their paths."""
    with open(src) as f:
        text = f.read()
    out = []
    for spec in specs:
        name, addr = spec[0], spec[1]
        t = re.sub(r"(?m)^slave_address = \d+", "slave_address = %d" % addr, text)
        for k, v in (spec[2] if len(spec) > 2 else {}).items():
            t, n = re.subn(r"(?m)^%s = .*$" % re.escape(k), "%s = %s" % (k, v), t)
            assert n == 1, k
        p = os.path.join(tmp, name + ".ini")
        with open(p, "w") as f:
            f.write(t)
        out.append(p)
    return out


class RawLine:
    """The pty opened raw (no parity: a pty has none), for byte-exact exchanges."""

    def __init__(self, path):
        import termios
        import tty
        self.fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        tty.setraw(self.fd)
        termios.tcflush(self.fd, termios.TCIOFLUSH)

    def close(self):
        os.close(self.fd)

    def flush(self):
        import termios
        termios.tcflush(self.fd, termios.TCIFLUSH)

    def send(self, data):
        os.write(self.fd, data)

    def recv(self, want, timeout):
        """Read until want bytes or timeout seconds; returns bytes."""
        import select
        out = b""
        end = time.monotonic() + timeout
        while len(out) < want:
            left = end - time.monotonic()
            if left <= 0:
                break
            r, _, _ = select.select([self.fd], [], [], left)
            if not r:
                break
            try:
                out += os.read(self.fd, want - len(out))
            except BlockingIOError:
                pass
        return out

    def xfer(self, frame, want, timeout=2.0):
        self.flush()
        self.send(frame)
        return self.recv(want, timeout)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--config", required=True)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--cycle-ms", type=int)
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--trace", action="store_true")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command and a.command[0] == "--" else a.command
    if not cmd:
        ap.error("no command")
    sim = Sim(a.sim, a.config, sets=a.set, cycle_ms=a.cycle_ms, trace=a.trace)
    sim.start()
    print("simlib: %s on %s (%s), link %s" % (a.config, sim.pty, sim.settings, sim.link), flush=True)
    cmd = [c.replace("{dev}", sim.link).replace("{ctl}", sim.control or "") for c in cmd]
    try:
        rc = subprocess.call(cmd, timeout=a.timeout)
    except subprocess.TimeoutExpired:
        print("simlib: %s timed out after %.0f s" % (cmd[0], a.timeout))
        rc = 124
    src, gone = sim.stop()
    if src != 0:
        print("simlib: modcp-sim exited with %s" % src)
        print("\n".join(sim.lines[-20:]))
        rc = rc or 1
    if not gone:
        print("simlib: the pty link %s was not removed" % sim.link)
        rc = rc or 1
    return rc


if __name__ == "__main__":
    sys.exit(main())
