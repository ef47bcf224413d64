/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — INI configuration -> parameter record + controller memory.
 * The schema is documented in docs/parameters.md; keep both in step. */
#define _POSIX_C_SOURCE 200809L
#include "modcp_conf.h"

#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "modcp/events.h"
#include "params_fields.h"
#include "params_internal.h"

#define IDX_GLOBAL 16u /* src[] slot for issue index 0xFF */

/* ---- defaults of the tool-level [cpu] keys ------------------------------------- */
#define DEF_I_BYTES 128u
#define DEF_Q_BYTES 128u
#define DEF_M_BYTES 256u
#define DEF_TIMERS 128u
#define DEF_COUNTERS 128u
#define DEF_CYCLE_MS 10u
#define MAX_CYCLE_MS 60000u

/* ---- small helpers ---------------------------------------------------------------- */

static void copy_str(char *dst, size_t cap, const char *src)
{
    if (cap == 0u) {
        return;
    }
    size_t n = strlen(src);
    if (n >= cap) {
        n = cap - 1u;
    }
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static void event_name(modcp_event_t ev, char *buf, size_t cap)
{
    (void)snprintf(buf, cap, "(%02X)%02XH", (unsigned)MODCP_EVENT_CLASS(ev),
                   (unsigned)MODCP_EVENT_NUMBER(ev));
}

/* Unsigned number, decimal or 0x hex, the whole string. */
static bool parse_u32(const char *s, uint32_t *v)
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

/* ---- problems ------------------------------------------------------------------------ */

static void vadd_problem(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc, const char *fmt,
                         va_list ap)
{
    if (c->problem_count < MODCP_CONF_MAX_PROBLEMS) {
        modcp_conf_problem_t *p = &c->problems[c->problem_count];
        char where[32];
        const char *file = loc.override != 0u ? "--set" : c->name;
        (void)snprintf(where, sizeof where, ":%lu: ",
                       (unsigned long)(loc.override != 0u ? loc.override : loc.line));
        size_t fl = strlen(file);
        if (fl > sizeof p->text / 2u) {
            fl = sizeof p->text / 2u;
        }
        memcpy(p->text, file, fl); /* c->name and p->text are in the same object */
        p->text[fl] = '\0';
        int n = (int)fl;
        size_t wl = strlen(where);
        memcpy(p->text + fl, where, wl + 1u);
        n += (int)wl;
        if (n >= 0 && (size_t)n < sizeof p->text) {
            (void)vsnprintf(p->text + n, sizeof p->text - (size_t)n, fmt, ap);
        }
        p->fatal = fatal;
    }
    c->problem_count++;
    if (fatal) {
        c->fatal_count++;
    }
}

/* "NAME:LINE: text" (a problem that is not about one key: syntax, I/O) */
static void add_problem(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd_problem(c, fatal, loc, fmt, ap);
    va_end(ap);
}

/* Values are shown as given, up to 159 characters (a longer one: 156 and "..."). */
static void show_value(char *dst, size_t cap, const char *value)
{
    size_t n = strlen(value);
    if (n < cap) {
        memcpy(dst, value, n + 1u);
    } else {
        memcpy(dst, value, cap - 4u);
        memcpy(dst + cap - 4u, "...", 4u);
    }
}

/* "NAME:LINE: section.key = value: rule (event (0E)23H)", or with "warning, " */
static void add_key_problem_at(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc,
                               const char *section, const char *key, const char *value,
                               const char *rule, modcp_event_t ev)
{
    char en[16];
    char shown[160];
    show_value(shown, sizeof shown, value);
    const char *dot = section[0] != '\0' ? "." : ""; /* a key before the first section */
    if (ev != MODCP_EV_NONE) {
        event_name(ev, en, sizeof en);
        add_problem(c, fatal, loc, "%s%s%s = %s: %s (%sevent %s)", section, dot, key, shown, rule,
                    fatal ? "" : "warning, ", en);
    } else {
        add_problem(c, fatal, loc, "%s%s%s = %s: %s%s", section, dot, key, shown, rule,
                    fatal ? "" : " (warning)");
    }
}

/* The same at the line being read. */
static void add_key_problem(modcp_conf_t *c, bool fatal, const char *section, const char *key,
                            const char *value, const char *rule, modcp_event_t ev)
{
    add_key_problem_at(c, fatal, c->cur, section, key, value, rule, ev);
}

static void src_set(modcp_conf_src_t *s, modcp_conf_loc_t loc, const char *section,
                    const char *key, const char *value)
{
    s->set = true;
    s->loc = loc;
    copy_str(s->section, sizeof s->section, section);
    copy_str(s->key, sizeof s->key, key);
    show_value(s->value, sizeof s->value, value);
}

static void set_src(modcp_conf_t *c, modcp_param_field_t f, unsigned idx, const char *section,
                    const char *key, const char *value)
{
    if ((unsigned)f >= MODCP_PF_COUNT || idx >= MODCP_CONF_SRC_INDEX) {
        return;
    }
    src_set(&c->src[f][idx], c->cur, section, key, value);
}

/* ---- key table ------------------------------------------------------------------------ */

/* The keys of the record's scalar fields are the rows of params_fields.h: section, key,
 * syntax, names, message, event, legal range. */

typedef enum { NUM, ENUM, BOOL, STR } syntax_t;

typedef struct {
    const char *name;
    uint8_t value;
} enum_name_t;

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

typedef struct {
    const char *section;
    const char *key; /* "" = no key of its own */
    uint8_t field;   /* modcp_param_field_t */
    uint8_t index;
    uint8_t width;   /* 1, 2, 4, MODCP_PW_STR */
    uint8_t syntax;  /* syntax_t */
    uint8_t flags;   /* MODCP_PF_* */
    uint32_t min, max;
    modcp_event_t event;
    size_t off;
    const enum_name_t *names;
    const char *rule;
    const char *meaning, *values, *source; /* docs/parameters.md */
} conf_key_t;

#define KEY_S(member, width, field, index, min, max, def, ev, flags, section, key, syntax, names, \
              rule, meaning, values, source)                                                     \
    {section, key,   field,   index, width, syntax,   flags,  min,     max,                       \
     ev,      offsetof(modcp_params_t, member), names_##names, rule, meaning, values, source},
#define KEY_G(...)
#define KEY_M(...)

static const conf_key_t keys[] = {MODCP_PARAM_ROWS(KEY_S, KEY_G, KEY_M)};

typedef struct {
    const char *section, *key, *meaning, *values, *def, *source, *event;
} doc_row_t;

#define DOC_D(section, key, meaning, values, def, source, event) \
    {section, key, meaning, values, def, source, event},

static const doc_row_t doc_rows[] = {MODCP_PARAM_DOC_ROWS(DOC_D)};

/* The [cpu] keys of the controller, not in the record (handle_cpu_tool). */
typedef struct {
    const char *key, *meaning, *values;
    uint32_t def; /* UINT32_MAX: "none" */
    const char *source, *event;
} tool_row_t;

static const tool_row_t cpu_tool_rows[] = {
    {"cycle_ms",
     "cycle time of the user program that calls the FB (simulator; `--cycle-ms` overrides)",
     "1 … 60000", DEF_CYCLE_MS, "—", "—"},
    {"work_db", "the FB's work area (instance DB), never writable by the master; must be in `dbs`",
     "0 (none) or a listed DB", 0u, "004 §4.2", "(0E)3AH"},
    {"i_bytes", "size of the input area I", "0 … 65535", DEF_I_BYTES, "004 §4.2", "—"},
    {"q_bytes", "size of the output area Q", "0 … 65535", DEF_Q_BYTES, "", "—"},
    {"m_bytes", "size of the flag area M", "0 … 65535", DEF_M_BYTES, "", "—"},
    {"timers", "number of timers T", "0 … 65535", DEF_TIMERS, "", "—"},
    {"counters", "number of counters C", "0 … 65535", DEF_COUNTERS, "", "—"},
    {"dbs", "data blocks `NUMBER:SIZE`, space separated, e.g. `800:1024 801:1024`",
     "up to 64 DBs, 1 … 65535 each", UINT32_MAX, "", "—"},
};

/* Sections in the order of docs/parameters.md; coils, inputs and memory have keys of
 * their own syntax (their list is given here), the others the keys of the rows. */
static const char *const section_keys[][2] = {
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

/* The keys of a section ("baud, data_bits, ..."), or false for an unknown section. */
static bool known_keys(const char *section, char *buf, size_t cap)
{
    for (size_t i = 0; i < sizeof section_keys / sizeof section_keys[0]; i++) {
        if (strcasecmp(section_keys[i][0], section) != 0) {
            continue;
        }
        buf[0] = '\0';
        if (section_keys[i][1] != NULL) {
            copy_str(buf, cap, section_keys[i][1]);
            return true;
        }
        size_t n = 0;
        for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
            if (strcmp(keys[k].section, section_keys[i][0]) == 0 && keys[k].key[0] != '\0') {
                n += (size_t)snprintf(buf + n, n < cap ? cap - n : 0u, "%s%s", n > 0u ? ", " : "",
                                      keys[k].key);
            }
        }
        for (size_t k = 0; k < sizeof doc_rows / sizeof doc_rows[0]; k++) {
            if (strcmp(doc_rows[k].section, section_keys[i][0]) == 0) {
                n += (size_t)snprintf(buf + n, n < cap ? cap - n : 0u, "%s%s", n > 0u ? ", " : "",
                                      doc_rows[k].key);
            }
        }
        for (size_t k = 0; strcmp(section_keys[i][0], "cpu") == 0 &&
                           k < sizeof cpu_tool_rows / sizeof cpu_tool_rows[0];
             k++) {
            n += (size_t)snprintf(buf + n, n < cap ? cap - n : 0u, "%s%s", n > 0u ? ", " : "",
                                  cpu_tool_rows[k].key);
        }
        return true;
    }
    return false;
}

/* ---- rules in words --------------------------------------------------------------------- */

static const conf_key_t *key_of_field(uint8_t field)
{
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
        if (keys[i].field == field && keys[i].rule[0] != '\0') {
            return &keys[i];
        }
    }
    return NULL;
}

