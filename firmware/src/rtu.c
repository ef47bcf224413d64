/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RTU framing ([RTU-2003] §5, docs/diagnostics.md): frame boundaries by the t3.5 gap, address
 * filter, running CRC, t1.5 check, frames that arrive while a request is in progress;
 * the common part of the receive automaton (frame start, the end of a skipped frame, the
 * busy states, the end of our frame), shared with interference suppression = modem mode
 * (rtu_modem.c, which calls it: rtu_internal.h), and normal operation's own part.
 *
 * The backend behind rtu_ops (modcp_framing_ops_t, link_internal.h; chosen by
 * rtu_configure), its state in l->fr (modcp_rtu_t, rtu_internal.h). A character of our
 * frame is stored by the link itself (link_rx_store: the character and its time, below
 * l->rx_end; with the t1.5 check on, every character reaches rtu_on_byte, which looks
 * at the time first); its CRC is computed over the buffer once the frame has ended, as FreeMODBUS
 * does. The end-of-frame timer is armed once, by the frame's first character (or line
 * error in place of one), and link.c re-arms it for the rest of t3.5 after the last
 * one; the frame is checked only when t3.5 has passed. Time stamps are the ends of
 * characters, as the UART receive interrupt sees them. A block of characters back to
 * back (modcp_cp_on_rx_block: DMA, FIFO) has the effect of its characters one by one at
 * their ends (link.c copies the runs of our frame).
 * The reply of an FC05 / FC06 is the request unchanged (l->reply_same, set by the CP
 * from the PDU engine): its frame goes out as received, the CRC already in place.
 *
 * Decisions where the manual is silent:
 *  - A byte that arrives in SKIP after a gap >= t3.5 (the expiry is late or the SKIP
 *    was entered without a time, see modcp_link_done) ends the skipped frame and starts
 *    a new one, so a request is never swallowed by someone else's frame. In RX the
 *    timer alone decides the end of a frame (a late timer is the port's fault).
 *  - A line error while our frame already ends in a valid CRC (>= 4 bytes, CRC 0) is
 *    "after the CRC" ([RTU-2003] §2.2): it is not part of the frame, does not restart t3.5,
 *    and the frame stays valid (reported in normal mode only, by link.c). This is the
 *    glitch an RS485 line produces when the master releases its driver.
 *  - Frames with a character error, BREAK or t1.5 violation inside count once in
 *    BUS_CRC (Serial Line V1.02 §6.1: the CRC cannot be evaluated), besides
 *    char_errors / breaks / t15_discards; never in BUS_MSG.
 *  - The t1.5 check applies to frames for us (RX); frames for other addresses are
 *    "not checked".
 *  - RS485 while transmitting: received characters are the echo of our own reply on
 *    the two-wire line and are ignored (no (08)37H for our own address).
 *  - RS485 two-wire in normal mode ([RTU-2003] §2.3): a line error or BREAK that is not inside
 *    a frame (idle line, after a frame's t3.5, while a request is processed and no
 *    frame is being followed) does not start a frame: it is ignored, so a BREAK level
 *    or a glitch in the pause can never swallow the next request. In normal mode on
 *    RS232 / RS422 it starts an (erroneous) frame that is skipped to its t3.5.
 *  - Interference suppression (mode = suppress, modem mode) is the variant in
 *    rtu_modem.c: frames start at our own address and end at their valid CRC. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/crc.h"
#include "rtu_internal.h"
#include "crc_internal.h"

static void count_char(modcp_rtu_t *r)
{
    if (r->count < RTU_MIN_FRAME) {
        r->count++; /* only ">= RTU_MIN_FRAME" is looked at */
    }
}

bool rtu_crc_ok(const modcp_link_t *l)
{
    const ptrdiff_t n = l->rx_at - l->buf; /* 0 .. cap */
    return n >= (ptrdiff_t)RTU_MIN_FRAME && modcp_crc16_update(MODCP_CRC_INIT, l->buf, (size_t)n) == 0u;
}

/* A character of the stretch that is not (or no longer) part of our frame (modem
 * mode: of a candidate): only for the bus counters. */
void rtu_fold(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = rtu_of(l);
    r->skip_crc = modcp_crc16_byte(r->skip_crc, b);
    count_char(r);
}

/* Our address (or 0) starts our frame (modem mode: a candidate) at buf[0]: the link
 * stores what follows up to the capacity (modem mode: up to the function code). */
void rtu_cand_start(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = rtu_of(l);
    l->rx_bad = false;
    l->rx_overflow = false;
    l->buf[0] = b; /* configured: cap >= RTU_MIN_FRAME */
    link_set_len(l, 1);
    r->total = 0; /* normal operation: always (the length by t3.5) */
    l->state = MODCP_LINK_RX;
    rtu_stop(l, r->modem ? 1u : l->cap);
}

/* Our frame (modem mode: the candidate) is given up: its first n characters belong to
 * the stretch again (modem mode: the rest, if any, stays in the buffer for its resync),
 * the line is followed in SKIP. */
void rtu_unclaim(modcp_link_t *l, uint16_t n)
{
    modcp_rtu_t *r = rtu_of(l);
    for (uint16_t i = 0; i < n; i++) {
        rtu_fold(l, l->buf[i]);
    }
    l->rx_bad = l->rx_bad || (r->flags & RTU_M_SBAD) != 0u;
    r->flags = (uint8_t)(r->flags & ~(RTU_M_FIRST | RTU_M_OPEN));
    link_set_len(l, 0);
    l->state = MODCP_LINK_SKIP;
    rtu_stop(l, 0);
}

/* A frame (modem mode: a stretch) starts after t3.5 (IDLE, or SKIP whose frame ended)
 * with b, or with a line error (err, b 0): the end-of-frame timer is armed here, once per
 * frame. Our address (or 0) starts our frame (modem mode: a candidate); any other
 * character starts one followed in SKIP (not ours: not checked, not answered), a line
 * error an erroneous one, skipped to its t3.5. */
static MODCP_SPEED_NOINLINE void frame_start(modcp_link_t *l, uint8_t b, uint32_t now_us,
                                             bool err)
{
    modcp_rtu_t *r = rtu_of(l);
    r->skip_crc = MODCP_CRC_INIT;
    r->count = 0;
    r->flags = 0;
    l->rx_bad = false;
    l->rx_overflow = false;
    link_set_len(l, 0);
    l->last_us = now_us;
    l->state = MODCP_LINK_SKIP;
    if (err) {
        link_mark_bad(l);
        count_char(r);
    } else if (b == l->own_addr || b == 0u) {
        rtu_cand_start(l, b);
        r->flags = RTU_M_LEAD | RTU_M_FIRST;
    } else {
        rtu_fold(l, b);
    }
    link_arm(l, l->t35_us);
}

/* t3.5 after a frame followed in SKIP (modem mode: a stretch without a frame), or
 * after our frame that was not formally correct (rtu_on_timer): a frame that began
 * with our address reports (08)36H and counts in BUS_CRC; another slave's frame counts
 * in BUS_MSG or BUS_CRC (modem mode: only in BUS_MSG, other stretches not at all). */
static void stretch_end(modcp_link_t *l)
{
    const modcp_rtu_t *r = rtu_of_c(l);
    l->state = MODCP_LINK_IDLE;
    if (l->rx_bad) {
        return; /* damaged: counted once already (modem mode: if a candidate was) */
    }
    if (r->count >= RTU_MIN_FRAME && r->skip_crc == 0u) {
        link_count(l, MODCP_CNT_BUS_MSG);
    } else if ((r->flags & RTU_M_LEAD) != 0u) {
        link_event(l, MODCP_EV_CRC);
        link_count(l, MODCP_CNT_BUS_CRC);
    } else if (!r->modem) {
        link_count(l, MODCP_CNT_BUS_CRC);
    } else {
        /* modem mode: stray characters, not counted */
    }
}

/* A character (or line error) while a request is processed or its reply is pending:
 * not stored; only frame starts are followed, for (08)37H and for the return to idle.
 * A frame for us or a broadcast (address 0) starting then is a message sequence error
 * (08)37H ([RTU-2003] §7.5): neither is executed, and no request is lost without a trace.
 * A line error that is not inside a frame (modem mode: after the CRC) with
 * interference suppression (or RS485) is ignored, as between messages. */
static void rtu_busy_track(modcp_link_t *l, uint8_t b, bool error, uint32_t now_us)
{
    if (l->rs485 && l->state == (uint8_t)MODCP_LINK_TX) {
        return; /* echo of our own transmission */
    }
    if (!l->busy_rx || now_us - l->last_us >= l->t35_us) {
        if (error) {
            if (l->suppress || l->rs485) { /* RS485 normal: between frames (link.c) */
                return;
            }
        } else if (b == l->own_addr || b == 0u) {
            link_event(l, MODCP_EV_SEQUENCE);
        } else {
            /* another slave's frame: followed */
        }
        l->busy_rx = true;
    }
    l->last_us = now_us;
}

/* The states both variants handle alike; a state RTU never uses (corrupted) reports
 * (0E)11H and goes back to idle, the character that found it starts a new frame. Modem
 * mode implies l->suppress. */
bool rtu_other_common(modcp_link_t *l, uint8_t b, uint32_t now_us, bool err)
{
    switch (l->state) {
    case MODCP_LINK_SKIP:
        if (now_us - l->last_us < l->t35_us) {
            return false;
        }
        stretch_end(l); /* modem mode: a line error would begin a stretch, ignored */
        break;          /* the skipped frame ended: b starts a new one */
    case MODCP_LINK_RX:
        return false;
    case MODCP_LINK_EOF:
    case MODCP_LINK_BUSY:
    case MODCP_LINK_TURNAROUND:
    case MODCP_LINK_TX:
        rtu_busy_track(l, b, err, now_us);
        return true;
    case MODCP_LINK_IDLE:
        break;
    default:
        link_event(l, MODCP_EV_INTERNAL_RECEIVE);
        l->state = MODCP_LINK_IDLE;
        l->busy_rx = false;
        link_set_len(l, 0);
        rtu_stop(l, 0);
        if (err) {
            return true;
        }
        break;
    }
    if (!err || (!l->suppress && !l->rs485)) { /* RS485 normal mode too (link.c) */
        frame_start(l, b, now_us, err);
    } /* else between messages: ignored, a frame starts only with a good character */
    return true;
}

/* Normal operation: every character the link did not store (the buffer is full, or
 * another state), and a line error in place of a character (err, b 0). Kept out of
 * line so that the entries stay leaves. */
static void byte_other(modcp_link_t *l, uint8_t b, uint32_t now_us, bool err)
{
    if (rtu_other_common(l, b, now_us, err)) {
        return;
    }
    if (l->state == (uint8_t)MODCP_LINK_RX && !err) {
        l->rx_overflow = true; /* the buffer is full: the frame is too long */
    } else if (l->state == (uint8_t)MODCP_LINK_SKIP && !err) {
        rtu_fold(l, b);
    } else if (l->state == (uint8_t)MODCP_LINK_RX && !l->rx_bad && !l->rx_overflow && rtu_crc_ok(l)) {
        return; /* after the CRC: not part of the frame */
    } else {
        link_mark_bad(l); /* (the count of our frame is not looked at: it is bad) */
        count_char(rtu_of(l));
    }
    l->last_us = now_us;
}

bool rtu_t15_violated(modcp_link_t *l, uint32_t now_us)
{
    if (!rtu_t15_late(l, now_us)) {
        return false;
    }
    if (!l->rx_bad) {
        l->diag->t15_discards = (uint16_t)(l->diag->t15_discards + 1u);
        if (!l->suppress) {
            link_event(l, MODCP_EV_ZVZ);
        }
    }
    return true;
}

/* A character the link did not store itself: with the t1.5 check on every one
 * (rx_end at buf: the silence before a character of our frame, the distance of the two
 * character ends minus one character time, must not exceed t1.5), else those at or
 * past the stop or in another state. */
#if !defined(__OPTIMIZE_SIZE__)
/* Built for speed: a character of our frame that came too late (t1.5) is counted and
 * the frame goes on, damaged, out of line, so that rtu_on_byte stays a leaf (tail calls
 * only: no registers saved for the common case). */
static MODCP_NOINLINE void late_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    (void)rtu_t15_violated(l, now_us); /* (true) */
    link_mark_bad(l);
    if (!link_store_below(l, l->run_stop, b, now_us)) {
        byte_other(l, b, now_us, false);
    }
}

