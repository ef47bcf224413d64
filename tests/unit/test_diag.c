/* SPDX-License-Identifier: Apache-2.0 */
/* Diagnostics (docs/diagnostics.md, [RTU-2003] §7, [VIPA-341] §8): STATUS word, diagnostic buffer, SYSTAT (first
 * six events, F / U / B, clear on read) and its service over the backplane, the
 * diagnostic interrupt records, wire break, the LEDs SF / TXD / RXD with their 200 ms
 * minimum on-time (1 us resolution), the status area, the diag_irq parameter, and the
 * events raised by cpdiag.c / the receive automaton ((0E)11H, (0E)30H, (0E)3CH). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal_log.h"
#include "lineworld.h"
#include "modcp/cpdiag.h"
#include "modcp/diag.h"
#include "modcp/leds.h"
#include "backplane_internal.h"
#include "cpdiag_internal.h"
#include "diag_internal.h"
#include "job_internal.h"
#include "params_internal.h"

#define FC08_REQ "05 08 00 00 A5 C3 DA 8E" /* [RTU-2003] §6.7, answered by the CP alone */
#define CHAR_US 1146u
#define T35_US 4000u
#define LED_ON(led) (((uint32_t)(led) << 1) | 1u)
#define LED_OFF(led) ((uint32_t)(led) << 1)

static modcp_params_t example(void)
{
    modcp_params_t p;
    world_example_params(&p);
    return p;
}

/* ---- STATUS word, diagnostic buffer, SYSTAT -------------------------------------- */

/* [VIPA-341] §8.1: bits 15..13 reserved (0), 12..8 class, 7..0 number; the last event. */
static void test_status_word(void **state)
{
    (void)state;
    modcp_diag_t d;
    modcp_diag_init(&d);
    assert_int_equal(d.status, 0);
    modcp_diag_event(&d, MODCP_EV_CRC);
    assert_int_equal(d.status, 0x0836);
    modcp_diag_event(&d, MODCP_EV_FB_NOT_RUNNING);
    assert_int_equal(d.status, 0x0E56);
    modcp_diag_event(&d, MODCP_EV_JOB_LENGTH); /* [VIPA-341] §8.2: (05)17H, "transfer length
                                                  > 1 kByte is too large for the CP" */
    assert_int_equal(d.status, 0x0517);
    modcp_diag_event(&d, MODCP_EV_CTS_TIMEOUT);
    assert_int_equal(d.status, 0x0708);
    modcp_diag_event(&d, MODCP_EVENT(0xFF, 0x01)); /* class wider than 5 bits: masked */
    assert_int_equal(d.status, 0x1F01);
    modcp_diag_event(&d, MODCP_EV_NONE); /* ignored */
    assert_int_equal(d.status, 0x1F01);
    assert_int_equal(d.events_total, 5);
}

/* [VIPA-341] §8.3: ring of 9 entries, newest first, the oldest drops out. */
static void test_diag_buffer_ring(void **state)
{
    (void)state;
    modcp_diag_t d;
    modcp_diag_init(&d);
    for (uint8_t i = 1; i <= 11; i++) {
        modcp_diag_event(&d, MODCP_EVENT(0x08, i));
    }
    assert_int_equal(d.buffer_len, 9);
    for (uint8_t k = 0; k < 9; k++) {
        assert_int_equal(d.buffer[k], MODCP_EVENT(0x08, 11 - k));
    }
    assert_int_equal(d.events_total, 11);
}

/* [RTU-2003] §7.4: only the first six events since the last read; F = an event entered,
 * U = overflow, B = BREAK; reading gives the 16-byte image and clears it. */
