/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — communication event log and flags (see modcp/commlog.h). */
#include "modcp/commlog.h"

#include <string.h>

#include "modcp/diag.h"
#include "commlog_internal.h"

_Static_assert(MODCP_COMM_LOG_LEN == MODCP_COMM_LOG, "comm event log length");
_Static_assert(MODCP_COMM_LOG_LEN <= 255u, "log_len is a byte");
_Static_assert((MODCP_COMM_LOG_LEN & (MODCP_COMM_LOG_LEN - 1u)) == 0u, "the log ring wraps by a mask");

void modcp_comm_log(modcp_comm_t *c, uint8_t ev)
{
    c->log_head = (uint8_t)((c->log_head - 1u) & (MODCP_COMM_LOG_LEN - 1u));
    c->log[c->log_head] = ev;
    if (c->log_len < MODCP_COMM_LOG_LEN) {
        c->log_len++;
    }
}

/* The receive event's flags: listen-only, and a character overrun not yet reported. */
static uint8_t rx_flags(modcp_comm_t *c)
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

void modcp_comm_rx(modcp_comm_t *c, bool broadcast)
{
    modcp_comm_log(c, (uint8_t)(rx_flags(c) | (broadcast ? MODCP_COMM_RX_BROADCAST : 0u)));
}

void modcp_comm_clear_log(modcp_comm_t *c)
{
    (void)memset(c->log, 0, sizeof c->log);
    c->log_len = 0;
    c->log_head = 0;
}

void modcp_comm_clear(modcp_comm_t *c)
{
    c->event_count = 0;
    c->diag_reg = 0;
    c->overrun_pending = false;
}

void modcp_comm_clear_overrun(modcp_comm_t *c)
{
    c->diag_reg = (uint16_t)(c->diag_reg & ~MODCP_DREG_OVERRUN);
    c->overrun_pending = false;
}

void modcp_comm_restart(modcp_comm_t *c, bool clear_log)
{
    modcp_comm_clear(c);
    c->listen_only = false;
    if (clear_log) {
        modcp_comm_clear_log(c);
    }
    modcp_comm_log(c, MODCP_COMM_RESTART);
}

void modcp_comm_listen(modcp_comm_t *c, bool on)
{
    c->listen_only = on;
    if (on) {
        modcp_comm_log(c, MODCP_COMM_LISTEN_ENTERED);
    }
}

void modcp_comm_counted(modcp_comm_t *c, unsigned counter)
{
    if (counter == (unsigned)MODCP_CNT_CHAR_OVERRUN) {
        c->overrun_pending = true;
        c->diag_reg |= MODCP_DREG_OVERRUN;
    } else if (counter == (unsigned)MODCP_CNT_BUS_CRC) {
        modcp_comm_log(c, (uint8_t)(rx_flags(c) | MODCP_COMM_RX_COMM_ERROR));
    } else {
        /* other counters leave no event byte */
    }
}
