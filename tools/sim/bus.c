/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — one line, several members (see bus.h). */
#define _GNU_SOURCE
#include "bus.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "modcp/crc.h"
#include "modcp/hal_posix.h"
#include "trace.h"

#define MAX_SENDERS 32
#define NOISE (-1)
#define SPIN_US 50.0

typedef struct {
    bool used;
    int who; /* member index or NOISE */
    uint8_t b[MODCP_POSIX_TX_MAX];
    uint16_t len;
    double t0; /* us since the bus's t0: start of the first start bit */
} sender_t;

struct sim_bus {
    sim_line_t line;
    double c_us;   /* character time */
    double bit_us; /* bit time */
    unsigned nbits;
    size_t n;
    char names[SIM_BUS_MAX_MEMBERS][24];
    uint8_t addr[SIM_BUS_MAX_MEMBERS];
    int member_fd[SIM_BUS_MAX_MEMBERS];
    int wake_fd[SIM_BUS_MAX_MEMBERS];
    /* what each member heard: byte + the member's clock at the end of its stop bit */
    pthread_mutex_t rx_mu;
    struct {
        uint8_t b[8192];
        uint32_t t[8192];
        size_t head, tail;
    } rxq[SIM_BUS_MAX_MEMBERS];
    int master_fd;
    modcp_posix_event_t wake; /* the bus thread's: a member replied, a request to stop */
    uint64_t t0_us64;
    void (*print)(void *user, const char *line);
    void *user;
    atomic_bool stop;
    atomic_bool trace_on;

    pthread_mutex_t mu; /* everything below */
    sender_t s[MAX_SENDERS];
    double from; /* the receiver looks for the next start bit from here */
    sim_fault_t fault[SIM_BUS_MAX_MEMBERS];
    uint32_t rng;
    /* what the receiver heard, cut at t3.5 like a frame */
    uint8_t heard[SIM_TRACE_MAX];
    size_t heard_len;
    double heard_t0, heard_end;
    bool heard_collided;
    uint32_t heard_mask; /* members that sent during the frame */
    /* the characters for the members, handed over when the line pauses: a member's
     * core cuts frames by t1.5 / t3.5 of its own clock, so a late wake-up of the bus
     * thread must not open a gap inside a frame it hears (a UART never does) */
    uint8_t mbuf[SIM_TRACE_MAX];
    uint32_t mdeaf[SIM_TRACE_MAX]; /* members sending while the character was on the line */
    double mt[SIM_TRACE_MAX];      /* end of its stop bit */
    size_t mlen;
    sim_trace_t tr;      /* bus thread only (after init) */
    /* MODCP_SIM_BUS_LOG=FILE: the bus thread's polls, reads and writes, each with its
     * CLOCK_MONOTONIC time (the times master_bus prints its errors with); off: NULL */
    FILE *log;
    pthread_mutex_t log_mu;
};

/* ---- time ------------------------------------------------------------------------ */

static double now_rel(const sim_bus_t *b)
{
    return (double)(modcp_posix_now_us64() - b->t0_us64);
}

/* One line of the bus log (MODCP_SIM_BUS_LOG): "<s.us> <what> [bytes]". Any thread. */
static void blog(sim_bus_t *b, const char *what, const uint8_t *p, size_t n)
{
    if (b->log == NULL) {
        return;
    }
    uint64_t t = modcp_posix_now_us64();
    char line[200];
    size_t pos = (size_t)snprintf(line, sizeof line, "%llu.%06llu %s",
                                  (unsigned long long)(t / 1000000u),
                                  (unsigned long long)(t % 1000000u), what);
    for (size_t i = 0; i < n && pos + 8u < sizeof line; i++) {
        pos += (size_t)snprintf(line + pos, sizeof line - pos, i == 12u && n > 13u ? " .." : " %02X",
                                p[i]);
        if (i == 12u && n > 13u) {
            break;
        }
    }
    pthread_mutex_lock(&b->log_mu);
    fprintf(b->log, "%s\n", line);
    pthread_mutex_unlock(&b->log_mu);
}

/* A member's 32-bit clock value as us since the bus's t0. */
static double rel_of(const sim_bus_t *b, uint32_t now_us)
{
    uint64_t n64 = modcp_posix_now_us64();
    uint32_t back = (uint32_t)n64 - now_us;
    return (double)(n64 - back - b->t0_us64);
}

/* ---- the line's levels ---------------------------------------------------------- */

/* Level of bit i (0 = start) of the character v. */
static int frame_bit(const sim_bus_t *b, uint8_t v, unsigned i)
{
    unsigned db = b->line.data_bits;
    if (i == 0u) {
        return 0;
    }
    if (i <= db) {
        return (v >> (i - 1u)) & 1;
    }
    if (b->line.parity != 0u && i == db + 1u) {
        unsigned ones = 0;
        for (unsigned k = 0; k < db; k++) {
            ones += ((unsigned)v >> k) & 1u;
        }
        return b->line.parity == 2u ? (int)(ones & 1u) : (int)((ones & 1u) ^ 1u);
    }
    return 1; /* stop bits, idle */
}

