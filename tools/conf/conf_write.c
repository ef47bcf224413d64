/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — writers: the parameter tables of docs/parameters.md and the C source
 * of modcp/cfg_gen.h for firmware images. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conf_internal.h"
#include "modcp/event_rows.h"

/* ---- the parameter tables of docs/parameters.md ---------------------------------------- */

static void doc_default(const modcp_params_t *d, const conf_key_t *k, char *out, size_t cap)
{
    const uint8_t *f = (const uint8_t *)d + k->off;
    uint32_t v = 0;
    if (k->width == 1u) {
        v = *f;
    } else if (k->width == 2u) {
        uint16_t x;
        memcpy(&x, f, sizeof x);
        v = x;
    } else if (k->width == 4u) {
        memcpy(&v, f, sizeof v);
    }
    switch (k->syntax) {
    case ENUM:
        for (const enum_name_t *e = k->names; e->name != NULL; e++) {
            if (e->value == v) {
                conf_copy_str(out, cap, e->name);
                return;
            }
        }
        break;
    case BOOL: conf_copy_str(out, cap, v != 0u ? "on" : "off"); return;
    case STR: conf_copy_str(out, cap, f[0] != 0u ? (const char *)f : "empty"); return;
    default: break;
    }
    (void)snprintf(out, cap, "%lu", (unsigned long)v);
}

static void doc_event(const conf_key_t *k, char *out, size_t cap)
{
    uint32_t type_max = k->width == 1u ? 0xFFu : (k->width == 2u ? 0xFFFFu : 0xFFFFFFFFu);
    if (k->min == 0u && k->max >= type_max && (k->flags & MODCP_PF_CUSTOM) == 0u) {
        conf_copy_str(out, cap, "—"); /* every value is legal */
        return;
    }
    char en[16];
    conf_event_name(k->event, en, sizeof en);
    (void)snprintf(out, cap, "%s%s", en, (k->flags & MODCP_PF_WARN) != 0u ? " (not fatal)" : "");
}

bool modcp_conf_write_doc_table(FILE *f)
{
    modcp_params_t d;
    modcp_params_defaults(&d);
    for (size_t i = 0; i < conf_section_count; i++) {
        const char *sec = conf_sections[i][0];
        if (conf_sections[i][1] != NULL) {
            continue; /* coils, inputs, memory: their own syntax, described in prose */
        }
        fprintf(f, "[%s]\n| key | meaning | values | default | source | event |\n"
                   "|---|---|---|---|---|---|\n",
                sec);
        for (size_t k = 0; k < conf_key_count; k++) {
            const conf_key_t *key = &conf_keys[k];
            if (strcmp(key->section, sec) != 0 || key->key[0] == '\0') {
                continue;
            }
            char def[40];
            char ev[40];
            doc_default(&d, key, def, sizeof def);
            doc_event(key, ev, sizeof ev);
            fprintf(f, "| `%s` | %s | %s | %s | %s | %s |\n", key->key, key->meaning, key->values,
                    def, key->source, ev);
        }
        for (size_t k = 0; k < conf_doc_row_count; k++) {
            const doc_row_t *r = &conf_doc_rows[k];
            if (strcmp(r->section, sec) == 0) {
                fprintf(f, "| `%s` | %s | %s | %s | %s | %s |\n", r->key, r->meaning, r->values,
                        r->def, r->source, r->event);
            }
        }
        for (size_t k = 0; strcmp(sec, "cpu") == 0 && k < conf_cpu_key_count;
             k++) {
            const tool_row_t *r = &conf_cpu_keys[k];
            char def[16] = "none";
            if (r->def != UINT32_MAX) {
                (void)snprintf(def, sizeof def, "%lu", (unsigned long)r->def);
            }
            fprintf(f, "| `%s` | %s | %s | %s | %s | %s |\n", r->key, r->meaning, r->values, def,
                    r->source, r->event);
        }
        fprintf(f, "\n");
    }
    return ferror(f) == 0;
}

/* ---- C generator ---------------------------------------------------------------------------------- */

static void write_bytes(FILE *f, const char *name, const uint8_t *b, size_t n)
{
    fprintf(f, "static uint8_t %s[%zu] = {", name, n);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (b[i] != 0u) {
            fprintf(f, "%s[%zu] = 0x%02X", (k % 6u == 0u) ? "\n    " : " ", i, (unsigned)b[i]);
            fputc(',', f);
            k++;
        }
    }
    fprintf(f, "%s};\n", k == 0u ? "0" : "\n");
}

