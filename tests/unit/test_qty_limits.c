/* SPDX-License-Identifier: Apache-2.0 */
/* Quantity limits, protocol.quantity_limits (issue 13 item 7): `manual` keeps the
 * manuals' RTU limits ([RTU-2003] §6: FC01/02/15 1 … 2040 bits, FC03/04/16 1 … 127 registers);
 * `spec` applies the Modbus application protocol's (V1.1b3 §6.1 FC01 and §6.2 FC02
 * "1 to 2000", §6.3 FC03 and §6.4 FC04 "1 to 125", §6.11 FC15 "1 to 1968 (0x7B0)",
 * §6.12 FC16 "1 to 123 (0x7B)", §6.17 FC23 "read 1 to 125, write 1 to 121"), with
 * exception 03 / (08)32H above them, so that no reply exceeds the 256-byte RTU ADU
 * (Modbus over serial line V1.02 §2.5.1). Each function code at its maximum (answered),
 * maximum + 1 and 0 (exception 03), through the whole CP (world.h: link, PDU, job, FB). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/quantity.h"
#include "world.h"
#include "quantity_internal.h"

#define RTU_ADU_MAX 256u /* Modbus over serial line V1.02 §2.5.1 */

/* The [RTU-2003] §9 example set, extended set (FC23), the given limit set; with regs32 a float
 * range 1000 … 1099 in DB801 (100 DBDs). */
static world_t *started(uint8_t qlimits, bool regs32)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_EXTENDED;
    p.qty_limits = qlimits;
    if (regs32) {
        p.regs32 = 1;
        p.r32[MODCP_R32_FLOAT] = (modcp_r32range_t){1000, 1099, 801};
    }
    world_t *w = world_new(&p);
    assert_true(world_start(w, 2000));
    return w;
}

/* FC01..04 request: the reply's ADU length (0 = none). */
static uint16_t read_req(world_t *w, uint8_t fc, uint16_t addr, uint16_t qty)
{
    uint8_t f[6] = {5, fc, (uint8_t)(addr >> 8), (uint8_t)addr, (uint8_t)(qty >> 8), (uint8_t)qty};
    return world_request_raw(w, f, sizeof f, 100);
}

/* FC15 / FC16 request with a byte count that matches the quantity (bytes per register
 * bpr: 2, or 4 in a 32-bit range; 0 for bits), at most 255 (the one-byte field: 2041
 * bits or 128 registers can only be asked with a byte count that does not match). */
static uint16_t write_req(world_t *w, uint8_t fc, uint16_t addr, uint16_t qty, uint8_t bpr)
{
    uint8_t f[700] = {5, fc, (uint8_t)(addr >> 8), (uint8_t)addr, (uint8_t)(qty >> 8), (uint8_t)qty};
    uint32_t bytes = bpr == 0u ? (qty + 7u) / 8u : (uint32_t)qty * bpr;
    if (bytes > 255u) {
        bytes = 255u;
    }
    f[6] = (uint8_t)bytes;
    for (uint32_t k = 0; k < bytes && 7u + k < sizeof f; k++) {
        f[7 + k] = (uint8_t)(0x11u * k);
    }
    return world_request_raw(w, f, 7u + bytes, 100);
}

/* FC23: read rqty from 0, write wqty at 200. */
static uint16_t rw_req(world_t *w, uint16_t rqty, uint16_t wqty)
{
    uint8_t f[700] = {5, 0x17, 0, 0, (uint8_t)(rqty >> 8), (uint8_t)rqty, 0, 200,
                      (uint8_t)(wqty >> 8), (uint8_t)wqty, (uint8_t)(2u * wqty)};
    for (uint32_t k = 0; k < 2u * wqty; k++) {
        f[11 + k] = (uint8_t)k;
    }
    return world_request_raw(w, f, 11u + 2u * wqty, 100);
}

static void expect_exception_03(world_t *w, uint16_t len, uint8_t fc)
{
    assert_int_equal(len, 5); /* address, fc | 80H, 03, CRC */
    assert_int_equal(w->fake.tx[1], fc | 0x80u);
    assert_int_equal(w->fake.tx[2], 0x03);
    assert_int_equal(world_last_event(w), MODCP_EV_QUANTITY); /* (08)32H */
}

/* A read answered with its byte count; returns the ADU length. */
static uint16_t expect_read(world_t *w, uint16_t len, uint8_t fc, uint16_t data_bytes)
{
    assert_int_equal(len, 5u + data_bytes);
    assert_int_equal(w->fake.tx[1], fc);
    assert_int_equal(w->fake.tx[2], (uint8_t)data_bytes);
    return len;
}

