/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — reading: the INI text line by line, --set overrides, duplicate keys,
 * and loading (defaults, validation, the tool-level checks). */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "conf_internal.h"
#include "params_internal.h"

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

static void on_ini_line(parse_ctx_t *px, const char *section, const char *name,
                        const char *value)
{
    modcp_conf_t *c = px->c;
    char keys_of[300];
    if (!conf_known_keys(section, keys_of, sizeof keys_of)) {
        const char *ov = override_of(px, section, name, &c->cur);
        if (ov != NULL) {
            value = ov;
        }
        if (px->bad_section == NULL || strcmp(px->bad_section, section) != 0) {
            free(px->bad_section);
            px->bad_section = strdup(section);
            conf_key_problem(c, true, section, name, value,
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
        conf_key_problem(c, true, section, name, value, rule, MODCP_EV_NONE);
        return;
    }
    const char *ov = override_of(px, section, name, &c->cur);
    if (ov != NULL) {
        value = ov;
    }
    conf_handle_key(c, section, name, value, keys_of);
}

static void conf_reset(modcp_conf_t *c, const char *name)
{
    memset(c, 0, sizeof *c);
    conf_copy_str(c->name, sizeof c->name, name);
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
    conf_add_problem(px->c, true, px->c->cur, "syntax error: %s: '%s'", what, shown);
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
            conf_add_problem(px->c, true, px->c->cur, "syntax error: a NUL byte in the line");
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
 * ([RTU-2009] Table 5-2, default "half duplex (RS485) 2-wire: modem"); the ASCII stop bits follow
 * the parity ([ASCII-32] §3.1). */
static void derived_defaults(modcp_conf_t *c)
{
    modcp_params_t *p = &c->params;
    if (!c->src[MODCP_PF_OPMODE][0].set && p->iface == MODCP_IFACE_RS485) {
        p->opmode = MODCP_OPMODE_SUPPRESS;
    }
    /* [ASCII-32] §3.1: "With even or odd parity 1 stop bit is pre-defined. None parity effects
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
        conf_add_problem(c, true, none, "out of memory");
    }
    modcp_param_issue_t issues[64];
    size_t n = modcp_params_validate(&c->params, issues, 64);
    for (size_t i = 0; i < n && i < 64u; i++) {
        conf_report_issue(c, &issues[i]);
    }
    conf_check_cpu(c);
    conf_check_memory(c);
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
        conf_add_problem(c, true, none, "out of memory");
        return c->fatal_count;
    }
    px->c = c;
    for (size_t i = 0; i < n_overrides; i++) {
        if (!add_override(px, overrides[i], (uint32_t)i + 1u)) {
            modcp_conf_loc_t at = {0u, (uint32_t)i + 1u};
            conf_add_problem(c, true, at, "%s: expected section.key=value (at most %u)", overrides[i],
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
        conf_add_problem(c, true, none, "cannot read the file (%s)", strerror(err));
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
