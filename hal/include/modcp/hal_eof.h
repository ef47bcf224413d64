/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — end-of-frame confirmation shared by the Cortex-M ports (docs/porting.md §4).
 *
 * A port reports an end-of-frame expiry to the core (modcp_cp_on_timer) only after it
 * has drained its UART and `rounds` expiries in a row found no new character: each
 * unconfirmed expiry starts a 1 us confirmation one-shot instead. In QEMU that makes the
 * end of a frame independent of host load; on silicon it costs a few microseconds. */
#ifndef MODCP_HAL_EOF_H
#define MODCP_HAL_EOF_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint32_t rx_mark;  /* characters received (+ errors) at the last arm / expiry */
    uint32_t quiet;    /* expiries in a row with nothing received */
    uint32_t confirms; /* confirmation one-shots started (statistics) */
} modcp_eof_confirm_t;

/* The core armed the end-of-frame timer; rx_mark = characters received so far. */
static inline void modcp_eof_confirm_arm(modcp_eof_confirm_t *c, uint32_t rx_mark)
{
    c->quiet = 0u;
    c->rx_mark = rx_mark;
}

/* An expiry after the UART was drained: true = report it to the core now, false = start
 * a 1 us confirmation one-shot (counted in confirms). */
static inline bool modcp_eof_confirm_expiry(modcp_eof_confirm_t *c, uint32_t rx_mark,
                                            uint32_t rounds)
{
    if (rx_mark != c->rx_mark) {
        c->rx_mark = rx_mark;
        c->quiet = 0u;
    } else {
        c->quiet++;
    }
    if (c->quiet < rounds) {
        c->confirms++;
        return false;
    }
    return true;
}

/* ---- the end-of-frame handler every port calls ----------------------------------
 *
 * A port keeps a modcp_eof_t and three small functions (modcp_eof_ops_t). Its
 * timer_arm callback calls modcp_eof_arm() before it (re)starts or stops the one-shot;
 * its one-shot interrupt, after checking and clearing the timer's flag (a stale expiry
 * is dropped there), calls modcp_eof_expired() and, when that returns true,
 * modcp_cp_on_timer(). modcp_eof_expired() drains the UART into the core first (a
 * character already received is older than this expiry); if the core re-armed the
 * timer meanwhile (a character came), that timer stands; otherwise the expiry counts as
 * quiet only when nothing was received since the last one, and an unconfirmed expiry
 * restarts the one-shot for 1 us. */
typedef struct {
    void (*drain)(void *port);                /* hand what the UART holds to the core */
    uint32_t (*rx_mark)(void *port);          /* characters + line errors received */
    void (*restart)(void *port, uint32_t us); /* start the one-shot again for us */
} modcp_eof_ops_t;

typedef struct {
    modcp_eof_confirm_t confirm;
    uint32_t gen; /* arms by the core (modcp_eof_arm) */
} modcp_eof_t;

/* The core called timer_arm (to arm, re-arm or disarm); rx_mark as in modcp_eof_ops_t. */
static inline void modcp_eof_arm(modcp_eof_t *e, uint32_t rx_mark)
{
    e->gen++;
    modcp_eof_confirm_arm(&e->confirm, rx_mark);
}

/* The one-shot expired (flag checked and cleared). true: call modcp_cp_on_timer() now. */
static inline bool modcp_eof_expired(modcp_eof_t *e, const modcp_eof_ops_t *ops, void *port,
                                     uint32_t rounds)
{
    uint32_t gen = e->gen;
    ops->drain(port);
    if (e->gen != gen) {
        return false; /* the core re-armed for a character: that timer stands */
    }
    if (!modcp_eof_confirm_expiry(&e->confirm, ops->rx_mark(port), rounds)) {
        ops->restart(port, 1u);
        return false;
    }
    return true;
}

#endif
