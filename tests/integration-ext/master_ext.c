/* SPDX-License-Identifier: Apache-2.0 */
/* master_ext — libmodbus checks of the extended function set (docs/extended-functions.md) against a modcp
 * slave with configs/default.ini plus the scanner of tests/integration-ext/CMakeLists.txt:
 *   [scanner] start = 4096, entries = MW1000 QW256 DB801.DBW20 IW134 T100 C200 DB800.DBW160
 *
 *   master_ext --device PATH [--baud 115200] [--profile extended|cp341] [--verbose]
 *
 * extended: FC17 (modbus_report_slave_id), FC22 (modbus_mask_write_register), FC23
 *   (modbus_write_and_read_registers), all natively; the scanner through FC03/06/16/23
 *   (cross-checked through FC01 on the M / Q coil windows and FC03 on the DB scheme);
 *   raw requests for FC08 (counter values after known traffic incl. CRC-corrupted
 *   frames), FC11, FC12 (exact event log), FC43/14 (exact objects).
 * cp341 (function_set = cp341): every extended FC -> exception 01; FC08 sub-functions
 *   other than 0000 -> exception 03; the scanner addresses are plain DB registers.
 * Every check asserts bytes or values; the last line is "N passed, M failed". */
#define _GNU_SOURCE
#include <errno.h>
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

static modbus_t *ctx;
static int timeout_ms = 1500;

/* Write a frame (CRC appended here, or corrupted with bad_crc) straight to the line and
 * read up to want bytes of reply. Returns the bytes read. */
static int raw(const char *req_hex, bool bad_crc, uint8_t *rsp, size_t want, int wait_ms)
{
    int fd = modbus_get_socket(ctx);
    uint8_t buf[600];
    size_t n = hex(req_hex, buf, sizeof buf - 2);
    uint16_t crc = crc16(buf, n);
    buf[n++] = (uint8_t)(crc & 0xFF);
    buf[n++] = (uint8_t)((crc >> 8) ^ (bad_crc ? 0x5A : 0));
    usleep(5000); /* well above t3.5: a frame of its own */
    modbus_flush(ctx);
    if (write(fd, buf, n) != (ssize_t)n) {
        return -1;
    }
    return read_want(fd, rsp, want, wait_ms);
}

/* Raw request, the reply must be exactly expect_hex + its CRC. */
static void raw_expect(const char *name, const char *req_hex, const char *expect_hex)
{
    uint8_t exp[300], rsp[300];
    size_t el = hex(expect_hex, exp, sizeof exp - 2);
    uint16_t crc = crc16(exp, el);
    exp[el++] = (uint8_t)(crc & 0xFF);
    exp[el++] = (uint8_t)(crc >> 8);
    int n = raw(req_hex, false, rsp, el, timeout_ms);
    char got[900], want[900];
    fmt_hex(rsp, n > 0 ? (size_t)n : 0u, got, sizeof got);
    fmt_hex(exp, el, want, sizeof want);
    ok(n == (int)el && memcmp(rsp, exp, el) == 0, "%s: reply %s (expected %s)", name,
       n > 0 ? got : "none", want);
}

/* FC08 counter sub-function: its value, or -1. */
static int counter(uint8_t sub)
{
    char req[32];
    uint8_t rsp[8];
    snprintf(req, sizeof req, "05 08 00 %02X 00 00", sub);
    int n = raw(req, false, rsp, 8, timeout_ms);
    if (n != 8 || crc16(rsp, 8) != 0 || rsp[1] != 0x08 || rsp[3] != sub) {
        return -1;
    }
    return (rsp[4] << 8) | rsp[5];
}

/* ---- extended ------------------------------------------------------------------------ */

static void fc17(void)
{
    uint8_t id[MODBUS_MAX_PDU_LENGTH];
    int n = modbus_report_slave_id(ctx, sizeof id, id);
    const char *s = "modcp CP341-MODBUS " MODCP_VERSION; /* revision empty: the version */
    ok(n == 2 + (int)strlen(s) && id[0] == 5 && id[1] == 0xFF && memcmp(id + 2, s, strlen(s)) == 0,
       "FC17: %d bytes, slave id %02X, run indicator %02X, '%.*s'", n, n > 0 ? id[0] : 0,
       n > 1 ? id[1] : 0, n > 2 ? n - 2 : 0, (const char *)id + 2);
}