static void test_systat_image(void **state)
{
    (void)state;
    modcp_diag_t d;
    modcp_diag_init(&d);
    uint8_t img[16];
    modcp_diag_read_systat(&d, true, img);
    static const uint8_t empty_run[16] = {0x02};
    assert_memory_equal(img, empty_run, 16);

    modcp_diag_event(&d, MODCP_EV_CRC);
    modcp_diag_event(&d, MODCP_EV_BREAK);
    modcp_diag_event(&d, MODCP_EV_SEQUENCE);
    modcp_diag_event(&d, MODCP_EV_FB_NOT_RUNNING);
    modcp_diag_event(&d, MODCP_EV_CHAR_ERROR);
    assert_int_equal(d.systat_flags, MODCP_SYSTAT_F | MODCP_SYSTAT_B);
    modcp_diag_event(&d, MODCP_EV_ZVZ);
    assert_int_equal(d.systat_flags, MODCP_SYSTAT_F | MODCP_SYSTAT_B);
    modcp_diag_event(&d, MODCP_EV_XFER_TIMEOUT); /* the seventh: not entered, U */
    assert_int_equal(d.systat_flags, MODCP_SYSTAT_F | MODCP_SYSTAT_B | MODCP_SYSTAT_U);
    modcp_diag_read_systat(&d, true, img);
    static const uint8_t want[16] = {0x02, 0x00, 0x07, 0x00, 0x08, 0x36, 0x08, 0x0D,
                                     0x08, 0x37, 0x0E, 0x56, 0x08, 0x0C, 0x08, 0x06};
    assert_memory_equal(img, want, 16);
    /* cleared on read; the diagnostic buffer is not */
    assert_int_equal(d.systat_len, 0);
    assert_int_equal(d.systat_flags, 0);
    assert_int_equal(d.buffer_len, 7);
    assert_int_equal(d.buffer[0], MODCP_EV_XFER_TIMEOUT);
    modcp_diag_event(&d, MODCP_EV_BREAK); /* after the read: entered again */
    modcp_diag_read_systat(&d, false, img);
    static const uint8_t want2[16] = {0x05, 0x00, 0x05, 0x00, 0x08, 0x0D};
    assert_memory_equal(img, want2, 16);
}

/* The CPU side reads SYSTAT through the backplane: request, the CP answers at its next
 * poll with the image and clears SYSTAT; an event between request and poll is in it,
 * an event after the poll is in the next image. */
static void test_systat_service(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* (08)36H */
    uint32_t req = modcp_bp_systat_request(&w->bp);
    assert_int_equal(req, 1);
    uint8_t img[16];
    assert_false(modcp_bp_systat_result(&w->bp, req, img)); /* not yet answered */
    assert_int_equal(world_request(w, "05 08 00 01 A5 C3 00 00", 100), 0); /* CRC again */
    world_run(w, 1000);
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    static const uint8_t want[16] = {0x02, 0x00, 0x01, 0x00, 0x08, 0x36, 0x08, 0x36};
    assert_memory_equal(img, want, 16);
    assert_int_equal(w->cp.diag.systat_len, 0);
    assert_int_equal(w->cp.diag.buffer_len, 2); /* the diagnostic buffer keeps them */

    /* an event after the answer goes into the next image only */
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0);
    world_run(w, 1000);
    assert_true(modcp_bp_systat_result(&w->bp, req, img)); /* the old answer stands */
    assert_memory_equal(img, want, 16);
    req = modcp_bp_systat_request(&w->bp);
    assert_int_equal(req, 2);
    world_run(w, 1000);
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    static const uint8_t want2[16] = {0x02, 0x00, 0x01, 0x00, 0x08, 0x36};
    assert_memory_equal(img, want2, 16);
    req = modcp_bp_systat_request(&w->bp);
    world_run(w, 1000);
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    static const uint8_t empty[16] = {0x02};
    assert_memory_equal(img, empty, 16);
    world_free(w);
}

/* A CP that is not ready reports 05H (fault) in byte 0. */
static void test_systat_fault_state(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.slave_addr = 0;
    p.start_time_ms = 300;
    world_t *w = world_new(&p);
    assert_false(world_start(w, 1000));
    uint32_t req = modcp_bp_systat_request(&w->bp);
    world_run(w, 1000);
    uint8_t img[16];
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    assert_int_equal(img[0], 0x05);
    assert_int_equal(img[2] & MODCP_SYSTAT_F, MODCP_SYSTAT_F);
    assert_int_equal(img[4], 0x0E);
    assert_int_equal(img[5], 0x23); /* the parameter event */
    world_free(w);
}

/* VIPA CP 341-1AH01 manual §8.3 (CP diagnostic buffer): "power-off or
 * re-parameterisation of the CP clears it". Events of the previous parameterisation are
 * gone after a new record; the new record's own events are kept. */
