/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — serial link layer: configuration, the framing backend behind its ops struct
 * (RTU in rtu.c, ASCII in ascii.c, selected once in modcp_link_configure), the
 * end-of-frame silence, line-error accounting, transmit, turnaround and RS485 driver
 * enable (docs/design.md).
 *
 * RS485: DE is switched on before the first byte (before the turnaround delay, so the
 * line is driven to idle while we wait) and released only in modcp_link_on_tx_done(),
 * which the port calls on *transmission complete* of the last stop bit. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "modcp/link.h"
#include "link_internal.h"
#include "diag_internal.h"
#include "params_internal.h"

static void set_de(const modcp_link_t *l, bool on)
{
    if (l->hal->set_de != NULL) {
        l->hal->set_de(l->hal->ctx, on);
    }
}

static void start_tx(modcp_link_t *l)
{
    l->state = MODCP_LINK_TX;
    l->tx_starts++;
    l->tx_on = true;
    l->hal->uart_tx(l->hal->ctx, l->buf, link_len(l)); /* never NULL (modcp/hal.h) */
}

static void reset_rx(modcp_link_t *l)
{
    l->state = MODCP_LINK_IDLE;
    link_set_len(l, 0);
    l->rx_bad = false;
    l->rx_overflow = false;
    l->busy_rx = false;
    link_set_stop(l, 0, 0);
    (void)memset(&l->fr, 0, sizeof l->fr);
}

/* A disabled (or not yet configured) link, state IDLE: the line and the timer are
 * ignored. Only on_byte (modcp_link_on_byte / _on_block) and on_timer are ever reached
 * through it: the other entry points check l->enabled or the state first. */
static void off_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    (void)l;
    (void)b;
    (void)now_us;
}
static bool off_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    (void)l;
    (void)now_us;
    (void)f;
    return false;
}
static const modcp_framing_ops_t off_ops = {.on_byte = off_byte, .on_timer = off_timer};

/* The backend for the framing parameter (the only place that names the framings),
 * configured: the ops to run, NULL if it cannot. */
static const modcp_framing_ops_t *framing_configure(modcp_link_t *l, const modcp_params_t *p)
{
    switch (p->framing) {
    case MODCP_FRAMING_RTU: /* interference suppression: modem mode, rtu_modem.c */
        return p->opmode == (uint8_t)MODCP_OPMODE_SUPPRESS ? rtu_modem_configure(l, p)
                                                          : rtu_configure(l, p);
#if MODCP_WITH_ASCII
    case MODCP_FRAMING_ASCII:
        return ascii_configure(l, p);
#endif
    default:
        return NULL;
    }
}

/* Back to receiving after a request. If a frame that started while we were busy is
 * still arriving (RTU: less than t3.5 since its last character), follow its tail in
 * SKIP so it is never taken for a new request. Without a time (have_now false) the
 * timer is armed for a full t3.5 and its expiry or the next character decides. */
static void resume_rx(modcp_link_t *l, uint32_t now_us, bool have_now)
{
    if (l->busy_rx) {
        uint32_t gap = have_now ? now_us - l->last_us : 0u;
        if (gap < LINK_SILENCE(l)) {
            l->busy_rx = false;
            l->state = MODCP_LINK_SKIP;
            l->rx_bad = true; /* only its tail was seen: not counted */
            l->rx_overflow = false;
            link_set_len(l, 0);
            link_arm(l, LINK_SILENCE(l) - gap);
            return;
        }
    }
    l->busy_rx = false;
    l->state = MODCP_LINK_IDLE;
}

void modcp_link_init(modcp_link_t *l, const modcp_hal_t *hal, modcp_diag_t *diag, uint8_t *buf,
                     uint16_t cap)
{
    (void)memset(l, 0, sizeof *l);
    l->hal = hal;
    l->diag = diag;
    l->buf = buf;
    l->size = cap;
    l->cap = l->size < MODCP_ADU_MAX ? l->size : (uint16_t)MODCP_ADU_MAX;
    l->rx_at = buf; /* nothing stored, nothing to store */
    l->rx_end = buf;
    l->ops = &off_ops; /* disabled: enabled false, state IDLE (zero) */
}

