/* modcp — Modbus ASCII framing (003 §2 = manual §8.1, SPEC §3.2): ':' + hex pairs +
 * LRC + CR LF, decoded into the same binary buffer as RTU (address at buf[0], PDU at
 * buf + 1, LRC last) while the characters arrive; the PDU engine and the mapping are
 * the ones RTU uses.
 *
 * Receive, by link state:
 *   IDLE  waiting for ':'. Any other character: wrong start character, event (08)38H
 *         (normal mode; interference suppression and RS485 are silent, 003 §3.2:
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
 * FC08 sub-function 03 changed it). There is no t3.5 in ASCII: every character in a
 * frame (RX / SKIP) re-arms the timer with the character delay time (ASCII timeout,
 * 1 ... 6500 ms); its expiry inside a frame for us discards it with (08)06H.
 *
 * Errors inside a frame for us discard it with no reply (003 §8.1, §6):
 *   ':' inside the frame ............ (08)39H, reception restarts at the new ':'
 *   not 0-9 / A-F (lower case a-f is accepted), an odd number of hex characters
 *   before CR, or CR not followed by the delimiter ... (08)3AH
 *   LRC wrong, or fewer than 3 bytes (address, function, LRC) ... (08)36H
 *   more bytes than the receive buffer (MODCP_ADU_MAX) ... (08)16H
 *   parity / framing / overrun / BREAK ... (08)0CH / 0DH, reported by link.c (normal
 *   mode only); the frame is discarded in both modes
 *   character delay time exceeded ... (08)06H
 * Each of these counts once in BUS_CRC (FC08 0C), like rtu.c; so do the same errors in
 * another slave's frame (without an event), except an over-long frame.
 * An error after CR LF (state EOF) does not touch the frame (004 §2.2 "after the
 * message"). With 7 data bits the eighth bit of a received character is masked.
 *
 * While a request is processed or its reply pending (BUSY / TURNAROUND / TX / EOF)
 * characters are not stored; a ':' followed by our address reports (08)37H, and the
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

#define ASCII_COLON 0x3Au
#define ASCII_CR 0x0Du
#define ASCII_MIN_FRAME 3u /* address, function, LRC */
#define HEX_BAD 0xFFu

