/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — replay of a capture (see replay.h).
 *
 * The capture is read as capture.c writes it: classic pcap (microseconds or
 * nanoseconds, either byte order), link type 252, each record's exported-PDU tags (the
 * dissector name, the protocol column, the P2P direction: 0 = the master). A request is
 * a master frame; its recorded reply is what the slaves sent after it, up to the next
 * request. The replay opens the line's pty as a master would, sends each request when
 * its recorded time (from the first one, divided by the speed) has come, reads until the
 * next request is due (at least t3.5 + 20 ms, and on while characters keep coming) and
 * compares what came with the recorded reply byte by byte. */
#define _GNU_SOURCE
#include "replay.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "modcp/hal_posix.h"

#define LINKTYPE_WIRESHARK_UPPER_PDU 252u

static uint32_t get32(const uint8_t *p, bool swap)
{
    return swap ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]
                : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static unsigned be16(const uint8_t *p)
{
    return (unsigned)p[0] << 8 | p[1];
}

/* The exported PDU's tags of one record: is it a Modbus frame, and whose? Returns the
 * offset of the payload, 0 when it is not a frame to replay. */
static size_t frame_of(const uint8_t *d, size_t len, bool *master)
{
    size_t k = 0;
    bool modbus = false;
    *master = false;
    while (k + 4u <= len) {
        unsigned tag = be16(d + k), tl = be16(d + k + 2u);
        k += 4u;
        if (tag == 0u) {
            return modbus ? k : 0u;
        }
        if (k + tl > len) {
            return 0;
        }
        if ((tag == 12u && tl >= 5u && memcmp(d + k, "mbrtu", 5) == 0 && (tl == 5u || d[k + 5u] == 0u)) ||
            (tag == 33u && tl >= 12u && memcmp(d + k, "MODBUS/ASCII", 12) == 0)) {
            modbus = true;
        }
        if (tag == 35u && tl == 4u) {
            *master = get32(d + k, true) == 0u;
        }
        k += tl;
    }
    return 0;
}

static bool read_header(FILE *f, bool *swap, bool *nano, char *err, size_t cap)
{
    uint8_t h[24];
    if (fread(h, 1, sizeof h, f) != sizeof h) {
        snprintf(err, cap, "not a pcap file (shorter than its header)");
        return false;
    }
    uint32_t magic = get32(h, false);
    *swap = magic == 0xD4C3B2A1u || magic == 0x4D3CB2A1u;
    *nano = magic == 0xA1B23C4Du || magic == 0x4D3CB2A1u;
    if (!*swap && magic != 0xA1B2C3D4u && magic != 0xA1B23C4Du) {
        snprintf(err, cap, "not a classic pcap file (magic 0x%08X; pcapng is not read)",
                 (unsigned)magic);
        return false;
    }
    uint32_t lt = get32(h + 20, *swap) & 0xFFFFu;
    if (lt != LINKTYPE_WIRESHARK_UPPER_PDU) {
        snprintf(err, cap, "link type %u; --replay reads modcp-sim's captures (link type 252, "
                           "exported PDU)", (unsigned)lt);
        return false;
    }
    return true;
}

bool sim_replay_load(sim_replay_t *r, const char *path, char *err, size_t cap)
{
    memset(r, 0, sizeof *r);
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        snprintf(err, cap, "%s", strerror(errno));
        return false;
    }
    bool swap = false, nano = false;
    bool ok = read_header(f, &swap, &nano, err, cap);
    r->f = ok ? calloc(SIM_REPLAY_MAX_FRAMES, sizeof *r->f) : NULL;
    if (ok && r->f == NULL) {
        snprintf(err, cap, "out of memory");
        ok = false;
    }
    static uint8_t d[65536];
    uint8_t rh[16];
    while (ok && r->n < SIM_REPLAY_MAX_FRAMES && fread(rh, 1, sizeof rh, f) == sizeof rh) {
        uint32_t incl = get32(rh + 8, swap);
        if (incl > sizeof d || fread(d, 1, incl, f) != incl) {
            snprintf(err, cap, "record %zu is cut short", r->n + 1u);
            ok = false;
            break;
        }
        bool master = false;
        size_t off = frame_of(d, incl, &master);
        if (off == 0u || incl - off > SIM_REPLAY_FRAME_MAX) {
            continue;
        }
        sim_replay_frame_t *fr = &r->f[r->n++];
        uint32_t frac = get32(rh + 4, swap);
        fr->t_us = (uint64_t)get32(rh, swap) * 1000000u + (nano ? frac / 1000u : frac);
        fr->master = master;
        fr->len = (uint16_t)(incl - off);
        memcpy(fr->b, d + off, fr->len);
    }
    fclose(f);
    if (ok && r->n == 0u) {
        snprintf(err, cap, "no Modbus frames in it");
        ok = false;
    }
    if (!ok) {
        sim_replay_free(r);
    }
    return ok;
}

void sim_replay_free(sim_replay_t *r)
{
    free(r->f);
    r->f = NULL;
    r->n = 0;
}