static void rtu_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (l->state == (uint8_t)MODCP_LINK_IDLE) { /* (nothing stored: no stop, no t1.5) */
        frame_start(l, b, now_us, false);       /* a frame's first character */
    } else if (rtu_t15_late(l, now_us)) {
        late_byte(l, b, now_us);
    } else if (!link_store_below(l, l->run_stop, b, now_us)) {
        byte_other(l, b, now_us, false);
    } else {
        /* stored */
    }
}
#else
/* Built for size (the same effect): one path. */
static void rtu_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (rtu_t15_violated(l, now_us)) {
        link_mark_bad(l); /* the frame goes on, damaged */
    }
    if (!link_store_below(l, l->run_stop, b, now_us)) {
        byte_other(l, b, now_us, false);
    }
}
#endif

static void rtu_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    (void)line_errors; /* every kind of error has the same effect on framing */
    byte_other(l, 0, now_us, true);
}

/* RS485 normal mode (link.c error_reported): RX / SKIP within t3.5 is inside a frame,
 * unless our frame is complete (its CRC in: what follows is "after the telegram"). */
bool rtu_in_frame(const modcp_link_t *l)
{
    return !(l->state == (uint8_t)MODCP_LINK_RX && !l->rx_bad && !l->rx_overflow && rtu_crc_ok(l));
}

