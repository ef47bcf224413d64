/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — frame trace (see trace.h). */
#include "trace.h"

#include <stdio.h>
#include <string.h>

#include "modcp/crc.h"
#include "modcp/diag.h"

static uint16_t be16(const uint8_t *p)
{
    return (uint16_t)(((unsigned)p[0] << 8) | p[1]);
}

static const char *fc_name(uint8_t fc)
{
    switch (fc) {
    case 0x01: return "read coils";
    case 0x02: return "read discrete inputs";
    case 0x03: return "read holding registers";
    case 0x04: return "read input registers";
    case 0x05: return "write single coil";
    case 0x06: return "write single register";
    case 0x08: return "diagnostics";
    case 0x0B: return "get comm event counter";
    case 0x0C: return "get comm event log";
    case 0x0F: return "write multiple coils";
    case 0x10: return "write multiple registers";
    case 0x11: return "report slave ID";
    case 0x16: return "mask write register";
    case 0x17: return "read/write multiple registers";
    case 0x2B: return "encapsulated interface (read device identification)";
    default: return "unknown function";
    }
}

static const char *exc_name(uint8_t code)
{
    switch (code) {
    case 1: return "illegal function";
    case 2: return "illegal data address";
    case 3: return "illegal data value";
    case 4: return "slave device failure";
    default: return "unknown exception";
    }
}

/* A reply's meaning (not an exception). */
static void describe_reply(uint8_t fc, const uint8_t *d, size_t n, char *out, size_t cap)
{
    switch (fc) {
    case 0x01: case 0x02: case 0x03: case 0x04: case 0x0C: case 0x11: case 0x17:
        snprintf(out, cap, "FC%02u reply, %u data bytes", (unsigned)fc, n >= 1u ? (unsigned)d[0] : 0u);
        return;
    case 0x05: case 0x06:
        if (n >= 4u) {
            snprintf(out, cap, "FC%02u reply addr 0x%04X (%u) value 0x%04X", (unsigned)fc,
                     be16(d), be16(d), be16(d + 2));
            return;
        }
        break;
    case 0x0F: case 0x10:
        if (n >= 4u) {
            snprintf(out, cap, "FC%02u reply addr 0x%04X (%u) qty %u", (unsigned)fc, be16(d),
                     be16(d), be16(d + 2));
            return;
        }
        break;
    case 0x08:
        if (n >= 4u) {
            snprintf(out, cap, "FC08 reply sub 0x%04X data 0x%04X", be16(d), be16(d + 2));
            return;
        }
        break;
    default: break;
    }
    snprintf(out, cap, "FC%02u reply (%s), %zu bytes", (unsigned)fc, fc_name(fc), n);
}

/* A request's meaning. */
static void describe_request(uint8_t fc, const uint8_t *d, size_t n, char *out, size_t cap)
{
    switch (fc) {
    case 0x01: case 0x02: case 0x03: case 0x04:
        if (n >= 4u) {
            snprintf(out, cap, "FC%02u %s addr 0x%04X (%u) qty %u", (unsigned)fc, fc_name(fc), be16(d),
                     be16(d), be16(d + 2));
            return;
        }
        break;
    case 0x05:
        if (n >= 4u) {
            uint16_t v = be16(d + 2);
            snprintf(out, cap, "FC05 %s addr 0x%04X (%u) value 0x%04X (%s)", fc_name(fc), be16(d),
                     be16(d), v, v == 0xFF00u ? "on" : (v == 0u ? "off" : "invalid"));
            return;
        }
        break;
    case 0x06:
        if (n >= 4u) {
            snprintf(out, cap, "FC06 %s addr 0x%04X (%u) value 0x%04X", fc_name(fc), be16(d), be16(d),
                     be16(d + 2));
            return;
        }
        break;
    case 0x08:
        if (n >= 4u) {
            snprintf(out, cap, "FC08 %s sub 0x%04X data 0x%04X", fc_name(fc), be16(d), be16(d + 2));
            return;
        }
        break;
    case 0x0F: case 0x10:
        if (n >= 5u) {
            snprintf(out, cap, "FC%02u %s addr 0x%04X (%u) qty %u, %u data bytes", (unsigned)fc,
                     fc_name(fc), be16(d), be16(d), be16(d + 2), (unsigned)d[4]);
            return;
        }
        break;
    case 0x16:
        if (n >= 6u) {
            snprintf(out, cap, "FC22 %s addr 0x%04X (%u) and 0x%04X or 0x%04X", fc_name(fc), be16(d),
                     be16(d), be16(d + 2), be16(d + 4));
            return;
        }
        break;
    case 0x17:
        if (n >= 9u) {
            snprintf(out, cap, "FC23 %s read addr 0x%04X qty %u, write addr 0x%04X qty %u",
                     fc_name(fc), be16(d), be16(d + 2), be16(d + 4), be16(d + 6));
            return;
        }
        break;
    case 0x2B:
        if (n >= 3u) {
            snprintf(out, cap, "FC43 MEI 0x%02X read device identification code %u object 0x%02X",
                     (unsigned)d[0], (unsigned)d[1], (unsigned)d[2]);
            return;
        }
        break;
    case 0x0B: case 0x0C: case 0x11:
        snprintf(out, cap, "FC%02u %s", (unsigned)fc, fc_name(fc));
        return;
    default:
        snprintf(out, cap, "FC%02u (0x%02X) %s", (unsigned)fc, (unsigned)fc, fc_name(fc));
        return;
    }
    snprintf(out, cap, "FC%02u %s, short request (%zu data bytes)", (unsigned)fc, fc_name(fc), n);
}

