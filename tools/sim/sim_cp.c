/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the CP thread: the UART, the one-shot timer and the paced reply around modcp_cp_*. */
#define _GNU_SOURCE
#include "sim.h"

/* ---- CP thread ----------------------------------------------------------------- */

void cp_snapshot(member_t *m)
{
    pthread_mutex_lock(&m->snap_mu);
    m->snap_diag = m->cp.diag;
    m->snap_configured = m->cp.configured;
    m->snap_ready = modcp_cp_ready(&m->cp);
    m->snap_param_event = m->cp.param_event;
    pthread_mutex_unlock(&m->snap_mu);
}

/* The events the core raised since the last call, to the trace at t (the core's time):
 * through the line, in time order with the frames. */
static void trace_events(member_t *m, uint64_t t)
{
    uint32_t total = m->cp.diag.events_total;
    if (total == m->events_seen) {
        return;
    }
    uint32_t n = total - m->events_seen;
    m->events_seen = total;
    if (!atomic_load(&m->sim->trace_on)) {
        return;
    }
    if (n > m->cp.diag.buffer_len) {
        n = m->cp.diag.buffer_len;
    }
    for (uint32_t i = n; i > 0u; i--) {
        char line[512];
        sim_trace_format_event(m->tr.ev_label, m->cp.diag.buffer[i - 1u], line, sizeof line);
        sim_line_note(&m->sim->wire, t, (int)m->index, SIM_NOTE_LINE, "%s", line);
    }
}

/* This thread's processor, -1 when unknown. */
int this_core(void)
{
#ifdef __linux__
    return sched_getcpu();
#else
    return -1;
#endif
}

/* The calling thread last ran on processor `core` too. Two threads that watch the
 * clock on one processor take turns: the CP thread watching for the reply there would
 * hold off the very FB call that makes it (until the scheduler preempts it, ~50 us). */
static bool same_core(int core)
{
    return core >= 0 && core == this_core();
}

/* Blocks published on a ring and not yet taken by its consumer. */
bool ring_pending(const modcp_ring_t *r)
{
    return atomic_load_explicit(&r->head, memory_order_acquire) !=
           atomic_load_explicit(&r->tail, memory_order_relaxed);
}

/* On a bus: our reply ended before anything heard after it (we were deaf while
 * sending): its end first, at its time on the line. */
static void bus_tx_done(member_t *m, uint32_t now)
{
    uint32_t end = m->port.tx_t0_us + (uint32_t)m->port.tx_len * m->port.char_us;
    if ((int32_t)(end - m->core_t) < 0) {
        end = m->core_t;
    }
    if ((int32_t)(now - end) < 0) {
        end = now;
    }
    m->port.now_us = end;
    modcp_cp_on_tx_done(&m->cp, end);
    m->core_t = end;
}

/* On a bus: the one-shot timer, each time it is due by t, at its deadline. */
static void timers_due(member_t *m, uint32_t t)
{
    while (m->port.timer_armed && (int32_t)(t - m->port.timer_deadline_us) >= 0) {
        uint32_t d = m->port.timer_deadline_us;
        if ((int32_t)(d - m->core_t) < 0) {
            d = m->core_t;
        }
        m->port.timer_armed = false;
        m->port.now_us = d;
        modcp_cp_on_timer(&m->cp, d);
        m->core_t = d;
    }
}

/* On a bus: one character heard at ti (the member's clock), after the timer when it fell
 * due first. */
static void bus_char(member_t *m, uint8_t byte, uint8_t errors, uint32_t ti, uint32_t now, bool tr,
                     uint64_t n64)
{
    if ((int32_t)(ti - m->core_t) < 0) {
        ti = m->core_t; /* never back in time for the core */
    }
    if ((int32_t)(now - ti) < 0) {
        ti = now;
    }
    timers_due(m, ti);
    m->port.now_us = ti;
    if (tr) {
        uint64_t tb = n64 - (uint32_t)((uint32_t)n64 - ti) - m->sim->t0_us64;
        sim_trace_rx(&m->tr, byte, errors, tb);
    }
    if (errors != 0u) {
        modcp_cp_on_line_error(&m->cp, errors, ti);
    } else {
        modcp_cp_on_rx(&m->cp, byte, ti);
    }
    m->core_t = ti;
}

