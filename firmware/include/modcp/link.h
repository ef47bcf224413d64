/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — serial link layer: frame boundaries, transmit and RS485 direction.
 * The framing is a backend behind an ops struct (link_internal.h): RTU in rtu.c, ASCII
 * in ascii.c, each with its own receive state (modcp_rtu_t / modcp_ascii_t below);
 * link.c never asks which one it runs. The transmit side, turnaround, driver enable
 * and the end-of-frame silence are shared.
 *
 * Receive: per byte the character is stored with the time of the last character (RTU:
 * by the link itself, the CRC checked over the buffer when the frame has ended; ASCII:
 * the framing decodes the hex pair and sums the LRC). (RTU in interference suppression = modem mode,
 * rtu_modem.c: a frame starts at our own address and ends at its valid CRC, its length
 * from the function code, handed over at once; the silence below ends only frames of
 * unknown length and everything that is not ours.) The end-of-frame timer is armed once, at a frame's first
 * character, with the silence that ends a frame (RTU t3.5, ASCII the character delay
 * time); when it expires the link compares now - last character with the silence and
 * re-arms for the remainder while characters kept coming, so the frame ends exactly one
 * silence after its last character without a HAL call per byte. Then the frame is
 * checked: address (own or 0, others ignored without checking), length, CRC ((08)36H
 * and silence on mismatch). Bytes that arrive while a request is being processed or
 * its reply is pending are not stored; their frame is followed, and if it is for us,
 * (08)37H is reported. Frames longer than the buffer are discarded and counted ((08)16H).
 *
 * Buffer: one buffer holds the request and then, in place, the reply. */
/* Public for layout only: modcp_cp_t embeds modcp_link_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/link_internal.h). */
#ifndef MODCP_LINK_H
#define MODCP_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/diag.h"
#include "modcp/features.h"
#include "modcp/hal.h"
#include "modcp/params.h"

#define MODCP_ADU_MAX 264u /* FC15 with 2040 bits: 1+1+2+2+1+255+2 */
/* ASCII (ascii.c): received frames are decoded to binary as they arrive (at most
 * MODCP_ADU_MAX bytes), but the reply is hex-encoded in place: ':' + 2 x (address,
 * PDU of up to 253 bytes, LRC) + CR LF = 513 characters. A CP's frame buffer is
 * MODCP_LINK_BUF_MAX bytes (249 more than RTU alone needs); RTU still uses only the
 * first MODCP_ADU_MAX. Built without ASCII (MODCP_WITH_ASCII 0, modcp/features.h) the
 * frame buffer is MODCP_ADU_MAX. */
#define MODCP_ASCII_PDU_MAX 253u
#define MODCP_ASCII_ADU_MAX (1u + 2u * (1u + MODCP_ASCII_PDU_MAX + 1u) + 2u)
#if MODCP_WITH_ASCII
#define MODCP_LINK_BUF_MAX MODCP_ASCII_ADU_MAX
#else
#define MODCP_LINK_BUF_MAX MODCP_ADU_MAX
#endif

typedef enum {
    MODCP_LINK_IDLE = 0,  /* waiting for the first byte of a frame */
    MODCP_LINK_BUSY = 1,  /* a request is being processed; buffer owned by the PDU */
    MODCP_LINK_TURNAROUND = 2, /* reply ready, waiting for the turnaround delay */
    MODCP_LINK_TX = 3,    /* transmitting */
    MODCP_LINK_RX = 4,    /* receiving, storing (RX and SKIP differ in bit 0 alone:
                             link_receiving(), link_internal.h) */
    MODCP_LINK_SKIP = 5,  /* receiving, not storing (other address, error, overflow) */
    MODCP_LINK_EOF = 8,   /* ASCII: CR LF of a good frame received; RTU modem mode: a
                             formally correct frame with a valid CRC; handed over on
                             the next timer expiry (armed with 1 us) */
} modcp_link_state_t;

