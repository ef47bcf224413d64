/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — comm-loss supervision (docs/parameters.md, §5.3; [ALTIVAR] §7) and the persistent state of
 * the extended set.
 *
 * params.commloss_ms = 0: off; 100 ... 30000 ms: the supervision is armed by the
 * first accepted write (FC05, 06, 15, 16, 22, 23 executed without exception) for our
 * own address since start-up / new parameters ([ALTIVAR] §7: "at least one command or
 * setpoint parameter written a first time"). Once armed, every valid request for our
 * address (CRC good, addressed to us, not broadcast; answered normally, with an
 * exception, or not at all in listen-only mode) restarts the time. When the time runs
 * out: event (0E)60H once and MODCP_CPST_COMMLOSS in the backplane status area,
 * which the CPU side's user program reads with modcp_bp_read_status(). The flag stays
 * latched, as the Altivar's resettable fault SLF1 ([ALTIVAR] §7), until the CPU side resets it
 * (modcp_bp_commloss_reset, seen at the CP's next poll; the time then starts afresh) or
 * new parameters arrive; with params.commloss_auto the next valid request for our
 * address clears it instead. The supervision stays armed either way.
 * Like the Altivar ([ALTIVAR] §7 pitfall), any request keeps it alive, also reads.
 * The comm-loss state is x->cl_lost and nowhere else: cp.c publishes
 * MODCP_CPST_COMMLOSS from it, the console reads that flag of the status area. */
#include <stddef.h>

#include "modcp/ext.h"
#include "commlog_internal.h"
#include "diag_internal.h"
#include "ext_internal.h"

void modcp_ext_init(modcp_ext_t *x)
{
    x->cl_armed = false;
    x->cl_lost = false;
    x->cl_last_us = 0u;
    x->ascii_delimiter = MODCP_ASCII_DELIMITER_DEFAULT;
    x->delimiter_changed = false;
    x->cpu_stalled = false;
}

void modcp_ext_reset(modcp_ext_t *x, modcp_diag_t *d)
{
    modcp_ext_init(x);
    if (d != NULL) {
        modcp_comm_listen(&d->comm, false);
    }
}

void modcp_ext_set_delimiter(modcp_ext_t *x, uint8_t ch)
{
    x->ascii_delimiter = ch;
    x->delimiter_changed = true;
}



void modcp_commloss_poll(modcp_ext_t *x, const modcp_params_t *p, modcp_diag_t *d,
                         uint32_t reset, uint32_t now_us)
{
    if (reset != x->cl_reset_seen) { /* the CPU side reset it (modcp_bp_commloss_reset) */
        x->cl_reset_seen = reset;
        if (x->cl_lost) {
            x->cl_lost = false;
            x->cl_last_us = now_us;
        }
    }
    if (p->commloss_ms == 0u) {
        x->cl_armed = false;
        x->cl_lost = false;
        return;
    }
    if (!x->cl_armed || x->cl_lost) {
        return;
    }
    if ((uint32_t)(now_us - x->cl_last_us) >= (uint32_t)p->commloss_ms * 1000u) {
        x->cl_lost = true;
        modcp_diag_event(d, MODCP_EV_COMMLOSS);
    }
}
