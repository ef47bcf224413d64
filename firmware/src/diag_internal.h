/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of diag.c (modcp/diag.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_DIAG_INTERNAL_H
#define MODCP_DIAG_INTERNAL_H

#include "modcp/diag.h"

void modcp_diag_init(modcp_diag_t *d);
/* Record an event (NONE is ignored). */
void modcp_diag_event(modcp_diag_t *d, modcp_event_t ev);
/* Increment a serial-line counter. Bus and slave message counts (0B, 0E) wrap
 * 65535 -> 0, the error counts saturate at 65535 ([ALTIVAR] §8: frame counters modulo
 * 65536, error counters saturating). */
void modcp_diag_count_error(modcp_diag_t *d, modcp_counter_t c);
static inline void modcp_diag_count(modcp_diag_t *d, modcp_counter_t c)
{
    if (c == MODCP_CNT_BUS_MSG || c == MODCP_CNT_SLAVE_MSG) {
        d->counters[c]++; /* uint16_t: wraps 65535 -> 0; no FC12 log entry of its own */
    } else {
        modcp_diag_count_error(d, c); /* the others saturate (diag.c) */
    }
}
/* The serial-line counters and, with the extended set, FC11's event counter and the
 * diagnostic register (FC08 sub 0A). */
void modcp_diag_clear_counters(modcp_diag_t *d);
#if MODCP_WITH_EXTENDED
/* FC08 sub 14: the character overrun counter and the overrun bit. */
void modcp_diag_clear_overrun(modcp_diag_t *d);
#endif
/* Empty the diagnostic buffer ([VIPA-341] §8.3: re-parameterisation of the CP clears it). */
void modcp_diag_clear_buffer(modcp_diag_t *d);
/* SYSTAT image (16 bytes as [RTU-2003] §7.4: state, 0, flags, 0, 6 event words high byte
 * first); clears the SYSTAT events and flags. run: CP state RUN (else fault). */
void modcp_diag_read_systat(modcp_diag_t *d, bool run, uint8_t out[16]);

#endif
