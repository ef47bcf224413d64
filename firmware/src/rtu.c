/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RTU framing ([RTU-2003] §5, docs/diagnostics.md): frame boundaries by the t3.5 gap, address
 * filter, running CRC, t1.5 check, frames that arrive while a request is in progress;
 * one receive automaton (rtu_on_byte, byte_other, rtu_on_error, rtu_on_block) with
 * one frame start and one end of a skipped frame for normal operation and interference
 * suppression = modem mode, whose differences (the characters of a stretch it looks
 * at, line errors inside a frame, the end of our frame) are the rtu_m_* hooks of
 * rtu_modem.c, called by l->modem off the hot path.
 *
 * The backend behind rtu_ops (modcp_framing_ops_t, link_internal.h; chosen by
 * rtu_configure), its state in l->fr.rtu. A
 * character of our frame costs a store and one table-CRC step (plus one comparison with
 * the t1.5 check on: a second entry, rtu_t15_ops, chosen at configuration); the
 * end-of-frame timer is armed once, by the frame's first character (or line error
 * in place of one), and link.c re-arms it for the rest of t3.5 after the last one; the
 * frame is checked only when t3.5 has passed. Time stamps are the ends of characters,
 * as the UART receive interrupt sees them. A block of characters back to back
 * (modcp_cp_on_rx_block: DMA, FIFO) has the effect of its characters one by one at
 * their ends; a run of our frame is stored and CRC'd in one loop (built for speed; for
 * size the link hands them to on_byte one by one).
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
#include "modcp/link.h"
#include "link_internal.h"
#include "crc_internal.h"

/* Placement by build goal. For speed (-O2): frame_start inlined in its two callers
 * (byte_other, rtu_on_block), t15_violated kept out of the t1.5 entry (a leaf with a
 * tail call). For size (-Os) neither has more than one caller (no block path): the
 * compiler inlines them (MODCP_SPEED_INLINE / MODCP_SPEED_NOINLINE, inline_internal.h). */

void rtu_count_char(modcp_rtu_t *r)
{
    if (r->count < RTU_MIN_FRAME) {
        r->count++; /* only ">= RTU_MIN_FRAME" is looked at */
    }
}

/* A character of the stretch that is not (or no longer) part of our frame (modem
 * mode: of a candidate): only for the bus counters. */
void rtu_fold(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = &l->fr.rtu;
    r->skip_crc = modcp_crc16_byte(r->skip_crc, b);
    rtu_count_char(r);
}

/* Our address (or 0) starts our frame (modem mode: a candidate) at buf[0]. */
MODCP_SIZE_NOINLINE void rtu_cand_start(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = &l->fr.rtu;
    l->rx_bad = false;
    l->rx_overflow = false;
    l->buf[0] = b; /* configured: cap >= RTU_MIN_FRAME */
    l->len = 1;
    r->crc = modcp_crc16_byte(MODCP_CRC_INIT, b);
    r->stop = l->cap; /* normal operation: the hot path runs up to the capacity */
    r->total = 0;     /* normal operation: always (the length by t3.5) */
    if (l->modem) {
        r->stop = 1; /* the function code is looked at */
    }
    l->state = MODCP_LINK_RX;
}

/* Our frame (modem mode: the candidate) is given up: its first n characters belong to
 * the stretch again (modem mode: the rest, if any, stays in the buffer for its resync),
 * the line is followed in SKIP. */
MODCP_NOINLINE void rtu_unclaim(modcp_link_t *l, uint16_t n)
{
    modcp_rtu_t *r = &l->fr.rtu;
    for (uint16_t i = 0; i < n; i++) {
        rtu_fold(l, l->buf[i]);
    }
    l->rx_bad = l->rx_bad || (r->flags & RTU_M_SBAD) != 0u;
    r->flags = (uint8_t)(r->flags & ~(RTU_M_FIRST | RTU_M_OPEN));
    l->len = 0;
    l->state = MODCP_LINK_SKIP;
}

/* A frame (modem mode: a stretch) starts after t3.5 (IDLE, or SKIP whose frame ended)
 * with b, or with a line error (err, b 0): the end-of-frame timer is armed here, once per
 * frame. Our address (or 0) starts our frame (modem mode: a candidate); any other
 * character starts one followed in SKIP (not ours: not checked, not answered), a line
 * error an erroneous one, skipped to its t3.5. */
