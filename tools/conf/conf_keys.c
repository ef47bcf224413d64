/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — the keys: the rows of params_fields.h as a key table (section, key,
 * syntax, names, rule, event, range), the [cpu] tool keys, the sections in the order of
 * docs/parameters.md, and the schema's coverage of the record's fields. */
#define _POSIX_C_SOURCE 200809L
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "conf_internal.h"
#include "params_fields.h"

static const enum_name_t names_parity[] = {
    {"none", MODCP_PARITY_NONE}, {"odd", MODCP_PARITY_ODD}, {"even", MODCP_PARITY_EVEN},
    {"n", MODCP_PARITY_NONE},    {"o", MODCP_PARITY_ODD},   {"e", MODCP_PARITY_EVEN},
    {NULL, 0}};
static const enum_name_t names_framing[] = {
    {"rtu", MODCP_FRAMING_RTU}, {"ascii", MODCP_FRAMING_ASCII}, {NULL, 0}};
static const enum_name_t names_mode[] = {{"normal", MODCP_OPMODE_NORMAL},
                                         {"suppress", MODCP_OPMODE_SUPPRESS},
                                         {"interference_suppression", MODCP_OPMODE_SUPPRESS},
                                         {"modem", MODCP_OPMODE_SUPPRESS},
                                         {NULL, 0}};
static const enum_name_t names_eof[] = {
    {"manual", MODCP_EOF_MANUAL}, {"modbus", MODCP_EOF_MODBUS}, {NULL, 0}};
static const enum_name_t names_iface[] = {{"rs232", MODCP_IFACE_RS232},
                                          {"rs422", MODCP_IFACE_RS422},
                                          {"rs485", MODCP_IFACE_RS485},
                                          {NULL, 0}};
static const enum_name_t names_rxpreset[] = {{"default", MODCP_RXP_DEFAULT},
                                             {"none", MODCP_RXP_NONE},
                                             {"break", MODCP_RXP_BREAK},
                                             {"high", MODCP_RXP_HIGH},
                                             {NULL, 0}};
static const enum_name_t names_fset[] = {
    {"cp341", MODCP_FSET_CP341}, {"extended", MODCP_FSET_EXTENDED}, {NULL, 0}};
static const enum_name_t names_qlimits[] = {
    {"manual", MODCP_QLIMITS_MANUAL}, {"spec", MODCP_QLIMITS_SPEC}, {NULL, 0}};
static const enum_name_t names_model[] = {
    {"cp341", MODCP_CPU_CP341}, {"cp441", MODCP_CPU_CP441}, {"cp441-2", MODCP_CPU_CP441}, {NULL, 0}};
#define names_none NULL

