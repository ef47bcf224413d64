/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — one member's CPU side, run by the scheduler (sim_sched.c): the cyclic user
 * program that calls the FB, and console commands between two calls. */
#define _GNU_SOURCE
#include "sim.h"

/* ---- CPU side ---------------------------------------------------------------------- */

static void exec_console(member_t *m)
{
    modcp_console_env_t env;
    modcp_diag_t diag;
    memset(&env, 0, sizeof env);
    pthread_mutex_lock(&m->snap_mu);
    diag = m->snap_diag;
    env.cp_configured = m->snap_configured;
    env.cp_ready = m->snap_ready;
    env.cp_param_event = m->snap_param_event;
    pthread_mutex_unlock(&m->snap_mu);
    env.mem = &m->memory.mem;
    env.diag = &diag;
    env.fb = &m->fb;
    env.paused = &m->paused;
    env.cp_start = &m->fb_in.cp_start;
    env.bp = &m->bp;
    env.cycles = m->cycles;
    /* the CP's status area, read from the backplane like any user program would */
    modcp_cp_status_t cst;
    for (int k = 0; k < 100; k++) {
        if (modcp_bp_read_status(&m->bp, &cst)) {
            env.cp_status = &cst;
            break;
        }
    }
    (void)modcp_console_exec(&env, m->cmd_line, m->cmd_out, sizeof m->cmd_out);
}

/* Blocks the CPU side has put (to the CP) plus blocks it has taken (from the CP): it
 * changes whenever an FB call gives the CP something to do. Read on the CPU thread,
 * which is the only writer of both counters. */
static uint32_t bp_moves(const modcp_backplane_t *bp)
{
    return atomic_load_explicit(&bp->to_cp.head, memory_order_relaxed) +
           atomic_load_explicit(&bp->to_cpu.tail, memory_order_relaxed);
}

void timespec_of(uint64_t us, struct timespec *ts)
{
    ts->tv_sec = (time_t)(us / 1000000u);
    ts->tv_nsec = (long)((us % 1000000u) * 1000u);
}

/* "modcp-sim: " or "modcp-sim: @b " */
static const char *who(const member_t *m, char *buf, size_t cap)
{
    if (!m->sim->solo) {
        snprintf(buf, cap, "@%s ", m->name);
    } else {
        buf[0] = '\0';
    }
    return buf;
}

/* A console command queued for this member: executed between two FB calls. */
void cpu_command(member_t *m)
{
    pthread_mutex_lock(&m->cmd_mu);
    if (m->cmd_pending) {
        exec_console(m);
        m->cmd_pending = false;
        m->cmd_done = true;
        pthread_cond_broadcast(&m->cmd_cv);
    }
    pthread_mutex_unlock(&m->cmd_mu);
}

/* Blocks from the CP wait for this member's next FB call. */
bool cpu_blocks_wait(const member_t *m)
{
    return !m->paused && ring_pending(&m->bp.to_cpu);
}


/* "ready" (on a bus: each member's, then the line's) or CP_START_ERROR when the FB's
 * state changed. */
static void cpu_report(member_t *m, const modcp_fb_out_t *out, cpu_report_t *r)
{
    sim_t *s = m->sim;
    if (m->fb.state == r->last_state) {
        return;
    }
    r->last_state = m->fb.state;
    atomic_store(&m->fb_state, r->last_state);
    if (r->last_state == MODCP_FBST_RUN && out->cp_start_ok && !r->ready_printed) {
        r->ready_printed = true;
        if (s->solo) {
            printf_line(s, "modcp-sim: ready");
            return;
        }
        printf_line(s, "modcp-sim: @%s ready", m->name);
        if (!r->counted) {
            r->counted = true;
            if (atomic_fetch_add(&s->ready_count, 1) + 1 == (int)s->n) {
                printf_line(s, "modcp-sim: ready");
            }
        }
    } else if (r->last_state == MODCP_FBST_FAILED) {
        char en[16], wb[32];
        modcp_console_event_name((modcp_event_t)out->error_info, en, sizeof en);
        printf_line(s, "modcp-sim: %sCP_START_ERROR, ERROR_NR %u ERROR_INFO 0x%04X %s (%s)",
                    who(m, wb, sizeof wb), (unsigned)out->error_nr, (unsigned)out->error_info, en,
                    modcp_event_text((modcp_event_t)out->error_info));
        r->ready_printed = false;
    } else if (r->last_state != MODCP_FBST_RUN) {
        r->ready_printed = false;
    }
}

void cpu_start(member_t *m, uint64_t t0)
{
    m->cpu_next = t0; /* every member's cycle in phase (two at one address answer at
                         once, as two PLCs polled alike would) */
    m->rep = (cpu_report_t){0xFF, false, false};
    m->fb_in.cp_start = true; /* OB100: CP_START set at start-up */
    atomic_store(&m->cpu_due, (unsigned)(t0 & 0xFFFFFFFFu));
    atomic_store(&m->cpu_core, -1);
    atomic_store(&m->cpu_calls, true);
}

void cpu_cycle(member_t *m)
{
    uint64_t next = m->cpu_next;
    if (!m->paused) {
        modcp_fb_out_t out = {0}; /* ERROR_NR / INFO read only when the FB wrote them */
        uint32_t moved0 = bp_moves(&m->bp);
        uint32_t fb_t0 = modcp_posix_now_us();
        atomic_store_explicit(&m->cpu_core, this_core(), memory_order_relaxed);
        modcp_fb_call(&m->fb, &m->fb_in, &out, modcp_posix_now_ms());
        if (bp_moves(&m->bp) != moved0) {
            sim_latlog_fb(&m->lat, next, fb_t0, modcp_posix_now_us());
            modcp_posix_wake(&m->port); /* the CP has blocks to take or room to put */
        }
        m->cycles++;
        cpu_report(m, &out, &m->rep);
    }
    uint64_t period = (uint64_t)m->cycle_ms * 1000u;
    next += period;
    uint64_t now = modcp_posix_now_us64();
    if (next + period < now) {
        /* overrun: do not catch up with a burst of cycles; stay in phase */
        next += ((now - next) / period + 1u) * period;
    }
    m->cpu_next = next;
    atomic_store_explicit(&m->cpu_due, (unsigned)(next & 0xFFFFFFFFu), memory_order_relaxed);
    atomic_store_explicit(&m->cpu_calls, !m->paused, memory_order_relaxed);
}
