/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the line model (see line.h). */
#define _GNU_SOURCE
#include "line.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "modcp/hal_posix.h"

void sim_line_init(sim_line_t *l, const sim_line_cfg_t *cfg, uint64_t t0_us64)
{
    memset(l, 0, sizeof *l);
    l->cfg = *cfg;
    if (l->cfg.char_us == 0u) {
        l->cfg.char_us = 1u;
    }
    /* what comes late: a reply or an event stamped by a thread that ran late, a
     * collision's note (at the end of the frame, known t3.5 after it). A pty chunk,
     * back-dated, never goes before what is on the line already (put_arrived). */
    uint64_t t35 = l->cfg.ascii ? 4u * (uint64_t)l->cfg.char_us : l->cfg.t35_us;
    l->hold_us = 50000u + 2u * t35;
    struct timespec rt;
    clock_gettime(CLOCK_REALTIME, &rt);
    uint64_t real = (uint64_t)rt.tv_sec * 1000000u + (uint64_t)rt.tv_nsec / 1000u;
    l->t0_real_us = real - (modcp_posix_now_us64() - t0_us64);
    l->last_src = SIM_SRC_NOISE;
    pthread_mutex_init(&l->mu, NULL);
}

void sim_line_member(sim_line_t *l, size_t i, const char *name, uint8_t addr)
{
    if (i < SIM_LINE_MAX_MEMBERS) {
        snprintf(l->names[i], sizeof l->names[i], "%s", name);
        l->addr[i] = addr;
        if (i + 1u > l->n_members) {
            l->n_members = i + 1u;
        }
    }
}

bool sim_line_observe(sim_line_t *l, sim_observer_t *o)
{
    pthread_mutex_lock(&l->mu);
    bool ok = l->nobs < SIM_LINE_MAX_OBSERVERS;
    if (ok) {
        l->obs[l->nobs] = o;
        atomic_store(&l->nobs, l->nobs + 1u);
    }
    pthread_mutex_unlock(&l->mu);
    return ok;
}

bool sim_line_watched(const sim_line_t *l)
{
    return l != NULL && atomic_load(&l->nobs) > 0u;
}

static size_t src_slot(int src)
{
    return (size_t)(src + 2);
}

/* The i-th held character (0: the oldest). */
static sim_char_t *held(sim_line_t *l, size_t i)
{
    return &l->q[(l->qh + i) % SIM_LINE_QUEUE];
}

/* The i-th held note (0: the oldest). */
static sim_note_t *note_at(sim_line_t *l, size_t i)
{
    return &l->notes[(l->nh + i) % SIM_LINE_NOTES];
}

/* The oldest held note to the observers (l->mu held). */
static void release_note(sim_line_t *l)
{
    sim_note_t *n = note_at(l, 0);
    if (n->t_us < l->released) {
        n->t_us = l->released;
    }
    l->released = n->t_us;
    for (size_t k = 0; k < l->nobs; k++) {
        if (l->obs[k]->on_note != NULL) {
            l->obs[k]->on_note(l->obs[k], n);
        }
    }
    l->nh = (l->nh + 1u) % SIM_LINE_NOTES;
    l->nn--;
}

/* The oldest held character to the observers (l->mu held). */
static void release_char(sim_line_t *l)
{
    sim_char_t c = *held(l, 0);
    l->qh = (l->qh + 1u) % SIM_LINE_QUEUE;
    l->qn--;
    if (c.t_us < l->released) {
        c.t_us = l->released; /* held too short: never back in time for an observer */
    }
    uint64_t end = c.t_us + c.len_us;
    /* the members and the noise share the wire: overlapping characters of two of them
     * collide (the master's pty is a line of its own) */
    if (c.src != SIM_SRC_MASTER) {
        if (l->last_src != c.src && l->last_rel_end > c.t_us) {
            c.flags |= SIM_CH_COLLIDED;
        }
        for (size_t i = 0; i < l->qn && held(l, i)->t_us < end; i++) {
            if (held(l, i)->src != c.src && held(l, i)->src != SIM_SRC_MASTER) {
                c.flags |= SIM_CH_COLLIDED;
            }
        }
        if (l->last_src != c.src || end > l->last_rel_end) {
            l->last_rel_end = end > l->last_rel_end ? end : l->last_rel_end;
        }
        l->last_src = c.src;
    }
    l->released = c.t_us;
    for (size_t k = 0; k < l->nobs; k++) {
        l->obs[k]->on_char(l->obs[k], &c);
    }
}

/* The oldest held character or note (a note first at the same time); false: none. */
static bool release_first(sim_line_t *l)
{
    if (l->nn > 0u && (l->qn == 0u || note_at(l, 0)->t_us <= held(l, 0)->t_us)) {
        release_note(l);
        return true;
    }
    if (l->qn > 0u) {
        release_char(l);
        return true;
    }
    return false;
}

/* The time from which the oldest held item may go (its end: a character is complete). */
static bool oldest_end(sim_line_t *l, uint64_t *end)
{
    if (l->nn > 0u && (l->qn == 0u || note_at(l, 0)->t_us <= held(l, 0)->t_us)) {
        *end = note_at(l, 0)->t_us;
        return true;
    }
    if (l->qn > 0u) {
        *end = held(l, 0)->t_us + held(l, 0)->len_us;
        return true;
    }
    return false;
}