static MODCP_SPEED_INLINE void frame_start(modcp_link_t *l, uint8_t b,
                                                          uint32_t now_us, bool err)
{
    modcp_rtu_t *r = &l->fr.rtu;
    r->skip_crc = MODCP_CRC_INIT;
    r->count = 0;
    r->flags = 0;
    l->rx_bad = false;
    l->rx_overflow = false;
    l->len = 0;
    l->last_us = now_us;
    l->state = MODCP_LINK_SKIP;
    if (err) {
        link_mark_bad(l);
        rtu_count_char(r);
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
void rtu_stretch_end(modcp_link_t *l)
{
    const modcp_rtu_t *r = &l->fr.rtu;
    l->state = MODCP_LINK_IDLE;
    if (l->rx_bad) {
        return; /* damaged: counted once already (modem mode: if a candidate was) */
    }
    if (r->count >= RTU_MIN_FRAME && r->skip_crc == 0u) {
        link_count(l, MODCP_CNT_BUS_MSG);
    } else if ((r->flags & RTU_M_LEAD) != 0u) {
        link_event(l, MODCP_EV_CRC);
        link_count(l, MODCP_CNT_BUS_CRC);
    } else if (!l->modem) {
        link_count(l, MODCP_CNT_BUS_CRC);
    }
}

/* Default branch of the receive automaton (a state RTU never uses, i.e. corrupted):
 * (0E)11H, back to idle; the character that found it starts a new frame. */
void rtu_internal_error(modcp_link_t *l)
{
    link_event(l, MODCP_EV_INTERNAL_RECEIVE);
    l->state = MODCP_LINK_IDLE;
    l->busy_rx = false;
    l->len = 0;
}

/* A character (or line error) while a request is processed or its reply is pending:
 * not stored; only frame starts are followed, for (08)37H and for the return to idle.
 * A frame for us or a broadcast (address 0) starting then is a message sequence error
 * (08)37H ([RTU-2003] §7.5): neither is executed, and no request is lost without a trace.
 * A line error that is not inside a frame (modem mode: after the CRC) with
 * interference suppression (or RS485) is ignored, as between messages. */
void rtu_busy_track(modcp_link_t *l, uint8_t b, bool error, uint32_t now_us)
{
    if (l->rs485 && l->state == MODCP_LINK_TX) {
        return; /* echo of our own transmission */
    }
    if (!l->busy_rx || now_us - l->last_us >= l->t35_us) {
        if (error) {
            if (l->suppress || l->rs485) { /* RS485 normal: between frames (link.c) */
                return;
            }
        } else if (b == l->own_addr || b == 0u) {
            link_event(l, MODCP_EV_SEQUENCE);
        }
        l->busy_rx = true;
    }
    l->last_us = now_us;
}

/* Every case but the plain one of rtu_on_byte() (another state or a full buffer), and
 * a line error in place of a character (err, b 0): the one receive automaton of both
 * modes. Kept out of line so that the hot path stays a leaf. Modem mode implies
 * l->suppress. */
static MODCP_NOINLINE void byte_other(modcp_link_t *l, uint8_t b, uint32_t now_us, bool err)
{
    modcp_rtu_t *r = &l->fr.rtu;
    switch (l->state) {
    case MODCP_LINK_SKIP:
        if (now_us - l->last_us >= l->t35_us) {
            rtu_stretch_end(l); /* modem mode: a line error would begin a stretch, ignored */
            goto start;         /* the skipped frame ended: b starts a new one */
        }
        if (l->modem) {
            if (err) {
                l->rx_bad = true; /* among stray characters / another frame: not counted */
            } else {
                rtu_m_push(l, b);
            }
        } else if (err) {
            goto bad;
        } else {
            rtu_fold(l, b);
        }
        break;
    case MODCP_LINK_RX: /* normal: the buffer is full, the frame is too long; modem mode:
                           function code, byte count, last character, or a full buffer */
        if (l->modem) {
            if (err) {
                rtu_m_cand_bad(l);
            } else {
                rtu_m_push(l, b);
            }
        } else if (!err) {
            l->rx_overflow = true;
        } else if (!l->rx_bad && !l->rx_overflow && l->len >= RTU_MIN_FRAME && r->crc == 0u) {
            return; /* after the CRC: not part of the frame */
        } else {
            goto bad; /* (its count is not looked at: the frame is bad) */
        }
        break;
    case MODCP_LINK_EOF:
    case MODCP_LINK_BUSY:
    case MODCP_LINK_TURNAROUND:
    case MODCP_LINK_TX:
        rtu_busy_track(l, b, err, now_us);
        return;
    default:
        if (l->state != MODCP_LINK_IDLE) {
            rtu_internal_error(l);
            if (err) {
                return;
            }
        }
    start:
        if (err && (l->suppress || l->rs485)) { /* RS485 normal mode too (link.c) */
            return; /* between messages: ignored, a frame starts only with a good character */
        }
        frame_start(l, b, now_us, err);
        return;
    bad:
        link_mark_bad(l);
        rtu_count_char(r);
        break;
    }
    l->last_us = now_us;
}

/* The hot path: a character of our frame, with room in the buffer (r->stop is the
 * capacity in normal operation; modem mode: see rtu_modem.c), is stored and goes
 * through one CRC step; nothing else. */
void rtu_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (l->state != MODCP_LINK_RX || l->len >= l->fr.rtu.stop) {
        byte_other(l, b, now_us, false);
        return;
    }
    l->last_us = now_us;
    l->fr.rtu.crc = modcp_crc16_byte(l->fr.rtu.crc, b);
    l->buf[l->len++] = b;
}

/* With the t1.5 check on: the silence before a character of our frame (distance of the
 * two character ends minus one character time) must not exceed t1.5. A separate entry,
 * so that the check costs nothing when it is off. */
static MODCP_SPEED_NOINLINE void t15_violated(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    const bool first = !l->rx_bad;
    if (l->modem) {
        rtu_m_cand_bad(l); /* the candidate is dropped; b may start the next one */
    } else {
        link_mark_bad(l);
    }
    if (first) {
        l->diag->t15_discards = (uint16_t)(l->diag->t15_discards + 1u);
        if (!l->suppress) {
            link_event(l, MODCP_EV_ZVZ);
        }
    }
    rtu_on_byte(l, b, now_us);
}

void rtu_on_byte_t15(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (l->state == MODCP_LINK_RX && now_us - l->last_us > l->t15_us + l->char_us) {
        t15_violated(l, b, now_us);
        return;
    }
    rtu_on_byte(l, b, now_us);
}

/* Characters back to back (the k-th of n ended at end_us - (n-1-k) * char_us): runs of
 * our frame with room in the buffer are stored and CRC'd in one loop, every other
 * character goes through byte_other() at its own time, exactly as one by one. Only the
 * block's first character can follow a silence (the others come one character time
 * after the one before): it goes through the ops' on_byte, with the t1.5 check if on,
 * or straight to frame_start() when the line is idle (byte_other()'s way there; no
 * t1.5 check before a frame's first character).
 * Built for size (-Os: the MCU builds) there is no block path: the link gives each
 * character to on_byte at its time (block_bytes, link.c), with the same effect and
 * about 110 bytes less (a few instructions more per character). */
#if !defined(__OPTIMIZE_SIZE__)
static void rtu_on_block(modcp_link_t *l, const uint8_t *b, uint16_t n, uint32_t end_us)
{
    const uint32_t c = l->char_us;
    const uint8_t *const e = b + n;
    uint32_t t = end_us - (uint32_t)(n - 1u) * c; /* end of the character at b */
    const uint8_t a = *b++; /* the only one that may follow a silence: t1.5 */
    if (l->state == MODCP_LINK_IDLE) {
        frame_start(l, a, t, false); /* byte_other()'s, without the detour */
    } else {
        l->ops->on_byte(l, a, t);
    }
    t += c;
    while (b < e) {
        const uint16_t stop = l->fr.rtu.stop;
        if (l->state != MODCP_LINK_RX || l->len >= stop) {
            byte_other(l, *b++, t, false); /* a frame's start included */
            t += c;
            continue;
        }
        unsigned m = (unsigned)(e - b); /* a run of our frame: as many as fit */
        if (m > (unsigned)(stop - l->len)) {
            m = (unsigned)(stop - l->len);
        }
        uint8_t *d = &l->buf[l->len];
        uint16_t crc = l->fr.rtu.crc;
        l->len = (uint16_t)(l->len + m);
        t += (m - 1u) * c;
        l->last_us = t;
        t += c;
        for (; m >= 2u; m -= 2u) { /* two per turn, half the loop */
            uint8_t c0 = b[0], c1 = b[1];
            d[0] = c0;
            d[1] = c1;
            crc = modcp_crc16_byte(modcp_crc16_byte(crc, c0), c1);
            b += 2;
            d += 2;
        }
        for (; m > 0u; m--) {
            crc = modcp_crc16_byte(crc, *b);
            *d++ = *b++;
        }
        l->fr.rtu.crc = crc;
    }
}
#endif

/* RS485 normal mode (link.c error_reported): RX / SKIP within t3.5 is inside a frame,
 * unless our frame is complete (its CRC in: what follows is "after the telegram"). */
static bool rtu_in_frame(const modcp_link_t *l)
{
    return !(l->state == MODCP_LINK_RX && !l->rx_bad && !l->rx_overflow &&
             l->len >= RTU_MIN_FRAME && l->fr.rtu.crc == 0u);
}

void rtu_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    (void)line_errors; /* every kind of error has the same effect on framing */
    byte_other(l, 0, now_us, true);
}

