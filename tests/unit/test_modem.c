/* SPDX-License-Identifier: Apache-2.0 */
/* Interference suppression = the French edition's modem mode ([RTU-2009] §5.6.1 "Fonctionnement
 * modem", [RTU-2009] §8 end of telegram; [RTU-2003] §2.2 "Interference suppression"): the start of a
 * frame is a correctly received own slave address, the end a formally correct frame
 * with a valid CRC; character errors and BREAK before the frame and after the CRC are
 * ignored. Through the whole CP (link, PDU, job, FB) on a simulated line with exact
 * time (lineworld.h), 9600 baud 8E1: one character = 1146 us, t3.5 = 4000 us.
 *
 * Counting: "ignored, not counted" means no event, no diagnostic buffer entry, no FC08
 * serial-line counter (0B / 0C) and no wire break; the status area's char_errors /
 * breaks are the UART's raw line statistics and count every line error in both modes
 * (test_link.c test_break_idle, test_diag.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "lineworld.h"

#define FC03_REQ "05 03 00 50 00 02 C5 9E" /* [RTU-2003] §6.3 */
#define FC03_RSP "05 03 04 87 65 43 21 76 70"
#define FC08_REQ "05 08 00 00 A5 C3 DA 8E" /* [RTU-2003] §6.7, answered by the CP alone */
#define CHAR_US 1146u
#define T35_US 4000u

static modcp_params_t params(uint8_t opmode)
{
    modcp_params_t p;
    world_example_params(&p);
    p.opmode = opmode;
    return p;
}

static lw_t *start(uint8_t opmode)
{
    modcp_params_t p = params(opmode);
    lw_t *x = lw_new(&p);
    memcpy(world_db(x->w, 800) + 160, "\x87\x65\x43\x21", 4); /* DBW160/162 for FC03 */
    lw_clear(x);
    return x;
}

/* Send the bytes of hex (plus their CRC when crc), one character time apart, the first
 * one character after the current time; returns the time of the last one. */
static uint32_t send(lw_t *x, const char *hex, bool crc)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b - 2);
    if (crc) {
        n = add_crc(b, n);
    }
    uint32_t t = lw_now(x);
    for (size_t i = 0; i < n; i++) {
        t += CHAR_US;
        lw_advance(x, t);
        lw_byte(x, b[i]);
    }
    return t;
}

/* A line error one character after the current time. */
static void error_next(lw_t *x, uint8_t flags)
{
    lw_advance(x, lw_now(x) + CHAR_US);
    lw_error(x, flags);
}

static const modcp_diag_t *diag(const lw_t *x)
{
    return &x->w->cp.diag;
}

static void assert_nothing_reported(const lw_t *x)
{
    assert_int_equal(diag(x)->buffer_len, 0);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_CRC], 0);
    assert_false(x->w->cp.cpdiag.wire_break);
}

/* ---- the start: a correctly received own slave address ------------------------------ */

/* Stray characters right before a request (less than t3.5: the same stretch): dropped,
 * the request is answered, nothing reported or counted. */
static void check_stray_before_request(const char *stray, uint8_t error_flags)
{
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    if (stray != NULL) {
        (void)send(x, stray, false);
    }
    if (error_flags != 0u) {
        error_next(x, error_flags);
    }
    uint32_t last = send(x, FC03_REQ, false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_nothing_reported(x);
    assert_int_equal(diag(x)->counters[MODCP_CNT_SLAVE_MSG], 1);
    lw_free(x);
}

static void test_modem_stray_ff_before_request_answered(void **state)
{
    (void)state;
    check_stray_before_request("FF", 0);
    check_stray_before_request("FF FF FF", 0);
}

static void test_modem_stray_00_before_request_answered(void **state)
{
    (void)state;
    check_stray_before_request("00", 0);
    check_stray_before_request("00 00", 0);
    check_stray_before_request("FF 00", 0);
}

static void test_modem_break_before_request_answered(void **state)
{
    (void)state;
    check_stray_before_request(NULL, MODCP_LINE_BREAK | MODCP_LINE_FRAMING);
    check_stray_before_request("FF", MODCP_LINE_BREAK);
    check_stray_before_request("00", MODCP_LINE_BREAK); /* a lone 00: before the frame */
}

static void test_modem_parity_error_before_request_answered(void **state)
{
    (void)state;
    check_stray_before_request(NULL, MODCP_LINE_PARITY);
    check_stray_before_request("FF", MODCP_LINE_PARITY);
    check_stray_before_request(NULL, MODCP_LINE_OVERRUN);
}

/* A stray copy of our own address (and a stray 00 + broadcast function code) starts a
 * candidate that fails its CRC at its length; the request inside is found again. */
static void test_modem_stray_own_address_before_request_answered(void **state)
{
    (void)state;
    check_stray_before_request("05", 0);
    check_stray_before_request("05 05", 0);
    check_stray_before_request("00 06", 0);
    check_stray_before_request("05 FF 00", 0);
}

/* Normal operation, for comparison: the stray FF starts a frame (address FF, not ours)
 * that runs into the request: the request is lost. */
static void test_normal_mode_stray_ff_loses_request(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_NORMAL);
    (void)send(x, "FF", false);
    uint32_t last = send(x, FC03_REQ, false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 0);
    lw_free(x);
}

