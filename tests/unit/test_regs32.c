/* SPDX-License-Identifier: Apache-2.0 */
/* The 32-bit register extension ([ASCII-32] §4.5, docs/mapping.md), end to end through the core in RTU
 * and in ASCII: three ranges int16 -> DB2.DBW, int32 -> DB3.DBD, float -> DB4.DBD
 * (3000-4999, 5000-5099, 7000-9999 as in the manual's example) replace the DB-offset
 * scheme of FC03/06/16; FC04 keeps it. Every worked example of [ASCII-32] §4.5 / §9.4, §9.8,
 * §9.12 and the address table of §9.4, the 32-bit ASCII vectors of [ASCII-32] §2, counts in
 * 32-bit entities, FC06 with 4 data bytes, straddling ranges, the quantity limits
 * (ASCII 62 / 61, RTU 63 / 63, modcp decision), IEEE-754 floats big-endian as stored. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "ascii_world.h"
#include "frames.h"
#include "modcp/map.h"
#include "modcp/quantity.h"
#include "map_internal.h"
#include "quantity_internal.h"

static world_t *rtu32(void)
{
    modcp_params_t p;
    world_example_params(&p);
    regs32_example_ranges(&p);
    return ascii_world_started(&p);
}

static world_t *ascii32(void)
{
    modcp_params_t p;
    ascii_example_params(&p);
    regs32_example_ranges(&p);
    return ascii_world_started(&p);
}

/* RTU request from spaced hex without CRC; expect the reply (CRC appended). */
static void rtu_expect(world_t *w, const char *req, const char *reply)
{
    uint8_t b[300];
    size_t n = hex_frame(req, b, sizeof b);
    uint16_t len = world_request_raw(w, b, n, 200);
    uint8_t e[300];
    size_t m = hex_frame(reply, e, sizeof e);
    m = add_crc(e, m);
    assert_int_equal(len, m);
    assert_memory_equal(w->fake.tx, e, m);
}

static void rtu_expect_exception(world_t *w, const uint8_t *b, size_t n, uint8_t code,
                                 modcp_event_t ev)
{
    assert_int_equal(world_request_raw(w, b, n, 2000), 5);
    assert_int_equal(w->fake.tx[1], b[1] | 0x80);
    assert_int_equal(w->fake.tx[2], code);
    assert_int_equal(world_last_event(w), ev);
}

static void ascii_expect(world_t *w, const char *req, const char *reply)
{
    assert_int_equal(ascii_request(w, req, 200), strlen(reply));
    assert_string_equal(ascii_reply(w), reply);
}

/* ---- [ASCII-32] §4.5 worked examples, RTU ------------------------------------------- */

/* FC03 16-bit: 0BEAH = 3050 -> DB2.DBW100, 2 registers, byte count 4 */
static void test_fc03_int16_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    memcpy(world_db(w, 2) + 100, "\x87\x65\x43\x21", 4);
    rtu_expect(w, "05 03 0B EA 00 02", "05 03 04 87 65 43 21");
    ascii_world_free(w);
}

/* FC03 32-bit (§9.4): 1B59H = 7001 -> DB4.DBD4 and DBD8; count = 2 registers of
 * 4 bytes, byte count 08; DBD4 bytes 1..4 first */
static void test_fc03_float_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    memcpy(world_db(w, 4) + 4, "\xCD\xDC\xAB\xBA\x11\x22\x33\x44", 8);
    rtu_expect(w, "05 03 1B 59 00 02", "05 03 08 CD DC AB BA 11 22 33 44");
    ascii_world_free(w);
}

/* FC06 16-bit: 0D37H = 3383 -> (3383 - 3000) x 2 = DB2.DBW766 */
static void test_fc06_int16_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    rtu_expect(w, "05 06 0D 37 2B 1A", "05 06 0D 37 2B 1A");
    assert_memory_equal(world_db(w, 2) + 766, "\x2B\x1A", 2);
    assert_memory_equal(world_db(w, 2) + 768, "\x00\x00", 2);
    ascii_world_free(w);
}

