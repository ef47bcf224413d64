/* SPDX-License-Identifier: Apache-2.0 */
/* master_regs32 — libmodbus (RTU) against a modcp slave in 32-bit register mode,
 * configured with configs/regs32.ini ([ASCII-32] §4.5: 3000-4999 int16 -> DB2.DBW0,
 * 5000-5099 int32 -> DB3.DBD0, 7000-9999 float -> DB4.DBD0; FC04 base DB 900).
 *
 *   master_regs32 --device PATH [--baud 9600] [--parity E] [--slave 5] [--verbose]
 *
 * libmodbus knows only 16-bit registers (its FC03 / FC06 / FC16 helpers count 2 bytes
 * per register), so every request is sent raw (modbus_send_raw_request: libmodbus
 * adds the address and the CRC) and the reply is read from the line here and compared
 * byte for byte, CRC included. Values: floats are IEEE-754 single, int32 two's
 * complement, both big-endian as stored in the DB (byte 1 = most significant).
 *
 * Groups: the worked examples of [ASCII-32] §4.5 / §9.4 / §9.8 / §9.12 with their exact
 * replies; the configured initial values (floats, int32); float / int32 write-then-read;
 * exceptions (straddling ranges, gaps, quantity, byte counts); the RTU limits (63
 * registers of 4 bytes, 127 of 2); FC04 unchanged. The memory the checks wrote is
 * verified from the controller side by run_regs32.py (the simulator's console).
 * Last line "N passed, M failed"; exit code 0 only when nothing failed. */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <modbus.h>
#include <poll.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "master_util.h"

static modbus_t *ctx;
static int slave = 5;

static long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

/* Read a reply: bytes until the line is silent for 50 ms after the first one, or
 * 2 s without any. Returns the length (0 = no reply). */
static int read_reply(uint8_t *rsp, int cap)
{
    int fd = modbus_get_socket(ctx);
    int n = 0;
    long deadline = now_ms() + 2000;
    for (;;) {
        long left = n == 0 ? deadline - now_ms() : 50;
        if (left <= 0) {
            break;
        }
        struct pollfd p = {fd, POLLIN, 0};
        int r = poll(&p, 1, (int)left);
        if (r <= 0) {
            break;
        }
        ssize_t got = read(fd, rsp + n, (size_t)(cap - n));
        if (got <= 0) {
            if (got < 0 && errno == EINTR) {
                continue;
            }
            break;
        }
        n += (int)got;
        if (n >= cap) {
            break;
        }
    }
    return n;
}

/* Send pdu (function code + data) raw; read the reply into rsp (address, PDU, CRC).
 * Returns the reply length; checks address and CRC. */
static int xfer(const uint8_t *pdu, int n, uint8_t *rsp, int cap, const char *what)
{
    uint8_t req[300];
    req[0] = (uint8_t)slave;
    memcpy(req + 1, pdu, (size_t)n);
    modbus_flush(ctx);
    if (n + 1 <= MODBUS_MAX_PDU_LENGTH + 1) {
        if (modbus_send_raw_request(ctx, req, n + 1) < 0) {
            ok(false, "%s: send: %s", what, modbus_strerror(errno));
            return 0;
        }
    } else {
        /* libmodbus refuses PDUs over the Modbus limit of 253 bytes; the CP 341 limits
         * exceed it (FC16 of 63 x 4 or 127 x 2 bytes: PDU 258 / 260): sent here */
        uint16_t crc = crc16(req, (size_t)n + 1u);
        req[n + 1] = (uint8_t)(crc & 0xFFu);
        req[n + 2] = (uint8_t)(crc >> 8);
        ssize_t w = write(modbus_get_socket(ctx), req, (size_t)n + 3u);
        if (w != n + 3) {
            ok(false, "%s: write: %s", what, strerror(errno));
            return 0;
        }
    }
    int len = read_reply(rsp, cap);
    if (len > 0) {
        bool good = len >= 4 && rsp[0] == (uint8_t)slave && crc16(rsp, (size_t)len) == 0;
        ok(good, "%s: reply address %d and CRC (%d bytes)", what, rsp[0], len);
    }
    return len;
}

