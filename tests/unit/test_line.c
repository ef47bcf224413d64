/* SPDX-License-Identifier: Apache-2.0 */
/* Line discipline end to end (docs/diagnostics.md, [RTU-2003] §2.2, §2.3, §5.3): character errors and
 * BREAK in normal and interference-suppression mode and on RS485, frame start by the
 * own address, errors after the CRC, the t1.5 check, the t3.5 end of frame, RS485
 * driver enable and turnaround, (08)37H — through the whole CP (link, PDU, job, FB)
 * on a simulated line with exact time (lineworld.h). Thresholds at 1 us.
 *
 * Line: 9600 baud 8E1 = 11 bits, one character = 1146 us, t3.5 = 4000 us ([RTU-2003] §5.3),
 * t1.5 = 1719 us (1.5 x 11 bits). Frames: [RTU-2003] §6 examples with the [RTU-2003] §9 CRCs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "lineworld.h"

#define FC03_REQ "05 03 00 50 00 02 C5 9E"     /* [RTU-2003] §6.3 */
#define FC03_RSP "05 03 04 87 65 43 21 76 70"
#define FC08_REQ "05 08 00 00 A5 C3 DA 8E"     /* [RTU-2003] §6.7, answered by the CP alone */
#define CHAR_US 1146u
#define T35_US 4000u
#define T15_US 1719u

static modcp_params_t example(void)
{
    modcp_params_t p;
    world_example_params(&p);
    return p;
}

static lw_t *start(const modcp_params_t *p)
{
    lw_t *x = lw_new(p);
    memcpy(world_db(x->w, 800) + 160, "\x87\x65\x43\x21", 4); /* DBW160/162 for FC03 */
    lw_clear(x);
    return x;
}

static modcp_event_t last_event(const lw_t *x)
{
    return world_last_event(x->w);
}

/* Send hex, then run `ms` milliseconds; returns the number of transmissions. */
static unsigned request(lw_t *x, const char *hex, uint32_t ms)
{
    unsigned before = x->tx_calls;
    uint32_t last = lw_send(x, hex);
    lw_advance(x, last + ms * 1000u);
    return x->tx_calls - before;
}

/* FC03 request with a line error in place of its 4th character. */
static uint32_t fc03_with_error(lw_t *x, uint8_t flags)
{
    static const uint8_t req[8] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x02, 0xC5, 0x9E};
    uint32_t t = lw_now(x);
    for (size_t i = 0; i < 8; i++) {
        lw_advance(x, t);
        if (i == 3) {
            lw_error(x, flags);
        } else {
            lw_byte(x, req[i]);
        }
        t += CHAR_US;
    }
    return t - CHAR_US;
}

/* ---- character errors and BREAK --------------------------------------------------- */

/* [RTU-2003] §2.2 normal operation: a parity error inside a request -> (08)0CH, no reply; the
 * next good request is answered. */
static void test_parity_error_normal(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = start(&p);
    uint32_t last = fc03_with_error(x, MODCP_LINE_PARITY);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(last_event(x), MODCP_EV_CHAR_ERROR);
    assert_int_equal(x->w->cp.diag.buffer_len, 1); /* no (08)36H on top */
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.char_errors, 1);
    assert_int_equal(st.status, 0x080C);

    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);

    /* framing and overrun: (08)0CH each; overrun also in the FC08 overrun counter */
    lw_advance(x, lw_now(x) + 10000);
    last = fc03_with_error(x, MODCP_LINE_FRAMING);
    lw_advance(x, last + 10000);
    last = fc03_with_error(x, MODCP_LINE_OVERRUN);
    lw_advance(x, last + 10000);
    assert_int_equal(x->w->cp.diag.char_errors, 3);
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_CHAR_ERROR);
    assert_int_equal(x->w->cp.diag.buffer[1], MODCP_EV_CHAR_ERROR);
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_CHAR_OVERRUN], 1);
    assert_int_equal(x->tx_calls, 1);
    lw_free(x);
}

/* [RTU-2003] §2.2 interference suppression: the frame is discarded silently; the next good
 * request is answered. */