static void test_diag_buffer_cleared_on_reparameterisation_8_3(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* (08)36H */
    world_run(w, 100);
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_CRC);

    /* a changed valid record and a CP_START edge re-parameterise the CP: buffer empty
     * (the same record would not: test_fb_restart.c) */
    w->params.cpu_timeout_ms = 1500;
    w->record_len = (uint16_t)modcp_params_encode(&w->params, w->record, sizeof w->record);
    modcp_fb_in_t in = {false};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    w->now_us += 1000;
    assert_true(world_start(w, 2000));
    assert_int_equal(w->cp.diag.buffer_len, 0);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_NONE);
    /* the line still reports into the emptied buffer */
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0);
    world_run(w, 100);
    assert_int_equal(w->cp.diag.buffer_len, 1);

    /* an invalid record: the buffer holds its event only */
    w->params.slave_addr = 0;
    w->params.start_time_ms = 300;
    w->record_len = modcp_params_encode(&w->params, w->record, sizeof w->record);
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    w->now_us += 1000;
    assert_false(world_start(w, 1000));
    assert_true(w->cp.diag.buffer_len >= 1);
    for (unsigned i = 0; i < w->cp.diag.buffer_len; i++) {
        assert_int_equal(w->cp.diag.buffer[i], MODCP_EV_SLAVE_ADDR); /* (0E)23H, no (08)36H */
    }
    world_free(w);
}

/* ---- wire break and diagnostic interrupt --------------------------------------- */

static lw_t *start(const modcp_params_t *p)
{
    lw_t *x = lw_new(p);
    lw_clear(x);
    return x;
}

/* [VIPA-341] §8.4: BREAK on RxD (normal mode) -> 25 0C 02 00, once while it lasts; SF on; the
 * next good character ends it -> 00 0C 00 00 (going), SF off. */
static void test_diag_irq_wire_break(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.diag_irq = 1;
    lw_t *x = start(&p);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.diag_irq_count, 0);
    assert_false(st.flags & MODCP_CPST_SF);
    lw_error(x, MODCP_LINE_BREAK | MODCP_LINE_FRAMING);
    assert_int_equal(world_last_event(x->w), MODCP_EV_BREAK);
    lw_advance(x, lw_now(x) + 10000);
    lw_error(x, MODCP_LINE_BREAK); /* still broken: no second interrupt */
    lw_advance(x, lw_now(x) + 10000);
    st = lw_status(x);
    static const uint8_t coming[4] = {0x25, 0x0C, 0x02, 0x00};
    assert_memory_equal(st.diag_irq, coming, 4);
    assert_int_equal(st.diag_irq_count, 1);
    assert_true(st.flags & MODCP_CPST_WIRE_BREAK);
    assert_true(st.flags & MODCP_CPST_SF);
    assert_true(x->led[MODCP_LED_SF]);
    assert_true(st.leds & (1u << MODCP_LED_SF));

    uint32_t last = lw_send(x, FC08_REQ); /* the line is back */
    lw_advance(x, last + 20000);
    assert_int_equal(x->tx_calls, 1);
    st = lw_status(x);
    static const uint8_t going[4] = {0x00, 0x0C, 0x00, 0x00};
    assert_memory_equal(st.diag_irq, going, 4);
    assert_int_equal(st.diag_irq_count, 2);
    assert_false(st.flags & (MODCP_CPST_WIRE_BREAK | MODCP_CPST_SF));
    assert_false(x->led[MODCP_LED_SF]);
    lw_free(x);

    /* interrupt off (default): wire break and SF all the same, no record */
    p.diag_irq = 0;
    x = start(&p);
    lw_error(x, MODCP_LINE_BREAK);
    lw_advance(x, lw_now(x) + 2000);
    st = lw_status(x);
    assert_int_equal(st.diag_irq_count, 0);
    assert_true(st.flags & MODCP_CPST_WIRE_BREAK);
    assert_true(x->led[MODCP_LED_SF]);
    lw_free(x);

    /* interference suppression and RS485 ignore BREAK: no wire break */
    p.diag_irq = 1;
    p.opmode = MODCP_OPMODE_SUPPRESS;
    x = start(&p);
    lw_error(x, MODCP_LINE_BREAK);
    lw_advance(x, lw_now(x) + 2000);
    st = lw_status(x);
    assert_int_equal(st.diag_irq_count, 0);
    assert_false(st.flags & (MODCP_CPST_WIRE_BREAK | MODCP_CPST_SF));
    assert_int_equal(st.breaks, 1);
    lw_free(x);
}

