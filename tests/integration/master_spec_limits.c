/* SPDX-License-Identifier: Apache-2.0 */
/* master_spec_limits — the quantity boundaries a libmodbus master expects (the logic of
 * libmodbus's tests/unit-test-client.c: its "too many data" checks and its crafted
 * requests of test_server(), written anew here), against a modcp slave configured with
 * configs/spec-limits.ini (protocol.quantity_limits = spec, libmodbus's unit-test
 * addresses, slave 17). Issue 13 item 7.
 *
 *   master_spec_limits --device PATH [--baud 9600] [--parity E|O|N]
 *                      [--limits spec|manual] [--timeout-ms 2000] [--verbose]
 *
 * --limits spec (the slave runs quantity_limits = spec), per function code:
 *   - the maximum of the Modbus application protocol through the libmodbus API
 *     (FC01/02 2000 bits, FC03/04 125 registers, FC15 1968 bits, FC16 123 registers,
 *     FC23 read 125 / write 121): answered, every reply within the 256-byte RTU ADU,
 *     values as written / as in unit-test.h;
 *   - maximum + 1 and 0 as raw requests (libmodbus refuses to send them itself):
 *     exception 03, nothing written, and the next request is answered (no desync);
 *   - FC15 / FC16 with a byte count that does not match the quantity (test_server's
 *     crafted writes): exception 03.
 * --limits manual (the slave runs the default, quantity_limits = manual): the reason the
 *   option exists. A 126-register read is answered with a 257-byte reply, which libmodbus
 *   refuses to receive; 128 registers get exception 03 (the manual's limit is 127).
 *
 * The last line is "N passed, M failed"; the exit code is 0 only when nothing failed. */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <modbus.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "master_util.h"

#define SLAVE 17
/* libmodbus tests/unit-test.h addresses and values (configs/spec-limits.ini) */
#define BITS_ADDR 0x130
#define INPUT_BITS_ADDR 0x1C4
#define REGS_ADDR 0x160
#define INPUT_REGS_ADDR 0x108
static const uint8_t bits_tab[] = {0xCD, 0x6B, 0xB2, 0x0E, 0x1B}; /* 37 bits */
#define BITS_NB 37
static const uint8_t input_bits_tab[] = {0xAC, 0xDB, 0x35}; /* 22 bits */
#define INPUT_BITS_NB 22
static const uint16_t regs_tab[] = {0x022B, 0x0001, 0x0064};
#define INPUT_REG_VALUE 0x000A
#define RTU_ADU_MAX 256

static modbus_t *ctx;

/* A raw request (slave, fc, ...; libmodbus appends the CRC): the ADU length of the
 * confirmation (-1: libmodbus could not receive it); the reply in rsp. */
static int raw(const uint8_t *req, int len, uint8_t *rsp)
{
    if (modbus_send_raw_request(ctx, req, len) != len + 2) {
        return -2;
    }
    return modbus_receive_confirmation(ctx, rsp);
}

/* Exception 03 to a raw request. */
static void expect_exc03(const char *what, const uint8_t *req, int len)
{
    uint8_t rsp[MODBUS_RTU_MAX_ADU_LENGTH];
    int rc = raw(req, len, rsp);
    ok(rc == 5 && rsp[0] == SLAVE && rsp[1] == (req[1] | 0x80) && rsp[2] == 0x03,
       "%s: exception 03 (rc %d, %02X %02X)", what, rc, rc > 1 ? rsp[1] : 0, rc > 2 ? rsp[2] : 0);
}

static void read_req(uint8_t *req, uint8_t fc, uint16_t addr, uint16_t qty)
{
    req[0] = SLAVE;
    req[1] = fc;
    req[2] = (uint8_t)(addr >> 8);
    req[3] = (uint8_t)addr;
    req[4] = (uint8_t)(qty >> 8);
    req[5] = (uint8_t)qty;
}

