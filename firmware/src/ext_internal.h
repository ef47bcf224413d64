/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of ext.c (modcp/ext.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_EXT_INTERNAL_H
#define MODCP_EXT_INTERNAL_H

#include "modcp/ext.h"

void modcp_ext_init(modcp_ext_t *x);
/* New parameters: supervision disarmed, delimiter LF, listen-only left. */
void modcp_ext_reset(modcp_ext_t *x, modcp_diag_t *d);
/* FC08 sub 03 / sub 01: the ASCII end-of-frame character, for the frames after this
 * request; modcp_ext_take_delimiter hands a change to the CP once (true: changed). */
void modcp_ext_set_delimiter(modcp_ext_t *x, uint8_t ch);
static inline bool modcp_ext_take_delimiter(modcp_ext_t *x, uint8_t *ch)
{
    if (!x->delimiter_changed) {
        return false; /* (every request: inline) */
    }
    *ch = x->ascii_delimiter;
    x->delimiter_changed = false;
    return true;
}
/* A request's CPU jobs ended: one timed out (timed_out), or it had a job and no
 * exception (ok): the FC17 run indicator / diagnostic register bit 2 (cpu_stalled;
 * every request: inline). */
static inline void modcp_ext_job_result(modcp_ext_t *x, bool timed_out, bool ok)
{
    if (timed_out) {
        x->cpu_stalled = true;
    } else if (ok) {
        x->cpu_stalled = false;
    } else {
        /* refused by the CPU side, or no job: the state stays */
    }
}
/* FC08 sub 01 / 0A effects (also used by tests). */
void modcp_ext_restart(modcp_ext_t *x, modcp_diag_t *d, bool clear_log);
void modcp_ext_clear_counters(modcp_diag_t *d);
/* Diagnostic register (FC08 sub 02): latched bits plus the live ones. */
uint16_t modcp_ext_diag_register(const modcp_ext_t *x, const modcp_diag_t *d);
/* A valid request for our address (not broadcast) arrived: restart the time; clear the
 * comm-loss state when it is not latched (params.commloss_auto). */
static inline void modcp_commloss_request(modcp_ext_t *x, const modcp_params_t *p,
                                          uint32_t now_us)
{
    x->cl_last_us = now_us;
    if (p->commloss_auto != 0u) {
        x->cl_lost = false;
    }
}
/* An accepted (executed, no exception) write for our address: arms the supervision. */
static inline void modcp_commloss_write(modcp_ext_t *x, const modcp_params_t *p,
                                        uint32_t now_us)
{
    if (p->commloss_ms == 0u || x->cl_armed) {
        return;
    }
    x->cl_armed = true;
    x->cl_lost = false;
    x->cl_last_us = now_us;
}
/* Expiry check (the CP's poll): reports MODCP_EV_COMMLOSS once per loss; reset: the
 * backplane's commloss_reset count (a change clears a latched loss). The state is
 * x->cl_lost alone; the CP publishes MODCP_CPST_COMMLOSS from it. */
void modcp_commloss_poll(modcp_ext_t *x, const modcp_params_t *p, modcp_diag_t *d,
                         uint32_t reset, uint32_t now_us);
/* True when the scanner is on (function set extended, scan_count > 0) and the register
 * range [reg, reg + qty) touches it (qty 0: never). */
bool modcp_scan_touches(const modcp_params_t *p, uint16_t reg, uint16_t qty);
/* Operand of scanner register reg for a read or a write (area NONE: unused entry,
 * reads give 0000, writes are discarded). Events: (0E)51H reg outside the scanner,
 * (0E)54H operand beyond the controller area, writes: (0E)55H to I, T, C,
 * (0E)52H outside the M / Q / DB write limits or to the FB's work DB. */
modcp_event_t modcp_scan_map(const modcp_params_t *p, const modcp_areas_t *a, uint16_t reg,
                             bool write, modcp_operand_t *out);
/* Check a whole range before anything is executed: it must lie inside the scanner
 * ((0E)54H when it runs past either end), not consist of unused entries only
 * ((0E)51H), and every used entry must map (modcp_scan_map). */
modcp_event_t modcp_scan_check(const modcp_params_t *p, const modcp_areas_t *a, uint16_t reg,
                               uint16_t qty, bool write);

#endif
