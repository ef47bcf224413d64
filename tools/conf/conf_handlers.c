/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — key handlers: a value given for a key of the parameter record
 * (table keys, bit windows, 32-bit ranges, write limits, scanner entries) into
 * modcp_params_t, or a problem naming the key, its value and the rule. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "conf_internal.h"

/* Unsigned number, decimal or 0x hex, the whole string. */
bool conf_parse_u32(const char *s, uint32_t *v)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    if (*s == '\0' || *s == '-' || *s == '+') {
        return false;
    }
    char *end = NULL;
    unsigned long long x = strtoull(s, &end, 0);
    if (end == s) {
        return false;
    }
    while (isspace((unsigned char)*end)) {
        end++;
    }
    if (*end != '\0' || x > 0xFFFFFFFFull) {
        return false;
    }
    *v = (uint32_t)x;
    return true;
}

static void handle_table_key(modcp_conf_t *c, const conf_key_t *k, const char *section,
                             const char *name, const char *value)
{
    uint8_t *base = (uint8_t *)&c->params;
    unsigned idx = k->index == 0xFFu ? IDX_GLOBAL : k->index;
    modcp_event_t ev = k->event;
    const char *rule = k->rule;
    uint32_t v = 0;
    conf_set_src(c, (modcp_param_field_t)k->field, idx, section, name, value);

    switch (k->syntax) {
    case ENUM:
        for (const enum_name_t *e = k->names; e->name != NULL; e++) {
            if (strcasecmp(e->name, value) == 0) {
                base[k->off] = e->value;
                return;
            }
        }
        conf_key_problem(c, true, section, name, value, rule, ev);
        return;
    case BOOL:
        if (strcasecmp(value, "on") == 0 || strcasecmp(value, "yes") == 0 ||
            strcasecmp(value, "true") == 0 || strcmp(value, "1") == 0) {
            base[k->off] = 1u;
        } else if (strcasecmp(value, "off") == 0 || strcasecmp(value, "no") == 0 ||
                   strcasecmp(value, "false") == 0 || strcmp(value, "0") == 0) {
            base[k->off] = 0u;
        } else {
            conf_key_problem(c, true, section, name, value, "must be on or off", ev);
        }
        return;
    case STR:
        if (strlen(value) > MODCP_ID_STRING_MAX) {
            conf_key_problem(c, true, section, name, value, rule, ev);
            return;
        }
        memset(base + k->off, 0, MODCP_ID_STRING_MAX + 1u);
        memcpy(base + k->off, value, strlen(value));
        return;
    default:
        break;
    }
    bool ok = conf_parse_u32(value, &v);
    bool soft = (k->flags & MODCP_PF_WARN) != 0u;
    uint32_t max = k->width == 1u ? 0xFFu : (k->width == 2u ? 0xFFFFu : 0xFFFFFFFFu);
    if (!ok) {
        conf_key_problem(c, true, section, name, value, "not a number", ev);
        return;
    }
    if (v > max) {
        if (soft) {
            v = 0; /* out of range: the CP's validation reports it and runs with the default */
        } else {
            conf_key_problem(c, true, section, name, value, rule, ev);
            return;
        }
    }
    switch (k->width) {
    case 1u: base[k->off] = (uint8_t)v; break;
    case 2u: {
        uint16_t x = (uint16_t)v;
        memcpy(base + k->off, &x, sizeof x);
        break;
    }
    default: memcpy(base + k->off, &v, sizeof v); break;
    }
}

/* "FROM-TO" (numbers decimal or 0x); returns false on a syntax error. */
static bool parse_range(const char *s, uint32_t *from, uint32_t *to)
{
    char *buf = strdup(s);
    char *dash = buf != NULL ? strchr(buf, '-') : NULL;
    bool ok = false;
    if (dash != NULL) {
        *dash = '\0';
        ok = conf_parse_u32(buf, from) && conf_parse_u32(dash + 1, to);
    }
    free(buf);
    return ok;
}

/* Number with an optional operand prefix: "1000", "MB1000", "M1000", "T100", "DB12". */
static bool parse_start(const char *s, const char *const *prefixes, uint32_t *v)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    if (prefixes != NULL) {
        for (size_t i = 0; prefixes[i] != NULL; i++) {
            size_t n = strlen(prefixes[i]);
            if (strncasecmp(s, prefixes[i], n) == 0 && isdigit((unsigned char)s[n])) {
                s += n;
                break;
            }
        }
    }
    return conf_parse_u32(s, v);
}

static const char *const pfx_m[] = {"MB", "M", NULL};
static const char *const pfx_q[] = {"QB", "Q", NULL};
static const char *const pfx_i[] = {"IB", "I", NULL};
static const char *const pfx_t[] = {"T", NULL};
static const char *const pfx_c[] = {"C", NULL};
static const char *const pfx_db[] = {"DBB", NULL};
static const char *const pfx_dbno[] = {"DB", NULL};

