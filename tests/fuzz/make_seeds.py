#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Hand-written seed inputs for the line targets (fuzz_rtu, fuzz_ascii), in the harness
encoding of fuzz_line.c: the first HEADER bytes build the parameter set (fuzz_cfg.c;
PRESETS below are the five sets the targets once had fixed), then 0xFE = the frame's
CRC / LRC, 0xF0 = end of frame, 0xFC = one FB cycle, 0xFD escapes a literal byte >= 0xF0.
    tests/fuzz/make_seeds.py build/fuzz/corpus/fuzz_rtu build/fuzz/corpus/fuzz_ascii
then `tools/fuzz --merge rtu ascii` keeps those that reach new coverage (with what the
fuzzer found) in tests/fuzz/corpus/.
    tests/fuzz/make_seeds.py --convert DIR...
rewrites inputs of the old encoding (byte 0 = parameter set 0..4, modulo 5) in place into
the new one (that set's header, then the rest), each named by its SHA-1 as libFuzzer
names them."""
import hashlib
import os
import sys

HEADER = 48  # FUZZ_CFG_BYTES (fuzz_cfg.h)


def preset(n):
    """The header that builds the old fixed parameter set n (fuzz_cfg.c's layout)."""
    h = [0] * HEADER
    if n == 1:  # 32-bit registers, diagnostic interrupts, comm loss 100 ms, 5 scanner entries
        h[3], h[4], h[5] = 0xC0, 0x08, 5
    elif n == 2:  # 19200, Modbus end of frame, t1.5, modem mode, RS485 turnaround 2 ms,
        # CP 441, DB-bit windows coils[4] -> DB 800 and inputs[2] -> DB 900 (8192..8991)
        h[0], h[1], h[2], h[3] = 0x07, 0x70, 0x12, 0x04
        h[27:30] = [0x26, 0xB1, 0]
        h[39:42] = [0x27, 0xB1, 0]
    elif n == 3:  # CP 341 function set, 2400 8N2, f_MUL 3
        h[0], h[1], h[3] = 0x54, 3, 0x01
    elif n == 4:  # 38400, RS232 automatic signals with RTS delays of 1 ms
        h[0], h[2] = 0x08, 0x44
    return h


def header(baud=0, parity=0, stop2=0, data8=0, fmul=0, eof_modbus=0, t15=0, modem=0,
           rs485_sel=0, iface=0, rs232_auto=0, turnaround=0, rts=0, cp341=0, qty_spec=0,
           cp441=0, job_limit=0, regs32=0, diag_irq=0, cpu_timeout=0, commloss=0,
           ascii_timeout=0, scan_count=0, scan_start=0, scan_rot=0, lim_m=0, lim_q=0,
           lim_db=0, hr_base=0, ir_base=0, r32=(0, 0, 0), coils=None, inputs=None, mem=0,
           ids=0, other_framing=0, restart_every=0):
    """A header from field values (indexes into fuzz_cfg.c's tables; 0 keeps the base)."""
    h = [0] * HEADER
    h[0] = baud | parity << 4 | stop2 << 6 | data8 << 7
    h[1] = fmul | eof_modbus << 4 | t15 << 5 | modem << 6 | rs485_sel << 7
    h[2] = iface | rs232_auto << 2 | turnaround << 3 | rts << 6
    h[3] = cp341 | qty_spec << 1 | cp441 << 2 | job_limit << 3 | regs32 << 6 | diag_irq << 7
    h[4] = cpu_timeout | commloss << 3 | ascii_timeout << 6
    h[5] = scan_count | scan_start << 5
    h[6] = scan_rot
    h[7], h[8], h[9], h[10], h[11] = lim_m, lim_q, lim_db, hr_base, ir_base
    h[12:15] = list(r32)
    for k, w in (coils or {}).items():
        h[15 + 3 * k:18 + 3 * k] = list(w)
    for k, w in (inputs or {}).items():
        h[33 + 3 * k:36 + 3 * k] = list(w)
    h[45], h[46], h[47] = mem, ids, other_framing | restart_every << 1
    return h


# Parameter sets besides the five old ones, one per kind of configuration users run: each
# is a seed of its own for every request of pdus() (tools/fuzz --merge keeps the inputs
# that reach new coverage).
VARIANTS = [
    header(other_framing=1),
    header(baud=7, eof_modbus=1, t15=1, iface=2, rs485_sel=1, turnaround=4),  # RS485 normal
    header(baud=2, fmul=10, iface=2, modem=1, turnaround=1),  # 600 baud, modem mode
    header(baud=11, eof_modbus=1, t15=1, parity=1, stop2=1),  # 115200 8N2
    header(rs232_auto=1, rts=3),  # RS232 signals, 20 ms delays
    header(rs232_auto=1),  # RS232 signals, no waiting time: CTS always ON
    header(job_limit=1),  # 32-byte jobs: every request split
    header(cp441=1, job_limit=6, qty_spec=1),
    header(cp341=1, parity=2),
    header(regs32=1, r32=(0x21, 0x42, 0x63), hr_base=3, ir_base=2),
    header(scan_count=16, scan_rot=5, scan_start=5, commloss=1, cpu_timeout=1),
    header(scan_count=12, scan_rot=11, diag_irq=1, commloss=3),
    header(lim_m=0xFF, lim_q=0x30, lim_db=0x31, hr_base=4),  # M off, Q 0..79, DB 80..900
    header(mem=0x1F, hr_base=1, ir_base=4),  # DBs missing / short, no work DB, M 100 bytes
    header(mem=0x20, ids=0xFF, lim_db=0x3A),  # ID strings of 16 characters
    header(ids=0x55),  # empty ID strings
    header(restart_every=2, cpu_timeout=1),
    header(coils={4: (0x26, 0x8F, 3), 5: (0x2F, 0x07, 1)}, inputs={2: (0x37, 0x10, 2), 3: (0x0B, 0x3F, 1)}),
    header(coils={0: (0x04, 0x81, 2), 1: (0x05, 0x8F, 9)}, inputs={0: (0x02, 0x7F, 30)}),
    header(other_framing=1, data8=1, parity=1, stop2=1, ascii_timeout=3, baud=9),
]


def convert(dirs):
    n = 0
    for d in dirs:
        for name in sorted(os.listdir(d)):
            path = os.path.join(d, name)
            old = open(path, "rb").read()
            if not old:
                continue
            new = bytes(preset(old[0] % 5)) + old[1:]
            os.remove(path)
            with open(os.path.join(d, hashlib.sha1(new).hexdigest()), "wb") as f:
                f.write(new)
            n += 1
    print("%d inputs converted" % n)

A = 5  # the harness's slave address


def w(v):
    return [(v >> 8) & 0xFF, v & 0xFF]


def pdus():
    out = []
    for addr, n in [(0, 16), (1000, 1), (2040, 16), (2048, 64), (4096, 32), (4608, 8), (8192, 40), (6000, 8)]:
        out.append([1] + w(addr) + w(n))
    for addr, n in [(0, 16), (4096, 64), (4090, 20), (8192, 16)]:
        out.append([2] + w(addr) + w(n))
    for fc in (3, 4):
        for reg, n in [(0, 4), (510, 4), (512, 2), (3000, 4), (5000, 4), (7000, 4), (40000, 5), (51200, 8), (0, 125), (0, 0)]:
            out.append([fc] + w(reg) + w(n))
    for addr, v in [(1000, 0xFF00), (8000, 0x0000), (2100, 0xFF00), (4100, 0xFF00), (8200, 0xFF00), (1, 0x1234)]:
        out.append([5] + w(addr) + w(v))
    for reg, v in [(51200, 0x1234), (0, 1), (3001, 7), (5002, 0xFFFF), (7000, 0x4120), (40000, 3), (40004, 9)]:
        out.append([6] + w(reg) + w(v))
    for addr, n in [(8000, 10), (2048, 16), (8192, 9)]:
        nb = (n + 7) // 8
        out.append([15] + w(addr) + w(n) + [nb] + [0xA5] * nb)
    for reg, n in [(51200, 3), (3000, 2), (5000, 2), (7000, 2), (40000, 2), (0, 1)]:
        out.append([16] + w(reg) + w(n) + [2 * n] + [0x12, 0x34] * n)
    for sub in list(range(0, 5)) + list(range(10, 19)) + [20, 21]:
        data = 0xFF00 if sub == 1 else (0x0D00 if sub == 3 else 0)
        out.append([8] + w(sub) + w(data))
    out += [[11], [12], [17]]
    out.append([22] + w(51200) + w(0xF0F0) + w(0x0F0F))
    out.append([22] + w(0) + w(0x00FF) + w(0x1200))
    out.append([23] + w(51200) + w(2) + w(51210) + w(2) + [4, 1, 2, 3, 4])
    out.append([23] + w(3000) + w(2) + w(3000) + w(1) + [2, 0xAB, 0xCD])
    for code, obj in [(1, 0), (2, 0), (3, 0), (4, 0), (4, 1), (4, 2), (4, 3), (4, 0x80), (1, 5)]:
        out.append([0x2B, 0x0E, code, obj])
    out += [[0x2B, 0x0D], [0x07], [0x99], [0x41, 1, 2]]
    return out


def esc(bs):
    r = []
    for b in bs:
        if b >= 0xF0:
            r.append(0xFD)
        r.append(b)
    return r


def hexs(bs):
    return [ord(c) for c in "".join("%02X" % b for b in bs)]


def main():
    if sys.argv[1] == "--convert":
        convert(sys.argv[2:])
        return
    rtu_dir, ascii_dir = sys.argv[1], sys.argv[2]
    os.makedirs(rtu_dir, exist_ok=True)
    os.makedirs(ascii_dir, exist_ok=True)
    n = 0
    for cfg, head in enumerate([preset(k) for k in range(5)] + VARIANTS):
        for k, pdu in enumerate(pdus()):
            for addr in ([A, 0] if pdu[0] in (5, 6, 15, 16) and k % 3 == 0 else [A]):
                frame = [addr] + pdu
                rtu = head + esc(frame) + [0xFE, 0xF0, 0xFC, 0xFC]
                asc = head + [ord(':')] + hexs(frame) + [0xFE, 0xFC, 0xFC]
                name = "seed-c%02d-%03d-a%d" % (cfg, k, addr)
                if head[47] & 1:  # the other framing than the target's
                    rtu, asc = head + asc[HEADER:], head + rtu[HEADER:]
                open(os.path.join(rtu_dir, name), "wb").write(bytes(rtu))
                open(os.path.join(ascii_dir, name), "wb").write(bytes(asc))
                n += 1
    print("%d seeds per target" % n)


if __name__ == "__main__":
    main()
