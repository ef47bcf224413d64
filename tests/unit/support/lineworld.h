/* SPDX-License-Identifier: Apache-2.0 */
/* Test helper: a world (world.h: CP + FB + memory) on a simulated serial line with
 * exact time. A tiny discrete-event loop delivers, in time order:
 *   - the one-shot timer the core arms (modcp_cp_on_timer at exactly armed + us),
 *   - transmission complete of the fake UART (len x character time after uart_tx),
 *   - FB cycles + modcp_cp_poll every 1 ms (when `cycles` is on).
 * Every HAL call is logged with the simulated time at which it happened. */
#ifndef MODCP_TEST_LINEWORLD_H
#define MODCP_TEST_LINEWORLD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal.h"
#include "world.h"

enum { LW_TX = 1, LW_ARM, LW_DE, LW_LED, LW_SIG, LW_ABORT, LW_TXDONE };

typedef struct {
    uint8_t kind;
    uint32_t value; /* TX: length; ARM: us; DE: on; LED: led << 1 | on; SIG: sig << 1 | on */
    uint32_t at;
} lw_ev_t;

#define LW_LOG_MAX 4096

typedef struct {
    world_t *w;
    lw_ev_t log[LW_LOG_MAX];
    size_t n;
    bool timer_on;
    uint32_t timer_at;
    bool tx_busy;
    uint32_t tx_end;
    bool auto_tx_done; /* report transmission complete (default true) */
    uint32_t char_us;  /* character time of the line */
    bool cycles;       /* FB cycles + CP polls every 1 ms (default true) */
    uint32_t next_cycle;
    bool de;
    bool led[3];
    bool sig[2];
    unsigned tx_calls;
    uint8_t tx[700];
    uint16_t tx_len;
} lw_t;

/* New world with params p (NULL: the [RTU-2003] §9 example set), HAL hooked, FB started. */
lw_t *lw_new(const modcp_params_t *p);
/* The same without starting the FB (hooks installed, time at the world's origin). */
lw_t *lw_new_unstarted(const modcp_params_t *p);
void lw_free(lw_t *x);
uint32_t lw_now(const lw_t *x);
/* Run every event due up to and including t, then stand at t. */
void lw_advance(lw_t *x, uint32_t t);
/* Line input at the current time. */
void lw_byte(lw_t *x, uint8_t b);
void lw_error(lw_t *x, uint8_t flags);
void lw_signals(lw_t *x, bool cts, bool dsr);
/* Feed the bytes of hex one character time apart, the first at the current time
 * (events due in between run first); returns the time of the last byte. */
uint32_t lw_send(lw_t *x, const char *hex);
/* The same with `gap_us` extra silence before byte number gap_before (0: none). */
uint32_t lw_send_gap(lw_t *x, const char *hex, size_t gap_before, uint32_t gap_us);
/* modcp_cp_poll at the current time (no FB cycle). */
void lw_poll(lw_t *x);
/* Fire the timer now whatever it was armed for (an early / spurious expiry). */
void lw_fire_now(lw_t *x);

/* Log queries. value_mask: compare value only if >= 0. */
size_t lw_count(const lw_t *x, uint8_t kind);
const lw_ev_t *lw_last(const lw_t *x, uint8_t kind);
/* First entry of kind with value at or after index from; -1 if none. */
long lw_find(const lw_t *x, uint8_t kind, long value, size_t from);
void lw_clear(lw_t *x);
/* The last transmission as "05 08 ..." (static buffer). */
const char *lw_tx_hex(const lw_t *x);
/* Status area as the CPU side reads it. */
modcp_cp_status_t lw_status(const lw_t *x);

#endif