/* A formally correct frame for us (or broadcast) in buf[0 .. len): counted and handed
 * to the CP in *f (state BUSY). */
static bool deliver(modcp_link_t *l, modcp_frame_t *f)
{
    link_count(l, MODCP_CNT_BUS_MSG);
    link_count(l, MODCP_CNT_SLAVE_MSG);
    f->addr = l->buf[0];
    f->pdu = &l->buf[1];
    f->pdu_len = (uint16_t)(link_len(l) - 3u);
    f->pdu_cap = (uint16_t)(l->cap - 3u);
    l->state = MODCP_LINK_BUSY;
    l->busy_rx = false;
    rtu_stop(l, 0);
    return true;
}

/* Modem mode: EOF, hand the frame over. RX / SKIP: t3.5 has passed since the last
 * character (link.c checked it). Our frame (modem mode: a candidate whose length is
 * known only by t3.5) is delivered if it is formally correct; else its characters
 * belong to the stretch again and its end is the stretch's (stretch_end): (08)36H
 * for a frame that began with our address, (08)16H once for one too long. */
bool rtu_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    (void)now_us;
    modcp_rtu_t *r = rtu_of(l);
    if (l->state == (uint8_t)MODCP_LINK_EOF ||
        (l->state == (uint8_t)MODCP_LINK_RX && !l->rx_bad && !l->rx_overflow && r->total == 0u &&
         rtu_crc_ok(l))) { /* modem mode: also by t3.5 (unknown FC) */
        return deliver(l, f);
    }
    if (l->state == (uint8_t)MODCP_LINK_RX) {
        if (l->rx_overflow) {
            if (!l->rx_bad && (r->flags & RTU_M_FIRST) != 0u) {
                link_frame_too_long(l);
            }
            l->rx_bad = true; /* the stretch is not complete in the buffer */
        }
        rtu_unclaim(l, link_len(l));
    }
    if (l->state == (uint8_t)MODCP_LINK_SKIP) {
        stretch_end(l);
    }
    return false; /* else a stale or spurious expiry */
}

