/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — rules in words: the message for each problem that validation
 * (modcp_params_validate) reports, at the key and value it came from. The issue says which
 * rule the value breaks (modcp_param_issue_t.rule, .other); nothing here decides again. */
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

/* A window's or 32-bit range's rule (what check_ranges decided: is->rule) in words. */
static const char *const r32_keys[3] = {"int16", "int32", "float"};

static void range_rule(const modcp_conf_t *c, const modcp_param_issue_t *is, char *rule, size_t cap)
{
    const bool r32 = is->field == MODCP_PF_R32;
    const bool coils = is->field == MODCP_PF_COILS;
    const char *illegal = r32 ? "" : "illegal from/to: ";
    const char *other = "?";
    if (is->other < (r32 ? 3u : coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS)) {
        other = r32 ? r32_keys[is->other] : coils ? c->coil_keys[is->other] : c->input_keys[is->other];
    }
    switch (is->rule) {
    case MODCP_PR_AREA:
        (void)snprintf(rule, cap, "%sarea %lu cannot be mapped here", illegal, (unsigned long)is->value);
        break;
    case MODCP_PR_FROM_TO:
        (void)snprintf(rule, cap, "%sfrom must not be greater than to", illegal);
        break;
    case MODCP_PR_DB_ZERO:
        (void)snprintf(rule, cap, "%sthe DB number must be 1..65535", illegal);
        break;
    case MODCP_PR_TC_SIZE:
        (void)snprintf(rule, cap, "%sa T/C window must span a multiple of 16 bits (it spans %lu)",
                       illegal, (unsigned long)is->value);
        break;
    case MODCP_PR_EXTENT:
        if (r32) {
            (void)snprintf(rule, cap, "the range needs more than one DB (%lu bytes > 65536)",
                           (unsigned long)is->value);
        } else {
            const modcp_bitwin_t *w = coils ? &c->params.coils[is->index % MODCP_COIL_WINDOWS]
                                            : &c->params.inputs[is->index % MODCP_INPUT_WINDOWS];
            (void)snprintf(rule, cap, "%sthe window ends beyond %s 65535", illegal,
                           conf_is_tc(w->area) ? "element" : "byte");
        }
        break;
    case MODCP_PR_OVERLAP:
        (void)snprintf(rule, cap, "overlaps the %s %s.%s", r32 ? "range" : "window",
                       r32 ? "registers" : coils ? "coils" : "inputs", other);
        break;
    case MODCP_PR_SAME_DB:
        (void)snprintf(rule, cap, "uses the same DB as registers.%s", other);
        break;
    default: (void)snprintf(rule, cap, "%sinvalid", illegal); break;
    }
}

/* A scalar's rule in words: its row's text, or, for a legal value that the other fields
 * forbid (MODCP_PR_RULE), what forbids it. */
static void field_rule(const modcp_conf_t *c, const modcp_param_issue_t *is, char *rule, size_t cap)
{
    const modcp_params_t *p = &c->params;
    if (is->rule == MODCP_PR_RULE && is->field == MODCP_PF_STOP_BITS) {
        bool none = p->parity == MODCP_PARITY_NONE;
        char par = none ? 'N' : (p->parity == MODCP_PARITY_ODD ? 'O' : 'E');
        (void)snprintf(rule, cap,
                       "the ASCII character frame %u%c%lu is not allowed: with parity even or "
                       "odd 1 stop bit, with parity none 2 ([ASCII-32] §3.1: 7E1, 7O1 or 7N2); "
                       "stop_bits = %u",
                       (unsigned)p->data_bits, par, (unsigned long)is->value, none ? 2u : 1u);
    } else if (is->rule == MODCP_PR_RULE && is->field == MODCP_PF_OPMODE) {
        (void)snprintf(rule, cap,
                       "normal is not allowed with interface.type = rs485 (two-wire runs in "
                       "interference suppression = modem mode) unless "
                       "protocol.rs485_mode_select = on ([RTU-2009] Table 5-2)");
    } else if (is->field == MODCP_PF_SCANNER && is->index == 0xFFu) {
        (void)snprintf(rule, cap, "at most 16 entries, and start + entries must not exceed 65536");
    } else if (is->field == MODCP_PF_SCANNER) {
        (void)snprintf(rule, cap,
                       "entry %u must be a word operand (MWn, IWn, QWn, DBn.DBWm with DB "
                       "1..65535, Tn, Cn)",
                       (unsigned)is->index + 1u);
    } else {
        conf_copy_str(rule, cap, conf_field_rule(is->field));
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
    if (is->field == MODCP_PF_COILS || is->field == MODCP_PF_INPUTS || is->field == MODCP_PF_R32) {
        range_rule(c, is, rule, sizeof rule);
    } else {
        field_rule(c, is, rule, sizeof rule);
    }
    conf_key_problem_at(c, is->fatal, loc, section, key, value, rule, is->event);
}
