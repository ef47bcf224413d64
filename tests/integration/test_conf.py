#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""modcp-conf and modcp-sim on good and bad INI files: exit codes, one line per
problem naming section, key, value, rule and event; the simulator refuses a bad file
with the same lines; the binary record's header, fields and CRC.

    test_conf.py --conf PATH/modcp-conf --sim PATH/modcp-sim --configs DIR
"""
import argparse
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simlib import Checks, crc16  # noqa: E402

BAD = """\
[serial]
baud = 9601
parity = mark
speed = 5

[protocol]
slave_address = 0
f_mul = 11
mode = weird

[coils]
m = 0-2047 @ 1000
q = 2000-2559 @ 256
t = 4096-4600 @ 100
i = 1-2 @ 3

[limits]
db = 900-800

[cpu]
work_db = 81
dbs = 80:64 800:1024

[memory]
MB9000 = 01
DB801.DBW0 = 1234

[nonsense]
a = 1
"""

# every problem is "FILE:LINE: section.key = value: rule"
EXPECTED = [
    "2: serial.baud = 9601: must be one of 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, "
    "57600, 76800, 115200 (event (0E)2EH)",
    "3: serial.parity = mark: must be none, odd or even (event (0E)2EH)",
    "4: serial.speed = 5: unknown key (keys: baud, data_bits, parity, stop_bits)",
    "7: protocol.slave_address = 0: must be 1..255 (event (0E)23H)",
    "8: protocol.f_mul = 11: must be 1..10; the CP runs with 1 (warning, event (0E)21H)",
    "9: protocol.mode = weird: must be normal or suppress (interference suppression) (event (0E)22H)",
    "13: coils.q = 2000-2559 @ 256: overlaps the window coils.m (event (0E)27H)",
    "14: coils.t = 4096-4600 @ 100: illegal from/to: a T/C window must span a multiple of 16 bits "
    "(it spans 505) (event (0E)25H)",
    "15: coils.i = 1-2 @ 3: unknown window (keys: m, q, t, c, dbN)",
    "18: limits.db = 900-800: must be MIN-MAX with MIN <= MAX (DB MIN >= 1), or off to disable "
    "writes (event (0E)24H)",
    "21: cpu.work_db = 81: DB81 is not in cpu.dbs (event (0E)3AH)",
    "25: memory.MB9000 = 01: outside M (m_bytes) of 256 bytes (event (0E)38H)",
    "26: memory.DB801.DBW0 = 1234: DB801 is not in cpu.dbs (event (0E)39H)",
    "29: nonsense.a = 1: unknown section",
]

BAUD_RULE = ("must be one of 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 57600, 76800, 115200 "
             "(event (0E)2EH)")
START_RULE = ("must be more than %d ms (2 x cycle_ms %d): the FB sends the record and INIT as 12 "
              "blocks, 4 per cycle, and sees the CP's answer at the earliest 3 cycles after "
              "CP_START; a shorter START_TIME always ends in CP_START_ERROR (ERROR_NR 2, "
              "ERROR_INFO (00)00H)")


def run(args):
    p = subprocess.run(args, capture_output=True, text=True, timeout=20)
    return p.returncode, p.stdout, p.stderr


def check_text(a, tmp, name, text, *sets):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    args = [a.conf, "check", path]
    for x in sets:
        args += ["--set", x]
    rc, out, err = run(args)
    return path, rc, out, err.splitlines()


def loses_nothing(t, a, tmp):
    """Issue 11 item 5: long lines are read whole, every duplicate is found, a START_TIME the
    FB cannot meet is refused, every problem is FILE:LINE: section.key = value: rule."""
    with open(os.path.join(a.configs, "default.ini")) as f:
        default = f.read()

    # a 300-character comment line: the key after it is read, line numbers stay right
    text = "[serial]\n; " + "x" * 300 + "\nbaud = 9601\n\n[protocol]\nslave_address = 0\n"
    p, rc, out, lines = check_text(a, tmp, "longcomment.ini", text)
    t.ok(rc == 2 and lines == ["%s:3: serial.baud = 9601: %s" % (p, BAUD_RULE),
                               "%s:6: protocol.slave_address = 0: must be 1..255 (event (0E)23H)" % p],
         "long comment line: the next key is read, lines 3 and 6 named (%r)" % lines)

    # long value lines, read whole: 40 DBs (the work DB last, at character 390), 16 scanner
    # entries (> 200 characters)
    dbs = " ".join("%d:256" % n for n in range(100, 150)) + " 80:64"
    entries = " ".join("DB%d.DBW%d" % (100 + i, 100 + 2 * i) for i in range(16))
    text = default.replace("dbs = 80:64 ", "dbs = %s " % dbs).replace(
        "[supervision]", "[scanner]\nstart = 4096\nentries = %s\n\n[supervision]" % entries, 1)
    if "[scanner]" not in text:
        text += "\n[scanner]\nstart = 4096\nentries = %s\n" % entries
    p, rc, out, lines = check_text(a, tmp, "longvalue.ini", text)
    t.ok(len(dbs) > 300 and len(entries) > 200 and rc == 0 and lines == [],
         "long value lines (%d, %d characters) read whole: exit 0 (%r)" % (len(dbs), len(entries), lines))
    bad_last = entries.rsplit(" ", 1)[0] + " XW1"
    p, rc, out, lines = check_text(a, tmp, "longvalue2.ini", text.replace(entries, bad_last))
    line = text[:text.index("entries = ")].count("\n") + 1
    t.ok(rc == 2 and lines == ["%s:%d: scanner.entries = %s...: entry 16 'XW1' must be a word operand "
                               "(MWn, IWn, QWn, DBn.DBWm, Tn, Cn) (event (0E)2EH)"
                               % (p, line, bad_last[:156])],
         "long value line: its 16th entry (after character 200) is read and checked (%r)" % lines)

    # a long value with a bad element at its end: named, the value shown cut at 156 + "..."
    vals = " ".join(["01"] * 80) + " zz"
    text = "[cpu]\nm_bytes = 256\n\n[memory]\nMB0 = %s\n" % vals
    p, rc, out, lines = check_text(a, tmp, "longbad.ini", text)
    t.ok(rc == 2 and lines == ["%s:5: memory.MB0 = %s...: bad value 'zz' (hex byte, e.g. 17)"
                               % (p, vals[:156])],
         "long value with a bad last element: refused, line 5 (%r)" % lines)

    # more than 256 keys: a duplicate after the 256th is still found
    mem = "".join("MB%d = 01\n" % i for i in range(250))
    text = default.replace("[memory]\n", "[memory]\n" + mem, 1)
    text = text.replace("MB1008 = 01 17 02 18\n", "")
    head = text[:text.index("[memory]\n")].count("\n") + 1  # line of [memory]
    text += "\n[memory]\nmb10 = 02\n"
    nlines = text.count("\n")
    nkeys = sum(1 for l in text.splitlines() if "=" in l and not l.lstrip().startswith(";"))
    p, rc, out, lines = check_text(a, tmp, "dup.ini", text)
    t.ok(nkeys > 256 and rc == 2 and lines == ["%s:%d: memory.mb10 = 02: key given twice (first on "
                                               "line %d)" % (p, nlines, head + 11)],
         "duplicate key after %d keys: refused, both lines named (%r)" % (nkeys, lines))

    # START_TIME the FB's initialisation cannot meet (3 cycles: 12 blocks through 4 slots)
    p, rc, out, lines = check_text(a, tmp, "start.ini", default, "cpu.start_time_ms=20")
    t.ok(rc == 2 and lines == ["--set:1: cpu.start_time_ms = 20: " + START_RULE % (20, 10)],
         "start_time_ms = 20 with cycle_ms = 10: refused with the rule (%r)" % lines)
    p, rc, out, lines = check_text(a, tmp, "start.ini", default, "cpu.start_time_ms=21")
    t.ok(rc == 0 and lines == [], "start_time_ms = 21 with cycle_ms = 10: accepted (%r)" % lines)
    text = default.replace("start_time_ms = 5000", "start_time_ms = 100").replace(
        "cycle_ms = 10", "cycle_ms = 50")
    line = text[:text.index("start_time_ms = 100")].count("\n") + 1
    p, rc, out, lines = check_text(a, tmp, "start50.ini", text)
    t.ok(rc == 2 and lines == ["%s:%d: cpu.start_time_ms = 100: " % (p, line) + START_RULE % (100, 50)],
         "start_time_ms = 100 with cycle_ms = 50: refused at its line (%r)" % lines)

    # overrides are named by their position; a key before any section; text after [section]
    p, rc, out, lines = check_text(a, tmp, "ov.ini", "baud = 9600\n[serial] parity = odd\n",
                                   "serial.baud=7", "nodot=1")
    t.ok(rc == 2 and lines == [
        "--set:2: nodot=1: expected section.key=value (at most 32)",
        "%s:1: baud = 9600: key before the first [section]" % p,
        "%s:2: syntax error: text after [section]: '[serial] parity = odd'" % p,
        "--set:1: serial.baud = 7: " + BAUD_RULE],
        "overrides, key before [section], text after [section] (%r)" % lines)


def record_of(a, tmp, text, *sets):
    """modcp-conf build of text: (exit code, stderr lines, record bytes)."""
    path = os.path.join(tmp, "rec.ini")
    with open(path, "w") as f:
        f.write(text)
    binf = os.path.join(tmp, "rec.bin")
    if os.path.exists(binf):
        os.remove(binf)
    args = [a.conf, "build", path, "-o", binf]
    for x in sets:
        args += ["--set", x]
    rc, out, err = run(args)
    rec = open(binf, "rb").read() if rc == 0 and os.path.exists(binf) else b""
    return rc, err.splitlines(), rec, path


OPMODE_AT = 8 + 9  # header, then baud u32, data bits, parity, stop bits, slave, framing, opmode


def rs485_mode_select(t, a, tmp):
    """Issue 13 item 4, [RTU-2009] Table 5-2: two-wire RS485 runs in modem (interference
    suppression) mode unless rs485_mode_select = on allows mode = normal."""
    with open(os.path.join(a.configs, "default.ini")) as f:
        default = f.read()
    text = default.replace("mode = normal\n", "")
    rc, lines, rec, p = record_of(a, tmp, text, "interface.type=rs485")
    t.ok(rc == 0 and lines == [] and len(rec) > OPMODE_AT and rec[OPMODE_AT] == 1,
         "[RTU-2009] Table 5-2: rs485 without mode: default modem (suppress) (%r)" % lines)
    rc, lines, rec, p = record_of(a, tmp, text, "interface.type=rs422")
    t.ok(rc == 0 and lines == [] and len(rec) > OPMODE_AT and rec[OPMODE_AT] == 0,
         "[RTU-2009] Table 5-2: rs422 4-wire without mode: default normal (%r)" % lines)
    line = default[:default.index("mode = normal")].count("\n") + 1
    rc, lines, rec, p = record_of(a, tmp, default, "interface.type=rs485")
    t.ok(rc == 2 and lines == ["%s:%d: protocol.mode = normal: normal is not allowed with "
                               "interface.type = rs485 (two-wire runs in interference suppression = "
                               "modem mode) unless protocol.rs485_mode_select = on ([RTU-2009] Table 5-2) "
                               "(event (0E)22H)" % (p, line)],
         "[RTU-2009] Table 5-2: rs485 with mode = normal: refused, (0E)22H, rule named (%r)" % lines)
    rc, lines, rec, p = record_of(a, tmp, default, "interface.type=rs485",
                                  "protocol.rs485_mode_select=on")
    t.ok(rc == 0 and lines == [] and len(rec) > OPMODE_AT and rec[OPMODE_AT] == 0,
         "[RTU-2009] Table 5-2: rs485 with mode = normal and rs485_mode_select = on: accepted (%r)" % lines)
    rc, lines, rec, p = record_of(a, tmp, default, "interface.type=rs485", "protocol.mode=modem")
    t.ok(rc == 0 and lines == [] and len(rec) > OPMODE_AT and rec[OPMODE_AT] == 1,
         "[RTU-2009] Table 5-2: mode = modem is interference suppression (%r)" % lines)


STOP_AT = 8 + 6  # header, baud u32, data bits, parity, stop bits


def ascii_frame(t, a, tmp):
    """Issue 13 item 5, [ASCII-32] §3.1: "with even or odd parity 1 stop bit is pre-defined; none
    parity effects two stop bits" -- the ASCII frame is 7E1, 7O1 or 7N2."""
    with open(os.path.join(a.configs, "ascii.ini")) as f:
        text = f.read()
    line = text[:text.index("stop_bits = 1")].count("\n") + 1
    for par, stop, ok in (("even", 1, True), ("odd", 1, True), ("none", 2, True),
                          ("none", 1, False), ("even", 2, False), ("odd", 2, False)):
        frame = "7%s%d" % (par[0].upper(), stop)
        rc, lines, rec, p = record_of(a, tmp, text, "serial.parity=" + par,
                                      "serial.stop_bits=%d" % stop)
        if ok:
            t.ok(rc == 0 and lines == [] and len(rec) > STOP_AT and rec[STOP_AT] == stop,
                 "[ASCII-32] §3.1: ASCII %s accepted (%r)" % (frame, lines))
        else:
            want = ("--set:2: serial.stop_bits = %d: the ASCII character frame %s is not allowed: "
                    "with parity even or odd 1 stop bit, with parity none 2 ([ASCII-32] §3.1: 7E1, 7O1 or "
                    "7N2); stop_bits = %d (event (0E)2EH)" % (stop, frame, 2 if par == "none" else 1))
            t.ok(rc == 2 and lines == [want], "[ASCII-32] §3.1: ASCII %s refused, rule named (%r)" % (frame, lines))
    # without a stop_bits key the stop bits follow the parity
    rc, lines, rec, p = record_of(a, tmp, text.replace("stop_bits = 1\n", ""), "serial.parity=none")
    t.ok(rc == 0 and lines == [] and len(rec) > STOP_AT and rec[STOP_AT] == 2,
         "[ASCII-32] §3.1: ASCII parity none without stop_bits: 2 stop bits (%r)" % lines)
    rc, lines, rec, p = record_of(a, tmp, text.replace("stop_bits = 1\n", ""), "serial.parity=odd")
    t.ok(rc == 0 and lines == [] and len(rec) > STOP_AT and rec[STOP_AT] == 1,
         "[ASCII-32] §3.1: ASCII parity odd without stop_bits: 1 stop bit (%r)" % lines)
    # in the file: the line of stop_bits is named
    rc, lines, rec, p = record_of(a, tmp, text.replace("parity = even", "parity = none"))
    t.ok(rc == 2 and len(lines) == 1 and lines[0].startswith("%s:%d: serial.stop_bits = 1: the ASCII "
                                                            "character frame 7N1" % (p, line)),
         "[ASCII-32] §3.1: 7N1 in the file: its stop_bits line named (%r)" % lines)
    # RTU keeps 1 or 2 stop bits with any parity ([RTU-2003] §2.1)
    with open(os.path.join(a.configs, "default.ini")) as f:
        rtu = f.read()
    rc, lines, rec, p = record_of(a, tmp, rtu, "serial.parity=none", "serial.stop_bits=1")
    t.ok(rc == 0 and lines == [], "[RTU-2003] §2.1: RTU 8N1 accepted (%r)" % lines)


