/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RTU framing in interference suppression = modem mode ([RTU-2009] §5.6.1, §8;
 * [RTU-2003] §2.2): the RTU backend's variant for the operating mode `suppression`, its
 * own ops (chosen by rtu_modem_configure) built on the common part of rtu.c's receive
 * automaton (rtu_internal.h: frame and stretch starts and ends, the busy states, the end
 * of a frame by t3.5, the encoder); rtu.c never calls it. The link stores a candidate's
 * characters below l->run_stop (the hot path); the ones that need a look (function
 * code, byte count, last character) and the characters of a stretch come here.
 *
 * "The start of a message is recognised by a correctly received slave address"; "the
 * end of the message by a formally correct message with a correct CRC". The line is
 * followed in stretches (characters without a silence of t3.5 between them):
 *   IDLE  the line has been quiet for t3.5. A character starts a stretch (SKIP) and
 *         arms the timer once; a line error is ignored.
 *   SKIP  following a stretch: stray characters, another slave's frame, the tail of a
 *         damaged one. Nothing is stored, only the stretch's CRC for the bus counters;
 *         our address (or 0) starts a candidate frame.
 *   RX    a candidate: stored by the link (the hot path, up to
 *         l->run_stop). Its function code gives its length (fc_table.c): fixed, or by
 *         its byte count; at that length a valid CRC ends the frame at once (EOF, handed
 *         over on a 1 us timer: no t3.5 wait), a wrong one drops the candidate's first
 *         character and looks for our address again in the rest (resync), so a stray
 *         00 or a stray copy of our address before a request does not lose it. An
 *         unknown function code (or FC08 / FC43 longer than their usual form) ends by
 *         t3.5 as in normal operation; 00 and 80H...FFH are no request's function
 *         code and fail at once.
 * A line error inside a candidate drops it (counted once in BUS_CRC when it has its
 * function code, no event); elsewhere (before the frame, after the CRC, among stray
 * characters) it is ignored. A stretch that began with our address and never became a
 * frame reports (08)36H at its t3.5, as normal operation does; other stretches count
 * in BUS_MSG when they end in a valid CRC (another slave's frame), else not at all.
 * Address 0 starts a candidate anywhere only with a function code broadcast may use
 * (05, 06, 15, 16); as a stretch's first character with any (the PDU engine reports
 * (08)30H). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "rtu_internal.h"
#include "fc_table_internal.h"

#define M_CONT 0 /* m_feed / m_check: follow on */
#define M_FAIL 1 /* the candidate failed: resync */
#define M_DONE 2 /* a frame (EOF) */

static bool m_addr(const modcp_link_t *l, uint8_t b)
{
    return b == l->own_addr || b == 0u;
}

/* The character at index l->run_stop was stored: function code, byte count or the last. */
static int m_check(modcp_link_t *l)
{
    modcp_rtu_t *r = rtu_of(l);
    const uint16_t n = link_len(l);
    if (n == 2u) {
        /* the request's length by its function code (fc_table.c): fixed, or by its byte
         * count; unknown (no row): t3.5 and no broadcast */
        const uint8_t fc = l->buf[1];
        const modcp_fc_row_t *row = modcp_fc_row(fc);
        if (l->buf[0] == 0u && (r->flags & RTU_M_FIRST) == 0u &&
            (row == NULL || (row->flags & F_BCAST) == 0u)) {
            return M_FAIL; /* no broadcast request */
        }
        if (fc == 0u || fc >= 0x80u) {
            return M_FAIL; /* no request has this function code */
        }
        if (row == NULL) {
            rtu_stop(l, l->cap); /* unknown function code: t3.5 */
            return M_CONT;
        }
        if ((row->form & FC_COUNT) != 0u) {
            rtu_stop(l, row->min_len); /* the byte count (address before the PDU) */
            return M_CONT;
        }
        /* address, PDU in its usual form, CRC */
        r->total = (uint16_t)(row->min_len + ((row->form & FC_PLUS2) != 0u ? 5u : 3u));
        if (((row->form & FC_OPEN) != 0u) ||
            (r->r32_on && ((row->flags & F_R32) != 0u) && ((row->form & FC_PLUS2) != 0u))) {
            r->flags |= RTU_M_OPEN;
        }
    } else if (r->total == 0u) { /* the byte count */
        r->total = (uint16_t)(n + l->buf[n - 1u] + 2u);
    } else {
        /* the last character: the length is known */
    }
    if (r->total > l->cap) {
        r->total = 0;
        rtu_stop(l, l->cap); /* too long for the buffer: t3.5 ends it */
        return M_CONT;
    }
    if (n < r->total) {
        rtu_stop(l, (uint16_t)(r->total - 1u));
        return M_CONT;
    }
    /* dropped by the link (DSR OFF, modcp_link_rx_discard: only with the RS232 signals;
     * every other damage drops a candidate at once) */
    if (MODCP_WITH_RS232_SIGNALS && l->rx_bad) {
        rtu_unclaim(l, link_len(l));
        return M_CONT;
    }
    if (rtu_crc_ok(l)) {
        l->state = MODCP_LINK_EOF; /* formally correct, valid CRC: the end */
        rtu_stop(l, 0);
        link_arm(l, 1u);
        return M_DONE;
    }
    if ((r->flags & RTU_M_OPEN) != 0u) {
        r->total = 0;
        rtu_stop(l, l->cap); /* FC08 / FC43 longer than usual: t3.5 */
        return M_CONT;
    }
    return M_FAIL;
}