/* On a bus: the characters heard, each at its time on the line, and the timer between
 * them when it fell due first. *timer: the timer is due at now after them. */
static void bus_turn(member_t *m, uint32_t now, bool *tx_done, bool *timer, bool tr, uint64_t n64)
{
    sim_t *s = m->sim;
    if (*timer) {
        m->port.timer_armed = true; /* ordered with the characters below */
        *timer = false;
    }
    if (*tx_done) {
        bus_tx_done(m, now);
        *tx_done = false;
    }
    uint8_t bb[RX_CHUNK], be[RX_CHUNK];
    uint32_t bt[RX_CHUNK];
    bool more = false;
    size_t k = sim_bus_take(s->bus, m->index, bb, be, bt, RX_CHUNK, now, &more);
    sim_latlog_rx(&m->lat, k, now);
    if (more) {
        modcp_posix_wake(&m->port); /* more due than one turn takes */
    }
    /* characters whose time lies after `now` (they arrived after `now` was read, or a
     * faulted request handed over ahead): a later turn takes them, cp_wait wakes for
     * them (pulled back to `now` they could precede the end of our own reply: (08)37H,
     * the request lost) */
    for (size_t i = 0; i < k; i++) {
        bus_char(m, bb[i], be[i], bt[i], now, tr, n64);
    }
    if (m->port.timer_armed && (int32_t)(now - m->port.timer_deadline_us) >= 0) {
        m->port.timer_armed = false;
        *timer = true;
    }
    m->core_t = now;
}

/* One slave on its own line (a serial device): the characters read at now (t: since
 * start), to the line model (and so to the trace) and the core. */
static void own_line_rx(member_t *m, const modcp_posix_rx_t *rx, int n, uint32_t now, uint64_t t)
{
    if (n > 0 && m->sim->bus == NULL && sim_line_watched(&m->sim->wire)) {
        uint8_t b[RX_CHUNK], fl[RX_CHUNK];
        for (int i = 0; i < n; i++) {
            uint8_t e = rx[i].errors;
            b[i] = rx[i].byte;
            fl[i] = (uint8_t)(((e & MODCP_LINE_PARITY) != 0u ? SIM_CH_PARITY : 0u) |
                              ((e & MODCP_LINE_FRAMING) != 0u ? SIM_CH_FRAMING : 0u) |
                              ((e & MODCP_LINE_BREAK) != 0u ? SIM_CH_BREAK : 0u));
        }
        sim_line_put_arrived(&m->sim->wire, SIM_SRC_MASTER, b, fl, (size_t)n, t);
    }
    for (int i = 0; i < n; i++) {
        if (rx[i].errors != 0u) {
            modcp_cp_on_line_error(&m->cp, rx[i].errors, now);
        } else {
            modcp_cp_on_rx(&m->cp, rx[i].byte, now);
        }
    }
}

bool cp_is_quiet(const member_t *m)
{
    return modcp_cp_ready(&m->cp) && !modcp_job_busy(&m->cp.job) && !m->cp.request_pending &&
           !m->port.timer_armed && !m->port.tx_active && !ring_pending(&m->bp.to_cp);
}

/* How long the CP thread may wait, the reply it watches for (port.expect_*): decided
 * under cp_mu, before the wait (the wait itself reads no core state). */
static uint32_t cp_plan(member_t *m)
{
    bool idle = modcp_cp_ready(&m->cp) && !modcp_job_busy(&m->cp.job) && !m->cp.request_pending;
    /* a job on the backplane: its reply comes at the CPU side's next FB call, watched
     * for (the backplane interrupt is immediate on a real CP) */
    m->port.expect_armed = m->cp.request_pending && !ring_pending(&m->bp.to_cp) &&
                           atomic_load_explicit(&m->cpu_calls, memory_order_relaxed) &&
                           !same_core(atomic_load_explicit(&m->cpu_core, memory_order_relaxed));
    m->port.expect_us = atomic_load_explicit(&m->cpu_due, memory_order_relaxed);
    sim_latlog_before_wait(&m->lat, &m->port);
    uint32_t max_us = idle ? IDLE_TICK_US : BUSY_TICK_US;
    uint32_t next = 0;
    if (m->sim->bus != NULL && sim_bus_next_time(m->sim->bus, m->index, &next)) {
        int32_t d = (int32_t)(next - modcp_posix_now_us());
        max_us = d <= 0 ? 0u : (uint32_t)d < max_us ? (uint32_t)d : max_us;
    }
    return max_us;
}

