/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the Wireshark capture (--capture FILE.pcap), an observer of the line.
 *
 * Classic pcap (microsecond time stamps), link type 252 (LINKTYPE_WIRESHARK_UPPER_PDU,
 * "exported PDU"): every record names the dissector that decodes it, so Wireshark and
 * tshark decode the frames with no setting of the user's:
 *   an RTU frame          dissector "mbrtu" (Modbus RTU: unit id, function, CRC check)
 *   an ASCII frame        "data-text-lines" with the protocol column "MODBUS/ASCII"
 *                         (Wireshark has no Modbus ASCII dissector: the line as text)
 *   a collided frame      "data" with the protocol column "COLLISION": what its sender
 *                         sent while another member (or the noise) sent too (what the
 *                         line carried then is in the trace and the waveform)
 *   noise (the fault)     "data" with the protocol column "NOISE" (collided or not)
 *   a line event          "data-text-lines" with the protocol column "LINE": parity or
 *                         framing error, BREAK, DE released early, as one line of text;
 *                         and a member's driver enable: "DE on (@a)" at its frame's
 *                         first start bit, "DE off (@a)" at the end of its last stop bit
 *                         (or where it was cut)
 * A record's time is the start of the first start bit of its first character (a line
 * event: of its character). The sender is in the record: the exported PDU's P2P
 * direction (0 = sent by the master, 1 = by a slave) and its source port: 0 for the
 * master, 1 + the member's index (@a = 1, @b = 2 ...) for a member, 65535 for the
 * noise; the destination port is 0 for replies, 65535 for requests.
 * Each source's frames are gathered apart (the master's pty is a line of its own: its
 * request may overlap the end of a reply, see docs/simulator.md); a frame ends at a gap
 * of t3.5 after its last character (RTU; ASCII: after LF or the character timeout),
 * and the frames that end are written in the order of their first characters. */
#define _GNU_SOURCE
#include "capture.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINKTYPE_WIRESHARK_UPPER_PDU 252u
#define TAG_DISSECTOR_NAME 12u
#define TAG_PORT_TYPE 24u
#define TAG_SRC_PORT 25u
#define TAG_DST_PORT 26u
#define TAG_COL_PROT_TEXT 33u
#define TAG_P2P_DIRECTION 35u
#define PT_UDP 3u
#define MAX_FRAME 1024u
#define MAX_NOTES 8u

#define NSLOT (2 + SIM_LINE_MAX_MEMBERS)

typedef struct {
    int src;
    uint8_t b[MAX_FRAME];
    size_t n;
    uint64_t t0, end;
    uint64_t de_end; /* a member's driver enable goes off (the end, or where it was cut) */
    bool collided; /* another member or the noise sent at the same time */
    /* line events inside it: written after it */
    char note[MAX_NOTES][96];
    uint64_t note_t[MAX_NOTES];
    size_t nn;
} frame_t;

struct sim_capture {
    sim_observer_t obs; /* first: the line calls it */
    const sim_line_t *line;
    FILE *f;
    frame_t fr[NSLOT]; /* the frame being gathered, per source */
    uint32_t records;
};

static void put16(uint8_t *p, unsigned v)
{
    p[0] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)v;
}