static void fc22(void)
{
    uint16_t r = 0;
    ok(modbus_write_register(ctx, 0x64, 0x0012) == 1, "FC06 DB800.DBW200 = 0012");
    ok(modbus_mask_write_register(ctx, 0x64, 0x00F2, 0x0025) == 1, "FC22 AND 00F2 OR 0025");
    ok(modbus_read_registers(ctx, 0x64, 1, &r) == 1 && r == 0x0017,
       "FC22 result %04X (Application Protocol example: 0017)", r);
    ok(modbus_mask_write_register(ctx, 0x64, 0xFF00, 0x1234) == 1 &&
           modbus_read_registers(ctx, 0x64, 1, &r) == 1 && r == 0x0034,
       "FC22 AND FF00 OR 1234 -> %04X (0034)", r);
    errno = 0;
    ok(modbus_mask_write_register(ctx, 0xC800, 0, 0) == -1 && errno == EMBXILADD,
       "FC22 DB900 outside the write limits -> exception 02 (%s)", modbus_strerror(errno));
}

static void fc23(void)
{
    uint16_t r[8] = {0};
    ok(modbus_write_registers(ctx, 0x70, 3, (const uint16_t[]){1, 2, 3}) == 3, "FC16 1 2 3");
    int n = modbus_write_and_read_registers(ctx, 0x71, 2, (const uint16_t[]){0xAAAA, 0xBBBB},
                                            0x70, 4, r);
    ok(n == 4 && r[0] == 1 && r[1] == 0xAAAA && r[2] == 0xBBBB && r[3] == 0,
       "FC23 write before read: %04X %04X %04X %04X (0001 AAAA BBBB 0000)", r[0], r[1], r[2], r[3]);
    /* both ranges checked first: a read across the end of DB 800 writes nothing */
    errno = 0;
    n = modbus_write_and_read_registers(ctx, 0x70, 1, (const uint16_t[]){0x5555}, 0x1FF, 2, r);
    ok(n == -1 && errno == EMBXILADD, "FC23 read across a DB boundary -> exception 02");
    ok(modbus_read_registers(ctx, 0x70, 1, r) == 1 && r[0] == 1, "... and nothing written (%04X)",
       r[0]);
    raw_expect("FC23 read quantity 126 -> exception 03", "05 17 00 00 00 7E 00 00 00 01 02 00 00",
               "05 97 03");
    raw_expect("FC23 write quantity 122 -> exception 03", "05 17 00 00 00 01 00 00 00 7A 02 00 00",
               "05 97 03");
    raw_expect("FC23 byte count mismatch -> exception 03", "05 17 00 00 00 01 00 00 00 01 04 00 00",
               "05 97 03");
}

static void scanner(void)
{
    /* 4096.. = MW1000 QW256 DB801.DBW20 IW134 T100 C200 DB800.DBW160 (default.ini values:
     * IB134 = 12 34, T100 = 1234, C200 = 9ABC, DB800.DBW160 = 8765) */
    uint16_t r[8] = {0};
    ok(modbus_write_registers(ctx, 4096, 3, (const uint16_t[]){0xA55A, 0x0F0F, 0xBEEF}) == 3,
       "scanner FC16: MW1000 QW256 DB801.DBW20");
    int n = modbus_read_registers(ctx, 4096, 7, r);
    ok(n == 7 && r[0] == 0xA55A && r[1] == 0x0F0F && r[2] == 0xBEEF && r[3] == 0x1234 &&
           r[4] == 0x1234 && r[5] == 0x9ABC && r[6] == 0x8765,
       "scanner FC03: %04X %04X %04X %04X %04X %04X %04X", r[0], r[1], r[2], r[3], r[4], r[5], r[6]);
    /* cross-checks: MW1000 = MB1000 MB1001 through FC01 coils 0..15 (M window @ MB1000),
     * QW256 through coils 2048..2063, DB801.DBW20 through the DB scheme (register 522) */
    uint8_t bits[16];
    uint16_t w = 0;
    bool good = modbus_read_bits(ctx, 0, 16, bits) == 16;
    for (int i = 0; i < 16; i++) {
        w |= (uint16_t)((bits[i] ? 1u : 0u) << (i < 8 ? 8 + i : i - 8));
    }
    ok(good && w == 0xA55A, "MW1000 through FC01 = %04X", w);
    w = 0;
    good = modbus_read_bits(ctx, 2048, 16, bits) == 16;
    for (int i = 0; i < 16; i++) {
        w |= (uint16_t)((bits[i] ? 1u : 0u) << (i < 8 ? 8 + i : i - 8));
    }
    ok(good && w == 0x0F0F, "QW256 through FC01 = %04X", w);
    ok(modbus_read_registers(ctx, 512 + 10, 1, r) == 1 && r[0] == 0xBEEF,
       "DB801.DBW20 through register 522 = %04X", r[0]);
    ok(modbus_write_register(ctx, 4096, 0x1111) == 1 && modbus_read_registers(ctx, 4096, 1, r) == 1 &&
           r[0] == 0x1111,
       "scanner FC06 MW1000 = %04X", r[0]);
    errno = 0;
    ok(modbus_write_register(ctx, 4099, 1) == -1 && errno == EMBXILADD, "scanner FC06 to IW134 -> 02");
    errno = 0;
    ok(modbus_write_register(ctx, 4100, 1) == -1 && errno == EMBXILADD, "scanner FC06 to T100 -> 02");
    errno = 0;
    ok(modbus_read_registers(ctx, 4095, 2, r) == -1 && errno == EMBXILADD,
       "read across the scanner's edge -> 02");
    /* FC22 and FC23 through the scanner */
    ok(modbus_mask_write_register(ctx, 4096, 0xFF00, 0x0022) == 1 &&
           modbus_read_registers(ctx, 4096, 1, r) == 1 && r[0] == 0x1122,
       "scanner FC22 MW1000 = %04X (1122)", r[0]);
    n = modbus_write_and_read_registers(ctx, 4097, 2, (const uint16_t[]){0x0101, 0x0202}, 4096, 4, r);
    ok(n == 4 && r[0] == 0x1122 && r[1] == 0x0101 && r[2] == 0x0202 && r[3] == 0x1234,
       "scanner FC23: %04X %04X %04X %04X", r[0], r[1], r[2], r[3]);
}