/* A formally correct frame for us (or broadcast) in buf[0 .. len): counted and handed
 * to the CP in *f (state BUSY). */
bool rtu_deliver(modcp_link_t *l, modcp_frame_t *f)
{
    link_count(l, MODCP_CNT_BUS_MSG);
    link_count(l, MODCP_CNT_SLAVE_MSG);
    f->addr = l->buf[0];
    f->pdu = &l->buf[1];
    f->pdu_len = (uint16_t)(l->len - 3u);
    f->pdu_cap = (uint16_t)(l->cap - 3u);
    l->state = MODCP_LINK_BUSY;
    l->busy_rx = false;
    return true;
}

/* Modem mode: EOF, hand the frame over. RX / SKIP: t3.5 has passed since the last
 * character (link.c checked it). Our frame (modem mode: a candidate whose length is
 * known only by t3.5) is delivered if it is formally correct; else its characters
 * belong to the stretch again and its end is the stretch's (rtu_stretch_end): (08)36H
 * for a frame that began with our address, (08)16H once for one too long. */
static bool rtu_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    (void)now_us;
    modcp_rtu_t *r = &l->fr.rtu;
    if (l->state == MODCP_LINK_EOF ||
        (l->state == MODCP_LINK_RX && !l->rx_bad && !l->rx_overflow && r->total == 0u &&
         l->len >= RTU_MIN_FRAME && r->crc == 0u)) { /* modem mode: also by t3.5 (unknown FC) */
        return rtu_deliver(l, f);
    }
    if (l->state == MODCP_LINK_RX) {
        if (l->rx_overflow) {
            if (!l->rx_bad && (r->flags & RTU_M_FIRST) != 0u) {
                link_frame_too_long(l);
            }
            l->rx_bad = true; /* the stretch is not complete in the buffer */
        }
        rtu_unclaim(l, l->len);
    }
    if (l->state == MODCP_LINK_SKIP) {
        rtu_stretch_end(l);
    }
    return false; /* else a stale or spurious expiry */
}

