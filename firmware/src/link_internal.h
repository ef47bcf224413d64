/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the link layer and its framing backends (link.c, rtu.c, ascii.c).
 * Internal to the core: not part of the public API. */
#ifndef MODCP_LINK_INTERNAL_H
#define MODCP_LINK_INTERNAL_H

#include "modcp/link.h"
#include "diag_internal.h"
#include "inline_internal.h"

/* A framing backend. The link calls it and never asks which one it runs; the backend
 * keeps its own state in l->fr and uses the link's shared fields (state, buffer, len,
 * rx_bad, rx_overflow, last_us, busy_rx) and configuration.
 *
 * Timer contract: the backend arms the one-shot timer (link_arm) once when a frame
 * starts (RX / SKIP entered from IDLE), never per character; it keeps l->last_us at the
 * end of the last character of the frame. The link handles every expiry in RX / SKIP
 * that comes before LINK_SILENCE(l) has passed since l->last_us by re-arming the rest. */
typedef struct modcp_framing_ops {
    /* A received character (the hot path: per byte a store and a check step). */
    void (*on_byte)(modcp_link_t *l, uint8_t b, uint32_t now_us);
    /* A line error in place of a character (counted and reported by link.c). */
    void (*on_error)(modcp_link_t *l, uint8_t line_errors, uint32_t now_us);
    /* RS485 two-wire in normal mode only (link.c error_reported): in RX / SKIP, less than
     * the silence after the last character, is a frame still arriving (not complete:
     * RTU our frame with its CRC in, ASCII stray characters are no frame)? */
    bool (*in_frame)(const modcp_link_t *l);
    /* A timer expiry the link did not claim: in RX / SKIP only once the silence has
     * passed since the last character (the frame has ended). True: a frame for us is
     * in *f and the state is BUSY. */
    bool (*on_timer)(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f);
    /* The reply PDU at buf + 1 (address at buf[0]) framed in place; its length on the
     * line, 0 if it does not fit. */
    uint16_t (*encode)(modcp_link_t *l, uint16_t pdu_len);
#if !defined(__OPTIMIZE_SIZE__)
    /* Optional: n > 0 characters back to back, the last one ended at end_us (the k-th
     * of n at end_us - (n-1-k) * char_us); must have exactly the effect of n on_byte
     * calls at those times. NULL: the link calls on_byte for each. Built for size
     * (-Os: the MCU builds) there is none: the link always does. */
    void (*on_block)(modcp_link_t *l, const uint8_t *b, uint16_t n, uint32_t end_us);
#endif
} modcp_framing_ops_t;

/* A framing's part of modcp_link_configure() (rtu_configure, ascii_configure; the link
 * calls the one of the framing parameter): its state (already zeroed), and
 * l->silence_us (built with ASCII). Returns the ops to run (the backend may have variants, e.g. RTU with
 * and without the t1.5 check), NULL if the buffer is too small. */
const modcp_framing_ops_t *rtu_configure(modcp_link_t *l, const modcp_params_t *p);
#if MODCP_WITH_ASCII
const modcp_framing_ops_t *ascii_configure(modcp_link_t *l, const modcp_params_t *p);
#endif

/* The silence that ends a frame (RTU t3.5, ASCII the character delay time). */
#if MODCP_WITH_ASCII
#define LINK_SILENCE(l) ((l)->silence_us)
#else
#define LINK_SILENCE(l) ((l)->t35_us)
#endif

/* Arm the one-shot timer (0 disarms): hal, its uart_tx and timer_arm are never NULL
 * (modcp/hal.h: the callbacks that "may be NULL" are the others). */
static inline void link_arm(const modcp_link_t *l, uint32_t us)
{
    l->hal->timer_arm(l->hal->ctx, us);
}

/* The common timer expiry while a frame arrives: armed once at its first character,
 * it expires before the silence has passed since the last one (characters kept
 * coming) and only the rest is armed again. True if that was the case (nothing else
 * to do, nothing else changed); false: modcp_link_on_timer() decides. (A link in RX
 * or SKIP is enabled: stopping it resets the state to IDLE.) */
static inline bool link_timer_rearm(const modcp_link_t *l, uint32_t now_us)
{
    if (l->state != MODCP_LINK_RX && l->state != MODCP_LINK_SKIP) {
        return false;
    }
    uint32_t gap = now_us - l->last_us;
    if (gap >= LINK_SILENCE(l)) {
        return false;
    }
    link_arm(l, LINK_SILENCE(l) - gap);
    return true;
}

/* The link's diagnostics (l->diag, never NULL: modcp_link_init). */
static inline void link_event(const modcp_link_t *l, modcp_event_t ev)
{
    modcp_diag_event(l->diag, ev);
}

