/* modcp — communication event log and flags (see modcp/commlog.h). */
#define MODCP_COMMLOG_C /* -Os: the out-of-line copies of commlog_internal.h */
#include "modcp/commlog.h"

#include <string.h>

#include "modcp/diag.h"
#include "commlog_internal.h"

_Static_assert(MODCP_COMM_LOG_LEN == MODCP_COMM_LOG, "comm event log length");
_Static_assert(MODCP_COMM_LOG_LEN <= 255u, "log_len is a byte");
_Static_assert((MODCP_COMM_LOG_LEN & (MODCP_COMM_LOG_LEN - 1u)) == 0u, "the log ring wraps by a mask");

void modcp_comm_clear_log(modcp_comm_t *c)
{
    memset(c->log, 0, sizeof c->log);
    c->log_len = 0;
    c->log_head = 0;
}

void modcp_comm_counted(modcp_comm_t *c, unsigned counter)
{
    if (counter == (unsigned)MODCP_CNT_CHAR_OVERRUN) {
        c->overrun_pending = true;
        c->diag_reg |= MODCP_DREG_OVERRUN;
    } else if (counter == (unsigned)MODCP_CNT_BUS_CRC) {
        modcp_comm_log(c, (uint8_t)(modcp_comm_rx_flags(c) | MODCP_COMM_RX_COMM_ERROR));
    }
}