static void test_parity_error_suppression(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.opmode = MODCP_OPMODE_SUPPRESS;
    lw_t *x = start(&p);
    uint32_t last = fc03_with_error(x, MODCP_LINE_PARITY);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_int_equal(lw_status(x).char_errors, 1); /* counted, not reported */
    last = fc03_with_error(x, MODCP_LINE_BREAK);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_int_equal(lw_status(x).breaks, 1);
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* RS485 two-wire in normal mode (Siemens MODBUS slave driver manual, 2009 edition,
 * Table 5-2 "enable operating-mode selection for RS485" and §5.6.5): an error inside a
 * frame is reported as on four-wire RS422 — (08)0CH, or (08)0DH with wire break, SF
 * and the SYSTAT B flag —, the frame discarded, the next one served. */
static void test_rs485_normal_reports_errors_inside_frame(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1;
    p.opmode = MODCP_OPMODE_NORMAL;
    lw_t *x = start(&p);
    uint32_t last = fc03_with_error(x, MODCP_LINE_PARITY);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    assert_int_equal(last_event(x), MODCP_EV_CHAR_ERROR);
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);

    lw_advance(x, lw_now(x) + 10000);
    last = lw_send(x, "05 03 00"); /* the line breaks inside the frame */
    lw_advance(x, last + CHAR_US);
    lw_error(x, MODCP_LINE_BREAK | MODCP_LINE_FRAMING);
    lw_advance(x, lw_now(x) + 20000); /* nothing received since */
    assert_int_equal(x->tx_calls, 1);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(last_event(x), MODCP_EV_BREAK);
    assert_true(st.flags & MODCP_CPST_WIRE_BREAK);
    assert_true(st.flags & MODCP_CPST_SF);
    assert_true(x->w->cp.diag.systat_flags & MODCP_SYSTAT_B);
    lw_free(x);
}

/* ... and ignores errors and BREAK before, after and between frames (§5.6.5: "all
 * transmission errors or BREAKs detected before and after received telegrams are
 * ignored; a BREAK level during the pauses between telegrams is also ignored"): on the
 * idle line, right after a request's CRC, while the request is processed. */
static void test_rs485_normal_ignores_errors_between_frames(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1;
    p.opmode = MODCP_OPMODE_NORMAL;
    lw_t *x = start(&p);
    lw_error(x, MODCP_LINE_BREAK); /* idle line */
    lw_advance(x, lw_now(x) + 10000);
    lw_error(x, MODCP_LINE_PARITY);
    lw_advance(x, lw_now(x) + 10000);
    x->w->fb_paused = true;
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + 300);
    lw_error(x, MODCP_LINE_FRAMING); /* after the CRC: the master releasing the line */
    lw_advance(x, last + T35_US + 1000);
    lw_error(x, MODCP_LINE_BREAK); /* while the request is processed */
    x->w->fb_paused = false;
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_false(st.flags & (MODCP_CPST_WIRE_BREAK | MODCP_CPST_SF));
    assert_int_equal(st.breaks, 2); /* counted, not reported */
    assert_int_equal(st.char_errors, 2);
    lw_free(x);
}

/* Without the mode selection two-wire RS485 is interference suppression ([RTU-2003] §2.3):
 * an error inside a frame discards it silently. */
static void test_rs485_without_selection_suppresses(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 0;
    p.opmode = MODCP_OPMODE_SUPPRESS;
    lw_t *x = start(&p);
    uint32_t last = fc03_with_error(x, MODCP_LINE_BREAK);
    lw_advance(x, last + 100000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_false(lw_status(x).flags & MODCP_CPST_WIRE_BREAK);
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* "The start of an incoming message is recognised by a correctly received slave
 * address" ([RTU-2003] §2.2): a glitch or BREAK on the idle line just before a request (less
 * than t3.5) does not swallow it in interference suppression and on RS485. In normal
 * mode the glitch starts a faulty frame that runs into the request: (08)0CH, lost. */
static void check_glitch_before_request(uint8_t opmode, uint8_t iface, uint8_t flags,
                                        bool served)
{
    modcp_params_t p = example();
    p.opmode = opmode;
    p.iface = iface;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    lw_t *x = start(&p);
    lw_error(x, flags);
    lw_advance(x, lw_now(x) + 300); /* 300 us later the master starts */
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + 50000);
    if (served) {
        assert_int_equal(x->tx_calls, 1);
        assert_string_equal(lw_tx_hex(x), FC08_REQ);
        assert_int_equal(x->w->cp.diag.buffer_len, 0);
    } else {
        assert_int_equal(x->tx_calls, 0);
        assert_int_equal(x->w->cp.diag.buffer_len, 1);
        assert_int_equal(last_event(x),
                         (flags & MODCP_LINE_BREAK) ? MODCP_EV_BREAK : MODCP_EV_CHAR_ERROR);
    }
    lw_free(x);
}

