#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""test_docs.py — the commands and example values that README.md and docs/ show, run.

    test_docs.py --root ROOT --build BUILD_DIR

1. Every shell command in a ```sh block of README.md and docs/*.md is run as a reader
   would paste it: `tools/run …` (its banner is read and the master command it prints is
   run), `mbpoll …` and `/usr/bin/python3 - <<'PY' … PY` against a simulator started with
   configs/default.ini (the configuration the docs name), `modcp-conf …` and
   `modcp-sim …` from the build, `tools/run-qemu BOARD` when its image exists. An
   expected result written as `# -> 0x8765 0x4321` must appear in the output. Synopses
   (lines with [options] or upper-case placeholders such as PATH) are not commands.
   Not re-run here, and said so: `tools/test` (it is the runner of this test), the
   commands that build or run the ARM images and the QEMU suites (tools/test runs them).
2. The libmodbus example (the ```c block of README.md) is compiled and run; it must
   print the values its comment names.
3. docs/simulator.md's console session (the ```console block: `> command` lines and the
   answers after them) is replayed on a simulator with configs/default.ini, answer for
   answer; every `OPERAND = VALUE` answer written in its console table must be one of
   the session's answers, so that the table cannot drift from the configuration.
Last line "N passed, M failed".
"""
import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "integration"))
from simlib import Checks, Sim  # noqa: E402

NOT_RUN = {
    "tools/test": "it is the runner of this test",
    "tools/build-arm": "tools/test builds the images",
    "tools/size": "needs the ARM images; tools/test's build covers it",
    "ctest": "the QEMU suites run in tools/test",
    "tests/bench/sim_latency.py": "a benchmark: tools/bench --summary runs it",
}
PLACEHOLDER = re.compile(r"\[[^\]]*\]|\b(PATH|FILE|COMMAND|CONFIG\.ini|N)\b")


def blocks(path, lang):
    """(first line number, [lines]) of each ```lang block of a Markdown file."""
    out, cur, start = [], None, 0
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if cur is None and line.strip() == "```" + lang:
                cur, start = [], n + 1
            elif cur is not None and line.strip().startswith("```"):
                out.append((start, cur))
                cur = None
            elif cur is not None:
                cur.append(line)
    return out


def commands(lines):
    """Commands of an sh block: continuation lines joined, heredocs kept whole."""
    cmds, i = [], 0
    while i < len(lines):
        line = lines[i]
        if not line.strip() or line.lstrip().startswith("#"):
            i += 1
            continue
        m = re.search(r"<<'(\w+)'", line)
        if m:
            end = i + 1
            while end < len(lines) and lines[end].strip() != m.group(1):
                end += 1
            cmds.append((i, line, lines[i + 1:end]))
            i = end + 1
            continue
        text = line
        while i + 1 < len(lines) and lines[i + 1].startswith(" ") and lines[i + 1].strip():
            i += 1
            text += " " + lines[i].strip()
        cmds.append((i, text, None))
        i += 1
    return cmds


def split_comment(text):
    """'cmd args   # -> a b' -> ('cmd args', ['a', 'b'])"""
    cmd, _, comment = text.partition(" #")
    want = []
    m = re.search(r"->\s*(.*)", comment)
    if m:
        want = m.group(1).split()
    return cmd.strip(), want