/* [VIPA-341] §8.4: parameterisation error -> 83 0C 00 00, once (not at every retry of the
 * FB); valid parameters later -> going. */
static void test_diag_irq_param_error(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.diag_irq = 1;
    p.slave_addr = 0;
    p.start_time_ms = 1000;
    world_t *w = world_new(&p);
    assert_false(world_start(w, 3000)); /* the FB retried for START_TIME */
    world_run(w, 1000);
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    static const uint8_t coming[4] = {0x83, 0x0C, 0x00, 0x00};
    assert_memory_equal(st.diag_irq, coming, 4);
    assert_int_equal(st.diag_irq_count, 1);
    assert_true(st.flags & MODCP_CPST_PARAM_ERROR);
    assert_true(st.flags & MODCP_CPST_SF);
    assert_int_equal(st.param_event, MODCP_EV_SLAVE_ADDR);

    /* corrected record, new CP_START edge */
    w->params.slave_addr = 5;
    size_t n = modcp_params_encode(&w->params, w->record, sizeof w->record);
    assert_int_equal(n, w->record_len);
    modcp_fb_in_t in = {false};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    w->now_us += 1000;
    assert_true(world_start(w, 2000));
    world_run(w, 1000);
    assert_true(modcp_bp_read_status(&w->bp, &st));
    static const uint8_t going[4] = {0x00, 0x0C, 0x00, 0x00};
    assert_memory_equal(st.diag_irq, going, 4);
    assert_int_equal(st.diag_irq_count, 2);
    assert_false(st.flags & (MODCP_CPST_PARAM_ERROR | MODCP_CPST_SF));
    world_free(w);
}

/* cpdiag alone: the setting of an undecodable record is the previous one; disabled:
 * no records; reparameterisation ends a wire break. */
static void test_cpdiag_unit(void **state)
{
    (void)state;
    modcp_cpdiag_t d;
    modcp_cpdiag_init(&d);
    modcp_cpdiag_params(&d, false, -1); /* default off: nothing */
    assert_int_equal(d.irq_count, 0);
    assert_true(d.param_error);
    modcp_cpdiag_params(&d, true, 1); /* on, and the fault is gone */
    assert_int_equal(d.irq_count, 1);
    assert_int_equal(d.irq[0], 0x00);
    modcp_cpdiag_params(&d, false, -1); /* CRC broken: still on */
    assert_int_equal(d.irq_count, 2);
    assert_int_equal(d.irq[0], 0x83);
    modcp_cpdiag_params(&d, false, 1); /* rejected again: no new interrupt */
    assert_int_equal(d.irq_count, 2);
    modcp_cpdiag_params(&d, true, 1);
    assert_int_equal(d.irq_count, 3);
    modcp_cpdiag_line_error(&d, MODCP_LINE_PARITY, true); /* not a BREAK */
    assert_false(d.wire_break);
    modcp_cpdiag_line_error(&d, MODCP_LINE_BREAK, false); /* not reported (suppression) */
    assert_false(d.wire_break);
    modcp_cpdiag_line_error(&d, MODCP_LINE_BREAK, true);
    assert_true(d.wire_break);
    assert_int_equal(d.irq_count, 4);
    modcp_cpdiag_params(&d, true, 0); /* reparameterised, interrupt now off */
    assert_false(d.wire_break);
    assert_int_equal(d.irq_count, 4);
}

/* ---- the diag_irq parameter ---------------------------------------------------- */

