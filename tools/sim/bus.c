/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — one line, several members (see bus.h). */
#define _GNU_SOURCE
#include "bus.h"
#include "bus_internal.h"

/* ---- time ------------------------------------------------------------------------ */

double now_rel(const sim_bus_t *b)
{
    return (double)(modcp_posix_now_us64() - b->t0_us64);
}

/* One line of the bus log (MODCP_SIM_BUS_LOG): "<s.us> <what> [bytes]". Any thread. */
void blog(sim_bus_t *b, const char *what, const uint8_t *p, size_t n)
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

/* ---- construction ----------------------------------------------------------------- */

static void trace_print(void *user, const char *line)
{
    sim_bus_t *b = user;
    b->print(b->user, line);
}

sim_bus_t *sim_bus_new(const sim_line_cfg_t *line, size_t n, const char *const names[],
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

void sim_bus_set_line(sim_bus_t *b, sim_line_t *wire, bool solo)
{
    b->wire = wire;
    b->solo = solo;
}

/* ---- replies onto the line ------------------------------------------------------- */

sender_t *new_sender(sim_bus_t *b)
{
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (!b->s[i].used) {
            memset(&b->s[i], 0, sizeof b->s[i]); /* no faults of its last use */
            if (i + 1u > b->s_hi) {
                b->s_hi = i + 1u;
            }
            return &b->s[i];
        }
    }
    return NULL; /* more than MAX_SENDERS at once: the reply is lost */
}

/* The trace of member m's reply at t: a reply not sent (on_line false) as a line of its
 * own, the note of one sent as the remark of its frame on the line (put before it). */
static void trace_line(sim_bus_t *b, size_t m, const char *label, const uint8_t *buf, size_t len,
                       double t, const char *note, bool on_line)
{
    if (!atomic_load(&b->trace_on)) {
        return;
    }
    uint64_t tu = (uint64_t)(t < 0.0 ? 0.0 : t);
    if (on_line) {
        if (note != NULL && note[0] != '\0') {
            sim_line_note(b->wire, tu, (int)m, SIM_NOTE_FRAME, "%s", note);
        }
        return;
    }
    char line[SIM_TRACE_LINE];
    sim_trace_format(&b->tr, label, buf, len, true, false, note, line, sizeof line);
    sim_line_note(b->wire, tu, (int)m, SIM_NOTE_LINE, "%s", line);
}

/* A transmission to the line model, with its serial faults as the characters' flags. */
static void line_put_sender(sim_bus_t *b, const sender_t *s)
{
    if (!sim_line_watched(b->wire)) {
        return;
    }
    uint64_t t0 = (uint64_t)(s->t0 < 0.0 ? 0.0 : s->t0);
    if (s->low_us > 0.0) {
        sim_char_t c = {t0, (uint32_t)s->low_us, 0, (int16_t)s->who, 0, SIM_CH_BREAK};
        sim_line_put(b->wire, &c);
        return;
    }
    for (size_t k = 0; k < s->len; k++) {
        sim_char_t c = {t0 + (uint64_t)((double)k * b->c_us), b->line.char_us, 0, (int16_t)s->who,
                        s->b[k], 0};
        if (k + 1u == s->parity_k) {
            c.flags |= SIM_CH_PARITY;
        }
        if (k + 1u == s->framing_k) {
            c.flags |= SIM_CH_FRAMING;
        }
        if (k + 1u == s->len && s->cut_bits != 0u) {
            c.flags |= SIM_CH_DE_CUT;
            c.de_off_us = (uint32_t)((double)(b->nbits - s->cut_bits) * b->bit_us);
        }
        sim_line_put(b->wire, &c);
    }
}

/* The noise fault: f->noise_bytes random characters one t3.5 after member m's reply s
 * (b->mu held). */
