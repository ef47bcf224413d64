/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — wire break, diagnostic interrupt, SYSTAT service (see modcp/cpdiag.h). */
#include "modcp/cpdiag.h"

#include <string.h>

#include "modcp/hal.h"
#include "backplane_internal.h"
#include "cpdiag_internal.h"
#include "diag_internal.h"
#include "job_internal.h"

#define MODULE_CLASS_CP 0x0Cu

static void irq(modcp_cpdiag_t *d, uint8_t b0, uint8_t b2)
{
    if (!d->irq_enabled) {
        return;
    }
    d->irq[0] = b0;
    d->irq[1] = MODULE_CLASS_CP;
    d->irq[2] = b2;
    d->irq[3] = 0x00u;
    d->irq_count++;
}

void modcp_cpdiag_init(modcp_cpdiag_t *d)
{
    (void)memset(d, 0, sizeof *d);
}

void modcp_cpdiag_line_error(modcp_cpdiag_t *d, uint8_t line_errors, bool reported)
{
    if (!reported || (line_errors & MODCP_LINE_BREAK) == 0u || d->wire_break) {
        return;
    }
    d->wire_break = true;
    irq(d, 0x25u, 0x02u); /* [VIPA-341] §8.4: wire break on RxD */
}

void modcp_cpdiag_good_char(modcp_cpdiag_t *d)
{
    if (!d->wire_break) {
        return;
    }
    d->wire_break = false;
    irq(d, 0x00u, 0x00u); /* going */
}

void modcp_cpdiag_params(modcp_cpdiag_t *d, bool ok, int irq_setting)
{
    if (irq_setting >= 0) {
        d->irq_enabled = irq_setting != 0;
    }
    bool was_fault = d->param_error || d->wire_break;
    d->wire_break = false; /* the link starts afresh */
    if (!ok) {
        if (!d->param_error) {
            d->param_error = true;
            irq(d, 0x83u, 0x00u); /* [VIPA-341] §8.4: parameterisation error */
        }
        return;
    }
    d->param_error = false;
    if (was_fault) {
        irq(d, 0x00u, 0x00u); /* going */
    }
}

void modcp_cpdiag_systat(modcp_cpdiag_t *d, modcp_diag_t *diag, modcp_backplane_t *bp,
                         uint32_t req, bool run)
{
    modcp_cp_status_t *st = modcp_bp_status_begin(bp); /* the CP is its only writer */
    modcp_diag_read_systat(diag, run, st->systat);
    modcp_bp_status_end(bp);
    d->systat_ack = req;
}

void modcp_cpdiag_backplane(modcp_diag_t *diag, unsigned errors)
{
    if ((errors & MODCP_JOB_ERR_ILLEGAL) != 0u) {
        modcp_diag_event(diag, MODCP_EV_ILLEGAL_JOB);
    }
    if ((errors & MODCP_JOB_ERR_PROTO) != 0u) {
        modcp_diag_event(diag, MODCP_EV_XFER_ACK);
    }
}
