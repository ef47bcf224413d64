/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — tool-level checks: [cpu] and [memory] against the controller, and
 * START_TIME against the FB's initialisation. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>

#include "conf_internal.h"
#include "modcp/backplane.h"

static const modcp_conf_db_t *conf_db(const modcp_conf_t *c, uint16_t number)
{
    for (uint16_t i = 0; i < c->db_count; i++) {
        if (c->dbs[i].number == number) {
            return &c->dbs[i];
        }
    }
    return NULL;
}

void conf_check_memory(modcp_conf_t *c)
{
    for (size_t i = 0; i < c->init_count; i++) {
        const modcp_conf_init_t *in = &c->inits[i];
        const modcp_s7op_t *op = &in->op;
        uint32_t end; /* one past the last byte / element */
        if (op->width == MODCP_S7_BIT) {
            end = op->offset + ((uint32_t)op->bit + in->count - 1u) / 8u + 1u;
        } else if (conf_is_tc(op->area)) {
            end = op->offset + (uint32_t)in->count;
        } else {
            end = op->offset + (uint32_t)op->width * in->count;
        }
        uint32_t size;
        const char *what;
        char dbwhat[48];
        modcp_event_t ev = MODCP_EV_AREA_ACCESS;
        switch (op->area) {
        case MODCP_AREA_I: size = c->i_bytes; what = "I (i_bytes)"; break;
        case MODCP_AREA_Q: size = c->q_bytes; what = "Q (q_bytes)"; break;
        case MODCP_AREA_M: size = c->m_bytes; what = "M (m_bytes)"; break;
        case MODCP_AREA_T: size = c->timers; what = "T (timers)"; break;
        case MODCP_AREA_C: size = c->counters; what = "C (counters)"; break;
        default: {
            const modcp_conf_db_t *db = conf_db(c, op->db);
            ev = MODCP_EV_DB_ACCESS;
            if (db == NULL) {
                char rule[96];
                (void)snprintf(rule, sizeof rule, "DB%u is not in cpu.dbs", (unsigned)op->db);
                conf_key_problem_at(c, true, in->loc, "memory", in->key, in->value, rule, ev);
                continue;
            }
            size = db->size;
            (void)snprintf(dbwhat, sizeof dbwhat, "DB%u", (unsigned)op->db);
            what = dbwhat;
            break;
        }
        }
        if (end > size) {
            char rule[128];
            (void)snprintf(rule, sizeof rule, "outside %s of %u %s", what, (unsigned)size,
                           conf_is_tc(op->area) ? "elements" : "bytes");
            conf_key_problem_at(c, true, in->loc, "memory", in->key, in->value, rule, ev);
        }
    }
}

static void window_warnings(modcp_conf_t *c, bool coils)
{
    size_t n = coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS;
    for (size_t i = 0; i < n; i++) {
        const modcp_bitwin_t *w = coils ? &c->params.coils[i] : &c->params.inputs[i];
        if (w->area == MODCP_AREA_NONE || w->from > w->to) {
            continue;
        }
        uint32_t bits = (uint32_t)w->to - w->from + 1u;
        uint32_t last = conf_is_tc(w->area) ? w->start + bits / 16u - 1u : w->start + (bits - 1u) / 8u;
        uint32_t size;
        char what[48];
        switch (w->area) {
        case MODCP_AREA_I: size = c->i_bytes; conf_copy_str(what, sizeof what, "cpu.i_bytes"); break;
        case MODCP_AREA_Q: size = c->q_bytes; conf_copy_str(what, sizeof what, "cpu.q_bytes"); break;
        case MODCP_AREA_M: size = c->m_bytes; conf_copy_str(what, sizeof what, "cpu.m_bytes"); break;
        case MODCP_AREA_T: size = c->timers; conf_copy_str(what, sizeof what, "cpu.timers"); break;
        case MODCP_AREA_C: size = c->counters; conf_copy_str(what, sizeof what, "cpu.counters"); break;
        default: {
            const modcp_conf_db_t *db = conf_db(c, w->db);
            size = db != NULL ? db->size : 0u;
            (void)snprintf(what, sizeof what, "the size of DB%u", (unsigned)w->db);
            break;
        }
        }
        if (last >= size) {
            const modcp_conf_src_t *s = &c->src[coils ? MODCP_PF_COILS : MODCP_PF_INPUTS][i];
            char rule[200];
            (void)snprintf(rule, sizeof rule,
                           "the window reaches %s %u but %s is %u: requests beyond get (0E)54H",
                           conf_is_tc(w->area) ? "element" : "byte", (unsigned)last, what,
                           (unsigned)size);
            conf_key_problem_at(c, false, s->loc, s->section, s->key, s->value, rule, MODCP_EV_NONE);
        }
    }
}