/* "FROM-TO @ START" */
static bool parse_window(const char *value, const char *const *pfx, uint32_t *from, uint32_t *to,
                         uint32_t *start)
{
    char *buf = strdup(value);
    char *at = buf != NULL ? strchr(buf, '@') : NULL;
    bool ok = false;
    if (at != NULL) {
        *at = '\0';
        ok = parse_range(buf, from, to) && parse_start(at + 1, pfx, start);
    }
    free(buf);
    return ok;
}

static void handle_window(modcp_conf_t *c, bool coils, const char *section, const char *name,
                          const char *value)
{
    modcp_bitwin_t w;
    memset(&w, 0, sizeof w);
    const char *const *pfx = NULL;
    modcp_event_t ev = coils ? MODCP_EV_COIL_FROMTO : MODCP_EV_INPUT_FROMTO;
    const char *usage = coils ? "unknown window (keys: m, q, t, c, dbN)"
                              : "unknown window (keys: m, i, dbN)";
    if (strcasecmp(name, "m") == 0) {
        w.area = MODCP_AREA_M;
        pfx = pfx_m;
    } else if (coils && strcasecmp(name, "q") == 0) {
        w.area = MODCP_AREA_Q;
        pfx = pfx_q;
    } else if (coils && strcasecmp(name, "t") == 0) {
        w.area = MODCP_AREA_T;
        pfx = pfx_t;
    } else if (coils && strcasecmp(name, "c") == 0) {
        w.area = MODCP_AREA_C;
        pfx = pfx_c;
    } else if (!coils && strcasecmp(name, "i") == 0) {
        w.area = MODCP_AREA_I;
        pfx = pfx_i;
    } else if (strncasecmp(name, "db", 2) == 0) {
        uint32_t db = 0;
        if (!conf_parse_u32(name + 2, &db) || db > 0xFFFFu || !isdigit((unsigned char)name[2])) {
            conf_key_problem(c, true, section, name, value, "bad DB number in the key (db1..db65535)",
                             ev);
            return;
        }
        w.area = MODCP_AREA_DB;
        w.db = (uint16_t)db;
        pfx = pfx_db;
    } else {
        conf_key_problem(c, true, section, name, value, usage, MODCP_EV_NONE);
        return;
    }
    uint8_t *count = coils ? &c->coil_count : &c->input_count;
    size_t cap = coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS;
    if (*count >= cap) {
        conf_key_problem(c, true, section, name, value,
                         coils ? "too many windows (at most 6)" : "too many windows (at most 4)", ev);
        return;
    }
    uint32_t from = 0, to = 0, start = 0;
    if (!parse_window(value, pfx, &from, &to, &start)) {
        conf_key_problem(c, true, section, name, value,
                         "syntax: FROM-TO @ START (e.g. 0-2047 @ 1000)", ev);
        return;
    }
    if (from > 0xFFFFu || to > 0xFFFFu || start > 0xFFFFu) {
        conf_key_problem(c, true, section, name, value,
                         "from, to and start must be 0..65535", ev);
        return;
    }
    w.from = (uint16_t)from;
    w.to = (uint16_t)to;
    w.start = (uint16_t)start;
    uint8_t idx = *count;
    (*count)++;
    if (coils) {
        c->params.coils[idx] = w;
        conf_copy_str(c->coil_keys[idx], sizeof c->coil_keys[idx], name);
    } else {
        c->params.inputs[idx] = w;
        conf_copy_str(c->input_keys[idx], sizeof c->input_keys[idx], name);
    }
    conf_set_src(c, coils ? MODCP_PF_COILS : MODCP_PF_INPUTS, idx, section, name, value);
}

static void handle_r32(modcp_conf_t *c, unsigned kind, const char *section, const char *name,
                       const char *value)
{
    uint32_t from = 0, to = 0, db = 0;
    conf_set_src(c, MODCP_PF_R32, kind, section, name, value);
    if (strcasecmp(value, "off") == 0) {
        memset(&c->params.r32[kind], 0, sizeof c->params.r32[kind]);
        return;
    }
    if (!parse_window(value, pfx_dbno, &from, &to, &db)) {
        conf_key_problem(c, true, section, name, value,
                         "syntax: FROM-TO @ DB (e.g. 1000-1099 @ 10) or off", MODCP_EV_PARAM_RECORD);
        return;
    }
    if (from > 0xFFFFu || to > 0xFFFFu || db > 0xFFFFu) {
        conf_key_problem(c, true, section, name, value, "from, to and DB must be 0..65535",
                         MODCP_EV_PARAM_RECORD);
        return;
    }
    c->params.r32[kind].from = (uint16_t)from;
    c->params.r32[kind].to = (uint16_t)to;
    c->params.r32[kind].db = (uint16_t)db;
}

