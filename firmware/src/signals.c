/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RS232 automatic secondary signals (see modcp/signals.h). */
#include "modcp/signals.h"

#include <stddef.h>
#include <string.h>
#include "diag_internal.h"
#include "link_internal.h"
#include "signals_internal.h"

static void out(modcp_sig_t *s, modcp_signal_t sig, bool on)
{
    bool *cur = sig == MODCP_SIG_RTS ? &s->rts : &s->dtr;
    if (*cur == on) {
        return;
    }
    *cur = on;
    if (s->hal->set_signal != NULL) {
        s->hal->set_signal(s->hal->ctx, sig, on);
    }
}

static void arm(const modcp_sig_t *s, uint32_t us)
{
    s->hal->timer_arm(s->hal->ctx, us); /* never NULL (modcp/hal.h) */
}

static void event(modcp_sig_t *s, modcp_event_t ev)
{
    modcp_diag_event(s->diag, ev); /* never NULL (modcp_sig_init) */
}

static MODCP_SIZE_NOINLINE void count_abort(modcp_sig_t *s)
{
    if (s->aborts < UINT16_MAX) {
        s->aborts++;
    }
}

/* Nothing in progress: RTS OFF, DTR ON in automatic mode, else OFF. */
static void reset(modcp_sig_t *s)
{
    s->state = MODCP_SIGST_IDLE;
    s->cts_missing = false;
    out(s, MODCP_SIG_RTS, false);
    out(s, MODCP_SIG_DTR, s->enabled);
}

void modcp_sig_init(modcp_sig_t *s, const modcp_hal_t *hal, modcp_diag_t *diag)
{
    (void)memset(s, 0, sizeof *s);
    s->hal = hal;
    s->diag = diag;
    /* power-on: outputs OFF (set explicitly, whatever the pins did before) */
    s->rts = true;
    s->dtr = true;
    reset(s); /* not enabled: both OFF */
}

void modcp_sig_disable(modcp_sig_t *s)
{
    s->enabled = false;
    reset(s);
}

void modcp_sig_configure(modcp_sig_t *s, const modcp_params_t *p)
{
    s->enabled = p->rs232_auto != 0u && p->iface == (uint8_t)MODCP_IFACE_RS232;
    s->on_delay_us = (uint32_t)p->rts_on_delay_ms * 1000u;
    s->off_delay_us = (uint32_t)p->rts_off_delay_ms * 1000u;
    reset(s);
}

bool modcp_sig_rx_allowed(const modcp_sig_t *s)
{
    return !s->enabled || s->dsr;
}

/* The data output waiting time has elapsed: send if CTS is ON, else give up. */
static void decide(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    if (s->cts && s->dsr) {
        s->state = MODCP_SIGST_SENDING;
        modcp_link_tx_release(l, true, now_us);
        return;
    }
    if (s->dsr) {
        event(s, MODCP_EV_CTS_TIMEOUT); /* DSR OFF was reported at its edge */
        s->cts_missing = true;
    }
    count_abort(s);
    s->state = MODCP_SIGST_IDLE;
    out(s, MODCP_SIG_RTS, false);
    modcp_link_tx_release(l, false, now_us);
}

void modcp_sig_on_reply(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    if (!s->enabled || l->state != (uint8_t)MODCP_LINK_TURNAROUND || s->state != (uint8_t)MODCP_SIGST_IDLE) {
        return;
    }
    if (!s->dsr) {
        /* DSR dropped while the request was processed: (08)18H was raised then */
        count_abort(s);
        modcp_link_tx_release(l, false, now_us);
        return;
    }
    out(s, MODCP_SIG_RTS, true);
    s->t0_us = now_us;
    s->state = MODCP_SIGST_WAIT_CTS;
    if (s->on_delay_us == 0u) {
        decide(s, l, now_us);
        return;
    }
    arm(s, s->on_delay_us);
}

/* RTS OFF after the last character: the link receives again. */
static void rts_off_done(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    s->state = MODCP_SIGST_IDLE;
    out(s, MODCP_SIG_RTS, false);
    modcp_link_on_tx_done(l, now_us);
}