static void put_locked(sim_line_t *l, const sim_char_t *c)
{
    while (l->qn == SIM_LINE_QUEUE) { /* full: what is oldest goes first, note or character */
        (void)release_first(l);
    }
    /* from the newest back: most characters come in time order */
    size_t i = l->qn;
    while (i > 0u && held(l, i - 1u)->t_us > c->t_us) {
        *held(l, i) = *held(l, i - 1u);
        i--;
    }
    *held(l, i) = *c;
    l->qn++;
    size_t slot = src_slot(c->src);
    if (slot < sizeof l->last_end / sizeof l->last_end[0] && c->t_us + c->len_us > l->last_end[slot]) {
        l->last_end[slot] = c->t_us + c->len_us;
    }
}

void sim_line_put(sim_line_t *l, const sim_char_t *c)
{
    if (!sim_line_watched(l)) {
        return;
    }
    pthread_mutex_lock(&l->mu);
    put_locked(l, c);
    pthread_mutex_unlock(&l->mu);
}

void sim_line_put_frame(sim_line_t *l, int src, const uint8_t *b, const uint8_t *flags, size_t n,
                        uint64_t t0)
{
    if (!sim_line_watched(l)) {
        return;
    }
    pthread_mutex_lock(&l->mu);
    for (size_t i = 0; i < n; i++) {
        sim_char_t c = {t0 + (uint64_t)i * l->cfg.char_us, l->cfg.char_us, 0, (int16_t)src, b[i],
                        flags != NULL ? flags[i] : 0u};
        put_locked(l, &c);
    }
    pthread_mutex_unlock(&l->mu);
}

void sim_line_put_arrived(sim_line_t *l, int src, const uint8_t *b, const uint8_t *flags, size_t n,
                          uint64_t t_end)
{
    if (!sim_line_watched(l) || n == 0u) {
        return;
    }
    pthread_mutex_lock(&l->mu);
    uint64_t span = (uint64_t)n * l->cfg.char_us;
    uint64_t t0 = t_end > span ? t_end - span : 0u;
    /* never before the end of a character already on the line (a pty is faster than
     * a line: a master that writes right after a reply gets its request after it) */
    for (size_t i = 0; i < sizeof l->last_end / sizeof l->last_end[0]; i++) {
        if (t0 < l->last_end[i]) {
            t0 = l->last_end[i];
        }
    }
    pthread_mutex_unlock(&l->mu);
    sim_line_put_frame(l, src, b, flags, n, t0);
}

void sim_line_note(sim_line_t *l, uint64_t t_us, int src, unsigned kind, const char *fmt, ...)
{
    if (!sim_line_watched(l)) {
        return;
    }
    sim_note_t n;
    n.t_us = t_us;
    n.src = (int16_t)src;
    n.kind = (uint8_t)kind;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(n.text, sizeof n.text, fmt, ap);
    va_end(ap);
    pthread_mutex_lock(&l->mu);
    while (l->nn == SIM_LINE_NOTES) { /* full: what is oldest goes first, note or character */
        (void)release_first(l);
    }
    size_t i = l->nn; /* from the newest back; the same time: after those before */
    while (i > 0u && note_at(l, i - 1u)->t_us > n.t_us) {
        *note_at(l, i) = *note_at(l, i - 1u);
        i--;
    }
    *note_at(l, i) = n;
    l->nn++;
    pthread_mutex_unlock(&l->mu);
}

void sim_line_tick(sim_line_t *l, uint64_t now)
{
    if (!sim_line_watched(l)) {
        return;
    }
    pthread_mutex_lock(&l->mu);
    uint64_t end = 0;
    while (oldest_end(l, &end) && end + l->hold_us <= now) {
        (void)release_first(l);
    }
    uint64_t upto = now > l->hold_us ? now - l->hold_us : 0u;
    for (size_t k = 0; k < l->nobs; k++) {
        if (l->obs[k]->on_time != NULL) {
            l->obs[k]->on_time(l->obs[k], upto);
        }
    }
    pthread_mutex_unlock(&l->mu);
}

void sim_line_close(sim_line_t *l)
{
    if (!sim_line_watched(l)) {
        return;
    }
    pthread_mutex_lock(&l->mu);
    while (release_first(l)) {
    }
    for (size_t k = 0; k < l->nobs; k++) {
        l->obs[k]->on_close(l->obs[k]);
    }
    atomic_store(&l->nobs, 0u);
    pthread_mutex_unlock(&l->mu);
}

unsigned sim_line_nbits(const sim_line_cfg_t *cfg)
{
    return 1u + cfg->data_bits + (cfg->parity != 0u ? 1u : 0u) + cfg->stop_bits;
}

int sim_line_bit(const sim_line_cfg_t *cfg, uint8_t v, unsigned i)
{
    unsigned db = cfg->data_bits;
    if (i == 0u) {
        return 0;
    }
    if (i <= db) {
        return (v >> (i - 1u)) & 1;
    }
    if (cfg->parity != 0u && i == db + 1u) {
        unsigned ones = 0;
        for (unsigned k = 0; k < db; k++) {
            ones += ((unsigned)v >> k) & 1u;
        }
        return cfg->parity == 2u ? (int)(ones & 1u) : (int)((ones & 1u) ^ 1u);
    }
    return 1; /* stop bits, idle */
}

const char *sim_line_src_name(const sim_line_t *l, int src)
{
    if (src == SIM_SRC_MASTER) {
        return "master";
    }
    if (src >= 0 && (size_t)src < l->n_members) {
        return l->names[src];
    }
    return "noise";
}