static void counters(void)
{
    uint8_t rsp[16];
    raw_expect("FC08 sub 0A clear counters", "05 08 00 0A 00 00", "05 08 00 0A 00 00");
    for (int k = 0; k < 3; k++) {
        raw_expect("FC03 good request", "05 03 00 50 00 02", "05 03 04 87 65 43 21");
    }
    for (int k = 0; k < 2; k++) {
        ok(raw("05 03 00 50 00 02", true, rsp, 5, 300) == 0, "CRC-corrupted frame: no reply");
    }
    ok(raw("07 03 00 50 00 02", false, rsp, 5, 300) == 0, "frame for slave 7: no reply");
    raw_expect("FC03 quantity 0 -> exception 03", "05 03 00 50 00 00", "05 83 03");
    int v = counter(0x0B);
    ok(v == 6, "FC08 0B bus messages = %d (3 + slave 7 + exception + itself)", v);
    v = counter(0x0C);
    ok(v == 2, "FC08 0C CRC errors = %d (2)", v);
    v = counter(0x0D);
    ok(v == 1, "FC08 0D exceptions = %d (1)", v);
    v = counter(0x0E);
    ok(v == 8, "FC08 0E slave messages = %d (3 + exc + 0B 0C 0D 0E)", v);
    v = counter(0x0F);
    ok(v == 0, "FC08 0F no response = %d (0)", v);
    v = counter(0x12);
    ok(v == 0, "FC08 12 overruns = %d (0)", v);
    /* FC11: 3 reads + 6 counter reads completed without exception */
    raw_expect("FC11 event counter", "05 0B", "05 0B 00 00 00 09");
    raw_expect("FC08 sub 02 diagnostic register", "05 08 00 02 00 00", "05 08 00 02 00 00");
    raw_expect("FC08 sub 00 echo", "05 08 00 00 A5 C3", "05 08 00 00 A5 C3");
    raw_expect("FC08 sub 05 -> exception 01", "05 08 00 05 00 00", "05 88 01");
}

static void event_log(void)
{
    raw_expect("FC08 sub 01 restart, clear log", "05 08 00 01 FF 00", "05 08 00 01 FF 00");
    raw_expect("FC03 good request", "05 03 00 50 00 02", "05 03 04 87 65 43 21");
    raw_expect("FC06 DB900 -> exception 02", "05 06 C8 00 00 01", "05 86 02");
    /* newest first: 80 (this FC12), 41 80 (exception 2), 40 80 (FC03), 00 (restart) */
    raw_expect("FC12 event log", "05 0C", "05 0C 0C 00 00 00 01 00 03 80 41 80 40 80 00");
}