/* A quiet CP's thread: asleep until its line has characters or it is woken (a frame for
 * it, blocks from the FB, the scheduler's tick gave it work), QUIET_MAX_US at most. It
 * touches nothing of the member: meanwhile the scheduler's tick runs its core
 * (cp_visit), under cp_mu, which this thread does not hold. */
static void quiet_sleep(const member_t *m)
{
    struct pollfd pfs[2] = {{m->port.fd, POLLIN, 0}, {m->port.wake.rd, POLLIN, 0}};
    struct timespec ts;
    timespec_of(QUIET_MAX_US, &ts);
    (void)ppoll(pfs, m->port.wake.rd >= 0 ? 2u : 1u, &ts, NULL);
}

/* Wait for the next event with cp_mu held on entry and on return; n characters (< 0: a
 * read error). Quiet (nothing to do but supervision): cp_quiet is set under cp_mu, so
 * the scheduler's tick (cp_visit, which checks it under cp_mu) runs the core only while
 * this thread is in quiet_sleep, and it is cleared under cp_mu before this thread
 * touches the port or the core again: the two never run the member at once. */
static int cp_wait(member_t *m, modcp_posix_rx_t *rx, bool *tx_done, bool *timer, uint32_t *now)
{
    uint32_t max_us = 0;
    bool quiet = cp_is_quiet(m);
    if (quiet) {
        atomic_store(&m->cp_quiet, true);
        sim_latlog_before_wait(&m->lat, &m->port);
    } else {
        max_us = cp_plan(m);
    }
    pthread_mutex_unlock(&m->cp_mu);
    if (quiet) {
        quiet_sleep(m);
    } else {
        /* not quiet: the scheduler's tick leaves the member alone */
        int n = modcp_posix_wait(&m->port, max_us, rx, RX_CHUNK, tx_done, timer, now);
        pthread_mutex_lock(&m->cp_mu);
        sim_latlog_after_wait(&m->lat, &m->port, n, *timer, *now);
        return n;
    }
    pthread_mutex_lock(&m->cp_mu);
    atomic_store(&m->cp_quiet, false);
    /* what woke it (and what the tick left due), without waiting */
    m->port.expect_armed = false;
    int n = modcp_posix_wait(&m->port, 0u, rx, RX_CHUNK, tx_done, timer, now);
    sim_latlog_after_wait(&m->lat, &m->port, n, *timer, *now);
    return n;
}

/* After the core ran: the backplane interrupt, the trace, the console's snapshot. */
void cp_after(member_t *m, uint32_t now, uint64_t t, bool tr)
{
    sim_latlog_after_core(&m->lat, &m->cp, &m->port, now);
    uint32_t put = atomic_load_explicit(&m->bp.to_cpu.head, memory_order_relaxed);
    if (put != m->cp_put_seen) {
        m->cp_put_seen = put;
        modcp_posix_event_signal(&m->sim->sched_irq); /* the backplane interrupt */
    }
    if (tr) {
        sim_trace_poll(&m->tr, t); /* MODCP_SIM_MEMBER_RX: what the member heard */
    }
    trace_events(m, t);
    cp_snapshot(m);
    if (m->sim->bus == NULL) {
        sim_line_tick(&m->sim->wire, t);
    }
}

