/* SPDX-License-Identifier: Apache-2.0 */
/* RS232 automatic secondary signals ([RTU-2003] §2.4, [VIPA-341] §1.6): DTR / RTS outputs, CTS / DSR
 * inputs, data output waiting time, time to RTS off, aborts and their events
 * ((07)08H, (08)18H), and the one-shot timer shared with the link. End to end through
 * the CP on a simulated line with exact time (lineworld.h); thresholds at 1 us.
 *
 * Line: 9600 8E1 (character 1146 us, t3.5 4000 us); data output waiting time 10 ms,
 * time to RTS off 20 ms. The FC08 example ([RTU-2003] §6.7) is answered by the CP alone, so
 * its reply is ready exactly at t3.5 after the request. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal_log.h"
#include "lineworld.h"
#include "modcp/signals.h"
#include "params_internal.h"
#include "signals_internal.h"

#define FC03_REQ "05 03 00 50 00 02 C5 9E"
#define FC03_RSP "05 03 04 87 65 43 21 76 70"
#define FC08_REQ "05 08 00 00 A5 C3 DA 8E"
#define CHAR_US 1146u
#define T35_US 4000u
#define ON_US 10000u
#define OFF_US 20000u
#define SIG_RTS_ON ((MODCP_SIG_RTS << 1) | 1)
#define SIG_RTS_OFF (MODCP_SIG_RTS << 1)
#define SIG_DTR_ON ((MODCP_SIG_DTR << 1) | 1)
#define SIG_DTR_OFF (MODCP_SIG_DTR << 1)

static modcp_params_t auto_params(void)
{
    modcp_params_t p;
    world_example_params(&p);
    p.rs232_auto = 1;
    p.rts_on_delay_ms = 10;
    p.rts_off_delay_ms = 20;
    return p;
}

/* Started, CTS and DSR ON, log cleared. */
static lw_t *start(const modcp_params_t *p)
{
    lw_t *x = lw_new(p);
    memcpy(world_db(x->w, 800) + 160, "\x87\x65\x43\x21", 4);
    lw_signals(x, true, true);
    lw_clear(x);
    return x;
}

static modcp_sig_t *sig(lw_t *x)
{
    return &x->w->cp.sig;
}

/* ---- outputs at power-on and configuration --------------------------------------- */

/* [RTU-2003] §2.4: "at CP power-on the outputs are OFF"; with automatic use the CP sets
 * RTS = OFF, DTR = ON once configured; an invalid record takes DTR OFF again. */
static void test_outputs_power_on_and_configure(void **state)
{
    (void)state;
    fake_hal_log_t f;
    modcp_hal_t hal;
    fake_hal_log_init(&f, &hal, true);
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    static modcp_cp_t cp;
    modcp_cp_init(&cp, &hal, &bp);
    assert_int_equal(fake_hal_log_count(&f, FHL_SIG), 2);
    assert_int_equal(f.log[fake_hal_log_find(&f, FHL_SIG, 0)].value, SIG_RTS_OFF);
    assert_int_equal(fake_hal_log_last(&f, FHL_SIG)->value, SIG_DTR_OFF);

    modcp_params_t p = auto_params();
    lw_t *x = lw_new_unstarted(&p);
    assert_true(world_start(x->w, 2000));
    assert_int_equal(lw_count(x, LW_SIG), 1); /* RTS already OFF */
    assert_int_equal(lw_last(x, LW_SIG)->value, SIG_DTR_ON);
    assert_true(x->sig[MODCP_SIG_DTR]);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_true(sig(x)->enabled);
    lw_signals(x, true, true);
    lw_advance(x, lw_now(x) + 2000);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.signals, MODCP_SIGBIT_AUTO | MODCP_SIGBIT_DTR | MODCP_SIGBIT_CTS |
                                     MODCP_SIGBIT_DSR);
    lw_free(x);

    /* not automatic: outputs stay OFF, CTS / DSR are ignored */
    p.rs232_auto = 0;
    x = lw_new_unstarted(&p);
    assert_true(world_start(x->w, 2000));
    assert_int_equal(lw_count(x, LW_SIG), 0);
    assert_false(sig(x)->enabled);
    lw_signals(x, false, false);
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + T35_US);
    assert_int_equal(x->tx_calls, 1); /* at once, no RTS */
    assert_int_equal(lw_count(x, LW_SIG), 0);
    lw_free(x);

    /* automatic use is refused on RS485 / RS422 (half duplex via DE there) */
    p.rs232_auto = 1;
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    modcp_param_issue_t is[4];
    assert_int_equal(modcp_params_validate(&p, is, 4), 1);
    assert_int_equal(is[0].field, MODCP_PF_RS232_AUTO);
}

