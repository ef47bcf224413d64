/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the faults of a member's replies: parsing, the transforms (exception, CRC), the counters. */
#define _GNU_SOURCE
#include "bus_internal.h"

/* ---- faults ---------------------------------------------------------------------- */

uint32_t rnd(sim_bus_t *b)
{
    uint32_t x = b->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    b->rng = x;
    return x;
}

bool chance(sim_bus_t *b, uint8_t pct)
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

/* "off": the settings off, the counters kept. */
static void faults_off(sim_fault_t *f)
{
    sim_fault_t z;
    memset(&z, 0, sizeof z);
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
}

/* P or P% with P in 0..100. */
static bool parse_pct(const char *kind, const char *val, uint8_t *pct, char *err, size_t cap)
{
    size_t vl = strlen(val);
    char num[16];
    uint32_t v = 0;
    if (vl > 0u && val[vl - 1u] == '%') {
        vl--;
    }
    if (vl > 0u && vl < sizeof num) {
        memcpy(num, val, vl);
        num[vl] = '\0';
        if (parse_u32(num, 100u, &v)) {
            *pct = (uint8_t)v;
            return true;
        }
    }
    snprintf(err, cap, "%s=%s: a share in percent, 0..100", kind, val);
    return false;
}

/* MS or MIN-MAX, 0..60000. */
static bool parse_delay(sim_fault_t *f, const char *val, char *err, size_t cap)
{
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

bool sim_fault_parse(sim_fault_t *f, const char *spec, char *err, size_t cap)
{
    if (strcmp(spec, "off") == 0) {
        faults_off(f);
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
        return parse_pct(kind, val, pct, err, cap);
    }
    if (strcmp(kind, "delay") == 0) {
        return parse_delay(f, val, err, cap);
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
uint16_t exception_frame(const sim_bus_t *b, const uint8_t *in, uint16_t len, uint8_t code,
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

void corrupt_check(const sim_bus_t *b, uint8_t *buf, uint16_t len)
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

/* The transforms of a reply (exception 06 / 04 instead, CRC or LRC corrupted, a delay)
 * on buf (*len bytes, room for MODCP_POSIX_TX_MAX), counted in f and described in note;
 * returns the delay in us. b->mu held. */
double reply_faults(sim_bus_t *b, sim_fault_t *f, uint8_t *buf, uint16_t *len, char *note,
                    size_t cap)
{
    uint8_t orig[MODCP_POSIX_TX_MAX];
    memcpy(orig, buf, *len);
    if (chance(b, f->exc06_pct)) {
        uint16_t k = exception_frame(b, orig, *len, 0x06u, buf);
        if (k != 0u) {
            *len = k;
            f->exc06++;
            snprintf(note, cap, "(fault: exception 06 instead)");
        }
    } else if (chance(b, f->exc04_pct)) {
        uint16_t k = exception_frame(b, orig, *len, 0x04u, buf);
        if (k != 0u) {
            *len = k;
            f->exc04++;
            snprintf(note, cap, "(fault: exception 04 instead)");
        }
    }
    if (chance(b, f->crc_pct)) {
        corrupt_check(b, buf, *len);
        f->crc_corrupted++;
        size_t nl = strlen(note);
        snprintf(note + nl, cap - nl, "%s(fault: %s corrupted)", nl > 0u ? " " : "",
                 b->line.ascii ? "LRC" : "CRC");
    }
    if (f->delay_max_ms == 0u) {
        return 0.0;
    }
    uint32_t d = f->delay_min_ms;
    if (f->delay_max_ms > f->delay_min_ms) {
        d += rnd(b) % (f->delay_max_ms - f->delay_min_ms + 1u);
    }
    f->delayed++;
    size_t nl = strlen(note);
    snprintf(note + nl, cap - nl, "%s(fault: delayed %u ms)", nl > 0u ? " " : "", (unsigned)d);
    return (double)d * 1000.0;
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
