/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RTU framing in interference suppression = modem mode ([RTU-2009] §5.6.1, §8;
 * [RTU-2003] §2.2): the part of the RTU backend (rtu.c, rtu_ops) that runs for the
 * operating mode `suppression` (l->modem, set by rtu_configure). It shares rtu.c's ops
 * table, receive automaton, block path and hot path (a character below r->stop: a store
 * and a CRC step), its frame and stretch starts and ends (frame_start, rtu_cand_start,
 * rtu_unclaim, rtu_stretch_end, rtu_on_timer); rtu.c calls the rtu_m_* hooks below
 * where modem mode differs: a character of a stretch or candidate that needs a look
 * (rtu_m_push), a line error in a candidate (rtu_m_cand_bad).
 *
 * "The start of a message is recognised by a correctly received slave address"; "the
 * end of the message by a formally correct message with a correct CRC". The line is
 * followed in stretches (characters without a silence of t3.5 between them):
 *   IDLE  the line has been quiet for t3.5. A character starts a stretch (SKIP) and
 *         arms the timer once; a line error is ignored.
 *   SKIP  following a stretch: stray characters, another slave's frame, the tail of a
 *         damaged one. Nothing is stored, only the stretch's CRC for the bus counters;
 *         our address (or 0) starts a candidate frame.
 *   RX    a candidate: stored with a CRC step per character (the hot path, up to
 *         r->stop). Its function code gives its length (fc_table.c): fixed, or by
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

#include "modcp/crc.h"
#include "modcp/link.h"
#include "link_internal.h"
#include "crc_internal.h"
#include "fc_table_internal.h"

enum { M_CONT, M_FAIL, M_DONE };

static bool m_addr(const modcp_link_t *l, uint8_t b)
{
    return b == l->own_addr || b == 0u;
}

/* The character at index r->stop was stored: function code, byte count or the last. */
static int m_check(modcp_link_t *l)
{
    modcp_rtu_t *r = &l->fr.rtu;
    const uint16_t n = l->len;
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
            r->stop = l->cap; /* unknown function code: t3.5 */
            return M_CONT;
        }
        if ((row->form & FC_COUNT) != 0u) {
            r->stop = row->min_len; /* the byte count (address before the PDU) */
            return M_CONT;
        }
        /* address, PDU in its usual form, CRC */
        r->total = (uint16_t)(row->min_len + ((row->form & FC_PLUS2) != 0u ? 5u : 3u));
        if ((row->form & FC_OPEN) != 0u) {
            r->flags |= RTU_M_OPEN;
        }
    } else if (r->total == 0u) { /* the byte count */
        r->total = (uint16_t)(n + l->buf[n - 1u] + 2u);
    }
    if (r->total > l->cap) {
        r->total = 0;
        r->stop = l->cap; /* too long for the buffer: t3.5 ends it */
        return M_CONT;
    }
    if (n < r->total) {
        r->stop = (uint16_t)(r->total - 1u);
        return M_CONT;
    }
    /* dropped by the link (DSR OFF, modcp_link_rx_discard: only with the RS232 signals;
     * every other damage drops a candidate at once) */
    if (MODCP_WITH_RS232_SIGNALS && l->rx_bad) {
        rtu_unclaim(l, l->len);
        return M_CONT;
    }
    if (r->crc == 0u) {
        l->state = MODCP_LINK_EOF; /* formally correct, valid CRC: the end */
        link_arm(l, 1u);
        return M_DONE;
    }
    if ((r->flags & RTU_M_OPEN) != 0u) {
        r->total = 0;
        r->stop = l->cap; /* FC08 / FC43 longer than usual: t3.5 */
        return M_CONT;
    }
    return M_FAIL;
}

/* One character through the automaton, SKIP or RX (no time: the callers keep it). */
static int m_feed(modcp_link_t *l, uint8_t b)
{
    modcp_rtu_t *r = &l->fr.rtu;
    if (l->state == MODCP_LINK_SKIP) {
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
    if (l->len >= l->cap) {
        l->rx_overflow = true;
        return M_CONT;
    }
    r->crc = modcp_crc16_byte(r->crc, b);
    l->buf[l->len++] = b;
    return l->len - 1u == r->stop ? m_check(l) : M_CONT;
}

/* The candidate in buf[0 .. len) failed its length and CRC: drop its first character
 * and run the rest through the automaton again, looking for our address. Each round
 * drops at least one character; the new candidate is written behind the read position
 * (in place). */
static void m_resync(modcp_link_t *l)
{
    uint16_t n = l->len;
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
        memmove(&l->buf[l->len], &l->buf[k], (size_t)(n - k));
        n = (uint16_t)(l->len + (n - k));
        l->len = n;
    }
}

void rtu_m_push(modcp_link_t *l, uint8_t b)
{
    if (m_feed(l, b) == M_FAIL) {
        m_resync(l);
    }
}

/* A damaged candidate: counted once when it has its function code, dropped. */
void rtu_m_cand_bad(modcp_link_t *l)
{
    if (l->len >= 2u) {
        link_mark_bad(l);
    } else {
        l->rx_bad = true; /* a lone address character: before the frame, not counted */
    }
    rtu_unclaim(l, l->len);
}
