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

#endif