bool modcp_sig_on_timer(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    uint32_t waited = now_us - s->t0_us;
    switch (s->state) {
    case MODCP_SIGST_WAIT_CTS:
        if (waited < s->on_delay_us) {
            arm(s, s->on_delay_us - waited);
        } else {
            decide(s, l, now_us);
        }
        return true;
    case MODCP_SIGST_RTS_OFF:
        if (waited < s->off_delay_us) {
            arm(s, s->off_delay_us - waited);
        } else {
            rts_off_done(s, l, now_us);
        }
        return true;
    case MODCP_SIGST_SENDING:
        return true; /* stale expiry: the link is in TX and has no timer either */
    default:
        return false;
    }
}

/* A character from the partner while RTS is still ON after our reply: the partner has
 * received the reply completely (it answers it), so the time to RTS off has done its
 * job: RTS goes OFF now and the character is received normally. */
void modcp_sig_on_rx(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    if (s->enabled && s->state == (uint8_t)MODCP_SIGST_RTS_OFF) {
        arm(s, 0);
        rts_off_done(s, l, now_us);
    }
}

bool modcp_sig_on_tx_done(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    if (!s->enabled) {
        return false;
    }
    if (s->state != (uint8_t)MODCP_SIGST_SENDING) {
        return true; /* late completion of an aborted transmission: ignored */
    }
    if (s->off_delay_us == 0u) {
        rts_off_done(s, l, now_us);
        return true;
    }
    s->state = MODCP_SIGST_RTS_OFF;
    s->t0_us = now_us;
    arm(s, s->off_delay_us);
    return true;
}

/* Abort a reply in progress (CTS / DSR OFF). */
static void abort_send(modcp_sig_t *s, modcp_link_t *l, uint32_t now_us)
{
    if (s->state == (uint8_t)MODCP_SIGST_WAIT_CTS) {
        count_abort(s);
        s->state = MODCP_SIGST_IDLE;
        out(s, MODCP_SIG_RTS, false);
        arm(s, 0);
        modcp_link_tx_release(l, false, now_us);
    } else if (s->state == (uint8_t)MODCP_SIGST_SENDING) {
        count_abort(s);
        if (s->hal->uart_tx_abort != NULL) {
            s->hal->uart_tx_abort(s->hal->ctx);
        }
        s->state = MODCP_SIGST_IDLE;
        out(s, MODCP_SIG_RTS, false);
        modcp_link_on_tx_done(l, now_us); /* back to receiving */
    } else {
        /* RTS_OFF: everything was sent; the time to RTS off runs out normally */
    }
}

void modcp_sig_on_inputs(modcp_sig_t *s, modcp_link_t *l, bool cts, bool dsr, uint32_t now_us)
{
    bool cts_fell = s->cts && !cts;
    bool dsr_fell = s->dsr && !dsr;
    s->cts = cts;
    s->dsr = dsr;
    if (cts) {
        s->cts_missing = false;
    }
    if (!s->enabled) {
        return;
    }
    if (dsr_fell) {
        event(s, MODCP_EV_SIGNAL_OFF);
        abort_send(s, l, now_us);
        if (l->state == (uint8_t)MODCP_LINK_RX) {
            count_abort(s);
            modcp_link_rx_discard(l);
        }
        return;
    }
    if (cts_fell && s->state == (uint8_t)MODCP_SIGST_SENDING) {
        s->cts_missing = true;
        event(s, MODCP_EV_SIGNAL_OFF);
        abort_send(s, l, now_us);
    }
}

uint8_t modcp_sig_bits(const modcp_sig_t *s)
{
    return (uint8_t)((s->rts ? MODCP_SIGBIT_RTS : 0u) | (s->dtr ? MODCP_SIGBIT_DTR : 0u) |
                     (s->cts ? MODCP_SIGBIT_CTS : 0u) | (s->dsr ? MODCP_SIGBIT_DSR : 0u) |
                     (s->enabled ? MODCP_SIGBIT_AUTO : 0u));
}
