/* SPDX-License-Identifier: Apache-2.0 */
/* The documented interpretations of issue 13 item 8: where modcp reads the manuals in a
 * particular way, a test pins the behaviour that the documents describe (with the
 * manual's words and the reason):
 *   - FC08 with a sub-function other than 0000: exception 03 / (08)35H in the cp341 set
 *     ([RTU-2003] §8.7), exception 01 / (08)35H in the extended set (docs/extended-functions.md);
 *   - the STATUS word of the status area keeps the last event, it never returns to 0
 *     ([VIPA-341] §8.1; docs/diagnostics.md);
 *   - lower-case ASCII hex is accepted, replies are upper case ([ASCII-32] §8.1;
 *     docs/ascii-and-32bit.md);
 *   - BREAK on a four-wire (RS422) line in interference suppression mode is not reported
 *     and is no wire break ([RTU-2003] §4.6.1, [RTU-2009] Table 5-8; docs/diagnostics.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ascii_world.h"
#include "lineworld.h"
#include "world.h"

#define FC08_REQ "05 08 00 00 A5 C3 DA 8E" /* [RTU-2003] §6.7 */

static world_t *started(uint8_t fset)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = fset;
    world_t *w = world_new(&p);
    assert_true(world_start(w, 2000));
    return w;
}

/* FC08 sub-function sub, data 0000: the exception code of the reply (0: no exception). */
static uint8_t fc08(world_t *w, uint16_t sub)
{
    uint8_t f[6] = {5, 0x08, (uint8_t)(sub >> 8), (uint8_t)sub, 0, 0};
    uint16_t n = world_request_raw(w, f, sizeof f, 50);
    assert_true(n >= 5);
    return w->fake.tx[1] == 0x88u ? w->fake.tx[2] : 0u;
}

/* [RTU-2003] §8.7: "Only diagnostic code 0000 is supported. Any other value -> exception 3,
 * (08)35H." The cp341 set keeps that. */
static void test_fc08_subcode_other_than_0000_answers_exception_03(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    assert_int_equal(fc08(w, 0x0000), 0);
    static const uint16_t subs[] = {0x0001, 0x0005, 0x000A, 0x0015, 0xFFFF};
    for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++) {
        assert_int_equal(fc08(w, subs[i]), 3);
        assert_int_equal(world_last_event(w), MODCP_EV_DIAG_SUBFC);
    }
    world_free(w);
}

#if MODCP_WITH_EXTENDED
/* Extended set: the sub-function space is that of Modbus over serial line; a sub-function
 * it does not implement is "function not supported" (Application Protocol V1.1b3 §6.8
 * state diagram: exception 01), with the manual's event (08)35H. */
static void test_mbap6_8_fc08_unsupported_subfunction_exception_01_event_0835(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_EXTENDED);
    static const uint16_t subs[] = {0x0005, 0x0009, 0x0013, 0x0015, 0x0100};
    for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++) {
        assert_int_equal(fc08(w, subs[i]), 1);
        assert_int_equal(world_last_event(w), MODCP_EV_DIAG_SUBFC);
    }
    assert_int_equal(fc08(w, 0x000B), 0); /* a supported one */
    world_free(w);
}
#endif

static uint16_t status_word(const world_t *w)
{
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    return st.status;
}

/* [VIPA-341] §8.1: the FB's STATUS output is "non-zero only while ERROR is set; otherwise
 * STATUS = 0". The STATUS word of the CP's status area is the last event and stays until
 * the next one: successful requests after an event do not clear it. */