/* Another slave's frames that contain our address and 00 are followed, never taken for
 * ours, counted as bus messages, and nothing is reported. */
static void test_modem_other_address_not_mistaken_for_ours(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    static const char *const frames[] = {
        "07 03 00 05 00 01",             /* request to 07 with our address in its data */
        "07 03 04 00 05 00 10",          /* a response of 07: 00 05 00 10 */
        "07 10 00 05 00 01 02 05 03",    /* 05 03 inside: a FC03 candidate, wrong CRC */
        "07 06 00 06 00 05",             /* 00 06: a broadcast candidate, wrong CRC */
    };
    uint32_t last = 0;
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        last = send(x, frames[i], true);
        lw_advance(x, last + 10000);
    }
    assert_int_equal(x->tx_calls, 0);
    assert_nothing_reported(x);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_MSG], 4);
    assert_int_equal(diag(x)->counters[MODCP_CNT_SLAVE_MSG], 0);
    assert_memory_equal(world_db(x->w, 800), "\0\0\0\0\0\0\0\0\0\0\0\0", 12); /* no write */
    /* and our request right after is answered */
    last = send(x, FC03_REQ, false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* Stray characters alone: nothing counted, nothing reported. */
static void test_modem_stray_characters_alone_not_counted(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    (void)send(x, "FF FF", false);
    error_next(x, MODCP_LINE_PARITY);
    (void)send(x, "00", false);
    lw_advance(x, lw_now(x) + 20000);
    assert_int_equal(x->tx_calls, 0);
    assert_nothing_reported(x);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_MSG], 0);
    lw_free(x);
}

/* A frame that starts with our address and never ends in a valid CRC is a CRC error,
 * reported at its t3.5 as in normal operation. */
static void test_modem_crc_error_reported(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    uint32_t last = send(x, "05 03 00 50 00 02 C5 9F", false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(diag(x)->buffer_len, 1);
    assert_int_equal(diag(x)->buffer[0], MODCP_EV_CRC);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_CRC], 1);
    lw_free(x);
}

/* A character error inside our frame discards it silently ([RTU-2003] §2.2), counted once in
 * FC08's bus error counter; the next request is answered. */
static void test_modem_error_inside_frame_discards_it(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    (void)send(x, "05 03 00", false);
    error_next(x, MODCP_LINE_PARITY);
    uint32_t last = send(x, "00 02 C5 9E", false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(diag(x)->buffer_len, 0);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_CRC], 1);
    last = send(x, FC03_REQ, false);
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 1);
    lw_free(x);
}

/* ---- the end: a formally correct frame with a valid CRC ---------------------------- */

