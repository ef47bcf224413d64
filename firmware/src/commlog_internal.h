/* modcp — the core's internal interface of commlog.c (modcp/commlog.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_COMMLOG_INTERNAL_H
#define MODCP_COMMLOG_INTERNAL_H

#include "modcp/commlog.h"

/* The log, the receive event: inline on the request path when built for speed; built
 * for size (-Os, the MCU builds) one out-of-line copy each, in commlog.c (which defines
 * MODCP_COMMLOG_C), as the calls are fewer bytes than the bodies at five call sites. */
#if defined(__OPTIMIZE_SIZE__) && !defined(MODCP_COMMLOG_C)
void modcp_comm_log(modcp_comm_t *c, uint8_t ev);
uint8_t modcp_comm_rx_flags(modcp_comm_t *c);
void modcp_comm_rx(modcp_comm_t *c, bool broadcast);
#else
#if defined(__OPTIMIZE_SIZE__)
#define MODCP_COMM_FN /* commlog.c: the out-of-line copies */
uint8_t modcp_comm_rx_flags(modcp_comm_t *c);
void modcp_comm_log(modcp_comm_t *c, uint8_t ev);
void modcp_comm_rx(modcp_comm_t *c, bool broadcast);
#else
#define MODCP_COMM_FN static inline
#endif
/* Add an event byte (newest first; the oldest falls out beyond 64): a ring, one store,
 * nothing moves. */
MODCP_COMM_FN void modcp_comm_log(modcp_comm_t *c, uint8_t ev)
{
    c->log_head = (uint8_t)((c->log_head - 1u) & (MODCP_COMM_LOG_LEN - 1u));
    c->log[c->log_head] = ev;
    if (c->log_len < MODCP_COMM_LOG_LEN) {
        c->log_len++;
    }
}
/* The receive event's flags: listen-only, and a character overrun not yet reported. */
MODCP_COMM_FN uint8_t modcp_comm_rx_flags(modcp_comm_t *c)
{
    uint8_t ev = MODCP_COMM_RX;
    if (c->listen_only) {
        ev |= MODCP_COMM_RX_LISTEN;
    }
    if (c->overrun_pending) {
        ev |= MODCP_COMM_RX_OVERRUN;
        c->overrun_pending = false;
    }
    return ev;
}
/* Log the receive event of a valid frame for us (broadcast: addr 0). */
MODCP_COMM_FN void modcp_comm_rx(modcp_comm_t *c, bool broadcast)
{
    modcp_comm_log(c, (uint8_t)(modcp_comm_rx_flags(c) | (broadcast ? MODCP_COMM_RX_BROADCAST : 0u)));
}
#undef MODCP_COMM_FN
#endif
void modcp_comm_clear_log(modcp_comm_t *c);
/* The i-th event byte of the log, newest first (i < log_len). */
static inline uint8_t modcp_comm_log_at(const modcp_comm_t *c, unsigned i)
{
    return c->log[(c->log_head + i) & (MODCP_COMM_LOG_LEN - 1u)];
}
/* A serial-line counter (modcp_counter_t) was incremented: keeps the overrun flag and
 * logs the 0x82 receive event of a damaged frame. Called by modcp_diag_count(). */
void modcp_comm_counted(modcp_comm_t *c, unsigned counter);

#endif