def quantity_limits(t, a, tmp):
    """Issue 13 item 7: [protocol] quantity_limits = manual | spec, in the record."""
    with open(os.path.join(a.configs, "default.ini")) as f:
        default = f.read()
    rc1, l1, manual, p = record_of(a, tmp, default)
    rc2, l2, spec, p = record_of(a, tmp, default, "protocol.quantity_limits=spec")
    diff = [i for i in range(min(len(manual), len(spec)) - 2) if manual[i] != spec[i]]
    t.ok(rc1 == 0 and rc2 == 0 and len(manual) == len(spec) and len(diff) == 1 and
         manual[diff[0]] == 0 and spec[diff[0]] == 1,
         "quantity_limits: manual (default) 0, spec 1, one byte of the record (%r)" % diff)
    rc, lines, rec, p = record_of(a, tmp, default, "protocol.quantity_limits=libmodbus")
    t.ok(rc == 2 and lines == ["--set:1: protocol.quantity_limits = libmodbus: must be manual or "
                               "spec (event (0E)2EH)"],
         "quantity_limits = libmodbus: refused (%r)" % lines)
    path = os.path.join(a.configs, "spec-limits.ini")
    rc, out, err = run([a.conf, "check", path])
    t.ok(rc == 0 and out.strip() == "%s: ok: slave 17, 9600 8E1 RTU, record %d bytes" % (path, len(spec))
         and err == "", "check spec-limits.ini: exit 0, no problems (%r %r)" % (out.strip(), err))