static void write_words(FILE *f, const char *name, const uint16_t *w, size_t n)
{
    fprintf(f, "static uint16_t %s[%zu] = {", name, n);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (w[i] != 0u) {
            fprintf(f, "%s[%zu] = 0x%04X,", (k % 5u == 0u) ? "\n    " : " ", i, (unsigned)w[i]);
            k++;
        }
    }
    fprintf(f, "%s};\n", k == 0u ? "0" : "\n");
}

bool modcp_conf_write_c(const modcp_conf_t *c, FILE *f)
{
    uint8_t rec[MODCP_PARAMS_RECORD_MAX];
    size_t rlen = modcp_conf_record(c, rec, sizeof rec);
    if (rlen == 0u) {
        return false;
    }
    modcp_conf_memory_t m;
    if (!modcp_conf_memory_alloc(c, &m)) {
        return false;
    }
    const char *base = strrchr(c->name, '/');
    base = base != NULL ? base + 1 : c->name;
    char settings[48];
    modcp_conf_line_settings(&c->params, settings, sizeof settings);
    fprintf(f, "/* Generated by modcp-conf from %s -- do not edit.\n"
               " * Slave %u, %s. See modcp/cfg_gen.h. */\n",
            base, (unsigned)c->params.slave_addr, settings);
    fprintf(f, "#include <stddef.h>\n#include <stdint.h>\n\n#include \"modcp/cfg_gen.h\"\n\n");
    fprintf(f, "const uint8_t modcp_cfg_record[%zu] = {", rlen);
    for (size_t i = 0; i < rlen; i++) {
        fprintf(f, "%s0x%02X,", (i % 12u == 0u) ? "\n    " : " ", (unsigned)rec[i]);
    }
    fprintf(f, "\n};\nconst uint16_t modcp_cfg_record_len = %zu;\n\n", rlen);

    if (c->i_bytes > 0u) {
        write_bytes(f, "cfg_i", m.mem.i, c->i_bytes);
    }
    if (c->q_bytes > 0u) {
        write_bytes(f, "cfg_q", m.mem.q, c->q_bytes);
    }
    if (c->m_bytes > 0u) {
        write_bytes(f, "cfg_m", m.mem.m, c->m_bytes);
    }
    if (c->timers > 0u) {
        write_words(f, "cfg_t", m.mem.t, c->timers);
    }
    if (c->counters > 0u) {
        write_words(f, "cfg_c", m.mem.c, c->counters);
    }
    for (uint16_t i = 0; i < c->db_count; i++) {
        char name[32];
        (void)snprintf(name, sizeof name, "cfg_db%u", (unsigned)c->dbs[i].number);
        write_bytes(f, name, m.dbs[i].data, c->dbs[i].size);
    }
    if (c->db_count > 0u) {
        fprintf(f, "\nstatic modcp_db_t cfg_dbs[%u] = {\n", (unsigned)c->db_count);
        for (uint16_t i = 0; i < c->db_count; i++) {
            fprintf(f, "    {%u, %u, cfg_db%u},\n", (unsigned)c->dbs[i].number,
                    (unsigned)c->dbs[i].size, (unsigned)c->dbs[i].number);
        }
        fprintf(f, "};\n");
    }
    fprintf(f, "\nmodcp_plcmem_t modcp_cfg_mem = {\n");
    fprintf(f, "    .i = %s,\n    .q = %s,\n    .m = %s,\n    .t = %s,\n    .c = %s,\n",
            c->i_bytes > 0u ? "cfg_i" : "NULL", c->q_bytes > 0u ? "cfg_q" : "NULL",
            c->m_bytes > 0u ? "cfg_m" : "NULL", c->timers > 0u ? "cfg_t" : "NULL",
            c->counters > 0u ? "cfg_c" : "NULL");
    fprintf(f, "    .i_size = %u,\n    .q_size = %u,\n    .m_size = %u,\n", (unsigned)c->i_bytes,
            (unsigned)c->q_bytes, (unsigned)c->m_bytes);
    fprintf(f, "    .t_count = %u,\n    .c_count = %u,\n", (unsigned)c->timers,
            (unsigned)c->counters);
    fprintf(f, "    .dbs = %s,\n    .db_count = %u,\n};\n\n", c->db_count > 0u ? "cfg_dbs" : "NULL",
            (unsigned)c->db_count);
    fprintf(f, "const uint16_t modcp_cfg_work_db = %u;\n", (unsigned)c->work_db);
    fprintf(f, "const uint32_t modcp_cfg_cycle_ms = %lu;\n", (unsigned long)c->cycle_ms);
    fprintf(f, "const uint32_t modcp_cfg_start_time_ms = %u;\n", (unsigned)c->params.start_time_ms);
    fprintf(f, "const uint8_t modcp_cfg_slave_addr = %u;\n", (unsigned)c->params.slave_addr);
    fprintf(f, "const uint32_t modcp_cfg_baud = %lu;\n", (unsigned long)c->params.baud);
    fprintf(f, "const char modcp_cfg_name[] = \"");
    for (const char *p = base; *p != '\0'; p++) {
        if (*p == '"' || *p == '\\') {
            fputc('\\', f);
        }
        fputc(isprint((unsigned char)*p) ? *p : '?', f);
    }
    fprintf(f, "\";\n");
    modcp_conf_memory_free(&m);
    return ferror(f) == 0;
}