static void expect_write(world_t *w, uint16_t len, uint8_t fc, uint16_t qty)
{
    assert_int_equal(len, 8); /* echo of address and quantity */
    assert_int_equal(w->fake.tx[1], fc);
    assert_int_equal((w->fake.tx[4] << 8) | w->fake.tx[5], qty);
}

/* ---- spec ------------------------------------------------------------------------------ */

/* V1.1b3 §6.1 / §6.2: quantity of coils / inputs 1 to 2000; reply 3 + 250 + 2 bytes. */
static void test_mbap6_1_6_2_spec_read_bits_1_to_2000(void **state)
{
    (void)state;
    world_t *w = started(MODCP_QLIMITS_SPEC, false);
    for (uint8_t fc = 1; fc <= 2; fc++) {
        assert_true(expect_read(w, read_req(w, fc, 0, 2000), fc, 250) <= RTU_ADU_MAX);
        expect_exception_03(w, read_req(w, fc, 0, 2001), fc);
        expect_exception_03(w, read_req(w, fc, 0, 0), fc);
        expect_read(w, read_req(w, fc, 0, 1), fc, 1);
    }
    world_free(w);
}

/* V1.1b3 §6.3 / §6.4: quantity of registers 1 to 125; reply 3 + 250 + 2 bytes. */
static void test_mbap6_3_6_4_spec_read_registers_1_to_125(void **state)
{
    (void)state;
    world_t *w = started(MODCP_QLIMITS_SPEC, false);
    for (uint8_t fc = 3; fc <= 4; fc++) {
        assert_true(expect_read(w, read_req(w, fc, 0, 125), fc, 250) <= RTU_ADU_MAX);
        expect_exception_03(w, read_req(w, fc, 0, 126), fc);
        expect_exception_03(w, read_req(w, fc, 0, 127), fc);
        expect_exception_03(w, read_req(w, fc, 0, 0), fc);
    }
    world_free(w);
}

/* V1.1b3 §6.11 FC15 1 to 1968 (request 9 + 246 bytes = 255), §6.12 FC16 1 to 123
 * (9 + 246); above: exception 03 and nothing written. */
static void test_mbap6_11_6_12_spec_write_1968_bits_123_registers(void **state)
{
    (void)state;
    world_t *w = started(MODCP_QLIMITS_SPEC, false);
    expect_write(w, write_req(w, 0x0F, 0, 1968, 0), 0x0F, 1968);
    assert_int_equal(w->m[1000 + 1], 0x11);
    assert_int_equal(w->m[1000 + 245], (uint8_t)(0x11u * 245u));
    memset(w->m + 1000, 0, 256);
    expect_exception_03(w, write_req(w, 0x0F, 0, 1969, 0), 0x0F);
    assert_int_equal(w->m[1000 + 1], 0);

    expect_write(w, write_req(w, 0x10, 0, 123, 2), 0x10, 123);
    assert_int_equal(world_db(w, 800)[245], (uint8_t)(0x11u * 245u));
    memset(world_db(w, 800), 0, 1024);
    expect_exception_03(w, write_req(w, 0x10, 0, 124, 2), 0x10);
    expect_exception_03(w, write_req(w, 0x10, 0, 0, 2), 0x10);
    assert_int_equal(world_db(w, 800)[1], 0);
    world_free(w);
}

/* V1.1b3 §6.17 FC23: read 1 to 125, write 1 to 121, in both sets. */
static void test_mbap6_17_fc23_read_125_write_121(void **state)
{
    (void)state;
    for (uint8_t set = MODCP_QLIMITS_MANUAL; set <= MODCP_QLIMITS_SPEC; set++) {
        world_t *w = started(set, false);
        assert_true(expect_read(w, rw_req(w, 125, 121), 0x17, 250) <= RTU_ADU_MAX);
        expect_exception_03(w, rw_req(w, 126, 1), 0x17);
        expect_exception_03(w, rw_req(w, 1, 122), 0x17);
        expect_exception_03(w, rw_req(w, 0, 1), 0x17);
        world_free(w);
    }
}

/* spec with 32-bit registers ([ASCII-32] §4.5): FC03 1 … 62 (248 bytes), FC16 1 … 61 (244
 * bytes) in an int32 / float range, the largest counts inside the spec's 125 / 123
 * words. */