static void test_frame_start_by_own_address(void **state)
{
    (void)state;
    check_glitch_before_request(MODCP_OPMODE_SUPPRESS, MODCP_IFACE_RS232, MODCP_LINE_FRAMING, true);
    check_glitch_before_request(MODCP_OPMODE_SUPPRESS, MODCP_IFACE_RS422, MODCP_LINE_BREAK, true);
    check_glitch_before_request(MODCP_OPMODE_NORMAL, MODCP_IFACE_RS485, MODCP_LINE_BREAK, true);
    check_glitch_before_request(MODCP_OPMODE_NORMAL, MODCP_IFACE_RS485, MODCP_LINE_PARITY, true);
    check_glitch_before_request(MODCP_OPMODE_NORMAL, MODCP_IFACE_RS232, MODCP_LINE_FRAMING, false);
    check_glitch_before_request(MODCP_OPMODE_NORMAL, MODCP_IFACE_RS422, MODCP_LINE_BREAK, false);
}

/* A glitch while a request is being processed (the FB has not answered yet), and the
 * next request right after the reply: served in suppression mode. */
static void test_glitch_while_busy_suppression(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.opmode = MODCP_OPMODE_SUPPRESS;
    lw_t *x = start(&p);
    x->w->fb_paused = true;
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + T35_US + 500);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_BUSY);
    lw_error(x, MODCP_LINE_BREAK); /* not inside any frame: ignored */
    x->w->fb_paused = false;
    lw_advance(x, lw_now(x) + 15000); /* the FB answers, the reply goes out */
    assert_int_equal(x->tx_calls, 1);
    assert_false(x->tx_busy);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(request(x, FC08_REQ, 20), 1);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    lw_free(x);
}

/* [RTU-2003] §2.2: errors after the CRC are ignored in suppression mode (the request is
 * answered, no event); normal mode reports them but still answers. In normal mode the
 * error does not restart t3.5. In suppression (modem) mode the valid CRC itself ended
 * the frame ([RTU-2009] §8): the FC08 reply was already on the line when the error came
 * (the timing there is test_modem.c's). */
static void test_error_after_crc(void **state)
{
    (void)state;
    for (int mode = 0; mode < 2; mode++) {
        modcp_params_t p = example();
        p.opmode = mode ? MODCP_OPMODE_SUPPRESS : MODCP_OPMODE_NORMAL;
        lw_t *x = start(&p);
        uint32_t last = lw_send(x, FC08_REQ);
        lw_advance(x, last + 500);
        lw_error(x, MODCP_LINE_FRAMING | MODCP_LINE_BREAK);
        if (!mode) {
            lw_advance(x, last + T35_US - 1);
            assert_int_equal(x->tx_calls, 0);
        }
        lw_advance(x, last + T35_US); /* the error did not restart t3.5 */
        assert_int_equal(x->tx_calls, 1);
        assert_int_equal(lw_last(x, LW_TX)->at, last + (mode ? 1u : T35_US));
        assert_string_equal(lw_tx_hex(x), FC08_REQ);
        assert_int_equal(x->w->cp.diag.buffer_len, mode ? 0 : 1);
        if (!mode) {
            assert_int_equal(last_event(x), MODCP_EV_BREAK);
        }
        lw_free(x);
    }
}

/* ---- t3.5 and t1.5 ----------------------------------------------------------------- */

/* [RTU-2003] §5.3: the reply to the FC08 example leaves exactly t3.5 after the last character
 * (the CP answers FC08 alone); an expiry 1 us early does not end the frame. */
static void test_t35_end_to_end(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    lw_advance(x, last + T35_US - 1);
    lw_fire_now(x); /* early expiry */
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(lw_last(x, LW_ARM)->value, 1); /* the remaining microsecond */
    lw_advance(x, last + T35_US);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(lw_last(x, LW_TX)->at, last + T35_US);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    lw_free(x);
}

/* The gap at the threshold: the timer armed by byte k expires at t_k + 4000; a byte at
 * t_k + 3999 continues the frame (served), a byte at t_k + 4000 comes after the expiry
 * and starts a new frame: "05 08 00 00" fails its CRC ((08)36H), "A5 C3 DA 8E" is a
 * frame for address A5H (no event for another address); no reply. */
static void test_t35_gap_threshold(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = start(&p);
    /* byte distance 3999 us = char + 2853 us extra */
    uint32_t last = lw_send_gap(x, FC08_REQ, 4, T35_US - 1 - CHAR_US);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    last = lw_send_gap(x, FC08_REQ, 4, T35_US - CHAR_US);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    assert_int_equal(x->w->cp.diag.buffer[0], MODCP_EV_CRC);
    /* bus counters: the first FC08 was good; both halves of the second are CRC errors */
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_BUS_CRC], 2);
    lw_free(x);
}

