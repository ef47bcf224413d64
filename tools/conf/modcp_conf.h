/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — INI configuration -> parameter record + controller memory.
 * Shared by modcp-conf and modcp-sim (host tools; may use POSIX and the heap).
 * Schema: docs/parameters.md. Lines are read whole, whatever their length; every
 * key is checked for duplicates, whatever the number of keys. */
#ifndef MODCP_CONF_H
#define MODCP_CONF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "modcp/console.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"

#define MODCP_CONF_MAX_DBS 64
#define MODCP_CONF_MAX_INITS 256
#define MODCP_CONF_MAX_VALUES 8192
#define MODCP_CONF_MAX_PROBLEMS 64
#define MODCP_CONF_PROBLEM_LEN 640
#define MODCP_CONF_SRC_INDEX 17 /* per field: 16 indexed entries + index 0xFF */

typedef struct {
    uint16_t number;
    uint16_t size;
} modcp_conf_db_t;

/* Where a value came from: a line of the file (override 0), or the N-th --set
 * override (override N, line 0). line 0 and override 0: a default. */
typedef struct {
    uint32_t line;
    uint32_t override;
} modcp_conf_loc_t;

/* One [memory] line: consecutive elements from op on. */
typedef struct {
    modcp_conf_loc_t loc;
    modcp_s7op_t op;
    uint16_t count;
    uint32_t first; /* index into values[] */
    char key[48];
    char value[160];
} modcp_conf_init_t;

/* Where a parameter came from (for messages). */
typedef struct {
    bool set;
    modcp_conf_loc_t loc;
    char section[24];
    char key[40];
    char value[160];
} modcp_conf_src_t;

typedef struct {
    bool fatal;
    char text[MODCP_CONF_PROBLEM_LEN];
} modcp_conf_problem_t;

typedef struct {
    char name[256]; /* file name as given */
    modcp_params_t params;
    /* [cpu]: the controller */
    uint16_t i_bytes, q_bytes, m_bytes, timers, counters;
    modcp_conf_db_t dbs[MODCP_CONF_MAX_DBS]; /* sorted by number */
    uint16_t db_count;
    uint16_t work_db;
    uint32_t cycle_ms;
    /* [memory] */
    modcp_conf_init_t inits[MODCP_CONF_MAX_INITS];
    size_t init_count;
    uint32_t values[MODCP_CONF_MAX_VALUES];
    size_t value_count;
    /* problems, in the order found */
    modcp_conf_problem_t problems[MODCP_CONF_MAX_PROBLEMS];
    size_t problem_count; /* may exceed MODCP_CONF_MAX_PROBLEMS (then not all stored) */
    size_t fatal_count;
    /* parse state */
    modcp_conf_loc_t cur; /* the line being read */
    modcp_conf_src_t src[MODCP_PF_COUNT][MODCP_CONF_SRC_INDEX];
    modcp_conf_src_t work_db_src, cycle_src; /* [cpu] keys checked after reading */
    uint8_t coil_count, input_count;
    char coil_keys[MODCP_COIL_WINDOWS][16];
    char input_keys[MODCP_INPUT_WINDOWS][16];
} modcp_conf_t;

/* Load and validate a file (or a string, for tests). Returns the number of fatal
 * problems (0 = usable; warnings may still be listed). Problems are formatted
 *   NAME:LINE: section.key = value: rule (event (0E)23H)
 *   NAME:LINE: protocol.f_mul = 11: must be 1..10; the CP runs with 1 (warning, event (0E)21H)
 *   NAME:LINE: syntax error: ...
 * A value given by the N-th override is reported as "--set:N: section.key = value: ...";
 * a default value that breaks a rule as "NAME:0: section.key = value (default): ...". */
size_t modcp_conf_load(modcp_conf_t *c, const char *path);
/* The same with overrides "section.key=value" that replace (or add) keys of the file,
 * e.g. "serial.baud=115200" (modcp-sim --set). */
size_t modcp_conf_load_ex(modcp_conf_t *c, const char *path, const char *const *overrides,
                          size_t n_overrides);
size_t modcp_conf_load_string(modcp_conf_t *c, const char *name, const char *text);

/* The binary parameter record; returns its length (0 if cap is too small). */
size_t modcp_conf_record(const modcp_conf_t *c, uint8_t *buf, size_t cap);

/* Controller memory of the [cpu] section with the [memory] values applied (heap). */
typedef struct {
    modcp_plcmem_t mem;
    modcp_db_t dbs[MODCP_CONF_MAX_DBS];
} modcp_conf_memory_t;

bool modcp_conf_memory_alloc(const modcp_conf_t *c, modcp_conf_memory_t *m);
void modcp_conf_memory_free(modcp_conf_memory_t *m);

/* Generate the C source of modcp/cfg_gen.h into f. Returns false on a write error. */
bool modcp_conf_write_c(const modcp_conf_t *c, FILE *f);

/* Parameter fields (modcp_param_field_t) without an INI key: should be none. Returns
 * how many, their ids in fields[0 .. cap). (`modcp-conf fields` prints them.) */
size_t modcp_conf_uncovered(uint8_t *fields, size_t cap);

/* The parameter tables of docs/parameters.md, rendered from the parameter rows
 * (params_fields.h): per section "[section]", the markdown table, an empty line.
 * (`modcp-conf doc-table` prints them; the integration.conf test compares them with the
 * document.) Returns false on a write error. */
bool modcp_conf_write_doc_table(FILE *f);
/* The event tables of docs/diagnostics.md ("### Class ..." to "### Not applicable" and its
 * table), from the event rows (modcp/event_rows.h). */
bool modcp_conf_write_event_table(FILE *f);

/* "9600 8E1 RTU" */
void modcp_conf_line_settings(const modcp_params_t *p, char *out, size_t cap);

#endif