void sim_describe_pdu(const uint8_t *pdu, size_t len, bool reply, char *out, size_t cap)
{
    if (len == 0u) {
        snprintf(out, cap, "empty PDU");
        return;
    }
    uint8_t fc = pdu[0];
    if (reply && (fc & 0x80u) != 0u) {
        uint8_t code = len >= 2u ? pdu[1] : 0u;
        snprintf(out, cap, "FC%02u exception %02X (%s)", (unsigned)(fc & 0x7Fu), (unsigned)code,
                 exc_name(code));
        return;
    }
    const uint8_t *d = pdu + 1;
    size_t n = len - 1u;
    if (reply) {
        describe_reply(fc, d, n, out, cap);
    } else {
        describe_request(fc, d, n, out, cap);
    }
}

void sim_trace_init(sim_trace_t *t, uint8_t own_addr, bool ascii, uint64_t gap_us,
                    void (*print)(void *user, const char *line), void *user)
{
    memset(t, 0, sizeof *t);
    t->own_addr = own_addr;
    t->ascii = ascii;
    t->gap_us = gap_us;
    t->print = print;
    t->user = user;
    snprintf(t->rx_label, sizeof t->rx_label, "master");
    snprintf(t->tx_label, sizeof t->tx_label, "slave %u", (unsigned)own_addr);
}

void sim_trace_labels(sim_trace_t *t, const char *rx, const char *tx, const char *ev)
{
    if (rx != NULL) {
        snprintf(t->rx_label, sizeof t->rx_label, "%s", rx);
    }
    if (tx != NULL) {
        snprintf(t->tx_label, sizeof t->tx_label, "%s", tx);
    }
    if (ev != NULL) {
        snprintf(t->ev_label, sizeof t->ev_label, "%s", ev);
    }
}

int sim_hex_value(uint8_t c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    return -1;
}

/* ":0503...LRC\r\n" -> bytes; returns false when it is not a well-formed ASCII frame. */
static bool ascii_decode(const uint8_t *in, size_t n, uint8_t *out, size_t cap, size_t *out_len)
{
    if (n < 3u || in[0] != ':') {
        return false;
    }
    size_t end = n;
    while (end > 1u && (in[end - 1u] == '\n' || in[end - 1u] == '\r')) {
        end--;
    }
    if ((end - 1u) % 2u != 0u) {
        *out_len = end - 1u; /* the caller names the odd count */
        return false;
    }
    size_t k = 0;
    for (size_t i = 1; i < end; i += 2u) {
        int hi = sim_hex_value(in[i]);
        int lo = sim_hex_value(in[i + 1u]);
        if (hi < 0 || lo < 0 || k >= cap) {
            return false;
        }
        out[k++] = (uint8_t)((hi << 4) | lo);
    }
    *out_len = k;
    return true;
}

/* Describe an ADU (address, PDU, check) received or sent. */
static void describe_adu(const sim_trace_t *t, const uint8_t *raw, size_t rlen, bool reply,
                         bool errors, char *out, size_t cap)
{
    uint8_t buf[SIM_TRACE_MAX];
    const uint8_t *a = raw;
    size_t n = rlen;
    size_t check = 2u;
    bool ok;
    if (t->ascii) {
        n = 0;
        if (!ascii_decode(raw, rlen, buf, sizeof buf, &n)) {
            if (n != 0u) {
                snprintf(out, cap, "%snot an ASCII frame: odd number of hex digits (%zu)",
                         errors ? "line error, " : "", n);
            } else {
                snprintf(out, cap, "%snot an ASCII frame", errors ? "line error, " : "");
            }
            return;
        }
        a = buf;
        check = 1u;
    }
    if (n < 1u + check + 1u) {
        snprintf(out, cap, "%sshort frame (%zu bytes)", errors ? "line error, " : "", n);
        return;
    }
    if (!reply && !t->any_addr && a[0] != t->own_addr && a[0] != 0u) {
        snprintf(out, cap, "%snot for us (slave %u)", errors ? "line error, " : "", (unsigned)a[0]);
        return;
    }
    if (t->ascii) {
        ok = modcp_lrc(a, n - 1u) == a[n - 1u];
    } else {
        ok = modcp_crc16(a, n) == 0u;
    }
    char what[200];
    sim_describe_pdu(a + 1, n - 1u - check, reply, what, sizeof what);
    const char *pre_err = errors ? "line error, " : "";
    const char *pre_chk = ok ? "" : (t->ascii ? "LRC error, " : "CRC error, ");
    if (reply) {
        snprintf(out, cap, "%s%s%s", pre_err, pre_chk, what);
        return;
    }
    if (a[0] == 0u) {
        snprintf(out, cap, "%s%sbroadcast %s", pre_err, pre_chk, what);
    } else {
        snprintf(out, cap, "%s%sslave %u %s", pre_err, pre_chk, (unsigned)a[0], what);
    }
}