static double end_of(const sim_bus_t *b, const sender_t *s)
{
    return s->t0 + (double)s->len * b->c_us;
}

static int sender_level(const sim_bus_t *b, const sender_t *s, double tau)
{
    double r = tau - s->t0;
    if (r < 0.0 || tau >= end_of(b, s)) {
        return 1;
    }
    size_t gb = (size_t)(r / b->bit_us);
    size_t k = gb / b->nbits;
    if (k >= s->len) {
        return 1;
    }
    return frame_bit(b, s->b[k], (unsigned)(gb % b->nbits));
}

static int line_level(const sim_bus_t *b, double tau)
{
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (b->s[i].used && sender_level(b, &b->s[i], tau) == 0) {
            return 0;
        }
    }
    return 1;
}

/* Earliest time >= from at which s drives a 0. */
static bool sender_first_low(const sim_bus_t *b, const sender_t *s, double from, double *at)
{
    double r = from - s->t0;
    if (from >= end_of(b, s)) {
        return false;
    }
    if (r < 0.0) {
        r = 0.0;
    }
    size_t total = (size_t)s->len * b->nbits;
    for (size_t gb = (size_t)(r / b->bit_us); gb < total; gb++) {
        if (frame_bit(b, s->b[gb / b->nbits], (unsigned)(gb % b->nbits)) == 0) {
            double start = (double)gb * b->bit_us;
            *at = s->t0 + (start > r ? start : r);
            return true;
        }
    }
    return false;
}

typedef struct {
    double start; /* start bit's falling edge */
    uint8_t byte;
    uint32_t mask;   /* members sending during the character */
    unsigned senders; /* senders (members and noise) during it */
} rxchar_t;

/* The receiver's next character from b->from on (not consumed). */
static bool decode_next(const sim_bus_t *b, rxchar_t *out)
{
    double from = b->from;
    for (int tries = 0; tries < 64; tries++) {
        bool found = false;
        double ts = 0.0;
        for (size_t i = 0; i < MAX_SENDERS; i++) {
            double at;
            if (b->s[i].used && sender_first_low(b, &b->s[i], from, &at) && (!found || at < ts)) {
                ts = at;
                found = true;
            }
        }
        if (!found) {
            return false;
        }
        if (line_level(b, ts + 0.5 * b->bit_us) != 0) {
            from = ts + 0.5 * b->bit_us; /* a glitch, not a start bit */
            continue;
        }
        uint8_t v = 0;
        for (unsigned i = 1; i <= b->line.data_bits; i++) {
            if (line_level(b, ts + ((double)i + 0.5) * b->bit_us) != 0) {
                v = (uint8_t)(v | (1u << (i - 1u)));
            }
        }
        out->start = ts;
        out->byte = v;
        out->mask = 0;
        out->senders = 0;
        for (size_t i = 0; i < MAX_SENDERS; i++) {
            const sender_t *s = &b->s[i];
            if (s->used && s->t0 < ts + b->c_us && end_of(b, s) > ts) {
                out->senders++;
                if (s->who >= 0) {
                    out->mask |= 1u << (unsigned)s->who;
                }
            }
        }
        return true;
    }
    return false;
}

/* ---- faults ---------------------------------------------------------------------- */

static uint32_t rnd(sim_bus_t *b)
{
    uint32_t x = b->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    b->rng = x;
    return x;
}

static bool chance(sim_bus_t *b, uint8_t pct)
{
    return pct != 0u && rnd(b) % 100u < pct;
}

static bool parse_u32(const char *s, uint32_t max, uint32_t *v)
{
    char *end = NULL;
    if (*s < '0' || *s > '9') {
        return false;
    }
    unsigned long x = strtoul(s, &end, 10);
    if (*end != '\0' || x > max) {
        return false;
    }
    *v = (uint32_t)x;
    return true;
}