/* [VIPA-341] §1.6 "DTR: CP is ready for operation": DTR goes ON with a valid parameter record,
 * already before the FB's INIT (the CP is parameterised; requests still get exception
 * 04, (0E)56H until INIT, test_cp_examples.c: test_exception_04_not_initialised). */
static void test_dtr_on_with_parameters_before_fb_init(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = lw_new_unstarted(&p);
    world_t *w = x->w;
    modcp_fb_in_t in = {false}; /* the FB hands over PARAMS, no CP_START: no INIT */
    for (int k = 0; k < 20; k++) {
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        modcp_cp_poll(&w->cp, w->now_us);
        w->now_us += 1000;
    }
    assert_true(w->cp.configured);
    assert_false(w->cp.env.fb_ready);
    assert_true(x->sig[MODCP_SIG_DTR]);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->value, SIG_DTR_ON);
    lw_free(x);
}

/* ---- the send sequence ----------------------------------------------------------- */

/* RTS ON when the reply is ready; the reply leaves exactly when the data output
 * waiting time has elapsed (not 1 us before, even on an early expiry); RTS OFF exactly
 * the time to RTS off after transmission complete; the link receives again only then. */
static void test_send_sequence_thresholds(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready);
    assert_int_equal(lw_count(x, LW_SIG), 1);
    assert_int_equal(lw_last(x, LW_SIG)->value, SIG_RTS_ON);
    assert_int_equal(lw_last(x, LW_SIG)->at, t_ready);
    assert_int_equal(lw_last(x, LW_ARM)->value, ON_US);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_TURNAROUND);
    assert_int_equal(sig(x)->state, MODCP_SIGST_WAIT_CTS);
    lw_advance(x, t_ready + ON_US - 1);
    assert_int_equal(x->tx_calls, 0);
    lw_fire_now(x); /* early expiry: re-armed for the remaining 1 us */
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(lw_last(x, LW_ARM)->value, 1);
    lw_advance(x, t_ready + ON_US);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(lw_last(x, LW_TX)->at, t_ready + ON_US);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    assert_int_equal(sig(x)->state, MODCP_SIGST_SENDING);

    uint32_t t_done = t_ready + ON_US + 8u * CHAR_US;
    lw_advance(x, t_done);
    assert_true(x->sig[MODCP_SIG_RTS]); /* does not wait for CTS OFF, but for the delay */
    assert_int_equal(lw_last(x, LW_ARM)->value, OFF_US);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_TX); /* half duplex: not receiving */
    lw_advance(x, t_done + OFF_US - 1);
    lw_fire_now(x); /* early expiry: the link must not take it */
    assert_true(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_TX);
    assert_int_equal(lw_last(x, LW_ARM)->value, 1);
    lw_advance(x, t_done + OFF_US);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->at, t_done + OFF_US);
    assert_int_equal(lw_count(x, LW_SIG), 2);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(sig(x)->state, MODCP_SIGST_IDLE);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);

    /* the next request (needs the FB: FC03) goes the same way */
    last = lw_send(x, FC03_REQ);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 2);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_count(x, LW_SIG), 4);
    lw_free(x);
}

/* A request that starts while RTS is still ON after our reply: the master already has
 * the whole reply, so RTS goes OFF at its first character (not later) and the request
 * is served — masters such as libmodbus send their next request at once. */
static void test_request_during_rts_off_time(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_done = last + T35_US + ON_US + 8u * CHAR_US;
    lw_advance(x, t_done + 1000);
    assert_true(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(sig(x)->state, MODCP_SIGST_RTS_OFF);
    uint32_t first = lw_now(x);
    lw_send(x, FC08_REQ);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->at, first);
    assert_int_not_equal(world_last_event(x->w), MODCP_EV_SEQUENCE);
    lw_advance(x, t_done + OFF_US + 50000);
    assert_int_equal(x->tx_calls, 2);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    lw_free(x);
}