/* Modbus serial line t1.5 (docs/diagnostics.md, optional): silence of exactly t1.5 inside a frame
 * is accepted; 1 us more discards the frame: (08)06H in normal mode, silently in
 * interference suppression; counted in the status area. */
static void test_t15_end_to_end(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.t15_check = 1;
    lw_t *x = start(&p);
    assert_int_equal(x->w->cp.link.t15_us, T15_US);
    uint32_t last = lw_send_gap(x, FC03_REQ, 4, T15_US);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);

    last = lw_send_gap(x, FC03_REQ, 4, T15_US + 1);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(last_event(x), MODCP_EV_ZVZ);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    modcp_cp_status_t st = lw_status(x);
    assert_int_equal(st.t15_discards, 1);
    assert_int_equal(st.status, 0x0806);
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    lw_free(x);

    p.opmode = MODCP_OPMODE_SUPPRESS;
    x = start(&p);
    last = lw_send_gap(x, FC03_REQ, 2, T15_US + 1);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(x->w->cp.diag.buffer_len, 0);
    assert_int_equal(lw_status(x).t15_discards, 1);
    lw_free(x);

    /* off (the manual's default): a long gap inside t3.5 is accepted */
    p.opmode = MODCP_OPMODE_NORMAL;
    p.t15_check = 0;
    x = start(&p);
    last = lw_send_gap(x, FC03_REQ, 4, 2800);
    lw_advance(x, last + 50000);
    assert_int_equal(x->tx_calls, 1);
    lw_free(x);
}

/* t1.5 at 19200 (860 us) and above 19200 (fixed 750 us), 1 us resolution */
static void test_t15_rates(void **state)
{
    (void)state;
    static const struct {
        uint32_t baud, t15;
    } tab[] = {{19200, 860}, {38400, 750}, {115200, 750}};
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++) {
        modcp_params_t p = example();
        p.t15_check = 1;
        p.eof_timing = MODCP_EOF_MODBUS; /* t3.5 1750 us above 19200: longer than t1.5 */
        p.baud = tab[i].baud;
        lw_t *x = start(&p);
        uint32_t last = lw_send_gap(x, FC08_REQ, 5, tab[i].t15);
        lw_advance(x, last + 50000);
        assert_int_equal(x->tx_calls, 1);
        last = lw_send_gap(x, FC08_REQ, 5, tab[i].t15 + 1);
        lw_advance(x, last + 50000);
        assert_int_equal(x->tx_calls, 1);
        assert_int_equal(last_event(x), MODCP_EV_ZVZ);
        lw_free(x);
    }
}

/* ---- RS485 direction and turnaround ----------------------------------------------- */

/* DE on before the first bit, TX exactly `turnaround` after the end of the request
 * (not 1 us before, even with an early timer expiry), DE off exactly at transmission
 * complete of the last stop bit (8 characters later), never before. */
static void check_turnaround(uint16_t turnaround_ms)
{
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    p.turnaround_ms = turnaround_ms;
    lw_t *x = start(&p);
    uint32_t ta = (uint32_t)turnaround_ms * 1000u;
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready);
    long de_on = lw_find(x, LW_DE, 1, 0);
    assert_true(de_on >= 0);
    assert_int_equal(x->log[de_on].at, t_ready);
    if (ta > 0u) {
        assert_int_equal(x->tx_calls, 0);
        assert_int_equal(lw_last(x, LW_ARM)->value, ta);
        lw_advance(x, t_ready + ta - 1);
        assert_int_equal(x->tx_calls, 0);
        lw_fire_now(x); /* expiry 1 us early: re-armed for the rest */
        assert_int_equal(x->tx_calls, 0);
        assert_int_equal(lw_last(x, LW_ARM)->value, 1);
        lw_advance(x, t_ready + ta);
    }
    assert_int_equal(x->tx_calls, 1);
    long tx = lw_find(x, LW_TX, -1, 0);
    assert_true(de_on < tx);
    assert_int_equal(x->log[tx].at, t_ready + ta);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    assert_true(x->de);
    uint32_t t_done = t_ready + ta + 8u * CHAR_US;
    lw_advance(x, t_done - 1);
    assert_true(x->de); /* not on TX-register empty: still driving */
    assert_int_equal(lw_count(x, LW_DE), 1);
    lw_advance(x, t_done);
    assert_false(x->de);
    assert_int_equal(lw_last(x, LW_DE)->at, t_done);
    assert_int_equal(lw_count(x, LW_DE), 2);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    /* the next request is served the same way */
    assert_int_equal(request(x, FC08_REQ, 150), 1);
    assert_int_equal(lw_count(x, LW_DE), 4);
    lw_free(x);
}