static void test_diag_irq_parameter(void **state)
{
    (void)state;
    modcp_params_t p;
    modcp_params_defaults(&p);
    assert_int_equal(p.diag_irq, 0); /* [VIPA-341] §8.4: disabled by default */
    p.diag_irq = 2;
    modcp_param_issue_t is[4];
    assert_int_equal(modcp_params_validate(&p, is, 4), 1);
    assert_int_equal(is[0].field, MODCP_PF_DIAG_IRQ);
    assert_int_equal(is[0].event, MODCP_EV_PARAM_RECORD);
    assert_true(is[0].fatal);
    assert_int_equal(is[0].value, 2);
    p.diag_irq = 1;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    uint8_t buf[MODCP_PARAMS_RECORD_MAX];
    size_t n = modcp_params_encode(&p, buf, sizeof buf);
    assert_int_equal(buf[n - 3], 1); /* the last payload byte */
    modcp_params_t q;
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_NONE);
    assert_int_equal(q.diag_irq, 1);
}

/* ---- LEDs ----------------------------------------------------------------------- */

/* Power-on: SF on, TXD and RXD off, each set once; SF off when the FB is initialised. */
static void test_leds_power_on(void **state)
{
    (void)state;
    fake_hal_log_t f;
    modcp_hal_t hal;
    fake_hal_log_init(&f, &hal, true);
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    static modcp_cp_t cp;
    modcp_cp_init(&cp, &hal, &bp);
    assert_int_equal(fake_hal_log_count(&f, FHL_LED), 3);
    long i = fake_hal_log_find(&f, FHL_LED, 0);
    assert_int_equal(f.log[i].value, LED_ON(MODCP_LED_SF));
    assert_int_equal(f.log[i + 1].value, LED_OFF(MODCP_LED_TXD));
    assert_int_equal(f.log[i + 2].value, LED_OFF(MODCP_LED_RXD));
    f.now = 5000;
    modcp_cp_poll(&cp, 5000); /* nothing changes: no call */
    assert_int_equal(fake_hal_log_count(&f, FHL_LED), 3);

    lw_t *x = lw_new_unstarted(NULL);
    assert_true(world_start(x->w, 2000));
    world_run(x->w, 1000);
    assert_false(x->led[MODCP_LED_SF]);
    assert_int_equal(lw_count(x, LW_LED), 1); /* only SF went off */
    assert_int_equal(lw_last(x, LW_LED)->value, LED_OFF(MODCP_LED_SF));
    lw_free(x);
}

/* Altivar 71 Modbus guide §8 ("each LED lights for 200 ms when a frame travels",
 * retriggered): RXD on at the first character of a frame, TXD on when the reply
 * starts; each stays on exactly 200 ms after the frame — RXD after its last character,
 * TXD after transmission complete (off at 200 ms, not at 200 ms - 1 us). */
static void test_leds_min_on_time(void **state)
{
    (void)state;
    lw_t *x = start(NULL);
    x->cycles = false; /* polls only where the test says */
    uint32_t t0 = lw_now(x) + 1000;
    lw_advance(x, t0);
    lw_byte(x, 0x05);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    assert_int_equal(lw_last(x, LW_LED)->at, t0);
    lw_advance(x, t0 + CHAR_US);
    uint32_t last = lw_send(x, "08 00 00 A5 C3 DA 8E");
    lw_poll(x);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready);
    assert_int_equal(x->tx_calls, 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_TXD]);
    assert_int_equal(lw_last(x, LW_LED)->at, t_ready);
    lw_advance(x, t_ready + 8 * CHAR_US); /* transmission complete */
    lw_poll(x);
    assert_true(x->led[MODCP_LED_TXD]);

    lw_advance(x, last + 200000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, last + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    assert_int_equal(lw_last(x, LW_LED)->at, last + 200000);
    uint32_t t_done = t_ready + 8 * CHAR_US;
    lw_advance(x, t_done + 200000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_TXD]);
    lw_advance(x, t_done + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_TXD]);
    assert_int_equal(lw_last(x, LW_LED)->at, t_done + 200000);
    assert_int_equal(lw_count(x, LW_LED), 4); /* RXD on/off, TXD on/off: no repeats */
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&x->w->bp, &st));
    assert_int_equal(st.leds, 0);
    lw_free(x);
}

/* The minimum counts from switching on, however late the poll: a frame seen only by a
 * poll 50 ms after it still lights RXD for 200 ms. */
