/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — the controller: [cpu] (area sizes, DBs, work DB, cycle) and [memory]
 * (initial values) keys, and the controller memory built from them. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "conf_internal.h"

/* Hex element value of a [memory] line (0x, 16#, B#16#, W#16#, DW#16# prefixes
 * optional). */
static bool parse_hex(const char *s, uint32_t max, uint32_t *v)
{
    static const char *const prefixes[] = {"0x", "dw#16#", "w#16#", "b#16#", "16#"};
    for (size_t i = 0; i < sizeof prefixes / sizeof prefixes[0]; i++) {
        size_t n = strlen(prefixes[i]);
        if (strncasecmp(s, prefixes[i], n) == 0) {
            s += n;
            break;
        }
    }
    if (*s == '\0') {
        return false;
    }
    for (const char *p = s; *p != '\0'; p++) {
        if (!isxdigit((unsigned char)*p)) {
            return false;
        }
    }
    char *end = NULL;
    unsigned long long x = strtoull(s, &end, 16);
    if (*end != '\0' || x > max) {
        return false;
    }
    *v = (uint32_t)x;
    return true;
}

static int cmp_db(const void *a, const void *b)
{
    const modcp_conf_db_t *x = a;
    const modcp_conf_db_t *y = b;
    return (int)x->number - (int)y->number;
}

static void handle_dbs(modcp_conf_t *c, const char *section, const char *name, const char *value)
{
    char *buf = strdup(value);
    if (buf == NULL) {
        conf_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
        return;
    }
    c->db_count = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t,", &save); tok != NULL; tok = strtok_r(NULL, " \t,", &save)) {
        char *colon = strchr(tok, ':');
        uint32_t no = 0, size = 0;
        if (colon != NULL) {
            *colon = '\0';
        }
        const char *nos = tok;
        if (strncasecmp(nos, "db", 2) == 0) {
            nos += 2;
        }
        char what[96];
        (void)snprintf(what, sizeof what, "entry '%s%s%s'", tok, colon != NULL ? ":" : "",
                       colon != NULL ? colon + 1 : "");
        if (colon == NULL || !conf_parse_u32(nos, &no) || !conf_parse_u32(colon + 1, &size)) {
            char rule[160];
            (void)snprintf(rule, sizeof rule, "%s: syntax NUMBER:SIZE (e.g. 800:1024)", what);
            conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            continue;
        }
        if (no < 1u || no > 0xFFFFu || size < 1u || size > 0xFFFFu) {
            char rule[160];
            (void)snprintf(rule, sizeof rule, "%s: DB number and size must be 1..65535", what);
            conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            continue;
        }
        bool dup = false;
        for (uint16_t i = 0; i < c->db_count; i++) {
            if (c->dbs[i].number == no) {
                dup = true;
            }
        }
        if (dup) {
            char rule[160];
            (void)snprintf(rule, sizeof rule, "%s: DB%u listed twice", what, (unsigned)no);
            conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            continue;
        }
        if (c->db_count >= MODCP_CONF_MAX_DBS) {
            conf_key_problem(c, true, section, name, value, "too many DBs (at most 64)",
                             MODCP_EV_NONE);
            break;
        }
        c->dbs[c->db_count].number = (uint16_t)no;
        c->dbs[c->db_count].size = (uint16_t)size;
        c->db_count++;
    }
    free(buf);
    qsort(c->dbs, c->db_count, sizeof c->dbs[0], cmp_db);
}