class Docs:
    def __init__(self, root, build):
        self.root, self.build = root, build
        self.sim_bin = os.path.join(build, "tools", "sim", "modcp-sim")
        self.conf_bin = os.path.join(build, "tools", "conf", "modcp-conf")
        self.t = Checks()
        self.sim = None
        self.tmp = tempfile.mkdtemp(prefix="modcp-docs-")

    def default_sim(self):
        if self.sim is None:
            self.sim = Sim(self.sim_bin, os.path.join(self.root, "configs", "default.ini")).start()
        return self.sim

    def fresh(self):
        if self.sim is not None:
            self.sim.stop()
            self.sim = None

    def close(self):
        if self.sim is not None:
            self.sim.stop()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def device_text(self, text):
        dev = self.default_sim().device
        return text.replace("/tmp/modcp-$USER", dev).replace("/tmp/modcp-root", dev)

    def run(self, argv, where, want, timeout=30, stdin=None):
        p = subprocess.run(argv, capture_output=True, text=True, timeout=timeout, cwd=self.root,
                           input=stdin)
        out = p.stdout + p.stderr
        missing = [w for w in want if w not in out]
        self.t.ok(p.returncode == 0 and not missing,
                  "%s: %s -> rc %d%s" % (where, " ".join(argv)[:90], p.returncode,
                                          ", missing %s in: %s" % (missing, out[-300:]) if missing else ""))

    # -- one command --------------------------------------------------------------------
    def command(self, where, text, heredoc):
        cmd, want = split_comment(text)
        if heredoc is not None:
            argv = shlex.split(cmd.split("<<")[0])
            body = self.device_text("\n".join(heredoc) + "\n")
            self.run(argv, where, want, stdin=body)
            return
        if PLACEHOLDER.search(cmd):
            print("synopsis (not a command): %s: %s" % (where, cmd[:70]))
            return
        words = shlex.split(cmd)
        head = words[0]
        if head in NOT_RUN:
            print("not run here: %s: %s (%s)" % (where, cmd, NOT_RUN[head]))
            return
        if head == "tools/run":
            self.tools_run(where, words[1:])
        elif head == "tools/run-qemu":
            self.run_qemu(where, words[1:])
        elif head == "mbpoll":
            self.run([self.device_text(w) for w in words], where, want)
        elif head == "modcp-conf":
            argv = [self.conf_bin]
            out_next = False
            for w in words[1:]:
                argv.append(os.path.join(self.tmp, w) if out_next else w)
                out_next = w == "-o"
            self.run(argv, where, want)
        elif head == "cmake":
            self.run(words, where, want, timeout=300)
        elif head == "modcp-sim" or head.endswith("/tools/sim/modcp-sim"):
            self.sim_starts(where, words[1:])
        else:
            self.t.ok(False, "%s: no rule to run '%s' (teach test_docs.py or fix the doc)" % (where, cmd))

    def tools_run(self, where, args):
        link = os.path.join(self.tmp, "run-link")
        argv = [os.path.join(self.root, "tools", "run")] + args + ["--pty-link", link]
        p = subprocess.Popen(argv, cwd=self.root, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True, start_new_session=True)
        lines, master = [], None
        deadline = time.monotonic() + 120
        try:
            while time.monotonic() < deadline:
                line = p.stdout.readline()
                if not line:
                    break
                lines.append(line.rstrip("\n"))
                if "from another terminal" in line:
                    master = p.stdout.readline().strip()
                    lines.append(master)
                if line.strip() == "modcp-sim: ready":
                    break
            ok = master is not None and lines[-1] == "modcp-sim: ready"
            self.t.ok(ok, "%s: tools/run %s starts and prints a master command (%s)"
                      % (where, " ".join(args), " | ".join(lines[-4:])))
            if ok:
                self.t.ok(link in master, "%s: the banner's command names the real link %s" % (where, link))
                q = subprocess.run(master, shell=True, capture_output=True, text=True, timeout=30)
                out = q.stdout + q.stderr
                self.t.ok(q.returncode == 0 and "0x8765" in out and "0x4321" in out,
                          "%s: the banner's command reads 0x8765 0x4321 (rc %d: %s)"
                          % (where, q.returncode, out.strip()[-200:]))
        finally:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(timeout=20)

    def run_qemu(self, where, args):
        board = args[0] if args else "mps2-an385"
        elf = os.path.join(self.root, "build", board, "modcp-%s.elf" % board)
        if not (shutil.which("qemu-system-arm") and os.path.exists(elf)):
            print("not run here: %s: tools/run-qemu %s (no image %s; tools/build-arm makes it)"
                  % (where, board, elf))
            return
        p = subprocess.Popen([os.path.join(self.root, "tools", "run-qemu")] + args, cwd=self.root,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             start_new_session=True)
        seen = []
        try:
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline and not any(s.startswith("CONSOLE_TTY=") for s in seen):
                line = p.stdout.readline()
                if not line:
                    break
                seen.append(line.strip())
        finally:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(timeout=20)
        self.t.ok(any(s.startswith("MODBUS_TTY=/dev/") for s in seen)
                  and any(s.startswith("CONSOLE_TTY=/dev/") for s in seen),
                  "%s: tools/run-qemu %s prints both ptys" % (where, " ".join(args)))

    def sim_starts(self, where, args):
        # configs named relative to the source tree (a bus names several); the pty link is
        # the test's own (Sim makes one)
        rest, i = [], 1
        while i < len(args):
            if args[i] == "--pty-link" and i + 1 < len(args):
                i += 2
                continue
            a = args[i]
            rest.append(os.path.join(self.root, a) if a.endswith(".ini") and not os.path.isabs(a)
                        else a)
            i += 1
        args = [args[0]] + rest
        s = Sim(self.sim_bin, os.path.join(self.root, args[0]), extra=args[1:])
        try:
            s.start()
            self.t.ok(True, "%s: modcp-sim %s becomes ready" % (where, " ".join(args)))
        except Exception as e:  # noqa: BLE001 - reported as a failed check
            self.t.ok(False, "%s: modcp-sim %s: %s" % (where, " ".join(args), e))
        finally:
            s.stop()

    # -- the libmodbus example ---------------------------------------------------------------
    def c_example(self, where, lines):
        src = os.path.join(self.tmp, "example.c")
        with open(src, "w", encoding="utf-8") as f:
            f.write(self.device_text("\n".join(lines) + "\n"))
        exe = os.path.join(self.tmp, "example")
        flags = subprocess.run(["pkg-config", "--cflags", "--libs", "libmodbus"], capture_output=True,
                               text=True).stdout.split()
        c = subprocess.run(["cc", src, "-o", exe] + flags, capture_output=True, text=True)
        self.t.ok(c.returncode == 0, "%s: the libmodbus example compiles (%s)" % (where, c.stderr[-200:]))
        if c.returncode == 0:
            want = re.findall(r"0x[0-9A-F]{4}", " ".join(l for l in lines if "/*" in l))
            self.run([exe], where, want)

    # -- the console session of docs/simulator.md ---------------------------------------------
    def console(self, where, lines, table_answers):
        sim = self.default_sim()
        session_answers = set()
        i = 0
        while i < len(lines):
            line = lines[i]
            if not line.startswith("> "):
                i += 1
                continue
            cmd = line[2:].strip()
            want = []
            i += 1
            while i < len(lines) and not lines[i].startswith("> "):
                if lines[i].strip():
                    want.append(lines[i].strip())
                i += 1
            got = [g.strip() for g in sim.cmd(cmd) if g.strip()]
            self.t.ok(got == want, "%s: console `%s` answers %s (docs: %s)" % (where, cmd, got, want))
            session_answers.update(want)
        for ans in sorted(table_answers):
            self.t.ok(ans in session_answers,
                      "docs/simulator.md console table example `%s` is an answer of the session "
                      "(configs/default.ini)" % ans)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--build", required=True)
    a = ap.parse_args()
    d = Docs(os.path.abspath(a.root), os.path.abspath(a.build))
    files = [os.path.join(d.root, "README.md")] + sorted(
        os.path.join(d.root, "docs", f) for f in os.listdir(os.path.join(d.root, "docs")) if f.endswith(".md"))
    try:
        for path in files:
            rel = os.path.relpath(path, d.root)
            d.fresh()  # each document's commands run in order on a simulator of its own
            for start, lines in blocks(path, "sh"):
                for k, text, heredoc in commands(lines):
                    d.command("%s:%d" % (rel, start + k), text, heredoc)
            for start, lines in blocks(path, "c"):
                if rel == "README.md":
                    d.c_example("%s:%d" % (rel, start), lines)
        sim_md = os.path.join(d.root, "docs", "simulator.md")
        with open(sim_md, encoding="utf-8") as f:
            text = f.read()
        console_table = text[text.index("## Console"):text.index("## Trace")]
        table_answers = set(re.findall(r"`([A-Z][A-Z0-9]*\d[A-Z0-9.]* = [^`]+)`", console_table))
        d.fresh()
        for start, lines in blocks(sim_md, "console"):
            d.console("docs/simulator.md:%d" % start, lines, table_answers)
    finally:
        d.close()
    return d.t.done()


if __name__ == "__main__":
    sys.exit(main())