/* The FB hands the record over as PARAMS blocks followed by one INIT block, at most
 * MODCP_BP_DEPTH blocks per call (the ring is full until the CP drains it), and reads
 * INIT_ACK at the earliest in the call after its last block: in call P after the
 * CP_START edge, P = ceil(blocks / depth). It checks START_TIME in every call before
 * that, at 1 .. P-1 cycles: START_TIME <= (P-1) cycles always ends in CP_START_ERROR
 * with ERROR_INFO (00)00H (no answer yet). */
static uint32_t init_cycles(const modcp_conf_t *c, uint32_t *blocks)
{
    uint8_t rec[MODCP_PARAMS_RECORD_MAX];
    size_t len = modcp_params_encode(&c->params, rec, sizeof rec);
    *blocks = (uint32_t)((len + MODCP_BLOCK_SIZE - 1u) / MODCP_BLOCK_SIZE) + 1u;
    return (*blocks + MODCP_BP_DEPTH - 1u) / MODCP_BP_DEPTH;
}

static void check_start_time(modcp_conf_t *c)
{
    uint32_t blocks = 0;
    uint32_t calls = init_cycles(c, &blocks);
    uint32_t min = (calls - 1u) * c->cycle_ms; /* START_TIME must be above this */
    if (c->params.start_time_ms > min) {
        return;
    }
    char rule[320];
    (void)snprintf(rule, sizeof rule,
                   "must be more than %lu ms (%lu x cycle_ms %lu): the FB sends the record and "
                   "INIT as %lu blocks, %u per cycle, and sees the CP's answer at the earliest "
                   "%lu cycles after CP_START; a shorter START_TIME always ends in "
                   "CP_START_ERROR (ERROR_NR 2, ERROR_INFO (00)00H)",
                   (unsigned long)min, (unsigned long)(calls - 1u), (unsigned long)c->cycle_ms,
                   (unsigned long)blocks, (unsigned)MODCP_BP_DEPTH, (unsigned long)calls);
    const modcp_conf_src_t *s = &c->src[MODCP_PF_START_TIME][0];
    if (s->set || !c->cycle_src.set) {
        char value[32];
        (void)snprintf(value, sizeof value, "%u (default)", (unsigned)c->params.start_time_ms);
        conf_key_problem_at(c, true, s->loc, "cpu", "start_time_ms", s->set ? s->value : value,
                            rule, MODCP_EV_NONE);
    } else { /* the default START_TIME and a long cycle: the cycle is the key to fix */
        char crule[160];
        (void)snprintf(crule, sizeof crule,
                       "must be less than start_time_ms %u (default) / %lu: the FB's "
                       "initialisation takes %lu cycles",
                       (unsigned)c->params.start_time_ms, (unsigned long)(calls - 1u),
                       (unsigned long)calls);
        conf_key_problem_at(c, true, c->cycle_src.loc, c->cycle_src.section, c->cycle_src.key,
                            c->cycle_src.value, crule, MODCP_EV_NONE);
    }
}

void conf_check_cpu(modcp_conf_t *c)
{
    if (c->work_db != 0u && conf_db(c, c->work_db) == NULL) {
        const modcp_conf_src_t *s = &c->work_db_src;
        char rule[96];
        (void)snprintf(rule, sizeof rule, "DB%u is not in cpu.dbs", (unsigned)c->work_db);
        conf_key_problem_at(c, true, s->loc, s->section, s->key, s->value, rule, MODCP_EV_WORK_DB);
    }
    window_warnings(c, true);
    window_warnings(c, false);
    const uint16_t bases[2] = {c->params.hr_base_db, c->params.ir_base_db};
    const modcp_conf_src_t *srcs[2] = {&c->src[MODCP_PF_HR_BASE][0], &c->src[MODCP_PF_IR_BASE][0]};
    for (unsigned k = 0; k < 2u; k++) {
        if (bases[k] != 0u && conf_db(c, bases[k]) == NULL) {
            const modcp_conf_src_t *s = srcs[k];
            char rule[128];
            (void)snprintf(rule, sizeof rule,
                           "DB%u is not in cpu.dbs: its registers get exception 04 ((0E)39H)",
                           (unsigned)bases[k]);
            conf_key_problem_at(c, false, s->loc, s->section, s->key, s->value, rule,
                                MODCP_EV_NONE);
        }
    }
    check_start_time(c);
}