static void hex(const uint8_t *b, size_t n, char *out, size_t cap)
{
    size_t k = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n && k + 4u < cap; i++) {
        k += (size_t)snprintf(out + k, cap - k, "%s%02X", i > 0u ? " " : "", b[i]);
    }
}

/* Reads from fd until deadline (us, monotonic), and on while characters keep coming
 * (a pause of quiet_us ends it). */
static size_t collect(int fd, uint8_t *buf, size_t cap, uint64_t deadline, uint64_t quiet_us,
                      const atomic_bool *stop)
{
    size_t n = 0;
    uint64_t last = 0;
    for (;;) {
        uint64_t now = modcp_posix_now_us64();
        uint64_t until = deadline;
        if (n > 0u && last + quiet_us > until) {
            until = last + quiet_us;
        }
        if (now >= until || atomic_load(stop)) {
            return n;
        }
        struct pollfd pf = {fd, POLLIN, 0};
        int ms = (int)((until - now + 999u) / 1000u);
        if (poll(&pf, 1, ms) > 0 && n < cap) {
            ssize_t k = read(fd, buf + n, cap - n);
            if (k > 0) {
                n += (size_t)k;
                last = modcp_posix_now_us64();
            }
        }
    }
}

/* The recorded reply of request i: the slaves' frames after it, up to the next request. */
static size_t recorded_reply(const sim_replay_t *r, size_t i, uint8_t *out, size_t cap)
{
    size_t n = 0;
    for (size_t k = i + 1u; k < r->n && !r->f[k].master; k++) {
        size_t len = r->f[k].len < cap - n ? r->f[k].len : cap - n;
        memcpy(out + n, r->f[k].b, len);
        n += len;
    }
    return n;
}

static void compare(sim_replay_t *r, size_t i, size_t req_no, const uint8_t *got, size_t n,
                    void (*print)(void *user, const char *line), void *user)
{
    uint8_t want[4096];
    size_t wn = recorded_reply(r, i, want, sizeof want);
    if (wn == n && memcmp(want, got, n) == 0) {
        return;
    }
    r->differ++;
    char line[1400], a[400], b[400], req[200];
    hex(r->f[i].b, r->f[i].len, req, sizeof req);
    hex(want, wn, a, sizeof a);
    hex(got, n, b, sizeof b);
    snprintf(line, sizeof line, "replay: request %zu (frame %zu: %s): the reply differs: "
             "recorded [%s], now [%s]", req_no, i + 1u, req, wn > 0u ? a : "none",
             n > 0u ? b : "none");
    print(user, line);
    size_t pos = (size_t)snprintf(line, sizeof line, "replay: request %zu: bytes", req_no);
    size_t max = wn > n ? wn : n, shown = 0;
    for (size_t k = 0; k < max && pos + 24u < sizeof line && shown < 16u; k++) {
        int w = k < wn ? want[k] : -1, g = k < n ? got[k] : -1;
        if (w != g) {
            pos += (size_t)snprintf(line + pos, sizeof line - pos, " %zu: %s%02X -> %s%02X", k + 1u,
                                    w < 0 ? "-" : "", w < 0 ? 0u : (unsigned)w, g < 0 ? "-" : "",
                                    g < 0 ? 0u : (unsigned)g);
            shown++;
        }
    }
    print(user, line);
}

bool sim_replay_run(sim_replay_t *r, const char *path, double speed, uint32_t t35_us,
                    const atomic_bool *stop, void (*print)(void *user, const char *line),
                    void *user)
{
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        return false;
    }
    struct termios tio;
    if (tcgetattr(fd, &tio) == 0) {
        cfmakeraw(&tio);
        (void)tcsetattr(fd, TCSANOW, &tio);
    }
    size_t first = 0;
    while (first < r->n && !r->f[first].master) {
        first++;
    }
    uint64_t t0 = modcp_posix_now_us64() + 20000u;
    uint64_t rec0 = first < r->n ? r->f[first].t_us : 0u;
    uint64_t min_wait = (uint64_t)t35_us + 20000u;
    for (size_t i = first; i < r->n && !atomic_load(stop); i++) {
        if (!r->f[i].master) {
            continue;
        }
        uint64_t due = t0 + (uint64_t)((double)(r->f[i].t_us - rec0) / speed);
        modcp_posix_sleep_until_us64(due);
        (void)tcflush(fd, TCIFLUSH);
        ssize_t w = write(fd, r->f[i].b, r->f[i].len);
        (void)w;
        r->requests++;
        size_t next = i + 1u;
        while (next < r->n && !r->f[next].master) {
            next++;
        }
        uint64_t end = next < r->n ? t0 + (uint64_t)((double)(r->f[next].t_us - rec0) / speed)
                                   : 0u;
        uint64_t now = modcp_posix_now_us64();
        if (end < now + min_wait) {
            end = now + min_wait;
        }
        uint8_t got[4096];
        size_t n = collect(fd, got, sizeof got, end, (uint64_t)t35_us + 5000u, stop);
        compare(r, i, r->requests, got, n, print, user);
    }
    close(fd);
    return true;
}
