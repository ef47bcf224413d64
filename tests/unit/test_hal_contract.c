/* SPDX-License-Identifier: Apache-2.0 */
/* The HAL contracts every port keeps (modcp/hal.h, docs/porting.md §1), seen from the
 * core, and the shared port pieces (modcp/hal_timebase.h, hal_conq.h, hal_eof.h):
 *   - the core never calls uart_tx with len 0 (a frame without a reply calls nothing);
 *   - CTS / DSR: with rs232_auto off the core ignores them, so a port need not report
 *     them; with rs232_auto on they count as OFF until the port's first report, so every
 *     port reports them once at start (ON, ON without modem inputs);
 *   - a lost character (overrun) is reported as MODCP_LINE_OVERRUN in its place and the
 *     good characters around it are delivered: one damaged frame, no reply, the next
 *     request answered. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "lineworld.h"
#include "modcp/hal_conq.h"
#include "modcp/hal_eof.h"
#include "modcp/hal_timebase.h"

#define FC03_REQ "05 03 00 50 00 02 C5 9E" /* [RTU-2003] §6.3 */
#define FC03_RSP "05 03 04 87 65 43 21 76 70"
#define CHAR_US 1146u

static lw_t *start(const modcp_params_t *p)
{
    lw_t *x = lw_new(p);
    memcpy(world_db(x->w, 800) + 160, "\x87\x65\x43\x21", 4); /* DBW160/162 */
    lw_clear(x);
    return x;
}

static unsigned request(lw_t *x, const char *hex, uint32_t ms)
{
    unsigned before = x->tx_calls;
    uint32_t last = lw_send(x, hex);
    lw_advance(x, last + ms * 1000u);
    return x->tx_calls - before;
}

/* ---- uart_tx is never called with len 0 ------------------------------------------ */

static void test_uart_tx_never_empty(void **state)
{
    (void)state;
    lw_t *x = start(NULL);
    assert_int_equal(request(x, FC03_REQ, 50), 1);              /* a reply */
    assert_int_equal(request(x, "00 06 00 50 12 34 85 7D", 50), 0); /* broadcast: none */
    assert_int_equal(request(x, "06 03 00 50 00 02 C5 AD", 50), 0); /* another slave */
    assert_int_equal(request(x, "05 03 00 50 00 02 C5 9F", 50), 0); /* CRC error */
    assert_int_equal(request(x, "05 41 00 00 50 FC", 50), 1);        /* exception */
    assert_int_equal(lw_count(x, LW_TX), 2);
    for (size_t k = 0; k < x->n; k++) {
        if (x->log[k].kind == LW_TX) {
            assert_true(x->log[k].value > 0u);
        }
    }
    lw_free(x);
}

/* ---- CTS / DSR at start --------------------------------------------------------------- */

static void test_signals_not_needed_without_rs232_auto(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.iface = MODCP_IFACE_RS232;
    p.rs232_auto = 0;
    lw_t *x = start(&p); /* no modcp_cp_on_signals at all */
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_signals(x, false, false); /* ignored without rs232_auto */
    assert_int_equal(request(x, FC03_REQ, 50), 1);
    lw_free(x);
}

static void test_signals_required_with_rs232_auto(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.iface = MODCP_IFACE_RS232;
    p.rs232_auto = 1;
    lw_t *x = start(&p);
    /* no report yet: CTS and DSR count as OFF, nothing is received */
    assert_int_equal(request(x, FC03_REQ, 50), 0);
    assert_int_equal(lw_count(x, LW_TX), 0);
    lw_signals(x, true, true); /* what a port without modem inputs reports at start */
    lw_advance(x, lw_now(x) + 10000u);
    assert_int_equal(request(x, FC03_REQ, 100), 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* ---- overrun: the lost character in its place, the good ones delivered --------------- */

static void test_overrun_in_place(void **state)
{
    (void)state;
    lw_t *x = start(NULL);
    static const uint8_t req[8] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x02, 0xC5, 0x9E};
    uint32_t t = lw_now(x);
    for (size_t i = 0; i < 8; i++) { /* character 4 lost: OVERRUN in its place */
        lw_advance(x, t);
        if (i == 4) {
            lw_error(x, MODCP_LINE_OVERRUN);
        } else {
            lw_byte(x, req[i]);
        }
        t += CHAR_US;
    }
    lw_advance(x, t + 20000u);
    assert_int_equal(x->tx_calls, 0); /* one damaged frame: no reply */
    assert_int_equal(x->w->cp.diag.char_errors, 1);
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_CHAR_OVERRUN], 1);
    assert_int_equal(x->w->cp.diag.counters[MODCP_CNT_BUS_MSG], 0);
    assert_int_equal(world_last_event(x->w), MODCP_EV_CHAR_ERROR);
    assert_int_equal(request(x, FC03_REQ, 50), 1); /* the next request: answered */
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* ---- hal_timebase.h ------------------------------------------------------------------ */

/* Feed readings of a counter `bits` wide at hz (down or up), steps below one period,
 * and compare us / ms with the exact count of cycles since the start. */