bool sim_fault_parse(sim_fault_t *f, const char *spec, char *err, size_t cap)
{
    if (strcmp(spec, "off") == 0) {
        sim_fault_t z;
        memset(&z, 0, sizeof z);
        /* settings off, counters kept */
        z.replies = f->replies;
        z.dropped = f->dropped;
        z.crc_corrupted = f->crc_corrupted;
        z.exc06 = f->exc06;
        z.exc04 = f->exc04;
        z.delayed = f->delayed;
        z.silenced = f->silenced;
        z.noise_sent = f->noise_sent;
        z.collisions = f->collisions;
        *f = z;
        return true;
    }
    const char *eq = strchr(spec, '=');
    char kind[16];
    size_t kl = eq != NULL ? (size_t)(eq - spec) : 0u;
    if (eq == NULL || kl == 0u || kl >= sizeof kind) {
        snprintf(err, cap, "'%s': expected KIND=VALUE or off (KIND: drop crc exc06 exc04 delay "
                           "silent noise)", spec);
        return false;
    }
    memcpy(kind, spec, kl);
    kind[kl] = '\0';
    const char *val = eq + 1;
    uint32_t v = 0;
    uint8_t *pct = strcmp(kind, "drop") == 0    ? &f->drop_pct
                   : strcmp(kind, "crc") == 0   ? &f->crc_pct
                   : strcmp(kind, "exc06") == 0 ? &f->exc06_pct
                   : strcmp(kind, "exc04") == 0 ? &f->exc04_pct
                                                : NULL;
    if (pct != NULL) {
        size_t vl = strlen(val);
        char num[16];
        if (vl > 0u && val[vl - 1u] == '%') {
            vl--;
        }
        if (vl == 0u || vl >= sizeof num) {
            snprintf(err, cap, "%s=%s: a share in percent, 0..100", kind, val);
            return false;
        }
        memcpy(num, val, vl);
        num[vl] = '\0';
        if (!parse_u32(num, 100u, &v)) {
            snprintf(err, cap, "%s=%s: a share in percent, 0..100", kind, val);
            return false;
        }
        *pct = (uint8_t)v;
        return true;
    }
    if (strcmp(kind, "delay") == 0) {
        uint32_t lo = 0, hi = 0;
        const char *dash = strchr(val, '-');
        bool ok;
        if (dash != NULL) {
            char a[16];
            size_t al = (size_t)(dash - val);
            ok = al > 0u && al < sizeof a;
            if (ok) {
                memcpy(a, val, al);
                a[al] = '\0';
                ok = parse_u32(a, 60000u, &lo) && parse_u32(dash + 1, 60000u, &hi) && lo <= hi;
            }
        } else {
            ok = parse_u32(val, 60000u, &lo);
            hi = lo;
        }
        if (!ok) {
            snprintf(err, cap, "delay=%s: MS or MIN-MAX, 0..60000 ms", val);
            return false;
        }
        f->delay_min_ms = lo;
        f->delay_max_ms = hi;
        return true;
    }
    if (strcmp(kind, "silent") == 0) {
        if (!parse_u32(val, 1000000u, &v)) {
            snprintf(err, cap, "silent=%s: a number of requests, 0..1000000", val);
            return false;
        }
        f->silent_left = v;
        return true;
    }
    if (strcmp(kind, "noise") == 0) {
        if (!parse_u32(val, 256u, &v)) {
            snprintf(err, cap, "noise=%s: a number of bytes, 0..256", val);
            return false;
        }
        f->noise_bytes = (uint16_t)v;
        return true;
    }
    snprintf(err, cap, "unknown fault '%s' (drop crc exc06 exc04 delay silent noise)", kind);
    return false;
}

static int hexval(uint8_t c)
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

static const char HEX[] = "0123456789ABCDEF";

/* The reply replaced by an exception reply with code. */
static uint16_t exception_frame(const sim_bus_t *b, const uint8_t *in, uint16_t len, uint8_t code,
                                uint8_t *out)
{
    uint8_t pdu[3];
    if (b->line.ascii) {
        if (len < 5u) {
            return 0;
        }
        pdu[0] = (uint8_t)((hexval(in[1]) << 4) | hexval(in[2]));
        pdu[1] = (uint8_t)((hexval(in[3]) << 4) | hexval(in[4]));
    } else {
        if (len < 2u) {
            return 0;
        }
        pdu[0] = in[0];
        pdu[1] = in[1];
    }
    pdu[1] = (uint8_t)(pdu[1] | 0x80u);
    pdu[2] = code;
    if (b->line.ascii) {
        uint8_t lrc = modcp_lrc(pdu, 3u);
        uint16_t k = 0;
        out[k++] = ':';
        for (size_t i = 0; i < 3u; i++) {
            out[k++] = (uint8_t)HEX[pdu[i] >> 4];
            out[k++] = (uint8_t)HEX[pdu[i] & 15u];
        }
        out[k++] = (uint8_t)HEX[lrc >> 4];
        out[k++] = (uint8_t)HEX[lrc & 15u];
        out[k++] = '\r';
        out[k++] = '\n';
        return k;
    }
    uint16_t crc = modcp_crc16(pdu, 3u);
    memcpy(out, pdu, 3u);
    out[3] = (uint8_t)(crc & 0xFFu);
    out[4] = (uint8_t)(crc >> 8);
    return 5u;
}

static void corrupt_check(const sim_bus_t *b, uint8_t *buf, uint16_t len)
{
    if (b->line.ascii) {
        if (len >= 4u) { /* the LRC's low digit, before CR LF */
            int v = hexval(buf[len - 3u]);
            buf[len - 3u] = (uint8_t)HEX[(unsigned)(v < 0 ? 0 : v) ^ 1u];
        }
    } else if (len >= 1u) {
        buf[len - 1u] ^= 0x5Au; /* the CRC's high byte */
    }
}

