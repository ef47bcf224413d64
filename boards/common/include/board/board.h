/* SPDX-License-Identifier: Apache-2.0 */
/* modcp boards — what the common application (boards/common/app.c) needs from a board.
 * A board implements these in its board.c on top of its HAL (hal/cmsdk, hal/stm32f4).
 * See docs/porting.md for the order in which to bring them up. */
#ifndef MODCP_BOARD_H
#define MODCP_BOARD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/params.h"

/* Clocks, pins, the free-running time base and the console UART. Interrupts are still
 * globally disabled when this is called; the console may be used right after it. */
void board_init(void);

/* Bring up the Modbus side for this CP with the line parameters of the record (baud,
 * data bits, parity, stop bits): UART, end-of-frame timer, transmit-complete detection,
 * RS485 DE and LEDs, and their interrupts at PRIO_CP. Returns the HAL the CP is to be
 * initialised with; modcp_cp_init() is called by the application in between
 * board_modbus_hal() and board_modbus_start(). */
const modcp_hal_t *board_modbus_hal(void);
void board_modbus_start(modcp_cp_t *cp, const modcp_params_t *line);

/* Free-running time: microseconds (wrapping at 2^32) and milliseconds since start. */
uint32_t board_now_us(void);
uint32_t board_now_ms(void);

/* Console UART: non-blocking read (-1 when nothing is there) and a write that queues
 * (and waits only when the transmit queue is full). */
int board_console_getc(void);
void board_console_write(const char *s, size_t n);

/* Human-readable name, printed at start. */
const char *board_name(void);

/* The CP task: the application's PendSV handler runs modcp_cp_poll(). The board's tick
 * (1 ms) requests it too, so job timeouts and LED times advance while the line is idle. */
void board_cp_task_request(void);

/* Provided by boards/common/app.c: the CP task body (called from PendSV). */
void app_cp_task(void);

#endif
