/* SPDX-License-Identifier: Apache-2.0 */
/* master_libmodbus — the full check list of a modcp slave configured with
 * configs/default.ini (or configs/manual-4.6.4.ini with --profile 4.6.4), over any
 * serial device: a modcp-sim pty, a QEMU -serial pty, a real line.
 *
 *   master_libmodbus --device PATH [--baud 9600] [--parity E|O|N] [--data-bits 8]
 *                    [--stop-bits 1] [--slave 5] [--random 10000] [--seed N]
 *                    [--timeout-ms 2000] [--cpu-timeout-ms 1000] [--control FIFO]
 *                    [--profile default|4.6.4] [--only GROUP[,GROUP]] [--verbose]
 *
 * Groups: manual (every FC of [RTU-2003] §6 with the exact reply bytes of [RTU-2003] §9), tc
 * (timer/counter words), exceptions (01, 02, 03, 04 from a missing DB), broadcast
 * (no reply, memory changed), big (largest frames), extended (FC17, FC22, FC23,
 * FC43/14, FC08 counters, FC11 of function_set = extended), random (write-then-read over all
 * writable windows, zero mismatches; the memory is restored afterwards), pause
 * (needs --control FIFO of modcp-sim: exception 04 after the CPU job timeout while
 * the user program is paused, nothing written later, normal service after resume).
 *
 * Every check asserts bytes or values. The last line is "N passed, M failed"; the
 * exit code is 0 only when nothing failed. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
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
#include "modcp/version.h"

/* ---- options and results ------------------------------------------------------- */

typedef struct {
    const char *device;
    int baud;
    char parity;
    int data_bits;
    int stop_bits;
    int slave;
    long random_ops;
    unsigned seed;
    int timeout_ms;
    int cpu_timeout_ms;
    const char *control;
    bool p464; /* configs/manual-4.6.4.ini: write limits DB 600-699, MB 1000-1127 */
    char only[256];
    bool verbose;
} opts_t;

static opts_t o;
static modbus_t *ctx;

static bool group(const char *name)
{
    if (o.only[0] == '\0') {
        return strcmp(name, "pause") != 0 || o.control != NULL;
    }
    char buf[300];
    snprintf(buf, sizeof buf, ",%s,", o.only);
    char pat[64];
    snprintf(pat, sizeof pat, ",%s,", name);
    return strstr(buf, pat) != NULL;
}