static void test_leds_late_poll(void **state)
{
    (void)state;
    lw_t *x = start(NULL);
    x->cycles = false;
    uint32_t last = lw_send(x, "07 03 00 50 00 02 C4 4F"); /* another slave's frame */
    lw_advance(x, last + 50000);
    lw_poll(x);
    uint32_t t_on = lw_now(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, t_on + 199999);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, t_on + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    assert_false(x->led[MODCP_LED_TXD]);
    lw_free(x);
}

/* 300 baud: a frame longer than 200 ms keeps RXD on until 200 ms after its last
 * character (its end, t3.5 = 128 ms after it, is earlier); a reply longer than 200 ms
 * keeps TXD on until 200 ms after transmission complete. */
static void test_leds_long_frames(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.baud = 300;
    lw_t *x = start(&p);
    x->cycles = false;
    assert_int_equal(x->char_us, 36667);
    uint32_t t0 = lw_now(x);
    lw_byte(x, 0x05);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, t0 + x->char_us);
    uint32_t last = lw_send(x, "08 00 00 A5 C3 DA 8E"); /* t0 + 256669 */
    assert_true(last - t0 > 200000);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, last + 128000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    uint32_t t_ready = last + 128000; /* the timer ends the frame and the reply starts */
    lw_advance(x, t_ready);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    assert_true(x->led[MODCP_LED_TXD]);
    lw_advance(x, last + 200000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]);
    lw_advance(x, last + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    uint32_t t_done = t_ready + 8u * x->char_us; /* 293336 us later */
    lw_advance(x, t_done + 200000 - 1);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_TXD]);
    lw_advance(x, t_done + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_TXD]);
    assert_int_equal(lw_last(x, LW_LED)->at, t_done + 200000);
    lw_free(x);
}

/* RS485: the echo of our own reply does not light RXD. */
static void test_leds_rs485_echo(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    lw_t *x = start(&p);
    x->cycles = false;
    x->auto_tx_done = false; /* the reply stays on the line */
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + T35_US);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_TX);
    lw_poll(x);
    assert_true(x->led[MODCP_LED_RXD]); /* the request */
    lw_advance(x, lw_now(x) + 200000);
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    lw_send(x, FC08_REQ); /* our own reply coming back on the two-wire line */
    lw_poll(x);
    assert_false(x->led[MODCP_LED_RXD]);
    assert_true(x->led[MODCP_LED_TXD]);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    lw_free(x);
}

/* ---- events of the receive automaton and the backplane -------------------------- */

/* (0E)11H: the receive automaton finds a state it never uses (corrupted): reported,
 * back to idle, and the character starts a frame: the request is still served. */
static void test_internal_receive_error(void **state)
{
    (void)state;
    lw_t *x = start(NULL);
    x->w->cp.link.state = 0x7F;
    uint32_t last = lw_send(x, FC08_REQ);
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_INTERNAL_RECEIVE);
    lw_advance(x, last + 20000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    x->w->cp.link.state = 0x7E;
    lw_error(x, MODCP_LINE_PARITY);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(x->w->cp.diag.buffer_len, 3); /* 0E11, 080C, 0E11 */
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_INTERNAL_RECEIVE);
    /* a corrupted state that shares a bit with RX and SKIP (0x0C: bit 2, as RX = 4) is
     * no frame arriving: an expiry less than t3.5 after the last character arms
     * nothing more (only RX and SKIP re-arm the rest of t3.5) */
    lw_advance(x, lw_now(x) + 20000);
    x->w->cp.link.last_us = lw_now(x);
    x->w->cp.link.state = 0x0C;
    size_t arms = lw_count(x, LW_ARM);
    lw_fire_now(x);
    assert_int_equal(lw_count(x, LW_ARM), arms);
    lw_free(x);
}

/* (0E)3CH: a message kind the CPU side must not send (JOB travels CP -> CPU);
 * (0E)30H: an unexpected block (a PARAMS continuation without its start). */