/* Errors and BREAK right after the CRC: ignored, not counted; the request is answered. */
static void test_modem_errors_after_crc_ignored_not_counted(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    x->w->fb_paused = true; /* the request waits for the FB while the errors come */
    uint32_t last = send(x, FC03_REQ, false);
    error_next(x, MODCP_LINE_FRAMING);
    error_next(x, MODCP_LINE_BREAK | MODCP_LINE_FRAMING);
    error_next(x, MODCP_LINE_PARITY);
    lw_advance(x, last + 2u * T35_US);
    x->w->fb_paused = false;
    lw_advance(x, last + 30000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_nothing_reported(x);
    assert_int_equal(diag(x)->counters[MODCP_CNT_BUS_MSG], 1);
    lw_free(x);
}

/* [RTU-2009] §8: the valid CRC ends the frame; the CP does not wait t3.5. FC08 is answered by
 * the CP alone: the reply leaves at the timer the last character armed (1 us), where
 * normal operation waits t3.5. */
static void test_modem_frame_ends_by_crc_without_t35(void **state)
{
    (void)state;
    for (int modem = 0; modem < 2; modem++) {
        lw_t *x = start(modem ? MODCP_OPMODE_SUPPRESS : MODCP_OPMODE_NORMAL);
        uint32_t last = send(x, FC08_REQ, false);
        lw_advance(x, last + 20000);
        assert_int_equal(x->tx_calls, 1);
        assert_string_equal(lw_tx_hex(x), FC08_REQ);
        assert_int_equal(lw_last(x, LW_TX)->at, last + (modem ? 1u : T35_US));
        lw_free(x);
    }
}

/* Lengths by function code: fixed (FC03, FC06, FC08), by the byte count (FC16), each
 * answered before t3.5; broadcast FC06 executed without a reply. */
static void test_modem_frame_lengths_by_function_code(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    x->cycles = false; /* the FB only where the test says: the job starts at once */
    (void)send(x, "FF", false);
    uint32_t last = send(x, "05 10 00 00 00 02 04 11 22 33 44", true);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_EOF);
    lw_advance(x, last + 1);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_BUSY);
    x->cycles = true;
    lw_advance(x, last + 20000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), "05 10 00 00 00 02 40 4C");
    assert_memory_equal(world_db(x->w, 800), "\x11\x22\x33\x44", 4);

    (void)send(x, "FF", false);
    last = send(x, "00 06 00 04 AB CD", true); /* broadcast */
    lw_advance(x, last + 20000);
    assert_int_equal(x->tx_calls, 1);
    assert_memory_equal(world_db(x->w, 800) + 8, "\xAB\xCD", 2);
    assert_int_equal(diag(x)->counters[MODCP_CNT_SLAVE_MSG], 2);
    assert_nothing_reported(x);
    lw_free(x);
}

/* Every request whose length its function code tells (the function-code table,
 * fc_table.c) ends at its CRC, in either function set: not one character earlier (the
 * link still receives), at the last one the frame is complete (EOF, handed over on the
 * 1 us timer). Fixed lengths, lengths by the byte count (FC15, FC16, FC23) and the usual
 * form of FC06, FC08 and FC43. */
static void test_modem_every_known_request_ends_at_its_crc(void **state)
{
    (void)state;
    static const char *const reqs[] = {
        "05 01 00 00 00 08", "05 02 00 00 00 08", "05 03 00 50 00 02", "05 04 00 00 00 01",
        "05 05 00 00 FF 00", "05 06 00 04 AB CD", "05 08 00 00 12 34", "05 0B", "05 0C",
        "05 0F 00 00 00 08 01 FF", "05 10 00 00 00 01 02 12 34", "05 11",
        "05 16 00 00 FF FF 00 00", "05 17 00 00 00 01 00 00 00 01 02 12 34", "05 2B 0E 01 00",
    };
    for (int set = 0; set < 2; set++) {
        modcp_params_t p = params(MODCP_OPMODE_SUPPRESS);
        p.fset = set ? MODCP_FSET_EXTENDED : MODCP_FSET_CP341;
        lw_t *x = lw_new(&p);
        for (size_t i = 0; i < sizeof reqs / sizeof reqs[0]; i++) {
            uint8_t b[32];
            size_t n = add_crc(b, hex_frame(reqs[i], b, sizeof b - 2));
            uint32_t t = lw_now(x);
            for (size_t k = 0; k < n; k++) {
                t += CHAR_US;
                lw_advance(x, t);
                assert_int_equal(x->w->cp.link.state, k == 0 ? MODCP_LINK_IDLE : MODCP_LINK_RX);
                lw_byte(x, b[k]);
            }
            assert_int_equal(x->w->cp.link.state, MODCP_LINK_EOF);
            lw_advance(x, t + 80000); /* answered (or refused), the line idle again */
        }
        lw_free(x);
    }
}

/* Function codes without a known length end by t3.5: an unsupported one (FC07) is
 * answered with exception 01 at t3.5, also after a stray character; FC08 with more
 * data than usual continues to t3.5 and is echoed. */