void *cp_thread(void *arg)
{
    member_t *m = arg;
    sim_t *s = m->sim;
    modcp_posix_rx_t rx[RX_CHUNK];
    /* the trace reads the line; on a bus MODCP_SIM_MEMBER_RX=1 adds what each member
     * heard (a debugging aid: "@b heard ...") */
    bool line_trace = s->bus != NULL && getenv("MODCP_SIM_MEMBER_RX") != NULL;
    if (s->bus != NULL) {
        char l[32];
        snprintf(l, sizeof l, "@%s heard", m->name);
        sim_trace_labels(&m->tr, l, NULL, NULL);
    }
    pthread_mutex_lock(&m->cp_mu);
    while (!atomic_load(&s->stop)) {
        bool tx_done = false, timer = false;
        uint32_t now = 0;
        int n = cp_wait(m, rx, &tx_done, &timer, &now);
        if ((int32_t)(now - m->core_t) < 0) {
            now = m->core_t; /* the scheduler's tick polled the core meanwhile */
        }
        if (n < 0) {
            printf_line(s, "modcp-sim: read error on %s: %s", m->port.path, strerror(-n));
            atomic_store(&s->stop, true);
            break;
        }
        bool tr = line_trace && atomic_load(&s->trace_on);
        /* the trace's time is exactly the core's `now` (widened to 64 bits), so its
         * t3.5 frame cut agrees with the core's timer: a frame is printed before the
         * events its end raises */
        uint64_t n64 = modcp_posix_now_us64();
        uint64_t t = n64 - (uint32_t)((uint32_t)n64 - now) - s->t0_us64;
        if (s->bus != NULL) {
            bus_turn(m, now, &tx_done, &timer, tr, n64);
        }
        m->port.now_us = now;
        bool cts = true, dsr = true;
        if (modcp_posix_modem_inputs(&m->port, &cts, &dsr)) {
            modcp_cp_on_signals(&m->cp, cts, dsr, now);
        }
        if (tx_done) {
            modcp_cp_on_tx_done(&m->cp, now);
        }
        if (timer) {
            modcp_cp_on_timer(&m->cp, now);
        }
        own_line_rx(m, rx, n, now, t);
        modcp_cp_poll(&m->cp, now);
        m->core_t = now;
        cp_after(m, now, t, tr);
    }
    pthread_mutex_unlock(&m->cp_mu);
    return NULL;
}

/* On a bus, a quiet member (its thread asleep): the characters of the line up to t
 * (frames for other addresses, which did not wake it) and the timer due by then. */
static void bus_catch_up(member_t *m, uint32_t t)
{
    uint8_t bb[RX_CHUNK], be[RX_CHUNK];
    uint32_t bt[RX_CHUNK];
    uint64_t n64 = modcp_posix_now_us64();
    bool more = true;
    while (more) {
        size_t k = sim_bus_take(m->sim->bus, m->index, bb, be, bt, RX_CHUNK, t, &more);
        for (size_t i = 0; i < k; i++) {
            bus_char(m, bb[i], be[i], bt[i], t, false, n64);
        }
    }
    timers_due(m, t);
}

/* The CP has work its thread must do (a timer alone waits for the next tick: a frame
 * for another address, whose t3.5 ends it). */
static bool cp_has_work(const member_t *m)
{
    return !modcp_cp_ready(&m->cp) || modcp_job_busy(&m->cp.job) || m->cp.request_pending ||
           m->port.tx_active || ring_pending(&m->bp.to_cp);
}

void cp_visit(member_t *m, uint32_t now)
{
    sim_t *s = m->sim;
    if (!atomic_load(&m->cp_quiet) || pthread_mutex_trylock(&m->cp_mu) != 0) {
        return; /* its thread runs it */
    }
    if (atomic_load(&m->cp_quiet)) { /* under cp_mu: its thread is in quiet_sleep */
        /* a little in the past: characters the bus hands over late keep their times */
        uint32_t t = now - CP_VISIT_LAG_US;
        if ((int32_t)(t - m->core_t) < 0) {
            t = m->core_t;
        }
        if (s->bus != NULL) {
            bus_catch_up(m, t);
        }
        m->port.now_us = t;
        modcp_cp_poll(&m->cp, t);
        m->core_t = t;
        cp_after(m, t, since_start_of(s, t), false);
        if (cp_has_work(m)) {
            modcp_posix_wake(&m->port); /* it has work now: its thread takes over */
        }
    }
    pthread_mutex_unlock(&m->cp_mu);
}