/* FC06 32-bit (§9.8): 1B5AH = 7002 -> DB4.DBD8 = 12233445H; 4 data bytes, echoed */
static void test_fc06_float_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    rtu_expect(w, "05 06 1B 5A 12 23 34 45", "05 06 1B 5A 12 23 34 45");
    assert_memory_equal(world_db(w, 4) + 8, "\x12\x23\x34\x45", 4);
    assert_memory_equal(world_db(w, 4) + 4, "\x00\x00\x00\x00", 4);
    assert_memory_equal(world_db(w, 4) + 12, "\x00\x00\x00\x00", 4);
    ascii_world_free(w);
}

/* The same FC06 32-bit request in interference suppression (modem mode: the frame ends at
 * its CRC, not by t3.5): its 4 data bytes make it 10 characters, 2 more than FC06's usual
 * form, so a wrong CRC at the 8th character is no end of the frame; the 16-bit form on
 * the same slave still ends at its CRC. */
static void test_fc06_32bit_in_modem_mode(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    regs32_example_ranges(&p);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    world_t *w = ascii_world_started(&p);
    rtu_expect(w, "05 06 1B 5A 12 23 34 45", "05 06 1B 5A 12 23 34 45");
    assert_memory_equal(world_db(w, 4) + 8, "\x12\x23\x34\x45", 4);
    rtu_expect(w, "05 06 0D 37 2B 1A", "05 06 0D 37 2B 1A");
    assert_memory_equal(world_db(w, 2) + 766, "\x2B\x1A", 2);
    ascii_world_free(w);
}

/* FC16 16-bit: 0C1CH = 3100 -> DB2.DBW200, 202, 204 */
static void test_fc16_int16_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    rtu_expect(w, "05 10 0C 1C 00 03 06 CD 09 DE 1A EF 2B", "05 10 0C 1C 00 03");
    assert_memory_equal(world_db(w, 2) + 200, "\xCD\x09\xDE\x1A\xEF\x2B", 6);
    ascii_world_free(w);
}

/* FC16 32-bit (§9.12): 138BH = 5003 -> DB3.DBD12 = 3A09DE1AH, DBD16 = 01020304H */
static void test_fc16_int32_example(void **state)
{
    (void)state;
    world_t *w = rtu32();
    rtu_expect(w, "05 10 13 8B 00 02 08 3A 09 DE 1A 01 02 03 04", "05 10 13 8B 00 02");
    assert_memory_equal(world_db(w, 3) + 12, "\x3A\x09\xDE\x1A\x01\x02\x03\x04", 8);
    assert_memory_equal(world_db(w, 3) + 8, "\x00\x00\x00\x00", 4);
    assert_memory_equal(world_db(w, 3) + 20, "\x00\x00\x00\x00", 4);
    ascii_world_free(w);
}

/* §9.4 address table: each address read as one register lands on its operand
 * (9900 -> DB4.DBD11600; the manual prints DBD7600, a doc error) */
static void test_address_table(void **state)
{
    (void)state;
    world_t *w = rtu32();
    static const struct {
        uint16_t reg;
        uint16_t db;
        uint16_t offset;
        uint8_t bytes;
    } rows[] = {
        {3127, 2, 254, 2},  {4900, 2, 3800, 2}, {5000, 3, 0, 4},
        {5090, 3, 360, 4},  {7100, 4, 400, 4},  {9900, 4, 11600, 4},
        {3000, 2, 0, 2},    {4999, 2, 3998, 2}, /* the ends of the three ranges */
        {5099, 3, 396, 4},  {7000, 4, 0, 4},    {9999, 4, 11996, 4},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        uint8_t *d = world_db(w, rows[k].db) + rows[k].offset;
        memcpy(d, "\xA1\xB2\xC3\xD4", rows[k].bytes);
        uint8_t req[] = {5, 3, (uint8_t)(rows[k].reg >> 8), (uint8_t)rows[k].reg, 0, 1};
        assert_int_equal(world_request_raw(w, req, sizeof req, 200), 5 + rows[k].bytes);
        assert_int_equal(w->fake.tx[2], rows[k].bytes);
        assert_memory_equal(&w->fake.tx[3], "\xA1\xB2\xC3\xD4", rows[k].bytes);
        memset(d, 0, rows[k].bytes);
        /* and the mapping on its own */
        modcp_operand_t o;
        assert_int_equal(modcp_map_regs(&w->cp.params, &w->cp.areas, 3, rows[k].reg, 1, &o),
                         MODCP_EV_NONE);
        assert_int_equal(o.db, rows[k].db);
        assert_int_equal(o.offset, rows[k].offset);
        assert_int_equal(o.count, rows[k].bytes);
    }
    ascii_world_free(w);
}