static void put32be(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static void put32le(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* One tag (value padded to 4 bytes) at p; returns its size. */
static size_t tag(uint8_t *p, unsigned type, const void *v, size_t len)
{
    size_t padded = (len + 3u) & ~(size_t)3u;
    put16(p, type);
    put16(p + 2, (unsigned)padded);
    memset(p + 4, 0, padded);
    memcpy(p + 4, v, len);
    return 4u + padded;
}

static size_t tag32(uint8_t *p, unsigned type, uint32_t v)
{
    uint8_t b[4];
    put32be(b, v);
    return tag(p, type, b, 4u);
}

static void record(sim_capture_t *c, uint64_t t, const char *dissector, const char *proto, int src,
                   const uint8_t *data, size_t len)
{
    uint8_t buf[256 + MAX_FRAME];
    size_t k = 16; /* the record header, below */
    k += tag(buf + k, TAG_DISSECTOR_NAME, dissector, strlen(dissector));
    if (proto != NULL) {
        k += tag(buf + k, TAG_COL_PROT_TEXT, proto, strlen(proto));
    }
    k += tag32(buf + k, TAG_P2P_DIRECTION, src == SIM_SRC_MASTER ? 0u : 1u);
    k += tag32(buf + k, TAG_PORT_TYPE, PT_UDP);
    uint32_t sport = src == SIM_SRC_MASTER ? 0u : src >= 0 ? (uint32_t)src + 1u : 65535u;
    k += tag32(buf + k, TAG_SRC_PORT, sport);
    k += tag32(buf + k, TAG_DST_PORT, src == SIM_SRC_MASTER ? 65535u : 0u);
    put16(buf + k, 0u); /* end of options */
    put16(buf + k + 2u, 0u);
    k += 4u;
    if (len > sizeof buf - k) {
        len = sizeof buf - k;
    }
    memcpy(buf + k, data, len);
    k += len;
    uint64_t ts = c->line->t0_real_us + t;
    put32le(buf, (uint32_t)(ts / 1000000u));
    put32le(buf + 4, (uint32_t)(ts % 1000000u));
    put32le(buf + 8, (uint32_t)(k - 16u));
    put32le(buf + 12, (uint32_t)(k - 16u));
    (void)fwrite(buf, 1, k, c->f);
    c->records++;
}

/* "DE on (@a)" / "DE off (@a)": a member's driver enable around its frame. */
static void de_record(sim_capture_t *c, const frame_t *fr, bool on)
{
    char txt[64];
    snprintf(txt, sizeof txt, "DE %s (%s)\n", on ? "on" : "off", sim_line_src_name(c->line, fr->src));
    record(c, on ? fr->t0 : fr->de_end, "data-text-lines", "LINE", fr->src, (const uint8_t *)txt,
           strlen(txt));
}

static void flush_frame(sim_capture_t *c, frame_t *fr)
{
    bool de = fr->src >= 0 && fr->n > 0u;
    if (de) {
        de_record(c, fr, true);
    }
    if (fr->n > 0u) {
        if (fr->src == SIM_SRC_NOISE) {
            record(c, fr->t0, "data", "NOISE", fr->src, fr->b, fr->n);
        } else if (fr->collided) {
            record(c, fr->t0, "data", "COLLISION", fr->src, fr->b, fr->n);
        } else if (c->line->cfg.ascii) {
            record(c, fr->t0, "data-text-lines", "MODBUS/ASCII", fr->src, fr->b, fr->n);
        } else {
            record(c, fr->t0, "mbrtu", NULL, fr->src, fr->b, fr->n);
        }
    }
    for (size_t i = 0; i < fr->nn; i++) {
        record(c, fr->note_t[i], "data-text-lines", "LINE", fr->src, (const uint8_t *)fr->note[i],
               strlen(fr->note[i]));
    }
    if (de) {
        de_record(c, fr, false);
    }
    fr->n = 0;
    fr->nn = 0;
    fr->collided = false;
}

/* Writes the frames that ended by t (all: UINT64_MAX), oldest first. */
static void flush_due(sim_capture_t *c, uint64_t t)
{
    for (;;) {
        frame_t *first = NULL;
        for (size_t i = 0; i < NSLOT; i++) {
            frame_t *fr = &c->fr[i];
            bool open = fr->n > 0u || fr->nn > 0u;
            bool lf = c->line->cfg.ascii && fr->n > 0u && fr->b[fr->n - 1u] == '\n';
            bool due = t == UINT64_MAX || lf || t >= fr->end + c->line->cfg.t35_us;
            if (open && due && (first == NULL || fr->t0 < first->t0)) {
                first = fr;
            }
        }
        if (first == NULL) {
            return;
        }
        flush_frame(c, first);
    }
}

static void note(sim_capture_t *c, frame_t *fr, const sim_char_t *ch, const char *what)
{
    if (fr->nn < MAX_NOTES) {
        snprintf(fr->note[fr->nn], sizeof fr->note[fr->nn], "%s (%s)\n", what,
                 sim_line_src_name(c->line, ch->src));
        fr->note_t[fr->nn++] = ch->t_us;
    }
}

static void line_events(sim_capture_t *c, frame_t *fr, const sim_char_t *ch)
{
    char what[80];
    if ((ch->flags & SIM_CH_BREAK) != 0u) {
        snprintf(what, sizeof what, "BREAK %u.%03u ms", (unsigned)(ch->len_us / 1000u),
                 (unsigned)(ch->len_us % 1000u));
        note(c, fr, ch, what);
        return;
    }
    if ((ch->flags & SIM_CH_PARITY) != 0u) {
        snprintf(what, sizeof what, "parity error on byte %zu (0x%02X)", fr->n, ch->byte);
        note(c, fr, ch, what);
    }
    if ((ch->flags & SIM_CH_FRAMING) != 0u) {
        snprintf(what, sizeof what, "framing error on byte %zu (0x%02X)", fr->n, ch->byte);
        note(c, fr, ch, what);
    }
    if ((ch->flags & SIM_CH_DE_CUT) != 0u) {
        snprintf(what, sizeof what, "DE released %u us into byte %zu (0x%02X): truncated",
                 (unsigned)ch->de_off_us, fr->n, ch->byte);
        note(c, fr, ch, what);
    }
}

static void on_char(sim_observer_t *o, const sim_char_t *ch)
{
    sim_capture_t *c = (sim_capture_t *)o;
    flush_due(c, ch->t_us);
    frame_t *fr = &c->fr[ch->src + 2 < (int)NSLOT ? ch->src + 2 : 0];
    if (fr->n == 0u && fr->nn == 0u) {
        fr->src = ch->src;
        fr->t0 = ch->t_us;
    }
    if ((ch->flags & SIM_CH_COLLIDED) != 0u) {
        fr->collided = true;
    }
    line_events(c, fr, ch);
    if ((ch->flags & SIM_CH_BREAK) == 0u && fr->n < MAX_FRAME) {
        fr->b[fr->n++] = ch->byte;
    }
    fr->end = ch->t_us + ch->len_us;
    fr->de_end = (ch->flags & SIM_CH_DE_CUT) != 0u ? ch->t_us + ch->de_off_us : fr->end;
}

static void on_close(sim_observer_t *o)
{
    sim_capture_t *c = (sim_capture_t *)o;
    flush_due(c, UINT64_MAX);
    fflush(c->f);
}

sim_capture_t *sim_capture_open(const sim_line_t *line, const char *path, char *err, size_t cap)
{
    sim_capture_t *c = calloc(1, sizeof *c);
    if (c == NULL) {
        snprintf(err, cap, "out of memory");
        return NULL;
    }
    c->f = fopen(path, "wb");
    if (c->f == NULL) {
        snprintf(err, cap, "cannot write %s: %s", path, strerror(errno));
        free(c);
        return NULL;
    }
    c->obs.on_char = on_char;
    c->obs.on_close = on_close;
    c->line = line;
    uint8_t h[24];
    put32le(h, 0xA1B2C3D4u); /* microseconds */
    h[4] = 2;
    h[5] = 0;
    h[6] = 4;
    h[7] = 0;
    put32le(h + 8, 0u);
    put32le(h + 12, 0u);
    put32le(h + 16, 65535u);
    put32le(h + 20, LINKTYPE_WIRESHARK_UPPER_PDU);
    (void)fwrite(h, 1, sizeof h, c->f);
    return c;
}

sim_observer_t *sim_capture_observer(sim_capture_t *c)
{
    return &c->obs;
}

uint32_t sim_capture_close(sim_capture_t *c)
{
    if (c == NULL) {
        return 0;
    }
    uint32_t n = c->records;
    fclose(c->f);
    free(c);
    return n;
}
