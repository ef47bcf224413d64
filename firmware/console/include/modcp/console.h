/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console (S7 notation) over the CPU side's memory, the FB and a
 * snapshot of the CP's diagnostics. Portable C11: no OS, no heap, no globals; only
 * snprintf / strtol / strtoul / strtod from libc. The host simulator feeds it from
 * stdin; a board feeds it from its second UART. Call it from the CPU side between two
 * FB calls, so that every access is consistent with the FB's jobs.
 *
 * One command per call; the answer is written to out (NUL-terminated, lines separated
 * by '\n', no trailing newline; empty for blank lines and comments). Answers are
 * machine-readable, e.g.
 *     get MB1000            -> MB1000 = 0x17 (23)
 *     get M1000.3           -> M1000.3 = 1
 *     get DB800.DBD4 float  -> DB800.DBD4 = 1.5 (0x3FC00000)
 *     set MW1000 0x1234     -> MW1000 = 0x1234 (4660)
 * Errors are one line "error: ...". See `help` and docs/simulator.md. */
#ifndef MODCP_CONSOLE_H
#define MODCP_CONSOLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/diag.h"
#include "modcp/events.h"
#include "modcp/fb.h"
#include "modcp/plcmem.h"

/* An S7 operand: M1000.3 (bit), MB / MW / MD, IB.., QB.., Tn, Cn, DBn.DBX/DBB/DBW/DBD. */
enum {
    MODCP_S7_BIT = 0,   /* X */
    MODCP_S7_BYTE = 1,  /* B */
    MODCP_S7_WORD = 2,  /* W, and T / C elements */
    MODCP_S7_DWORD = 4, /* D */
};

typedef struct {
    uint8_t area;    /* modcp_area_t: I, Q, M, T, C, DB */
    uint8_t width;   /* MODCP_S7_* (T and C: WORD) */
    uint8_t bit;     /* 0..7 for MODCP_S7_BIT */
    uint16_t db;     /* DB number for MODCP_AREA_DB */
    uint16_t offset; /* byte offset (I, Q, M, DB) or element number (T, C) */
} modcp_s7op_t;

/* Parse an operand such as "MB1000", "m1000.3", "DB800.DBW160", "T100" (case-
 * insensitive, whole string). Returns false on a syntax error or a number > 65535. */
bool modcp_s7op_parse(const char *s, modcp_s7op_t *op);

/* Canonical name ("MB1000", "DB800.DBX0.1"); returns the length written. */
size_t modcp_s7op_name(const modcp_s7op_t *op, char *out, size_t cap);

/* Read / write the operand's value (bit: 0/1; byte, word, dword big-endian as the
 * controller stores them; T/C: the element). Returns MODCP_EV_NONE, (0E)38H when the
 * operand lies outside I/Q/M/T/C, or (0E)39H for a missing or too short DB. */
modcp_event_t modcp_s7op_read(const modcp_plcmem_t *mem, const modcp_s7op_t *op, uint32_t *value);
modcp_event_t modcp_s7op_write(modcp_plcmem_t *mem, const modcp_s7op_t *op, uint32_t value);

/* What the console looks at. Every pointer may be NULL (the commands that need it
 * then answer "error: ... not available"). */
typedef struct modcp_console_env {
    modcp_plcmem_t *mem;      /* CPU-side controller memory: get / set / dump */
    const modcp_diag_t *diag; /* a copy of the CP's diagnostics: diag / status */
    const modcp_fb_t *fb;     /* the FB: init state, outputs, jobs: status */
    bool *paused;             /* the cyclic user program is paused: pause / resume */
    bool *cp_start;           /* the FB's CP_START input: start 0|1 (optional) */
    modcp_backplane_t *bp;    /* the backplane: commloss reset (optional) */
    /* CP-side state for `status` (filled by the host from the CP or its snapshot) */
    bool cp_configured;            /* valid parameter record applied */
    bool cp_ready;                 /* configured and the FB's INIT accepted */
    modcp_event_t cp_param_event;  /* first fatal parameter event, NONE if configured */
    uint32_t cycles;               /* user program cycles so far */
    /* The CP's status area as the CPU side reads it from the backplane
     * (modcp_bp_read_status); optional: LEDs, RS232 signals, line state and the last
     * diagnostic interrupt record in `status`. */
    const modcp_cp_status_t *cp_status;
} modcp_console_env_t;

enum {
    MODCP_CONSOLE_OK = 0,
    MODCP_CONSOLE_ERROR = -1, /* out holds "error: ..." */
};

/* Recommended size of out for every answer (diag, help, dump) to fit. */
#define MODCP_CONSOLE_OUT_MAX 2048u

/* Execute one command line. Never writes more than cap bytes (answers that do not fit
 * are cut at a line boundary and end with "..."). */
int modcp_console_exec(modcp_console_env_t *env, const char *line, char *out, size_t cap);

/* Name of an FB state (modcp_fbst_t): STOPPED, INIT_SEND, INIT_WAIT, RUN, FAILED. */
const char *modcp_console_fb_state(uint8_t state);

/* "(0E)23H" for an event word; returns the length written. */
size_t modcp_console_event_name(modcp_event_t ev, char *out, size_t cap);

#endif