/* ---- the same in ASCII: the 32-bit vectors of [ASCII-32] §2 ---------------------------- */

static void test_ascii_vectors(void **state)
{
    (void)state;
    world_t *w = ascii32();
    memcpy(world_db(w, 4) + 4, "\xCD\xDC\xAB\xBA\x11\x22\x33\x44", 8);
    ascii_expect(w, ":05031B59000282\r\n", ":050308CDDCABBA1122334438\r\n");
    ascii_expect(w, ":05061B5A12233445D2\r\n", ":05061B5A12233445D2\r\n");
    assert_memory_equal(world_db(w, 4) + 8, "\x12\x23\x34\x45", 4);
    ascii_expect(w, ":0510138B0002083A09DE1A01020304FE\r\n", ":0510138B00024B\r\n");
    assert_memory_equal(world_db(w, 3) + 12, "\x3A\x09\xDE\x1A\x01\x02\x03\x04", 8);
    /* the 16-bit examples of §4.5 through ASCII */
    memcpy(world_db(w, 2) + 100, "\x87\x65\x43\x21", 4);
    ascii_expect(w, ascii_frame_hex("05 03 0B EA 00 02"), ":05030487654321A4\r\n");
    ascii_expect(w, ":05060D372B1A6C\r\n", ":05060D372B1A6C\r\n");
    assert_memory_equal(world_db(w, 2) + 766, "\x2B\x1A", 2);
    ascii_expect(w, ":05100C1C000306CD09DE1AEF2BD2\r\n", ":05100C1C0003C0\r\n");
    assert_memory_equal(world_db(w, 2) + 200, "\xCD\x09\xDE\x1A\xEF\x2B", 6);
    assert_int_equal(w->cp.diag.buffer_len, 0);
    ascii_world_free(w);
}

/* ---- values: IEEE-754 single and int32, big-endian as stored -------------------- */

static void test_float_and_int32_values(void **state)
{
    (void)state;
    world_t *w = rtu32();
    /* 7000 = 3.14159274f (40490FDBH), 7001 = -1.5f (BFC00000H) */
    rtu_expect(w, "05 10 1B 58 00 02 08 40 49 0F DB BF C0 00 00", "05 10 1B 58 00 02");
    const uint8_t *d = world_db(w, 4);
    float f0, f1;
    uint32_t u = (uint32_t)d[0] << 24 | (uint32_t)d[1] << 16 | (uint32_t)d[2] << 8 | d[3];
    memcpy(&f0, &u, 4);
    u = (uint32_t)d[4] << 24 | (uint32_t)d[5] << 16 | (uint32_t)d[6] << 8 | d[7];
    memcpy(&f1, &u, 4);
    assert_true(f0 == 3.14159274f);
    assert_true(f1 == -1.5f);
    /* 5001 = -2 (FFFFFFFEH), read back with 5000..5002 */
    rtu_expect(w, "05 06 13 89 FF FF FF FE", "05 06 13 89 FF FF FF FE");
    memcpy(world_db(w, 3) + 8, "\x7F\xFF\xFF\xFF", 4);
    rtu_expect(w, "05 03 13 88 00 03",
               "05 03 0C 00 00 00 00 FF FF FF FE 7F FF FF FF");
    ascii_world_free(w);
}

/* ---- errors ------------------------------------------------------------------- */

/* a request may not straddle ranges or run past a range end: exception 02 (0E)54H;
 * an address in a gap or past the last range: exception 02 (0E)51H */
