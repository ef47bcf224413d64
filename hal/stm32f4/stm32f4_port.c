/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — the Modbus port: USART receive / transmit with transmission
 * complete, the end-of-frame one-shot (TIM2 one-pulse mode or the SysTick deadline),
 * RS485 DE and the LEDs, feeding the CP's event functions. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal_stm32f4.h"
#include "stm32f4_internal.h"
#include "stm32f4_regs.h"

/* ---- end-of-frame one-shot ---- */

static void rx_drain(void *ctx);
static void oneshot_fired(void *ctx, uint32_t now_us);

static void tim_setup(const modcp_stm32_cfg_t *cfg)
{
    uintptr_t t = cfg->tim;
    TIM_CR1(t) = 0u;
    TIM_DIER(t) = 0u;
    TIM_PSC(t) = cfg->tim_clk_hz / 1000000u - 1u; /* 1 us per count */
    TIM_ARR(t) = 0xFFFFFFFFu;
    TIM_CR1(t) = TIM_CR1_OPM | TIM_CR1_URS; /* stop at the update; only overflow sets UIF */
    TIM_EGR(t) = TIM_EGR_UG;                /* load PSC */
    TIM_SR(t) = 0u;
    TIM_DIER(t) = TIM_DIER_UIE;
}

/* Start the one-shot for `us` (0: stop it). */
static void oneshot_start(modcp_stm32_port_t *p, uint32_t us)
{
    if (p->cfg->oneshot == (uint8_t)MODCP_STM32_ONESHOT_SYSTICK) {
        stm32_systick_oneshot(us, oneshot_fired, p);
        return;
    }
    uintptr_t t = p->cfg->tim;
    TIM_CR1(t) = TIM_CR1_OPM | TIM_CR1_URS; /* CEN off */
    TIM_SR(t) = 0u; /* an expiry not yet handled is dropped: the ISR finds UIF clear */
    if (us == 0u) {
        return;
    }
    TIM_CNT(t) = 0u;
    TIM_ARR(t) = us > 1u ? us - 1u : 1u; /* update after ARR + 1 counts; ARR 0 would stop it */
    TIM_CR1(t) = TIM_CR1_OPM | TIM_CR1_URS | TIM_CR1_CEN;
}

static uint32_t eof_mark(void *ctx)
{
    const modcp_stm32_port_t *p = ctx;
    return p->rx_bytes + p->line_errors;
}

static void eof_restart(void *ctx, uint32_t us)
{
    oneshot_start(ctx, us);
}

static const modcp_eof_ops_t eof_ops = {
    .drain = rx_drain,
    .rx_mark = eof_mark,
    .restart = eof_restart,
};

static void hal_timer_arm(void *ctx, uint32_t us)
{
    modcp_stm32_port_t *p = ctx;
    modcp_eof_arm(&p->eof, eof_mark(p));
    oneshot_start(p, us);
}

/* End-of-frame expiry, reported to the core only after MODCP_STM32_EOF_QUIET_ROUNDS
 * expiries in a row (the first one and 1 us confirmation one-shots) found no character
 * in the USART or arriving meanwhile (modcp/hal_eof.h). On silicon that delays the report by a few
 * microseconds. In QEMU it makes the end of frame independent of host load: QEMU moves
 * the next byte of the pty into the USART and raises the timer interrupts in the same
 * main-loop thread, one byte per loop iteration and in each iteration the byte first;
 * a late expiry (the thread was descheduled) would otherwise be taken before a byte
 * the master wrote long before (SysTick even wins a tie against the USART interrupt).
 * A confirmation one-shot expires in a later iteration, and two quiet rounds prove that
 * an iteration polled the pty with the USART empty and found nothing (the third is
 * margin). The core gets on_timer only then and decides from its own timestamps. See
 * docs/porting.md. */
static void oneshot_fired(void *ctx, uint32_t now_us)
{
    modcp_stm32_port_t *p = ctx;
    (void)now_us;
    if (modcp_eof_expired(&p->eof, &eof_ops, p, MODCP_STM32_EOF_QUIET_ROUNDS) && p->cp != NULL) {
        modcp_cp_on_timer(p->cp, p->cfg->now_us());
    }
}

