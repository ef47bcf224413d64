/* SPDX-License-Identifier: Apache-2.0 */
#include "lineworld.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"

static void add(lw_t *x, uint8_t kind, uint32_t value)
{
    assert_true(x->n < LW_LOG_MAX);
    x->log[x->n].kind = kind;
    x->log[x->n].value = value;
    x->log[x->n].at = x->w->now_us;
    x->n++;
}

static void h_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    lw_t *x = ctx;
    assert_true(len <= sizeof x->tx);
    assert_false(x->tx_busy); /* never two transmissions at once */
    memcpy(x->tx, buf, len);
    x->tx_len = len;
    x->tx_calls++;
    x->tx_busy = true;
    x->tx_end = x->w->now_us + (uint32_t)len * x->char_us;
    add(x, LW_TX, len);
}

static void h_arm(void *ctx, uint32_t us)
{
    lw_t *x = ctx;
    x->timer_on = us != 0u;
    x->timer_at = x->w->now_us + us;
    add(x, LW_ARM, us);
}

static void h_de(void *ctx, bool on)
{
    lw_t *x = ctx;
    x->de = on;
    add(x, LW_DE, on ? 1u : 0u);
}

static void h_led(void *ctx, modcp_led_t led, bool on)
{
    lw_t *x = ctx;
    x->led[led] = on;
    add(x, LW_LED, ((uint32_t)led << 1) | (on ? 1u : 0u));
}

static void h_sig(void *ctx, modcp_signal_t sig, bool on)
{
    lw_t *x = ctx;
    x->sig[sig] = on;
    add(x, LW_SIG, ((uint32_t)sig << 1) | (on ? 1u : 0u));
}

static void h_abort(void *ctx)
{
    lw_t *x = ctx;
    x->tx_busy = false;
    add(x, LW_ABORT, 0);
}

static lw_t *make(const modcp_params_t *p)
{
    lw_t *x = calloc(1, sizeof *x);
    assert_non_null(x);
    x->w = world_new(p);
    x->auto_tx_done = true;
    x->cycles = true;
    x->char_us = modcp_params_char_us(&x->w->params);
    /* the CP keeps a pointer to w->hal: hook it */
    x->w->hal = (modcp_hal_t){.ctx = x, .uart_tx = h_tx, .timer_arm = h_arm, .set_de = h_de,
                              .set_led = h_led, .set_signal = h_sig, .uart_tx_abort = h_abort};
    return x;
}

lw_t *lw_new_unstarted(const modcp_params_t *p)
{
    lw_t *x = make(p);
    x->next_cycle = x->w->now_us;
    return x;
}

lw_t *lw_new(const modcp_params_t *p)
{
    lw_t *x = make(p);
    assert_true(world_start(x->w, 2000));
    assert_true(modcp_cp_ready(&x->w->cp));
    x->next_cycle = x->w->now_us + 1000u;
    return x;
}

void lw_free(lw_t *x)
{
    world_free(x->w);
    free(x);
}

uint32_t lw_now(const lw_t *x)
{
    return x->w->now_us;
}

static bool due(uint32_t at, uint32_t t)
{
    return (int32_t)(t - at) >= 0;
}

static bool before(uint32_t a, uint32_t b)
{
    return (int32_t)(b - a) > 0;
}

void lw_advance(lw_t *x, uint32_t t)
{
    world_t *w = x->w;
    for (;;) {
        /* the earliest due event: tx complete, then timer, then cycle on ties */
        int which = 0;
        uint32_t at = t;
        if (x->tx_busy && x->auto_tx_done && due(x->tx_end, t)) {
            which = 1;
            at = x->tx_end;
        }
        if (x->timer_on && due(x->timer_at, t) && (which == 0 || before(x->timer_at, at))) {
            which = 2;
            at = x->timer_at;
        }
        if (x->cycles && due(x->next_cycle, t) && (which == 0 || before(x->next_cycle, at))) {
            which = 3;
            at = x->next_cycle;
        }
        if (which == 0) {
            break;
        }
        w->now_us = at;
        if (which == 1) {
            x->tx_busy = false;
            add(x, LW_TXDONE, 0);
            modcp_cp_on_tx_done(&w->cp, at);
        } else if (which == 2) {
            x->timer_on = false;
            modcp_cp_on_timer(&w->cp, at);
        } else {
            x->next_cycle = at + 1000u;
            if (!w->fb_paused) {
                modcp_fb_in_t in = {true};
                modcp_fb_call(&w->fb, &in, &w->fb_out, at / 1000u);
            }
            modcp_cp_poll(&w->cp, at);
        }
    }
    w->now_us = t;
}

void lw_byte(lw_t *x, uint8_t b)
{
    modcp_cp_on_rx(&x->w->cp, b, x->w->now_us);
}

void lw_error(lw_t *x, uint8_t flags)
{
    modcp_cp_on_line_error(&x->w->cp, flags, x->w->now_us);
}

void lw_signals(lw_t *x, bool cts, bool dsr)
{
    modcp_cp_on_signals(&x->w->cp, cts, dsr, x->w->now_us);
}

uint32_t lw_send_gap(lw_t *x, const char *hex, size_t gap_before, uint32_t gap_us)
{
    uint8_t b[700];
    size_t n = hex_frame(hex, b, sizeof b);
    uint32_t t = x->w->now_us;
    for (size_t i = 0; i < n; i++) {
        if (i > 0) {
            t += x->char_us + (i == gap_before ? gap_us : 0u);
        }
        lw_advance(x, t);
        lw_byte(x, b[i]);
    }
    return t;
}

uint32_t lw_send(lw_t *x, const char *hex)
{
    return lw_send_gap(x, hex, 0, 0);
}

void lw_poll(lw_t *x)
{
    modcp_cp_poll(&x->w->cp, x->w->now_us);
}

void lw_fire_now(lw_t *x)
{
    x->timer_on = false;
    modcp_cp_on_timer(&x->w->cp, x->w->now_us);
}

size_t lw_count(const lw_t *x, uint8_t kind)
{
    size_t c = 0;
    for (size_t i = 0; i < x->n; i++) {
        c += x->log[i].kind == kind;
    }
    return c;
}

const lw_ev_t *lw_last(const lw_t *x, uint8_t kind)
{
    for (size_t i = x->n; i > 0; i--) {
        if (x->log[i - 1].kind == kind) {
            return &x->log[i - 1];
        }
    }
    return NULL;
}

long lw_find(const lw_t *x, uint8_t kind, long value, size_t from)
{
    for (size_t i = from; i < x->n; i++) {
        if (x->log[i].kind == kind && (value < 0 || x->log[i].value == (uint32_t)value)) {
            return (long)i;
        }
    }
    return -1;
}

void lw_clear(lw_t *x)
{
    x->n = 0;
    x->tx_calls = 0;
    x->tx_len = 0;
}

const char *lw_tx_hex(const lw_t *x)
{
    static char s[2200];
    size_t o = 0;
    s[0] = 0;
    for (uint16_t k = 0; k < x->tx_len; k++) {
        o += (size_t)snprintf(s + o, sizeof s - o, k ? " %02X" : "%02X", x->tx[k]);
    }
    return s;
}

modcp_cp_status_t lw_status(const lw_t *x)
{
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&x->w->bp, &st));
    return st;
}