static void test_straddle_and_gaps(void **state)
{
    (void)state;
    world_t *w = rtu32();
    uint8_t a[] = {5, 3, 0x13, 0x87, 0, 2}; /* 4999 (int16) + 5000 (int32) */
    rtu_expect_exception(w, a, sizeof a, 2, MODCP_EV_PAST_END);
    uint8_t b[] = {5, 3, 0x13, 0xEB, 0, 1}; /* 5099 is the last int32 register: ok */
    assert_int_equal(world_request_raw(w, b, sizeof b, 200), 9);
    b[5] = 2; /* 5099, 5100 */
    rtu_expect_exception(w, b, sizeof b, 2, MODCP_EV_PAST_END);
    uint8_t c[] = {5, 3, 0x17, 0x70, 0, 1}; /* 6000: a gap */
    rtu_expect_exception(w, c, sizeof c, 2, MODCP_EV_NO_WINDOW);
    uint8_t d[] = {5, 3, 0x00, 0x50, 0, 1}; /* 0050H: the DB-offset scheme is off */
    rtu_expect_exception(w, d, sizeof d, 2, MODCP_EV_NO_WINDOW);
    uint8_t e[] = {5, 16, 0x27, 0x0F, 0, 2, 8, 1, 2, 3, 4, 5, 6, 7, 8}; /* 9999, 10000 */
    rtu_expect_exception(w, e, sizeof e, 2, MODCP_EV_PAST_END);
    uint8_t f[] = {5, 6, 0x27, 0x10, 1, 2}; /* 10000 (16-bit length: no range holds it) */
    rtu_expect_exception(w, f, sizeof f, 2, MODCP_EV_NO_WINDOW);
    assert_memory_equal(world_db(w, 4) + 11996, "\x00\x00\x00\x00", 4); /* nothing written */
    ascii_world_free(w);
}

/* FC06: 4 data bytes for an int32 / float register, 2 for int16; FC16: byte count
 * 4 x quantity: otherwise exception 03 (08)33H */
static void test_byte_counts(void **state)
{
    (void)state;
    world_t *w = rtu32();
    uint8_t a[] = {5, 6, 0x1B, 0x5A, 0x12, 0x23}; /* float register, 2 data bytes */
    rtu_expect_exception(w, a, sizeof a, 3, MODCP_EV_BYTE_COUNT);
    uint8_t b[] = {5, 6, 0x0D, 0x37, 1, 2, 3, 4}; /* int16 register, 4 data bytes */
    rtu_expect_exception(w, b, sizeof b, 3, MODCP_EV_BYTE_COUNT);
    uint8_t c[] = {5, 16, 0x13, 0x8B, 0, 2, 4, 1, 2, 3, 4}; /* int32 x 2, byte count 4 */
    rtu_expect_exception(w, c, sizeof c, 3, MODCP_EV_BYTE_COUNT);
    uint8_t d[] = {5, 16, 0x13, 0x8B, 0, 2, 8, 1, 2, 3, 4, 5, 6, 7}; /* 7 of 8 bytes */
    rtu_expect_exception(w, d, sizeof d, 3, MODCP_EV_BYTE_COUNT);
    uint8_t e[] = {5, 16, 0x0C, 0x1C, 0, 2, 8, 1, 2, 3, 4, 5, 6, 7, 8}; /* int16 x 2, bc 8 */
    rtu_expect_exception(w, e, sizeof e, 3, MODCP_EV_BYTE_COUNT);
    assert_memory_equal(world_db(w, 3) + 12, "\x00\x00\x00\x00", 4);
    ascii_world_free(w);
}

/* FC04 is never 32-bit ([ASCII-32] §4.4): the DB-offset scheme with its own base DB 900 */
static void test_fc04_unchanged(void **state)
{
    (void)state;
    world_t *w = rtu32();
    memcpy(world_db(w, 901) + 384, "\xA1\xA2\xA3\xA4\xA5\xA6", 6);
    rtu_expect(w, "05 04 02 C0 00 03", "05 04 06 A1 A2 A3 A4 A5 A6");
    uint8_t r[] = {5, 4, 0x1B, 0x58, 0, 1}; /* 7000: DB900 + 13 = DB913 does not exist */
    rtu_expect_exception(w, r, sizeof r, 4, MODCP_EV_DB_ACCESS);
    ascii_world_free(w);
}