#define KEY_S(member, width, field, index, min, max, def, ev, flags, section, key, syntax, names, \
              rule, meaning, values, source)                                                     \
    {section, key,   field,   index, width, syntax,   flags,  min,     max,                       \
     ev,      offsetof(modcp_params_t, member), names_##names, rule, meaning, values, source},
#define KEY_G(...)
#define KEY_M(...)

const conf_key_t conf_keys[] = {MODCP_PARAM_ROWS(KEY_S, KEY_G, KEY_M)};
const size_t conf_key_count = sizeof conf_keys / sizeof conf_keys[0];

#define DOC_D(section, key, meaning, values, def, source, event) \
    {section, key, meaning, values, def, source, event},

const doc_row_t conf_doc_rows[] = {MODCP_PARAM_DOC_ROWS(DOC_D)};
const size_t conf_doc_row_count = sizeof conf_doc_rows / sizeof conf_doc_rows[0];

const tool_row_t conf_cpu_keys[] = {
    {"cycle_ms",
     "cycle time of the user program that calls the FB (simulator; `--cycle-ms` overrides)",
     "1 … 60000", DEF_CYCLE_MS, "—", "—"},
    {"work_db", "the FB's work area (instance DB), never writable by the master; must be in `dbs`",
     "0 (none) or a listed DB", 0u, "[RTU-2003] §4.2", "(0E)3AH"},
    {"i_bytes", "size of the input area I", "0 … 65535", DEF_I_BYTES, "[RTU-2003] §4.2", "—"},
    {"q_bytes", "size of the output area Q", "0 … 65535", DEF_Q_BYTES, "", "—"},
    {"m_bytes", "size of the flag area M", "0 … 65535", DEF_M_BYTES, "", "—"},
    {"timers", "number of timers T", "0 … 65535", DEF_TIMERS, "", "—"},
    {"counters", "number of counters C", "0 … 65535", DEF_COUNTERS, "", "—"},
    {"dbs", "data blocks `NUMBER:SIZE`, space separated, e.g. `800:1024 801:1024`",
     "up to 64 DBs, 1 … 65535 each", UINT32_MAX, "", "—"},
};
const size_t conf_cpu_key_count = sizeof conf_cpu_keys / sizeof conf_cpu_keys[0];

/* Sections in the order of docs/parameters.md; coils, inputs and memory have keys of
 * their own syntax (their list is given here), the others the keys of the rows. */
const char *const conf_sections[][2] = {
    {"serial", NULL},
    {"protocol", NULL},
    {"interface", NULL},
    {"coils", "m, q, t, c, dbN (FROM-TO @ START)"},
    {"inputs", "m, i, dbN (FROM-TO @ START)"},
    {"registers", NULL},
    {"limits", NULL},
    {"cpu", NULL},
    {"memory", "S7 operands, e.g. MB1008, M1000.3, DB800.DBW160, T100"},
    {"supervision", NULL},
    {"scanner", NULL},
    {"identification", NULL},
    {"diagnostics", NULL},
};
const size_t conf_section_count = sizeof conf_sections / sizeof conf_sections[0];

/* ", key" after the n characters in buf (n counts what would have been written). */
static void append_key(char *buf, size_t cap, size_t *n, const char *key)
{
    *n += (size_t)snprintf(buf + *n, *n < cap ? cap - *n : 0u, "%s%s", *n > 0u ? ", " : "", key);
}

bool conf_known_keys(const char *section, char *buf, size_t cap)
{
    for (size_t i = 0; i < conf_section_count; i++) {
        const char *sec = conf_sections[i][0];
        if (strcasecmp(sec, section) != 0) {
            continue;
        }
        buf[0] = '\0';
        if (conf_sections[i][1] != NULL) {
            conf_copy_str(buf, cap, conf_sections[i][1]);
            return true;
        }
        size_t n = 0;
        for (size_t k = 0; k < conf_key_count; k++) {
            if (strcmp(conf_keys[k].section, sec) == 0 && conf_keys[k].key[0] != '\0') {
                append_key(buf, cap, &n, conf_keys[k].key);
            }
        }
        for (size_t k = 0; k < conf_doc_row_count; k++) {
            if (strcmp(conf_doc_rows[k].section, sec) == 0) {
                append_key(buf, cap, &n, conf_doc_rows[k].key);
            }
        }
        for (size_t k = 0; strcmp(sec, "cpu") == 0 && k < conf_cpu_key_count; k++) {
            append_key(buf, cap, &n, conf_cpu_keys[k].key);
        }
        return true;
    }
    return false;
}

/* ---- schema coverage ------------------------------------------------------------------ */

size_t modcp_conf_uncovered(uint8_t *fields, size_t cap)
{
    size_t n = 0;
    for (unsigned f = 1; f < MODCP_PF_COUNT; f++) {
        bool covered = f == MODCP_PF_COILS || f == MODCP_PF_INPUTS || f == MODCP_PF_R32 ||
                       f == MODCP_PF_LIM_DB || f == MODCP_PF_LIM_M || f == MODCP_PF_LIM_Q ||
                       f == MODCP_PF_SCANNER;
        for (size_t i = 0; !covered && i < conf_key_count; i++) {
            covered = conf_keys[i].field == f;
        }
        if (!covered) {
            if (n < cap) {
                fields[n] = (uint8_t)f;
            }
            n++;
        }
    }
    return n;
}