def db_in_32bit_mode(t, a, tmp):
    """Issue 27 item 4: [limits] db_in_32bit_mode = off (default, [ASCII-32] §3.7) | on, one byte
    of the record; configs/regs32.ini says off."""
    with open(os.path.join(a.configs, "regs32.ini")) as f:
        text = f.read()
    rc1, l1, off, p = record_of(a, tmp, text)
    rc2, l2, on, p = record_of(a, tmp, text, "limits.db_in_32bit_mode=on")
    rc3, l3, dflt, p = record_of(a, tmp, text.replace("db_in_32bit_mode = off\n", ""))
    diff = [i for i in range(min(len(off), len(on)) - 2) if off[i] != on[i]]
    t.ok(rc1 == 0 and rc2 == 0 and rc3 == 0 and len(off) == len(on) and len(diff) == 1 and
         off[diff[0]] == 0 and on[diff[0]] == 1 and dflt == off,
         "db_in_32bit_mode: off (default) 0, on 1, one byte of the record (%r)" % diff)
    rc, lines, rec, p = record_of(a, tmp, text, "limits.db_in_32bit_mode=maybe")
    t.ok(rc == 2 and lines == ["--set:1: limits.db_in_32bit_mode = maybe: must be on or off "
                               "(event (0E)2EH)"],
         "db_in_32bit_mode = maybe: refused (%r)" % lines)