/* ---- construction ----------------------------------------------------------------- */

static void trace_print(void *user, const char *line)
{
    sim_bus_t *b = user;
    b->print(b->user, line);
}

sim_bus_t *sim_bus_new(const sim_line_t *line, size_t n, const char *const names[],
                       const uint8_t addr[], int master_fd, const int member_fd[],
                       const int wake_fd[], uint64_t t0_us64,
                       void (*print)(void *user, const char *line), void *user, uint32_t seed)
{
    if (n == 0u || n > SIM_BUS_MAX_MEMBERS) {
        return NULL;
    }
    sim_bus_t *b = calloc(1, sizeof *b);
    if (b == NULL) {
        return NULL;
    }
    b->line = *line;
    b->nbits = 1u + line->data_bits + (line->parity != 0u ? 1u : 0u) + line->stop_bits;
    b->c_us = (double)(line->char_us != 0u ? line->char_us : 1u);
    b->bit_us = b->c_us / (double)b->nbits;
    b->n = n;
    for (size_t i = 0; i < n; i++) {
        snprintf(b->names[i], sizeof b->names[i], "%s", names[i]);
        b->addr[i] = addr[i];
        b->member_fd[i] = member_fd[i];
        b->wake_fd[i] = wake_fd[i];
    }
    pthread_mutex_init(&b->rx_mu, NULL);
    b->master_fd = master_fd;
    if (modcp_posix_event_open(&b->wake) != 0) {
        free(b);
        return NULL;
    }
    b->t0_us64 = t0_us64;
    b->print = print;
    b->user = user;
    atomic_init(&b->stop, false);
    atomic_init(&b->trace_on, false);
    pthread_mutex_init(&b->mu, NULL);
    b->rng = seed != 0u ? seed : 0x2545F491u;
    pthread_mutex_init(&b->log_mu, NULL);
    const char *log = getenv("MODCP_SIM_BUS_LOG");
    if (log != NULL && log[0] != '\0') {
        b->log = fopen(log, "w");
        if (b->log != NULL) {
            (void)setvbuf(b->log, NULL, _IOFBF, 1u << 20);
        }
    }
    sim_trace_init(&b->tr, 0, line->ascii, line->t35_us, trace_print, b);
    b->tr.any_addr = true;
    return b;
}

void sim_bus_free(sim_bus_t *b)
{
    if (b != NULL) {
        modcp_posix_event_close(&b->wake);
        if (b->log != NULL) {
            fclose(b->log);
        }
        pthread_mutex_destroy(&b->log_mu);
        pthread_mutex_destroy(&b->mu);
        pthread_mutex_destroy(&b->rx_mu);
        free(b);
    }
}

static void wake(sim_bus_t *b)
{
    modcp_posix_event_signal(&b->wake);
}

void sim_bus_stop(sim_bus_t *b)
{
    atomic_store(&b->stop, true);
    wake(b);
}

void sim_bus_trace(sim_bus_t *b, bool on)
{
    atomic_store(&b->trace_on, on);
}

/* ---- replies onto the line ------------------------------------------------------- */

static sender_t *new_sender(sim_bus_t *b)
{
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (!b->s[i].used) {
            return &b->s[i];
        }
    }
    return NULL; /* more than MAX_SENDERS at once: the reply is lost */
}

static void trace_line(sim_bus_t *b, const char *label, const uint8_t *buf, size_t len,
                       double t, const char *note)
{
    if (atomic_load(&b->trace_on)) {
        sim_trace_frame(&b->tr, label, buf, len, true, (uint64_t)(t < 0.0 ? 0.0 : t), note);
    }
}