uint16_t rtu_encode(modcp_link_t *l, uint16_t pdu_len)
{
    uint32_t n = 1u + (uint32_t)pdu_len; /* address + PDU */
    if (l->reply_same && l->rx_at == l->buf + n + 2u) {
        return (uint16_t)(n + 2u); /* the request's frame, unchanged: its CRC is in place
                                      (len <= cap) */
    }
    if (n + 2u > (uint32_t)l->cap) { /* no buffer: cap 0 */
        return 0;
    }
    return modcp_crc16_append(l->buf, (uint16_t)n); /* a tail call: no stack frame */
}

bool rtu_setup(modcp_link_t *l, bool modem)
{
#if MODCP_WITH_ASCII
    l->silence_us = l->t35_us; /* (built without ASCII the silence is t35_us) */
#endif
    rtu_of(l)->modem = modem;
    return l->cap >= RTU_MIN_FRAME;
}

static const modcp_framing_ops_t rtu_ops = {.on_byte = rtu_on_byte,
                                            .on_error = rtu_on_error,
                                            .in_frame = rtu_in_frame,
                                            .on_timer = rtu_on_timer,
                                            .encode = rtu_encode};

/* Normal operation (the operating mode parameter; modem mode: rtu_modem_configure). */
const modcp_framing_ops_t *rtu_configure(modcp_link_t *l, const modcp_params_t *p)
{
    (void)p;
    return rtu_setup(l, false) ? &rtu_ops : NULL;
}