/* The link is in step: a one-register read is answered with the unit-test value. */
static void in_step(const char *after)
{
    uint16_t v = 0;
    int rc = modbus_read_input_registers(ctx, INPUT_REGS_ADDR, 1, &v);
    ok(rc == 1 && v == INPUT_REG_VALUE, "after %s: the next request is answered (rc %d, %04X)",
       after, rc, v);
}

static bool bit_of(const uint8_t *tab, int i)
{
    return (tab[i / 8] >> (i % 8)) & 1u;
}

/* ---- spec ----------------------------------------------------------------------------- */

static void check_values(void)
{
    uint8_t b[64];
    uint16_t r[4];
    int rc = modbus_read_bits(ctx, BITS_ADDR, BITS_NB, b);
    bool same = rc == BITS_NB;
    for (int i = 0; same && i < BITS_NB; i++) {
        same = b[i] == bit_of(bits_tab, i);
    }
    ok(same, "FC01 %d coils at 0x130 = unit-test.h UT_BITS_TAB (rc %d)", BITS_NB, rc);
    rc = modbus_read_input_bits(ctx, INPUT_BITS_ADDR, INPUT_BITS_NB, b);
    same = rc == INPUT_BITS_NB;
    for (int i = 0; same && i < INPUT_BITS_NB; i++) {
        same = b[i] == bit_of(input_bits_tab, i);
    }
    ok(same, "FC02 %d inputs at 0x1C4 = UT_INPUT_BITS_TAB (rc %d)", INPUT_BITS_NB, rc);
    rc = modbus_read_registers(ctx, REGS_ADDR, 3, r);
    ok(rc == 3 && memcmp(r, regs_tab, sizeof regs_tab) == 0,
       "FC03 3 registers at 0x160 = UT_REGISTERS_TAB (rc %d)", rc);
    in_step("FC03");
}

/* FC01..04: the maximum answered (within the RTU ADU), maximum + 1 and 0 refused. */
static void check_reads(void)
{
    static const struct {
        uint8_t fc;
        uint16_t addr, max;
        const char *name;
    } reads[] = {
        {0x01, BITS_ADDR, MODBUS_MAX_READ_BITS, "FC01 read coils"},
        {0x02, INPUT_BITS_ADDR, MODBUS_MAX_READ_BITS, "FC02 read discrete inputs"},
        {0x03, REGS_ADDR, MODBUS_MAX_READ_REGISTERS, "FC03 read holding registers"},
        {0x04, INPUT_REGS_ADDR, MODBUS_MAX_READ_REGISTERS, "FC04 read input registers"},
    };
    for (size_t k = 0; k < sizeof reads / sizeof reads[0]; k++) {
        uint8_t req[6];
        uint8_t rsp[MODBUS_RTU_MAX_ADU_LENGTH];
        char what[96];
        bool bits = reads[k].fc <= 2;
        int data = bits ? (reads[k].max + 7) / 8 : 2 * reads[k].max;
        read_req(req, reads[k].fc, reads[k].addr, reads[k].max);
        int rc = raw(req, 6, rsp);
        ok(rc == 5 + data && rc <= RTU_ADU_MAX && rsp[1] == reads[k].fc && rsp[2] == data,
           "%s %u (the maximum): answered, %d-byte reply <= %d (rc %d)", reads[k].name,
           reads[k].max, 5 + data, RTU_ADU_MAX, rc);
        /* and through the API, with the unit-test values at its start */
        uint8_t b[MODBUS_MAX_READ_BITS];
        uint16_t r[MODBUS_MAX_READ_REGISTERS];
        switch (reads[k].fc) {
        case 0x01: rc = modbus_read_bits(ctx, reads[k].addr, reads[k].max, b); break;
        case 0x02: rc = modbus_read_input_bits(ctx, reads[k].addr, reads[k].max, b); break;
        case 0x03: rc = modbus_read_registers(ctx, reads[k].addr, reads[k].max, r); break;
        default: rc = modbus_read_input_registers(ctx, reads[k].addr, reads[k].max, r); break;
        }
        bool first = reads[k].fc == 0x01   ? b[0] == bit_of(bits_tab, 0) && b[36] == bit_of(bits_tab, 36)
                     : reads[k].fc == 0x02 ? b[0] == bit_of(input_bits_tab, 0) && b[21] == bit_of(input_bits_tab, 21)
                     : reads[k].fc == 0x03 ? r[0] == regs_tab[0] && r[2] == regs_tab[2]
                                           : r[0] == INPUT_REG_VALUE;
        ok(rc == reads[k].max && first, "%s %u through modbus_read_*: rc %d, unit-test values",
           reads[k].name, reads[k].max, rc);
        snprintf(what, sizeof what, "%s %u (maximum + 1)", reads[k].name, reads[k].max + 1);
        read_req(req, reads[k].fc, reads[k].addr, (uint16_t)(reads[k].max + 1));
        expect_exc03(what, req, 6);
        in_step(what);
        snprintf(what, sizeof what, "%s 0", reads[k].name);
        read_req(req, reads[k].fc, reads[k].addr, 0);
        expect_exc03(what, req, 6);
        in_step(what);
    }
}