void sim_bus_tx(sim_bus_t *b, size_t m, const uint8_t *buf, uint16_t len, uint32_t now_us)
{
    if (m >= b->n || len == 0u) {
        return;
    }
    if (len > MODCP_POSIX_TX_MAX) {
        len = MODCP_POSIX_TX_MAX;
    }
    double t0 = rel_of(b, now_us);
    if (b->log != NULL) {
        char what[64];
        snprintf(what, sizeof what, "tx @%s t0=+%.0f", b->names[m], now_rel(b) - t0);
        blog(b, what, buf, len);
    }
    char label[48];
    snprintf(label, sizeof label, "@%s slave %u", b->names[m], (unsigned)b->addr[m]);
    pthread_mutex_lock(&b->mu);
    sim_fault_t *f = &b->fault[m];
    f->replies++;
    char note[96] = "";
    if (f->silent_left > 0u) {
        f->silent_left--;
        f->silenced++;
        trace_line(b, label, buf, len, t0, "(fault: silent, not on the line)");
        pthread_mutex_unlock(&b->mu);
        return;
    }
    if (chance(b, f->drop_pct)) {
        f->dropped++;
        trace_line(b, label, buf, len, t0, "(fault: dropped, not on the line)");
        pthread_mutex_unlock(&b->mu);
        return;
    }
    sender_t *s = new_sender(b);
    if (s == NULL) {
        pthread_mutex_unlock(&b->mu);
        return;
    }
    s->who = (int)m;
    s->len = len;
    memcpy(s->b, buf, len);
    if (chance(b, f->exc06_pct)) {
        uint16_t k = exception_frame(b, buf, len, 0x06u, s->b);
        if (k != 0u) {
            s->len = k;
            f->exc06++;
            snprintf(note, sizeof note, "(fault: exception 06 instead)");
        }
    } else if (chance(b, f->exc04_pct)) {
        uint16_t k = exception_frame(b, buf, len, 0x04u, s->b);
        if (k != 0u) {
            s->len = k;
            f->exc04++;
            snprintf(note, sizeof note, "(fault: exception 04 instead)");
        }
    }
    if (chance(b, f->crc_pct)) {
        corrupt_check(b, s->b, s->len);
        f->crc_corrupted++;
        size_t nl = strlen(note);
        snprintf(note + nl, sizeof note - nl, "%s(fault: %s corrupted)", nl > 0u ? " " : "",
                 b->line.ascii ? "LRC" : "CRC");
    }
    if (f->delay_max_ms > 0u) {
        uint32_t d = f->delay_min_ms;
        if (f->delay_max_ms > f->delay_min_ms) {
            d += rnd(b) % (f->delay_max_ms - f->delay_min_ms + 1u);
        }
        t0 += (double)d * 1000.0;
        f->delayed++;
        size_t nl = strlen(note);
        snprintf(note + nl, sizeof note - nl, "%s(fault: delayed %u ms)", nl > 0u ? " " : "",
                 (unsigned)d);
    }
    s->t0 = t0;
    s->used = true;
    trace_line(b, label, s->b, s->len, t0, note[0] != '\0' ? note : NULL);
    if (f->noise_bytes > 0u) {
        sender_t *z = new_sender(b);
        if (z != NULL) {
            z->who = NOISE;
            z->len = f->noise_bytes;
            for (uint16_t i = 0; i < z->len; i++) {
                z->b[i] = (uint8_t)(rnd(b) >> 7);
            }
            z->t0 = end_of(b, s) + (double)b->line.t35_us;
            z->used = true;
            f->noise_sent += z->len;
            char nlabel[48];
            snprintf(nlabel, sizeof nlabel, "noise (fault of @%s)", b->names[m]);
            if (atomic_load(&b->trace_on)) {
                char line[1200];
                size_t pos = (size_t)snprintf(line, sizeof line, "[%5lu.%06lu] %s",
                                              (unsigned long)((uint64_t)z->t0 / 1000000u),
                                              (unsigned long)((uint64_t)z->t0 % 1000000u), nlabel);
                for (uint16_t i = 0; i < z->len && pos + 4u < sizeof line; i++) {
                    pos += (size_t)snprintf(line + pos, sizeof line - pos, " %02X", z->b[i]);
                }
                b->print(b->user, line);
            }
        }
    }
    pthread_mutex_unlock(&b->mu);
    wake(b);
}

/* An external member (a QEMU board) sent bytes: they arrive as its UART emulation
 * writes them, not paced; the bus paces them on the line from their arrival, as one
 * reply while they follow each other within a character time of its end. */
static void external_tx(sim_bus_t *b, size_t m, const uint8_t *buf, size_t n, double now)
{
    pthread_mutex_lock(&b->mu);
    sender_t *s = NULL;
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (b->s[i].used && b->s[i].who == (int)m && end_of(b, &b->s[i]) + b->c_us >= now) {
            s = &b->s[i];
        }
    }
    if (s == NULL || (size_t)s->len + n > MODCP_POSIX_TX_MAX) {
        s = new_sender(b);
        if (s == NULL) {
            pthread_mutex_unlock(&b->mu);
            return;
        }
        s->who = (int)m;
        s->len = 0;
        s->t0 = now;
        s->used = true;
        b->fault[m].replies++;
    }
    memcpy(s->b + s->len, buf, n);
    s->len = (uint16_t)(s->len + n);
    pthread_mutex_unlock(&b->mu);
}

/* ---- the bus thread ----------------------------------------------------------------- */

