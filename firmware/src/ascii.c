/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — Modbus ASCII framing ([ASCII-32] §2 = manual §8.1, docs/ascii-and-32bit.md): ':' + hex pairs +
 * LRC + CR LF, decoded into the same binary buffer as RTU (address at buf[0], PDU at
 * buf + 1, LRC last) while the characters arrive; the PDU engine and the mapping are
 * the ones RTU uses.
 *
 * The backend behind ascii_ops (modcp_framing_ops_t, link_internal.h; chosen by
 * ascii_configure), its state in l->fr (modcp_ascii_t below).
 *
 * Receive, by link state:
 *   IDLE  waiting for ':'. Any other character: wrong start character, event (08)38H
 *         (normal mode; interference suppression and RS485 are silent, [ASCII-32] §3.2:
 *         "the start of the receive message is recognised by the correctly received
 *         start character"), then the rest of the run of stray characters is ignored
 *         without further events until a ':' or the character delay time ends it.
 *   RX    a frame for us (or whose address is not decoded yet): characters are decoded
 *         and stored. The first byte (two hex characters) is the address: another
 *         address -> SKIP (not checked, not answered; followed for the bus counters).
 *   SKIP  following a frame that is not ours or was already found bad, to its end.
 *   EOF   CR + delimiter of a good frame received: the frame is handed over on the
 *         one-shot timer, armed with 1 us (link.c delivers frames on timer expiry).
 * End of a frame: CR followed by the input delimiter (l->ascii_delim, LF unless
 * FC08 sub-function 03 changed it). There is no t3.5 in ASCII: the character delay time
 * (ASCII timeout, 1 ... 6500 ms) is the link's silence; the timer is armed with it once,
 * at the start of a frame or of a run of stray characters, and link.c re-arms it for the
 * rest after the last character; a silence that long inside a frame for us discards it
 * with (08)06H.
 *
 * Errors inside a frame for us discard it with no reply ([ASCII-32] §8.1, §6):
 *   ':' inside the frame ............ (08)39H, reception restarts at the new ':'
 *   not 0-9 / A-F (lower case a-f is accepted), an odd number of hex characters
 *   before CR, or CR not followed by the delimiter ... (08)3AH
 *   LRC wrong, or fewer than 3 bytes (address, function, LRC) ... (08)36H
 *   more than 2 x 252 data characters ([ASCII-32] §8.1: 255 bytes from address to LRC) ... (08)16H
 *   parity / framing / overrun / BREAK ... (08)0CH / 0DH, reported by link.c (normal
 *   mode only); the frame is discarded in both modes
 *   character delay time exceeded ... (08)06H
 * Each of these counts once in BUS_CRC (FC08 0C), like rtu.c; so do the same errors in
 * another slave's frame (without an event), except an over-long frame.
 * An error after CR LF (state EOF) does not touch the frame ([RTU-2003] §2.2 "after the
 * message"). With 7 data bits the eighth bit of a received character is masked.
 *
 * While a request is processed or its reply pending (BUSY / TURNAROUND / TX / EOF)
 * characters are not stored; a ':' followed by our address or 00 (broadcast) reports (08)37H, and the
 * frame is followed to its delimiter so that link.c knows whether a frame is still
 * arriving when the reply is out (RS485: our own echo while sending is ignored).
 *
 * Transmit: the binary reply (address, PDU) gets its LRC and is hex-encoded in place
 * from the back (upper-case, high nibble first), ':' in front, CR LF behind (CR LF
 * also after FC08/03: the changed delimiter is an input delimiter). The link buffer
 * must hold 2 x (binary length) + 3 characters: MODCP_LINK_BUF_MAX = 513 bytes. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/crc.h"
#include "modcp/link.h"
#include "link_internal.h"

/* ASCII receive state, in l->fr. */
typedef struct {
    uint16_t count;  /* bytes decoded in the current frame, up to 3 (busy: address
                        decoded) */
    uint8_t lrc;     /* running byte sum */
    uint8_t hex_hi;  /* first hex character of a pair */
    bool hex_half;   /* a pair is half received */
    bool got_cr;     /* the last character was CR */
    bool in_frame;   /* a ':' started what is being followed (false: stray characters) */
    uint8_t char_mask; /* 7 data bits: 7FH, the eighth bit of a character is masked */
} modcp_ascii_t;
_Static_assert(sizeof(modcp_ascii_t) <= sizeof(modcp_link_fr_t), "modcp_link_fr_t holds it");

static modcp_ascii_t *ascii_of(modcp_link_t *l)
{
    return (modcp_ascii_t *)(void *)&l->fr;
}

static const modcp_ascii_t *ascii_of_c(const modcp_link_t *l)
{
    return (const modcp_ascii_t *)(const void *)&l->fr;
}

#define ASCII_COLON 0x3Au
#define ASCII_CR 0x0Du
#define ASCII_MIN_FRAME 3u /* address, function, LRC */
/* The longest frame ([ASCII-32] §8.1): address, function, at most 2 x 252 data characters (252
 * bytes), LRC; one more byte is an over-long frame, (08)16H. */
#define ASCII_MAX_FRAME (1u + 1u + 252u + 1u)
#define HEX_BAD 0xFFu

/* The upper-case hex digit of d (0 ... 15). */
static uint8_t hex_digit(unsigned d)
{
    return (uint8_t)(d + (d < 10u ? (unsigned)'0' : (unsigned)'A' - 10u));
}

static uint8_t hexval(uint8_t c)
{
    if ((uint8_t)(c - (uint8_t)'0') <= 9u) {
        return (uint8_t)(c - (uint8_t)'0');
    }
    c |= 0x20u; /* 'A' ... 'F' -> 'a' ... 'f' (nothing else lands there) */
    if ((uint8_t)(c - (uint8_t)'a') <= 5u) {
        return (uint8_t)(c - (uint8_t)'a' + 10u);
    }
    return HEX_BAD;
}

#define PAIR_BAD (-1)  /* hex_pair: not a hex digit (the pair is not touched) */
#define PAIR_HALF (-2) /* hex_pair: the first digit of a pair, kept */

/* A character into the hex pair being received: PAIR_BAD, PAIR_HALF, or the byte
 * (0 ... 255) the pair makes. */
static MODCP_NOINLINE int hex_pair(modcp_ascii_t *a, uint8_t c)
{
    uint8_t v = hexval(c);
    if (v == HEX_BAD) {
        return PAIR_BAD;
    }
    if (!a->hex_half) {
        a->hex_hi = v;
        a->hex_half = true;
        return PAIR_HALF;
    }
    a->hex_half = false;
    const unsigned pair = ((unsigned)a->hex_hi << 4) | (unsigned)v;
    return (int)pair;
}

/* A ':' starts a frame (in_frame; false: a run of stray characters); the timer is
 * armed here, once per frame. */
static MODCP_NOINLINE void frame_start(modcp_link_t *l, uint32_t now_us)
{
    modcp_ascii_t *a = ascii_of(l);
    l->state = MODCP_LINK_RX;
    a->in_frame = true;
    link_set_len(l, 0);
    a->count = 0;
    a->lrc = 0; /* running byte sum for the LRC */
    a->hex_half = false;
    a->hex_hi = 0;
    a->got_cr = false;
    l->rx_bad = false;
    l->rx_overflow = false;
    l->last_us = now_us;
    link_arm(l, l->silence_us);
}

/* The frame is bad: report ev for our frame (NONE: already reported by link.c) and
 * follow it to its end without storing. */
static void discard(modcp_link_t *l, modcp_event_t ev)
{
    if (l->state == (uint8_t)MODCP_LINK_RX && !l->rx_bad) {
        link_event(l, ev);
    }
    l->state = MODCP_LINK_SKIP;
    link_mark_bad(l);
}

/* CR + delimiter: the end of the frame in RX or SKIP. */
static void frame_end(modcp_link_t *l)
{
    const bool ours = l->state == (uint8_t)MODCP_LINK_RX; /* else SKIP: another slave's frame */
    link_arm(l, 0);
    l->state = MODCP_LINK_IDLE;
    if (l->rx_bad) {
        return; /* counted once already, or dropped by the link (DSR OFF) */
    }
    if (l->rx_overflow) {
        link_frame_too_long(l); /* ours only: SKIP stores nothing */
        return;
    }
    if (ascii_of(l)->count < ASCII_MIN_FRAME || ascii_of(l)->lrc != 0u) {
        if (ours) {
            link_event(l, MODCP_EV_CRC); /* [ASCII-32] §8.5 (08)36H "LRC incorrect" */
        }
        link_count(l, MODCP_CNT_BUS_CRC);
        return;
    }
    link_count(l, MODCP_CNT_BUS_MSG);
    if (ours) {
        link_count(l, MODCP_CNT_SLAVE_MSG);
        l->state = MODCP_LINK_EOF;
        link_arm(l, 1u); /* hand the frame over on the timer, as RTU does */
    }
}

/* One decoded byte of the frame in RX / SKIP. */
static void frame_byte(modcp_link_t *l, uint8_t b)
{
    modcp_ascii_t *a = ascii_of(l);
    a->lrc = (uint8_t)(a->lrc + b);
    if (a->count < ASCII_MIN_FRAME) {
        a->count++; /* only the first byte and ">= ASCII_MIN_FRAME" are looked at */
    }
    if (l->state != (uint8_t)MODCP_LINK_RX) {
        return;
    }
    if (a->count == 1u && b != l->own_addr && b != 0u) {
        l->state = MODCP_LINK_SKIP; /* another slave's frame: not checked, not answered */
        return;
    }
    if (link_len(l) < l->cap && link_len(l) < ASCII_MAX_FRAME) { /* no buffer: cap 0 */
        l->buf[link_len(l)] = b;
        link_set_len(l, (uint16_t)(link_len(l) + 1u));
    } else {
        l->rx_overflow = true;
    }
}

/* A character in RX / SKIP (a frame or a run of stray characters). */
static void frame_char(modcp_link_t *l, uint8_t c, uint32_t now_us)
{
    modcp_ascii_t *a = ascii_of(l);
    if (c == ASCII_COLON) {
        if (a->in_frame) {
            /* the first part is discarded ([ASCII-32] §8.5 (08)39H; another slave's: silently) */
            discard(l, MODCP_EV_ASCII_RESTART);
        }
        frame_start(l, now_us);
        return;
    }
    l->last_us = now_us;
    if (!a->in_frame) {
        return; /* stray characters before a start character */
    }
    if (a->got_cr || c == ASCII_CR) {
        if (a->got_cr && c == l->ascii_delim) {
            frame_end(l);
            return;
        }
        if (a->got_cr || a->hex_half) { /* (after CR no pair is half received) */
            /* CR not followed by the delimiter, or an odd number of hex characters */
            a->hex_half = false;
            discard(l, MODCP_EV_ASCII_NOT_HEX);
        }
        a->got_cr = c == ASCII_CR;
        return;
    }
    int v = hex_pair(a, c);
    if (v == PAIR_BAD) {
        discard(l, MODCP_EV_ASCII_NOT_HEX);
    } else if (v >= 0) {
        frame_byte(l, (uint8_t)v);
    } else {
        /* the first character of a pair: kept */
    }
}

/* A character while a request is processed or its reply pending. */
static void busy_track(modcp_link_t *l, uint8_t c, uint32_t now_us)
{
    modcp_ascii_t *a = ascii_of(l);
    if (l->rs485 && l->state == (uint8_t)MODCP_LINK_TX) {
        return; /* echo of our own transmission */
    }
    l->last_us = now_us;
    if (c == ASCII_COLON) {
        l->busy_rx = true;
        a->count = 0;
        a->hex_half = false;
        a->got_cr = false;
        return;
    }
    if (!l->busy_rx) {
        return;
    }
    if (a->got_cr && c == l->ascii_delim) {
        l->busy_rx = false; /* that frame is complete */
        a->got_cr = false;
        return;
    }
    a->got_cr = c == ASCII_CR;
    if (a->count != 0u) {
        return; /* the address is decoded */
    }
    int v = hex_pair(a, c);
    if (v < 0) {
        return; /* not a hex digit, or half a pair */
    }
    a->count = 1;
    if ((uint8_t)v == l->own_addr || v == 0) { /* for us or broadcast: see rtu_busy_track */
        link_event(l, MODCP_EV_SEQUENCE);
    }
}

static void ascii_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    b &= ascii_of(l)->char_mask;
    switch (l->state) {
    case MODCP_LINK_IDLE:
        if (b == ASCII_COLON) {
            frame_start(l, now_us);
            break;
        }
        if (!l->suppress && !l->rs485) { /* RS485: between frames ([RTU-2009] §5.6.5) */
            link_event(l, MODCP_EV_ASCII_START);
        }
        l->state = MODCP_LINK_SKIP; /* ignore the rest of the stray characters */
        ascii_of(l)->in_frame = false;
        l->rx_bad = true;
        l->last_us = now_us;
        link_arm(l, l->silence_us); /* once, for the whole run */
        break;
    case MODCP_LINK_RX:
    case MODCP_LINK_SKIP:
        frame_char(l, b, now_us);
        break;
    default: /* EOF, BUSY, TURNAROUND, TX */
        busy_track(l, b, now_us);
        break;
    }
}

static void ascii_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    (void)line_errors; /* every kind of error has the same effect on framing */
    if (!link_receiving(l->state)) {
        return; /* between frames, after CR LF, or while busy: the frame is not touched */
    }
    if (!ascii_of(l)->in_frame) {
        return; /* among stray characters */
    }
    discard(l, MODCP_EV_NONE); /* link.c reported it (normal mode) */
    ascii_of(l)->got_cr = false;
    l->last_us = now_us;
}