/* A write request fc at addr with quantity qty, byte count bc and bc data bytes. */
static int write_req(uint8_t *req, uint8_t fc, uint16_t addr, uint16_t qty, uint8_t bc)
{
    read_req(req, fc, addr, qty);
    req[6] = bc;
    for (int i = 0; i < bc; i++) {
        req[7 + i] = (uint8_t)(0x5A ^ i);
    }
    return 7 + bc;
}

static void check_fc15(void)
{
    static uint8_t pattern[MODBUS_MAX_WRITE_BITS], back[MODBUS_MAX_WRITE_BITS];
    for (int i = 0; i < MODBUS_MAX_WRITE_BITS; i++) {
        pattern[i] = (uint8_t)((i * 7 + i / 5) & 1);
    }
    int rc = modbus_write_bits(ctx, BITS_ADDR, MODBUS_MAX_WRITE_BITS, pattern);
    ok(rc == MODBUS_MAX_WRITE_BITS, "FC15 write coils 1968 (the maximum): rc %d", rc);
    rc = modbus_read_bits(ctx, BITS_ADDR, MODBUS_MAX_WRITE_BITS, back);
    ok(rc == MODBUS_MAX_WRITE_BITS && memcmp(back, pattern, sizeof back) == 0,
       "FC15 1968: read back equal (rc %d)", rc);
    uint8_t req[300];
    int n = write_req(req, 0x0F, BITS_ADDR, MODBUS_MAX_WRITE_BITS + 1, 6);
    expect_exc03("FC15 1969 coils (maximum + 1), byte count 6", req, n);
    n = write_req(req, 0x0F, BITS_ADDR, MODBUS_MAX_WRITE_BITS + 1, 247);
    expect_exc03("FC15 1969 coils (maximum + 1), byte count 247", req, n);
    n = write_req(req, 0x0F, BITS_ADDR, MODBUS_MAX_WRITE_BITS, 6);
    expect_exc03("FC15 1968 coils with byte count 6 (not 246)", req, n);
    n = write_req(req, 0x0F, BITS_ADDR, 0, 0);
    expect_exc03("FC15 0 coils", req, n);
    rc = modbus_read_bits(ctx, BITS_ADDR, MODBUS_MAX_WRITE_BITS, back);
    ok(rc == MODBUS_MAX_WRITE_BITS && memcmp(back, pattern, sizeof back) == 0,
       "FC15 after the refused writes: nothing written (rc %d)", rc);
    uint8_t ut[BITS_NB];
    for (int i = 0; i < BITS_NB; i++) {
        ut[i] = bit_of(bits_tab, i);
    }
    ok(modbus_write_bits(ctx, BITS_ADDR, BITS_NB, ut) == BITS_NB, "FC15: UT_BITS_TAB restored");
}