/* One character through the automaton, SKIP or RX (no time: the callers keep it). */
static int m_feed(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = rtu_of(l);
    if (l->state == (uint8_t)MODCP_LINK_SKIP) {
        if (m_addr(l, b)) {
            /* a candidate inside the stretch: whether the stretch had a line error */
            r->flags = (uint8_t)((r->flags & ~(RTU_M_FIRST | RTU_M_SBAD)) |
                                 (l->rx_bad ? RTU_M_SBAD : 0u));
            rtu_cand_start(l, b);
        } else {
            rtu_fold(l, b);
        }
        return M_CONT;
    }
    const uint16_t n = link_len(l);
    if (n >= l->cap) {
        l->rx_overflow = true;
        return M_CONT;
    }
    l->buf[n] = b;
    link_set_len(l, (uint16_t)(n + 1u));
    return n == l->run_stop ? m_check(l) : M_CONT;
}

/* The candidate in buf[0 .. len) failed its length and CRC: drop its first character
 * and run the rest through the automaton again, looking for our address. Each round
 * drops at least one character; the new candidate is written behind the read position
 * (in place). */
static void m_resync(modcp_link_t *l)
{
    uint16_t n = link_len(l);
    for (;;) {
        rtu_unclaim(l, 1u);
        int res = M_CONT;
        uint16_t k = 1;
        while (k < n && res == M_CONT) {
            res = m_feed(l, l->buf[k]);
            k++;
        }
        if (res != M_FAIL) {
            return; /* following, in a candidate, or a frame (what followed it: after the CRC) */
        }
        (void)memmove(&l->buf[link_len(l)], &l->buf[k], (size_t)n - (size_t)k);
        n = (uint16_t)(link_len(l) + (n - k));
        link_set_len(l, n);
    }
}

static void m_push(modcp_link_t *l, uint8_t b)
{
    if (m_feed(l, b) == M_FAIL) {
        m_resync(l);
    }
}

/* A damaged candidate: counted once when it has its function code, dropped. */
static void m_cand_bad(modcp_link_t *l)
{
    if (link_len(l) >= 2u) {
        link_mark_bad(l);
    } else {
        l->rx_bad = true; /* a lone address character: before the frame, not counted */
    }
    rtu_unclaim(l, link_len(l));
}

/* Every character the link did not store (a stretch, or a candidate's character that
 * needs a look), and a line error in place of a character (err, b 0). */
static void m_other(modcp_link_t *l, uint8_t b, uint32_t now_us, bool err)
{
    if (rtu_other_common(l, b, now_us, err)) {
        return;
    }
    if (!err) {
        m_push(l, b);
    } else if (l->state == (uint8_t)MODCP_LINK_RX) {
        m_cand_bad(l);
    } else {
        l->rx_bad = true; /* among stray characters / another frame: not counted */
    }
    l->last_us = now_us;
}

/* A character the link did not store itself (see rtu.c rtu_on_byte): a t1.5 violation
 * drops the candidate, b may start the next. */
static void m_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (rtu_t15_violated(l, now_us)) {
        m_cand_bad(l);
    }
    if (!link_store_below(l, l->run_stop, b, now_us)) {
        m_other(l, b, now_us, false);
    }
}

static void m_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    (void)line_errors; /* every kind of error has the same effect on framing */
    m_other(l, 0, now_us, true);
}

static const modcp_framing_ops_t m_ops = {.on_byte = m_on_byte,
                                          .on_error = m_on_error,
                                          .in_frame = rtu_in_frame,
                                          .on_timer = rtu_on_timer,
                                          .encode = rtu_encode};

/* Interference suppression (the operating mode parameter). */
const modcp_framing_ops_t *rtu_modem_configure(modcp_link_t *l, const modcp_params_t *p)
{
    const bool ok = rtu_setup(l, true);
    rtu_of(l)->r32_on = p->regs32 != 0u; /* without them FC06 still ends at its CRC */
    return ok ? &m_ops : NULL;
}