def doc_tables(path):
    """The "| key | meaning | values | default | source | event |" table of each
    "## [section]" of docs/parameters.md, as modcp-conf doc-table prints them."""
    out, sec, lines = [], None, open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"## \[([a-z]+)\]", lines[i])
        if m:
            sec = m.group(1)
        if lines[i] == "| key | meaning | values | default | source | event |" and sec:
            j = i
            while j < len(lines) and lines[j].startswith("|"):
                j += 1
            out.append("[%s]\n%s\n" % (sec, "\n".join(lines[i:j])))
            sec, i = None, j
            continue
        i += 1
    return "\n".join(out)


def doc_table_matches(t, a):
    """Issue 12 item 3: the parameter tables of docs/parameters.md are the descriptor's."""
    docs = os.path.join(a.configs, os.pardir, "docs", "parameters.md")
    rc, out, err = run([a.conf, "doc-table"])
    want = doc_tables(docs)
    t.ok(rc == 0 and out.count("[") >= 10 and out.strip() == want.strip(),
         "docs/parameters.md tables == modcp-conf doc-table (the parameter rows)%s" % (
             "" if out.strip() == want.strip() else ":\n" + "\n".join(
                 "  docs: %s\n  rows: %s" % (x, y) for x, y in zip(want.strip().split("\n"),
                                                            out.strip().split("\n")) if x != y)))