/* broadcast FC06 / FC16 to 32-bit registers: executed, never answered */
static void test_broadcast(void **state)
{
    (void)state;
    world_t *w = rtu32();
    uint8_t a[] = {0, 6, 0x1B, 0x5A, 0x12, 0x23, 0x34, 0x45};
    assert_int_equal(world_request_raw(w, a, sizeof a, 200), 0);
    assert_memory_equal(world_db(w, 4) + 8, "\x12\x23\x34\x45", 4);
    uint8_t b[] = {0, 16, 0x13, 0x8B, 0, 1, 4, 0xDE, 0xAD, 0xBE, 0xEF};
    assert_int_equal(world_request_raw(w, b, sizeof b, 200), 0);
    assert_memory_equal(world_db(w, 3) + 12, "\xDE\xAD\xBE\xEF", 4);
    assert_int_equal(w->fake.tx_count, 0);
    ascii_world_free(w);
}

/* [ASCII-32] §3.7, §5.4 (default, db_in_32bit_mode = off): the DB MIN/MAX limits are the
 * standard mode's; in 32-bit mode the three ranges' DBs stay writable whatever lim_db says.
 * The FB's work DB stays refused ([RTU-2003] §3.5). FC06/16 in the DB scheme of a standard-mode
 * CP still obey lim_db (test_map.c, test_cp_examples.c). */
static void test_regs32_ranges_writable_outside_db_limits(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    regs32_example_ranges(&p);
    p.lim_db = (modcp_limit_t){600, 699}; /* none of DB2, DB3, DB4 */
    assert_int_equal(p.r32_lim_db, 0);    /* the default */
    world_t *w = ascii_world_started(&p);
    rtu_expect(w, "05 06 0D 37 2B 1A", "05 06 0D 37 2B 1A"); /* int16 3383 -> DB2.DBW766 */
    assert_memory_equal(world_db(w, 2) + 766, "\x2B\x1A", 2);
    rtu_expect(w, "05 10 13 8B 00 02 08 3A 09 DE 1A 01 02 03 04", "05 10 13 8B 00 02");
    assert_memory_equal(world_db(w, 3) + 12, "\x3A\x09\xDE\x1A\x01\x02\x03\x04", 8);
    rtu_expect(w, "05 06 1B 5A 12 23 34 45", "05 06 1B 5A 12 23 34 45"); /* float 7002 */
    assert_memory_equal(world_db(w, 4) + 8, "\x12\x23\x34\x45", 4);
    ascii_world_free(w);

    /* a range on the FB's work DB: written never, whatever the limits */
    p.r32[MODCP_R32_INT16].db = WORLD_WORK_DB;
    p.lim_db = (modcp_limit_t){1, 65535};
    w = ascii_world_started(&p);
    uint8_t work[] = {5, 6, 0x0B, 0xB8, 0x12, 0x34}; /* 3000 -> DB80.DBW0 */
    rtu_expect_exception(w, work, sizeof work, 2, MODCP_EV_WRITE_DENIED);
    assert_memory_equal(world_db(w, WORLD_WORK_DB), "\0\0", 2);
    ascii_world_free(w);
}

/* db_in_32bit_mode = on (r32_lim_db 1): modcp's stricter rule, the DB limits apply to the
 * three ranges' DBs too: exception 02, (0E)52H, nothing written. */
static void test_32bit_db_limits_option_refuses_writes_outside_db_limits(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    regs32_example_ranges(&p);
    p.r32_lim_db = 1;
    p.lim_db = (modcp_limit_t){3, 899}; /* DB2 (int16) outside */
    world_t *w = ascii_world_started(&p);
    memcpy(world_db(w, 2) + 766, "\x55\x66", 2);
    uint8_t a[] = {5, 6, 0x0D, 0x37, 0x2B, 0x1A};
    rtu_expect_exception(w, a, sizeof a, 2, MODCP_EV_WRITE_DENIED);
    assert_memory_equal(world_db(w, 2) + 766, "\x55\x66", 2);   /* not written */
    rtu_expect(w, "05 03 0D 37 00 01", "05 03 02 55 66");        /* reads are not limited */
    rtu_expect(w, "05 06 1B 5A 12 23 34 45", "05 06 1B 5A 12 23 34 45"); /* DB4 inside */
    ascii_world_free(w);
}