static void test_rs485_turnaround_thresholds(void **state)
{
    (void)state;
    check_turnaround(0);
    check_turnaround(1);
    check_turnaround(5);
    check_turnaround(100); /* the maximum (docs/diagnostics.md: 0 ... 100 ms) */
}

/* A request that needs the CPU (FC03): the reply waits for the FB's data, then the
 * turnaround; DE is switched on only when the reply is ready. */
static void test_rs485_turnaround_after_job(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    p.turnaround_ms = 3;
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + T35_US);
    assert_int_equal(lw_count(x, LW_DE), 0); /* job in progress */
    lw_advance(x, last + 20000);
    long de_on = lw_find(x, LW_DE, 1, 0);
    assert_true(de_on >= 0);
    uint32_t t_ready = x->log[de_on].at;
    assert_true(t_ready > last + T35_US);
    assert_int_equal(lw_last(x, LW_TX)->at, t_ready + 3000);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* (08)37H: the master sends a new request while our reply waits for the turnaround;
 * the pending reply still goes out on time, the new request is not taken. */
static void test_sequence_error_during_turnaround(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    p.turnaround_ms = 20;
    lw_t *x = start(&p);
    uint32_t last = lw_send(x, FC08_REQ);
    uint32_t t_ready = last + T35_US;
    lw_advance(x, t_ready + 1000);
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_TURNAROUND);
    lw_send(x, FC03_REQ);
    assert_int_equal(last_event(x), MODCP_EV_SEQUENCE);
    assert_int_equal(lw_status(x).status, 0x0837);
    lw_advance(x, t_ready + 20000);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(lw_last(x, LW_TX)->at, t_ready + 20000);
    assert_string_equal(lw_tx_hex(x), FC08_REQ);
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(x->tx_calls, 1); /* the FC03 seen while busy is not answered */
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* (08)37H on RS232 while the FB has not answered yet. */
static void test_sequence_error_while_job_pending(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = start(&p);
    x->w->fb_paused = true;
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + 10000);
    lw_send(x, FC03_REQ);
    assert_int_equal(last_event(x), MODCP_EV_SEQUENCE);
    x->w->fb_paused = false;
    lw_advance(x, lw_now(x) + 10000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* [RTU-2003] §7.5 (08)37H "the master sent a new request before the last reply had been
 * transferred": a broadcast (address 0) in that position is a request too. It is not
 * executed (DB800.DBW0 untouched) and not lost without a trace: (08)37H, as for a
 * request for us. The same broadcast once the reply is out is executed. */
static void test_sequence_error_broadcast_while_job_pending(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = start(&p);
    uint8_t *dbw0 = world_db(x->w, 800);
    dbw0[0] = 0xAB;
    dbw0[1] = 0xCD;
    x->w->fb_paused = true;
    uint32_t last = lw_send(x, FC03_REQ);
    lw_advance(x, last + 10000);
    lw_send(x, "00 06 00 00 12 34 85 6C"); /* broadcast FC06 while the FC03 waits */
    assert_int_equal(last_event(x), MODCP_EV_SEQUENCE);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    x->w->fb_paused = false;
    lw_advance(x, lw_now(x) + 10000);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(dbw0[0], 0xAB); /* not executed */
    assert_int_equal(dbw0[1], 0xCD);
    lw_send(x, "00 06 00 00 12 34 85 6C"); /* now: executed, not answered */
    lw_advance(x, lw_now(x) + 50000);
    assert_int_equal(dbw0[0], 0x12);
    assert_int_equal(dbw0[1], 0x34);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(x->w->cp.diag.buffer_len, 1);
    lw_free(x);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parity_error_normal),
        cmocka_unit_test(test_parity_error_suppression),
        cmocka_unit_test(test_rs485_normal_reports_errors_inside_frame),
        cmocka_unit_test(test_rs485_normal_ignores_errors_between_frames),
        cmocka_unit_test(test_rs485_without_selection_suppresses),
        cmocka_unit_test(test_frame_start_by_own_address),
        cmocka_unit_test(test_glitch_while_busy_suppression),
        cmocka_unit_test(test_error_after_crc),
        cmocka_unit_test(test_t35_end_to_end),
        cmocka_unit_test(test_t35_gap_threshold),
        cmocka_unit_test(test_t15_end_to_end),
        cmocka_unit_test(test_t15_rates),
        cmocka_unit_test(test_rs485_turnaround_thresholds),
        cmocka_unit_test(test_rs485_turnaround_after_job),
        cmocka_unit_test(test_sequence_error_during_turnaround),
        cmocka_unit_test(test_sequence_error_while_job_pending),
        cmocka_unit_test(test_sequence_error_broadcast_while_job_pending),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