static const char *field_rule(uint8_t field)
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

/* ---- INI handler --------------------------------------------------------------------------- */

/* "section.key=value" of --set: pointers into the caller's string, which outlives the load. */
typedef struct {
    const char *section;
    size_t section_len;
    const char *key;
    size_t key_len;
    const char *value;
    uint32_t number; /* 1-based position among the --set arguments */
    bool used;
} override_t;

#define MAX_OVERRIDES 32

/* Keys read so far ("section" NUL "key", lower case) with where they were first given: an
 * open-addressing hash set that grows with the file, so no key escapes the check. */
typedef struct {
    char *name;
    modcp_conf_loc_t loc;
} seen_t;

typedef struct {
    modcp_conf_t *c;
    char *section;        /* current section, as written */
    char *bad_section;    /* last unknown section reported */
    override_t ov[MAX_OVERRIDES];
    size_t ov_count;
    seen_t *seen;
    size_t seen_cap; /* power of two, 0 before the first key */
    size_t seen_count;
    bool oom;
} parse_ctx_t;

static void on_ini_line(parse_ctx_t *px, const char *section, const char *name,
                        const char *value);

/* "section.key=value" */
static bool add_override(parse_ctx_t *px, const char *text, uint32_t number)
{
    const char *dot = strchr(text, '.');
    const char *eq = strchr(text, '=');
    if (px->ov_count >= MAX_OVERRIDES || dot == NULL || eq == NULL || eq < dot || dot == text ||
        eq == dot + 1) {
        return false;
    }
    override_t *o = &px->ov[px->ov_count];
    o->section = text;
    o->section_len = (size_t)(dot - text);
    o->key = dot + 1;
    o->key_len = (size_t)(eq - dot - 1);
    o->value = eq + 1;
    o->number = number;
    o->used = false;
    px->ov_count++;
    return true;
}