static void test_modem_unknown_length_ends_by_t35(void **state)
{
    (void)state;
    lw_t *x = start(MODCP_OPMODE_SUPPRESS);
    (void)send(x, "FF", false);
    uint32_t last = send(x, "05 07", true);
    lw_advance(x, last + T35_US - 1);
    assert_int_equal(x->tx_calls, 0);
    lw_advance(x, last + T35_US + 20000);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(lw_last(x, LW_TX)->at, last + T35_US);
    assert_string_equal(lw_tx_hex(x), "05 87 01 C3 F1");

    last = send(x, "05 08 00 00 12 34 56 78", true);
    lw_advance(x, last + T35_US + 20000);
    assert_int_equal(x->tx_calls, 2);
    assert_int_equal(lw_last(x, LW_TX)->at, last + T35_US);
    assert_int_equal(x->tx_len, 10);
    assert_memory_equal(x->tx, "\x05\x08\x00\x00\x12\x34\x56\x78", 8);
    lw_free(x);
}

/* The slave time (end of the request's last character to the end of the reply's first
 * character) in both modes, with the injected clock: FC08 (the CP alone) and FC03
 * (a job through the FB, CPU cycle 1 ms, 100 requests at every phase of the cycle).
 * Model: normal t3.5 + 1/2 cycle + 1 character; modem mode without t3.5. Printed. */
static void test_slave_time_normal_and_modem(void **state)
{
    (void)state;
    uint32_t avg[2];
    for (int modem = 0; modem < 2; modem++) {
        lw_t *x = start(modem ? MODCP_OPMODE_SUPPRESS : MODCP_OPMODE_NORMAL);
        uint64_t sum = 0;
        const unsigned n = 100;
        for (unsigned k = 0; k < n; k++) {
            lw_advance(x, lw_now(x) + 10000u + k * 10u); /* walk the phase over the cycle */
            unsigned before = x->tx_calls;
            uint32_t last = send(x, FC03_REQ, false);
            lw_advance(x, last + 30000);
            assert_int_equal(x->tx_calls, before + 1u);
            sum += lw_last(x, LW_TX)->at + CHAR_US - last;
        }
        avg[modem] = (uint32_t)(sum / n);
        uint32_t fc08 = 0;
        uint32_t last = send(x, FC08_REQ, false);
        lw_advance(x, last + 30000);
        fc08 = lw_last(x, LW_TX)->at + CHAR_US - last;
        printf("slave_time_us_%s_9600_fc03_cycle1ms_avg=%u fc08=%u (model: %s + 1/2 cycle "
               "500 + 1 character %u = %u)\n",
               modem ? "modem" : "normal", (unsigned)avg[modem], (unsigned)fc08,
               modem ? "1 us timer" : "t3.5 4000", CHAR_US,
               (modem ? 1u : T35_US) + 500u + CHAR_US);
        assert_int_equal(fc08, (modem ? 1u : T35_US) + CHAR_US);
        lw_free(x);
    }
    assert_true(avg[1] + T35_US - 1000u <= avg[0]); /* t3.5 saved, within a cycle */
    assert_true(avg[1] < T35_US);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_modem_stray_ff_before_request_answered),
        cmocka_unit_test(test_modem_stray_00_before_request_answered),
        cmocka_unit_test(test_modem_break_before_request_answered),
        cmocka_unit_test(test_modem_parity_error_before_request_answered),
        cmocka_unit_test(test_modem_stray_own_address_before_request_answered),
        cmocka_unit_test(test_normal_mode_stray_ff_loses_request),
        cmocka_unit_test(test_modem_other_address_not_mistaken_for_ours),
        cmocka_unit_test(test_modem_stray_characters_alone_not_counted),
        cmocka_unit_test(test_modem_crc_error_reported),
        cmocka_unit_test(test_modem_error_inside_frame_discards_it),
        cmocka_unit_test(test_modem_errors_after_crc_ignored_not_counted),
        cmocka_unit_test(test_modem_frame_ends_by_crc_without_t35),
        cmocka_unit_test(test_modem_frame_lengths_by_function_code),
        cmocka_unit_test(test_modem_every_known_request_ends_at_its_crc),
        cmocka_unit_test(test_modem_unknown_length_ends_by_t35),
        cmocka_unit_test(test_slave_time_normal_and_modem),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