static void heard_flush(sim_bus_t *b)
{
    if (b->heard_len > 0u && !b->heard_collided && atomic_load(&b->trace_on)) {
        for (size_t m = 0; m < b->n; m++) { /* an external member's reply, as heard */
            if (b->wake_fd[m] < 0 && b->heard_mask == (1u << m)) {
                char label[48];
                snprintf(label, sizeof label, "@%s (external)", b->names[m]);
                sim_trace_frame(&b->tr, label, b->heard, b->heard_len, true,
                                (uint64_t)b->heard_t0, NULL);
            }
        }
    }
    if (b->heard_len > 0u && b->heard_collided) {
        for (size_t m = 0; m < b->n; m++) {
            if ((b->heard_mask & (1u << m)) != 0u) {
                b->fault[m].collisions++;
            }
        }
        if (atomic_load(&b->trace_on)) {
            char label[160];
            size_t pos = (size_t)snprintf(label, sizeof label, "collision");
            for (size_t m = 0; m < b->n; m++) {
                if ((b->heard_mask & (1u << m)) != 0u) {
                    pos += (size_t)snprintf(label + pos, sizeof label - pos, " @%s", b->names[m]);
                }
            }
            snprintf(label + pos, sizeof label - pos, ", the line carried");
            sim_trace_frame(&b->tr, label, b->heard, b->heard_len, true, (uint64_t)b->heard_t0,
                            NULL);
        }
    }
    b->heard_len = 0;
    b->heard_collided = false;
    b->heard_mask = 0;
}

static void write_all(int fd, const uint8_t *p, size_t n)
{
    while (n > 0u) {
        ssize_t w = write(fd, p, n);
        if (w < 0) {
            if (errno == EINTR) {
                continue;
            }
            return; /* EAGAIN: nobody reads; drop like a line without a listener */
        }
        p += w;
        n -= (size_t)w;
    }
}

static void write_all(int fd, const uint8_t *p, size_t n);

/* Characters for member m, each ending on the line at t (us since the bus's t0). */
static void deliver(sim_bus_t *b, size_t m, const uint8_t *bytes, const double *t, size_t n)
{
    if (n == 0u) {
        return;
    }
    if (b->log != NULL) {
        char what[64];
        snprintf(what, sizeof what, "to @%s at -%.0f", b->names[m], now_rel(b) - t[n - 1u]);
        blog(b, what, bytes, n);
    }
    if (b->wake_fd[m] < 0) { /* an external member (a QEMU board's UART): its tty */
        write_all(b->member_fd[m], bytes, n);
        return;
    }
    pthread_mutex_lock(&b->rx_mu);
    for (size_t i = 0; i < n; i++) {
        size_t next = (b->rxq[m].head + 1u) % 8192u;
        if (next == b->rxq[m].tail) {
            break; /* the member does not read: drop, like an overrun */
        }
        b->rxq[m].b[b->rxq[m].head] = bytes[i];
        b->rxq[m].t[b->rxq[m].head] = (uint32_t)(b->t0_us64 + (uint64_t)(t[i] < 0.0 ? 0.0 : t[i]));
        b->rxq[m].head = next;
    }
    pthread_mutex_unlock(&b->rx_mu);
    char c = 1;
    ssize_t r = write(b->wake_fd[m], &c, 1);
    (void)r;
}

size_t sim_bus_take(sim_bus_t *b, size_t m, uint8_t *bytes, uint32_t *t_us, size_t cap,
                    uint32_t until_us, bool *more)
{
    size_t k = 0;
    pthread_mutex_lock(&b->rx_mu);
    while (k < cap && b->rxq[m].tail != b->rxq[m].head &&
           (int32_t)(b->rxq[m].t[b->rxq[m].tail] - until_us) <= 0) {
        bytes[k] = b->rxq[m].b[b->rxq[m].tail];
        t_us[k] = b->rxq[m].t[b->rxq[m].tail];
        k++;
        b->rxq[m].tail = (b->rxq[m].tail + 1u) % 8192u;
    }
    *more = b->rxq[m].tail != b->rxq[m].head;
    pthread_mutex_unlock(&b->rx_mu);
    return k;
}

static void master_write(sim_bus_t *b, const uint8_t *p, size_t n)
{
    if (n > 0u) {
        blog(b, "to master", p, n);
        write_all(b->master_fd, p, n);
    }
}

static void members_flush(sim_bus_t *b)
{
    for (size_t m = 0; m < b->n && b->mlen > 0u; m++) {
        uint8_t out[SIM_TRACE_MAX];
        double t[SIM_TRACE_MAX];
        size_t k = 0;
        for (size_t i = 0; i < b->mlen; i++) {
            if ((b->mdeaf[i] & (1u << m)) == 0u) {
                t[k] = b->mt[i];
                out[k++] = b->mbuf[i];
            }
        }
        deliver(b, m, out, t, k);
    }
    b->mlen = 0;
}

/* Is member m sending at any time in [a, z)? (then its transceiver does not hear) */
static bool member_sending(const sim_bus_t *b, size_t m, double a, double z)
{
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        const sender_t *s = &b->s[i];
        if (s->used && s->who == (int)m && s->t0 < z && end_of(b, s) > a) {
            return true;
        }
    }
    return false;
}

/* Emit the characters due by now; returns the time the next one ends (*later: it
 * continues a frame), or -1 for none.
 *
 * The members get a frame's characters before the master gets its last one: the
 * master answers a reply with its next request (after t3.5), and a member that took
 * the reply only after that — the bus thread preempted between the two writes while
 * the member's clock ran on — would see it at its own later time (a member's core
 * never goes back in time), glued to the request, and miss the request. */
