/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP's view of the RS232 automatic secondary signals (signals.c), or of none
 * in a build without them (MODCP_WITH_RS232_SIGNALS 0). Included by cp.c only. */
#ifndef MODCP_CP_SIGNALS_INTERNAL_H
#define MODCP_CP_SIGNALS_INTERNAL_H

#include "modcp/cp.h"
#include "signals_internal.h"

/* ---- RS232 automatic secondary signals (signals.c), or none in this build ------ */

#if MODCP_WITH_RS232_SIGNALS
static inline bool sig_enabled(const modcp_cp_t *cp)
{
    return cp->sig.enabled;
}
static inline bool sig_rx_allowed(const modcp_cp_t *cp)
{
    return modcp_sig_rx_allowed(&cp->sig);
}
static inline void sig_on_rx(modcp_cp_t *cp, uint32_t now_us)
{
    modcp_sig_on_rx(&cp->sig, &cp->link, now_us);
}
/* Disabled signals are idle (modcp_sig_configure / _disable): no timer of their own,
 * transmission complete goes to the link; so the calls are skipped then. */
static inline bool sig_on_timer(modcp_cp_t *cp, uint32_t now_us)
{
    return cp->sig.enabled && modcp_sig_on_timer(&cp->sig, &cp->link, now_us);
}
static inline bool sig_on_tx_done(modcp_cp_t *cp, uint32_t now_us)
{
    return cp->sig.enabled && modcp_sig_on_tx_done(&cp->sig, &cp->link, now_us);
}
#else
/* Built without RS232 signals: reception always allowed, no timer or transmit
 * complete of their own, RTS / DTR never driven (rs232_auto is refused, params.c). */
static inline bool sig_enabled(const modcp_cp_t *cp)
{
    (void)cp;
    return false;
}
static inline bool sig_rx_allowed(const modcp_cp_t *cp)
{
    (void)cp;
    return true;
}
static inline void sig_on_rx(modcp_cp_t *cp, uint32_t now_us)
{
    (void)cp;
    (void)now_us;
}
static inline bool sig_on_timer(modcp_cp_t *cp, uint32_t now_us)
{
    (void)cp;
    (void)now_us;
    return false;
}
static inline bool sig_on_tx_done(modcp_cp_t *cp, uint32_t now_us)
{
    (void)cp;
    (void)now_us;
    return false;
}
#endif

#endif
