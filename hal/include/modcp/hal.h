/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the hardware abstraction the core sees. A port implements these callbacks
 * (one struct, one context pointer) and feeds the core's event functions from its
 * interrupts: modcp_cp_on_rx(), modcp_cp_on_line_error(), modcp_cp_on_timer(),
 * modcp_cp_on_tx_done(), modcp_cp_on_signals() (RS232 CTS / DSR) and modcp_cp_poll()
 * (see modcp/cp.h). Time is always passed
 * in by the port (microseconds, free-running, wrapping at 2^32). */
#ifndef MODCP_HAL_H
#define MODCP_HAL_H

#include <stdbool.h>
#include <stdint.h>

/* Contracts every port keeps (the ports in hal/ agree; tests/unit/test_hal_contract.c
 * checks the core's side):
 *   - uart_tx is never called with len == 0: a frame without a reply calls nothing.
 *     (A port may still accept 0 and complete it from an interrupt, never from inside
 *     uart_tx.)
 *   - CTS / DSR: with automatic secondary signals (params.rs232_auto) the core takes
 *     both as OFF until the port's first modcp_cp_on_signals() — it receives nothing
 *     while DSR is OFF. So every port reports them once at start (before or after the
 *     parameters arrive: the core keeps the last report), and on every change; a UART
 *     without modem inputs reports CTS = DSR = ON. With rs232_auto off the core
 *     ignores them: the report is harmless and not needed.
 *   - Line errors: a character received with a parity / framing error or as a BREAK is
 *     reported with modcp_cp_on_line_error() in its place, not with modcp_cp_on_rx().
 *     A character lost to an overrun is reported as MODCP_LINE_OVERRUN in its place,
 *     and every good character the UART still delivers is given with modcp_cp_on_rx()
 *     in its order: a UART that keeps the older character and loses the new one (STM32
 *     ORE, nRF51 ERRORSRC.OVERRUN, CMSDK RX overflow) delivers the held character, then
 *     reports OVERRUN; a UART that flags the first character after the loss (PL011 OE
 *     in DR) reports OVERRUN, then delivers that character. One event per character
 *     on the line keeps the core's timing and frame length right. */

/* Line errors reported with a received character (or alone for BREAK): bits of an
 * unsigned mask (macros, not an anonymous enum: MISRA rules 5.7 and 10.4, docs/misra.md). */
#define MODCP_LINE_PARITY 0x01u
#define MODCP_LINE_FRAMING 0x02u
#define MODCP_LINE_OVERRUN 0x04u
#define MODCP_LINE_BREAK 0x08u

typedef enum { MODCP_LED_SF = 0, MODCP_LED_TXD = 1, MODCP_LED_RXD = 2 } modcp_led_t;

typedef enum { MODCP_SIG_RTS = 0, MODCP_SIG_DTR = 1 } modcp_signal_t;

/* Receive-line preset of the X27 (RS422 / RS485) interface ([RTU-2009] Table 5-8, [RTU-2003] §2.3). */
typedef enum {
    MODCP_RXP_DEFAULT = 0, /* by interface ([RTU-2009] Table 5-8): RS422 BREAK, RS485 HIGH */
    MODCP_RXP_NONE = 1,    /* no bias: the partner provides it */
    MODCP_RXP_BREAK = 2,   /* R(A) 5 V / R(B) 0 V: a broken line is a BREAK level (RS422) */
    MODCP_RXP_HIGH = 3,    /* R(A) 0 V / R(B) 5 V: a broken line is idle, BREAK not seen */
} modcp_rx_preset_t;
/* (the parameter's MODCP_RXP_DEFAULT is resolved by the CP: set_rx_preset never gets it) */

typedef struct modcp_hal {
    void *ctx;
    /* Start sending len bytes. buf stays valid and unchanged until the port calls
     * modcp_cp_on_tx_done(), which it must do when the last stop bit has left the
     * shift register (transmission complete), not when the data register empties.
     * Never called with len == 0 (see the contracts above). Required: must not be
     * NULL (the core calls it without a check). */
    void (*uart_tx)(void *ctx, const uint8_t *buf, uint16_t len);
    /* Arm the one-shot timer to call modcp_cp_on_timer() after `us` microseconds,
     * replacing any armed one; us == 0 disarms. Required: must not be NULL (the core
     * calls it without a check). */
    void (*timer_arm)(void *ctx, uint32_t us);
    /* RS485 driver enable (DE). May be NULL (RS232 / RS422). */
    void (*set_de)(void *ctx, bool on);
    /* LEDs SF / TXD / RXD. May be NULL. */
    void (*set_led)(void *ctx, modcp_led_t led, bool on);
    /* RS232 output signals RTS / DTR. May be NULL. With automatic secondary signals
     * (params.rs232_auto) the port also reports the inputs CTS and DSR with
     * modcp_cp_on_signals() at start and on every change. */
    void (*set_signal)(void *ctx, modcp_signal_t sig, bool on);
    /* Stop the transmission started by uart_tx at once (RS232 automatic signals: CTS or
     * DSR went OFF while sending). The port must not call modcp_cp_on_tx_done() for
     * the aborted transmission. May be NULL: the UART then finishes the frame and its
     * late transmission-complete is ignored. */
    void (*uart_tx_abort)(void *ctx);
    /* Receive-line preset of RS422 / RS485 ([RTU-2009] Table 5-8, [RTU-2003] §2.3), set with every
     * valid parameter set: preset is MODCP_RXP_NONE (no bias), MODCP_RXP_BREAK (R(A) 5 V /
     * R(B) 0 V: a broken line shows as BREAK) or MODCP_RXP_HIGH (R(A) 0 V / R(B) 5 V: a
     * broken line looks idle, so the port never sees a BREAK). May be
     * NULL (a fixed bias, or RS232). */
    void (*set_rx_preset)(void *ctx, uint8_t preset);
} modcp_hal_t;

#endif
