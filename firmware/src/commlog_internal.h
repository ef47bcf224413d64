/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of commlog.c (modcp/commlog.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_COMMLOG_INTERNAL_H
#define MODCP_COMMLOG_INTERNAL_H

#include "modcp/commlog.h"

/* Add an event byte (newest first; the oldest falls out beyond 64): a ring, one store,
 * nothing moves. */
void modcp_comm_log(modcp_comm_t *c, uint8_t ev);
/* Log the receive event of a valid frame for us (broadcast: addr 0). */
void modcp_comm_rx(modcp_comm_t *c, bool broadcast);
void modcp_comm_clear_log(modcp_comm_t *c);
/* A request completed successfully (FC11's event counter; every request: inline). */
static inline void modcp_comm_completed(modcp_comm_t *c)
{
    c->event_count++; /* wraps 65535 -> 0 */
}
/* FC08 sub 0A: event counter, diagnostic register and the pending overrun cleared. */
void modcp_comm_clear(modcp_comm_t *c);
/* FC08 sub 14: the overrun bit of the diagnostic register and the pending overrun. */
void modcp_comm_clear_overrun(modcp_comm_t *c);
/* FC08 sub 01: modcp_comm_clear, listen-only left, the log emptied (clear_log) and the
 * restart event logged. */
void modcp_comm_restart(modcp_comm_t *c, bool clear_log);
/* Listen-only mode on (FC08 sub 04: logged) or off (new parameters). */
void modcp_comm_listen(modcp_comm_t *c, bool on);
/* The i-th event byte of the log, newest first (i < log_len). */
static inline uint8_t modcp_comm_log_at(const modcp_comm_t *c, unsigned i)
{
    return c->log[(c->log_head + i) & (MODCP_COMM_LOG_LEN - 1u)];
}
/* A serial-line counter (modcp_counter_t) was incremented: keeps the overrun flag and
 * logs the 0x82 receive event of a damaged frame. Called by modcp_diag_count(). */
void modcp_comm_counted(modcp_comm_t *c, unsigned counter);

#endif