/* Timer off, driver off, nothing received, the line ignored. */
static void stop(modcp_link_t *l)
{
    link_arm(l, 0);
    set_de(l, false);
    reset_rx(l);
    l->tx_on = false;
    l->ops = &off_ops;
    l->enabled = false;
}

void modcp_link_configure(modcp_link_t *l, const modcp_params_t *p)
{
    stop(l);
    l->own_addr = p->slave_addr;
    l->rs485 = p->iface == (uint8_t)MODCP_IFACE_RS485;
    /* two-wire RS485 is interference suppression unless its mode selection is on ([RTU-2009]
     * Table 5-2; params.c refuses mode = normal without it) */
    l->suppress = p->opmode == (uint8_t)MODCP_OPMODE_SUPPRESS || (l->rs485 && p->rs485_sel == 0u);
    l->t35_us = modcp_params_t35_us(p);
    l->t15_us = p->t15_check != 0u ? modcp_params_t15_us(p) : 0u;
    l->char_us = modcp_params_char_us(p);
    l->turnaround_us = l->rs485 ? (uint32_t)p->turnaround_ms * 1000u : 0u;
#if MODCP_WITH_RS232_SIGNALS /* else rs232_auto is refused (params.c): never held */
    l->tx_hold = p->rs232_auto != 0u && p->iface == (uint8_t)MODCP_IFACE_RS232;
#endif
#if MODCP_WITH_ASCII
    l->ascii_delim = 0x0Au; /* LF until FC08 sub-function 03 changes it */
#endif
    const modcp_framing_ops_t *ops = framing_configure(l, p);
    if (ops != NULL) {
        l->ops = ops;
        l->enabled = true;
    }
}

void modcp_link_disable(modcp_link_t *l)
{
    stop(l);
}

/* A character: stored by the link (the hot path) or given to the framing. */
void modcp_link_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (!link_rx_store(l, b, now_us)) {
        l->ops->on_byte(l, b, now_us); /* (a disabled link has the "off" backend) */
    }
}

/* Characters back to back (the k-th of n ended at end_us - (n-1-k) * char_us), with the
 * effect of the characters one by one at their ends: the first (the only one that can
 * follow a silence: a frame's start, the t1.5 check) goes to the framing, then each run
 * the framing lets the link store (below l->run_stop) is copied at once, every other
 * character goes to the framing at its time. A block holds no silence, so it never
 * contains the end of one frame and the start of the next. Only modcp_cp_on_rx_block
 * calls this: a port that never does links none of it. */
void modcp_link_on_block(modcp_link_t *l, const uint8_t *b, uint16_t n, uint32_t end_us)
{
    if (n == 0u) {
        return;
    }
    const uint32_t c = l->char_us;
    uint32_t t = end_us - ((uint32_t)n - 1u) * c; /* end of the character at b[0] */
    l->ops->on_byte(l, b[0], t);
#if defined(__OPTIMIZE_SIZE__) /* -Os (the MCU builds): a character at a time (68 B less) */
    for (uint16_t k = 1; k < n; k++) {
        t += c;
        modcp_link_on_byte(l, b[k], t);
    }
#else
    uint16_t k = 1;
    while (k < n) {
        t += c; /* end of the character at b[k] */
        const uint16_t len = link_len(l);
        if (len < l->run_stop) {
            uint16_t m = (uint16_t)(n - k); /* a run of our frame: as many as fit */
            if (m > (uint16_t)(l->run_stop - len)) {
                m = (uint16_t)(l->run_stop - len);
            }
            (void)memcpy(&l->buf[len], &b[k], m);
            link_set_len(l, (uint16_t)(len + m));
            k = (uint16_t)(k + m);
            t += ((uint32_t)m - 1u) * c;
            l->last_us = t;
        } else {
            l->ops->on_byte(l, b[k], t);
            k++;
        }
    }
#endif
}

/* Whether a line error is reported ((08)0CH / (08)0DH): in normal mode; never in
 * interference suppression (the frame is discarded silently); on two-wire RS485 in
 * normal mode (mode selection on, [RTU-2009] Table 5-2) only inside a frame — ours before its
 * CRC is complete, or another slave's — never before, after or between frames ([RTU-2009]
 * §5.6.5: "all transmission errors or BREAKs detected before and after received
 * telegrams are ignored ... a BREAK level during the pauses too"). */