void modcp_stm32_port_tim_isr(modcp_stm32_port_t *port)
{
    uintptr_t t = port->cfg->tim;
    if ((TIM_SR(t) & TIM_SR_UIF) == 0u) {
        return;
    }
    TIM_SR(t) = 0u;
    oneshot_fired(port, port->cfg->now_us());
}

/* ---- transmit ---- */

static void hal_uart_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    modcp_stm32_port_t *p = ctx;
    uintptr_t u = p->cfg->usart;
    p->tx_buf = buf;
    p->tx_len = len;
    p->tx_pos = 0u;
    /* The interrupt (at this, the CP's priority, so only after we return) writes the
     * bytes on TXE and reports transmission complete on TC. */
    uint32_t cr1 = USART_CR1(u) & ~(USART_CR1_TXEIE | USART_CR1_TCIE);
    USART_CR1(u) = cr1 | (len > 0u ? USART_CR1_TXEIE : USART_CR1_TCIE);
    stm32_irq_pend(p->cfg->usart_irq); /* QEMU 7.2 raises no TXE / TC interrupt */
}

static void hal_uart_tx_abort(void *ctx)
{
    modcp_stm32_port_t *p = ctx;
    uintptr_t u = p->cfg->usart;
    USART_CR1(u) &= ~(USART_CR1_TXEIE | USART_CR1_TCIE);
    p->tx_len = p->tx_pos; /* the byte in the shift register still finishes */
}

static void hal_set_de(void *ctx, bool on)
{
    modcp_stm32_port_t *p = ctx;
    modcp_stm32_pin_set(&p->cfg->de, on);
}

static void hal_set_led(void *ctx, modcp_led_t led, bool on)
{
    modcp_stm32_port_t *p = ctx;
    if ((unsigned)led < 3u) {
        modcp_stm32_pin_set(&p->cfg->led[led], on);
    }
}

void modcp_stm32_port_init(modcp_stm32_port_t *port, const modcp_stm32_cfg_t *cfg)
{
    *port = (modcp_stm32_port_t){0};
    port->cfg = cfg;
    port->data_mask = 0xFFu;
    port->hal.ctx = port;
    port->hal.uart_tx = hal_uart_tx;
    port->hal.timer_arm = hal_timer_arm;
    port->hal.set_de = cfg->de.port != 0u ? hal_set_de : NULL;
    port->hal.set_led = hal_set_led;
    port->hal.set_signal = NULL;
    port->hal.uart_tx_abort = hal_uart_tx_abort;
    modcp_stm32_pin_output(&cfg->de);
    for (unsigned i = 0; i < 3u; i++) {
        modcp_stm32_pin_output(&cfg->led[i]);
    }
    if (cfg->oneshot == (uint8_t)MODCP_STM32_ONESHOT_TIM2) {
        tim_setup(cfg);
    }
}

void modcp_stm32_port_start(modcp_stm32_port_t *port, modcp_cp_t *cp, const modcp_params_t *p)
{
    uintptr_t u = port->cfg->usart;
    port->cp = cp;
    uint32_t cr1 = USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
    bool parity = p->parity != (uint8_t)MODCP_PARITY_NONE;
    if (parity) {
        cr1 |= USART_CR1_PCE;
        if (p->parity == (uint8_t)MODCP_PARITY_ODD) {
            cr1 |= USART_CR1_PS;
        }
    }
    /* word length counts the parity bit: 8 data + parity = 9 bits (M = 1). 7 data
     * without parity has no USART mode; it runs as 8 data bits. */
    if (p->data_bits >= 8u && parity) {
        cr1 |= USART_CR1_M;
    }
    port->data_mask = (p->data_bits == 7u && parity) ? 0x7Fu : 0xFFu;
    port->rs485 = p->iface == (uint8_t)MODCP_IFACE_RS485;
    uint32_t baud = p->baud != 0u ? p->baud : 9600u;
    USART_CR1(u) = 0u;
    USART_BRR(u) = (port->cfg->usart_clk_hz + baud / 2u) / baud; /* oversampling by 16 */
    USART_CR2(u) = p->stop_bits == 2u ? USART_CR2_STOP_2 : 0u;
    USART_CR3(u) = 0u;
    USART_CR1(u) = cr1 | USART_CR1_UE;
    /* no modem inputs wired: CTS and DSR are permanently ON (see hal_stm32f4.h) */
    modcp_cp_on_signals(cp, true, true, port->cfg->now_us());
}