static void run_timebase(uint32_t hz, uint32_t bits, bool down, uint32_t start_count,
                         uint64_t seed)
{
    modcp_timebase_t tb;
    uint32_t mask = bits >= 32u ? 0xFFFFFFFFu : (1u << bits) - 1u;
    modcp_timebase_init(&tb, hz, bits, down, start_count);
    uint64_t total = 0, cyc_per_us = hz / 1000000u;
    uint32_t count = start_count & mask;
    for (int k = 0; k < 60000; k++) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        uint32_t step = (uint32_t)(seed >> 33) % (mask < 0x7FFFFFFFu ? mask : 0x7FFFFFFFu);
        total += step;
        count = (down ? count - step : count + step) & mask;
        modcp_timebase_feed(&tb, count);
        uint64_t us = total / cyc_per_us;
        assert_int_equal(tb.us, (uint32_t)us);
        assert_int_equal(tb.ms, (uint32_t)(us / 1000u));
    }
    assert_true(total / cyc_per_us > 0xFFFFFFFFull); /* the us count wrapped */
}

static void test_timebase_exact(void **state)
{
    (void)state;
    run_timebase(50000000u, 24u, true, 0u, 1u);          /* SysTick at 50 MHz (lm3s) */
    run_timebase(25000000u, 32u, true, 0xFFFFFFFFu, 2u); /* CMSDK timer at 25 MHz */
    run_timebase(1000000u, 32u, false, 0xFFFFFF00u, 3u); /* a 1 MHz up counter */
}

/* ---- hal_conq.h ---------------------------------------------------------------------- */

static modcp_conq_t conq;
static unsigned kicks;

/* The transmit interrupt: takes two characters per kick into out[]. */
static char out[3 * MODCP_CONQ_TX];
static size_t out_n;
static void drain_two(void *ctx)
{
    modcp_conq_t *q = ctx;
    kicks++;
    for (int k = 0; k < 2; k++) {
        int c = modcp_conq_tx_next(q);
        if (c >= 0) {
            out[out_n++] = (char)c;
        }
    }
}

static void test_conq(void **state)
{
    (void)state;
    modcp_conq_init(&conq);
    assert_int_equal(modcp_conq_getc(&conq), -1);
    for (unsigned k = 0; k < MODCP_CONQ_RX; k++) {
        assert_true(modcp_conq_rx_put(&conq, (uint8_t)k));
    }
    assert_false(modcp_conq_rx_put(&conq, 0xAA)); /* full: dropped and counted */
    assert_int_equal(conq.rx_dropped, 1);
    for (unsigned k = 0; k < MODCP_CONQ_RX; k++) {
        assert_int_equal(modcp_conq_getc(&conq), (int)(uint8_t)k);
    }
    assert_int_equal(modcp_conq_getc(&conq), -1);
    /* more than the queue holds: the writer kicks and waits for room, nothing lost */
    static char text[2 * MODCP_CONQ_TX + 5];
    for (size_t k = 0; k < sizeof text; k++) {
        text[k] = (char)('a' + k % 26u);
    }
    modcp_conq_write(&conq, text, sizeof text, drain_two, &conq);
    while (modcp_conq_tx_next(&conq) >= 0) {
        out_n++; /* the rest, in order (checked below by count) */
    }
    assert_int_equal(out_n, sizeof text);
    assert_memory_equal(out, text, 64);
    assert_true(kicks > 1);
}

/* ---- hal_eof.h: the end-of-frame handler --------------------------------------------- */

typedef struct {
    modcp_eof_t eof;
    uint32_t mark;       /* characters received */
    uint32_t pending;    /* characters waiting in the "UART" */
    bool rearm_on_drain; /* the core re-arms for a drained character */
    unsigned restarts;
    uint32_t restart_us;
} eport_t;

static void e_drain(void *ctx)
{
    eport_t *p = ctx;
    p->mark += p->pending;
    if (p->pending != 0u && p->rearm_on_drain) {
        modcp_eof_arm(&p->eof, p->mark); /* the core's timer_arm */
    }
    p->pending = 0u;
}
static uint32_t e_mark(void *ctx)
{
    return ((eport_t *)ctx)->mark;
}
static void e_restart(void *ctx, uint32_t us)
{
    eport_t *p = ctx;
    p->restarts++;
    p->restart_us = us;
}
static const modcp_eof_ops_t e_ops = {.drain = e_drain, .rx_mark = e_mark, .restart = e_restart};

static void test_eof_handler(void **state)
{
    (void)state;
    eport_t p = {0};
    modcp_eof_arm(&p.eof, p.mark);
    /* three quiet expiries: the first two restart a 1 us one-shot, the third reports */
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u));
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u));
    assert_int_equal(p.restarts, 2);
    assert_int_equal(p.restart_us, 1);
    assert_true(modcp_eof_expired(&p.eof, &e_ops, &p, 3u));
    /* a character found by the drain starts the count again */
    modcp_eof_arm(&p.eof, p.mark);
    p.restarts = 0;
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u)); /* quiet 1 */
    p.pending = 1;
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u)); /* reset to 0 */
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u)); /* 1 */
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u)); /* 2 */
    assert_true(modcp_eof_expired(&p.eof, &e_ops, &p, 3u));  /* 3 */
    assert_int_equal(p.restarts, 4);
    /* the core re-arms for a drained character: that timer stands, no restart */
    modcp_eof_arm(&p.eof, p.mark);
    p.restarts = 0;
    p.pending = 2;
    p.rearm_on_drain = true;
    assert_false(modcp_eof_expired(&p.eof, &e_ops, &p, 3u));
    assert_int_equal(p.restarts, 0);
    assert_int_equal(p.mark, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uart_tx_never_empty),
        cmocka_unit_test(test_signals_not_needed_without_rs232_auto),
        cmocka_unit_test(test_signals_required_with_rs232_auto),
        cmocka_unit_test(test_overrun_in_place),
        cmocka_unit_test(test_timebase_exact),
        cmocka_unit_test(test_conq),
        cmocka_unit_test(test_eof_handler),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
