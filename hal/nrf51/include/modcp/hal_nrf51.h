/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL for the Nordic nRF51 series (nRF51822: BBC micro:bit), Cortex-M0.
 *
 *   Time base     TIMER0, 32 bit at 1 MHz, free running: its counter is the microsecond
 *                 time (read by a CAPTURE task into CC[0]).
 *   Tick          TIMER2, a COMPARE[0] that clears the counter: the board's periodic
 *                 1 ms interrupt (the nRF51's Cortex-M0 has no SysTick).
 *   Modbus port   UART0 (RXDRDY, TXDRDY, ERROR events, one interrupt)
 *                 TIMER1 at 1 MHz: the end-of-frame one-shot (modcp_hal_t.timer_arm). On
 *                 silicon TIMER1 has 16 bits: a longer wait is run as several compares.
 *   Console       none: the nRF51 has one UART and the Modbus line has it.
 *
 * Transmission complete: the nRF51 UART raises TXDRDY when a byte "has been successfully
 * transmitted" (nRF51 RM v3.0, 29.5) and has no transmit buffer beyond TXD, so the
 * TXDRDY after the last byte is the moment its stop bit has left: the port reports
 * modcp_cp_on_tx_done() there (a frame of 0 bytes: from the interrupt, pended by
 * software, never from inside uart_tx). With RS232 / RS422 a character received after
 * the last byte was written also completes the transmission (the master answers only
 * after our last stop bit): under QEMU the master may have the reply, and its next
 * request may be in, before the guest has taken the last TXDRDY interrupt.
 *
 * Line format: the nRF51 UART has 8 data bits, 1 stop bit, and parity none or even
 * only. Odd parity, 7 data bits and 2 stop bits cannot be produced: such a record runs
 * the line as 8 data bits with even parity (odd) or none, 1 stop bit, which a master
 * configured as the record says will not understand; use even or none. Receive errors
 * (ERRORSRC: parity, framing, break) are reported with modcp_cp_on_line_error() in
 * place of the character; an overrun (a character lost while RXD was full) as
 * MODCP_LINE_OVERRUN after the characters RXD still delivers (modcp/hal.h).
 *
 * RS232 secondary signals: RTS / CTS exist as pins but only for hardware flow control;
 * set_signal is NULL and CTS and DSR are reported permanently ON at start (3-wire line).
 *
 * Concurrency: all modcp_nrf51_port_* interrupt entry points, the tick and the CP task
 * must run at one interrupt priority. */
#ifndef MODCP_HAL_NRF51_H
#define MODCP_HAL_NRF51_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal.h"
#include "modcp/hal_eof.h"
#include "modcp/hal_timebase.h"

#define MODCP_NRF51_TIMER0 0x40008000u
#define MODCP_NRF51_TIMER1 0x40009000u
#define MODCP_NRF51_TIMER2 0x4000A000u
#define MODCP_NRF51_UART0 0x40002000u
#define MODCP_NRF51_PIN_NONE 0xFFu

/* Interrupt numbers (peripheral ID = address bits 12..16). */
enum {
    MODCP_NRF51_IRQ_UART0 = 2,
    MODCP_NRF51_IRQ_TIMER0 = 8,
    MODCP_NRF51_IRQ_TIMER1 = 9,
    MODCP_NRF51_IRQ_TIMER2 = 10,
    MODCP_NRF51_IRQ_COUNT = 32,
};

/* ---- clocks and time base ------------------------------------------------------ */

/* Start the 16 MHz crystal oscillator (UART baud accuracy); false when it did not
 * report started within a bounded wait (the SoC then stays on its RC oscillator). */
bool modcp_nrf51_hfclk_start(void);
/* Start `timer` (TIMER0: 32 bit) free running at 1 MHz. */
void modcp_nrf51_clock_init(uintptr_t timer);
/* Microseconds since modcp_nrf51_clock_init (wraps at 2^32) and milliseconds (needs a
 * call at least every 71 minutes: the tick does it). Safe from thread mode and
 * interrupts. */
uint32_t modcp_nrf51_clock_us(void);
uint32_t modcp_nrf51_clock_ms(void);
/* Start `timer` (TIMER2) as a periodic interrupt every tick_us (<= 65535); the board
 * enables its interrupt. Its handler calls modcp_nrf51_tick_isr(): true on a tick. */
void modcp_nrf51_tick_init(uintptr_t timer, uint32_t tick_us);
bool modcp_nrf51_tick_isr(void);

/* ---- GPIO -------------------------------------------------------------------------- */

typedef struct {
    uint8_t pin; /* P0.n, or MODCP_NRF51_PIN_NONE */
    bool active_low;
} modcp_nrf51_pin_t;

void modcp_nrf51_pin_output(const modcp_nrf51_pin_t *p); /* output, inactive */
void modcp_nrf51_pin_set(const modcp_nrf51_pin_t *p, bool on);

/* ---- Modbus port --------------------------------------------------------------- */

typedef struct {
    uintptr_t uart;   /* UART0 */
    uint8_t uart_irq; /* its interrupt number (pended for a 0-byte frame) */
    uint8_t txd_pin;  /* P0.n */
    uint8_t rxd_pin;
    uintptr_t timer; /* end-of-frame one-shot: TIMER1 or TIMER2 (16 bit) */
    uint32_t (*now_us)(void);
    modcp_nrf51_pin_t de;     /* RS485 driver enable; pin NONE: no RS485 */
    modcp_nrf51_pin_t led[3]; /* SF, TXD, RXD; pin NONE: not fitted */
} modcp_nrf51_cfg_t;

typedef struct {
    modcp_hal_t hal; /* hand &port->hal to modcp_cp_init() */
    const modcp_nrf51_cfg_t *cfg;
    modcp_cp_t *cp;
    const uint8_t *tx_buf;
    uint16_t tx_len;
    uint16_t tx_pos;
    bool rs485;
    bool tx_active;   /* a frame is being sent: on_tx_done still to come */
    uint32_t os_left; /* one-shot: microseconds still to wait after the running compare */
    uint32_t rx_bytes;
    uint32_t tx_bytes;
    uint32_t line_errors;
    modcp_eof_t eof; /* end-of-frame handler (modcp/hal_eof.h), mark = rx_bytes + line_errors */
} modcp_nrf51_port_t;

/* Expiries in a row without a received character before one reaches the core
 * (docs/porting.md section 4). */
#ifndef MODCP_NRF51_EOF_QUIET_ROUNDS
#define MODCP_NRF51_EOF_QUIET_ROUNDS 3u /* 1: report the first quiet expiry (no confirmation; experiments) */
#endif

/* Fill port->hal, set up the one-shot timer and the DE / LED pins. */
void modcp_nrf51_port_init(modcp_nrf51_port_t *port, const modcp_nrf51_cfg_t *cfg);
/* Program the UART for the record's line (see above) and start receiving for cp. The
 * caller enables the UART and one-shot timer interrupts afterwards. */
void modcp_nrf51_port_start(modcp_nrf51_port_t *port, modcp_cp_t *cp, const modcp_params_t *p);

/* Interrupt entry points. The UART one may also be called from the tick: it handles
 * only events that are set (a safety net for a TXDRDY whose interrupt was lost). */
void modcp_nrf51_port_uart_isr(modcp_nrf51_port_t *port);
void modcp_nrf51_port_timer_isr(modcp_nrf51_port_t *port);

/* The BAUDRATE register value for a baud rate: baud * 2^32 / 16 MHz, rounded to the
 * 4096 steps the reference manual's table uses (9600 -> 0x00275000). */
uint32_t modcp_nrf51_baudrate_reg(uint32_t baud);

#endif