/* ---- interrupt ---- */

/* Transmission complete (TC with TCIE on): report it once. */
static void tx_check_complete(modcp_stm32_port_t *port)
{
    uintptr_t u = port->cfg->usart;
    uint32_t cr1 = USART_CR1(u);
    if ((cr1 & USART_CR1_TCIE) != 0u && (USART_SR(u) & USART_SR_TC) != 0u) {
        /* transmission complete: the last stop bit has left the line */
        USART_CR1(u) = cr1 & ~USART_CR1_TCIE;
        if (port->cp != NULL) {
            modcp_cp_on_tx_done(port->cp, port->cfg->now_us());
        }
    }
}

/* Take every received character (or line error) out of the USART and hand it to the
 * core. RS232 / RS422: a transmission that is complete (TC) when a character is taken
 * is reported first — the master answers only after our last stop bit. Without that,
 * a CPU that took the interrupt late (in QEMU: the vCPU thread descheduled between the
 * reply and its TC interrupt, while the master already sent the next request) would
 * hand the request's first byte to the core while it still transmits, which drops it
 * and cuts the request. RS485 keeps the order: there the echo of our own last byte
 * arrives with TC. */
static void rx_drain(void *ctx)
{
    modcp_stm32_port_t *port = ctx;
    uintptr_t u = port->cfg->usart;
    uint32_t sr = USART_SR(u);
    while ((sr & (USART_SR_RXNE | USART_SR_ORE)) != 0u) {
        if (!port->rs485) {
            tx_check_complete(port);
        }
        uint8_t b = (uint8_t)(USART_DR(u) & port->data_mask); /* clears RXNE, PE, FE, ORE */
        uint32_t now = port->cfg->now_us();
        uint8_t err = 0u;
        if ((sr & USART_SR_FE) != 0u && b == 0u) {
            err |= (uint8_t)MODCP_LINE_BREAK; /* all-zero character without stop bit */
        } else {
            if ((sr & USART_SR_FE) != 0u) {
                err |= (uint8_t)MODCP_LINE_FRAMING;
            }
            if ((sr & USART_SR_PE) != 0u) {
                err |= (uint8_t)MODCP_LINE_PARITY;
            }
        }
        if (port->cp != NULL) {
            if (err != 0u) {
                port->line_errors++;
                modcp_cp_on_line_error(port->cp, err, now);
            } else {
                port->rx_bytes++;
                modcp_cp_on_rx(port->cp, b, now);
            }
            /* ORE: DR holds the character received before the lost one, so that one is
             * delivered and the lost one reported after it (the contract of modcp/hal.h) */
            if ((sr & USART_SR_ORE) != 0u) {
                port->line_errors++;
                modcp_cp_on_line_error(port->cp, MODCP_LINE_OVERRUN, now);
            }
        }
        sr = USART_SR(u);
    }
}

void modcp_stm32_port_usart_isr(modcp_stm32_port_t *port)
{
    uintptr_t u = port->cfg->usart;
    rx_drain(port);
    uint32_t cr1 = USART_CR1(u);
    if ((cr1 & USART_CR1_TXEIE) != 0u) {
        /* Silicon: TXE comes back one character after the previous write, so this loop
         * writes one byte (two at the start). QEMU: every write is complete at once. */
        while (port->tx_pos < port->tx_len && (USART_SR(u) & USART_SR_TXE) != 0u) {
            USART_DR(u) = port->tx_buf[port->tx_pos++]; /* SR read + DR write clear TC */
            port->tx_bytes++;
        }
        if (port->tx_pos >= port->tx_len) {
            /* the last byte is in DR / the shift register: now wait for its stop bit */
            cr1 = (USART_CR1(u) & ~USART_CR1_TXEIE) | USART_CR1_TCIE;
            USART_CR1(u) = cr1;
        }
    }
    tx_check_complete(port);
}