void conf_handle_cpu(modcp_conf_t *c, const char *section, const char *name,
                     const char *value)
{
    uint32_t v = 0;
    uint16_t *dst = NULL;
    if (strcasecmp(name, "dbs") == 0) {
        handle_dbs(c, section, name, value);
        return;
    }
    if (strcasecmp(name, "i_bytes") == 0) {
        dst = &c->i_bytes;
    } else if (strcasecmp(name, "q_bytes") == 0) {
        dst = &c->q_bytes;
    } else if (strcasecmp(name, "m_bytes") == 0) {
        dst = &c->m_bytes;
    } else if (strcasecmp(name, "timers") == 0) {
        dst = &c->timers;
    } else if (strcasecmp(name, "counters") == 0) {
        dst = &c->counters;
    } else if (strcasecmp(name, "work_db") == 0) {
        dst = &c->work_db;
        conf_src_set(&c->work_db_src, c->cur, section, name, value);
    }
    if (dst != NULL) {
        if (!conf_parse_u32(value, &v) || v > 0xFFFFu) {
            conf_key_problem(c, true, section, name, value, "must be 0..65535", MODCP_EV_NONE);
            return;
        }
        *dst = (uint16_t)v;
        return;
    }
    if (strcasecmp(name, "cycle_ms") == 0) {
        conf_src_set(&c->cycle_src, c->cur, section, name, value);
        if (!conf_parse_u32(value, &v) || v < 1u || v > MAX_CYCLE_MS) {
            conf_key_problem(c, true, section, name, value, "must be 1..60000 ms", MODCP_EV_NONE);
            return;
        }
        c->cycle_ms = v;
        return;
    }
    char list[256];
    char rule[300];
    (void)conf_known_keys("cpu", list, sizeof list);
    (void)snprintf(rule, sizeof rule, "unknown key (keys: %s)", list);
    conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
}

/* One element value of a [memory] line: bits 0 or 1, hex up to the width, or a float
 * for a double word. */
static bool memory_value(const modcp_s7op_t *op, const char *tok, uint32_t *v)
{
    if (op->width == MODCP_S7_DWORD && strpbrk(tok, ".") != NULL) {
        char *end = NULL;
        float f = strtof(tok, &end);
        memcpy(v, &f, sizeof *v);
        return end != tok && *end == '\0';
    }
    if (op->width == MODCP_S7_BIT) {
        *v = tok[0] == '1' ? 1u : 0u;
        return strcmp(tok, "0") == 0 || strcmp(tok, "1") == 0;
    }
    uint32_t max = op->width == MODCP_S7_BYTE ? 0xFFu
                   : op->width == MODCP_S7_WORD ? 0xFFFFu
                                                : 0xFFFFFFFFu;
    return parse_hex(tok, max, v);
}

static const char *memory_value_syntax(uint8_t width)
{
    switch (width) {
    case MODCP_S7_BIT: return "bits: 0 or 1";
    case MODCP_S7_DWORD: return "hex, at most 8 digits, or a float such as 1.5";
    case MODCP_S7_BYTE: return "hex byte, e.g. 17";
    default: return "hex word, e.g. 8765";
    }
}

/* The values of a [memory] line into c->values[] for in; false (and none kept) with a
 * problem at the first bad one. */
static bool memory_values(modcp_conf_t *c, modcp_conf_init_t *in, const char *section,
                          const char *name, const char *value, char *buf)
{
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t,", &save); tok != NULL; tok = strtok_r(NULL, " \t,", &save)) {
        uint32_t v = 0;
        if (!memory_value(&in->op, tok, &v)) {
            char rule[200];
            (void)snprintf(rule, sizeof rule, "bad value '%s' (%s)", tok,
                           memory_value_syntax(in->op.width));
            conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            c->value_count = in->first;
            return false;
        }
        if (c->value_count >= MODCP_CONF_MAX_VALUES) {
            conf_key_problem(c, true, section, name, value,
                             "too many [memory] values (at most 8192)", MODCP_EV_NONE);
            c->value_count = in->first;
            return false;
        }
        c->values[c->value_count++] = v;
        in->count++;
    }
    return true;
}

/* The offset of the last element of count elements from op on. */
static uint32_t memory_last(const modcp_s7op_t *op, uint16_t count)
{
    if (op->width == MODCP_S7_BIT) {
        return op->offset + ((uint32_t)op->bit + count - 1u) / 8u;
    }
    if (op->area == MODCP_AREA_T || op->area == MODCP_AREA_C) {
        return op->offset + count - 1u;
    }
    return op->offset + (uint32_t)op->width * count - 1u;
}

