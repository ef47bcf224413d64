/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (LM3S) — the Modbus port: PL011 receive / transmit, the end-of-frame and
 * transmit-complete one-shots on two GPTMs, feeding the CP's event functions. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lm3s_regs.h"
#include "modcp/cp.h"
#include "modcp/hal_lm3s.h"

static uint32_t cycles_of(const modcp_lm3s_port_t *p, uint32_t us)
{
    uint32_t max_us = 0xFFFFFFFFu / p->cyc_per_us;
    if (us > max_us) {
        us = max_us;
    }
    uint32_t c = us * p->cyc_per_us;
    return c != 0u ? c : 1u;
}

/* A 32-bit one-shot on timer A of GPTM `t` (us == 0: stopped). Disabling and clearing
 * the time-out first drops an expiry already pending: the ISR finds MIS clear. */
static void oneshot(const modcp_lm3s_port_t *p, uintptr_t t, uint32_t us)
{
    GPTM_CTL(t) = 0u;
    GPTM_ICR(t) = GPTM_INT_TATO;
    if (us == 0u) {
        return;
    }
    GPTM_CFG(t) = GPTM_CFG_32BIT;
    GPTM_TAMR(t) = GPTM_TAMR_ONESHOT;
    GPTM_TAILR(t) = cycles_of(p, us);
    GPTM_IMR(t) = GPTM_INT_TATO;
    GPTM_CTL(t) = GPTM_CTL_TAEN;
}

static void txc_stop(modcp_lm3s_port_t *p)
{
    oneshot(p, p->cfg->txc, 0u);
    p->txc_pending = false;
}

static void tx_complete(modcp_lm3s_port_t *p, uint32_t now_us)
{
    txc_stop(p);
    if (p->cp != NULL) {
        modcp_cp_on_tx_done(p->cp, now_us);
    }
}

static bool tx_all_written(const modcp_lm3s_port_t *p)
{
    return p->tx_active && p->tx_pos >= p->tx_len;
}

/* ---- modcp_hal_t callbacks (at the CP's priority) ---- */

static void hal_uart_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    modcp_lm3s_port_t *p = ctx;
    uintptr_t u = p->cfg->uart;
    p->tx_buf = buf;
    p->tx_len = len;
    p->tx_pos = 0u;
    if (len == 0u) {
        /* nothing to send: complete from the one-shot, never from here (modcp/hal.h) */
        oneshot(p, p->cfg->txc, 1u);
        p->txc_pending = true;
        return;
    }
    p->tx_active = true;
    UART_ICR(u) = UART_INT_TX;
    UART_IM(u) |= UART_INT_TX;
    p->tx_pos = 1u;
    p->tx_bytes++;
    UART_DR(u) = buf[0];
}

static void eof_restart(void *ctx, uint32_t us)
{
    modcp_lm3s_port_t *p = ctx;
    oneshot(p, p->cfg->eof, us);
}

static uint32_t eof_mark(void *ctx)
{
    const modcp_lm3s_port_t *p = ctx;
    return p->rx_bytes + p->line_errors;
}

static void hal_timer_arm(void *ctx, uint32_t us)
{
    modcp_lm3s_port_t *p = ctx;
    modcp_eof_arm(&p->eof, eof_mark(p));
    oneshot(p, p->cfg->eof, us);
}

static void hal_uart_tx_abort(void *ctx)
{
    modcp_lm3s_port_t *p = ctx;
    UART_IM(p->cfg->uart) &= ~UART_INT_TX;
    p->tx_len = p->tx_pos; /* the character in the shift register still finishes */
    p->tx_active = false;
    txc_stop(p);
}

static void hal_set_de(void *ctx, bool on)
{
    modcp_lm3s_port_t *p = ctx;
    p->cfg->set_de(on);
}

static void hal_set_led(void *ctx, modcp_led_t led, bool on)
{
    modcp_lm3s_port_t *p = ctx;
    p->cfg->set_led(led, on);
}

void modcp_lm3s_port_init(modcp_lm3s_port_t *port, const modcp_lm3s_cfg_t *cfg)
{
    *port = (modcp_lm3s_port_t){0};
    port->cfg = cfg;
    port->cyc_per_us = cfg->clk_hz / 1000000u != 0u ? cfg->clk_hz / 1000000u : 1u;
    port->data_mask = 0xFFu;
    port->hal.ctx = port;
    port->hal.uart_tx = hal_uart_tx;
    port->hal.timer_arm = hal_timer_arm;
    port->hal.set_de = cfg->set_de != NULL ? hal_set_de : NULL;
    port->hal.set_led = cfg->set_led != NULL ? hal_set_led : NULL;
    port->hal.set_signal = NULL; /* no RTS / DTR on UART0 */
    port->hal.uart_tx_abort = hal_uart_tx_abort;
}