static void fc43(void)
{
    /* object 02: the configuration leaves the revision empty, modcp's version answers */
    char rev[64], want[200];
    int n = snprintf(rev, sizeof rev, "02 %02X", (unsigned)strlen(MODCP_VERSION));
    for (const char *c = MODCP_VERSION; *c != '\0' && n > 0 && n < (int)sizeof rev; c++) {
        n += snprintf(rev + n, sizeof rev - (size_t)n, " %02X", (unsigned)(uint8_t)*c);
    }
    snprintf(want, sizeof want, "05 2B 0E 01 82 00 00 03 00 05 6D 6F 64 63 70 01 0C 43 50 33 34 31 "
             "2D 4D 4F 44 42 55 53 %s", rev);
    raw_expect("FC43/14 basic stream", "05 2B 0E 01 00", want);
    snprintf(want, sizeof want, "05 2B 0E 02 82 00 00 02 %s 06 0E 6D 61 6E 75 61 6C 20 65 78 61 "
             "6D 70 6C 65", rev);
    raw_expect("FC43/14 regular from 02", "05 2B 0E 02 02", want);
    raw_expect("FC43/14 individual 06", "05 2B 0E 04 06",
               "05 2B 0E 04 82 00 00 01 06 0E 6D 61 6E 75 61 6C 20 65 78 61 6D 70 6C 65");
    raw_expect("FC43/14 individual 05 -> exception 02", "05 2B 0E 04 05", "05 AB 02");
    raw_expect("FC43/14 ReadDevId 07 -> exception 03", "05 2B 0E 07 00", "05 AB 03");
    raw_expect("FC43/13 -> exception 01", "05 2B 0D 01 00", "05 AB 01");
}

/* ---- cp341 ---------------------------------------------------------------------------- */

static void cp341(void)
{
    uint8_t id[MODBUS_MAX_PDU_LENGTH];
    uint16_t r[4];
    errno = 0;
    ok(modbus_report_slave_id(ctx, sizeof id, id) == -1 && errno == EMBXILFUN, "cp341: FC17 -> 01");
    errno = 0;
    ok(modbus_mask_write_register(ctx, 0x64, 0, 0) == -1 && errno == EMBXILFUN, "cp341: FC22 -> 01");
    errno = 0;
    ok(modbus_write_and_read_registers(ctx, 0x70, 1, (const uint16_t[]){1}, 0x70, 1, r) == -1 &&
           errno == EMBXILFUN,
       "cp341: FC23 -> 01");
    raw_expect("cp341: FC11 -> 01", "05 0B", "05 8B 01");
    raw_expect("cp341: FC12 -> 01", "05 0C", "05 8C 01");
    raw_expect("cp341: FC43 -> 01", "05 2B 0E 01 00", "05 AB 01");
    raw_expect("cp341: FC08 sub 0B -> 03", "05 08 00 0B 00 00", "05 88 03");
    raw_expect("cp341: FC08 sub 04 -> 03", "05 08 00 04 00 00", "05 88 03");
    raw_expect("cp341: FC08 sub 00 echo", "05 08 00 00 12 34", "05 08 00 00 12 34");
    /* no scanner: register 4096 = DB 808, which does not exist -> 04 */
    errno = 0;
    ok(modbus_read_registers(ctx, 4096, 1, r) == -1 && errno == EMBXSFAIL,
       "cp341: register 4096 is DB808 (missing) -> 04, not the scanner");
}

int main(int argc, char **argv)
{
    const char *device = NULL;
    const char *profile = "extended";
    int baud = 115200;
    static const struct option lo[] = {{"device", 1, 0, 'd'}, {"baud", 1, 0, 'b'},
                                       {"profile", 1, 0, 'p'}, {"verbose", 0, 0, 'v'},
                                       {0, 0, 0, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "d:b:p:v", lo, NULL)) != -1) {
        switch (c) {
        case 'd': device = optarg; break;
        case 'b': baud = atoi(optarg); break;
        case 'p': profile = optarg; break;
        case 'v': verbose = true; break;
        default:
            fprintf(stderr, "usage: master_ext --device PATH [--baud N] [--profile extended|cp341]\n");
            return 2;
        }
    }
    if (device == NULL) {
        fprintf(stderr, "usage: master_ext --device PATH [--baud N] [--profile extended|cp341]\n");
        return 2;
    }
    ctx = modbus_new_rtu(device, baud, 'E', 8, 1);
    if (ctx == NULL || modbus_set_slave(ctx, 5) != 0 || modbus_connect(ctx) != 0) {
        fprintf(stderr, "master_ext: %s: %s\n", device, modbus_strerror(errno));
        printf("0 passed, 1 failed\n");
        return 1;
    }
    modbus_set_response_timeout(ctx, (uint32_t)(timeout_ms / 1000),
                                (uint32_t)((timeout_ms % 1000) * 1000));
    printf("master_ext: %s %d, profile %s\n", device, baud, profile);
    if (strcmp(profile, "cp341") == 0) {
        cp341();
    } else {
        fc17();
        fc22();
        fc23();
        scanner();
        counters();
        event_log();
        fc43();
    }
    modbus_close(ctx);
    modbus_free(ctx);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
