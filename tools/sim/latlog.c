/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — stage time stamps of every reply (see latlog.h). */
#include "latlog.h"

#include <stdlib.h>

void sim_latlog_open(sim_latlog_t *l)
{
    const char *path = getenv("MODCP_SIM_LATLOG");
    l->f = NULL;
    if (path != NULL && path[0] != '\0') {
        l->f = fopen(path, "w");
    }
}

void sim_latlog_close(sim_latlog_t *l)
{
    if (l->f != NULL) {
        fclose(l->f);
        l->f = NULL;
    }
}

void sim_latlog_before_wait(sim_latlog_t *l, const modcp_posix_port_t *p)
{
    if (l->f == NULL) {
        return;
    }
    l->timer_armed = p->timer_armed;
    l->timer_deadline = p->timer_deadline_us;
    l->first_pending = p->tx_active && p->tx_pos == 0u;
}

void sim_latlog_after_wait(sim_latlog_t *l, const modcp_posix_port_t *p, int n, bool timer_fired,
                           uint32_t now)
{
    if (l->f == NULL) {
        return;
    }
    if (n > 0) {
        l->rx = now;
    }
    if (timer_fired && l->timer_armed) {
        l->timer_due = l->timer_deadline;
        l->timer_seen = now;
    }
    if (l->first_pending && (p->tx_pos > 0u || !p->tx_active) && p->tx_t0_us == l->tx_t0) {
        l->first_pending = false;
        fprintf(l->f, "%u %u %u %u %u %u %u %u %u %u %u %u\n", (unsigned)l->seq, (unsigned)l->rx,
                (unsigned)l->timer_due, (unsigned)l->timer_seen, (unsigned)l->job,
                atomic_load(&l->fb_due), atomic_load(&l->fb_start), atomic_load(&l->fb_end),
                (unsigned)l->take, (unsigned)l->tx_t0, (unsigned)(l->tx_t0 + p->char_us),
                (unsigned)now);
        fflush(l->f);
        l->seq++;
    }
}

void sim_latlog_rx(sim_latlog_t *l, size_t n, uint32_t now)
{
    if (l->f != NULL && n > 0u) {
        l->rx = now;
    }
}

void sim_latlog_after_core(sim_latlog_t *l, const modcp_cp_t *cp, const modcp_posix_port_t *p,
                           uint32_t now)
{
    if (l->f == NULL) {
        return;
    }
    if (cp->request_pending && !l->pending) {
        l->job = modcp_posix_now_us();
    }
    l->pending = cp->request_pending;
    if (p->tx_active && p->tx_pos == 0u && p->tx_t0_us != l->tx_t0) {
        l->tx_t0 = p->tx_t0_us;
        l->take = now;
    }
}

void sim_latlog_fb(sim_latlog_t *l, uint64_t due, uint32_t start, uint32_t end)
{
    if (l->f == NULL) {
        return;
    }
    atomic_store(&l->fb_due, (unsigned)(due & 0xFFFFFFFFu));
    atomic_store(&l->fb_start, start);
    atomic_store(&l->fb_end, end);
}