/* Waiting time 0: RTS ON and the reply in the same instant, RTS first. Time to RTS off
 * 0: RTS OFF at transmission complete. */
static void test_zero_delays(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    p.rts_on_delay_ms = 0;
    p.rts_off_delay_ms = 0;
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready);
    long rts = lw_find(x, LW_SIG, SIG_RTS_ON, 0);
    long tx = lw_find(x, LW_TX, -1, 0);
    assert_true(rts >= 0 && tx > rts);
    assert_int_equal(x->log[tx].at, t_ready);
    lw_advance(x, t_ready + 8u * CHAR_US);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->at, t_ready + 8u * CHAR_US);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    lw_free(x);
}

/* ---- CTS ------------------------------------------------------------------------- */

/* CTS not ON when the waiting time has elapsed: (07)08H, nothing sent, RTS OFF; CTS
 * that comes ON during the waiting time: sent at its end, not earlier. */
static void test_cts_timeout(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    lw_signals(x, false, true);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready + ON_US - 1);
    assert_true(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    lw_advance(x, t_ready + ON_US);
    assert_int_equal(x->tx_calls, 0);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->at, t_ready + ON_US);
    assert_int_equal(world_last_event(x->w), MODCP_EV_CTS_TIMEOUT);
    lw_poll(x); /* the status area is published by the CP task */
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.status, 0x0708);
    assert_int_equal(st.signal_aborts, 1);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    lw_signals(x, true, true); /* too late for that reply */
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 0);

    /* CTS OFF at the request, ON 5 ms into the waiting time */
    lw_signals(x, false, true);
    last = lw_send(x, FC08_REQ);
    t_ready = last + T35_US;
    lw_advance(x, t_ready + 5000);
    lw_signals(x, true, true);
    lw_advance(x, t_ready + ON_US - 1);
    assert_int_equal(x->tx_calls, 0);
    lw_advance(x, t_ready + ON_US);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    lw_free(x);
}

/* CTS ON -> OFF while sending: (08)18H, the transmission is aborted, RTS OFF at once,
 * the CP receives again; the late or missing transmission complete changes nothing. */
static void test_cts_off_while_sending(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_tx = last + T35_US + ON_US;
    lw_advance(x, t_tx + 2000);
    assert_int_equal(x->tx_calls, 1);
    lw_signals(x, false, true);
    assert_int_equal(world_last_event(x->w), MODCP_EV_SIGNAL_OFF);
    assert_int_equal(lw_count(x, LW_ABORT), 1);
    assert_int_equal(lw_last(x, LW_ABORT)->at, t_tx + 2000);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(lw_last(x, LW_SIG)->at, t_tx + 2000);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(sig(x)->state, MODCP_SIGST_IDLE);
    /* a transmission complete that a port reports anyway is ignored */
    modcp_cp_on_tx_done(&x->w->cp, lw_now(x) + 5000);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(lw_count(x, LW_SIG), 2);
    /* CTS OFF outside a transmission: no event */
    lw_signals(x, true, true);
    lw_signals(x, false, true);
    lw_signals(x, true, true);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    lw_advance(x, lw_now(x) + 10000);
    last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 2);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    lw_free(x);
}

/* ---- DSR ------------------------------------------------------------------------- */

/* Receiving only while DSR = ON: a request with DSR OFF is not seen at all (no event:
 * no ON -> OFF edge). */
static void test_dsr_off_no_reception(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = lw_new(&p);
    lw_clear(x);
    /* the port has not reported the inputs yet: both OFF */
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_BUS_MSG], 0);
    lw_signals(x, true, true);
    last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    lw_free(x);
}

/* DSR ON -> OFF in the middle of a request: (08)18H, the frame is dropped without
 * (08)36H; DSR ON again: the next request is served. */