static bool error_reported(const modcp_link_t *l, uint32_t now_us)
{
    if (l->suppress) {
        return false;
    }
    if (!l->rs485) {
        return true;
    }
    return link_receiving(l->state) &&
           now_us - l->last_us < LINK_SILENCE(l) && l->ops->in_frame(l);
}

bool modcp_link_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    if (!l->enabled || line_errors == 0u) {
        return false;
    }
    const bool brk = (line_errors & MODCP_LINE_BREAK) != 0u;
    uint16_t *n = brk ? &l->diag->breaks : &l->diag->char_errors;
    *n = (uint16_t)(*n + 1u);
    const bool report = error_reported(l, now_us);
    if (report) {
        link_event(l, brk ? MODCP_EV_BREAK : MODCP_EV_CHAR_ERROR);
    }
    if ((line_errors & MODCP_LINE_OVERRUN) != 0u) {
        link_count(l, MODCP_CNT_CHAR_OVERRUN);
    }
    l->ops->on_error(l, line_errors, now_us);
    return report;
}

bool modcp_link_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    if (link_timer_rearm(l, now_us)) {
        return false; /* characters kept coming: the rest of the silence is armed */
    }
    if (l->state == (uint8_t)MODCP_LINK_TURNAROUND) {
        uint32_t waited = now_us - l->tx_at_us;
        if (TX_HOLD(l)) {
            return false; /* RS232 automatic signals: signals.c releases the reply */
        }
        if (waited < l->turnaround_us) {
            link_arm(l, l->turnaround_us - waited); /* early expiry: never before turnaround */
            return false;
        }
        start_tx(l);
        return false;
    }
    return l->ops->on_timer(l, now_us, f);
}

void modcp_link_reply(modcp_link_t *l, uint16_t pdu_len, bool same, uint32_t now_us)
{
    if (l->state != (uint8_t)MODCP_LINK_BUSY) {
        return; /* (a disabled link is IDLE) */
    }
    l->reply_same = same;
    l->tx_at_us = now_us;
    link_set_len(l, l->ops->encode(l, pdu_len)); /* now the reply's length on the line */
    if (link_len(l) == 0u) {
        link_event(l, MODCP_EV_INTERNAL_SEND); /* reply does not fit */
        modcp_link_done(l);
        return;
    }
    if (l->rs485) {
        set_de(l, true);
    }
    if (TX_HOLD(l)) {
        l->state = MODCP_LINK_TURNAROUND; /* signals.c: RTS, data output waiting time, CTS */
        return;
    }
    if (l->turnaround_us > 0u) { /* RS485 only (modcp_link_configure) */
        l->state = MODCP_LINK_TURNAROUND;
        link_arm(l, l->turnaround_us);
        return;
    }
    start_tx(l);
}

void modcp_link_done(modcp_link_t *l)
{
    if (l->state != (uint8_t)MODCP_LINK_BUSY) {
        return;
    }
    resume_rx(l, 0, false);
}

void modcp_link_tx_complete(modcp_link_t *l, uint32_t now_us)
{
    l->tx_on = false;
    l->tx_end_us = now_us;
}

void modcp_link_on_tx_done(modcp_link_t *l, uint32_t now_us)
{
    if (l->tx_on) { /* (with RS232 signals: already at modcp_link_tx_complete) */
        modcp_link_tx_complete(l, now_us);
    }
    if (l->state != (uint8_t)MODCP_LINK_TX) {
        return;
    }
    if (l->rs485) {
        set_de(l, false);
    }
    resume_rx(l, now_us, true);
}

void modcp_link_tx_release(modcp_link_t *l, bool send, uint32_t now_us)
{
    if (l->state != (uint8_t)MODCP_LINK_TURNAROUND) {
        return;
    }
    if (send) {
        start_tx(l);
    } else {
        resume_rx(l, now_us, true);
    }
}

void modcp_link_set_delimiter(modcp_link_t *l, uint8_t delim)
{
    l->ascii_delim = delim;
}

void modcp_link_rx_discard(modcp_link_t *l)
{
    if (l->state == (uint8_t)MODCP_LINK_RX) {
        l->rx_bad = true;
    }
}
