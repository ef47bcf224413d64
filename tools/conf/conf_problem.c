/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — problems: the messages that name the key, its value and the rule, and
 * where each value came from (file line, --set override or default). */
#define _POSIX_C_SOURCE 200809L
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "conf_internal.h"

void conf_copy_str(char *dst, size_t cap, const char *src)
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

void conf_event_name(modcp_event_t ev, char *buf, size_t cap)
{
    (void)snprintf(buf, cap, "(%02X)%02XH", (unsigned)MODCP_EVENT_CLASS(ev),
                   (unsigned)MODCP_EVENT_NUMBER(ev));
}

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
void conf_add_problem(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vadd_problem(c, fatal, loc, fmt, ap);
    va_end(ap);
}

/* Values are shown as given, up to 159 characters (a longer one: 156 and "..."). */
void conf_show_value(char *dst, size_t cap, const char *value)
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
void conf_key_problem_at(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc,
                         const char *section, const char *key, const char *value,
                         const char *rule, modcp_event_t ev)
{
    char en[16];
    char shown[160];
    conf_show_value(shown, sizeof shown, value);
    const char *dot = section[0] != '\0' ? "." : ""; /* a key before the first section */
    if (ev != MODCP_EV_NONE) {
        conf_event_name(ev, en, sizeof en);
        conf_add_problem(c, fatal, loc, "%s%s%s = %s: %s (%sevent %s)", section, dot, key, shown, rule,
                         fatal ? "" : "warning, ", en);
    } else {
        conf_add_problem(c, fatal, loc, "%s%s%s = %s: %s%s", section, dot, key, shown, rule,
                         fatal ? "" : " (warning)");
    }
}

/* The same at the line being read. */
void conf_key_problem(modcp_conf_t *c, bool fatal, const char *section, const char *key,
                      const char *value, const char *rule, modcp_event_t ev)
{
    conf_key_problem_at(c, fatal, c->cur, section, key, value, rule, ev);
}

void conf_src_set(modcp_conf_src_t *s, modcp_conf_loc_t loc, const char *section,
                  const char *key, const char *value)
{
    s->set = true;
    s->loc = loc;
    conf_copy_str(s->section, sizeof s->section, section);
    conf_copy_str(s->key, sizeof s->key, key);
    conf_show_value(s->value, sizeof s->value, value);
}

void conf_set_src(modcp_conf_t *c, modcp_param_field_t f, unsigned idx, const char *section,
                  const char *key, const char *value)
{
    if ((unsigned)f >= MODCP_PF_COUNT || idx >= MODCP_CONF_SRC_INDEX) {
        return;
    }
    conf_src_set(&c->src[f][idx], c->cur, section, key, value);
}
