/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (nRF51) — the Modbus port: UART0 receive / transmit, the end-of-frame
 * one-shot on a 16-bit TIMER, RS485 DE and the LEDs, feeding the CP's event functions. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal_nrf51.h"
#include "nrf51_regs.h"

#define OS_MAX_US 0xFFFFu /* one compare of a 16-bit timer at 1 MHz */

uint32_t modcp_nrf51_baudrate_reg(uint32_t baud)
{
    /* baud * 2^32 / 16e6 = baud * 2^22 / 15625; in 4096 steps: (baud * 1024 / 15625) << 12 */
    if (baud > 1000000u) {
        baud = 1000000u;
    }
    return ((baud * 1024u + 15625u / 2u) / 15625u) << 12;
}

/* ---- end-of-frame one-shot ---- */

static void os_start(modcp_nrf51_port_t *p)
{
    uintptr_t t = p->cfg->timer;
    uint32_t chunk = p->os_left > OS_MAX_US ? OS_MAX_US : p->os_left;
    p->os_left -= chunk;
    TIMER_TASKS_CLEAR(t) = 1u;
    TIMER_CC(t, 0) = chunk;
    TIMER_TASKS_START(t) = 1u; /* COMPARE[0] stops and clears it (SHORTS) */
}

/* Start the one-shot for `us` (0: stop it). */
static void oneshot_start(modcp_nrf51_port_t *p, uint32_t us)
{
    uintptr_t t = p->cfg->timer;
    TIMER_TASKS_STOP(t) = 1u;
    TIMER_EVENTS_COMPARE(t, 0) = 0u; /* an expiry not yet handled is dropped: the ISR
                                      * finds the event clear */
    p->os_left = 0u;
    if (us == 0u) {
        return;
    }
    p->os_left = us;
    os_start(p);
}

static uint32_t eof_mark(void *ctx)
{
    const modcp_nrf51_port_t *p = ctx;
    return p->rx_bytes + p->line_errors;
}

static void eof_restart(void *ctx, uint32_t us)
{
    oneshot_start(ctx, us);
}

static void eof_drain(void *ctx)
{
    modcp_nrf51_port_uart_isr(ctx);
}

static const modcp_eof_ops_t eof_ops = {
    .drain = eof_drain,
    .rx_mark = eof_mark,
    .restart = eof_restart,
};

static void hal_timer_arm(void *ctx, uint32_t us)
{
    modcp_nrf51_port_t *p = ctx;
    modcp_eof_arm(&p->eof, eof_mark(p));
    oneshot_start(p, us);
}

void modcp_nrf51_port_timer_isr(modcp_nrf51_port_t *port)
{
    uintptr_t t = port->cfg->timer;
    if (TIMER_EVENTS_COMPARE(t, 0) == 0u) {
        return;
    }
    TIMER_EVENTS_COMPARE(t, 0) = 0u;
    if (port->os_left != 0u) {
        os_start(port); /* a wait longer than the 16-bit compare: the next part */
        return;
    }
    /* End-of-frame expiry, reported to the core only after MODCP_NRF51_EOF_QUIET_ROUNDS
     * expiries in a row (the first one and 1 us confirmation one-shots) found no
     * character in the UART or arriving meanwhile (modcp/hal_eof.h, docs/porting.md
     * section 4). In QEMU the UART model's 6-byte FIFO is filled from the pty and the
     * timers run in the same main-loop iteration, the pty first; a late expiry would
     * otherwise be taken before bytes the master wrote long before. */
    if (modcp_eof_expired(&port->eof, &eof_ops, port, MODCP_NRF51_EOF_QUIET_ROUNDS) &&
        port->cp != NULL) {
        modcp_cp_on_timer(port->cp, port->cfg->now_us());
    }
}

/* ---- transmit ---- */

