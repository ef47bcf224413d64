/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf internal: what the reader's files share. By concern, as the reader runs:
 *   conf_read.c      the INI text line by line, --set overrides, duplicate keys, loading
 *   conf_keys.c      the key table (params_fields.h rows), [cpu] tool keys, sections
 *   conf_handlers.c  a value for a key of the parameter record -> modcp_params_t
 *   conf_cpu.c       [cpu] and [memory] keys, the controller memory built from them
 *   conf_rules.c     validation issues -> problems with the rule in words
 *   conf_check.c     tool-level checks of [cpu] and [memory] against the controller
 *   conf_problem.c   the problem list, where each value came from
 *   conf_write.c     the docs/parameters.md tables and the C source of cfg_gen.h */
#ifndef MODCP_CONF_INTERNAL_H
#define MODCP_CONF_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/events.h"
#include "modcp_conf.h"
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

/* ---- key table (conf_keys.c) ---------------------------------------------------- */

/* The keys of the record's scalar fields are the rows of params_fields.h: section, key,
 * syntax, names, message, event, legal range. */

typedef enum { NUM, ENUM, BOOL, STR } syntax_t;

typedef struct {
    const char *name;
    uint8_t value;
} enum_name_t;

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

/* Keys documented in docs/parameters.md whose value is handled by their own code. */
typedef struct {
    const char *section, *key, *meaning, *values, *def, *source, *event;
} doc_row_t;

/* The [cpu] keys of the controller, not in the record (conf_handle_cpu). */
typedef struct {
    const char *key, *meaning, *values;
    uint32_t def; /* UINT32_MAX: "none" */
    const char *source, *event;
} tool_row_t;

extern const conf_key_t conf_keys[];
extern const size_t conf_key_count;
extern const doc_row_t conf_doc_rows[];
extern const size_t conf_doc_row_count;
extern const tool_row_t conf_cpu_keys[];
extern const size_t conf_cpu_key_count;
/* Sections in the order of docs/parameters.md: {name, NULL} when its keys are rows of
 * the tables above, {name, "the list of its keys"} for keys of their own syntax. */
extern const char *const conf_sections[][2];
extern const size_t conf_section_count;

/* The keys of a section ("baud, data_bits, ..."), or false for an unknown section. */
bool conf_known_keys(const char *section, char *buf, size_t cap);

/* ---- problems (conf_problem.c) ----------------------------------------------------- */

void conf_copy_str(char *dst, size_t cap, const char *src);
/* "(0E)23H" */
void conf_event_name(modcp_event_t ev, char *buf, size_t cap);
/* Values are shown as given, up to cap - 1 characters (a longer one: cap - 4 and "..."). */
void conf_show_value(char *dst, size_t cap, const char *value);
/* "NAME:LINE: text" (a problem that is not about one key: syntax, I/O) */
void conf_add_problem(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* "NAME:LINE: section.key = value: rule (event (0E)23H)", or with "warning, " */
void conf_key_problem_at(modcp_conf_t *c, bool fatal, modcp_conf_loc_t loc, const char *section,
                         const char *key, const char *value, const char *rule, modcp_event_t ev);
/* The same at the line being read. */
void conf_key_problem(modcp_conf_t *c, bool fatal, const char *section, const char *key,
                      const char *value, const char *rule, modcp_event_t ev);
/* Where a value came from: the line being read. */
void conf_src_set(modcp_conf_src_t *s, modcp_conf_loc_t loc, const char *section, const char *key,
                  const char *value);
void conf_set_src(modcp_conf_t *c, modcp_param_field_t f, unsigned idx, const char *section,
                  const char *key, const char *value);

/* ---- key handlers (conf_handlers.c, conf_cpu.c) ----------------------------------------- */

/* Unsigned number, decimal or 0x hex, the whole string. */
bool conf_parse_u32(const char *s, uint32_t *v);
/* A key of a known section (after the duplicate check and the overrides); keys_of lists
 * the section's keys for the message of an unknown key. */
void conf_handle_key(modcp_conf_t *c, const char *section, const char *name, const char *value,
                     const char *keys_of);
void conf_handle_cpu(modcp_conf_t *c, const char *section, const char *name, const char *value);
void conf_handle_memory(modcp_conf_t *c, const char *section, const char *name,
                        const char *value);

/* ---- rules and checks (conf_rules.c, conf_check.c) ------------------------------------------ */

const char *conf_field_rule(uint8_t field);
/* One issue of modcp_params_validate as a problem at the key and value it came from. */
void conf_report_issue(modcp_conf_t *c, const modcp_param_issue_t *is);
/* [cpu] against the record (work DB, windows, base DBs, START_TIME) and [memory]
 * against the controller's areas. */
void conf_check_cpu(modcp_conf_t *c);
void conf_check_memory(modcp_conf_t *c);

static inline bool conf_is_tc(uint8_t area)
{
    return area == MODCP_AREA_T || area == MODCP_AREA_C;
}

#endif