/* "05 03 ..." spaced hex, without CRC -> bytes */
/* Exchange a request (spaced hex, address included, no CRC) and compare the reply
 * (spaced hex, no CRC) byte for byte. */
static void expect(const char *req, const char *reply, const char *what)
{
    uint8_t q[300], e[300], r[600];
    int nq = hex(req, q, sizeof q);
    int ne = hex(reply, e, sizeof e);
    int nr = xfer(q + 1, nq - 1, r, sizeof r, what);
    ok(nr == ne + 2 && memcmp(r, e, (size_t)ne) == 0, "%s: %s -> %s (got %d bytes)", what, req,
       reply, nr);
}

static void expect_exception(const uint8_t *pdu, int n, uint8_t code, const char *what)
{
    uint8_t r[300];
    int nr = xfer(pdu, n, r, sizeof r, what);
    ok(nr == 5 && r[1] == (uint8_t)(pdu[0] | 0x80u) && r[2] == code,
       "%s: exception %02X (got %d bytes, %02X %02X)", what, code, nr, nr > 1 ? r[1] : 0,
       nr > 2 ? r[2] : 0);
}

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static float f_of(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static uint32_t u_of(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* FC03 of n 4-byte registers from reg: values into out; true when the reply is
 * well-formed with byte count 4 n. */
static bool read32(uint16_t reg, uint16_t n, uint32_t *out, const char *what)
{
    uint8_t pdu[5] = {3, (uint8_t)(reg >> 8), (uint8_t)reg, (uint8_t)(n >> 8), (uint8_t)n};
    uint8_t r[600];
    int nr = xfer(pdu, 5, r, sizeof r, what);
    bool good = nr == 5 + 4 * n && r[1] == 3 && r[2] == 4 * n;
    ok(good, "%s: FC03 %u x 4 bytes from %u, byte count %u", what, n, reg, 4u * n);
    if (!good) {
        return false;
    }
    for (uint16_t k = 0; k < n; k++) {
        out[k] = be32(r + 3 + 4 * k);
    }
    return true;
}

/* FC16 of n 4-byte registers; true when the reply echoes start and quantity. */
static bool write32(uint16_t reg, uint16_t n, const uint32_t *v, const char *what)
{
    uint8_t pdu[6 + 256];
    pdu[0] = 16;
    pdu[1] = (uint8_t)(reg >> 8);
    pdu[2] = (uint8_t)reg;
    pdu[3] = (uint8_t)(n >> 8);
    pdu[4] = (uint8_t)n;
    pdu[5] = (uint8_t)(4 * n);
    for (uint16_t k = 0; k < n; k++) {
        put32(pdu + 6 + 4 * k, v[k]);
    }
    uint8_t r[300];
    int nr = xfer(pdu, 6 + 4 * n, r, sizeof r, what);
    bool good = nr == 8 && memcmp(r + 1, pdu, 5) == 0;
    ok(good, "%s: FC16 %u x 4 bytes to %u acknowledged", what, n, reg);
    return good;
}

/* ---- groups ------------------------------------------------------------------------ */

static void manual_examples(void)
{
    /* [ASCII-32] §4.5 with the [memory] values of configs/regs32.ini */
    expect("05 03 0B EA 00 02", "05 03 04 87 65 43 21", "[ASCII-32] §4.5 FC03 int16 3050 -> DB2.DBW100");
    expect("05 03 1B 59 00 02", "05 03 08 CD DC AB BA 11 22 33 44",
           "[ASCII-32] §9.4 FC03 float 7001 -> DB4.DBD4, DBD8");
    expect("05 06 0D 37 2B 1A", "05 06 0D 37 2B 1A", "[ASCII-32] §4.5 FC06 int16 3383 -> DB2.DBW766");
    expect("05 06 1B 5A 12 23 34 45", "05 06 1B 5A 12 23 34 45",
           "[ASCII-32] §9.8 FC06 float 7002 -> DB4.DBD8, 4 data bytes echoed");
    expect("05 10 0C 1C 00 03 06 CD 09 DE 1A EF 2B", "05 10 0C 1C 00 03",
           "[ASCII-32] §4.5 FC16 int16 3100 -> DB2.DBW200..204");
    expect("05 10 13 8B 00 02 08 3A 09 DE 1A 01 02 03 04", "05 10 13 8B 00 02",
           "[ASCII-32] §9.12 FC16 int32 5003 -> DB3.DBD12, DBD16");
    /* read back what the writes stored */
    expect("05 03 0D 37 00 01", "05 03 02 2B 1A", "read back DB2.DBW766");
    expect("05 03 1B 59 00 02", "05 03 08 CD DC AB BA 12 23 34 45", "read back DB4.DBD4, DBD8");
    expect("05 03 13 8B 00 02", "05 03 08 3A 09 DE 1A 01 02 03 04", "read back DB3.DBD12, 16");
    expect("05 03 0C 1C 00 03", "05 03 06 CD 09 DE 1A EF 2B", "read back DB2.DBW200..204");
    /* FC04 keeps the DB-offset scheme with its own base DB 900 ([ASCII-32] §4.4) */
    expect("05 04 02 C0 00 03", "05 04 06 A1 A2 A3 A4 A5 A6", "[ASCII-32] §9.5 FC04 -> DB901.DBW384");
}

static void values(void)
{
    uint32_t v[4];
    if (read32(7000, 1, v, "float 7000 = DB4.DBD0")) {
        ok(f_of(v[0]) == 1.5f, "DB4.DBD0 = 1.5 (IEEE-754 3FC00000), got %08X", v[0]);
    }
    if (read32(7100, 1, v, "float 7100 = DB4.DBD400")) {
        ok(f_of(v[0]) == 3.14159274f && v[0] == 0x40490FDBu, "DB4.DBD400 = 3.14159274, got %08X",
           v[0]);
    }
    if (read32(9999, 1, v, "float 9999 = DB4.DBD11996 (last of the range)")) {
        ok(f_of(v[0]) == -0.25f, "DB4.DBD11996 = -0.25 (BE800000), got %08X", v[0]);
    }
    if (read32(5000, 2, v, "int32 5000, 5001 = DB3.DBD0, DBD4")) {
        ok((int32_t)v[0] == -2 && (int32_t)v[1] == INT32_MAX, "DB3.DBD0 = -2, DBD4 = 2147483647, got %08X %08X",
           v[0], v[1]);
    }
    /* write-then-read: floats and int32 through FC16 and FC06 */
    const float fl[4] = {0.001f, -123.5f, 6.02214076e23f, -0.0f};
    uint32_t w[4];
    for (int k = 0; k < 4; k++) {
        w[k] = u_of(fl[k]);
    }
    if (write32(7200, 4, w, "floats to 7200..7203 = DB4.DBD800..812") &&
        read32(7200, 4, v, "floats back")) {
        ok(memcmp(v, w, sizeof w) == 0, "floats read back bit-identical (%g %g %g %g)", (double)f_of(v[0]),
           (double)f_of(v[1]), (double)f_of(v[2]), (double)f_of(v[3]));
    }
    const uint32_t iv[3] = {0x80000000u, 0x00000001u, 0xFFFF0000u};
    if (write32(5050, 3, iv, "int32 to 5050..5052 = DB3.DBD200..208") &&
        read32(5050, 3, v, "int32 back")) {
        ok((int32_t)v[0] == INT32_MIN && v[1] == 1 && (int32_t)v[2] == -65536,
           "int32 read back %d %d %d", (int32_t)v[0], (int32_t)v[1], (int32_t)v[2]);
    }
    expect("05 06 1B 61 C2 F6 E9 79", "05 06 1B 61 C2 F6 E9 79", "FC06 float 7009 = -123.456");
    if (read32(7009, 1, v, "float 7009 back")) {
        ok(f_of(v[0]) == -123.456f, "DB4.DBD36 = -123.456, got %g", (double)f_of(v[0]));
    }
}

static void exceptions(void)
{
    const uint8_t straddle[] = {3, 0x13, 0x87, 0, 2}; /* 4999 int16 + 5000 int32 */
    expect_exception(straddle, sizeof straddle, 2, "FC03 4999 x 2 straddles int16 / int32");
    const uint8_t past[] = {3, 0x13, 0xEB, 0, 2}; /* 5099, 5100 */
    expect_exception(past, sizeof past, 2, "FC03 5099 x 2 runs past the int32 range");
    const uint8_t gap[] = {3, 0x17, 0x70, 0, 1}; /* 6000 */
    expect_exception(gap, sizeof gap, 2, "FC03 6000 lies in a gap");
    const uint8_t off[] = {3, 0x00, 0x50, 0, 1}; /* the DB-offset scheme is replaced */
    expect_exception(off, sizeof off, 2, "FC03 0050H outside every range");
    const uint8_t qty[] = {3, 0x1B, 0x58, 0, 64};
    expect_exception(qty, sizeof qty, 3, "FC03 64 x 4 bytes exceeds the RTU limit 63");
    const uint8_t qty16[] = {3, 0x0B, 0xB8, 0, 128};
    expect_exception(qty16, sizeof qty16, 3, "FC03 128 int16 exceeds 127");
    const uint8_t fc06[] = {6, 0x1B, 0x5A, 0x12, 0x23}; /* float register, 2 data bytes */
    expect_exception(fc06, sizeof fc06, 3, "FC06 float register with 2 data bytes");
    const uint8_t fc16[] = {16, 0x13, 0x8B, 0, 2, 4, 1, 2, 3, 4}; /* byte count 2 x 2 */
    expect_exception(fc16, sizeof fc16, 3, "FC16 int32 x 2 with byte count 4");
    /* nothing of the refused writes landed */
    expect("05 03 1B 5A 00 01", "05 03 04 12 23 34 45", "DB4.DBD8 unchanged");
}

static void limits(void)
{
    uint32_t v[63], back[63];
    for (int k = 0; k < 63; k++) {
        v[k] = u_of((float)k * 0.5f - 7.0f);
    }
    if (write32(8000, 63, v, "FC16 63 floats (252 bytes), the RTU maximum") &&
        read32(8000, 63, back, "FC03 63 floats")) {
        ok(memcmp(v, back, sizeof v) == 0, "63 floats read back bit-identical");
    }
    uint8_t pdu[5] = {3, 0x0B, 0xB8, 0, 127}; /* 3000 x 127 int16 */
    uint8_t r[300];
    int nr = xfer(pdu, 5, r, sizeof r, "FC03 127 int16");
    ok(nr == 5 + 254 && r[2] == 254, "FC03 127 int16: byte count 254 (got %d bytes)", nr);
}

int main(int argc, char **argv)
{
    const char *device = NULL;
    int baud = 9600;
    char parity = 'E';
    static const struct option opts[] = {
        {"device", required_argument, NULL, 'd'}, {"baud", required_argument, NULL, 'b'},
        {"parity", required_argument, NULL, 'p'}, {"slave", required_argument, NULL, 's'},
        {"verbose", no_argument, NULL, 'v'},      {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "d:b:p:s:v", opts, NULL)) != -1) {
        switch (c) {
        case 'd': device = optarg; break;
        case 'b': baud = atoi(optarg); break;
        case 'p': parity = optarg[0]; break;
        case 's': slave = atoi(optarg); break;
        case 'v': verbose = true; break;
        default:
            fprintf(stderr, "usage: master_regs32 --device PATH [--baud N] [--parity E|O|N] "
                            "[--slave N] [--verbose]\n");
            return 2;
        }
    }
    if (device == NULL) {
        fprintf(stderr, "master_regs32: --device is required\n");
        return 2;
    }
    ctx = modbus_new_rtu(device, baud, parity, 8, 1);
    if (ctx == NULL || modbus_set_slave(ctx, slave) < 0 || modbus_connect(ctx) < 0) {
        fprintf(stderr, "master_regs32: %s: %s\n", device, modbus_strerror(errno));
        return 2;
    }
    manual_examples();
    values();
    exceptions();
    limits();
    modbus_close(ctx);
    modbus_free(ctx);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 && passed > 0 ? 0 : 1;
}
