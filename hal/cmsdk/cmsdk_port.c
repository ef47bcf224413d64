/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — the Modbus port: UART receive / transmit, the end-of-frame
 * one-shot and transmit-complete detection, feeding the CP's event functions. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cmsdk_regs.h"
#include "modcp/cp.h"
#include "modcp/hal_cmsdk.h"

/* Longest one-shot the 32-bit counter can time at this PCLK. */
static uint32_t cycles_of(const modcp_cmsdk_port_t *p, uint32_t us)
{
    uint32_t max_us = 0xFFFFFFFFu / p->cyc_per_us;
    if (us > max_us) {
        us = max_us;
    }
    uint32_t c = us * p->cyc_per_us;
    return c != 0u ? c : 1u;
}

static void txc_arm(modcp_cmsdk_port_t *p, uint32_t us)
{
    uintptr_t d = p->cfg->dualtimer;
    DUAL_CTRL(d) = 0u;
    DUAL_INTCLR(d) = 1u;
    DUAL_LOAD(d) = cycles_of(p, us);
    DUAL_CTRL(d) = DUAL_CTRL_ONESHOT | DUAL_CTRL_32BIT | DUAL_CTRL_INTEN | DUAL_CTRL_EN;
    p->txc_pending = true;
}

static void txc_stop(modcp_cmsdk_port_t *p)
{
    uintptr_t d = p->cfg->dualtimer;
    DUAL_CTRL(d) = 0u;
    DUAL_INTCLR(d) = 1u; /* a pending interrupt finds MIS clear and does nothing */
    p->txc_pending = false;
}

/* Every byte handed to the UART, the last TX interrupt still to come. */
static bool tx_all_written(const modcp_cmsdk_port_t *p)
{
    return p->tx_active && p->tx_pos >= p->tx_len;
}

static void tx_complete(modcp_cmsdk_port_t *p, uint32_t now_us)
{
    txc_stop(p);
    if (p->cp != NULL) {
        modcp_cp_on_tx_done(p->cp, now_us);
    }
}

/* ---- modcp_hal_t callbacks (called by the core at the CP's priority) ---- */

static void hal_uart_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    modcp_cmsdk_port_t *p = ctx;
    uintptr_t u = p->cfg->uart;
    p->tx_buf = buf;
    p->tx_len = len;
    p->tx_pos = 0u;
    if (len == 0u) {
        txc_arm(p, 1u);
        return;
    }
    p->tx_active = true;
    /* TXINTEN first: the UART latches the TX interrupt only while it is enabled. The
     * interrupt runs at this (the CP's) priority, so it cannot preempt this function. */
    UART_INT(u) = UART_INT_TX;
    UART_CTRL(u) |= UART_CTRL_TXINT;
    p->tx_pos = 1u;
    p->tx_bytes++;
    UART_DATA(u) = buf[0];
}

/* Start the end-of-frame timer for `us` (0: stop it). A stale expiry is dropped by the
 * ISR (INTSTATUS clear). */
static void eof_start(modcp_cmsdk_port_t *p, uint32_t us)
{
    uintptr_t t = p->cfg->timer;
    TIMER_CTRL(t) = 0u;
    TIMER_INT(t) = 1u;
    if (us == 0u) {
        return;
    }
    uint32_t c = cycles_of(p, us);
    TIMER_RELOAD(t) = c;
    TIMER_VALUE(t) = c;
    TIMER_CTRL(t) = TIMER_CTRL_EN | TIMER_CTRL_IRQEN;
}

static uint32_t eof_mark(void *ctx)
{
    const modcp_cmsdk_port_t *p = ctx;
    return p->rx_bytes + p->overruns;
}

static void eof_restart(void *ctx, uint32_t us)
{
    eof_start(ctx, us);
}

static void hal_timer_arm(void *ctx, uint32_t us)
{
    modcp_cmsdk_port_t *p = ctx;
    modcp_eof_arm(&p->eof, eof_mark(p));
    eof_start(p, us);
}

static void hal_uart_tx_abort(void *ctx)
{
    modcp_cmsdk_port_t *p = ctx;
    uintptr_t u = p->cfg->uart;
    UART_CTRL(u) &= ~UART_CTRL_TXINT;
    p->tx_len = p->tx_pos; /* the byte in the shift register still finishes */
    p->tx_active = false;
    txc_stop(p);
}

static void hal_set_de(void *ctx, bool on)
{
    modcp_cmsdk_port_t *p = ctx;
    if (p->cfg->set_de != NULL) {
        p->cfg->set_de(on);
    }
}

static void hal_set_led(void *ctx, modcp_led_t led, bool on)
{
    modcp_cmsdk_port_t *p = ctx;
    if (p->cfg->set_led != NULL) {
        p->cfg->set_led(led, on);
    }
}

void modcp_cmsdk_port_init(modcp_cmsdk_port_t *port, const modcp_cmsdk_cfg_t *cfg)
{
    *port = (modcp_cmsdk_port_t){0};
    port->cfg = cfg;
    port->cyc_per_us = cfg->pclk_hz / 1000000u != 0u ? cfg->pclk_hz / 1000000u : 1u;
    port->hal.ctx = port;
    port->hal.uart_tx = hal_uart_tx;
    port->hal.timer_arm = hal_timer_arm;
    port->hal.set_de = cfg->set_de != NULL ? hal_set_de : NULL;
    port->hal.set_led = cfg->set_led != NULL ? hal_set_led : NULL;
    port->hal.set_signal = NULL; /* no RTS / DTR on this UART */
    port->hal.uart_tx_abort = hal_uart_tx_abort;
}