/* ---- quantity limits ------------------------------------------------------------ */

static void read_n(world_t *w, bool ascii, uint16_t reg, uint16_t n, uint16_t expect_len)
{
    uint8_t r[] = {5, 3, (uint8_t)(reg >> 8), (uint8_t)reg, (uint8_t)(n >> 8), (uint8_t)n};
    uint16_t len = ascii ? ascii_request(w, ascii_frame(r, 6), 200)
                         : world_request_raw(w, r, 6, 200);
    assert_int_equal(len, expect_len);
}

static void write_n(world_t *w, bool ascii, uint16_t reg, uint16_t n, uint8_t per,
                    uint16_t expect_len)
{
    uint8_t r[7 + 260];
    size_t bc = (size_t)n * per;
    assert_true(bc <= 255);
    memcpy(r, (uint8_t[]){5, 16, (uint8_t)(reg >> 8), (uint8_t)reg, (uint8_t)(n >> 8),
                          (uint8_t)n, (uint8_t)bc},
           7);
    for (size_t k = 0; k < bc; k++) {
        r[7 + k] = (uint8_t)(k + 1);
    }
    uint16_t len = ascii ? ascii_request(w, ascii_frame(r, 7 + bc), 200)
                         : world_request_raw(w, r, 7 + bc, 200);
    assert_int_equal(len, expect_len);
}

