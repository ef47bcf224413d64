/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — rules in words: the message for each problem that validation
 * (modcp_params_validate) reports, at the key and value it came from. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>

#include "conf_internal.h"
#include "params_internal.h"

static const conf_key_t *key_of_field(uint8_t field)
{
    for (size_t i = 0; i < conf_key_count; i++) {
        if (conf_keys[i].field == field && conf_keys[i].rule[0] != '\0') {
            return &conf_keys[i];
        }
    }
    return NULL;
}

const char *conf_field_rule(uint8_t field)
{
    const conf_key_t *k = key_of_field(field);
    if (k != NULL) {
        return k->rule;
    }
    switch (field) {
    case MODCP_PF_LIM_DB:
    case MODCP_PF_LIM_M:
    case MODCP_PF_LIM_Q:
        return "must be MIN-MAX with MIN <= MAX (DB MIN >= 1), or off to disable writes";
    default: return "invalid value";
    }
}

static const char *default_key(uint8_t field, unsigned index, const char **section)
{
    for (size_t i = 0; i < conf_key_count; i++) {
        if (conf_keys[i].field == field && conf_keys[i].key[0] != '\0' &&
            (conf_keys[i].index == index || conf_keys[i].index == 0xFFu)) {
            *section = conf_keys[i].section;
            return conf_keys[i].key;
        }
    }
    switch (field) {
    case MODCP_PF_LIM_DB: *section = "limits"; return "db";
    case MODCP_PF_LIM_M: *section = "limits"; return "m";
    case MODCP_PF_LIM_Q: *section = "limits"; return "q";
    case MODCP_PF_SCANNER: *section = "scanner"; return "entries";
    default: *section = "?"; return "?";
    }
}

static void window_rule(const modcp_conf_t *c, const modcp_param_issue_t *is, char *rule, size_t cap)
{
    bool coils = is->field == MODCP_PF_COILS;
    const modcp_bitwin_t *w = coils ? &c->params.coils[is->index] : &c->params.inputs[is->index];
    if (is->event == MODCP_EV_COIL_OVERLAP || is->event == MODCP_EV_INPUT_OVERLAP) {
        const char *other = "?";
        if (is->value < (coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS)) {
            other = coils ? c->coil_keys[is->value] : c->input_keys[is->value];
        }
        (void)snprintf(rule, cap, "overlaps the window %s.%s", coils ? "coils" : "inputs", other);
        return;
    }
    if (w->from > w->to) {
        (void)snprintf(rule, cap, "illegal from/to: from must not be greater than to");
    } else if (w->area == MODCP_AREA_DB && w->db == 0u) {
        (void)snprintf(rule, cap, "illegal from/to: the DB number must be 1..65535");
    } else if (conf_is_tc(w->area) && ((uint32_t)w->to - w->from + 1u) % 16u != 0u) {
        (void)snprintf(rule, cap,
                       "illegal from/to: a T/C window must span a multiple of 16 bits (it spans %u)",
                       (unsigned)((uint32_t)w->to - w->from + 1u));
    } else if (conf_is_tc(w->area)) {
        (void)snprintf(rule, cap, "illegal from/to: the window ends beyond element 65535");
    } else {
        (void)snprintf(rule, cap, "illegal from/to: the window ends beyond byte 65535");
    }
}

static const char *const r32_keys[3] = {"int16", "int32", "float"};