void modcp_cmsdk_port_start(modcp_cmsdk_port_t *port, modcp_cp_t *cp, const modcp_params_t *p)
{
    uintptr_t u = port->cfg->uart;
    uint32_t baud = p->baud != 0u ? p->baud : 9600u;
    port->cp = cp;
    port->char_us = modcp_params_char_us(p);
    port->rs485 = p->iface == (uint8_t)MODCP_IFACE_RS485;
    port->txc_pending = false;
    port->tx_active = false;
    uint32_t div = port->cfg->pclk_hz / baud;
    UART_CTRL(u) = 0u;
    UART_BAUDDIV(u) = div >= UART_BAUDDIV_MIN ? div : UART_BAUDDIV_MIN;
    UART_STATE(u) = UART_STATE_RXOVR | UART_STATE_TXOVR;
    UART_INT(u) = UART_INT_TX | UART_INT_RX | UART_INT_TXOVR | UART_INT_RXOVR;
    /* the timers start stopped */
    TIMER_CTRL(port->cfg->timer) = 0u;
    TIMER_INT(port->cfg->timer) = 1u;
    DUAL_CTRL(port->cfg->dualtimer) = 0u;
    DUAL_INTCLR(port->cfg->dualtimer) = 1u;
    UART_CTRL(u) = UART_CTRL_TXEN | UART_CTRL_RXEN | UART_CTRL_RXINT | UART_CTRL_RXOVRINT;
    /* no modem inputs: CTS and DSR are permanently ON (see hal_cmsdk.h) */
    modcp_cp_on_signals(cp, true, true, port->cfg->now_us());
}

/* ---- interrupts ---- */

/* Take every received character out of the UART and hand it to the core. */
static void rx_drain(void *ctx)
{
    modcp_cmsdk_port_t *port = ctx;
    uintptr_t u = port->cfg->uart;
    while ((UART_STATE(u) & UART_STATE_RXFULL) != 0u) {
        uint8_t b = (uint8_t)UART_DATA(u);
        uint32_t now = port->cfg->now_us();
        port->rx_bytes++;
        if (!port->rs485 && (port->txc_pending || tx_all_written(port))) {
            /* the master has our whole reply, so it is out: see hal_cmsdk.h */
            UART_CTRL(u) &= ~UART_CTRL_TXINT;
            UART_INT(u) = UART_INT_TX;
            port->tx_active = false;
            tx_complete(port, now);
        }
        if (port->cp != NULL) {
            modcp_cp_on_rx(port->cp, b, now);
        }
    }
}

void modcp_cmsdk_port_rx_isr(modcp_cmsdk_port_t *port)
{
    UART_INT(port->cfg->uart) = UART_INT_RX;
    rx_drain(port);
}

void modcp_cmsdk_port_tx_isr(modcp_cmsdk_port_t *port)
{
    uintptr_t u = port->cfg->uart;
    UART_INT(u) = UART_INT_TX;
    if ((UART_CTRL(u) & UART_CTRL_TXINT) == 0u) {
        return;
    }
    if (port->tx_pos < port->tx_len) {
        UART_DATA(u) = port->tx_buf[port->tx_pos++];
        port->tx_bytes++;
        return;
    }
    /* The buffer emptied after the last byte: that byte is in the shift register now
     * and its stop bit ends one character time from here. */
    UART_CTRL(u) &= ~UART_CTRL_TXINT;
    port->tx_active = false;
    txc_arm(port, port->char_us);
}

void modcp_cmsdk_port_overflow_isr(modcp_cmsdk_port_t *port)
{
    uintptr_t u = port->cfg->uart;
    if ((UART_INT(u) & UART_INT_RXOVR) == 0u) {
        return;
    }
    UART_STATE(u) = UART_STATE_RXOVR;
    UART_INT(u) = UART_INT_RXOVR;
    port->overruns++;
    if (port->cp != NULL) {
        modcp_cp_on_line_error(port->cp, MODCP_LINE_OVERRUN, port->cfg->now_us());
    }
}

static const modcp_eof_ops_t eof_ops = {
    .drain = rx_drain,
    .rx_mark = eof_mark,
    .restart = eof_restart,
};

/* End-of-frame expiry, reported to the core only after MODCP_CMSDK_EOF_QUIET_ROUNDS
 * expiries in a row found nothing received (modcp/hal_eof.h; docs/porting.md §4: in
 * QEMU it makes the end of frame independent of host load). */
void modcp_cmsdk_port_timer_isr(modcp_cmsdk_port_t *port)
{
    uintptr_t t = port->cfg->timer;
    if ((TIMER_INT(t) & 1u) == 0u) {
        return; /* disarmed or re-armed after it fired */
    }
    TIMER_CTRL(t) = 0u;
    TIMER_INT(t) = 1u;
    if (modcp_eof_expired(&port->eof, &eof_ops, port, MODCP_CMSDK_EOF_QUIET_ROUNDS) &&
        port->cp != NULL) {
        modcp_cp_on_timer(port->cp, port->cfg->now_us());
    }
}

void modcp_cmsdk_port_txc_isr(modcp_cmsdk_port_t *port)
{
    uintptr_t d = port->cfg->dualtimer;
    if ((DUAL_MIS(d) & 1u) == 0u) {
        return;
    }
    tx_complete(port, port->cfg->now_us());
}