static const char hex_digits[16] = {'0', '1', '2', '3', '4', '5', '6', '7',
                                    '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};

static uint8_t hexval(uint8_t c)
{
    if (c >= (uint8_t)'0' && c <= (uint8_t)'9') {
        return (uint8_t)(c - (uint8_t)'0');
    }
    if (c >= (uint8_t)'A' && c <= (uint8_t)'F') {
        return (uint8_t)(c - (uint8_t)'A' + 10u);
    }
    if (c >= (uint8_t)'a' && c <= (uint8_t)'f') {
        return (uint8_t)(c - (uint8_t)'a' + 10u);
    }
    return HEX_BAD;
}

/* A ':' starts a frame (l->first = ':' marks a frame, 0 a run of stray characters). */
static void frame_start(modcp_link_t *l, uint32_t now_us)
{
    l->state = MODCP_LINK_RX;
    l->first = (uint8_t)ASCII_COLON;
    l->len = 0;
    l->count = 0;
    l->crc = 0; /* running byte sum for the LRC */
    l->hex_half = false;
    l->hex_hi = 0;
    l->got_cr = false;
    l->rx_bad = false;
    l->rx_overflow = false;
    l->last_us = now_us;
    link_arm(l, l->ascii_timeout_us);
}

/* The frame is bad: report ev for our frame (NONE: already reported by link.c) and
 * follow it to its end without storing. */
static void discard(modcp_link_t *l, modcp_event_t ev)
{
    if (l->state == MODCP_LINK_RX && !l->rx_bad) {
        link_event(l, ev);
    }
    l->state = MODCP_LINK_SKIP;
    link_mark_bad(l);
}

/* CR + delimiter: the end of the frame in RX or SKIP. */
static void frame_end(modcp_link_t *l)
{
    const bool lrc_ok = l->count >= ASCII_MIN_FRAME && (l->crc & 0xFFu) == 0u;
    link_arm(l, 0);
    if (l->state == MODCP_LINK_SKIP) {
        if (!l->rx_bad) {
            link_count(l, lrc_ok ? MODCP_CNT_BUS_MSG : MODCP_CNT_BUS_CRC);
        }
        l->state = MODCP_LINK_IDLE;
        return;
    }
    l->state = MODCP_LINK_IDLE;
    if (l->rx_bad) {
        return; /* dropped by the link (modcp_link_rx_discard: DSR OFF) */
    }
    if (l->rx_overflow) {
        if (l->diag != NULL) {
            l->diag->frames_too_long = (uint16_t)(l->diag->frames_too_long + 1u);
        }
        link_event(l, MODCP_EV_FRAME_TOO_LONG);
        return;
    }
    if (!lrc_ok) {
        link_event(l, MODCP_EV_CRC); /* 003 §8.5 (08)36H "LRC incorrect" */
        link_count(l, MODCP_CNT_BUS_CRC);
        return;
    }
    link_count(l, MODCP_CNT_BUS_MSG);
    link_count(l, MODCP_CNT_SLAVE_MSG);
    l->state = MODCP_LINK_EOF;
    link_arm(l, 1u); /* hand the frame over on the timer, as RTU does */
}

/* One decoded byte of the frame in RX / SKIP. */
static void frame_byte(modcp_link_t *l, uint8_t b)
{
    l->crc = (uint16_t)((l->crc + b) & 0xFFu);
    if (l->count < UINT16_MAX) {
        l->count++;
    }
    if (l->state != MODCP_LINK_RX) {
        return;
    }
    if (l->count == 1u && b != l->own_addr && b != 0u) {
        l->state = MODCP_LINK_SKIP; /* another slave's frame: not checked, not answered */
        return;
    }
    if (l->buf != NULL && l->len < l->cap) {
        l->buf[l->len] = b;
        l->len++;
    } else {
        l->rx_overflow = true;
    }
}

/* A character in RX / SKIP (a frame or a run of stray characters). */
static void frame_char(modcp_link_t *l, uint8_t c, uint32_t now_us)
{
    if (c == ASCII_COLON) {
        if (l->first == ASCII_COLON) {
            /* the first part is discarded (003 §8.5 (08)39H; another slave's: silently) */
            discard(l, MODCP_EV_ASCII_RESTART);
        }
        frame_start(l, now_us);
        return;
    }
    l->last_us = now_us;
    link_arm(l, l->ascii_timeout_us);
    if (l->first != ASCII_COLON) {
        return; /* stray characters before a start character */
    }
    if (l->got_cr) {
        if (c == l->ascii_delim) {
            frame_end(l);
            return;
        }
        discard(l, MODCP_EV_ASCII_NOT_HEX); /* CR not followed by the delimiter */
        l->got_cr = c == ASCII_CR;
        return;
    }
    if (c == ASCII_CR) {
        l->got_cr = true;
        if (l->hex_half) {
            l->hex_half = false;
            discard(l, MODCP_EV_ASCII_NOT_HEX); /* odd number of hex characters */
        }
        return;
    }
    uint8_t v = hexval(c);
    if (v == HEX_BAD) {
        discard(l, MODCP_EV_ASCII_NOT_HEX);
        return;
    }
    if (!l->hex_half) {
        l->hex_hi = v;
        l->hex_half = true;
        return;
    }
    l->hex_half = false;
    frame_byte(l, (uint8_t)((unsigned)l->hex_hi << 4 | v));
}

/* A character while a request is processed or its reply pending. */
static void busy_track(modcp_link_t *l, uint8_t c, uint32_t now_us)
{
    if (l->rs485 && l->state == MODCP_LINK_TX) {
        return; /* echo of our own transmission */
    }
    l->last_us = now_us;
    if (c == ASCII_COLON) {
        l->busy_rx = true;
        l->count = 0;
        l->hex_half = false;
        l->got_cr = false;
        return;
    }
    if (!l->busy_rx) {
        return;
    }
    if (l->got_cr && c == l->ascii_delim) {
        l->busy_rx = false; /* that frame is complete */
        l->got_cr = false;
        return;
    }
    l->got_cr = c == ASCII_CR;
    uint8_t v = hexval(c);
    if (v == HEX_BAD || l->count != 0u) {
        return;
    }
    if (!l->hex_half) {
        l->hex_hi = v;
        l->hex_half = true;
        return;
    }
    l->hex_half = false;
    l->count = 1;
    if ((uint8_t)((unsigned)l->hex_hi << 4 | v) == l->own_addr) {
        link_event(l, MODCP_EV_SEQUENCE);
    }
}

void modcp_ascii_on_byte(modcp_link_t *l, uint8_t b, uint32_t now_us)
{
    if (l->ascii7) {
        b &= 0x7Fu;
    }
    switch (l->state) {
    case MODCP_LINK_IDLE:
        if (b == ASCII_COLON) {
            frame_start(l, now_us);
            break;
        }
        if (!l->suppress) {
            link_event(l, MODCP_EV_ASCII_START);
        }
        l->state = MODCP_LINK_SKIP; /* ignore the rest of the stray characters */
        l->first = 0;
        l->rx_bad = true;
        l->last_us = now_us;
        link_arm(l, l->ascii_timeout_us);
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

void modcp_ascii_on_error(modcp_link_t *l, uint8_t line_errors, uint32_t now_us)
{
    (void)line_errors; /* every kind of error has the same effect on framing */
    if (l->state != MODCP_LINK_RX && l->state != MODCP_LINK_SKIP) {
        return; /* between frames, after CR LF, or while busy: the frame is not touched */
    }
    if (l->first != ASCII_COLON) {
        return; /* among stray characters */
    }
    discard(l, MODCP_EV_NONE); /* link.c reported it (normal mode) */
    l->got_cr = false;
    l->last_us = now_us;
    link_arm(l, l->ascii_timeout_us);
}

bool modcp_ascii_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f)
{
    if (l->state == MODCP_LINK_EOF) {
        if (f == NULL || l->buf == NULL) {
            l->state = MODCP_LINK_IDLE;
            return false;
        }
        uint32_t room = ((uint32_t)l->size - 3u) / 2u; /* binary bytes the reply may have */
        if (room > l->cap) {
            room = l->cap;
        }
        f->addr = l->buf[0];
        f->pdu = &l->buf[1];
        f->pdu_len = (uint16_t)(l->len - 2u); /* without address and LRC */
        f->pdu_cap = (uint16_t)(room - 2u);
        l->state = MODCP_LINK_BUSY;
        l->busy_rx = false;
        return true;
    }
    if (l->state != MODCP_LINK_RX && l->state != MODCP_LINK_SKIP) {
        return false; /* stale or spurious expiry */
    }
    uint32_t gap = now_us - l->last_us;
    if (gap < l->ascii_timeout_us) {
        link_arm(l, l->ascii_timeout_us - gap); /* an expiry that raced a character */
        return false;
    }
    if (l->first == ASCII_COLON) {
        discard(l, MODCP_EV_ZVZ); /* character delay time exceeded inside a frame */
    }
    l->state = MODCP_LINK_IDLE;
    return false;
}

uint16_t modcp_ascii_encode(modcp_link_t *l, uint16_t pdu_len)
{
    const uint32_t n = 1u + (uint32_t)pdu_len;    /* address + PDU */
    const uint32_t out = 1u + 2u * (n + 1u) + 2u; /* ':' hex(address PDU LRC) CR LF */
    if (l->buf == NULL || out > (uint32_t)l->size) {
        return 0;
    }
    l->buf[n] = modcp_lrc(l->buf, n);
    /* in place from the back: byte i goes to 1 + 2i and 2 + 2i, both beyond i */
    for (uint32_t i = n + 1u; i-- > 0u;) {
        uint8_t b = l->buf[i];
        l->buf[1u + 2u * i] = (uint8_t)hex_digits[b >> 4];
        l->buf[2u + 2u * i] = (uint8_t)hex_digits[b & 0x0Fu];
    }
    l->buf[0] = (uint8_t)ASCII_COLON;
    l->buf[out - 2u] = (uint8_t)ASCII_CR;
    l->buf[out - 1u] = 0x0Au; /* LF */
    return (uint16_t)out;
}