EVENT_BEGIN = "<!-- generated by `modcp-conf event-table`"
EVENT_END = "<!-- end of the generated event tables -->"


def event_table_matches(t, a):
    """Issue 27 item 9: the event tables of docs/diagnostics.md are the event rows'
    (modcp-conf event-table), between the page's two markers."""
    docs = os.path.join(a.configs, os.pardir, "docs", "diagnostics.md")
    text = open(docs, encoding="utf-8").read()
    i, j = text.find(EVENT_BEGIN), text.find(EVENT_END)
    want = text[text.index("\n", i) + 1:j].strip() if 0 <= i < j else ""
    rc, out, err = run([a.conf, "event-table"])
    got = out.strip()
    t.ok(rc == 0 and err == "" and got.count("### Class ") >= 4 and got == want,
         "docs/diagnostics.md event tables == modcp-conf event-table (the event rows)%s" % (
             "" if got == want else ":\n" + "\n".join(
                 "  docs: %s\n  rows: %s" % (x, y) for x, y in zip(want.split("\n"),
                                                            got.split("\n")) if x != y)))



def r32_messages(t, a, tmp):
    """Issue 25 §2.2: the message names the rule validation decided (the issue's rule and the
    range it collides with), the tool does not test again: an int16 range too large for one
    DB is reported on its own and left out of the overlap checks, so the float range that
    overlaps both int16 and int32 is reported against int32, the range the core names."""
    text = ("[registers]\nwith_32bit_registers = on\nint16 = 0-40000 @ 2\n"
            "int32 = 1000-1999 @ 3\nfloat = 1500-2500 @ 4\n")
    p, rc, out, lines = check_text(a, tmp, "r32.ini", text)
    t.ok(rc == 2 and lines == [
        "%s:3: registers.int16 = 0-40000 @ 2: the range needs more than one DB (80002 bytes > "
        "65536) (event (0E)2EH)" % p,
        "%s:5: registers.float = 1500-2500 @ 4: overlaps the range registers.int32 "
        "(event (0E)2EH)" % p],
         "32-bit ranges: extent, then the overlap with the range validation names (%r)" % lines)
    p, rc, out, lines = check_text(a, tmp, "r32db.ini", text.replace("1500-2500 @ 4", "3000-3999 @ 3"))
    t.ok(rc == 2 and lines[1:] == [
        "%s:5: registers.float = 3000-3999 @ 3: uses the same DB as registers.int32 "
        "(event (0E)2EH)" % p],
         "32-bit ranges: the same DB as int32 (%r)" % lines)

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--conf", required=True)
    ap.add_argument("--sim", required=True)
    ap.add_argument("--configs", required=True)
    a = ap.parse_args()
    t = Checks()
    tmp = tempfile.mkdtemp(prefix="modcp-conf-")
    for name in ("default.ini", "manual-4.6.4.ini"):
        path = os.path.join(a.configs, name)
        rc, out, err = run([a.conf, "check", path])
        t.ok(rc == 0 and re.fullmatch(r"%s: ok: slave 5, 9600 8E1 RTU, record \d+ bytes" % re.escape(path),
                                      out.strip()) is not None and err == "",
             "check %s: exit 0, no problems (%r %r)" % (name, out.strip(), err))

    bad = os.path.join(tmp, "bad.ini")
    with open(bad, "w") as f:
        f.write(BAD)
    rc, out, err = run([a.conf, "check", bad])
    lines = err.splitlines()
    t.ok(rc == 2, "check bad.ini: exit code 2 (got %d)" % rc)
    for e in EXPECTED:
        want = "%s:%s" % (bad, e)
        t.ok(any(l == want or (e.endswith("unknown section") and l.startswith(want)) for l in lines),
             "check bad.ini: %s" % e)
    t.ok(all(re.match(r"%s:\d+: [a-z]+\.\S+ = " % re.escape(bad), l) for l in lines),
         "check bad.ini: every line is FILE:LINE: section.key = value")

    # the simulator refuses the same file with the same lines
    link = os.path.join(tmp, "tty")
    rc, out, serr = run([a.sim, bad, "--pty-link", link])
    t.ok(rc == 2, "modcp-sim bad.ini: exit code 2 (got %d)" % rc)
    t.ok(all(l in serr.splitlines() for l in lines), "modcp-sim bad.ini: the same problem lines")
    t.ok("not started" in serr and not os.path.lexists(link), "modcp-sim bad.ini: not started, no pty")

    # a warning alone does not fail
    warn = os.path.join(tmp, "warn.ini")
    with open(os.path.join(a.configs, "default.ini")) as f:
        text = f.read().replace("f_mul = 1\n", "f_mul = 0\n")
    with open(warn, "w") as f:
        f.write(text)
    rc, out, err = run([a.conf, "check", warn])
    line = text[:text.index("f_mul = 0")].count("\n") + 1
    t.ok(rc == 0 and err.strip() == "%s:%d: protocol.f_mul = 0: must be 1..10; the CP runs with 1 "
         "(warning, event (0E)21H)" % (warn, line), "check f_mul = 0: warning, exit 0 (%r)" % err.strip())

    # syntax error with its line number
    syn = os.path.join(tmp, "syntax.ini")
    with open(syn, "w") as f:
        f.write("[serial]\nbaud = 9600\nthis line is wrong\n")
    rc, out, err = run([a.conf, "check", syn])
    t.ok(rc == 2 and err == "%s:3: syntax error: expected [section] or key = value: "
         "'this line is wrong'\n" % syn, "syntax error: line 3 named (%r)" % err)

    loses_nothing(t, a, tmp)
    rs485_mode_select(t, a, tmp)
    ascii_frame(t, a, tmp)
    quantity_limits(t, a, tmp)
    db_in_32bit_mode(t, a, tmp)
    r32_messages(t, a, tmp)

    # binary record
    binf = os.path.join(tmp, "default.bin")
    rc, out, err = run([a.conf, "build", os.path.join(a.configs, "default.ini"), "-o", binf])
    rec = open(binf, "rb").read() if rc == 0 else b""
    t.ok(rc == 0 and len(rec) >= 10, "build: record of %d bytes" % len(rec))
    if len(rec) >= 10:
        magic, version, plen = struct.unpack_from("<4sHH", rec, 0)
        t.ok(magic == b"MCPR" and version == 4 and plen == len(rec) - 10,
             "build: header MCPR v4, payload %d bytes" % plen)
        t.ok(crc16(rec[:-2]) == rec[-2:], "build: CRC-16 over the record")
        baud, db, par, sb, slave = struct.unpack_from("<IBBBB", rec, 8)
        t.ok((baud, db, par, sb, slave) == (9600, 8, 2, 1, 5), "build: 9600 8E1 slave 5")

    # C source
    cfile = os.path.join(tmp, "cfg.c")
    rc, out, err = run([a.conf, "c", os.path.join(a.configs, "default.ini"), "-o", cfile])
    src = open(cfile).read() if rc == 0 else ""
    t.ok(rc == 0 and all(s in src for s in ("modcp_cfg_record[%d]" % len(rec),
                                              "modcp_cfg_record_len = %d" % len(rec),
                                              "modcp_plcmem_t modcp_cfg_mem", "modcp_cfg_work_db = 80",
                                              "modcp_cfg_cycle_ms = 10", "[1008] = 0x01")),
         "c: generated source defines the cfg_gen.h symbols")
    rc, out, err = run([a.conf, "build", bad, "-o", os.path.join(tmp, "bad.bin")])
    t.ok(rc == 2 and not os.path.exists(os.path.join(tmp, "bad.bin")), "build bad.ini: exit 2, no file")
    rc, out, err = run([a.conf, "fields"])
    t.ok(rc == 0, "schema: every modcp_param_field_t has an INI key (%s)" % out.strip())
    doc_table_matches(t, a)
    event_table_matches(t, a)
    rc, out, err = run([a.conf, "frobnicate"])
    t.ok(rc == 1 and "usage" in err, "usage error: exit 1")
    shutil.rmtree(tmp, ignore_errors=True)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
