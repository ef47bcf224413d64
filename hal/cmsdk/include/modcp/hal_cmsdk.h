/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL for ARM CMSDK peripherals (MPS2 AN385 and other CMSDK-based systems).
 *
 *   Modbus port   CMSDK APB UART (RX, TX, overflow interrupts)
 *                 CMSDK APB timer: the end-of-frame one-shot (modcp_hal_t.timer_arm)
 *                 CMSDK APB dual timer, timer 1: transmit complete (see below)
 *   Time base     CMSDK APB timer, free running at PCLK, extended to microseconds
 *   Console       a second CMSDK APB UART with interrupt-driven queues
 *
 * Transmission complete: the CMSDK UART has no "transmit complete" flag; its TX
 * interrupt fires when the one-byte buffer empties, i.e. when a byte moves into the
 * shift register. After the last byte's TX interrupt the port starts a one-shot of one
 * character time (start + data + parity + stop bits at the configured baud rate) on the
 * dual timer, and reports modcp_cp_on_tx_done() when it expires: that is the moment the
 * last stop bit has left the line. The UART itself sends 8N1 only; parity and 2 stop
 * bits are not available on this UART (the character time is still computed from the
 * parameters, so the timing follows the configured frame).
 * With RS232 / RS422 (no driver enable to time), a character received after the last
 * byte was handed to the UART (while its TX interrupt or that one-shot is still to
 * come) completes the transmission at once: the master answers only after it has
 * received our last stop bit, so the reply is out. This matters under QEMU, whose UART
 * hands each byte over instantly: the master has the whole reply up to one character
 * time before the one-shot expires (and, with the host busy, even before the guest has
 * taken the last TX interrupt) and may start its next request inside that window.
 * With RS485 the full character time is always waited for (DE must cover the stop bit,
 * and a transceiver may echo our own bytes).
 *
 * Line errors: the CMSDK UART detects no parity or framing errors and no BREAK; a
 * receive overrun (RX overflow interrupt) is reported as MODCP_LINE_OVERRUN.
 *
 * RS232 secondary signals: the UART has no RTS / DTR outputs and no CTS / DSR inputs.
 * set_signal is NULL and the port reports CTS and DSR permanently ON at start (a 3-wire
 * line), so automatic secondary signals (rs232_auto) keep their timing (data output
 * waiting time, time to RTS off) and never see CTS / DSR drop.
 *
 * Concurrency: all modcp_cmsdk_port_* interrupt entry points must run at one interrupt
 * priority (together with the CP task that calls modcp_cp_poll()). */
#ifndef MODCP_HAL_CMSDK_H
#define MODCP_HAL_CMSDK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal.h"
#include "modcp/hal_conq.h"
#include "modcp/hal_eof.h"
#include "modcp/hal_timebase.h"

/* ---- time base ---------------------------------------------------------------- */

/* Start timer `base` free running at pclk_hz (a whole number of MHz). */
void modcp_cmsdk_clock_init(uintptr_t base, uint32_t pclk_hz);
/* Microseconds since modcp_cmsdk_clock_init (wraps at 2^32), and milliseconds. Safe
 * from thread mode and interrupts; must be called at least once per 2^32 PCLK cycles
 * (171 s at 25 MHz) — the board's tick does that. */
uint32_t modcp_cmsdk_clock_us(void);
uint32_t modcp_cmsdk_clock_ms(void);

/* ---- Modbus port -------------------------------------------------------------- */

typedef struct {
    uintptr_t uart;      /* APB UART base */
    uintptr_t timer;     /* APB timer base: end-of-frame one-shot */
    uintptr_t dualtimer; /* APB dual timer base: its timer 1 times transmit complete */
    uint32_t pclk_hz;
    uint32_t (*now_us)(void);
    void (*set_de)(bool on);                    /* RS485 driver enable; may be NULL */
    void (*set_led)(modcp_led_t led, bool on);  /* may be NULL */
} modcp_cmsdk_cfg_t;

typedef struct {
    modcp_hal_t hal; /* hand &port->hal to modcp_cp_init() */
    const modcp_cmsdk_cfg_t *cfg;
    modcp_cp_t *cp;
    const uint8_t *tx_buf;
    uint16_t tx_len;
    uint16_t tx_pos;
    uint32_t cyc_per_us;
    uint32_t char_us;
    bool rs485;
    bool tx_active;   /* bytes still to hand over, or the last TX interrupt to come */
    bool txc_pending; /* the transmit-complete one-shot runs */
    uint32_t rx_bytes;
    uint32_t tx_bytes;
    uint32_t overruns;
    modcp_eof_t eof; /* end-of-frame handler (modcp/hal_eof.h), mark = rx_bytes + overruns */
} modcp_cmsdk_port_t;

/* End-of-frame expiries in a row without a received character before the core hears of
 * it (see modcp_cmsdk_port_timer_isr). */
#ifndef MODCP_CMSDK_EOF_QUIET_ROUNDS
#define MODCP_CMSDK_EOF_QUIET_ROUNDS 3u /* 1: report the first quiet expiry (no confirmation; experiments) */
#endif

/* Fill port->hal; no hardware is touched. */
void modcp_cmsdk_port_init(modcp_cmsdk_port_t *port, const modcp_cmsdk_cfg_t *cfg);
/* Program the UART for the record's baud rate (8N1) and start receiving for cp; the
 * transmit-complete delay is one character of the configured frame
 * (modcp_params_char_us()). The caller enables the interrupts (UART RX, TX, overflow,
 * timer, dual timer) afterwards. */
void modcp_cmsdk_port_start(modcp_cmsdk_port_t *port, modcp_cp_t *cp, const modcp_params_t *p);

/* Interrupt entry points. */
void modcp_cmsdk_port_rx_isr(modcp_cmsdk_port_t *port);
void modcp_cmsdk_port_tx_isr(modcp_cmsdk_port_t *port);
void modcp_cmsdk_port_overflow_isr(modcp_cmsdk_port_t *port);
void modcp_cmsdk_port_timer_isr(modcp_cmsdk_port_t *port);
void modcp_cmsdk_port_txc_isr(modcp_cmsdk_port_t *port);

/* ---- console UART ------------------------------------------------------------- */

typedef struct {
    uintptr_t uart;
    volatile bool tx_active;
    modcp_conq_t q; /* the shared queues (modcp/hal_conq.h) */
} modcp_cmsdk_con_t;

void modcp_cmsdk_con_init(modcp_cmsdk_con_t *con, uintptr_t uart, uint32_t pclk_hz,
                          uint32_t baud);
int modcp_cmsdk_con_getc(modcp_cmsdk_con_t *con);
void modcp_cmsdk_con_write(modcp_cmsdk_con_t *con, const char *s, size_t n);
void modcp_cmsdk_con_rx_isr(modcp_cmsdk_con_t *con);
void modcp_cmsdk_con_tx_isr(modcp_cmsdk_con_t *con);
void modcp_cmsdk_con_overflow_isr(modcp_cmsdk_con_t *con);

#endif