static void check_fc16(void)
{
    uint16_t pattern[MODBUS_MAX_WRITE_REGISTERS], back[MODBUS_MAX_WRITE_REGISTERS];
    for (int i = 0; i < MODBUS_MAX_WRITE_REGISTERS; i++) {
        pattern[i] = (uint16_t)(0xA500 + i * 3);
    }
    int rc = modbus_write_registers(ctx, REGS_ADDR, MODBUS_MAX_WRITE_REGISTERS, pattern);
    ok(rc == MODBUS_MAX_WRITE_REGISTERS, "FC16 write registers 123 (the maximum): rc %d", rc);
    rc = modbus_read_registers(ctx, REGS_ADDR, MODBUS_MAX_WRITE_REGISTERS, back);
    ok(rc == MODBUS_MAX_WRITE_REGISTERS && memcmp(back, pattern, sizeof back) == 0,
       "FC16 123: read back equal (rc %d)", rc);
    uint8_t req[300];
    int n = write_req(req, 0x10, REGS_ADDR, MODBUS_MAX_WRITE_REGISTERS + 1, 6);
    expect_exc03("FC16 124 registers (maximum + 1), byte count 6", req, n);
    n = write_req(req, 0x10, REGS_ADDR, MODBUS_MAX_WRITE_REGISTERS, 6);
    expect_exc03("FC16 123 registers with byte count 6 (not 246)", req, n);
    n = write_req(req, 0x10, REGS_ADDR, 0, 0);
    expect_exc03("FC16 0 registers", req, n);
    rc = modbus_read_registers(ctx, REGS_ADDR, MODBUS_MAX_WRITE_REGISTERS, back);
    ok(rc == MODBUS_MAX_WRITE_REGISTERS && memcmp(back, pattern, sizeof back) == 0,
       "FC16 after the refused writes: nothing written (rc %d)", rc);
    ok(modbus_write_registers(ctx, REGS_ADDR, 3, regs_tab) == 3, "FC16: UT_REGISTERS_TAB restored");
}

/* FC23 read rqty at REGS_ADDR, write wqty at REGS_ADDR with byte count bc. */
static int rw_req(uint8_t *req, uint16_t rqty, uint16_t wqty, uint8_t bc)
{
    read_req(req, 0x17, REGS_ADDR, rqty);
    req[6] = (uint8_t)(REGS_ADDR >> 8);
    req[7] = (uint8_t)REGS_ADDR;
    req[8] = (uint8_t)(wqty >> 8);
    req[9] = (uint8_t)wqty;
    req[10] = bc;
    for (int i = 0; i < bc; i++) {
        req[11 + i] = (uint8_t)(0x12 + i);
    }
    return 11 + bc;
}

static void check_fc23(void)
{
    uint16_t src[MODBUS_MAX_WR_WRITE_REGISTERS], dest[MODBUS_MAX_WR_READ_REGISTERS];
    for (int i = 0; i < MODBUS_MAX_WR_WRITE_REGISTERS; i++) {
        src[i] = (uint16_t)(0x3C00 + i);
    }
    int rc = modbus_write_and_read_registers(ctx, REGS_ADDR, MODBUS_MAX_WR_WRITE_REGISTERS, src,
                                             REGS_ADDR, MODBUS_MAX_WR_READ_REGISTERS, dest);
    ok(rc == MODBUS_MAX_WR_READ_REGISTERS && memcmp(dest, src, sizeof src) == 0,
       "FC23 write 121 / read 125 (the maxima): rc %d, the write read back", rc);
    uint8_t req[300];
    int n = rw_req(req, MODBUS_MAX_WR_READ_REGISTERS + 1, 1, 2);
    expect_exc03("FC23 read 126 (maximum + 1)", req, n);
    in_step("FC23 read 126");
    n = rw_req(req, 0, 1, 2);
    expect_exc03("FC23 read 0", req, n);
    n = rw_req(req, 1, MODBUS_MAX_WR_WRITE_REGISTERS + 1, 2);
    expect_exc03("FC23 write 122 (maximum + 1)", req, n);
    n = rw_req(req, 1, 0, 0);
    expect_exc03("FC23 write 0", req, n);
    uint16_t back[MODBUS_MAX_WR_WRITE_REGISTERS];
    rc = modbus_read_registers(ctx, REGS_ADDR, MODBUS_MAX_WR_WRITE_REGISTERS, back);
    ok(rc == MODBUS_MAX_WR_WRITE_REGISTERS && memcmp(back, src, sizeof src) == 0,
       "FC23 after the refused requests: nothing written (rc %d)", rc);
    ok(modbus_write_registers(ctx, REGS_ADDR, 3, regs_tab) == 3, "FC23: UT_REGISTERS_TAB restored");
}

