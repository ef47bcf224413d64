/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of signals.c (modcp/signals.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_SIGNALS_INTERNAL_H
#define MODCP_SIGNALS_INTERNAL_H

#include "modcp/signals.h"

/* Power-on: RTS and DTR OFF. diag: where events are reported, never NULL. */
void modcp_sig_init(modcp_sig_t *s, const modcp_hal_t *hal, modcp_diag_t *diag);
/* Apply parameters (after modcp_link_configure): automatic -> DTR ON, RTS OFF. */
void modcp_sig_configure(modcp_sig_t *s, const modcp_params_t *p);
/* CP not ready: RTS and DTR OFF, nothing in progress. */
void modcp_sig_disable(modcp_sig_t *s);
/* May a received character / line error go to the link (DSR ON or not automatic)? */
bool modcp_sig_rx_allowed(const modcp_sig_t *s);
/* After modcp_link_reply(): a reply held in TURNAROUND starts RTS / the waiting time. */
void modcp_sig_on_reply(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us);
/* Timer expiry: true when it was ours (the link must not see it). */
bool modcp_sig_on_timer(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us);
/* Transmission complete: true when handled here (automatic mode); the link then gets
 * its modcp_link_on_tx_done() when RTS goes OFF. */
bool modcp_sig_on_tx_done(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us);
/* A received character or line error: ends the time to RTS off early (see signals.c). */
void modcp_sig_on_rx(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us);
/* The port reports CTS / DSR (at start and on every change). */
void modcp_sig_on_inputs(modcp_sig_t *s, modcp_link_t *l, bool cts, bool dsr, uint32_t now_us);
/* SF's part ([ASCII-32] §10.1 "CTS/DSR not asserted"): automatic signals with DSR OFF, or CTS
 * not ON when a reply needed it (until CTS is ON again). */
static inline bool modcp_sig_fault(const modcp_sig_t *s)
{
    return s->enabled && (!s->dsr || s->cts_missing);
}
/* Signal levels as a bit set for the status area: MODCP_SIGBIT_*. */
uint8_t modcp_sig_bits(const modcp_sig_t *s);

#endif
