/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — stage time stamps of every reply, for latency analysis
 * (tests/bench/sim_latency.py --stages).
 *
 * With MODCP_SIM_LATLOG=FILE in the environment, the CP thread of a simulator with one
 * slave (a member of the simulated line, or on --device) writes one line per reply to FILE (created anew at the start), when the reply's first byte has been
 * written to the line:
 *
 *   seq rx timer_due timer_seen job fb_due fb_start fb_end take tx_t0 first_due first
 *
 * all CLOCK_MONOTONIC microseconds (low 32 bits, like modcp_posix_now_us()):
 *   rx          the CP thread took the request's last characters (on --device: read)
 *   timer_due   the one-shot timer's deadline that ended the frame (t3.5)
 *   timer_seen  the CP thread saw it expire
 *   job         the request was on the backplane (after modcp_cp_on_timer)
 *   fb_due      the CPU cycle's nominal start of the FB call that answered
 *   fb_start    that FB call began; fb_end it returned (the reply put)
 *   take        the CP thread woke and took the reply (modcp_cp_poll -> uart_tx)
 *   tx_t0       the time the reply was handed to the UART (the core's now)
 *   first_due   tx_t0 + one character time: when the first byte is due on the line
 *   first       the first byte was written to the member's pty (the line hands it to
 *               the master's pty at the same due time)
 * Without the variable nothing is recorded (one branch per wait). */
#ifndef MODCP_SIM_LATLOG_H
#define MODCP_SIM_LATLOG_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "modcp/cp.h"
#include "modcp/hal_posix.h"

typedef struct {
    FILE *f; /* NULL: off */
    uint32_t seq;
    /* CP thread */
    bool pending, timer_armed, first_pending;
    uint32_t timer_deadline, tx_t0;
    uint32_t rx, timer_due, timer_seen, job, take;
    /* CPU thread: the FB call that moved blocks last */
    atomic_uint fb_due, fb_start, fb_end;
} sim_latlog_t;

/* Open from MODCP_SIM_LATLOG (nothing when unset). */
void sim_latlog_open(sim_latlog_t *l);
void sim_latlog_close(sim_latlog_t *l);

/* CP thread, before modcp_posix_wait. */
void sim_latlog_before_wait(sim_latlog_t *l, const modcp_posix_port_t *p);
/* CP thread, after modcp_posix_wait returned n characters, timer_fired, at now. */
void sim_latlog_after_wait(sim_latlog_t *l, const modcp_posix_port_t *p, int n, bool timer_fired,
                           uint32_t now);
/* CP thread: n characters taken from the line (a bus member) at now. */
void sim_latlog_rx(sim_latlog_t *l, size_t n, uint32_t now);
/* CP thread, after the core was fed (on_timer / on_rx / poll) at now. */
void sim_latlog_after_core(sim_latlog_t *l, const modcp_cp_t *cp, const modcp_posix_port_t *p,
                           uint32_t now);
/* CPU thread: an FB call due at due (64-bit us) ran from start to end and moved blocks. */
void sim_latlog_fb(sim_latlog_t *l, uint64_t due, uint32_t start, uint32_t end);

#endif