/* ---- manual --------------------------------------------------------------------------- */

static void check_manual(void)
{
    uint8_t req[6];
    uint8_t rsp[MODBUS_RTU_MAX_ADU_LENGTH];
    read_req(req, 0x03, REGS_ADDR, 126);
    int rc = raw(req, 6, rsp);
    ok(rc == -1, "manual: FC03 126 registers is answered with 257 bytes, which libmodbus "
                 "cannot receive (rc %d, %s)", rc, rc == -1 ? modbus_strerror(errno) : "-");
    usleep(300000);
    modbus_flush(ctx);
    in_step("manual FC03 126 (after a flush)");
    read_req(req, 0x03, REGS_ADDR, 128);
    expect_exc03("manual: FC03 128 registers (the manual's maximum 127 + 1)", req, 6);
    read_req(req, 0x03, REGS_ADDR, 125);
    rc = raw(req, 6, rsp);
    ok(rc == 255, "manual: FC03 125 registers answered (rc %d)", rc);
}

static int usage(void)
{
    fprintf(stderr, "usage: master_spec_limits --device PATH [--baud 9600] [--parity E|O|N] "
                    "[--limits spec|manual] [--timeout-ms 2000] [--verbose]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *device = NULL;
    int baud = 9600;
    char parity = 'E';
    bool spec = true;
    int timeout_ms = 2000;
    static const struct option lo[] = {
        {"device", required_argument, 0, 'd'}, {"baud", required_argument, 0, 'b'},
        {"parity", required_argument, 0, 'p'}, {"limits", required_argument, 0, 'l'},
        {"timeout-ms", required_argument, 0, 't'}, {"verbose", no_argument, 0, 'v'},
        {0, 0, 0, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (c) {
        case 'd': device = optarg; break;
        case 'b': baud = atoi(optarg); break;
        case 'p': parity = optarg[0]; break;
        case 'l':
            if (strcmp(optarg, "manual") == 0) {
                spec = false;
            } else if (strcmp(optarg, "spec") != 0) {
                return usage();
            }
            break;
        case 't': timeout_ms = atoi(optarg); break;
        case 'v': verbose = true; break;
        default: return usage();
        }
    }
    if (device == NULL) {
        return usage();
    }
    ctx = modbus_new_rtu(device, baud, parity, 8, 1);
    if (ctx == NULL || modbus_set_slave(ctx, SLAVE) != 0 || modbus_connect(ctx) != 0) {
        fprintf(stderr, "master_spec_limits: %s: %s\n", device, modbus_strerror(errno));
        printf("0 passed, 1 failed\n");
        return 1;
    }
    modbus_set_response_timeout(ctx, (uint32_t)(timeout_ms / 1000),
                                (uint32_t)((timeout_ms % 1000) * 1000));
    printf("master_spec_limits: %s %d 8%c1 slave %d, quantity_limits = %s\n", device, baud, parity,
           SLAVE, spec ? "spec" : "manual");
    fflush(stdout);
    check_values();
    if (spec) {
        check_reads();
        check_fc15();
        check_fc16();
        check_fc23();
        check_values();
    } else {
        check_manual();
    }
    modbus_close(ctx);
    modbus_free(ctx);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
