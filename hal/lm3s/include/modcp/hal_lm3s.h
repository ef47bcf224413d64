/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL for TI Stellaris LM3S (LM3S6965 and other LM3S with PL011 UARTs and GPTM
 * timers; board lm3s6965evb).
 *
 *   Modbus port   PL011 UART, FIFOs off (one-character holding register, like the
 *                 other ports' UARTs): receive with the error bits of DR, transmit
 *                 interrupt per character
 *                 GPTM A (32-bit one-shot): the end-of-frame one-shot (timer_arm)
 *                 GPTM B (32-bit one-shot): transmit complete (see below)
 *   Time base     SysTick, free running over its 24 bits at the core clock, extended to
 *                 microseconds and milliseconds (modcp/hal_timebase.h)
 *   Console       a second PL011 with the shared queues (modcp/hal_conq.h)
 *
 * Transmission complete: the PL011 has no "transmit complete" interrupt (FR.BUSY only,
 * polled). Its transmit interrupt (FIFOs off) comes when the holding register empties,
 * i.e. when a character moves into the shift register; after the last character's the
 * port starts a one-shot of one character time (start + data + parity + stop bits at the
 * configured rate) and reports modcp_cp_on_tx_done() when it expires. With RS232 /
 * RS422 a character received after the last one was handed over completes the
 * transmission at once (the master answers only after our last stop bit), as on the
 * CMSDK port; with RS485 the full character time is always waited for.
 *
 * Line errors: DR's FE / PE / BE bits come with the character they concern, which is
 * reported with modcp_cp_on_line_error() in its place (BE as MODCP_LINE_BREAK). OE marks
 * the first character received after one was lost: the lost one is reported as
 * MODCP_LINE_OVERRUN, then this good character with modcp_cp_on_rx() (the contract of
 * modcp/hal.h).
 *
 * RS232 secondary signals: UART0 of the LM3S6965 has no modem lines. set_signal is NULL
 * and the port reports CTS and DSR ON once at start (modcp/hal.h).
 *
 * Concurrency: all modcp_lm3s_port_* interrupt entry points run at one priority, with
 * the CP task. */
#ifndef MODCP_HAL_LM3S_H
#define MODCP_HAL_LM3S_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal.h"
#include "modcp/hal_conq.h"
#include "modcp/hal_eof.h"
#include "modcp/hal_timebase.h"

/* ---- clocks and time base --------------------------------------------------------- */

/* The core clock from the PLL: 200 MHz / sysdiv from an 8 MHz crystal (the EVB's);
 * bounded wait for the lock, stays on the reset clock otherwise. Returns the clock in
 * Hz it set (QEMU derives its clock from RCC.SYSDIV alone, so the value is the same). */
uint32_t modcp_lm3s_clock_init(uint32_t sysdiv);
/* SysTick free running (no interrupt) as the time base at hz. */
void modcp_lm3s_time_init(uint32_t hz);
/* Microseconds / milliseconds since modcp_lm3s_time_init (wrap at 2^32). Safe from
 * thread mode and interrupts; called at least every 2^24 cycles (the 1 ms tick). */
uint32_t modcp_lm3s_now_us(void);
uint32_t modcp_lm3s_now_ms(void);

/* ---- Modbus port ------------------------------------------------------------------ */

typedef struct {
    uintptr_t uart;   /* PL011 base */
    uintptr_t eof;    /* GPTM base: the end-of-frame one-shot */
    uintptr_t txc;    /* GPTM base: the transmit-complete one-shot */
    uint32_t clk_hz;  /* UART and timer clock */
    uint32_t (*now_us)(void);
    void (*set_de)(bool on);                   /* RS485 driver enable; may be NULL */
    void (*set_led)(modcp_led_t led, bool on); /* may be NULL */
} modcp_lm3s_cfg_t;

typedef struct {
    modcp_hal_t hal; /* hand &port->hal to modcp_cp_init() */
    const modcp_lm3s_cfg_t *cfg;
    modcp_cp_t *cp;
    const uint8_t *tx_buf;
    uint16_t tx_len;
    uint16_t tx_pos;
    uint32_t cyc_per_us;
    uint32_t char_us;
    uint8_t data_mask; /* 0x7F with 7 data bits */
    bool rs485;
    bool tx_active;   /* characters still to hand over, or the last TX interrupt to come */
    bool txc_pending; /* the transmit-complete one-shot runs */
    uint32_t rx_bytes;
    uint32_t tx_bytes;
    uint32_t line_errors;
    modcp_eof_t eof; /* end-of-frame confirmation, mark = rx_bytes + line_errors */
} modcp_lm3s_port_t;

#ifndef MODCP_LM3S_EOF_QUIET_ROUNDS
#define MODCP_LM3S_EOF_QUIET_ROUNDS 3u
#endif

/* Fill port->hal; no hardware is touched. */
void modcp_lm3s_port_init(modcp_lm3s_port_t *port, const modcp_lm3s_cfg_t *cfg);
/* Program the UART (baud rate, 7/8 data bits, parity, 1/2 stop bits) and the timers and
 * start receiving for cp. The caller enables the interrupts afterwards. */
void modcp_lm3s_port_start(modcp_lm3s_port_t *port, modcp_cp_t *cp, const modcp_params_t *p);

/* Interrupt entry points: the UART, the end-of-frame GPTM, the transmit-complete GPTM. */
void modcp_lm3s_port_uart_isr(modcp_lm3s_port_t *port);
void modcp_lm3s_port_eof_isr(modcp_lm3s_port_t *port);
void modcp_lm3s_port_txc_isr(modcp_lm3s_port_t *port);

/* ---- console UART (8N1, FIFOs on) --------------------------------------------------- */

typedef struct {
    uintptr_t uart;
    volatile bool tx_active;
    modcp_conq_t q;
} modcp_lm3s_con_t;

void modcp_lm3s_con_init(modcp_lm3s_con_t *con, uintptr_t uart, uint32_t clk_hz, uint32_t baud);
int modcp_lm3s_con_getc(modcp_lm3s_con_t *con);
void modcp_lm3s_con_write(modcp_lm3s_con_t *con, const char *s, size_t n);
void modcp_lm3s_con_isr(modcp_lm3s_con_t *con);

/* ---- 1 ms tick on a GPTM (periodic) --------------------------------------------------- */

void modcp_lm3s_tick_init(uintptr_t gptm, uint32_t clk_hz);
/* true when the tick's time-out was pending (and is now cleared). */
bool modcp_lm3s_tick_ack(uintptr_t gptm);

/* PL011 baud-rate divisor: IBRD << 6 | FBRD for clk_hz / (16 baud), rounded. */
static inline uint32_t modcp_lm3s_brd(uint32_t clk_hz, uint32_t baud)
{
    return (uint32_t)(((uint64_t)clk_hz * 4u + baud / 2u) / baud);
}

#endif
