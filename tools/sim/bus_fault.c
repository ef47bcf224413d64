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
    z.parity_errs = f->parity_errs;
    z.framing_errs = f->framing_errs;
    z.breaks_sent = f->breaks_sent;
    z.gaps_made = f->gaps_made;
    z.de_cuts = f->de_cuts;
    z.early_sent = f->early_sent;
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

/* gap=K:US */
static bool parse_gap(sim_fault_t *f, const char *val, char *err, size_t cap)
{
    const char *colon = strchr(val, ':');
    char k[16];
    uint32_t kv = 0, us = 0;
    size_t kl = colon != NULL ? (size_t)(colon - val) : 0u;
    if (colon != NULL && kl > 0u && kl < sizeof k) {
        memcpy(k, val, kl);
        k[kl] = '\0';
        if (parse_u32(k, 255u, &kv) && kv >= 1u && parse_u32(colon + 1, 10000000u, &us)) {
            f->gap_k = (uint16_t)kv;
            f->gap_us = us;
            return true;
        }
    }
    snprintf(err, cap, "gap=%s: K:US, a pause of US us (0..10000000) after byte K (1..255)", val);
    return false;
}

/* The serial-layer kinds: 1 set, 0 bad value (err), -1 not one of them. */
static int parse_serial(sim_fault_t *f, const char *kind, const char *val, char *err, size_t cap)
{
    uint32_t v = 0;
    if (strcmp(kind, "gap") == 0) {
        return parse_gap(f, val, err, cap) ? 1 : 0;
    }
    uint16_t *byte_k = strcmp(kind, "parity") == 0    ? &f->parity_k
                       : strcmp(kind, "framing") == 0 ? &f->framing_k
                                                      : NULL;
    if (byte_k != NULL) {
        if (!parse_u32(val, 255u, &v)) {
            snprintf(err, cap, "%s=%s: the byte of each frame, 1..255 (0: off)", kind, val);
            return 0;
        }
        *byte_k = (uint16_t)v;
        return 1;
    }
    if (strcmp(kind, "break") == 0 || strcmp(kind, "early") == 0) {
        bool brk = kind[0] == 'b';
        if (!parse_u32(val, brk ? 10000u : 1000000u, &v)) {
            snprintf(err, cap, brk ? "break=%s: a BREAK of MS ms, 0..10000"
                                   : "early=%s: US after the reply's end, 0..1000000", val);
            return 0;
        }
        *(brk ? &f->break_ms : &f->early_us) = v;
        return 1;
    }
    if (strcmp(kind, "de_cut") == 0) {
        if (!parse_u32(val, 12u, &v)) {
            snprintf(err, cap, "de_cut=%s: bits of the last character cut, 0..12", val);
            return 0;
        }
        f->de_cut_bits = (uint8_t)v;
        return 1;
    }
    return -1;
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
    int sr = parse_serial(f, kind, val, err, cap);
    if (sr >= 0) {
        return sr == 1;
    }
    snprintf(err, cap, "unknown fault '%s' (drop crc exc06 exc04 delay silent noise parity "
                       "framing break gap de_cut early)", kind);
    return false;
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
        pdu[0] = (uint8_t)((sim_hex_value(in[1]) << 4) | sim_hex_value(in[2]));
        pdu[1] = (uint8_t)((sim_hex_value(in[3]) << 4) | sim_hex_value(in[4]));
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
            int v = sim_hex_value(buf[len - 3u]);
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

static void note_add(char *note, size_t cap, const char *what)
{
    size_t nl = strlen(note);
    snprintf(note + nl, cap - nl, "%s(fault: %s)", nl > 0u ? " " : "", what);
}

/* The rest of s after byte k as a sender of its own, starting at t0 (its faults moved
 * with it); s keeps bytes 1..k. NULL: no sender free. */
static sender_t *split_after(sim_bus_t *b, sender_t *s, uint16_t k, double t0)
{
    sender_t *rest = new_sender(b);
    if (rest == NULL) {
        return NULL;
    }
    *rest = *s;
    rest->len = (uint16_t)(s->len - k);
    memmove(rest->b, s->b + k, rest->len);
    rest->t0 = t0;
    rest->parity_k = s->parity_k > k ? (uint16_t)(s->parity_k - k) : 0u;
    rest->framing_k = s->framing_k > k ? (uint16_t)(s->framing_k - k) : 0u;
    s->len = k;
    s->cut_bits = 0;
    s->parity_k = s->parity_k <= k ? s->parity_k : 0u;
    s->framing_k = s->framing_k <= k ? s->framing_k : 0u;
    return rest;
}

/* A BREAK after s's first character, the rest after it; returns the senders made. */
static size_t add_break(sim_bus_t *b, sim_fault_t *f, sender_t *s, sender_t **extra)
{
    size_t n = 0;
    sender_t *z = new_sender(b);
    if (z == NULL) {
        return 0;
    }
    z->who = s->who;
    z->t0 = s->t0 + b->c_us; /* after the first character */
    z->low_us = (double)f->break_ms * 1000.0;
    z->used = true;
    extra[n++] = z;
    f->breaks_sent++;
    if (s->len > 1u) {
        sender_t *rest = split_after(b, s, 1u, z->t0 + z->low_us + b->bit_us);
        if (rest != NULL) {
            extra[n++] = rest;
        }
    }
    return n;
}

size_t serial_faults(sim_bus_t *b, sim_fault_t *f, sender_t *s, sender_t **extra, char *note,
                     size_t cap)
{
    char what[64];
    size_t n_extra = 0;
    if (f->parity_k != 0u && f->parity_k <= s->len && b->line.parity != 0u) {
        s->parity_k = f->parity_k;
        f->parity_errs++;
        snprintf(what, sizeof what, "parity error on byte %u", (unsigned)f->parity_k);
        note_add(note, cap, what);
    }
    if (f->framing_k != 0u && f->framing_k <= s->len) {
        s->framing_k = f->framing_k;
        f->framing_errs++;
        snprintf(what, sizeof what, "framing error on byte %u", (unsigned)f->framing_k);
        note_add(note, cap, what);
    }
    if (f->de_cut_bits != 0u) {
        s->cut_bits = f->de_cut_bits < b->nbits ? f->de_cut_bits : (uint8_t)(b->nbits - 1u);
        f->de_cuts++;
        snprintf(what, sizeof what, "DE off %u bits early", (unsigned)s->cut_bits);
        note_add(note, cap, what);
    }
    if (f->gap_k != 0u && f->gap_k < s->len) {
        sender_t *rest = split_after(b, s, f->gap_k,
                                     s->t0 + (double)f->gap_k * b->c_us + (double)f->gap_us);
        if (rest != NULL) {
            extra[n_extra++] = rest;
            f->gaps_made++;
            snprintf(what, sizeof what, "%u us gap after byte %u", (unsigned)f->gap_us,
                     (unsigned)f->gap_k);
            note_add(note, cap, what);
        }
    }
    if (f->break_ms != 0u) {
        size_t k = add_break(b, f, s, extra + n_extra);
        if (k > 0u) {
            n_extra += k;
            snprintf(what, sizeof what, "BREAK of %u ms after byte 1", (unsigned)f->break_ms);
            note_add(note, cap, what);
        }
    }
    return n_extra;
}

/* ---- faults from the console ------------------------------------------------------ */

bool sim_bus_fault_set(sim_bus_t *b, size_t m, const char *spec, char *err, size_t cap)
{
    if (m >= b->n && m != SIM_BUS_MASTER) {
        snprintf(err, cap, "no member %zu", m + 1u);
        return false;
    }
    pthread_mutex_lock(&b->mu);
    sim_fault_t *dst = m == SIM_BUS_MASTER ? &b->mfault : &b->fault[m];
    sim_fault_t f = *dst;
    bool ok = sim_fault_parse(&f, spec, err, cap);
    if (ok && m == SIM_BUS_MASTER &&
        (f.drop_pct | f.crc_pct | f.exc06_pct | f.exc04_pct | f.delay_max_ms | f.silent_left |
         f.noise_bytes) != 0u) {
        snprintf(err, cap, "'%s': the master's direction takes the serial faults only (parity "
                           "framing break gap de_cut early)", spec);
        ok = false;
    }
    if (ok && m != SIM_BUS_MASTER && f.early_us != 0u) {
        snprintf(err, cap, "'%s': early is a fault of the master's direction (@master)", spec);
        ok = false;
    }
    if (ok) {
        f.used = true;
        *dst = f;
    }
    pthread_mutex_unlock(&b->mu);
    return ok;
}

bool sim_bus_master_faulted(sim_bus_t *b)
{
    sim_fault_t f = sim_bus_fault_get(b, SIM_BUS_MASTER);
    return f.replies != 0u || (f.parity_k | f.framing_k | f.gap_k | f.de_cut_bits) != 0u ||
           (f.break_ms | f.early_us) != 0u;
}

sim_fault_t sim_bus_fault_get(sim_bus_t *b, size_t m)
{
    pthread_mutex_lock(&b->mu);
    sim_fault_t f = m == SIM_BUS_MASTER ? b->mfault : b->fault[m < b->n ? m : 0u];
    pthread_mutex_unlock(&b->mu);
    return f;
}

/* " parity=K framing=K break=MS gap=K:US de_cut=B[ early=US]" and the counters */
static void describe_serial(const sim_fault_t *f, bool master, char *set, size_t scap,
                            char *cnt, size_t ccap)
{
    int k = snprintf(set, scap, " parity=%u framing=%u break=%u gap=%u:%u de_cut=%u",
                     (unsigned)f->parity_k, (unsigned)f->framing_k, (unsigned)f->break_ms,
                     (unsigned)f->gap_k, (unsigned)f->gap_us, (unsigned)f->de_cut_bits);
    if (master && k > 0 && (size_t)k < scap) {
        snprintf(set + k, scap - (size_t)k, " early=%u", (unsigned)f->early_us);
    }
    k = snprintf(cnt, ccap, " parity_errors=%u framing_errors=%u breaks=%u gaps=%u de_cuts=%u",
                 (unsigned)f->parity_errs, (unsigned)f->framing_errs, (unsigned)f->breaks_sent,
                 (unsigned)f->gaps_made, (unsigned)f->de_cuts);
    if (master && k > 0 && (size_t)k < ccap) {
        snprintf(cnt + k, ccap - (size_t)k, " early=%u", (unsigned)f->early_sent);
    }
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
    char serial[160], counts[200];
    describe_serial(&f, m == SIM_BUS_MASTER, serial, sizeof serial, counts, sizeof counts);
    if (m == SIM_BUS_MASTER) {
        snprintf(out, cap, "master faults: serial:%s | requests=%u%s", serial, (unsigned)f.replies,
                 counts);
        return;
    }
    snprintf(out, cap,
             "faults: drop=%u%% crc=%u%% exc06=%u%% exc04=%u%% delay=%s silent=%u noise=%u | "
             "replies=%u dropped=%u crc_corrupted=%u exc06_sent=%u exc04_sent=%u delayed=%u "
             "silenced=%u noise_bytes=%u collisions=%u | serial:%s |%s",
             (unsigned)f.drop_pct, (unsigned)f.crc_pct, (unsigned)f.exc06_pct,
             (unsigned)f.exc04_pct, delay, (unsigned)f.silent_left, (unsigned)f.noise_bytes,
             (unsigned)f.replies, (unsigned)f.dropped, (unsigned)f.crc_corrupted,
             (unsigned)f.exc06, (unsigned)f.exc04, (unsigned)f.delayed, (unsigned)f.silenced,
             (unsigned)f.noise_sent, (unsigned)f.collisions, serial, counts);
}
