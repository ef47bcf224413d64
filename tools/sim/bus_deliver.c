/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — what the line's receiver heard, handed to the master's pty and to the members. */
#define _GNU_SOURCE
#include "bus_internal.h"

/* What the receiver heard, cut at t3.5: a collision counted for each member that sent
 * in it and, with the trace on, noted on the line at the frame's end (when it is known;
 * the senders' own frames are traced from the line). */
void heard_flush(sim_bus_t *b)
{
    if (b->heard_len > 0u && b->heard_collided) {
        for (size_t m = 0; m < b->n; m++) {
            if (mset_has(&b->heard_mask, m)) {
                b->fault[m].collisions++;
            }
        }
        if (atomic_load(&b->trace_on)) {
            char label[160];
            size_t pos = (size_t)snprintf(label, sizeof label, "collision");
            for (size_t m = 0; m < b->n; m++) {
                if (!mset_has(&b->heard_mask, m)) {
                    continue;
                }
                if (pos + 32u > sizeof label) { /* 247 members fit no line */
                    pos += (size_t)snprintf(label + pos, sizeof label - pos, " ...");
                    break;
                }
                pos += (size_t)snprintf(label + pos, sizeof label - pos, " @%s", b->names[m]);
            }
            snprintf(label + pos, sizeof label - pos, ", the line carried");
            char line[SIM_TRACE_LINE];
            sim_trace_format(&b->tr, label, b->heard, b->heard_len, true, false, NULL, line,
                             sizeof line);
            sim_line_note(b->wire, (uint64_t)b->heard_end, SIM_SRC_NOISE, SIM_NOTE_LINE, "%s", line);
        }
    }
    b->heard_len = 0;
    b->heard_collided = false;
    memset(&b->heard_mask, 0, sizeof b->heard_mask);
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


/* Characters for member m, each ending on the line at t (us since the bus's t0). */
void deliver(sim_bus_t *b, size_t m, const uint8_t *bytes, const uint8_t *errors, const double *t,
             size_t n)
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
    /* a frame begins after a silence of t1.5 at least (conservative: the core's t3.5) */
    double gap_min = (double)b->line.t35_us * 3.0 / 7.0;
    bool urgent = false;
    pthread_mutex_lock(&b->rx_mu);
    for (size_t i = 0; i < n; i++) {
        bool starts = b->last_t[m] <= 0.0 || t[i] - b->last_t[m] >= gap_min;
        uint8_t e = errors != NULL ? errors[i] : 0u;
        if (e != 0u || (starts && (bytes[i] == b->addr[m] || bytes[i] == 0u))) {
            urgent = true;
        }
        b->last_t[m] = t[i] > 0.0 ? t[i] : 1.0;
        size_t next = (b->rxq[m].head + 1u) % 8192u;
        if (next == b->rxq[m].tail) {
            break; /* the member does not read: drop, like an overrun */
        }
        b->rxq[m].b[b->rxq[m].head] = bytes[i];
        b->rxq[m].e[b->rxq[m].head] = errors != NULL ? errors[i] : 0u;
        b->rxq[m].t[b->rxq[m].head] = (uint32_t)(b->t0_us64 + (uint64_t)(t[i] < 0.0 ? 0.0 : t[i]));
        b->rxq[m].head = next;
    }
    pthread_mutex_unlock(&b->rx_mu);
    /* after the queue: a member that goes quiet now finds the characters at its tick */
    if (urgent || b->line.ascii || b->quiet[m] == NULL || !atomic_load(b->quiet[m])) {
        char c = 1;
        ssize_t r = write(b->wake_fd[m], &c, 1);
        (void)r;
    }
}

void sim_bus_member_quiet(sim_bus_t *b, size_t m, const atomic_bool *quiet)
{
    if (m < b->n) {
        b->quiet[m] = quiet;
    }
}

size_t sim_bus_take(sim_bus_t *b, size_t m, uint8_t *bytes, uint8_t *errors, uint32_t *t_us,
                    size_t cap, uint32_t until_us, bool *more)
{
    size_t k = 0;
    pthread_mutex_lock(&b->rx_mu);
    while (k < cap && b->rxq[m].tail != b->rxq[m].head &&
           (int32_t)(b->rxq[m].t[b->rxq[m].tail] - until_us) <= 0) {
        bytes[k] = b->rxq[m].b[b->rxq[m].tail];
        errors[k] = b->rxq[m].e[b->rxq[m].tail];
        t_us[k] = b->rxq[m].t[b->rxq[m].tail];
        k++;
        b->rxq[m].tail = (b->rxq[m].tail + 1u) % 8192u;
    }
    *more = b->rxq[m].tail != b->rxq[m].head &&
            (int32_t)(b->rxq[m].t[b->rxq[m].tail] - until_us) <= 0;
    pthread_mutex_unlock(&b->rx_mu);
    return k;
}

bool sim_bus_next_time(sim_bus_t *b, size_t m, uint32_t *t_us)
{
    pthread_mutex_lock(&b->rx_mu);
    bool any = b->rxq[m].tail != b->rxq[m].head;
    if (any) {
        *t_us = b->rxq[m].t[b->rxq[m].tail];
    }
    pthread_mutex_unlock(&b->rx_mu);
    return any;
}

void master_write(sim_bus_t *b, const uint8_t *p, size_t n)
{
    if (n > 0u) {
        blog(b, "to master", p, n);
        write_all(b->master_fd, p, n);
    }
}

void members_flush(sim_bus_t *b)
{
    for (size_t m = 0; m < b->n && b->mlen > 0u; m++) {
        uint8_t out[SIM_TRACE_MAX], err[SIM_TRACE_MAX];
        double t[SIM_TRACE_MAX];
        size_t k = 0;
        for (size_t i = 0; i < b->mlen; i++) {
            if (!mset_has(&b->mdeaf[i], m)) {
                t[k] = b->mt[i];
                err[k] = b->merr[i];
                out[k++] = b->mbuf[i];
            }
        }
        deliver(b, m, out, err, t, k);
    }
    b->mlen = 0;
}