static bool same_name(const char *a, size_t alen, const char *b)
{
    return strlen(b) == alen && strncasecmp(a, b, alen) == 0;
}

/* The override of section.name, if any; *loc receives its location. */
static const char *override_of(parse_ctx_t *px, const char *section, const char *name,
                               modcp_conf_loc_t *loc)
{
    for (size_t i = 0; i < px->ov_count; i++) {
        override_t *o = &px->ov[i];
        if (same_name(o->section, o->section_len, section) && same_name(o->key, o->key_len, name)) {
            o->used = true;
            loc->line = 0u;
            loc->override = o->number;
            return o->value;
        }
    }
    return NULL;
}

static char *dup_n(const char *s, size_t n)
{
    char *d = malloc(n + 1u);
    if (d != NULL) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static void apply_unused_overrides(parse_ctx_t *px)
{
    for (size_t i = 0; i < px->ov_count; i++) {
        override_t *o = &px->ov[i];
        if (!o->used) {
            px->c->cur.line = 0u;
            px->c->cur.override = o->number;
            char *sec = dup_n(o->section, o->section_len);
            char *key = dup_n(o->key, o->key_len);
            if (sec != NULL && key != NULL) {
                on_ini_line(px, sec, key, o->value); /* marks it used */
            } else {
                px->oom = true;
            }
            free(sec);
            free(key);
        }
    }
}

static uint32_t name_hash(const char *name, size_t len)
{
    uint32_t h = 2166136261u; /* FNV-1a */
    for (size_t i = 0; i < len; i++) {
        h = (h ^ (uint8_t)name[i]) * 16777619u;
    }
    return h;
}

static bool seen_grow(parse_ctx_t *px)
{
    size_t cap = px->seen_cap == 0u ? 64u : px->seen_cap * 2u;
    seen_t *t = calloc(cap, sizeof *t);
    if (t == NULL) {
        return false;
    }
    for (size_t i = 0; i < px->seen_cap; i++) {
        char *n = px->seen[i].name;
        if (n != NULL) {
            size_t len = strlen(n) + 1u;
            len += strlen(n + len);
            size_t j = name_hash(n, len) & (cap - 1u);
            while (t[j].name != NULL) {
                j = (j + 1u) & (cap - 1u);
            }
            t[j] = px->seen[i];
        }
    }
    free(px->seen);
    px->seen = t;
    px->seen_cap = cap;
    return true;
}

/* True (and *first = where) when section/key was given before; records it otherwise. */
static bool seen_before(parse_ctx_t *px, const char *section, const char *key,
                        modcp_conf_loc_t *first)
{
    size_t sl = strlen(section);
    size_t kl = strlen(key);
    char *name = malloc(sl + kl + 2u);
    if (name == NULL || (px->seen_count * 2u >= px->seen_cap && !seen_grow(px))) {
        free(name);
        px->oom = true;
        return false;
    }
    for (size_t i = 0; i < sl; i++) {
        name[i] = (char)tolower((unsigned char)section[i]);
    }
    name[sl] = '\0';
    for (size_t i = 0; i <= kl; i++) {
        name[sl + 1u + i] = (char)tolower((unsigned char)key[i]);
    }
    size_t len = sl + 1u + kl;
    size_t j = name_hash(name, len) & (px->seen_cap - 1u);
    for (; px->seen[j].name != NULL; j = (j + 1u) & (px->seen_cap - 1u)) {
        const char *n = px->seen[j].name;
        if (strcmp(n, name) == 0 && strcmp(n + sl + 1u, name + sl + 1u) == 0) {
            *first = px->seen[j].loc;
            free(name);
            return true;
        }
    }
    px->seen[j].name = name;
    px->seen[j].loc = px->c->cur;
    px->seen_count++;
    return false;
}

static void ctx_free(parse_ctx_t *px)
{
    for (size_t i = 0; i < px->seen_cap; i++) {
        free(px->seen[i].name);
    }
    free(px->seen);
    free(px->section);
    free(px->bad_section);
}

static void handle_table_key(modcp_conf_t *c, const conf_key_t *k, const char *section,
                             const char *name, const char *value)
{
    uint8_t *base = (uint8_t *)&c->params;
    unsigned idx = k->index == 0xFFu ? IDX_GLOBAL : k->index;
    modcp_event_t ev = k->event;
    const char *rule = k->rule;
    uint32_t v = 0;
    set_src(c, (modcp_param_field_t)k->field, idx, section, name, value);

    switch (k->syntax) {
    case ENUM:
        for (const enum_name_t *e = k->names; e->name != NULL; e++) {
            if (strcasecmp(e->name, value) == 0) {
                base[k->off] = e->value;
                return;
            }
        }
        add_key_problem(c, true, section, name, value, rule, ev);
        return;
    case BOOL:
        if (strcasecmp(value, "on") == 0 || strcasecmp(value, "yes") == 0 ||
            strcasecmp(value, "true") == 0 || strcmp(value, "1") == 0) {
            base[k->off] = 1u;
        } else if (strcasecmp(value, "off") == 0 || strcasecmp(value, "no") == 0 ||
                   strcasecmp(value, "false") == 0 || strcmp(value, "0") == 0) {
            base[k->off] = 0u;
        } else {
            add_key_problem(c, true, section, name, value, "must be on or off", ev);
        }
        return;
    case STR:
        if (strlen(value) > MODCP_ID_STRING_MAX) {
            add_key_problem(c, true, section, name, value, rule, ev);
            return;
        }
        memset(base + k->off, 0, MODCP_ID_STRING_MAX + 1u);
        memcpy(base + k->off, value, strlen(value));
        return;
    default:
        break;
    }
    bool ok = parse_u32(value, &v);
    bool soft = (k->flags & MODCP_PF_WARN) != 0u;
    uint32_t max = k->width == 1u ? 0xFFu : (k->width == 2u ? 0xFFFFu : 0xFFFFFFFFu);
    if (!ok) {
        add_key_problem(c, true, section, name, value, "not a number", ev);
        return;
    }
    if (v > max) {
        if (soft) {
            v = 0; /* out of range: the CP's validation reports it and runs with the default */
        } else {
            add_key_problem(c, true, section, name, value, rule, ev);
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
        ok = parse_u32(buf, from) && parse_u32(dash + 1, to);
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
    return parse_u32(s, v);
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
        if (!parse_u32(name + 2, &db) || db > 0xFFFFu || !isdigit((unsigned char)name[2])) {
            add_key_problem(c, true, section, name, value, "bad DB number in the key (db1..db65535)",
                            ev);
            return;
        }
        w.area = MODCP_AREA_DB;
        w.db = (uint16_t)db;
        pfx = pfx_db;
    } else {
        add_key_problem(c, true, section, name, value, usage, MODCP_EV_NONE);
        return;
    }
    uint8_t *count = coils ? &c->coil_count : &c->input_count;
    size_t cap = coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS;
    if (*count >= cap) {
        add_key_problem(c, true, section, name, value,
                        coils ? "too many windows (at most 6)" : "too many windows (at most 4)", ev);
        return;
    }
    uint32_t from = 0, to = 0, start = 0;
    if (!parse_window(value, pfx, &from, &to, &start)) {
        add_key_problem(c, true, section, name, value,
                        "syntax: FROM-TO @ START (e.g. 0-2047 @ 1000)", ev);
        return;
    }
    if (from > 0xFFFFu || to > 0xFFFFu || start > 0xFFFFu) {
        add_key_problem(c, true, section, name, value,
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
        copy_str(c->coil_keys[idx], sizeof c->coil_keys[idx], name);
    } else {
        c->params.inputs[idx] = w;
        copy_str(c->input_keys[idx], sizeof c->input_keys[idx], name);
    }
    set_src(c, coils ? MODCP_PF_COILS : MODCP_PF_INPUTS, idx, section, name, value);
}

static void handle_r32(modcp_conf_t *c, unsigned kind, const char *section, const char *name,
                       const char *value)
{
    uint32_t from = 0, to = 0, db = 0;
    set_src(c, MODCP_PF_R32, kind, section, name, value);
    if (strcasecmp(value, "off") == 0) {
        memset(&c->params.r32[kind], 0, sizeof c->params.r32[kind]);
        return;
    }
    if (!parse_window(value, pfx_dbno, &from, &to, &db)) {
        add_key_problem(c, true, section, name, value,
                        "syntax: FROM-TO @ DB (e.g. 1000-1099 @ 10) or off", MODCP_EV_PARAM_RECORD);
        return;
    }
    if (from > 0xFFFFu || to > 0xFFFFu || db > 0xFFFFu) {
        add_key_problem(c, true, section, name, value, "from, to and DB must be 0..65535",
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
        add_key_problem(c, true, section, name, value, "unknown key (keys: db, m, q)",
                        MODCP_EV_NONE);
        return;
    }
    set_src(c, f, 0, section, name, value);
    if (strcasecmp(value, "off") == 0) {
        l->min = 0;
        l->max = 0;
        return;
    }
    uint32_t lo = 0, hi = 0;
    if (!parse_range(value, &lo, &hi) || lo > 0xFFFFu || hi > 0xFFFFu) {
        add_key_problem(c, true, section, name, value, field_rule((uint8_t)f), MODCP_EV_WRITE_LIMITS);
        return;
    }
    l->min = (uint16_t)lo;
    l->max = (uint16_t)hi;
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
        add_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
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
        if (colon == NULL || !parse_u32(nos, &no) || !parse_u32(colon + 1, &size)) {
            char rule[160];
            (void)snprintf(rule, sizeof rule, "%s: syntax NUMBER:SIZE (e.g. 800:1024)", what);
            add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            continue;
        }
        if (no < 1u || no > 0xFFFFu || size < 1u || size > 0xFFFFu) {
            char rule[160];
            (void)snprintf(rule, sizeof rule, "%s: DB number and size must be 1..65535", what);
            add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
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
            add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            continue;
        }
        if (c->db_count >= MODCP_CONF_MAX_DBS) {
            add_key_problem(c, true, section, name, value, "too many DBs (at most 64)",
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

static void handle_cpu_tool(modcp_conf_t *c, const char *section, const char *name,
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
        src_set(&c->work_db_src, c->cur, section, name, value);
    }
    if (dst != NULL) {
        if (!parse_u32(value, &v) || v > 0xFFFFu) {
            add_key_problem(c, true, section, name, value, "must be 0..65535", MODCP_EV_NONE);
            return;
        }
        *dst = (uint16_t)v;
        return;
    }
    if (strcasecmp(name, "cycle_ms") == 0) {
        src_set(&c->cycle_src, c->cur, section, name, value);
        if (!parse_u32(value, &v) || v < 1u || v > MAX_CYCLE_MS) {
            add_key_problem(c, true, section, name, value, "must be 1..60000 ms", MODCP_EV_NONE);
            return;
        }
        c->cycle_ms = v;
        return;
    }
    char list[256];
    char rule[300];
    (void)known_keys("cpu", list, sizeof list);
    (void)snprintf(rule, sizeof rule, "unknown key (keys: %s)", list);
    add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
}

static void handle_scanner_entries(modcp_conf_t *c, const char *section, const char *name,
                                   const char *value)
{
    char *buf = strdup(value);
    if (buf == NULL) {
        add_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
        return;
    }
    set_src(c, MODCP_PF_SCANNER, IDX_GLOBAL, section, name, value);
    memset(c->params.scan, 0, sizeof c->params.scan);
    unsigned n = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t,", &save); tok != NULL; tok = strtok_r(NULL, " \t,", &save)) {
        if (n >= MODCP_SCANNER_MAX) {
            add_key_problem(c, true, section, name, value, "at most 16 entries",
                            MODCP_EV_PARAM_RECORD);
            break;
        }
        set_src(c, MODCP_PF_SCANNER, n, section, name, tok);
        modcp_s7op_t op;
        if (!modcp_s7op_parse(tok, &op) || op.width != MODCP_S7_WORD) {
            char rule[200];
            (void)snprintf(rule, sizeof rule,
                           "entry %u '%s' must be a word operand (MWn, IWn, QWn, DBn.DBWm, Tn, Cn)",
                           n + 1u, tok);
            add_key_problem(c, true, section, name, value, rule, MODCP_EV_PARAM_RECORD);
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

static void handle_memory(modcp_conf_t *c, const char *section, const char *name, const char *value)
{
    modcp_s7op_t op;
    if (!modcp_s7op_parse(name, &op)) {
        add_key_problem(c, true, section, name, value,
                        "not an operand (e.g. MB1008, M1000.3, IW4, DB800.DBW160, T100)",
                        MODCP_EV_NONE);
        return;
    }
    if (c->init_count >= MODCP_CONF_MAX_INITS) {
        add_key_problem(c, true, section, name, value, "too many [memory] lines (at most 256)",
                        MODCP_EV_NONE);
        return;
    }
    modcp_conf_init_t *in = &c->inits[c->init_count];
    in->loc = c->cur;
    in->op = op;
    in->count = 0;
    in->first = (uint32_t)c->value_count;
    copy_str(in->key, sizeof in->key, name);
    show_value(in->value, sizeof in->value, value);
    char *buf = strdup(value);
    if (buf == NULL) {
        add_key_problem(c, true, section, name, value, "out of memory", MODCP_EV_NONE);
        return;
    }
    char *save = NULL;
    uint32_t max = op.width == MODCP_S7_BIT    ? 1u
                   : op.width == MODCP_S7_BYTE ? 0xFFu
                   : op.width == MODCP_S7_WORD ? 0xFFFFu
                                               : 0xFFFFFFFFu;
    bool bad = false;
    for (char *tok = strtok_r(buf, " \t,", &save); tok != NULL; tok = strtok_r(NULL, " \t,", &save)) {
        uint32_t v = 0;
        bool ok;
        if (op.width == MODCP_S7_DWORD && strpbrk(tok, ".") != NULL) {
            char *end = NULL;
            float f = strtof(tok, &end);
            ok = end != tok && *end == '\0';
            memcpy(&v, &f, sizeof v);
        } else if (op.width == MODCP_S7_BIT) {
            ok = strcmp(tok, "0") == 0 || strcmp(tok, "1") == 0;
            v = tok[0] == '1' ? 1u : 0u;
        } else {
            ok = parse_hex(tok, max, &v);
        }
        if (!ok) {
            char rule[200];
            (void)snprintf(rule, sizeof rule,
                           "bad value '%s' (%s)", tok,
                           op.width == MODCP_S7_BIT
                               ? "bits: 0 or 1"
                               : (op.width == MODCP_S7_DWORD
                                      ? "hex, at most 8 digits, or a float such as 1.5"
                                      : (op.width == MODCP_S7_BYTE ? "hex byte, e.g. 17"
                                                                   : "hex word, e.g. 8765")));
            add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
            bad = true;
            break;
        }
        if (c->value_count >= MODCP_CONF_MAX_VALUES) {
            add_key_problem(c, true, section, name, value, "too many [memory] values (at most 8192)",
                            MODCP_EV_NONE);
            bad = true;
            break;
        }
        c->values[c->value_count++] = v;
        in->count++;
    }
    free(buf);
    if (bad) {
        c->value_count = in->first;
        return;
    }
    if (in->count == 0u) {
        add_key_problem(c, true, section, name, value, "no value", MODCP_EV_NONE);
        return;
    }
    /* the last element's offset must still be addressable */
    uint32_t last;
    if (op.width == MODCP_S7_BIT) {
        last = op.offset + ((uint32_t)op.bit + in->count - 1u) / 8u;
    } else if (op.area == MODCP_AREA_T || op.area == MODCP_AREA_C) {
        last = op.offset + in->count - 1u;
    } else {
        last = op.offset + (uint32_t)op.width * in->count - 1u;
    }
    if (last > 0xFFFFu) {
        add_key_problem(c, true, section, name, value, "runs beyond offset 65535", MODCP_EV_NONE);
        c->value_count = in->first;
        return;
    }
    c->init_count++;
}

static void on_ini_line(parse_ctx_t *px, const char *section, const char *name,
                        const char *value)
{
    modcp_conf_t *c = px->c;
    char keys_of[300];
    if (!known_keys(section, keys_of, sizeof keys_of)) {
        const char *ov = override_of(px, section, name, &c->cur);
        if (ov != NULL) {
            value = ov;
        }
        if (px->bad_section == NULL || strcmp(px->bad_section, section) != 0) {
            free(px->bad_section);
            px->bad_section = strdup(section);
            add_key_problem(c, true, section, name, value,
                            section[0] == '\0'
                                ? "key before the first [section]"
                                : "unknown section (sections: serial, protocol, interface, "
                                  "coils, inputs, registers, limits, cpu, memory, supervision, "
                                  "scanner, identification, diagnostics)",
                            MODCP_EV_NONE);
        }
        return;
    }
    modcp_conf_loc_t first;
    if (seen_before(px, section, name, &first)) {
        char rule[64];
        if (first.override != 0u) {
            (void)snprintf(rule, sizeof rule, "key given twice (first by --set %lu)",
                           (unsigned long)first.override);
        } else {
            (void)snprintf(rule, sizeof rule, "key given twice (first on line %lu)",
                           (unsigned long)first.line);
        }
        add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
        return;
    }
    const char *ov = override_of(px, section, name, &c->cur);
    if (ov != NULL) {
        value = ov;
    }
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
        if (keys[i].key[0] != '\0' && strcasecmp(keys[i].section, section) == 0 &&
            strcasecmp(keys[i].key, name) == 0) {
            handle_table_key(c, &keys[i], section, name, value);
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
        handle_cpu_tool(c, section, name, value);
        return;
    } else if (strcasecmp(section, "memory") == 0) {
        handle_memory(c, section, name, value);
        return;
    } else if (strcasecmp(section, "scanner") == 0 && strcasecmp(name, "entries") == 0) {
        handle_scanner_entries(c, section, name, value);
        return;
    }
    char rule[340];
    (void)snprintf(rule, sizeof rule, "unknown key (keys: %s)", keys_of);
    add_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
    return;
}

/* ---- schema coverage ------------------------------------------------------------------ */

size_t modcp_conf_uncovered(uint8_t *fields, size_t cap)
{
    size_t n = 0;
    for (unsigned f = 1; f < MODCP_PF_COUNT; f++) {
        bool covered = f == MODCP_PF_COILS || f == MODCP_PF_INPUTS || f == MODCP_PF_R32 ||
                       f == MODCP_PF_LIM_DB || f == MODCP_PF_LIM_M || f == MODCP_PF_LIM_Q ||
                       f == MODCP_PF_SCANNER;
        for (size_t i = 0; !covered && i < sizeof keys / sizeof keys[0]; i++) {
            covered = keys[i].field == f;
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
                copy_str(out, cap, e->name);
                return;
            }
        }
        break;
    case BOOL: copy_str(out, cap, v != 0u ? "on" : "off"); return;
    case STR: copy_str(out, cap, f[0] != 0u ? (const char *)f : "empty"); return;
    default: break;
    }
    (void)snprintf(out, cap, "%lu", (unsigned long)v);
}

static void doc_event(const conf_key_t *k, char *out, size_t cap)
{
    uint32_t type_max = k->width == 1u ? 0xFFu : (k->width == 2u ? 0xFFFFu : 0xFFFFFFFFu);
    if (k->min == 0u && k->max >= type_max && (k->flags & MODCP_PF_CUSTOM) == 0u) {
        copy_str(out, cap, "—"); /* every value is legal */
        return;
    }
    char en[16];
    event_name(k->event, en, sizeof en);
    (void)snprintf(out, cap, "%s%s", en, (k->flags & MODCP_PF_WARN) != 0u ? " (not fatal)" : "");
}

bool modcp_conf_write_doc_table(FILE *f)
{
    modcp_params_t d;
    modcp_params_defaults(&d);
    for (size_t i = 0; i < sizeof section_keys / sizeof section_keys[0]; i++) {
        const char *sec = section_keys[i][0];
        if (section_keys[i][1] != NULL) {
            continue; /* coils, inputs, memory: their own syntax, described in prose */
        }
        fprintf(f, "[%s]\n| key | meaning | values | default | source | event |\n"
                   "|---|---|---|---|---|---|\n",
                sec);
        for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
            const conf_key_t *key = &keys[k];
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
        for (size_t k = 0; k < sizeof doc_rows / sizeof doc_rows[0]; k++) {
            const doc_row_t *r = &doc_rows[k];
            if (strcmp(r->section, sec) == 0) {
                fprintf(f, "| `%s` | %s | %s | %s | %s | %s |\n", r->key, r->meaning, r->values,
                        r->def, r->source, r->event);
            }
        }
        for (size_t k = 0; strcmp(sec, "cpu") == 0 && k < sizeof cpu_tool_rows / sizeof cpu_tool_rows[0];
             k++) {
            const tool_row_t *r = &cpu_tool_rows[k];
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
                copy_str(exc, sizeof exc, e->answer);
            }
            char en[16];
            event_name(e->ev, en, sizeof en);
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

/* ---- validation issues -> problems ---------------------------------------------------------- */

static const char *default_key(uint8_t field, unsigned index, const char **section)
{
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
        if (keys[i].field == field && keys[i].key[0] != '\0' &&
            (keys[i].index == index || keys[i].index == 0xFFu)) {
            *section = keys[i].section;
            return keys[i].key;
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

static bool is_tc(uint8_t area)
{
    return area == MODCP_AREA_T || area == MODCP_AREA_C;
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
    } else if (is_tc(w->area) && ((uint32_t)w->to - w->from + 1u) % 16u != 0u) {
        (void)snprintf(rule, cap,
                       "illegal from/to: a T/C window must span a multiple of 16 bits (it spans %u)",
                       (unsigned)((uint32_t)w->to - w->from + 1u));
    } else if (is_tc(w->area)) {
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

static void report_issue(modcp_conf_t *c, const modcp_param_issue_t *is)
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
                           "odd 1 stop bit, with parity none 2 (003 §3.1: 7E1, 7O1 or 7N2); "
                           "stop_bits = %u",
                           (unsigned)p->data_bits, par, (unsigned long)is->value, none ? 2u : 1u);
        } else {
            copy_str(rule, sizeof rule, field_rule(is->field));
        }
        break;
    case MODCP_PF_OPMODE:
        if (is->value == MODCP_OPMODE_NORMAL) { /* legal value, not on two-wire RS485 */
            (void)snprintf(rule, sizeof rule,
                           "normal is not allowed with interface.type = rs485 (two-wire runs in "
                           "interference suppression = modem mode) unless "
                           "protocol.rs485_mode_select = on (000 Table 5-2)");
        } else {
            copy_str(rule, sizeof rule, field_rule(is->field));
        }
        break;
    default: copy_str(rule, sizeof rule, field_rule(is->field)); break;
    }
    add_key_problem_at(c, is->fatal, loc, section, key, value, rule, is->event);
}

/* ---- tool-level checks: [cpu] and [memory] against the controller ------------------------- */

static const modcp_conf_db_t *conf_db(const modcp_conf_t *c, uint16_t number)
{
    for (uint16_t i = 0; i < c->db_count; i++) {
        if (c->dbs[i].number == number) {
            return &c->dbs[i];
        }
    }
    return NULL;
}

static void check_memory(modcp_conf_t *c)
{
    for (size_t i = 0; i < c->init_count; i++) {
        const modcp_conf_init_t *in = &c->inits[i];
        const modcp_s7op_t *op = &in->op;
        uint32_t end; /* one past the last byte / element */
        if (op->width == MODCP_S7_BIT) {
            end = op->offset + ((uint32_t)op->bit + in->count - 1u) / 8u + 1u;
        } else if (is_tc(op->area)) {
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
                add_key_problem_at(c, true, in->loc, "memory", in->key, in->value, rule, ev);
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
                           is_tc(op->area) ? "elements" : "bytes");
            add_key_problem_at(c, true, in->loc, "memory", in->key, in->value, rule, ev);
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
        uint32_t last = is_tc(w->area) ? w->start + bits / 16u - 1u : w->start + (bits - 1u) / 8u;
        uint32_t size;
        char what[48];
        switch (w->area) {
        case MODCP_AREA_I: size = c->i_bytes; copy_str(what, sizeof what, "cpu.i_bytes"); break;
        case MODCP_AREA_Q: size = c->q_bytes; copy_str(what, sizeof what, "cpu.q_bytes"); break;
        case MODCP_AREA_M: size = c->m_bytes; copy_str(what, sizeof what, "cpu.m_bytes"); break;
        case MODCP_AREA_T: size = c->timers; copy_str(what, sizeof what, "cpu.timers"); break;
        case MODCP_AREA_C: size = c->counters; copy_str(what, sizeof what, "cpu.counters"); break;
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
                           is_tc(w->area) ? "element" : "byte", (unsigned)last, what,
                           (unsigned)size);
            add_key_problem_at(c, false, s->loc, s->section, s->key, s->value, rule, MODCP_EV_NONE);
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
        add_key_problem_at(c, true, s->loc, "cpu", "start_time_ms", s->set ? s->value : value,
                           rule, MODCP_EV_NONE);
    } else { /* the default START_TIME and a long cycle: the cycle is the key to fix */
        char crule[160];
        (void)snprintf(crule, sizeof crule,
                       "must be less than start_time_ms %u (default) / %lu: the FB's "
                       "initialisation takes %lu cycles",
                       (unsigned)c->params.start_time_ms, (unsigned long)(calls - 1u),
                       (unsigned long)calls);
        add_key_problem_at(c, true, c->cycle_src.loc, c->cycle_src.section, c->cycle_src.key,
                           c->cycle_src.value, crule, MODCP_EV_NONE);
    }
}

static void check_cpu(modcp_conf_t *c)
{
    if (c->work_db != 0u && conf_db(c, c->work_db) == NULL) {
        const modcp_conf_src_t *s = &c->work_db_src;
        char rule[96];
        (void)snprintf(rule, sizeof rule, "DB%u is not in cpu.dbs", (unsigned)c->work_db);
        add_key_problem_at(c, true, s->loc, s->section, s->key, s->value, rule, MODCP_EV_WORK_DB);
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
            add_key_problem_at(c, false, s->loc, s->section, s->key, s->value, rule,
                               MODCP_EV_NONE);
        }
    }
    check_start_time(c);
}

/* ---- loading ------------------------------------------------------------------------------------ */

static void conf_reset(modcp_conf_t *c, const char *name)
{
    memset(c, 0, sizeof *c);
    copy_str(c->name, sizeof c->name, name);
    modcp_params_defaults(&c->params);
    c->i_bytes = DEF_I_BYTES;
    c->q_bytes = DEF_Q_BYTES;
    c->m_bytes = DEF_M_BYTES;
    c->timers = DEF_TIMERS;
    c->counters = DEF_COUNTERS;
    c->cycle_ms = DEF_CYCLE_MS;
}

/* ---- reading -------------------------------------------------------------------------------------
 * The INI dialect of libinih, read whole: a line of any length is one line (libinih
 * splits lines at 200 characters, so a long comment hid the key after it and shifted
 * every later line number). "[section]", "key = value" (or "key: value"), comment lines
 * starting with ';' or '#', an inline comment from a ';' after white space. Names and
 * values are trimmed. Unlike libinih, an indented line is an ordinary line (not the
 * continuation of the previous value), and text after "[section]" is a syntax error. */

static char *lskip(char *s)
{
    while (*s != '\0' && isspace((unsigned char)*s)) {
        s++;
    }
    return s;
}

static void rstrip(char *s)
{
    size_t n = strlen(s);
    while (n > 0u && isspace((unsigned char)s[n - 1u])) {
        s[--n] = '\0';
    }
}

/* First of chars (NULL: none) or of an inline comment (';' after white space). */
static char *find_chars_or_comment(char *s, const char *chars)
{
    bool was_space = false;
    while (*s != '\0' && (chars == NULL || strchr(chars, *s) == NULL) &&
           !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s) != 0;
        s++;
    }
    return s;
}

static void syntax_error(parse_ctx_t *px, const char *what, const char *line)
{
    char shown[84];
    size_t n = strlen(line);
    if (n < sizeof shown) {
        memcpy(shown, line, n + 1u);
    } else {
        memcpy(shown, line, sizeof shown - 4u);
        memcpy(shown + sizeof shown - 4u, "...", 4u);
    }
    add_problem(px->c, true, px->c->cur, "syntax error: %s: '%s'", what, shown);
}

static void parse_line(parse_ctx_t *px, char *line)
{
    rstrip(line);
    char *s = lskip(line);
    if (*s == '\0' || *s == ';' || *s == '#') {
        return;
    }
    if (*s == '[') {
        char *end = find_chars_or_comment(s + 1, "]");
        if (*end != ']') {
            syntax_error(px, "expected ']'", s);
            return;
        }
        char *rest = lskip(end + 1);
        if (*rest != '\0' && *rest != ';' && *rest != '#') {
            syntax_error(px, "text after [section]", s);
            return;
        }
        *end = '\0';
        char *name = lskip(s + 1);
        rstrip(name);
        char *dup = strdup(name);
        if (dup == NULL) {
            px->oom = true;
            return;
        }
        free(px->section);
        px->section = dup;
        return;
    }
    char *end = find_chars_or_comment(s, "=:");
    if (*end != '=' && *end != ':') {
        syntax_error(px, "expected [section] or key = value", s);
        return;
    }
    *end = '\0';
    rstrip(s);
    if (*s == '\0') {
        *end = '=';
        syntax_error(px, "no key before '='", s);
        return;
    }
    char *value = lskip(end + 1);
    *find_chars_or_comment(value, NULL) = '\0';
    rstrip(value);
    on_ini_line(px, px->section != NULL ? px->section : "", s, value);
}

/* Every line of text[0 .. len), with its number. */
static void parse_text(parse_ctx_t *px, const char *text, size_t len)
{
    size_t pos = 0;
    uint32_t lineno = 0;
    if (len >= 3u && memcmp(text, "\xEF\xBB\xBF", 3u) == 0) {
        pos = 3u; /* UTF-8 byte order mark */
    }
    while (pos < len && !px->oom) {
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t n = nl != NULL ? (size_t)(nl - (text + pos)) : len - pos;
        lineno++;
        px->c->cur.line = lineno;
        px->c->cur.override = 0u;
        if (memchr(text + pos, '\0', n) != NULL) {
            add_problem(px->c, true, px->c->cur, "syntax error: a NUL byte in the line");
        } else {
            char *line = dup_n(text + pos, n);
            if (line == NULL) {
                px->oom = true;
                break;
            }
            parse_line(px, line);
            free(line);
        }
        pos += n + 1u;
    }
}

/* Defaults that follow another key, as the manuals' parameter dialogs set them: two-wire
 * RS485 runs in interference suppression (modem) mode unless `mode` says otherwise
 * (000 Table 5-2, default "half duplex (RS485) 2-wire: modem"); the ASCII stop bits follow
 * the parity (003 §3.1). */
static void derived_defaults(modcp_conf_t *c)
{
    modcp_params_t *p = &c->params;
    if (!c->src[MODCP_PF_OPMODE][0].set && p->iface == MODCP_IFACE_RS485) {
        p->opmode = MODCP_OPMODE_SUPPRESS;
    }
    /* 003 §3.1: "With even or odd parity 1 stop bit is pre-defined. None parity effects
     * two stop bits." */
    if (!c->src[MODCP_PF_STOP_BITS][0].set && p->framing == MODCP_FRAMING_ASCII) {
        p->stop_bits = p->parity == MODCP_PARITY_NONE ? 2u : 1u;
    }
}

static size_t finish(modcp_conf_t *c, parse_ctx_t *px)
{
    apply_unused_overrides(px);
    derived_defaults(c);
    bool oom = px->oom;
    ctx_free(px);
    if (oom) {
        modcp_conf_loc_t none = {0u, 0u};
        add_problem(c, true, none, "out of memory");
    }
    modcp_param_issue_t issues[64];
    size_t n = modcp_params_validate(&c->params, issues, 64);
    for (size_t i = 0; i < n && i < 64u; i++) {
        report_issue(c, &issues[i]);
    }
    check_cpu(c);
    check_memory(c);
    return c->fatal_count;
}

/* The whole file, NUL-terminated (heap), or NULL. */
static char *read_file(FILE *f, size_t *len)
{
    size_t cap = 0;
    size_t n = 0;
    char *buf = NULL;
    for (;;) {
        if (n + 1u >= cap) {
            size_t ncap = cap == 0u ? 4096u : cap * 2u;
            char *b = realloc(buf, ncap);
            if (b == NULL) {
                free(buf);
                return NULL;
            }
            buf = b;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, cap - n - 1u, f);
        n += got;
        if (got == 0u) {
            if (ferror(f)) {
                free(buf);
                return NULL;
            }
            buf[n] = '\0';
            *len = n;
            return buf;
        }
    }
}

size_t modcp_conf_load_ex(modcp_conf_t *c, const char *path, const char *const *overrides,
                          size_t n_overrides)
{
    conf_reset(c, path);
    modcp_conf_loc_t none = {0u, 0u};
    parse_ctx_t *px = calloc(1, sizeof *px);
    if (px == NULL) {
        add_problem(c, true, none, "out of memory");
        return c->fatal_count;
    }
    px->c = c;
    for (size_t i = 0; i < n_overrides; i++) {
        if (!add_override(px, overrides[i], (uint32_t)i + 1u)) {
            modcp_conf_loc_t at = {0u, (uint32_t)i + 1u};
            add_problem(c, true, at, "%s: expected section.key=value (at most %u)", overrides[i],
                        (unsigned)MAX_OVERRIDES);
        }
    }
    FILE *f = fopen(path, "rb");
    size_t len = 0;
    char *text = NULL;
    int err = errno;
    if (f != NULL) {
        text = read_file(f, &len);
        err = errno;
        fclose(f);
    }
    if (text == NULL) {
        add_problem(c, true, none, "cannot read the file (%s)", strerror(err));
        ctx_free(px);
        free(px);
        return c->fatal_count;
    }
    parse_text(px, text, len);
    free(text);
    size_t fatal = finish(c, px);
    free(px);
    return fatal;
}

size_t modcp_conf_load(modcp_conf_t *c, const char *path)
{
    return modcp_conf_load_ex(c, path, NULL, 0u);
}

size_t modcp_conf_load_string(modcp_conf_t *c, const char *name, const char *text)
{
    conf_reset(c, name);
    parse_ctx_t px;
    memset(&px, 0, sizeof px);
    px.c = c;
    parse_text(&px, text, strlen(text));
    return finish(c, &px);
}

size_t modcp_conf_record(const modcp_conf_t *c, uint8_t *buf, size_t cap)
{
    return modcp_params_encode(&c->params, buf, cap);
}

/* ---- controller memory ------------------------------------------------------------------------ */

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
            } else if (is_tc(op.area)) {
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
