/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the scheduler: one thread runs every member's CPU side (the FB call once
 * per cycle of that member, console commands between two calls) and visits the CPs
 * that have nothing to do on one shared supervision tick.
 *
 * A member's CP thread sleeps while its CP is quiet (no job, no request, no timer, no
 * reply on the line) and wakes only for work: characters, its timer, its reply's bytes,
 * blocks from the FB. The supervision a quiet CP still needs (comm-loss time, LEDs,
 * modcp_cp_poll) is done here, every QUIET_TICK_US for all quiet members in one pass,
 * under the member's cp_mu (cp_visit). So an idle line of 247 members wakes one thread
 * per cycle and per tick, not two threads per member. */
#define _GNU_SOURCE
#include "sim.h"

/* Console commands queued for any member. */
static void run_commands(sim_t *s)
{
    if (atomic_exchange(&s->cmds, false)) {
        for (size_t i = 0; i < s->n; i++) {
            cpu_command(&s->m[i]);
        }
    }
}

/* Every FB call due by now; the quiet CPs' tick when it is due. */
static void run_due(sim_t *s, uint64_t *tick)
{
    for (size_t i = 0; i < s->n && !atomic_load(&s->stop); i++) {
        if (s->m[i].cpu_next <= modcp_posix_now_us64()) {
            cpu_cycle(&s->m[i]);
        }
    }
    uint64_t now = modcp_posix_now_us64();
    if (now >= *tick) {
        uint32_t now32 = (uint32_t)now; /* modcp_posix_now_us's clock */
        for (size_t i = 0; i < s->n; i++) {
            cp_visit(&s->m[i], now32);
        }
        *tick += QUIET_TICK_US;
        if (*tick <= now) {
            *tick = now + QUIET_TICK_US; /* late: no burst of ticks */
        }
    }
}

/* When to wake next: the earliest FB call (CPU_SPIN_US ahead of a call that blocks from
 * the CP wait for) or the tick. *spin_to: a call with blocks waiting is due within
 * CPU_SPIN_US: watch the clock up to it (0: none). */
static uint64_t next_wake(sim_t *s, uint64_t tick, uint64_t now, uint64_t *spin_to)
{
    uint64_t at = tick;
    *spin_to = 0;
    for (size_t i = 0; i < s->n; i++) {
        const member_t *m = &s->m[i];
        bool waits = cpu_blocks_wait(m);
        uint64_t wake = waits && m->cpu_next > CPU_SPIN_US ? m->cpu_next - CPU_SPIN_US : m->cpu_next;
        if (waits && wake <= now && (*spin_to == 0u || m->cpu_next < *spin_to)) {
            *spin_to = m->cpu_next; /* blocks wait: it starts on time, not a wake-up late */
        }
        if (wake < at) {
            at = wake;
        }
    }
    return at;
}

void *sched_thread(void *arg)
{
    sim_t *s = arg;
    for (size_t i = 0; i < s->n; i++) {
        cpu_start(&s->m[i], s->cpu_t0_us64);
    }
    uint64_t tick = s->cpu_t0_us64 + QUIET_TICK_US;
    while (!atomic_load(&s->stop)) {
        run_commands(s);
        run_due(s, &tick);
        uint64_t now = modcp_posix_now_us64();
        uint64_t spin_to = 0;
        uint64_t at = next_wake(s, tick, now, &spin_to);
        if (spin_to != 0u) {
            modcp_posix_spin_until_us64(spin_to);
        } else if (at > now) {
            (void)modcp_posix_event_wait_until(&s->sched_irq, at);
        }
    }
    return NULL;
}