static void handle_limit(modcp_conf_t *c, const char *section, const char *name, const char *value)
{
    modcp_limit_t *l;
    modcp_param_field_t f;
    if (strcasecmp(name, "db") == 0) {
        l = &c->params.lim_db;
        f = MODCP_PF_LIM_DB;
    } else if (strcasecmp(name, "m") == 0) {
        l = &c->params.lim_m;
        f = MODCP_PF_LIM_M;
    } else if (strcasecmp(name, "q") == 0) {
        l = &c->params.lim_q;
        f = MODCP_PF_LIM_Q;
    } else {
        conf_key_problem(c, true, section, name, value, "unknown key (keys: db, m, q)",
                         MODCP_EV_NONE);
        return;
    }
    conf_set_src(c, f, 0, section, name, value);
    if (strcasecmp(value, "off") == 0) {
        l->min = 0;
        l->max = 0;
        return;
    }
    uint32_t lo = 0, hi = 0;
    if (!parse_range(value, &lo, &hi) || lo > 0xFFFFu || hi > 0xFFFFu) {
        conf_key_problem(c, true, section, name, value, conf_field_rule((uint8_t)f), MODCP_EV_WRITE_LIMITS);
        return;
    }
    l->min = (uint16_t)lo;
    l->max = (uint16_t)hi;
}

static void handle_scanner_entries(modcp_conf_t *c, const char *section, const char *name,
                                   const char *value)
{
    char *buf = strdup(value);
    if (buf == NULL) {
        conf_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
        return;
    }
    conf_set_src(c, MODCP_PF_SCANNER, IDX_GLOBAL, section, name, value);
    memset(c->params.scan, 0, sizeof c->params.scan);
    unsigned n = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t,", &save); tok != NULL; tok = strtok_r(NULL, " \t,", &save)) {
        if (n >= MODCP_SCANNER_MAX) {
            conf_key_problem(c, true, section, name, value, "at most 16 entries",
                             MODCP_EV_PARAM_RECORD);
            break;
        }
        conf_set_src(c, MODCP_PF_SCANNER, n, section, name, tok);
        modcp_s7op_t op;
        if (!modcp_s7op_parse(tok, &op) || op.width != MODCP_S7_WORD) {
            char rule[200];
            (void)snprintf(rule, sizeof rule,
                           "entry %u '%s' must be a word operand (MWn, IWn, QWn, DBn.DBWm, Tn, Cn)",
                           n + 1u, tok);
            conf_key_problem(c, true, section, name, value, rule, MODCP_EV_PARAM_RECORD);
            n++;
            continue;
        }
        c->params.scan[n].area = op.area;
        c->params.scan[n].db = op.db;
        c->params.scan[n].offset = op.offset;
        n++;
    }
    free(buf);
    c->params.scan_count = (uint8_t)(n > MODCP_SCANNER_MAX ? MODCP_SCANNER_MAX : n);
}

/* A key of a known section (after the duplicate check and the overrides): the record's
 * keys here, [cpu] and [memory] in conf_cpu.c; keys_of lists the section's keys. */
void conf_handle_key(modcp_conf_t *c, const char *section, const char *name, const char *value,
                     const char *keys_of)
{
    for (size_t i = 0; i < conf_key_count; i++) {
        if (conf_keys[i].key[0] != '\0' && strcasecmp(conf_keys[i].section, section) == 0 &&
            strcasecmp(conf_keys[i].key, name) == 0) {
            handle_table_key(c, &conf_keys[i], section, name, value);
            return;
        }
    }
    if (strcasecmp(section, "coils") == 0 || strcasecmp(section, "inputs") == 0) {
        handle_window(c, strcasecmp(section, "coils") == 0, section, name, value);
        return;
    }
    if (strcasecmp(section, "registers") == 0) {
        static const char *const kinds[3] = {"int16", "int32", "float"};
        for (unsigned k = 0; k < 3u; k++) {
            if (strcasecmp(name, kinds[k]) == 0) {
                handle_r32(c, k, section, name, value);
                return;
            }
        }
    } else if (strcasecmp(section, "limits") == 0) {
        handle_limit(c, section, name, value);
        return;
    } else if (strcasecmp(section, "cpu") == 0) {
        conf_handle_cpu(c, section, name, value);
        return;
    } else if (strcasecmp(section, "memory") == 0) {
        conf_handle_memory(c, section, name, value);
        return;
    } else if (strcasecmp(section, "scanner") == 0 && strcasecmp(name, "entries") == 0) {
        handle_scanner_entries(c, section, name, value);
        return;
    }
    char rule[340];
    (void)snprintf(rule, sizeof rule, "unknown key (keys: %s)", keys_of);
    conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
    return;
}