static void test_dsr_off_while_receiving(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    lw_send(x, "05 08 00 00");
    lw_signals(x, true, false);
    assert_int_equal(world_last_event(x->w), MODCP_EV_SIGNAL_OFF);
    uint32_t t = lw_now(x);
    lw_advance(x, t + CHAR_US);
    lw_send(x, "A5 C3 DA 8E"); /* dropped: DSR OFF */
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    assert_int_equal(lw_status(x).signal_aborts, 1);
    lw_signals(x, true, true);
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    lw_free(x);
}

/* DSR ON -> OFF while waiting for the data output time, and while sending: (08)18H,
 * aborted, RTS OFF at once. */
static void test_dsr_off_while_sending(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready + 3000);
    lw_signals(x, true, false);
    assert_int_equal(world_last_event(x->w), MODCP_EV_SIGNAL_OFF);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    lw_advance(x, t_ready + ON_US + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 1); /* no (07)08H on top */
    assert_true(x->sig[MODCP_SIG_DTR]);           /* DTR stays ON: the CP is ready */

    lw_signals(x, true, true);
    last = lw_send(x, FC08_REQ);
    uint32_t t_tx = last + T35_US + ON_US;
    lw_advance(x, t_tx + 1000);
    assert_int_equal(x->tx_calls, 1);
    lw_signals(x, true, false);
    assert_int_equal(lw_count(x, LW_ABORT), 1);
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_int_equal(x->w->cp.diag.buffer_len, 2);
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_SIGNAL_OFF);
    lw_poll(x);
    assert_int_equal(lw_status(x).signal_aborts, 2);
    lw_free(x);
}

/* DSR drops while the FB processes the request: (08)18H at the edge; when the reply is
 * ready DSR is still OFF: dropped, RTS never ON, no second event. */
static void test_dsr_off_while_job_pending(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    x->w->fb_paused = true;
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + 10000);
    lw_signals(x, true, false);
    x->w->fb_paused = false;
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(lw_count(x, LW_SIG), 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    lw_free(x);
}

/* A port without uart_tx_abort: the aborted frame finishes on the wire and its
 * transmission complete is ignored. */
static void test_abort_without_port_support(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    x->w->hal.uart_tx_abort = NULL;
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_tx = last + T35_US + ON_US;
    lw_advance(x, t_tx + 1000);
    lw_signals(x, false, true);
    assert_int_equal(lw_count(x, LW_ABORT), 0);
    assert_false(x->sig[MODCP_SIG_RTS]);
    lw_advance(x, t_tx + 8u * CHAR_US); /* the UART finishes: ignored */
    assert_int_equal(lw_count(x, LW_TXDONE), 1);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(lw_count(x, LW_SIG), 2);
    lw_free(x);
}

/* Re-parameterisation in the middle of a send: everything OFF, then DTR ON again. */
static void test_reparameterisation_resets(void **state)
{
    (void)state;
    modcp_params_t p = auto_params();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + T35_US + 1000);
    assert_true(x->sig[MODCP_SIG_RTS]);
    modcp_params_t q;
    modcp_params_apply(&p, &q, NULL);
    modcp_sig_disable(sig(x));
    assert_false(x->sig[MODCP_SIG_RTS]);
    assert_false(x->sig[MODCP_SIG_DTR]);
    assert_false(modcp_sig_on_timer(sig(x), &x->w->cp.link, lw_now(x)));
    modcp_sig_configure(sig(x), &q);
    assert_true(x->sig[MODCP_SIG_DTR]);
    assert_false(x->sig[MODCP_SIG_RTS]);
    lw_free(x);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outputs_power_on_and_configure),
        cmocka_unit_test(test_dtr_on_with_parameters_before_fb_init),
        cmocka_unit_test(test_send_sequence_thresholds),
        cmocka_unit_test(test_request_during_rts_off_time),
        cmocka_unit_test(test_zero_delays),
        cmocka_unit_test(test_cts_timeout),
        cmocka_unit_test(test_cts_off_while_sending),
        cmocka_unit_test(test_dsr_off_no_reception),
        cmocka_unit_test(test_dsr_off_while_receiving),
        cmocka_unit_test(test_dsr_off_while_sending),
        cmocka_unit_test(test_dsr_off_while_job_pending),
        cmocka_unit_test(test_abort_without_port_support),
        cmocka_unit_test(test_reparameterisation_resets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