static void hal_uart_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    modcp_nrf51_port_t *p = ctx;
    uintptr_t u = p->cfg->uart;
    p->tx_buf = buf;
    p->tx_len = len;
    p->tx_pos = 0u;
    p->tx_active = true;
    if (len == 0u) {
        /* done at once, but reported from the interrupt, not from inside uart_tx */
        NRF_NVIC_ISPR = 1u << p->cfg->uart_irq;
        return;
    }
    UART_EVENTS_TXDRDY(u) = 0u;
    p->tx_pos = 1u;
    p->tx_bytes++;
    UART_TXD(u) = buf[0]; /* the TXDRDY interrupt (at this priority) sends the rest */
}

static void hal_uart_tx_abort(void *ctx)
{
    modcp_nrf51_port_t *p = ctx;
    p->tx_len = p->tx_pos; /* the byte on the line still finishes */
    p->tx_active = false;
}

static void hal_set_de(void *ctx, bool on)
{
    modcp_nrf51_port_t *p = ctx;
    modcp_nrf51_pin_set(&p->cfg->de, on);
}

static void hal_set_led(void *ctx, modcp_led_t led, bool on)
{
    modcp_nrf51_port_t *p = ctx;
    if ((unsigned)led < 3u) {
        modcp_nrf51_pin_set(&p->cfg->led[led], on);
    }
}

void modcp_nrf51_port_init(modcp_nrf51_port_t *port, const modcp_nrf51_cfg_t *cfg)
{
    *port = (modcp_nrf51_port_t){0};
    port->cfg = cfg;
    port->hal.ctx = port;
    port->hal.uart_tx = hal_uart_tx;
    port->hal.timer_arm = hal_timer_arm;
    port->hal.set_de = cfg->de.pin != MODCP_NRF51_PIN_NONE ? hal_set_de : NULL;
    port->hal.set_led = hal_set_led;
    port->hal.set_signal = NULL;
    port->hal.uart_tx_abort = hal_uart_tx_abort;
    modcp_nrf51_pin_output(&cfg->de);
    for (unsigned i = 0; i < 3u; i++) {
        modcp_nrf51_pin_output(&cfg->led[i]);
    }
    uintptr_t t = cfg->timer;
    TIMER_TASKS_STOP(t) = 1u;
    TIMER_MODE(t) = TIMER_MODE_TIMER;
    TIMER_BITMODE(t) = TIMER_BITMODE_16;
    TIMER_PRESCALER(t) = TIMER_PRESCALER_1MHZ;
    TIMER_SHORTS(t) = TIMER_SHORTS_COMPARE_CLEAR(0) | TIMER_SHORTS_COMPARE_STOP(0);
    TIMER_INTENCLR(t) = 0xFFFFFFFFu;
    TIMER_EVENTS_COMPARE(t, 0) = 0u;
    TIMER_INTENSET(t) = TIMER_INT_COMPARE(0);
}

void modcp_nrf51_port_start(modcp_nrf51_port_t *port, modcp_cp_t *cp, const modcp_params_t *p)
{
    uintptr_t u = port->cfg->uart;
    port->cp = cp;
    port->tx_active = false;
    port->rs485 = p->iface == (uint8_t)MODCP_IFACE_RS485;
    UART_ENABLE(u) = 0u;
    UART_PSELTXD(u) = port->cfg->txd_pin;
    UART_PSELRXD(u) = port->cfg->rxd_pin;
    UART_PSELRTS(u) = UART_PSEL_DISCONNECTED;
    UART_PSELCTS(u) = UART_PSEL_DISCONNECTED;
    /* RX pin: input with pull-up (an open line reads idle, not BREAK) */
    GPIO_PIN_CNF(port->cfg->rxd_pin) = GPIO_PIN_CNF_INPUT_CONNECT | GPIO_PIN_CNF_PULLUP;
    GPIO_OUTSET = 1u << port->cfg->txd_pin; /* TX idles high */
    GPIO_DIRSET = 1u << port->cfg->txd_pin;
    UART_BAUDRATE(u) = modcp_nrf51_baudrate_reg(p->baud != 0u ? p->baud : 9600u);
    /* even parity or none; odd is not available on this UART (see hal_nrf51.h) */
    UART_CONFIG(u) = p->parity != (uint8_t)MODCP_PARITY_NONE ? UART_CONFIG_PARITY_EVEN : 0u;
    UART_ENABLE(u) = UART_ENABLE_ON;
    UART_EVENTS_RXDRDY(u) = 0u;
    UART_EVENTS_TXDRDY(u) = 0u;
    UART_EVENTS_ERROR(u) = 0u;
    UART_ERRORSRC(u) = 0xFu;
    UART_INTENSET(u) = UART_INT_RXDRDY | UART_INT_TXDRDY | UART_INT_ERROR;
    UART_TASKS_STARTRX(u) = 1u;
    UART_TASKS_STARTTX(u) = 1u;
    /* no modem inputs wired: CTS and DSR are permanently ON */
    modcp_cp_on_signals(cp, true, true, port->cfg->now_us());
}