static void test_mbap6_spec_limits_32bit_registers(void **state)
{
    (void)state;
    world_t *w = started(MODCP_QLIMITS_SPEC, true);
    assert_true(expect_read(w, read_req(w, 3, 1000, 62), 3, 248) <= RTU_ADU_MAX);
    expect_exception_03(w, read_req(w, 3, 1000, 63), 3);
    expect_write(w, write_req(w, 0x10, 1000, 61, 4), 0x10, 61);
    expect_exception_03(w, write_req(w, 0x10, 1000, 62, 4), 0x10);
    world_free(w);
    /* manual, RTU: 63 each (the modcp decision of modcp/quantity.h) */
    w = started(MODCP_QLIMITS_MANUAL, true);
    expect_read(w, read_req(w, 3, 1000, 63), 3, 252);
    expect_exception_03(w, read_req(w, 3, 1000, 64), 3);
    expect_write(w, write_req(w, 0x10, 1000, 63, 4), 0x10, 63);
    world_free(w);
}

/* ---- manual (the default) ----------------------------------------------------------- */

/* [RTU-2003] §6: FC01/02 1 … 2040 bits, FC03/04 1 … 127 registers, FC15 1 … 2040, FC16 1 … 127
 * stay the default; a 127-register reply is 259 bytes, beyond the RTU ADU of the Modbus
 * specification (why `spec` exists). */
static void test_manual_quantity_limits_stay_the_default(void **state)
{
    (void)state;
    modcp_params_t d;
    modcp_params_defaults(&d);
    assert_int_equal(d.qty_limits, MODCP_QLIMITS_MANUAL);
    world_t *w = started(MODCP_QLIMITS_MANUAL, false);
    for (uint8_t fc = 1; fc <= 2; fc++) {
        expect_read(w, read_req(w, fc, 0, 2040), fc, 255);
        expect_exception_03(w, read_req(w, fc, 0, 2041), fc);
    }
    for (uint8_t fc = 3; fc <= 4; fc++) {
        assert_true(expect_read(w, read_req(w, fc, 0, 127), fc, 254) > RTU_ADU_MAX);
        expect_read(w, read_req(w, fc, 0, 126), fc, 252);
        expect_exception_03(w, read_req(w, fc, 0, 128), fc);
    }
    expect_write(w, write_req(w, 0x0F, 0, 2040, 0), 0x0F, 2040);
    expect_exception_03(w, write_req(w, 0x0F, 0, 2041, 0), 0x0F);
    expect_write(w, write_req(w, 0x10, 0, 127, 2), 0x10, 127);
    expect_exception_03(w, write_req(w, 0x10, 0, 128, 2), 0x10);
    world_free(w);
}

/* The table: spec is at or below the manual's limit of either framing, and ASCII with
 * spec uses the spec's numbers (its 252-byte frame holds them). */
static void test_mbap6_spec_table_in_both_framings(void **state)
{
    (void)state;
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.qty_limits = MODCP_QLIMITS_SPEC;
    const uint8_t f32 = MODCP_R32_FLOAT + 1;
    for (uint8_t framing = MODCP_FRAMING_RTU; framing <= MODCP_FRAMING_ASCII; framing++) {
        p.framing = framing;
        assert_int_equal(world_qty_max(&p, 1, 0), 2000);
        assert_int_equal(world_qty_max(&p, 2, 0), 2000);
        assert_int_equal(world_qty_max(&p, 15, 0), 1968);
        assert_int_equal(world_qty_max(&p, 3, 0), 125);
        assert_int_equal(world_qty_max(&p, 4, 0), 125);
        assert_int_equal(world_qty_max(&p, 16, 0), 123);
        assert_int_equal(world_qty_max(&p, 3, f32), 62);
        assert_int_equal(world_qty_max(&p, 16, f32), 61);
        assert_int_equal(modcp_qty_limit(&p, MODCP_QLIM_RW_READ, 0), 125);
        assert_int_equal(modcp_qty_limit(&p, MODCP_QLIM_RW_WRITE, 0), 121);
        for (uint8_t lim = 0; lim < MODCP_QLIM_COUNT; lim++) {
            for (uint8_t k = 0; k <= 1; k++) {
                uint8_t kind = k ? f32 : 0;
                modcp_params_t m = p;
                m.qty_limits = MODCP_QLIMITS_MANUAL;
                assert_true(modcp_qty_limit(&p, lim, kind) <= modcp_qty_limit(&m, lim, kind));
            }
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mbap6_1_6_2_spec_read_bits_1_to_2000),
        cmocka_unit_test(test_mbap6_3_6_4_spec_read_registers_1_to_125),
        cmocka_unit_test(test_mbap6_11_6_12_spec_write_1968_bits_123_registers),
        cmocka_unit_test(test_mbap6_17_fc23_read_125_write_121),
        cmocka_unit_test(test_mbap6_spec_limits_32bit_registers),
        cmocka_unit_test(test_manual_quantity_limits_stay_the_default),
        cmocka_unit_test(test_mbap6_spec_table_in_both_framings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