void sim_trace_format(const sim_trace_t *t, const char *label, const uint8_t *b, size_t n,
                      bool reply, bool errors, const char *note, char *line, size_t cap)
{
    size_t pos = (size_t)snprintf(line, cap, "%s", label);
    for (size_t i = 0; i < n && pos + 420u < cap; i++) {
        if (t->ascii && (b[i] < 0x20u || b[i] >= 0x7Fu) && i == 0u) {
            line[pos++] = ' ';
        }
        if (t->ascii && b[i] >= 0x20u && b[i] < 0x7Fu) {
            if (i == 0u) {
                line[pos++] = ' ';
            }
            line[pos++] = (char)b[i];
        } else if (t->ascii && (b[i] == '\r' || b[i] == '\n')) {
            pos += (size_t)snprintf(line + pos, cap - pos, "%s", b[i] == '\r' ? "\\r" : "\\n");
        } else if (t->ascii) {
            pos += (size_t)snprintf(line + pos, cap - pos, "<%02X>", (unsigned)b[i]);
        } else {
            pos += (size_t)snprintf(line + pos, cap - pos, " %02X", (unsigned)b[i]);
        }
    }
    char what[400];
    describe_adu(t, b, n, reply, errors, what, sizeof what);
    snprintf(line + pos, cap - pos, " | %s%s%s", what, note != NULL ? " " : "",
             note != NULL ? note : "");
}

void sim_trace_print(sim_trace_t *t, const char *text, uint64_t t_us)
{
    char line[SIM_TRACE_LINE + 32];
    snprintf(line, sizeof line, "[%5lu.%06lu] %s", (unsigned long)(t_us / 1000000u),
             (unsigned long)(t_us % 1000000u), text);
    if (t->print != NULL) {
        t->print(t->user, line);
    }
}

static void print_frame(sim_trace_t *t, const char *dir, const uint8_t *b, size_t n, bool reply,
                        bool errors, uint64_t t_us, const char *note)
{
    char line[SIM_TRACE_LINE];
    sim_trace_format(t, dir, b, n, reply, errors, note, line, sizeof line);
    sim_trace_print(t, line, t_us);
}

static void rx_flush(sim_trace_t *t)
{
    if (t->rx_len > 0u) {
        print_frame(t, t->rx_label, t->rx, t->rx_len, false, t->rx_errors, t->rx_t0, NULL);
    }
    t->rx_len = 0;
    t->rx_errors = false;
}

void sim_trace_rx(sim_trace_t *t, uint8_t byte, uint8_t errors, uint64_t t_us)
{
    if (t->rx_len > 0u && t_us - t->rx_last >= t->gap_us) {
        rx_flush(t);
    }
    if (t->ascii && byte == ':' && t->rx_len > 0u) {
        rx_flush(t); /* a start character begins a new frame */
    }
    if (t->rx_len == 0u) {
        t->rx_t0 = t_us;
    }
    if (t->rx_len < sizeof t->rx) {
        t->rx[t->rx_len++] = byte;
    }
    if (errors != 0u) {
        t->rx_errors = true;
    }
    t->rx_last = t_us;
    if (t->ascii && byte == '\n') {
        rx_flush(t);
    }
}

void sim_trace_poll(sim_trace_t *t, uint64_t t_us)
{
    if (t->rx_len > 0u && t_us - t->rx_last >= t->gap_us) {
        rx_flush(t);
    }
}

void sim_trace_format_event(const char *prefix, modcp_event_t ev, char *out, size_t cap)
{
    const char *cls = modcp_event_class_text(MODCP_EVENT_CLASS(ev));
    snprintf(out, cap, "%sevent (%02X)%02XH %s: %s", prefix, (unsigned)MODCP_EVENT_CLASS(ev),
             (unsigned)MODCP_EVENT_NUMBER(ev), cls, modcp_event_text(ev));
}