static void msleep(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* ---- hex and CRC ------------------------------------------------------------------------- */

/* ---- raw exchanges ---------------------------------------------------------------------- */

/* libmodbus raw request (address + PDU, libmodbus adds the CRC); compares the whole
 * reply including its CRC with `expect` (hex incl. CRC). */
static void raw_lm(const char *name, const char *req_hex, const char *expect_hex)
{
    uint8_t req[300], exp[300], rsp[MODBUS_RTU_MAX_ADU_LENGTH];
    size_t rl = hex(req_hex, req, sizeof req);
    size_t el = hex(expect_hex, exp, sizeof exp);
    modbus_flush(ctx);
    int n = -1;
    if (modbus_send_raw_request(ctx, req, (int)rl) > 0) {
        n = modbus_receive_confirmation(ctx, rsp);
    }
    char got[900], want[900];
    fmt_hex(rsp, n > 0 ? (size_t)n : 0u, got, sizeof got);
    fmt_hex(exp, el, want, sizeof want);
    ok(n == (int)el && memcmp(rsp, exp, el) == 0, "%s: reply %s (expected %s)%s%s", name,
       n > 0 ? got : "none", want, n < 0 ? ": " : "", n < 0 ? modbus_strerror(errno) : "");
}

/* Same, expected reply given without its CRC (computed here). */
static void raw_lmc(const char *name, const char *req_hex, const char *expect_nocrc)
{
    uint8_t exp[300];
    size_t el = add_crc(exp, hex(expect_nocrc, exp, sizeof exp - 2));
    char want[900];
    fmt_hex(exp, el, want, sizeof want);
    raw_lm(name, req_hex, want);
}

/* Direct I/O on the line for what libmodbus cannot frame (FC08, silence). Sends
 * req (hex without CRC), reads until want bytes arrived or wait_ms passed. */
static int raw_fd(const uint8_t *req, size_t rl, uint8_t *rsp, size_t want, int wait_ms)
{
    int fd = modbus_get_socket(ctx);
    uint8_t buf[600];
    memcpy(buf, req, rl);
    size_t n = add_crc(buf, rl);
    modbus_flush(ctx);
    if (write(fd, buf, n) != (ssize_t)n) {
        return -1;
    }
    return read_want(fd, rsp, want, wait_ms);
}

static void raw_echo(const char *name, const char *req_hex, const char *expect_hex)
{
    uint8_t req[300], exp[300], rsp[300];
    size_t rl = hex(req_hex, req, sizeof req);
    size_t el = hex(expect_hex, exp, sizeof exp);
    int n = raw_fd(req, rl, rsp, el, o.timeout_ms);
    char got[900], want[900];
    fmt_hex(rsp, n > 0 ? (size_t)n : 0u, got, sizeof got);
    fmt_hex(exp, el, want, sizeof want);
    ok(n == (int)el && memcmp(rsp, exp, el) == 0, "%s: reply %s (expected %s)", name,
       n > 0 ? got : "none", want);
}

/* A request whose reply is its own echo (CRC computed here). */
static void raw_echo_self(const char *name, const char *req_hex)
{
    uint8_t exp[300];
    size_t el = add_crc(exp, hex(req_hex, exp, sizeof exp - 2));
    char want[900];
    fmt_hex(exp, el, want, sizeof want);
    raw_echo(name, req_hex, want);
}

/* A request that must stay unanswered. */
static void raw_silent(const char *name, const char *req_hex, int wait_ms)
{
    uint8_t req[300], rsp[300];
    size_t rl = hex(req_hex, req, sizeof req);
    int n = raw_fd(req, rl, rsp, sizeof rsp, wait_ms);
    char got[900];
    fmt_hex(rsp, n > 0 ? (size_t)n : 0u, got, sizeof got);
    ok(n == 0, "%s: no reply (got %s)", name, n > 0 ? got : "nothing");
}

/* An exception: 05 (FC|80) code + CRC, through libmodbus's raw functions. */
static void raw_exc(const char *name, const char *req_hex, unsigned code)
{
    uint8_t req[300], exp[8];
    (void)hex(req_hex, req, sizeof req);
    exp[0] = req[0];
    exp[1] = (uint8_t)(req[1] | 0x80u);
    exp[2] = (uint8_t)code;
    size_t el = add_crc(exp, 3);
    char want[64];
    fmt_hex(exp, el, want, sizeof want);
    raw_lm(name, req_hex, want);
}

/* ---- typed helpers (libmodbus API) ----------------------------------------------------------- */

static bool read_bits(int addr, int n, uint8_t *dst)
{
    for (int done = 0; done < n;) {
        int k = n - done > 2000 ? 2000 : n - done;
        if (modbus_read_bits(ctx, addr + done, k, dst + done) != k) {
            return false;
        }
        done += k;
    }
    return true;
}

static bool read_regs(int addr, int n, uint16_t *dst)
{
    for (int done = 0; done < n;) {
        int k = n - done > 125 ? 125 : n - done;
        int blk = 512 - ((addr + done) % 512); /* never cross a DB */
        if (k > blk) {
            k = blk;
        }
        if (modbus_read_registers(ctx, addr + done, k, dst + done) != k) {
            return false;
        }
        done += k;
    }
    return true;
}

static bool write_bits(int addr, int n, const uint8_t *src)
{
    for (int done = 0; done < n;) {
        int k = n - done > 1968 ? 1968 : n - done;
        if (modbus_write_bits(ctx, addr + done, k, src + done) != k) {
            return false;
        }
        done += k;
    }
    return true;
}

static bool write_regs(int addr, int n, const uint16_t *src)
{
    for (int done = 0; done < n;) {
        int k = n - done > 123 ? 123 : n - done;
        int blk = 512 - ((addr + done) % 512);
        if (k > blk) {
            k = blk;
        }
        if (modbus_write_registers(ctx, addr + done, k, src + done) != k) {
            return false;
        }
        done += k;
    }
    return true;
}

/* ---- groups -------------------------------------------------------------------------------------- */

static void g_manual(void)
{
    /* [RTU-2003] §6 / §9: the manual's frames, reply bytes including the CRC */
    raw_lm("[RTU-2003] §6.1 FC01 M1008.0..M1011.7", "05 01 00 40 00 20", "05 01 04 01 17 02 18 0E 83");
    raw_lm("[RTU-2003] §6.2 FC02 I134.0..I136.7", "05 02 10 30 00 18", "05 02 03 12 34 56 4F 31");
    raw_lm("[RTU-2003] §6.3 FC03 DB800.DBW160/162", "05 03 00 50 00 02", "05 03 04 87 65 43 21 76 70");
    raw_lm("[RTU-2003] §6.4 FC04 DB901.DBW384..388", "05 04 02 C0 00 03",
           "05 04 06 A1 A2 A3 A4 A5 A6 2A 76");
    raw_echo("[RTU-2003] §6.7 FC08 loopback", "05 08 00 00 A5 C3", "05 08 00 00 A5 C3 DA 8E");

    /* FC05: Q257.1 (coil 2057); first clear it, then the manual's frame */
    uint8_t b[16], before[16];
    ok(modbus_write_bit(ctx, 2057, 0) == 1, "FC05 clear Q257.1");
    bool rd = read_bits(2056, 8, before);
    raw_lm("[RTU-2003] §6.5 FC05 Q257.1 on", "05 05 08 09 FF 00", "05 05 08 09 FF 00 5F DC");
    rd = rd && read_bits(2056, 8, b);
    before[1] = 1;
    ok(rd && memcmp(b, before, 8) == 0, "FC05 read back Q257.1 = %u, Q257.0/2..7 unchanged", b[1]);

    /* FC06: DB800.DBW768 := 2B1A */
    uint16_t r[8];
    ok(modbus_write_register(ctx, 0x180, 0) == 1, "FC06 clear DB800.DBW768");
    raw_lm("[RTU-2003] §6.6 FC06 DB800.DBW768 = 2B1A", "05 06 01 80 2B 1A", "05 06 01 80 2B 1A 17 61");
    rd = read_regs(0x180, 1, r);
    ok(rd && r[0] == 0x2B1A, "FC06 read back DB800.DBW768 = %04X", r[0]);

    /* FC15: M1144.0..M1145.3 = CD, 9; M1145.4..7 untouched (set to 1 first) */
    uint8_t pre[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
    ok(write_bits(1152, 16, pre), "FC15 prepare MB1144 = 00, MB1145 = F0");
    raw_lm("[RTU-2003] §6.8 FC15 M1144.0..M1145.3", "05 0F 04 80 00 0C 02 CD 09",
           "05 0F 04 80 00 0C 54 92");
    raw_lmc("FC15 read back MB1144/1145 = CD F9 (M1145.4..7 untouched)", "05 01 04 80 00 10",
           "05 01 02 CD F9");

    /* FC16: DB800.DBW100..104 */
    ok(write_regs(0x32, 3, (const uint16_t[]){0, 0, 0}), "FC16 clear DB800.DBW100..104");
    raw_lm("[RTU-2003] §6.9 FC16 DB800.DBW100..104", "05 10 00 32 00 03 06 CD 09 DE 1A EF 2B",
           "05 10 00 32 00 03 20 43");
    rd = read_regs(0x32, 3, r);
    ok(rd && r[0] == 0xCD09 && r[1] == 0xDE1A && r[2] == 0xEF2B, "FC16 read back %04X %04X %04X",
       r[0], r[1], r[2]);
}

static void g_tc(void)
{
    /* T100 = 1234, T101 = 5678, C200 = 9ABC in the config; high byte first on the wire */
    raw_lmc("FC01 T100 (one 16-bit word)", "05 01 10 00 00 10", "05 01 02 12 34");
    raw_lmc("FC01 T100..T101", "05 01 10 00 00 20", "05 01 04 12 34 56 78");
    raw_lmc("FC01 C200", "05 01 12 00 00 10", "05 01 02 9A BC");
    raw_exc("FC01 T window, 8 bits (not a multiple of 16) -> 03", "05 01 10 00 00 08", 3);
    raw_exc("FC01 T window, start 4104 (misaligned) -> 02", "05 01 10 08 00 10", 2);
    raw_exc("FC05 on a timer -> 02", "05 05 10 00 FF 00", 2);
    raw_exc("FC15 on a counter -> 02", "05 0F 12 00 00 10 02 FF FF", 2);
}

static void g_exceptions(void)
{
    raw_exc("FC 0x41 -> 01 (illegal function)", "05 41 00 00 00 01", 1);
    raw_exc("FC 0x07 -> 01 (not in the manual's set)", "05 07", 1);
    raw_exc("FC01 address 3000 (gap between Q and T) -> 02", "05 01 0B B8 00 08", 2);
    raw_exc("FC02 address 5120 (after the I window) -> 02", "05 02 14 00 00 08", 2);
    raw_exc("FC15 across the M window end -> 02", "05 0F 07 F8 00 10 02 00 00", 2);
    raw_exc("FC06 DB900 (outside the DB write limits) -> 02", "05 06 C8 00 12 34", 2);
    raw_exc("FC03 across a DB boundary (reg 510, 4) -> 02", "05 03 01 FE 00 04", 2);
    raw_exc("FC03 128 registers -> 03", "05 03 00 00 00 80", 3);
    raw_exc("FC03 0 registers -> 03", "05 03 00 00 00 00", 3);
    raw_exc("FC01 2041 bits -> 03", "05 01 00 00 07 F9", 3);
    raw_exc("FC05 value 1234 -> 03", "05 05 00 00 12 34", 3);
    raw_exc("FC15 byte count 1 for 12 bits -> 03", "05 0F 04 80 00 0C 01 CD", 3);
    raw_exc("FC16 byte count 4 for 3 registers -> 03", "05 10 00 32 00 03 04 00 01 00 02", 3);
    raw_exc("FC03 DB803 does not exist -> 04", "05 03 06 00 00 01", 4);
    raw_exc("FC04 DB902 does not exist -> 04", "05 04 04 00 00 01", 4);
    /* and the slave serves the next good request normally */
    raw_lm("next good request after exceptions", "05 03 00 50 00 02", "05 03 04 87 65 43 21 76 70");
}

static void g_broadcast(void)
{
    uint16_t r[4];
    uint8_t b[16];
    ok(modbus_write_register(ctx, 0x64, 0) == 1, "broadcast: clear DB800.DBW200");
    raw_silent("broadcast FC06 DB800.DBW200 = 1234", "00 06 00 64 12 34", 300);
    bool rd = read_regs(0x64, 1, r);
    ok(rd && r[0] == 0x1234, "broadcast FC06 read back %04X", r[0]);
    raw_silent("broadcast FC16 DB800.DBW202..204", "00 10 00 65 00 02 04 AB CD EF 01", 300);
    rd = read_regs(0x65, 2, r);
    ok(rd && r[0] == 0xABCD && r[1] == 0xEF01, "broadcast FC16 read back %04X %04X", r[0], r[1]);
    ok(modbus_write_bit(ctx, 2058, 0) == 1, "broadcast: clear Q257.2");
    raw_silent("broadcast FC05 Q257.2 on", "00 05 08 0A FF 00", 300);
    rd = read_bits(2058, 1, b);
    ok(rd && b[0] == 1, "broadcast FC05 read back Q257.2 = %u", b[0]);
    raw_silent("broadcast FC15 Q300.0..7 = A5", "00 0F 09 60 00 08 01 A5", 300);
    rd = read_bits(2400, 8, b);
    ok(rd && b[0] == 1 && b[1] == 0 && b[2] == 1 && b[3] == 0 && b[4] == 0 && b[5] == 1 && b[6] == 0 &&
           b[7] == 1,
       "broadcast FC15 read back Q300 bits %u%u%u%u%u%u%u%u", b[7], b[6], b[5], b[4], b[3], b[2],
       b[1], b[0]);
    raw_silent("broadcast FC03 (not allowed, (08)30H)", "00 03 00 50 00 02", 300);
    raw_silent("broadcast FC08 (not allowed)", "00 08 00 00 12 34", 300);
    raw_silent("frame for slave 7", "07 03 00 50 00 02", 300);
    raw_lm("good request after broadcasts", "05 03 00 50 00 02", "05 03 04 87 65 43 21 76 70");
}

static void g_big(void)
{
    /* FC03 127 registers of DB800 */
    uint8_t req[300];
    uint16_t regs[127];
    uint8_t rsp[600];
    size_t rl;
    int n;
    bool good;
    size_t k = 0;
    if (o.p464) {
        /* DB800 is outside DB 600-699: read the 127 registers, writes refused */
        rl = hex("05 03 01 00 00 7F", req, sizeof req);
        n = raw_fd(req, rl, rsp, 5 + 254, o.timeout_ms);
        ok(n == 259 && rsp[2] == 254 && crc16(rsp, 259) == 0,
           "big: FC03 127 registers, 259-byte reply (got %d bytes)", n);
        k = 0;
        req[k++] = 5;
        req[k++] = 0x10;
        req[k++] = 0x01;
        req[k++] = 0x00;
        req[k++] = 0x00;
        req[k++] = 127;
        req[k++] = 254;
        for (int i = 0; i < 254; i++) {
            req[k++] = (uint8_t)i;
        }
        n = raw_fd(req, k, rsp, 5, o.timeout_ms);
        ok(n == 5 && rsp[1] == 0x90 && rsp[2] == 2 && crc16(rsp, 5) == 0,
           "big: FC16 127 registers into DB800 refused with 02 (4.6.4 limits)");
    } else {
        for (int i = 0; i < 127; i++) {
            regs[i] = (uint16_t)(0x1000 + i * 7);
        }
        ok(write_regs(256, 127, regs), "big: FC16 DB800.DBW512.. 127 registers (2 requests)");
        rl = hex("05 03 01 00 00 7F", req, sizeof req);
        n = raw_fd(req, rl, rsp, 5 + 254, o.timeout_ms);
        good = n == 259 && rsp[2] == 254 && crc16(rsp, 259) == 0;
        for (int i = 0; good && i < 127; i++) {
            good = ((rsp[3 + 2 * i] << 8) | rsp[4 + 2 * i]) == regs[i];
        }
        ok(good, "big: FC03 127 registers, 259-byte reply (got %d bytes)", n);

        /* FC16 127 registers in one request (262-byte frame, more than libmodbus sends) */
        k = 0;
        req[k++] = 5;
        req[k++] = 0x10;
        req[k++] = 0x01;
        req[k++] = 0x00;
        req[k++] = 0x00;
        req[k++] = 127;
        req[k++] = 254;
        for (int i = 0; i < 127; i++) {
            regs[i] = (uint16_t)(0xA000 + i * 3);
            req[k++] = (uint8_t)(regs[i] >> 8);
            req[k++] = (uint8_t)(regs[i] & 0xFF);
        }
        n = raw_fd(req, k, rsp, 8, o.timeout_ms);
        uint8_t exp[8] = {5, 0x10, 0x01, 0x00, 0x00, 127};
        add_crc(exp, 6);
        ok(n == 8 && memcmp(rsp, exp, 8) == 0, "big: FC16 127 registers in one frame (reply %d bytes)",
           n);
        uint16_t back[127];
        ok(read_regs(256, 127, back) && memcmp(back, regs, sizeof back) == 0,
           "big: FC16 127 registers read back");
    }

    /* FC15 2040 coils in one request (264-byte frame) and FC01 2040 coils (260-byte reply);
     * MB1000..1254 are restored afterwards (they hold the FC01 example's M1008..1011) */
    uint8_t bits[2040];
    static uint8_t saved[2040];
    bool have_saved = read_bits(0, 2040, saved);
    ok(have_saved, "big: save coils 0..2039");
    k = 0;
    req[k++] = 5;
    req[k++] = 0x0F;
    req[k++] = 0;
    req[k++] = 0;
    req[k++] = 0x07;
    req[k++] = 0xF8;
    req[k++] = 255;
    for (int i = 0; i < 255; i++) {
        uint8_t v = (uint8_t)(i * 37 + 11);
        req[k++] = v;
        for (int j = 0; j < 8; j++) {
            bits[i * 8 + j] = (uint8_t)((v >> j) & 1u);
        }
    }
    n = raw_fd(req, k, rsp, 8, o.timeout_ms);
    uint8_t exp15[8] = {5, 0x0F, 0, 0, 0x07, 0xF8};
    add_crc(exp15, 6);
    if (o.p464) {
        ok(n == 5 && rsp[1] == 0x8F && rsp[2] == 2,
           "big: FC15 2040 coils beyond MB1127 refused with 02 (4.6.4 limits)");
    } else {
        ok(n == 8 && memcmp(rsp, exp15, 8) == 0, "big: FC15 2040 coils in one frame (reply %d bytes)",
           n);
        rl = hex("05 01 00 00 07 F8", req, sizeof req);
        n = raw_fd(req, rl, rsp, 5 + 255, o.timeout_ms);
        good = n == 260 && rsp[2] == 255 && crc16(rsp, 260) == 0;
        for (int i = 0; good && i < 2040; i++) {
            good = ((rsp[3 + i / 8] >> (i % 8)) & 1u) == bits[i];
        }
        ok(good, "big: FC01 2040 coils, 260-byte reply (got %d bytes)", n);
        uint8_t back[2040];
        ok(have_saved && write_bits(0, 2040, saved) && read_bits(0, 2040, back) &&
               memcmp(back, saved, sizeof back) == 0,
           "big: coils 0..2039 restored");
    }
}

/* ---- extended function set (function_set = extended) ------------------------------------------- */

static void g_extended(void)
{
    uint16_t r[8];
    bool rd;
    /* FC17 report slave ID: [slave id/byte count data...]; run indicator FF, the strings of
     * [identification] (vendor modcp, product CP341-MODBUS) */
    uint8_t id[MODBUS_MAX_PDU_LENGTH];
    int n = modbus_report_slave_id(ctx, sizeof id, id);
    bool run = false, vendor = false, product = false;
    for (int i = 0; i < n; i++) {
        run = run || id[i] == 0xFF;
    }
    if (n > 0) {
        id[n < (int)sizeof id ? n : (int)sizeof id - 1] = 0;
        for (int i = 0; i < n; i++) {
            vendor = vendor || memcmp(id + i, "modcp", 5) == 0;
            product = product || memcmp(id + i, "CP341-MODBUS", 12) == 0;
        }
    }
    ok(n > 2 && run && vendor && product, "FC17 report slave ID: %d bytes, run indicator FF, "
       "vendor 'modcp', product 'CP341-MODBUS'", n);

    /* FC22 mask write: (0x1234 AND FF00) OR (0055 AND NOT FF00) = 0x1255 */
    ok(modbus_write_register(ctx, 0x64, 0x1234) == 1, "FC22: DB800.DBW200 = 1234");
    ok(modbus_mask_write_register(ctx, 0x64, 0xFF00, 0x0055) == 1, "FC22 mask write AND FF00 OR 0055");
    rd = read_regs(0x64, 1, r);
    ok(rd && r[0] == 0x1255, "FC22 result %04X (expected 1255)", r[0]);

    /* FC23: the write happens before the read */
    ok(write_regs(0x70, 3, (const uint16_t[]){1, 2, 3}), "FC23: DB800.DBW224..228 = 1 2 3");
    n = modbus_write_and_read_registers(ctx, 0x70, 2, (const uint16_t[]){0xAAAA, 0xBBBB}, 0x70, 3, r);
    ok(n == 3 && r[0] == 0xAAAA && r[1] == 0xBBBB && r[2] == 3,
       "FC23 write 2 then read 3: %04X %04X %04X (expected AAAA BBBB 0003)", r[0], r[1], r[2]);

    /* FC43/14 read device identification, basic objects 00..02 */
    uint8_t req[8], rsp[300];
    size_t rl = hex("05 2B 0E 01 00", req, sizeof req);
    int m = raw_fd(req, rl, rsp, sizeof rsp, 300);
    bool good = m > 10 && crc16(rsp, (size_t)m) == 0 && rsp[1] == 0x2B && rsp[2] == 0x0E && rsp[3] == 0x01;
    char v[3][32] = {"", "", ""};
    if (good) {
        int nobj = rsp[7];
        int pos = 8;
        for (int i = 0; i < nobj && pos + 2 <= m - 2; i++) {
            int oid = rsp[pos], len = rsp[pos + 1];
            if (oid < 3 && len < 32 && pos + 2 + len <= m - 2) {
                memcpy(v[oid], rsp + pos + 2, (size_t)len);
                v[oid][len] = 0;
            }
            pos += 2 + len;
        }
    }
    ok(good && strcmp(v[0], "modcp") == 0 && strcmp(v[1], "CP341-MODBUS") == 0 &&
           strcmp(v[2], MODCP_VERSION) == 0, /* revision empty: modcp's version */
       "FC43/14 basic objects: '%s' '%s' '%s' (expected modcp, CP341-MODBUS, " MODCP_VERSION ")",
       v[0], v[1], v[2]);

    /* FC08 counters: clear (sub 0A, echo), then the CRC error counter (sub 0C) reads 0 and
     * the bus message counter (sub 0B) counts the requests since */
    raw_echo_self("FC08 sub 0A clear counters (echo)", "05 08 00 0A 00 00");
    raw_echo_self("FC08 sub 0C CRC errors after the clear = 0 (echo)", "05 08 00 0C 00 00");
    rl = hex("05 08 00 0B 00 00", req, sizeof req);
    m = raw_fd(req, rl, rsp, 8, o.timeout_ms);
    unsigned cnt = m == 8 ? (unsigned)((rsp[4] << 8) | rsp[5]) : 0u;
    ok(m == 8 && crc16(rsp, 8) == 0 && rsp[3] == 0x0B && cnt >= 2 && cnt <= 3,
       "FC08 sub 0B bus messages since the clear = %u (2 or 3)", cnt);

    /* FC11 get comm event counter: status 0000 (not busy), a count */
    rl = hex("05 0B", req, sizeof req);
    m = raw_fd(req, rl, rsp, 8, o.timeout_ms);
    ok(m == 8 && crc16(rsp, 8) == 0 && rsp[1] == 0x0B && rsp[2] == 0 && rsp[3] == 0,
       "FC11 comm event counter: status 0000, count %u", m == 8 ? (unsigned)((rsp[4] << 8) | rsp[5]) : 0u);
    raw_lm("good request after the extended set", "05 03 00 50 00 02", "05 03 04 87 65 43 21 76 70");
}

/* ---- random write-then-read ------------------------------------------------------------------ */

typedef struct {
    int from, count; /* Modbus coil addresses */
} win_t;

static unsigned rnd(unsigned n)
{
    return (unsigned)(rand() % (int)n);
}

static void g_random(void)
{
    /* writable windows of the profile */
    win_t cw[2];
    int ncw = 0;
    if (o.p464) {
        cw[ncw++] = (win_t){0, 1024}; /* M 0..1023 -> MB1000..1127 */
    } else {
        cw[ncw++] = (win_t){0, 2048}; /* M -> MB1000..1255 */
    }
    cw[ncw++] = (win_t){2048, 512}; /* Q -> QB256..319 */
    int nregs = o.p464 ? 0 : 3 * 512; /* DB800..802 (DB 600-699 do not exist in 4.6.4) */

    uint8_t *coils[2];
    uint8_t *orig_coils[2];
    uint16_t *regs = NULL, *orig_regs = NULL;
    for (int w = 0; w < ncw; w++) {
        coils[w] = calloc((size_t)cw[w].count, 1);
        orig_coils[w] = calloc((size_t)cw[w].count, 1);
        ok(read_bits(cw[w].from, cw[w].count, coils[w]), "random: snapshot coils %d..%d",
           cw[w].from, cw[w].from + cw[w].count - 1);
        memcpy(orig_coils[w], coils[w], (size_t)cw[w].count);
    }
    if (nregs > 0) {
        regs = calloc((size_t)nregs, sizeof *regs);
        orig_regs = calloc((size_t)nregs, sizeof *regs);
        ok(read_regs(0, nregs, regs), "random: snapshot registers 0..%d", nregs - 1);
        memcpy(orig_regs, regs, (size_t)nregs * sizeof *regs);
    }

    long mismatches = 0, errors = 0;
    double t0 = now_s();
    for (long op = 0; op < o.random_ops; op++) {
        unsigned kind = nregs > 0 ? rnd(4) : rnd(2);
        if (kind < 2) {
            int w = (int)rnd((unsigned)ncw);
            int len = kind == 0 ? 1 : 1 + (int)(rnd(8) == 0 ? rnd(1968) : rnd(64));
            if (len > cw[w].count) {
                len = cw[w].count;
            }
            int start = (int)rnd((unsigned)(cw[w].count - len + 1));
            uint8_t v[2048];
            for (int i = 0; i < len; i++) {
                v[i] = (uint8_t)rnd(2);
            }
            int rc = kind == 0 ? modbus_write_bit(ctx, cw[w].from + start, v[0])
                               : modbus_write_bits(ctx, cw[w].from + start, len, v);
            if (rc != (kind == 0 ? 1 : len)) {
                errors++;
                if (errors <= 5) {
                    printf("random op %ld: FC%s coil %d len %d: %s\n", op, kind == 0 ? "05" : "15",
                           cw[w].from + start, len, modbus_strerror(errno));
                }
                continue;
            }
            memcpy(coils[w] + start, v, (size_t)len);
            int lo = start - 8 < 0 ? 0 : start - 8;
            int hi = start + len + 8 > cw[w].count ? cw[w].count : start + len + 8;
            uint8_t back[2100];
            if (!read_bits(cw[w].from + lo, hi - lo, back)) {
                errors++;
                continue;
            }
            if (memcmp(back, coils[w] + lo, (size_t)(hi - lo)) != 0) {
                mismatches++;
                if (mismatches <= 5) {
                    printf("random op %ld: coils %d..%d differ after writing %d..%d\n", op,
                           cw[w].from + lo, cw[w].from + hi - 1, cw[w].from + start,
                           cw[w].from + start + len - 1);
                }
                memcpy(coils[w] + lo, back, (size_t)(hi - lo)); /* resync */
            }
        } else {
            int len = kind == 2 ? 1 : 1 + (int)(rnd(8) == 0 ? rnd(123) : rnd(16));
            int start = (int)rnd((unsigned)nregs);
            int room = 512 - start % 512;
            if (len > room) {
                len = room;
            }
            uint16_t v[128];
            for (int i = 0; i < len; i++) {
                v[i] = (uint16_t)rnd(65536);
            }
            int rc = kind == 2 ? modbus_write_register(ctx, start, v[0])
                               : modbus_write_registers(ctx, start, len, v);
            if (rc != (kind == 2 ? 1 : len)) {
                errors++;
                if (errors <= 5) {
                    printf("random op %ld: FC%s reg %d len %d: %s\n", op, kind == 2 ? "06" : "16",
                           start, len, modbus_strerror(errno));
                }
                continue;
            }
            memcpy(regs + start, v, (size_t)len * sizeof *v);
            int dbase = start - start % 512;
            int lo = start - 2 < dbase ? dbase : start - 2;
            int hi = start + len + 2 > dbase + 512 ? dbase + 512 : start + len + 2;
            uint16_t back[140];
            if (!read_regs(lo, hi - lo, back)) {
                errors++;
                continue;
            }
            if (memcmp(back, regs + lo, (size_t)(hi - lo) * sizeof *back) != 0) {
                mismatches++;
                if (mismatches <= 5) {
                    printf("random op %ld: registers %d..%d differ after writing %d..%d\n", op, lo,
                           hi - 1, start, start + len - 1);
                }
                memcpy(regs + lo, back, (size_t)(hi - lo) * sizeof *back);
            }
        }
    }
    double dt = now_s() - t0;
    ok(mismatches == 0 && errors == 0,
       "random: %ld write-then-read operations, %ld mismatches, %ld errors (%.1f s, %.2f ms/op)",
       o.random_ops, mismatches, errors, dt, o.random_ops > 0 ? dt * 1000.0 / (double)o.random_ops : 0.0);

    /* the whole image once more, then restore what was there before */
    for (int w = 0; w < ncw; w++) {
        uint8_t *back = calloc((size_t)cw[w].count, 1);
        ok(read_bits(cw[w].from, cw[w].count, back) && memcmp(back, coils[w], (size_t)cw[w].count) == 0,
           "random: final image of coils %d..%d", cw[w].from, cw[w].from + cw[w].count - 1);
        ok(write_bits(cw[w].from, cw[w].count, orig_coils[w]) &&
               read_bits(cw[w].from, cw[w].count, back) &&
               memcmp(back, orig_coils[w], (size_t)cw[w].count) == 0,
           "random: coils %d..%d restored", cw[w].from, cw[w].from + cw[w].count - 1);
        free(back);
        free(coils[w]);
        free(orig_coils[w]);
    }
    if (nregs > 0) {
        uint16_t *back = calloc((size_t)nregs, sizeof *back);
        ok(read_regs(0, nregs, back) && memcmp(back, regs, (size_t)nregs * sizeof *back) == 0,
           "random: final image of registers 0..%d", nregs - 1);
        ok(write_regs(0, nregs, orig_regs) && read_regs(0, nregs, back) &&
               memcmp(back, orig_regs, (size_t)nregs * sizeof *back) == 0,
           "random: registers 0..%d restored", nregs - 1);
        free(back);
        free(regs);
        free(orig_regs);
    }
}

/* ---- paused user program (modcp-sim --control FIFO) ------------------------------------------ */

static bool control(const char *cmd)
{
    int fd = open(o.control, O_WRONLY | O_NONBLOCK);
    if (fd < 0) {
        return false;
    }
    char line[64];
    int n = snprintf(line, sizeof line, "%s\n", cmd);
    bool good = write(fd, line, (size_t)n) == n;
    close(fd);
    msleep(100); /* a few cycles */
    return good;
}

static void g_pause(void)
{
    uint8_t b[8];
    ok(modbus_write_bit(ctx, 2059, 0) == 1, "pause: clear Q257.3");
    ok(control("pause"), "pause: user program paused via %s", o.control);
    double t0 = now_s();
    raw_exc("paused: FC03 -> 04 after the CPU job timeout ((0E)31H)", "05 03 00 50 00 02", 4);
    double dt = (now_s() - t0) * 1000.0;
    ok(dt >= o.cpu_timeout_ms * 0.9 && dt <= o.cpu_timeout_ms + 1000.0,
       "paused: exception after %.0f ms (CPU job timeout %d ms)", dt, o.cpu_timeout_ms);
    t0 = now_s();
    raw_exc("paused: FC05 Q257.3 -> 04 after the timeout ((0E)3BH)", "05 05 08 0B FF 00", 4);
    dt = (now_s() - t0) * 1000.0;
    ok(dt >= o.cpu_timeout_ms * 0.9 && dt <= o.cpu_timeout_ms + 1000.0,
       "paused: FC05 exception after %.0f ms", dt);
    ok(control("resume"), "pause: user program resumed");
    raw_lm("resumed: the next good request is served", "05 03 00 50 00 02",
           "05 03 04 87 65 43 21 76 70");
    bool rd = read_bits(2059, 1, b);
    ok(rd && b[0] == 0, "resumed: the timed-out FC05 was not executed later (Q257.3 = %u)", b[0]);
}

/* ---- main ------------------------------------------------------------------------------------------- */

static int usage(void)
{
    fprintf(stderr,
            "usage: master_libmodbus --device PATH [--baud 9600] [--parity E|O|N] [--data-bits 8]\n"
            "         [--stop-bits 1] [--slave 5] [--random 10000] [--seed N] [--timeout-ms 2000]\n"
            "         [--cpu-timeout-ms 1000] [--control FIFO] [--profile default|4.6.4]\n"
            "         [--only manual,tc,exceptions,broadcast,big,extended,random,pause] [--verbose]\n");
    return 2;
}

int main(int argc, char **argv)
{
    o.baud = 9600;
    o.parity = 'E';
    o.data_bits = 8;
    o.stop_bits = 1;
    o.slave = 5;
    o.random_ops = 10000;
    o.seed = (unsigned)time(NULL);
    o.timeout_ms = 2000;
    o.cpu_timeout_ms = 1000;
    static const struct option lo[] = {
        {"device", required_argument, 0, 'd'},  {"baud", required_argument, 0, 'b'},
        {"parity", required_argument, 0, 'p'},  {"data-bits", required_argument, 0, 'D'},
        {"stop-bits", required_argument, 0, 'S'}, {"slave", required_argument, 0, 'a'},
        {"random", required_argument, 0, 'r'},  {"seed", required_argument, 0, 's'},
        {"timeout-ms", required_argument, 0, 't'}, {"cpu-timeout-ms", required_argument, 0, 'T'},
        {"control", required_argument, 0, 'c'}, {"profile", required_argument, 0, 'P'},
        {"only", required_argument, 0, 'o'},    {"verbose", no_argument, 0, 'v'},
        {0, 0, 0, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (c) {
        case 'd': o.device = optarg; break;
        case 'b': o.baud = atoi(optarg); break;
        case 'p': o.parity = optarg[0]; break;
        case 'D': o.data_bits = atoi(optarg); break;
        case 'S': o.stop_bits = atoi(optarg); break;
        case 'a': o.slave = atoi(optarg); break;
        case 'r': o.random_ops = atol(optarg); break;
        case 's': o.seed = (unsigned)strtoul(optarg, NULL, 0); break;
        case 't': o.timeout_ms = atoi(optarg); break;
        case 'T': o.cpu_timeout_ms = atoi(optarg); break;
        case 'c': o.control = optarg; break;
        case 'P':
            if (strcmp(optarg, "4.6.4") == 0) {
                o.p464 = true;
            } else if (strcmp(optarg, "default") != 0) {
                return usage();
            }
            break;
        case 'o': snprintf(o.only, sizeof o.only, "%s", optarg); break;
        case 'v': o.verbose = verbose = true; break;
        default: return usage();
        }
    }
    if (o.device == NULL || o.slave != 5) {
        if (o.slave != 5) {
            fprintf(stderr, "master_libmodbus: the check list expects slave 5 (configs/default.ini)\n");
        }
        return usage();
    }
    char par = o.parity == 'e' ? 'E' : o.parity == 'o' ? 'O' : o.parity == 'n' ? 'N' : o.parity;
    ctx = modbus_new_rtu(o.device, o.baud, par, o.data_bits, o.stop_bits);
    if (ctx == NULL || modbus_set_slave(ctx, o.slave) != 0 || modbus_connect(ctx) != 0) {
        fprintf(stderr, "master_libmodbus: %s: %s\n", o.device, modbus_strerror(errno));
        printf("0 passed, 1 failed\n");
        return 1;
    }
    modbus_set_response_timeout(ctx, (uint32_t)(o.timeout_ms / 1000),
                                (uint32_t)((o.timeout_ms % 1000) * 1000));
    modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_PROTOCOL);
    srand(o.seed);
    printf("master_libmodbus: %s %d %d%c%d slave %d, profile %s, seed %u\n", o.device, o.baud,
           o.data_bits, par, o.stop_bits, o.slave, o.p464 ? "4.6.4" : "default", o.seed);
    fflush(stdout);

    double t0 = now_s();
    if (group("manual")) {
        if (o.p464) {
            raw_lm("[RTU-2003] §6.1 FC01", "05 01 00 40 00 20", "05 01 04 01 17 02 18 0E 83");
            raw_lm("[RTU-2003] §6.3 FC03", "05 03 00 50 00 02", "05 03 04 87 65 43 21 76 70");
            raw_lm("[RTU-2003] §6.5 FC05 Q257.1 (inside QB 256-319)", "05 05 08 09 FF 00",
                   "05 05 08 09 FF 00 5F DC");
            raw_exc("4.6.4: FC06 example DB800 outside DB 600-699 -> 02", "05 06 01 80 2B 1A", 2);
            raw_exc("4.6.4: FC16 example DB800 -> 02", "05 10 00 32 00 03 06 CD 09 DE 1A EF 2B", 2);
            raw_exc("4.6.4: FC15 example MB1144 outside MB 1000-1127 -> 02",
                    "05 0F 04 80 00 0C 02 CD 09", 2);
            raw_lmc("4.6.4: FC05 M1127.7 (last writable flag)", "05 05 03 FF FF 00",
                   "05 05 03 FF FF 00");
            raw_exc("4.6.4: FC05 M1128.0 -> 02", "05 05 04 00 FF 00", 2);
        } else {
            g_manual();
        }
    }
    if (group("tc")) {
        g_tc();
    }
    if (group("exceptions")) {
        g_exceptions();
    }
    if (group("broadcast") && !o.p464) {
        g_broadcast();
    }
    if (group("big")) {
        g_big();
    }
    if (group("extended")) {
        g_extended();
    }
    if (group("pause")) {
        if (o.control == NULL) {
            ok(false, "pause: needs --control FIFO");
        } else {
            g_pause();
        }
    }
    if (group("random") && o.random_ops > 0) {
        g_random();
    }
    printf("master_libmodbus: %.1f s\n", now_s() - t0);
    printf("%d passed, %d failed\n", passed, failed);
    modbus_close(ctx);
    modbus_free(ctx);
    return failed == 0 ? 0 : 1;
}