/* ---- interrupt ---- */

static void tx_done(modcp_nrf51_port_t *p)
{
    p->tx_active = false;
    if (p->cp != NULL) {
        modcp_cp_on_tx_done(p->cp, p->cfg->now_us());
    }
}

void modcp_nrf51_port_uart_isr(modcp_nrf51_port_t *port)
{
    uintptr_t u = port->cfg->uart;
    /* Transmit first: when the master's next request and our last TXDRDY are both
     * pending, the reply is complete (the master answers only after our stop bit). */
    if (port->tx_active && port->tx_len == 0u) {
        tx_done(port);
    }
    /* Silicon: TXDRDY comes one character after the write, so this loop sends one byte
     * per interrupt. QEMU: the write is complete at once and sets TXDRDY again, so the
     * loop sends the whole frame and reports its end before looking at received bytes. */
    while (UART_EVENTS_TXDRDY(u) != 0u) {
        UART_EVENTS_TXDRDY(u) = 0u;
        if (!port->tx_active) {
            break;
        }
        if (port->tx_pos < port->tx_len) {
            port->tx_bytes++;
            UART_TXD(u) = port->tx_buf[port->tx_pos++];
        } else {
            tx_done(port); /* the last byte's stop bit has left */
        }
    }
    uint8_t err = 0u;
    bool overrun = false;
    if (UART_EVENTS_ERROR(u) != 0u) {
        UART_EVENTS_ERROR(u) = 0u;
        uint32_t src = UART_ERRORSRC(u);
        UART_ERRORSRC(u) = src;
        if ((src & UART_ERRORSRC_BREAK) != 0u) {
            err |= (uint8_t)MODCP_LINE_BREAK;
        } else {
            if ((src & UART_ERRORSRC_FRAMING) != 0u) {
                err |= (uint8_t)MODCP_LINE_FRAMING;
            }
            if ((src & UART_ERRORSRC_PARITY) != 0u) {
                err |= (uint8_t)MODCP_LINE_PARITY;
            }
        }
        overrun = (src & UART_ERRORSRC_OVERRUN) != 0u;
    }
    bool reported = false;
    while (UART_EVENTS_RXDRDY(u) != 0u) {
        UART_EVENTS_RXDRDY(u) = 0u; /* before reading RXD: the next byte sets it again */
        uint8_t b = (uint8_t)UART_RXD(u);
        uint32_t now = port->cfg->now_us();
        if (port->cp == NULL) {
            continue;
        }
        if (err != 0u && !reported) {
            reported = true; /* the erroneous character is reported as the error */
            port->line_errors++;
            modcp_cp_on_line_error(port->cp, err, now);
        } else {
            port->rx_bytes++;
            modcp_cp_on_rx(port->cp, b, now);
        }
    }
    if (err != 0u && !reported && port->cp != NULL) {
        port->line_errors++; /* BREAK, or an error without a character */
        modcp_cp_on_line_error(port->cp, err, port->cfg->now_us());
    }
    /* OVERRUN: the characters in RXD were received; the one lost came after them, so it
     * is reported after them (the contract of modcp/hal.h) */
    if (overrun && port->cp != NULL) {
        port->line_errors++;
        modcp_cp_on_line_error(port->cp, MODCP_LINE_OVERRUN, port->cfg->now_us());
    }
}