static void test_status_word_keeps_last_event(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    assert_int_equal(status_word(w), 0); /* no event since power-on */
    assert_int_equal(world_request(w, "05 08 00 00 A5 C3 DA 8F", 50), 0); /* bad CRC */
    world_run(w, 5000);
    assert_int_equal(status_word(w), 0x0836);
    for (int i = 0; i < 3; i++) {
        assert_int_equal(world_request(w, FC08_REQ, 50), 8);
        assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9E", 100), 9);
    }
    world_run(w, 5000);
    assert_int_equal(status_word(w), 0x0836);
    uint8_t many[] = {5, 0x03, 0x00, 0x00, 0x00, 0x80}; /* 128 registers */
    assert_int_equal(world_request_raw(w, many, sizeof many, 50), 5);
    assert_int_equal(world_request(w, FC08_REQ, 50), 8);
    world_run(w, 5000);
    assert_int_equal(status_word(w), 0x0832); /* the newest event, still there */
    world_free(w);
}

/* [ASCII-32] §8.1: "each 8-bit byte is sent as two ASCII hex characters 0-9 A-F"; a character
 * that "is not an ASCII hex character" rejects the string. a-f are accepted as hex, the
 * reply is upper case; g is not hex: rejected with (08)3AH. */
static void test_ascii_lower_case_hex_accepted_reply_upper_case(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    world_t *w = ascii_world_started(&p);
    assert_true(ascii_request(w, ":05080000a5c38b\r\n", 100) > 0);
    assert_string_equal(ascii_reply(w), ":05080000A5C38B\r\n");
    assert_true(ascii_request(w, ":05080000A5c38B\r\n", 100) > 0); /* mixed */
    assert_string_equal(ascii_reply(w), ":05080000A5C38B\r\n");
    assert_int_equal(ascii_request(w, ":05080000g5C38B\r\n", 100), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_NOT_HEX);
    ascii_world_free(w);
}

/* [RTU-2003] §4.6.1 interference suppression: a BREAK during a message makes it faulty and
 * ignored, BREAK after the CRC is ignored; [RTU-2009] Table 5-8: on four-wire RS422 "error
 * handling follows the operating mode". So on RS422 in suppression mode a BREAK (the
 * receive-line preset R(A) 5V / R(B) 0V shows a broken line as BREAK) is not reported:
 * no (08)0DH, no wire break, SF off; the next request is answered. In normal mode the
 * same BREAK is (08)0DH and a wire break. */
static void test_break_in_four_wire_suppression_not_reported(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.iface = MODCP_IFACE_RS422;
    p.opmode = MODCP_OPMODE_SUPPRESS;
    lw_t *x = lw_new(&p);
    lw_clear(x);
    lw_error(x, MODCP_LINE_BREAK); /* idle line */
    lw_advance(x, lw_now(x) + 20000);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_false(st.flags & (MODCP_CPST_WIRE_BREAK | MODCP_CPST_SF));
    assert_false(x->led[MODCP_LED_SF]);
    /* a BREAK inside a request: the request is lost, nothing reported */
    lw_byte(x, 0x05);
    lw_advance(x, lw_now(x) + 1146);
    lw_byte(x, 0x08);
    lw_advance(x, lw_now(x) + 1146);
    lw_error(x, MODCP_LINE_BREAK);
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_false(lw_status(x).flags & MODCP_CPST_WIRE_BREAK);
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    lw_free(x);

    /* normal mode on the same line: reported, a wire break */
    p.opmode = MODCP_OPMODE_NORMAL;
    x = lw_new(&p);
    lw_clear(x);
    lw_error(x, MODCP_LINE_BREAK);
    lw_advance(x, lw_now(x) + 20000);
    assert_int_equal(world_last_event(x->w), MODCP_EV_BREAK);
    assert_true(lw_status(x).flags & MODCP_CPST_WIRE_BREAK);
    lw_free(x);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fc08_subcode_other_than_0000_answers_exception_03),
#if MODCP_WITH_EXTENDED
        cmocka_unit_test(test_mbap6_8_fc08_unsupported_subfunction_exception_01_event_0835),
#endif
        cmocka_unit_test(test_status_word_keeps_last_event),
        cmocka_unit_test(test_ascii_lower_case_hex_accepted_reply_upper_case),
        cmocka_unit_test(test_break_in_four_wire_suppression_not_reported),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
