/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the link layer and its framing backends (link.c, rtu.c, ascii.c).
 * Internal to the core: not part of the public API. */
#ifndef MODCP_LINK_INTERNAL_H
#define MODCP_LINK_INTERNAL_H

#include <stddef.h>

#include "modcp/link.h"
#include "diag_internal.h"
#include "inline_internal.h"

/* A framing backend. The link calls it and never asks which one it runs; the backend
 * keeps its own state in l->fr and uses the link's shared fields (state, buffer and the
 * length stored (link_len: rx_at), rx_end, run_stop, rx_bad, rx_overflow, last_us,
 * busy_rx) and configuration.
 *
 * Receive hot path: a framing that stores characters as they are (RTU) sets where the
 * link stores them itself (link_set_stop: l->rx_end, l->run_stop; link_rx_store: the
 * character and its time, nothing else); every other character goes to on_byte. No
 * frame is stored while they are buf / 0.
 *
 * Timer contract: the backend arms the one-shot timer (link_arm) once when a frame
 * starts (RX / SKIP entered from IDLE), never per character; it keeps l->last_us at the
 * end of the last character of the frame. The link handles every expiry in RX / SKIP
 * that comes before LINK_SILENCE(l) has passed since l->last_us by re-arming the rest. */
typedef struct modcp_framing_ops {
    /* A received character the link did not store. */
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
} modcp_framing_ops_t;

/* A framing's part of modcp_link_configure() (the link calls the one of the framing and
 * operating mode parameters): its state (already zeroed), and l->silence_us (built with
 * ASCII). Returns the ops to run (a backend may have variants, e.g. RTU with and without
 * the t1.5 check), NULL if the buffer is too small. */
const modcp_framing_ops_t *rtu_configure(modcp_link_t *l, const modcp_params_t *p);
const modcp_framing_ops_t *rtu_modem_configure(modcp_link_t *l, const modcp_params_t *p);
const modcp_framing_ops_t *ascii_configure(modcp_link_t *l, const modcp_params_t *p); /* ascii.c:
                                                                  built with ASCII only */

/* RS232 automatic signals (signals.c): a reply waits for them, and every received
 * character goes through the CP's entry for them (modcp_cp_on_rx): the link never stores
 * one by itself (link_set_stop); never without them. */
#if MODCP_WITH_RS232_SIGNALS
#define TX_HOLD(l) ((l)->tx_hold)
#else
#define TX_HOLD(l) false
#endif

/* The bytes stored (the reply's length once it is framed) and setting it. */
static inline uint16_t link_len(const modcp_link_t *l)
{
    const ptrdiff_t n = l->rx_at - l->buf; /* 0 .. size */
    return (uint16_t)n;
}

static inline void link_set_len(modcp_link_t *l, uint16_t n)
{
    l->rx_at = l->buf + n;
}

/* Where the link stops storing a frame's characters itself: stop (a buffer index) for
 * the port's per-character entry (0: every character goes to the framing's on_byte;
 * always so with the RS232 automatic signals), run for the characters of a block after
 * its first (modcp_link_on_block). */
static inline void link_set_stop(modcp_link_t *l, uint16_t stop, uint16_t run)
{
    l->rx_end = TX_HOLD(l) ? l->buf : l->buf + stop;
    l->run_stop = run;
}

/* The receive hot path (the port's receive interrupt, modcp_cp_on_rx): a character of a
 * frame the framing stores as it is, below l->rx_end, is stored with its time; nothing
 * else (a write pointer: no index, no length to update). False: the framing's on_byte
 * decides. */
static inline bool link_rx_store(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    uint8_t *at = l->rx_at;
    if (at >= l->rx_end) {
        return false;
    }
    *at = b;
    l->rx_at = at + 1;
    l->last_us = now_us;
    return true;
}

/* The same below the buffer index stop (a framing's own entry, e.g. RTU with the t1.5
 * check: l->run_stop). */
static inline bool link_store_below(modcp_link_t *l, uint16_t stop, uint8_t b,
                                    uint32_t now_us)
{
    uint8_t *at = l->rx_at;
    if (at >= l->buf + stop) {
        return false;
    }
    *at = b;
    l->rx_at = at + 1;
    l->last_us = now_us;
    return true;
}

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

/* RX or SKIP (a frame is being received): the two states differ in bit 0 alone, so one
 * OR and one compare; no other value of the state byte passes (a corrupted state is
 * neither, as with two compares). */
_Static_assert(((unsigned)MODCP_LINK_RX | 1u) == (unsigned)MODCP_LINK_SKIP &&
                   ((unsigned)MODCP_LINK_RX & 1u) == 0u,
               "MODCP_LINK_RX and MODCP_LINK_SKIP differ in bit 0 alone");
static inline bool link_receiving(uint8_t state)
{
    return ((uint32_t)state | 1u) == (uint32_t)MODCP_LINK_SKIP;
}

/* The common timer expiry while a frame arrives: armed once at its first character,
 * it expires before the silence has passed since the last one (characters kept
 * coming) and only the rest is armed again. True if that was the case (nothing else
 * to do, nothing else changed); false: modcp_link_on_timer() decides. (A link in RX
 * or SKIP is enabled: stopping it resets the state to IDLE.) */
static inline bool link_timer_rearm(const modcp_link_t *l, uint32_t now_us)
{
    if (!link_receiving(l->state)) {
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
static inline void link_event(modcp_link_t *l, modcp_event_t ev)
{
    modcp_diag_event(l->diag, ev);
}

static inline void link_count(modcp_link_t *l, modcp_counter_t c)
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
static inline void link_frame_too_long(modcp_link_t *l)
{
    l->diag->frames_too_long = (uint16_t)(l->diag->frames_too_long + 1u);
    link_event(l, MODCP_EV_FRAME_TOO_LONG);
}

/* Moved from modcp/link.h: the core's own interface. */
/* hal: the port's (never NULL, see link_arm); diag: where the link counts and reports,
 * never NULL; buf: the frame buffer of cap bytes, never NULL (the receive write pointers
 * start at it: arithmetic on a null pointer would be undefined). */
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
/* Send the reply PDU that was written to f->pdu[0 .. pdu_len); same: it is the request's
 * PDU, unchanged (FC05 / FC06: RTU sends the frame as received, its CRC in place). */
void modcp_link_reply(modcp_link_t *l, uint16_t pdu_len, bool same, uint32_t now_us);
/* ASCII: the end of a frame is CR and this character (FC08 sub-function 03). */
void modcp_link_set_delimiter(modcp_link_t *l, uint8_t delim);
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