static void test_backplane_protocol_events(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    modcp_block_t b;
    memset(&b, 0, sizeof b);
    b.kind = MODCP_BP_JOB;
    b.flags = MODCP_BLK_FIRST | MODCP_BLK_LAST;
    b.len = 8;
    assert_true(modcp_ring_put(&w->bp.to_cp, &b, &w->fb.tx_seq));
    world_run(w, 1000);
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_int_equal(world_last_event(w), MODCP_EV_ILLEGAL_JOB);
    b.kind = MODCP_BP_PARAMS;
    b.flags = MODCP_BLK_LAST;
    assert_true(modcp_ring_put(&w->bp.to_cp, &b, &w->fb.tx_seq));
    world_run(w, 1000);
    assert_int_equal(w->cp.diag.buffer_len, 2);
    assert_int_equal(world_last_event(w), MODCP_EV_XFER_ACK);
    world_run(w, 5000); /* reported once */
    assert_int_equal(w->cp.diag.buffer_len, 2);
    /* the CP works on */
    assert_int_equal(world_request(w, FC08_REQ, 100), 8);
    world_free(w);
}

/* cpdiag alone: the error kinds job.c saw since the last call (its new_errors), each
 * reported once per call; a call with nothing new reports nothing. */
static void test_backplane_error_kinds(void **state)
{
    (void)state;
    modcp_diag_t d;
    modcp_diag_init(&d);
    modcp_cpdiag_backplane(&d, MODCP_JOB_ERR_PROTO | MODCP_JOB_ERR_ILLEGAL); /* both kinds */
    assert_int_equal(d.buffer_len, 2);
    assert_int_equal(d.buffer[0], MODCP_EV_XFER_ACK);
    assert_int_equal(d.buffer[1], MODCP_EV_ILLEGAL_JOB);
    modcp_cpdiag_backplane(&d, 0u); /* nothing new */
    assert_int_equal(d.buffer_len, 2);
    modcp_cpdiag_backplane(&d, MODCP_JOB_ERR_ILLEGAL); /* one illegal only */
    assert_int_equal(d.buffer_len, 3);
    assert_int_equal(d.buffer[0], MODCP_EV_ILLEGAL_JOB);
    modcp_cpdiag_backplane(&d, MODCP_JOB_ERR_PROTO); /* others only */
    assert_int_equal(d.buffer_len, 4);
    assert_int_equal(d.buffer[0], MODCP_EV_XFER_ACK);
}

/* ---- the status area (what the console's `diag` / `status` print) -------------- */

static void test_status_area_fields(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.t15_check = 1;
    lw_t *x = start(&p);
    lw_error(x, MODCP_LINE_PARITY);
    lw_advance(x, lw_now(x) + 10000);
    lw_error(x, MODCP_LINE_BREAK);
    lw_advance(x, lw_now(x) + 10000);
    uint32_t last = lw_send_gap(x, FC08_REQ, 3, 2000); /* t1.5 violated */
    lw_advance(x, last + 20000);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.char_errors, 1);
    assert_int_equal(st.breaks, 1);
    assert_int_equal(st.t15_discards, 1);
    assert_int_equal(st.frames_too_long, 0);
    assert_int_equal(st.signals, 0); /* RS232, not automatic, outputs OFF */
    assert_int_equal(st.buffer_len, 3);
    assert_int_equal(st.buffer[0], MODCP_EV_ZVZ);
    assert_int_equal(st.buffer[1], MODCP_EV_BREAK);
    assert_int_equal(st.buffer[2], MODCP_EV_CHAR_ERROR);
    assert_int_equal(st.status, 0x0806);
    assert_true(st.leds & (1u << MODCP_LED_RXD));
    assert_false(st.flags & MODCP_CPST_WIRE_BREAK); /* the request's bytes ended it */
    assert_int_equal(st.systat_ack, 0);
    lw_free(x);
}

/* Issue 12 item 4: the status area is published only when something in it changed —
 * polls in which nothing happened leave it (and its seqlock) alone; a request, the
 * LEDs going off with time and a SYSTAT request of the CPU side each publish it. */