static double emit_due(sim_bus_t *b, double now, bool *later)
{
    *later = false;
    uint8_t mo[SIM_TRACE_MAX]; /* for the master, after the members */
    size_t mol = 0;
    for (;;) {
        rxchar_t ch;
        if (!decode_next(b, &ch)) {
            break;
        }
        double at = ch.start + b->c_us;
        if (b->mlen > 0u && ch.start > b->heard_end + 0.5 * b->c_us) {
            members_flush(b); /* the line paused: the members get what it carried */
        }
        if (at > now + 1.0) {
            /* a frame goes on (or the line paused, the members have it): the master
             * gets what was due */
            master_write(b, mo, mol);
            /* a later character of a frame: no need to watch the clock */
            *later = b->heard_len > 0u && ch.start - b->heard_end < (double)b->line.t35_us;
            return at;
        }
        if (b->mlen == sizeof b->mbuf) {
            members_flush(b);
        }
        if (mol == sizeof mo) {
            master_write(b, mo, mol);
            mol = 0;
        }
        mo[mol++] = ch.byte;
        uint32_t deaf = 0;
        for (size_t m = 0; m < b->n; m++) {
            if (member_sending(b, m, ch.start, at)) {
                deaf |= 1u << m;
            }
        }
        b->mbuf[b->mlen] = ch.byte;
        b->mdeaf[b->mlen] = deaf;
        b->mt[b->mlen] = at;
        b->mlen++;
        if (b->heard_len > 0u && ch.start - b->heard_end >= (double)b->line.t35_us) {
            heard_flush(b);
        }
        if (b->heard_len == 0u) {
            b->heard_t0 = ch.start;
        }
        if (b->heard_len < sizeof b->heard) {
            b->heard[b->heard_len++] = ch.byte;
        }
        b->heard_end = at;
        b->heard_mask |= ch.mask;
        if (ch.senders > 1u) {
            b->heard_collided = true;
        }
        b->from = ch.start + ((double)b->nbits - 0.5) * b->bit_us;
    }
    members_flush(b); /* nothing follows back to back */
    master_write(b, mo, mol);
    /* senders the receiver is done with */
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (b->s[i].used && end_of(b, &b->s[i]) <= b->from + 0.5 * b->bit_us &&
            end_of(b, &b->s[i]) <= now) {
            b->s[i].used = false;
        }
    }
    if (b->heard_len > 0u && now - b->heard_end >= (double)b->line.t35_us) {
        heard_flush(b);
    }
    return -1.0;
}