static void add_noise(sim_bus_t *b, size_t m, const sender_t *s)
{
    sim_fault_t *f = &b->fault[m];
    sender_t *z = new_sender(b);
    if (z == NULL) {
        return;
    }
    z->who = NOISE;
    z->len = f->noise_bytes;
    for (uint16_t i = 0; i < z->len; i++) {
        z->b[i] = (uint8_t)(rnd(b) >> 7);
    }
    z->t0 = end_of(b, s) + (double)b->line.t35_us;
    z->used = true;
    f->noise_sent += z->len;
    sim_line_put_frame(b->wire, SIM_SRC_NOISE, z->b, NULL, z->len, (uint64_t)z->t0);
    if (atomic_load(&b->trace_on)) {
        char line[SIM_NOTE_MAX];
        size_t pos = (size_t)snprintf(line, sizeof line, "noise (fault of @%s)", b->names[m]);
        for (uint16_t i = 0; i < z->len && pos + 4u < sizeof line; i++) {
            pos += (size_t)snprintf(line + pos, sizeof line - pos, " %02X", z->b[i]);
        }
        sim_line_note(b->wire, (uint64_t)z->t0, SIM_SRC_NOISE, SIM_NOTE_LINE, "%s", line);
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
    if (b->solo) {
        snprintf(label, sizeof label, "slave %u", (unsigned)b->addr[m]);
    } else {
        snprintf(label, sizeof label, "@%s slave %u", b->names[m], (unsigned)b->addr[m]);
    }
    pthread_mutex_lock(&b->mu);
    sim_fault_t *f = &b->fault[m];
    f->replies++;
    char note[96] = "";
    if (f->silent_left > 0u) {
        f->silent_left--;
        f->silenced++;
        trace_line(b, m, label, buf, len, t0, "(fault: silent, not on the line)", false);
        pthread_mutex_unlock(&b->mu);
        return;
    }
    if (chance(b, f->drop_pct)) {
        f->dropped++;
        trace_line(b, m, label, buf, len, t0, "(fault: dropped, not on the line)", false);
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
    t0 += reply_faults(b, f, s->b, &s->len, note, sizeof note);
    s->t0 = t0;
    s->used = true;
    sender_t *extra[3];
    size_t n_extra = serial_faults(b, f, s, extra, note, sizeof note);
    trace_line(b, m, label, s->b, s->len, t0, note, true); /* before its characters */
    line_put_sender(b, s);
    for (size_t i = 0; i < n_extra; i++) {
        line_put_sender(b, extra[i]);
    }
    b->reply_end = end_of(b, n_extra > 0u ? extra[n_extra - 1u] : s);
    if (f->noise_bytes > 0u) {
        add_noise(b, m, s);
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
    for (size_t i = 0; i < b->s_hi; i++) {
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
    sim_line_put_frame(b->wire, (int)m, buf, NULL, n, (uint64_t)(s->t0 + (double)s->len * b->c_us));
    s->len = (uint16_t)(s->len + n);
    pthread_mutex_unlock(&b->mu);
}

/* ---- the bus thread ----------------------------------------------------------------- */

/* Is member m sending at any time in [a, z)? (then its transceiver does not hear) */
static bool member_sending(const sim_bus_t *b, size_t m, double a, double z)
{
    for (size_t i = 0; i < b->s_hi; i++) {
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
        double at = ch.start + ch.len_us;
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
        mo[mol++] = ch.errors != 0u ? 0u : ch.byte; /* as termios reads it (INPCK, no PARMRK) */
        mset_t deaf;
        memset(&deaf, 0, sizeof deaf);
        for (size_t m = 0; m < b->n; m++) {
            if (member_sending(b, m, ch.start, at)) {
                mset_add(&deaf, m);
            }
        }
        b->mbuf[b->mlen] = ch.byte;
        b->merr[b->mlen] = ch.errors;
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
        mset_or(&b->heard_mask, &ch.mask);
        if (ch.senders > 1u) {
            b->heard_collided = true;
        }
        b->from = (ch.errors & MODCP_LINE_BREAK) != 0u
                      ? ch.start + ch.len_us
                      : ch.start + ((double)b->nbits - 0.5) * b->bit_us;
    }
    members_flush(b); /* nothing follows back to back */
    master_write(b, mo, mol);
    /* senders the receiver is done with */
    for (size_t i = 0; i < b->s_hi; i++) {
        if (b->s[i].used && end_of(b, &b->s[i]) <= b->from + 0.5 * b->bit_us &&
            end_of(b, &b->s[i]) <= now) {
            b->s[i].used = false;
        }
    }
    while (b->s_hi > 0u && !b->s[b->s_hi - 1u].used) {
        b->s_hi--;
    }
    if (b->heard_len > 0u && now - b->heard_end >= (double)b->line.t35_us) {
        heard_flush(b);
    }
    return -1.0;
}

/* How long the bus thread may sleep: until SPIN_US before the next character (then it
 * watches the clock: *spin), or until a later character of a frame, or the 5 ms tick. */
static double wait_for(double now, double next, bool later, bool *spin)
{
    double wait_us = 5000.0;
    *spin = false;
    if (next >= 0.0 && later) { /* a later character of a frame: just sleep until it */
        double d = next - now;
        wait_us = d < wait_us ? (d > 0.0 ? d : 0.0) : wait_us;
    } else if (next >= 0.0) { /* (-1: nothing on the line, the 5 ms tick) */
        double d = next - now;
        if (d < wait_us) {
            wait_us = d > SPIN_US ? d - SPIN_US : 0.0;
            *spin = true;
        }
    }
    return wait_us;
}

static int bus_poll(sim_bus_t *b, struct pollfd *pf, nfds_t nf, double wait_us, bool spin,
                    double next)
{
    struct timespec ts = {(time_t)(wait_us / 1e6),
                          (long)((long long)(wait_us * 1000.0) % 1000000000LL)};
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
    return pr;
}

/* The master wrote: every member hears it at once (a pty delivers a request at once, as
 * to one slave); the line model gets it, its last stop bit ending at t. */
static void master_read(sim_bus_t *b, double t)
{
    uint8_t buf[512];
    ssize_t n = read(b->master_fd, buf, sizeof buf);
    if (b->log != NULL) {
        char what[64];
        snprintf(what, sizeof what, "master read %zd%s", n, n < 0 ? strerror(errno) : "");
        blog(b, what, buf, n > 0 ? (size_t)n : 0u);
    }
    if (n < 0 && errno == EIO) {
        struct timespec s1 = {0, 1000000L};
        nanosleep(&s1, NULL);
    }
    if (n <= 0) {
        return;
    }
    pthread_mutex_lock(&b->mu);
    members_flush(b); /* what the line carried before comes first */
    const sim_fault_t *f = &b->mfault;
    bool faulted = (f->parity_k | f->framing_k | f->gap_k | f->de_cut_bits) != 0u ||
                   (f->break_ms | f->early_us) != 0u;
    if (faulted) {
        master_faults(b, buf, (size_t)n, t);
        (void)master_due(b, t);
    }
    pthread_mutex_unlock(&b->mu);
    if (!faulted) {
        double at_[512];
        for (ssize_t i = 0; i < n; i++) {
            at_[i] = t;
        }
        for (size_t m = 0; m < b->n; m++) {
            deliver(b, m, buf, NULL, at_, (size_t)n);
        }
        sim_line_put_arrived(b->wire, SIM_SRC_MASTER, buf, NULL, (size_t)n, (uint64_t)t);
    }
}

/* What the members' ptys gave: an external member's characters go on the line; a
 * member of ours sends its paced copy of its reply, which the bus has already. */
static void members_read(sim_bus_t *b, const struct pollfd *pf)
{
    for (size_t m = 0; m < b->n; m++) {
        if ((pf[m].revents & POLLIN) != 0) {
            uint8_t got[512];
            ssize_t k;
            while ((k = read(b->member_fd[m], got, sizeof got)) > 0) {
                if (b->wake_fd[m] < 0) {
                    external_tx(b, m, got, (size_t)k, now_rel(b));
                }
            }
        }
    }
}

void *sim_bus_thread(void *arg)
{
    sim_bus_t *b = arg;
    struct pollfd pf[2 + SIM_BUS_MAX_MEMBERS];
    nfds_t nf = 0;
    pf[nf++] = (struct pollfd){b->wake.rd, POLLIN, 0};
    pf[nf++] = (struct pollfd){b->master_fd, POLLIN, 0};
    /* only external members' ttys: a member of ours hands its reply over (sim_bus_tx);
     * the paced copy it writes to its own pty is not read (a full pty drops it), so 247
     * idle ptys cost the bus's poll nothing */
    for (size_t m = 0; m < b->n; m++) {
        pf[nf++] = (struct pollfd){b->wake_fd[m] < 0 ? b->member_fd[m] : -1, POLLIN, 0};
    }
    pthread_mutex_lock(&b->mu);
    b->from = now_rel(b);
    pthread_mutex_unlock(&b->mu);
    while (!atomic_load(&b->stop)) {
        double now = now_rel(b);
        pthread_mutex_lock(&b->mu);
        bool later = false;
        double next = emit_due(b, now, &later);
        double mnext = master_due(b, now);
        pthread_mutex_unlock(&b->mu);
        if (mnext >= 0.0 && (next < 0.0 || mnext < next)) {
            next = mnext; /* the master's next character (a gap, a BREAK): on time */
            later = false;
        }
        sim_line_tick(b->wire, (uint64_t)now);
        bool spin = false;
        double wait_us = wait_for(now, next, later, &spin);
        int pr = bus_poll(b, pf, nf, wait_us, spin, next);
        if (pr < 0) {
            continue;
        }
        double t = now_rel(b);
        if ((pf[0].revents & POLLIN) != 0) {
            modcp_posix_event_clear(&b->wake);
        }
        if ((pf[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
            master_read(b, t);
        }
        members_read(b, pf + 2);
    }
    return NULL;
}