static void test_status_area_published_on_change(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 1000));
    world_run(w, 500000); /* LEDs settled */
    uint32_t s0 = atomic_load(&w->bp.status_seq);
    assert_int_equal(s0 & 1u, 0);
    world_run(w, 100000); /* 100 FB cycles and CP polls, nothing happens */
    assert_int_equal(atomic_load(&w->bp.status_seq), s0);
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    assert_true(st.flags & MODCP_CPST_READY);
    assert_int_equal(st.leds, 0);
    uint16_t bus = st.counters[MODCP_CNT_BUS_MSG];

    assert_int_equal(world_request(w, FC08_REQ, 100), 8);
    world_run(w, 1000); /* the next CP poll publishes */
    uint32_t s1 = atomic_load(&w->bp.status_seq);
    assert_int_not_equal(s1, s0);
    assert_true(modcp_bp_read_status(&w->bp, &st));
    assert_int_equal(st.counters[MODCP_CNT_BUS_MSG], (uint16_t)(bus + 1u));
    assert_true(st.leds & (1u << MODCP_LED_RXD));

    world_run(w, 500000); /* RXD / TXD off after their minimum on-time */
    uint32_t s2 = atomic_load(&w->bp.status_seq);
    assert_int_not_equal(s2, s1);
    assert_true(modcp_bp_read_status(&w->bp, &st));
    assert_int_equal(st.leds, 0);
    world_run(w, 100000);
    assert_int_equal(atomic_load(&w->bp.status_seq), s2);

    uint32_t req = modcp_bp_systat_request(&w->bp);
    world_run(w, 2000);
    uint8_t img[16];
    assert_true(modcp_bp_systat_result(&w->bp, req, img));
    assert_int_not_equal(atomic_load(&w->bp.status_seq), s2);
    world_free(w);
}

/* Issue 27 item 9: every event row gives its event a text, a remedy and a class name;
 * the manual's words for (0E)56H; an event that has no row is "unknown". */
static void test_event_rows_give_text_remedy_and_class(void **state)
{
    (void)state;
#define ROW(NAME, cls, num, ...)                                                                  \
    assert_int_equal(MODCP_EV_##NAME, MODCP_EVENT(cls, num));                                     \
    assert_string_not_equal(modcp_event_text(MODCP_EV_##NAME), "unknown event");                 \
    assert_true(modcp_event_remedy(MODCP_EV_##NAME)[0] != '\0');                                  \
    assert_string_not_equal(modcp_event_class_text(cls), "other event");
    MODCP_EVENT_ROWS(ROW)
#undef ROW
    /* one row per event word */
#define WORD(NAME, ...) MODCP_EV_##NAME,
    static const modcp_event_t words[] = {MODCP_EVENT_ROWS(WORD)};
#undef WORD
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        for (size_t j = i + 1; j < sizeof words / sizeof words[0]; j++) {
            assert_int_not_equal(words[i], words[j]);
        }
    }
    assert_string_equal(modcp_event_text(MODCP_EV_FB_NOT_RUNNING),
                        "data link not possible: communication FB not running");
    assert_string_equal(modcp_event_class_text(0x07), "send error");
    assert_string_equal(modcp_event_class_text(0x08), "receive error");
    assert_string_equal(modcp_event_class_text(0x0E), "driver processing error");
    assert_string_equal(modcp_event_text(MODCP_EVENT(0x0E, 0x32)), "unknown event"); /* n/a */
    assert_string_equal(modcp_event_remedy(MODCP_EVENT(0x0E, 0x32)), "");
    assert_string_equal(modcp_event_class_text(0x1E), "other event");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_status_word),
        cmocka_unit_test(test_diag_buffer_ring),
        cmocka_unit_test(test_systat_image),
        cmocka_unit_test(test_systat_service),
        cmocka_unit_test(test_systat_fault_state),
        cmocka_unit_test(test_diag_buffer_cleared_on_reparameterisation_8_3),
        cmocka_unit_test(test_diag_irq_wire_break),
        cmocka_unit_test(test_diag_irq_param_error),
        cmocka_unit_test(test_cpdiag_unit),
        cmocka_unit_test(test_diag_irq_parameter),
        cmocka_unit_test(test_leds_power_on),
        cmocka_unit_test(test_leds_min_on_time),
        cmocka_unit_test(test_leds_late_poll),
        cmocka_unit_test(test_leds_long_frames),
        cmocka_unit_test(test_leds_rs485_echo),
        cmocka_unit_test(test_internal_receive_error),
        cmocka_unit_test(test_event_rows_give_text_remedy_and_class),
        cmocka_unit_test(test_backplane_protocol_events),
        cmocka_unit_test(test_backplane_error_kinds),
        cmocka_unit_test(test_status_area_fields),
        cmocka_unit_test(test_status_area_published_on_change),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
