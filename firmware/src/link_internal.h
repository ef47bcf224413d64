/* modcp — helpers shared by the link layer and its framings (link.c, rtu.c, ascii.c).
 * Internal to the core: not part of the public API. */
#ifndef MODCP_LINK_INTERNAL_H
#define MODCP_LINK_INTERNAL_H

#include "modcp/link.h"

/* Arm the one-shot timer (0 disarms). */
static inline void link_arm(const modcp_link_t *l, uint32_t us)
{
    if (l->hal != NULL && l->hal->timer_arm != NULL) {
        l->hal->timer_arm(l->hal->ctx, us);
    }
}

static inline void link_event(const modcp_link_t *l, modcp_event_t ev)
{
    if (l->diag != NULL) {
        modcp_diag_event(l->diag, ev);
    }
}

static inline void link_count(const modcp_link_t *l, modcp_counter_t c)
{
    if (l->diag != NULL) {
        modcp_diag_count(l->diag, c);
    }
}

/* The current frame is damaged (character error, BREAK, t1.5, bad character): it is
 * discarded and, once per frame, counted as a bus communication error (Serial Line
 * V1.02 §6.1 counter 2: "in case of an error detected on the character level ... this
 * counter is also incremented"). */
static inline void link_mark_bad(modcp_link_t *l)
{
    if (!l->rx_bad) {
        l->rx_bad = true;
        link_count(l, MODCP_CNT_BUS_CRC);
    }
}

#endif