void conf_handle_memory(modcp_conf_t *c, const char *section, const char *name, const char *value)
{
    modcp_s7op_t op;
    if (!modcp_s7op_parse(name, &op)) {
        conf_key_problem(c, true, section, name, value,
                         "not an operand (e.g. MB1008, M1000.3, IW4, DB800.DBW160, T100)",
                         MODCP_EV_NONE);
        return;
    }
    if (c->init_count >= MODCP_CONF_MAX_INITS) {
        conf_key_problem(c, true, section, name, value, "too many [memory] lines (at most 256)",
                         MODCP_EV_NONE);
        return;
    }
    modcp_conf_init_t *in = &c->inits[c->init_count];
    in->loc = c->cur;
    in->op = op;
    in->count = 0;
    in->first = (uint32_t)c->value_count;
    conf_copy_str(in->key, sizeof in->key, name);
    conf_show_value(in->value, sizeof in->value, value);
    char *buf = strdup(value);
    if (buf == NULL) {
        conf_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
        return;
    }
    bool ok = memory_values(c, in, section, name, value, buf);
    free(buf);
    if (!ok) {
        return;
    }
    if (in->count == 0u) {
        conf_key_problem(c, true, section, name, value, "no value", MODCP_EV_NONE);
        return;
    }
    /* the last element's offset must still be addressable */
    if (memory_last(&op, in->count) > 0xFFFFu) {
        conf_key_problem(c, true, section, name, value, "runs beyond offset 65535", MODCP_EV_NONE);
        c->value_count = in->first;
        return;
    }
    c->init_count++;
}

static void apply_inits(const modcp_conf_t *c, modcp_plcmem_t *mem)
{
    for (size_t i = 0; i < c->init_count; i++) {
        const modcp_conf_init_t *in = &c->inits[i];
        modcp_s7op_t op = in->op;
        for (uint16_t k = 0; k < in->count; k++) {
            (void)modcp_s7op_write(mem, &op, c->values[in->first + k]);
            if (op.width == MODCP_S7_BIT) {
                if (op.bit == 7u) {
                    op.bit = 0;
                    op.offset = (uint16_t)(op.offset + 1u);
                } else {
                    op.bit = (uint8_t)(op.bit + 1u);
                }
            } else if (conf_is_tc(op.area)) {
                op.offset = (uint16_t)(op.offset + 1u);
            } else {
                op.offset = (uint16_t)(op.offset + op.width);
            }
        }
    }
}

bool modcp_conf_memory_alloc(const modcp_conf_t *c, modcp_conf_memory_t *m)
{
    memset(m, 0, sizeof *m);
    modcp_plcmem_t *mem = &m->mem;
    mem->i = calloc(c->i_bytes + 1u, 1);
    mem->q = calloc(c->q_bytes + 1u, 1);
    mem->m = calloc(c->m_bytes + 1u, 1);
    mem->t = calloc(c->timers + 1u, sizeof(uint16_t));
    mem->c = calloc(c->counters + 1u, sizeof(uint16_t));
    mem->i_size = c->i_bytes;
    mem->q_size = c->q_bytes;
    mem->m_size = c->m_bytes;
    mem->t_count = c->timers;
    mem->c_count = c->counters;
    bool ok = mem->i != NULL && mem->q != NULL && mem->m != NULL && mem->t != NULL && mem->c != NULL;
    for (uint16_t i = 0; i < c->db_count; i++) {
        m->dbs[i].number = c->dbs[i].number;
        m->dbs[i].size = c->dbs[i].size;
        m->dbs[i].data = calloc(c->dbs[i].size, 1);
        ok = ok && m->dbs[i].data != NULL;
    }
    mem->dbs = m->dbs;
    mem->db_count = c->db_count;
    if (!ok) {
        modcp_conf_memory_free(m);
        return false;
    }
    apply_inits(c, mem);
    return true;
}

void modcp_conf_memory_free(modcp_conf_memory_t *m)
{
    free(m->mem.i);
    free(m->mem.q);
    free(m->mem.m);
    free(m->mem.t);
    free(m->mem.c);
    for (size_t i = 0; i < MODCP_CONF_MAX_DBS; i++) {
        free(m->dbs[i].data);
    }
    memset(m, 0, sizeof *m);
}
