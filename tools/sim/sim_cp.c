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

static void trace_events(member_t *m)
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
    uint64_t t = since_start(m->sim);
    for (uint32_t i = n; i > 0u; i--) {
        sim_trace_event(&m->tr, m->cp.diag.buffer[i - 1u], t);
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

void *cp_thread(void *arg)
{
    member_t *m = arg;
    sim_t *s = m->sim;
    modcp_posix_rx_t rx[RX_CHUNK];
    /* on a bus, the bus traces the line; MODCP_SIM_MEMBER_RX=1 adds what each member
     * heard (a debugging aid: "@b heard ...") */
    bool line_trace = s->bus == NULL || getenv("MODCP_SIM_MEMBER_RX") != NULL;
    if (s->bus != NULL) {
        char l[32];
        snprintf(l, sizeof l, "@%s heard", m->name);
        sim_trace_labels(&m->tr, l, NULL, NULL);
    }
    while (!atomic_load(&s->stop)) {
        bool idle = modcp_cp_ready(&m->cp) && !modcp_job_busy(&m->cp.job) && !m->cp.request_pending;
        bool tx_done = false, timer = false;
        uint32_t now = 0;
        /* a job on the backplane: its reply comes at the CPU side's next FB call,
         * watched for (the backplane interrupt is immediate on a real CP) */
        m->port.expect_armed = m->cp.request_pending && !ring_pending(&m->bp.to_cp) &&
                               atomic_load_explicit(&m->cpu_calls, memory_order_relaxed) &&
                               !same_core(atomic_load_explicit(&m->cpu_core, memory_order_relaxed));
        m->port.expect_us = atomic_load_explicit(&m->cpu_due, memory_order_relaxed);
        sim_latlog_before_wait(&m->lat, &m->port);
        int n = modcp_posix_wait(&m->port, idle ? IDLE_TICK_US : BUSY_TICK_US, rx, RX_CHUNK,
                                 &tx_done, &timer, &now);
        sim_latlog_after_wait(&m->lat, &m->port, n, timer, now);
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
            /* on a bus: the characters heard, each at its time on the line, and the
             * timer between them when it fell due first */
            if (timer) {
                m->port.timer_armed = true; /* ordered with the characters below */
                timer = false;
            }
            if (tx_done) {
                /* our reply ended before anything heard after it (we were deaf while
                 * sending): its end first, at its time on the line */
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
                tx_done = false;
            }
            uint8_t bb[RX_CHUNK];
            uint32_t bt[RX_CHUNK];
            bool more = false;
            size_t k = sim_bus_take(s->bus, m->index, bb, bt, RX_CHUNK, now, &more);
            if (more) {
                /* characters that arrived after `now` was read: the next turn takes
                 * them (pulled back to `now` they could precede the end of our own
                 * reply: (08)37H, the request lost) */
                modcp_posix_wake(&m->port);
            }
            for (size_t i = 0; i < k; i++) {
                uint32_t ti = bt[i];
                if ((int32_t)(ti - m->core_t) < 0) {
                    ti = m->core_t; /* never back in time for the core */
                }
                if ((int32_t)(now - ti) < 0) {
                    ti = now;
                }
                while (m->port.timer_armed && (int32_t)(ti - m->port.timer_deadline_us) >= 0) {
                    uint32_t d = m->port.timer_deadline_us;
                    if ((int32_t)(d - m->core_t) < 0) {
                        d = m->core_t;
                    }
                    m->port.timer_armed = false;
                    m->port.now_us = d;
                    modcp_cp_on_timer(&m->cp, d);
                    m->core_t = d;
                }
                m->port.now_us = ti;
                if (tr) {
                    uint64_t tb = n64 - (uint32_t)((uint32_t)n64 - ti) - s->t0_us64;
                    sim_trace_rx(&m->tr, bb[i], 0, tb);
                }
                modcp_cp_on_rx(&m->cp, bb[i], ti);
                m->core_t = ti;
            }
            if (m->port.timer_armed && (int32_t)(now - m->port.timer_deadline_us) >= 0) {
                m->port.timer_armed = false;
                timer = true;
            }
            m->core_t = now;
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
        for (int i = 0; i < n; i++) {
            if (tr) {
                sim_trace_rx(&m->tr, rx[i].byte, rx[i].errors, t);
            }
            if (rx[i].errors != 0u) {
                modcp_cp_on_line_error(&m->cp, rx[i].errors, now);
            } else {
                modcp_cp_on_rx(&m->cp, rx[i].byte, now);
            }
        }
        modcp_cp_poll(&m->cp, now);
        sim_latlog_after_core(&m->lat, &m->cp, &m->port, now);
        uint32_t put = atomic_load_explicit(&m->bp.to_cpu.head, memory_order_relaxed);
        if (put != m->cp_put_seen) {
            m->cp_put_seen = put;
            modcp_posix_event_signal(&m->cpu_irq); /* the backplane interrupt */
        }
        if (tr) {
            sim_trace_poll(&m->tr, t);
        }
        trace_events(m);
        cp_snapshot(m);
    }
    return NULL;
}
