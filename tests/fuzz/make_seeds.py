#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Hand-written seed inputs for the line targets (fuzz_rtu, fuzz_ascii), in the harness
encoding of fuzz_line.c: byte 0 = parameter set, 0xFE = the frame's CRC / LRC, 0xF0 =
end of frame, 0xFC = one FB cycle, 0xFD escapes a literal byte >= 0xF0.
    tests/fuzz/make_seeds.py build/fuzz/corpus/fuzz_rtu build/fuzz/corpus/fuzz_ascii
then `tools/fuzz --merge rtu ascii` keeps those that reach new coverage (with what the
fuzzer found) in tests/fuzz/corpus/."""
import os
import sys

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
    rtu_dir, ascii_dir = sys.argv[1], sys.argv[2]
    os.makedirs(rtu_dir, exist_ok=True)
    os.makedirs(ascii_dir, exist_ok=True)
    n = 0
    for cfg in range(5):
        for k, pdu in enumerate(pdus()):
            for addr in ([A, 0] if pdu[0] in (5, 6, 15, 16) and k % 3 == 0 else [A]):
                frame = [addr] + pdu
                rtu = [cfg] + esc(frame) + [0xFE, 0xF0, 0xFC, 0xFC]
                asc = [cfg, ord(':')] + hexs(frame) + [0xFE, 0xFC, 0xFC]
                name = "seed-c%d-%03d-a%d" % (cfg, k, addr)
                open(os.path.join(rtu_dir, name), "wb").write(bytes(rtu))
                open(os.path.join(ascii_dir, name), "wb").write(bytes(asc))
                n += 1
    print("%d seeds per target" % n)


if __name__ == "__main__":
    main()