typedef struct {
    uint8_t addr;        /* 0 = broadcast */
    uint8_t *pdu;        /* function code + data, inside the link buffer */
    uint16_t pdu_len;
    uint16_t pdu_cap;    /* room for the reply PDU at pdu[] */
} modcp_frame_t;

/* The framing's own receive state: opaque here, defined by its backend (rtu_internal.h,
 * ascii.c), which checks that it fits. */
typedef union {
    uint32_t align_;
    uint16_t words_[6];
} modcp_link_fr_t;

struct modcp_framing_ops; /* link_internal.h */

typedef struct { /* members by size, the small ones first: every byte within reach of the
                    short (16-bit) Thumb load / store (offset < 32), every halfword too
                    (< 64); no padding but a byte or two */
    uint8_t state;    /* modcp_link_state_t */
    bool rx_bad;      /* character error / BREAK / t1.5 violation inside the frame */
    bool rx_overflow;
    bool busy_rx;     /* a frame is being followed while BUSY/TURNAROUND/TX */
    uint8_t own_addr;
    bool suppress;    /* interference suppression (also RS485) */
    bool rs485;
    bool enabled;     /* configured; a disabled link ignores the line */
    bool tx_on;       /* a transmission is on the line: from its start to transmission
                         complete (or its abort) */
    bool reply_same;  /* the reply being sent is the request's PDU, unchanged (FC05 /
                         FC06 echo; modcp_link_reply), so a framing may send the frame as
                         received (RTU: its CRC in place) */
#if MODCP_WITH_RS232_SIGNALS
    bool tx_hold;     /* RS232 automatic signals: a reply waits in TURNAROUND until
                         modcp_link_tx_release() (signals.c decides RTS / CTS) */
#endif
    uint8_t ascii_delim; /* ASCII: end of frame is CR + this (LF; FC08 sub-function 03) */
    modcp_link_fr_t fr; /* the framing's own receive state */
    uint16_t run_stop; /* the characters of a block after its first are stored by the
                          link itself (modcp_link_on_block) while the buffer holds fewer:
                          rx_end's index, or more where every character must reach the
                          framing (RTU's t1.5 check; the RS232 automatic signals, rx_end
                          at buf); 0 while no frame is stored (set by the framing) */
    uint16_t cap;     /* receive / RTU capacity: the buffer, at most MODCP_ADU_MAX */
    uint16_t size;    /* the whole buffer (ASCII replies are hex-encoded in place) */
    uint16_t tx_starts; /* transmissions started (the TXD LED reads it, leds.h) */
    const modcp_hal_t *hal;
    modcp_diag_t *diag;
    uint8_t *buf;
    uint8_t *rx_at;   /* buf + the bytes stored (link_len, link_internal.h); from
                         modcp_link_reply() on (TURNAROUND, TX) + the reply's length on
                         the line */
    const uint8_t *rx_end; /* the receive hot path (link_rx_store, link_internal.h): a
                         character is stored at rx_at by the link itself while rx_at is
                         below it; buf while no frame is stored (set by the framing) */
    const struct modcp_framing_ops *ops; /* the framing (never NULL: "off" when disabled) */
    /* configuration */
#if MODCP_WITH_ASCII
    uint32_t silence_us; /* the silence that ends a frame: t35_us (RTU) or the ASCII
                            character delay time; built without ASCII it is t35_us
                            (LINK_SILENCE, link_internal.h) */
#endif
    uint32_t t35_us;
    uint32_t t15_us;  /* 0 = no t1.5 check */
    uint32_t char_us; /* one character time; byte timestamps are character ends, so the
                         silence between two bytes is their distance minus char_us */
    uint32_t turnaround_us;
    /* receive and transmit state shared by the framings */
    uint32_t last_us;  /* time of the last received character (every state but the
                          echo of our own RS485 reply; never reset: the RXD LED reads
                          it at poll time, leds.h) */
    uint32_t tx_at_us; /* when the reply was handed over (start of the turnaround) */
    uint32_t tx_end_us; /* transmission complete of the last reply (the TXD LED) */
} modcp_link_t;

#endif