void *sim_bus_thread(void *arg)
{
    sim_bus_t *b = arg;
    struct pollfd pf[2 + SIM_BUS_MAX_MEMBERS];
    nfds_t nf = 0;
    pf[nf++] = (struct pollfd){b->wake.rd, POLLIN, 0};
    pf[nf++] = (struct pollfd){b->master_fd, POLLIN, 0};
    for (size_t m = 0; m < b->n; m++) {
        pf[nf++] = (struct pollfd){b->member_fd[m], POLLIN, 0};
    }
    pthread_mutex_lock(&b->mu);
    b->from = now_rel(b);
    pthread_mutex_unlock(&b->mu);
    while (!atomic_load(&b->stop)) {
        double now = now_rel(b);
        pthread_mutex_lock(&b->mu);
        bool later = false;
        double next = emit_due(b, now, &later);
        bool frame_open = b->tr.rx_len > 0u;
        pthread_mutex_unlock(&b->mu);
        /* sleep until SPIN_US before the next character, then watch the clock */
        double wait_us = 5000.0;
        bool spin = false;
        if (next >= 0.0 && later) { /* a later character of a frame: just sleep until it */
            double d = next - now;
            wait_us = d < wait_us ? (d > 0.0 ? d : 0.0) : wait_us;
        } else if (next >= 0.0) { /* (-1: nothing on the line, the 5 ms tick) */
            double d = next - now;
            if (d < wait_us) {
                wait_us = d > SPIN_US ? d - SPIN_US : 0.0;
                spin = true;
            }
        }
        if (frame_open && (double)b->tr.gap_us < wait_us) {
            wait_us = (double)b->tr.gap_us; /* end the master's frame in the trace */
        }
        struct timespec ts = {(time_t)(wait_us / 1e6), (long)((long long)(wait_us * 1000.0) %
                                                             1000000000LL)};
        if (b->log != NULL) {
            char what[64];
            snprintf(what, sizeof what, "poll %.0f%s", wait_us, spin ? " spin" : "");
            blog(b, what, NULL, 0);
        }
        int pr = ppoll(pf, nf, &ts, NULL);
        if (b->log != NULL) {
            char what[80];
            snprintf(what, sizeof what, "polled %d wake=%x master=%x", pr, (unsigned)pf[0].revents,
                     (unsigned)pf[1].revents);
            blog(b, what, NULL, 0);
        }
        if (pr == 0 && spin) {
            const struct timespec zero = {0, 0};
            while (pr == 0 && now_rel(b) < next) {
                pr = ppoll(pf, nf, &zero, NULL);
            }
        }
        if (pr < 0) {
            continue;
        }
        double t = now_rel(b);
        if ((pf[0].revents & POLLIN) != 0) {
            modcp_posix_event_clear(&b->wake);
        }
        if ((pf[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
            uint8_t buf[512];
            ssize_t n = read(b->master_fd, buf, sizeof buf);
            if (b->log != NULL) {
                char what[64];
                snprintf(what, sizeof what, "master read %zd%s", n,
                         n < 0 ? strerror(errno) : "");
                blog(b, what, buf, n > 0 ? (size_t)n : 0u);
            }
            if (n > 0) {
                double at_[512];
                for (ssize_t i = 0; i < n; i++) {
                    at_[i] = t; /* a pty delivers a request at once, as to one slave */
                }
                pthread_mutex_lock(&b->mu);
                members_flush(b); /* what the line carried before comes first */
                pthread_mutex_unlock(&b->mu);
                for (size_t m = 0; m < b->n; m++) {
                    deliver(b, m, buf, at_, (size_t)n);
                }
                if (atomic_load(&b->trace_on)) {
                    pthread_mutex_lock(&b->mu);
                    for (ssize_t i = 0; i < n; i++) {
                        sim_trace_rx(&b->tr, buf[i], 0, (uint64_t)t);
                    }
                    pthread_mutex_unlock(&b->mu);
                }
            } else if (n < 0 && errno == EIO) {
                struct timespec s1 = {0, 1000000L};
                nanosleep(&s1, NULL);
            }
        }
        for (size_t m = 0; m < b->n; m++) {
            if ((pf[2 + m].revents & POLLIN) != 0) {
                uint8_t got[512];
                ssize_t k;
                while ((k = read(b->member_fd[m], got, sizeof got)) > 0) {
                    if (b->wake_fd[m] < 0) {
                        external_tx(b, m, got, (size_t)k, now_rel(b));
                    }
                    /* else: the member's paced copy of its reply: the bus has it */
                }
            }
        }
        if (atomic_load(&b->trace_on)) {
            pthread_mutex_lock(&b->mu);
            sim_trace_poll(&b->tr, (uint64_t)now_rel(b));
            pthread_mutex_unlock(&b->mu);
        }
    }
    return NULL;
}

/* ---- faults from the console ------------------------------------------------------ */

bool sim_bus_fault_set(sim_bus_t *b, size_t m, const char *spec, char *err, size_t cap)
{
    if (m >= b->n) {
        snprintf(err, cap, "no member %zu", m + 1u);
        return false;
    }
    pthread_mutex_lock(&b->mu);
    sim_fault_t f = b->fault[m];
    bool ok = sim_fault_parse(&f, spec, err, cap);
    if (ok) {
        b->fault[m] = f;
    }
    pthread_mutex_unlock(&b->mu);
    return ok;
}

sim_fault_t sim_bus_fault_get(sim_bus_t *b, size_t m)
{
    pthread_mutex_lock(&b->mu);
    sim_fault_t f = b->fault[m < b->n ? m : 0u];
    pthread_mutex_unlock(&b->mu);
    return f;
}

void sim_bus_fault_describe(sim_bus_t *b, size_t m, char *out, size_t cap)
{
    sim_fault_t f = sim_bus_fault_get(b, m);
    char delay[32];
    if (f.delay_max_ms == 0u) {
        snprintf(delay, sizeof delay, "0");
    } else if (f.delay_min_ms == f.delay_max_ms) {
        snprintf(delay, sizeof delay, "%ums", (unsigned)f.delay_min_ms);
    } else {
        snprintf(delay, sizeof delay, "%u-%ums", (unsigned)f.delay_min_ms,
                 (unsigned)f.delay_max_ms);
    }
    snprintf(out, cap,
             "faults: drop=%u%% crc=%u%% exc06=%u%% exc04=%u%% delay=%s silent=%u noise=%u | "
             "replies=%u dropped=%u crc_corrupted=%u exc06_sent=%u exc04_sent=%u delayed=%u "
             "silenced=%u noise_bytes=%u collisions=%u",
             (unsigned)f.drop_pct, (unsigned)f.crc_pct, (unsigned)f.exc06_pct,
             (unsigned)f.exc04_pct, delay, (unsigned)f.silent_left, (unsigned)f.noise_bytes,
             (unsigned)f.replies, (unsigned)f.dropped, (unsigned)f.crc_corrupted,
             (unsigned)f.exc06, (unsigned)f.exc04, (unsigned)f.delayed, (unsigned)f.silenced,
             (unsigned)f.noise_sent, (unsigned)f.collisions);
}