void modcp_lm3s_port_start(modcp_lm3s_port_t *port, modcp_cp_t *cp, const modcp_params_t *p)
{
    uintptr_t u = port->cfg->uart;
    uint32_t baud = p->baud != 0u ? p->baud : 9600u;
    port->cp = cp;
    port->char_us = modcp_params_char_us(p);
    port->rs485 = p->iface == (uint8_t)MODCP_IFACE_RS485;
    port->data_mask = p->data_bits == 7u ? 0x7Fu : 0xFFu;
    port->txc_pending = false;
    port->tx_active = false;
    uint32_t lcrh = p->data_bits == 7u ? UART_LCRH_WLEN_7 : UART_LCRH_WLEN_8; /* FIFOs off */
    if (p->parity != (uint8_t)MODCP_PARITY_NONE) {
        lcrh |= UART_LCRH_PEN;
        if (p->parity == (uint8_t)MODCP_PARITY_EVEN) {
            lcrh |= UART_LCRH_EPS;
        }
    }
    if (p->stop_bits == 2u) {
        lcrh |= UART_LCRH_STP2;
    }
    uint32_t brd = modcp_lm3s_brd(port->cfg->clk_hz, baud);
    UART_CTL(u) = 0u;
    UART_IBRD(u) = brd >> 6;
    UART_FBRD(u) = brd & 63u;
    UART_LCRH(u) = lcrh; /* after IBRD / FBRD: the write latches them */
    UART_RSR(u) = 0u;
    UART_ICR(u) = 0x7F0u;
    oneshot(port, port->cfg->eof, 0u);
    oneshot(port, port->cfg->txc, 0u);
    UART_IM(u) = UART_INT_RX | UART_INT_ERR;
    UART_CTL(u) = UART_CTL_UARTEN | UART_CTL_TXE | UART_CTL_RXE;
    /* no modem inputs: CTS and DSR are ON, reported once (modcp/hal.h) */
    modcp_cp_on_signals(cp, true, true, port->cfg->now_us());
}

/* ---- interrupts ---- */

/* Take every received character out of the UART and hand it to the core. */
static void rx_drain(void *ctx)
{
    modcp_lm3s_port_t *port = ctx;
    uintptr_t u = port->cfg->uart;
    UART_ICR(u) = UART_INT_RX | UART_INT_RT | UART_INT_ERR;
    while ((UART_FR(u) & UART_FR_RXFE) == 0u) {
        uint32_t d = UART_DR(u);
        uint32_t now = port->cfg->now_us();
        if (!port->rs485 && (port->txc_pending || tx_all_written(port))) {
            /* the master has our whole reply, so it is out (hal_lm3s.h) */
            UART_IM(u) &= ~UART_INT_TX;
            port->tx_active = false;
            tx_complete(port, now);
        }
        if ((d & UART_DR_OE) != 0u) {
            /* a character was lost before this one (modcp/hal.h): report it first */
            UART_RSR(u) = 0u;
            port->line_errors++;
            if (port->cp != NULL) {
                modcp_cp_on_line_error(port->cp, MODCP_LINE_OVERRUN, now);
            }
        }
        uint8_t err = 0u;
        if ((d & UART_DR_BE) != 0u) {
            err = MODCP_LINE_BREAK;
        } else if ((d & UART_DR_FE) != 0u) {
            err = MODCP_LINE_FRAMING;
        } else if ((d & UART_DR_PE) != 0u) {
            err = MODCP_LINE_PARITY;
        }
        if (err != 0u) {
            UART_RSR(u) = 0u;
            port->line_errors++;
            if (port->cp != NULL) {
                modcp_cp_on_line_error(port->cp, err, now);
            }
            continue;
        }
        port->rx_bytes++;
        if (port->cp != NULL) {
            modcp_cp_on_rx(port->cp, (uint8_t)(d & port->data_mask), now);
        }
    }
}

void modcp_lm3s_port_uart_isr(modcp_lm3s_port_t *port)
{
    uintptr_t u = port->cfg->uart;
    /* Transmit first: QEMU raises the TX interrupt on the data write itself, and a
     * stalled vCPU may find the master's next request already waiting beside it. */
    if ((UART_MIS(u) & UART_INT_TX) != 0u) {
        UART_ICR(u) = UART_INT_TX;
        if (port->tx_pos < port->tx_len) {
            port->tx_bytes++;
            UART_DR(u) = port->tx_buf[port->tx_pos++];
        } else if (port->tx_active) {
            /* the last character moved into the shift register: its stop bit ends one
             * character time from now */
            UART_IM(u) &= ~UART_INT_TX;
            port->tx_active = false;
            oneshot(port, port->cfg->txc, port->char_us);
            port->txc_pending = true;
        } else {
            UART_IM(u) &= ~UART_INT_TX;
        }
    }
    rx_drain(port);
}

static const modcp_eof_ops_t eof_ops = {
    .drain = rx_drain,
    .rx_mark = eof_mark,
    .restart = eof_restart,
};

void modcp_lm3s_port_eof_isr(modcp_lm3s_port_t *port)
{
    uintptr_t t = port->cfg->eof;
    if ((GPTM_MIS(t) & GPTM_INT_TATO) == 0u) {
        return; /* disarmed or re-armed after it fired */
    }
    GPTM_ICR(t) = GPTM_INT_TATO;
    if (modcp_eof_expired(&port->eof, &eof_ops, port, MODCP_LM3S_EOF_QUIET_ROUNDS) &&
        port->cp != NULL) {
        modcp_cp_on_timer(port->cp, port->cfg->now_us());
    }
}

void modcp_lm3s_port_txc_isr(modcp_lm3s_port_t *port)
{
    uintptr_t t = port->cfg->txc;
    if ((GPTM_MIS(t) & GPTM_INT_TATO) == 0u) {
        return;
    }
    tx_complete(port, port->cfg->now_us());
}
