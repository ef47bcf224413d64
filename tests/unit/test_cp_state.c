/* SPDX-License-Identifier: Apache-2.0 */
/* The CP's state as the user sees it: SF (Siemens MODBUS slave driver manual §9.1.1, CP
 * 341 MODBUS ASCII slave manual §10.1), SYSTAT byte 0 (driver manual §9.2.3: 02H RUN,
 * 05H fault) and the RXD / TXD LEDs retriggered per frame (Altivar 71 integrated Modbus
 * guide §8). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "lineworld.h"
#include "modcp/backplane.h"
#include "modcp/leds.h"

#define FC08_REQ "05 08 00 00 A5 C3 DA 8E"
#define CHAR_US 1146u

/* SYSTAT image byte 0 as the CPU side reads it (the request is served by a poll). */
static uint8_t systat_state(world_t *w)
{
    uint32_t req = modcp_bp_systat_request(&w->bp);
    modcp_cp_poll(&w->cp, w->now_us);
    uint8_t img[16];
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    return img[0];
}

static uint32_t status_flags(world_t *w)
{
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    return st.flags;
}

/* Parameterised, FB not (yet) initialised: SF off ("off after initialisation", the CP's
 * own with its parameters), SYSTAT RUN; requests get exception 04 / (0E)56H. Without
 * valid parameters: SF on, SYSTAT 05H (fault). */
static void test_parameterised_cp_runs_before_fb_init(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_int_equal(systat_state(w), 0x05); /* power-on: no parameters yet */
    assert_true(status_flags(w) & MODCP_CPST_SF);
    modcp_fb_in_t in = {false}; /* the FB sends PARAMS at its first call, no CP_START */
    for (int k = 0; k < 20; k++) {
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        modcp_cp_poll(&w->cp, w->now_us);
        w->now_us += 1000;
    }
    assert_true(w->cp.configured);
    assert_false(modcp_cp_ready(&w->cp));
    assert_false(status_flags(w) & MODCP_CPST_SF);
    assert_int_equal(w->cp.leds.bits & 1u, 0); /* the SF LED */
    assert_int_equal(systat_state(w), 0x02);
    w->fb_paused = true;
    assert_true(world_request(w, FC08_REQ, 50) > 0);
    assert_string_equal(world_reply_hex(w), "05 88 04 06 02"); /* exception 04 */
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_FB_NOT_RUNNING);
    world_free(w);

    modcp_params_t p;
    world_example_params(&p);
    p.slave_addr = 0; /* rejected: (0E)23H */
    w = world_new(&p);
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    for (int k = 0; k < 20; k++) {
        modcp_cp_poll(&w->cp, w->now_us);
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        w->now_us += 1000;
    }
    assert_false(w->cp.configured);
    assert_true(status_flags(w) & MODCP_CPST_SF);
    assert_int_equal(systat_state(w), 0x05);
    world_free(w);
}

/* CP 341 ASCII slave manual §10.1: SF also "CTS/DSR not asserted" (RS232 automatic
 * signals): DSR OFF lights it until DSR is ON; CTS not ON when the data output waiting
 * time ends ((07)08H) lights it until CTS is ON again. A wire break is SF but the CP
 * still RUNs (SYSTAT 02H, B flag). */
static void test_sf_cts_dsr_not_asserted(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.rs232_auto = 1;
    p.rts_on_delay_ms = 10;
    lw_t *x = lw_new(&p);
    lw_signals(x, false, true); /* DSR ON, CTS OFF (idle: no RTS) */
    lw_advance(x, lw_now(x) + 2000);
    assert_false(status_flags(x->w) & MODCP_CPST_SF);
    lw_signals(x, false, false); /* DSR OFF */
    lw_advance(x, lw_now(x) + 2000);
    assert_true(status_flags(x->w) & MODCP_CPST_SF);
    assert_true(x->led[MODCP_LED_SF]);
    lw_signals(x, false, true);
    lw_advance(x, lw_now(x) + 2000);
    assert_false(status_flags(x->w) & MODCP_CPST_SF);

    uint32_t last = lw_send(x, FC08_REQ); /* CTS stays OFF: (07)08H */
    lw_advance(x, last + 40000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_CTS_TIMEOUT);
    assert_true(status_flags(x->w) & MODCP_CPST_SF);
    lw_signals(x, true, true);
    lw_advance(x, lw_now(x) + 2000);
    assert_false(status_flags(x->w) & MODCP_CPST_SF);

    lw_error(x, MODCP_LINE_BREAK); /* wire break: SF, still RUN */
    lw_advance(x, lw_now(x) + 2000);
    assert_true(status_flags(x->w) & MODCP_CPST_SF);
    assert_int_equal(systat_state(x->w), 0x02);
    lw_free(x);
}

/* Altivar guide §8: "each LED lights for 200 ms when a frame travels", retriggered: two
 * frames 150 ms apart keep RXD on without a gap until 200 ms after the second one's last
 * character. */
static void test_rxd_retriggered_per_frame(void **state)
{
    (void)state;
    lw_t *x = lw_new(NULL);
    lw_clear(x);
    x->cycles = false;
    uint32_t last1 = lw_send(x, "07 03 00 50 00 02 C4 4F"); /* another slave's frames */
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, last1 + 150000);
    uint32_t last2 = lw_send(x, "07 03 00 50 00 02 C4 4F");
    lw_advance(x, last1 + 200000);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]); /* 200 ms after the first: still on */
    lw_advance(x, last2 + 200000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, last2 + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    assert_int_equal(lw_count(x, LW_LED), 2); /* one on, one off */
    lw_free(x);
}

/* Siemens MODBUS slave driver manual (2009) Table 5-8: the receive-line preset reaches
 * the port with every valid parameter set (set_rx_preset); `default` is R(A) 5 V / R(B)
 * 0 V with BREAK detection on four-wire RS422 and R(A) 0 V / R(B) 5 V on two-wire RS485
 * (the manual's defaults), none on RS232. */
static void test_receive_preset_reaches_port(void **state)
{
    (void)state;
    static const struct {
        uint8_t iface, preset;
        int want;
    } cases[] = {
        {MODCP_IFACE_RS232, MODCP_RXP_DEFAULT, MODCP_RXP_NONE},
        {MODCP_IFACE_RS422, MODCP_RXP_DEFAULT, MODCP_RXP_BREAK},
        {MODCP_IFACE_RS485, MODCP_RXP_DEFAULT, MODCP_RXP_HIGH},
        {MODCP_IFACE_RS422, MODCP_RXP_NONE, MODCP_RXP_NONE},
        {MODCP_IFACE_RS422, MODCP_RXP_HIGH, MODCP_RXP_HIGH},
        {MODCP_IFACE_RS485, MODCP_RXP_NONE, MODCP_RXP_NONE},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        modcp_params_t p;
        world_example_params(&p);
        p.iface = cases[k].iface;
        p.opmode = p.iface == MODCP_IFACE_RS485 ? MODCP_OPMODE_SUPPRESS : MODCP_OPMODE_NORMAL;
        p.rx_preset = cases[k].preset;
        world_t *w = world_new(&p);
        assert_int_equal(w->fake.rx_preset, -1); /* nothing before the parameters */
        assert_true(world_start(w, 2000));
        assert_int_equal(w->fake.rx_preset, cases[k].want);
        world_free(w);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parameterised_cp_runs_before_fb_init),
        cmocka_unit_test(test_sf_cts_dsr_not_asserted),
        cmocka_unit_test(test_rxd_retriggered_per_frame),
        cmocka_unit_test(test_receive_preset_reaches_port),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