/* ASCII ([ASCII-32] §4.5, §8.5 (08)32H): 32-bit read 62 / write 61, int16 125 / 123 */
static void test_limits_ascii(void **state)
{
    (void)state;
    world_t *w = ascii32();
    read_n(w, true, 7000, 62, 1 + 2 * (3 + 248 + 1) + 2);
    read_n(w, true, 7000, 63, 11);
    assert_string_equal(ascii_reply(w), ":05830375\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_QUANTITY);
    write_n(w, true, 7000, 61, 4, 17);
    assert_int_equal(world_db(w, 4)[243], 244);
    write_n(w, true, 7000, 62, 4, 0); /* 253 data bytes: over-long ([ASCII-32] §8.1) */
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    read_n(w, true, 5000, 62, 1 + 2 * (3 + 248 + 1) + 2); /* int32 the same */
    read_n(w, true, 5000, 63, 11);
    read_n(w, true, 3000, 125, 1 + 2 * (3 + 250 + 1) + 2);
    read_n(w, true, 3000, 126, 11);
    write_n(w, true, 3000, 123, 2, 17);
    write_n(w, true, 3000, 124, 2, 0);
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    ascii_world_free(w);
}

/* RTU (modcp decision): 32-bit 63 / 63, int16 127 / 127 */
static void test_limits_rtu(void **state)
{
    (void)state;
    world_t *w = rtu32();
    read_n(w, false, 7000, 63, 5 + 252);
    read_n(w, false, 7000, 64, 5);
    assert_int_equal(w->fake.tx[2], 3);
    write_n(w, false, 7000, 63, 4, 8);
    assert_int_equal(world_db(w, 4)[251], 252);
    uint8_t r[7] = {5, 16, 0x1B, 0x58, 0, 64, 0}; /* 64 registers: (08)32H before bc */
    rtu_expect_exception(w, r, sizeof r, 3, MODCP_EV_QUANTITY);
    read_n(w, false, 3000, 127, 5 + 254);
    read_n(w, false, 3000, 128, 5);
    write_n(w, false, 3000, 127, 2, 8);
    assert_int_equal(world_qty_max(&w->cp.params, 16, 0), 127);
    ascii_world_free(w);
}

/* the limits table of modcp/quantity.h */
static void test_quantity_table(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    regs32_example_ranges(&p);
    assert_int_equal(modcp_regs32_kind(&p, 3, 2999), 0);
    assert_int_equal(modcp_regs32_kind(&p, 3, 3000), MODCP_R32_INT16 + 1);
    assert_int_equal(modcp_regs32_kind(&p, 6, 5000), MODCP_R32_INT32 + 1);
    assert_int_equal(modcp_regs32_kind(&p, 16, 9999), MODCP_R32_FLOAT + 1);
    assert_int_equal(modcp_regs32_kind(&p, 4, 7000), 0); /* FC04 never */
    assert_int_equal(modcp_reg_bytes(0), 2);
    assert_int_equal(modcp_reg_bytes(MODCP_R32_INT16 + 1), 2);
    assert_int_equal(modcp_reg_bytes(MODCP_R32_INT32 + 1), 4);
    assert_int_equal(modcp_reg_bytes(MODCP_R32_FLOAT + 1), 4);
    const uint8_t f32 = MODCP_R32_FLOAT + 1;
    assert_int_equal(world_qty_max(&p, 1, 0), 2040);
    assert_int_equal(world_qty_max(&p, 15, 0), 2040);
    assert_int_equal(world_qty_max(&p, 3, 0), 127);
    assert_int_equal(world_qty_max(&p, 3, f32), 63);
    assert_int_equal(world_qty_max(&p, 16, f32), 63);
    p.framing = MODCP_FRAMING_ASCII;
    assert_int_equal(world_qty_max(&p, 1, 0), 2008);
    assert_int_equal(world_qty_max(&p, 2, 0), 2008);
    assert_int_equal(world_qty_max(&p, 15, 0), 1976);
    assert_int_equal(world_qty_max(&p, 3, 0), 125);
    assert_int_equal(world_qty_max(&p, 4, 0), 125);
    assert_int_equal(world_qty_max(&p, 16, 0), 123);
    assert_int_equal(world_qty_max(&p, 3, f32), 62);
    assert_int_equal(world_qty_max(&p, 16, f32), 61);
    assert_int_equal(world_qty_max(&p, 16, MODCP_R32_INT32 + 1), 61);
    assert_int_equal(world_qty_max(&p, 16, MODCP_R32_INT16 + 1), 123);
    assert_int_equal(world_qty_max(&p, 8, 0), 0);
}

/* overlapping ranges, DB 0, one DB twice: refused, the CP stays not ready ([ASCII-32] §8.6) */
static void test_bad_ranges_refused(void **state)
{
    (void)state;
    for (int k = 0; k < 3; k++) {
        modcp_params_t p;
        world_example_params(&p);
        regs32_example_ranges(&p);
        if (k == 0) {
            p.r32[MODCP_R32_FLOAT].from = 5099; /* overlaps int32 */
        } else if (k == 1) {
            p.r32[MODCP_R32_INT32].db = 0;
        } else {
            p.r32[MODCP_R32_FLOAT].db = 2; /* the int16 DB */
        }
        world_t *w = world_new(&p);
        assert_false(world_start(w, 200));
        assert_false(modcp_cp_ready(&w->cp));
        assert_int_equal(w->cp.param_event, MODCP_EV_PARAM_RECORD);
        assert_int_equal(world_request(w, "05 03 1B 59 00 02 00 00", 100), 0);
        world_free(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fc03_int16_example),
        cmocka_unit_test(test_fc03_float_example),
        cmocka_unit_test(test_fc06_int16_example),
        cmocka_unit_test(test_fc06_float_example),
        cmocka_unit_test(test_fc06_32bit_in_modem_mode),
        cmocka_unit_test(test_fc16_int16_example),
        cmocka_unit_test(test_fc16_int32_example),
        cmocka_unit_test(test_address_table),
        cmocka_unit_test(test_ascii_vectors),
        cmocka_unit_test(test_float_and_int32_values),
        cmocka_unit_test(test_straddle_and_gaps),
        cmocka_unit_test(test_byte_counts),
        cmocka_unit_test(test_fc04_unchanged),
        cmocka_unit_test(test_broadcast),
        cmocka_unit_test(test_regs32_ranges_writable_outside_db_limits),
        cmocka_unit_test(test_32bit_db_limits_option_refuses_writes_outside_db_limits),
        cmocka_unit_test(test_limits_ascii),
        cmocka_unit_test(test_limits_rtu),
        cmocka_unit_test(test_quantity_table),
        cmocka_unit_test(test_bad_ranges_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