void modcp_conf_line_settings(const modcp_params_t *p, char *out, size_t cap)
{
    char par = p->parity == MODCP_PARITY_EVEN ? 'E' : (p->parity == MODCP_PARITY_ODD ? 'O' : 'N');
    (void)snprintf(out, cap, "%lu %u%c%u %s", (unsigned long)p->baud, (unsigned)p->data_bits, par,
                   (unsigned)p->stop_bits, p->framing == MODCP_FRAMING_ASCII ? "ASCII" : "RTU");
}

/* ---- the event tables of docs/diagnostics.md ------------------------------------------- */

typedef struct {
    modcp_event_t ev;
    uint8_t exc;
    const char *answer, *text, *remedy, *cause, *path, *test;
} doc_event_t;

#define DOC_EVENT_ROW(NAME, cls, num, exc, answer, text, remedy, cause, path, test)               \
    {MODCP_EV_##NAME, (exc), answer, text, remedy, cause, path, test},
static const doc_event_t doc_events[] = {MODCP_EVENT_ROWS(DOC_EVENT_ROW)};
#undef DOC_EVENT_ROW

bool modcp_conf_write_event_table(FILE *f)
{
    static const struct {
        uint8_t cls;
        const char *heading;
    } classes[] = {
#define DOC_CLASS_ROW(cls, name, heading) {(cls), heading},
        MODCP_EVENT_CLASS_ROWS(DOC_CLASS_ROW)
#undef DOC_CLASS_ROW
    };
    for (size_t c = 0; c < sizeof classes / sizeof classes[0]; c++) {
        fprintf(f, "%s### Class %02XH — %s\n\n"
                   "| event | text | cause in modcp | remedy | exc. | path | test |\n"
                   "|---|---|---|---|---|---|---|\n",
                c == 0u ? "" : "\n", (unsigned)classes[c].cls, classes[c].heading);
        for (size_t i = 0; i < sizeof doc_events / sizeof doc_events[0]; i++) {
            const doc_event_t *e = &doc_events[i];
            if (MODCP_EVENT_CLASS(e->ev) != classes[c].cls) {
                continue;
            }
            char exc[48];
            if (e->exc != 0u) {
                (void)snprintf(exc, sizeof exc, "%02u%s", (unsigned)e->exc, e->answer);
            } else {
                conf_copy_str(exc, sizeof exc, e->answer);
            }
            char en[16];
            conf_event_name(e->ev, en, sizeof en);
            fprintf(f, "| %s | %s | %s | %s | %s | %s | %s |\n", en, e->text, e->cause, e->remedy,
                    exc, e->path, e->test);
        }
    }
    fprintf(f, "\n### Not applicable\n\n"
               "| event | manual | manual text | why it cannot happen in modcp |\n"
               "|---|---|---|---|\n");
#define DOC_NA_ROW(cls, num, source, text, reason)                                                \
    fprintf(f, "| (%02X)%02XH | %s | %s | %s |\n", (unsigned)(cls), (unsigned)(num), source, text,  \
            reason);
    MODCP_EVENT_NA_ROWS(DOC_NA_ROW)
#undef DOC_NA_ROW
    return ferror(f) == 0;
}
