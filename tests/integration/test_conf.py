#!/usr/bin/python3
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

EXPECTED = [
    "[serial] baud = 9601: must be one of 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, "
    "57600, 76800, 115200 (event (0E)2EH)",
    "[serial] parity = mark: must be none, odd or even (event (0E)2EH)",
    "[serial] speed = 5: unknown key (keys: baud, data_bits, parity, stop_bits)",
    "[protocol] slave_address = 0: must be 1..255 (event (0E)23H)",
    "[protocol] f_mul = 11: must be 1..10; the CP runs with 1 (warning, event (0E)21H)",
    "[protocol] mode = weird: must be normal or suppress (interference suppression) (event (0E)22H)",
    "[coils] q = 2000-2559 @ 256: overlaps the window [coils] m (event (0E)27H)",
    "[coils] t = 4096-4600 @ 100: illegal from/to: a T/C window must span a multiple of 16 bits "
    "(it spans 505) (event (0E)25H)",
    "[coils] i = 1-2 @ 3: unknown window (keys: m, q, t, c, dbN)",
    "[limits] db = 900-800: must be MIN-MAX with MIN <= MAX (DB MIN >= 1), or off to disable "
    "writes (event (0E)24H)",
    "[cpu] work_db = 81: DB81 is not in [cpu] dbs (event (0E)3AH)",
    "[memory] MB9000 = 01: outside M (m_bytes) of 256 bytes (event (0E)38H)",
    "[memory] DB801.DBW0 = 1234: DB801 is not in [cpu] dbs (event (0E)39H)",
    "[nonsense] a = 1: unknown section",
]


def run(args):
    p = subprocess.run(args, capture_output=True, text=True, timeout=20)
    return p.returncode, p.stdout, p.stderr


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
        want = "%s: %s" % (bad, e)
        t.ok(any(l == want or (e.endswith("unknown section") and l.startswith(want)) for l in lines),
             "check bad.ini: %s" % e)
    t.ok(all(l.startswith(bad + ": ") for l in lines), "check bad.ini: every line names the file")

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
    t.ok(rc == 0 and err.strip() == "%s: [protocol] f_mul = 0: must be 1..10; the CP runs with 1 "
         "(warning, event (0E)21H)" % warn, "check f_mul = 0: warning, exit 0 (%r)" % err.strip())

    # syntax error with its line number
    syn = os.path.join(tmp, "syntax.ini")
    with open(syn, "w") as f:
        f.write("[serial]\nbaud = 9600\nthis line is wrong\n")
    rc, out, err = run([a.conf, "check", syn])
    t.ok(rc == 2 and "%s: line 3: syntax error" % syn in err, "syntax error: line 3 named (%r)" % err)

    # binary record
    binf = os.path.join(tmp, "default.bin")
    rc, out, err = run([a.conf, "build", os.path.join(a.configs, "default.ini"), "-o", binf])
    rec = open(binf, "rb").read() if rc == 0 else b""
    t.ok(rc == 0 and len(rec) >= 10, "build: record of %d bytes" % len(rec))
    if len(rec) >= 10:
        magic, version, plen = struct.unpack_from("<4sHH", rec, 0)
        t.ok(magic == b"MCPR" and version == 1 and plen == len(rec) - 10,
             "build: header MCPR v1, payload %d bytes" % plen)
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
    rc, out, err = run([a.conf, "frobnicate"])
    t.ok(rc == 1 and "usage" in err, "usage error: exit 1")
    shutil.rmtree(tmp, ignore_errors=True)
    return t.done()


if __name__ == "__main__":
    sys.exit(main())