static inline void link_count(const modcp_link_t *l, modcp_counter_t c)
{
    modcp_diag_count(l->diag, c);
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

/* A frame for us was too long for the buffer: (08)16H. */
void link_frame_too_long(modcp_link_t *l);

/* ---- shared by the RTU variants (rtu.c, rtu_modem.c) ---- */
#define RTU_MIN_FRAME 4u /* address, function, CRC */
/* modcp_rtu_t.flags (modem mode) */
#define RTU_M_LEAD 0x01u  /* the stretch began with our address or 0 */
#define RTU_M_FIRST 0x02u /* the candidate is the stretch's first character */
#define RTU_M_OPEN 0x04u  /* a wrong CRC at the length: continue to t3.5 (FC08, FC43) */
#define RTU_M_SBAD 0x08u  /* the stretch around the candidate had a line error */
void rtu_count_char(modcp_rtu_t *r);
/* A character of the stretch that is not part of our frame (bus counters only). */
void rtu_fold(modcp_link_t *l, uint8_t b);
/* Our address (or 0) starts our frame (modem mode: a candidate) at buf[0]. */
void rtu_cand_start(modcp_link_t *l, uint8_t b);
/* Our frame (modem mode: the candidate) given up: its first n characters folded into
 * the stretch, state SKIP. */
void rtu_unclaim(modcp_link_t *l, uint16_t n);
/* t3.5 after a frame followed in SKIP (modem mode: a stretch without a frame). */
void rtu_stretch_end(modcp_link_t *l);
/* A character (or line error) while a request is processed or its reply pending. */
void rtu_busy_track(modcp_link_t *l, uint8_t b, bool error, uint32_t now_us);
/* A state RTU never uses: (0E)11H, back to idle. */
void rtu_internal_error(modcp_link_t *l);
/* A formally correct frame in the buffer: counted, handed over (BUSY). */
bool rtu_deliver(modcp_link_t *l, modcp_frame_t *f);
/* The receive automaton of both variants (rtu.c). The hot path: a character of the
 * frame (modem mode: the candidate) below r->stop (normal operation: the capacity) is
 * stored and goes through one CRC step. Where modem mode differs (the characters of a
 * stretch it looks at, line errors, t1.5, the end of our frame) it calls rtu_m_* by
 * l->modem. */
void rtu_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us);
void rtu_on_byte_t15(modcp_link_t *l, uint8_t b, uint32_t now_us);
void rtu_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us);
/* Modem mode's part of that automaton (rtu_modem.c). */
void rtu_m_push(modcp_link_t *l, uint8_t b);   /* a character of the stretch / candidate */
void rtu_m_cand_bad(modcp_link_t *l);          /* a line error in the candidate */
uint16_t rtu_encode(modcp_link_t *l, uint16_t pdu_len);

/* Moved from modcp/link.h: the core's own interface. */
/* hal: the port's (never NULL, see link_arm); diag: where the link counts and reports,
 * never NULL. */
void modcp_link_init(modcp_link_t *l, const modcp_hal_t *hal, modcp_diag_t *diag, uint8_t *buf,
                     uint16_t cap);
/* Apply parameters (framing, address, timing, interface) and enable. */
void modcp_link_configure(modcp_link_t *l, const modcp_params_t *p);
/* Stop listening (CP not ready). */
void modcp_link_disable(modcp_link_t *l);
void modcp_link_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us);
/* n characters back to back, the last one ended at end_us (modcp_cp_on_rx_block). */
void modcp_link_on_block(modcp_link_t *l, const uint8_t *b, uint16_t n, uint32_t end_us);
/* Returns whether it was reported ((08)0CH / (08)0DH): never in interference
 * suppression, on RS485 two-wire in normal mode only inside a frame. */
bool modcp_link_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us);
/* Timer expiry. Returns true when a valid frame for us or broadcast is ready in *f (f
 * never NULL); the link is then BUSY until modcp_link_reply() or modcp_link_done(). */
bool modcp_link_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f);
/* Send the reply PDU that was written to f->pdu[0 .. pdu_len). */
void modcp_link_reply(modcp_link_t *l, uint16_t pdu_len, uint32_t now_us);
/* Request finished without a reply (broadcast, error). */
void modcp_link_done(modcp_link_t *l);
/* Transmission complete: the driver is released and the link receives again. */
void modcp_link_on_tx_done(modcp_link_t *l, uint32_t now_us);
/* Transmission complete of the last stop bit, recorded for the TXD LED; with RS232
 * automatic signals the link receives again only later (modcp_link_on_tx_done at RTS
 * OFF). */
void modcp_link_tx_complete(modcp_link_t *l, uint32_t now_us);
/* RS232 automatic signals (signals.c): a reply held in TURNAROUND is sent now (send)
 * or dropped (!send, back to receiving). */
void modcp_link_tx_release(modcp_link_t *l, bool send, uint32_t now_us);
/* Drop the frame being received (DSR went OFF): it ends silently at t3.5. */
void modcp_link_rx_discard(modcp_link_t *l);

#endif