static void r32_rule(const modcp_conf_t *c, const modcp_param_issue_t *is, char *rule, size_t cap)
{
    const modcp_r32range_t *r = &c->params.r32[is->index % 3u];
    uint32_t per = is->index == MODCP_R32_INT16 ? 2u : 4u;
    if (r->from > r->to) {
        (void)snprintf(rule, cap, "from must not be greater than to");
    } else if (r->db == 0u) {
        (void)snprintf(rule, cap, "the DB number must be 1..65535");
    } else if (((uint32_t)r->to - r->from + 1u) * per > 65536u) {
        (void)snprintf(rule, cap, "the range needs more than one DB (%u bytes > 65536)",
                       (unsigned)(((uint32_t)r->to - r->from + 1u) * per));
    } else {
        for (unsigned i = 0; i < is->index && i < 3u; i++) {
            const modcp_r32range_t *a = &c->params.r32[i];
            if (a->from <= r->to && r->from <= a->to) {
                (void)snprintf(rule, cap, "overlaps the range registers.%s", r32_keys[i]);
                return;
            }
            if (a->db == r->db) {
                (void)snprintf(rule, cap, "uses the same DB as registers.%s", r32_keys[i]);
                return;
            }
        }
        (void)snprintf(rule, cap, "illegal 32-bit register range");
    }
}

void conf_report_issue(modcp_conf_t *c, const modcp_param_issue_t *is)
{
    char rule[256];
    unsigned idx = is->index == 0xFFu ? IDX_GLOBAL : is->index;
    const char *section = "?";
    const char *key = "?";
    const char *value = "(default)";
    char valbuf[64];
    modcp_conf_loc_t loc = {0u, 0u};
    if (is->field < MODCP_PF_COUNT && idx < MODCP_CONF_SRC_INDEX && c->src[is->field][idx].set) {
        const modcp_conf_src_t *s = &c->src[is->field][idx];
        loc = s->loc;
        section = s->section;
        key = s->key;
        value = s->value;
    } else {
        key = default_key(is->field, idx, &section);
        (void)snprintf(valbuf, sizeof valbuf, "%lu (default)", (unsigned long)is->value);
        value = valbuf;
    }
    switch (is->field) {
    case MODCP_PF_COILS:
    case MODCP_PF_INPUTS: window_rule(c, is, rule, sizeof rule); break;
    case MODCP_PF_R32: r32_rule(c, is, rule, sizeof rule); break;
    case MODCP_PF_SCANNER:
        if (is->index == 0xFFu) {
            (void)snprintf(rule, sizeof rule,
                           "at most 16 entries, and start + entries must not exceed 65536");
        } else {
            (void)snprintf(rule, sizeof rule,
                           "entry %u must be a word operand (MWn, IWn, QWn, DBn.DBWm with DB "
                           "1..65535, Tn, Cn)",
                           (unsigned)is->index + 1u);
        }
        break;
    case MODCP_PF_STOP_BITS:
        if (is->value == 1u || is->value == 2u) { /* legal value, not for this ASCII frame */
            const modcp_params_t *p = &c->params;
            bool none = p->parity == MODCP_PARITY_NONE;
            char par = none ? 'N' : (p->parity == MODCP_PARITY_ODD ? 'O' : 'E');
            (void)snprintf(rule, sizeof rule,
                           "the ASCII character frame %u%c%lu is not allowed: with parity even or "
                           "odd 1 stop bit, with parity none 2 ([ASCII-32] §3.1: 7E1, 7O1 or 7N2); "
                           "stop_bits = %u",
                           (unsigned)p->data_bits, par, (unsigned long)is->value, none ? 2u : 1u);
        } else {
            conf_copy_str(rule, sizeof rule, conf_field_rule(is->field));
        }
        break;
    case MODCP_PF_OPMODE:
        if (is->value == MODCP_OPMODE_NORMAL) { /* legal value, not on two-wire RS485 */
            (void)snprintf(rule, sizeof rule,
                           "normal is not allowed with interface.type = rs485 (two-wire runs in "
                           "interference suppression = modem mode) unless "
                           "protocol.rs485_mode_select = on ([RTU-2009] Table 5-2)");
        } else {
            conf_copy_str(rule, sizeof rule, conf_field_rule(is->field));
        }
        break;
    default: conf_copy_str(rule, sizeof rule, conf_field_rule(is->field)); break;
    }
    conf_key_problem_at(c, is->fatal, loc, section, key, value, rule, is->event);
}