uint16_t rtu_encode(modcp_link_t *l, uint16_t pdu_len)
{
    uint32_t n = 1u + (uint32_t)pdu_len; /* address + PDU */
    if (l->reply_same && n + 2u == (uint32_t)l->len) {
        return l->len; /* the request's frame, unchanged: its CRC is in place (len <= cap) */
    }
    if (n + 2u > (uint32_t)l->cap) { /* no buffer: cap 0 */
        return 0;
    }
    return modcp_crc16_append(l->buf, (uint16_t)n); /* a tail call: no stack frame */
}

static const modcp_framing_ops_t rtu_ops, rtu_t15_ops;

/* Normal operation or interference suppression (modem mode, the operating mode
 * parameter: l->modem, one ops table for both); the variant is the t1.5 check. */
const modcp_framing_ops_t *rtu_configure(modcp_link_t *l, const modcp_params_t *p)
{
#if MODCP_WITH_ASCII
    l->silence_us = l->t35_us; /* (built without ASCII the silence is t35_us) */
#endif
    l->modem = p->opmode == (uint8_t)MODCP_OPMODE_SUPPRESS;
    if (l->cap < RTU_MIN_FRAME) {
        return NULL;
    }
    return l->t15_us != 0u ? &rtu_t15_ops : &rtu_ops;
}

#if defined(__OPTIMIZE_SIZE__)
#define RTU_ON_BLOCK /* no block path (link_internal.h) */
#else
#define RTU_ON_BLOCK .on_block = rtu_on_block,
#endif
static const modcp_framing_ops_t rtu_ops = {.on_byte = rtu_on_byte, .on_error = rtu_on_error,
                                            .in_frame = rtu_in_frame, .on_timer = rtu_on_timer, .encode = rtu_encode,
                                            RTU_ON_BLOCK};
static const modcp_framing_ops_t rtu_t15_ops = {.on_byte = rtu_on_byte_t15,
                                                .on_error = rtu_on_error,
                                                .in_frame = rtu_in_frame,
                                                .on_timer = rtu_on_timer,
                                                .encode = rtu_encode, RTU_ON_BLOCK};