/* RS485 normal mode (link.c error_reported): a ':' started what is followed. */
static bool ascii_in_frame(const modcp_link_t *l)
{
    return ascii_of_c(l)->in_frame;
}

/* EOF: hand the frame over. RX / SKIP: the character delay time has passed since the
 * last character (link.c checked it). */
static bool ascii_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    (void)now_us;
    if (l->state == (uint8_t)MODCP_LINK_EOF) {
        uint32_t room = ((uint32_t)l->size - 3u) / 2u; /* binary bytes the reply may have */
        if (room > l->cap) {
            room = l->cap;
        }
        f->addr = l->buf[0];
        f->pdu = &l->buf[1];
        f->pdu_len = (uint16_t)(link_len(l) - 2u); /* without address and LRC */
        f->pdu_cap = (uint16_t)(room - 2u);
        l->state = MODCP_LINK_BUSY;
        l->busy_rx = false;
        return true;
    }
    if (!link_receiving(l->state)) {
        return false; /* stale or spurious expiry */
    }
    if (ascii_of(l)->in_frame) {
        discard(l, MODCP_EV_ZVZ); /* character delay time exceeded inside a frame */
    }
    l->state = MODCP_LINK_IDLE;
    return false;
}

static uint16_t ascii_encode(modcp_link_t *l, uint16_t pdu_len)
{
    const uint32_t n = 1u + (uint32_t)pdu_len;    /* address + PDU */
    const uint32_t out = 1u + 2u * (n + 1u) + 2u; /* ':' hex(address PDU LRC) CR LF */
    if (out > (uint32_t)l->size) { /* no buffer: size 0 */
        return 0;
    }
    l->buf[n] = modcp_lrc(l->buf, n);
    /* in place from the back: byte i goes to 1 + 2i and 2 + 2i, both beyond i */
    uint32_t i = n + 1u;
    while (i > 0u) {
        i--;
        const uint8_t b = l->buf[i];
        l->buf[1u + 2u * i] = hex_digit(b >> 4);
        l->buf[2u + 2u * i] = hex_digit(b & 0x0Fu);
    }
    l->buf[0] = (uint8_t)ASCII_COLON;
    l->buf[out - 2u] = (uint8_t)ASCII_CR;
    l->buf[out - 1u] = 0x0Au; /* LF */
    return (uint16_t)out;
}

static const modcp_framing_ops_t ascii_ops = {.on_byte = ascii_on_byte,
                                              .on_error = ascii_on_error,
                                              .in_frame = ascii_in_frame,
                                              .on_timer = ascii_on_timer,
                                              .encode = ascii_encode};

const modcp_framing_ops_t *ascii_configure(modcp_link_t *l, const modcp_params_t *p)
{
    ascii_of(l)->char_mask = p->data_bits == 7u ? 0x7Fu : 0xFFu;
    /* the character delay time plays t3.5's part */
    l->silence_us = (uint32_t)p->ascii_timeout_ms * 1000u;
    return l->cap >= ASCII_MIN_FRAME && l->size >= 11u ? &ascii_ops : NULL;
}
