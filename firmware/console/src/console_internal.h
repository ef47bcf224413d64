/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the monitor console's internals, shared by its files (not a public header).
 *
 *   console.c       one command line: tokenizer, dispatch, help, pause / resume, start
 *   console_out.c   the answer buffer (cut at a line boundary when full, "error: ..."),
 *                   and the number / word scanning every command uses
 *   s7op.c          S7 operands: parse, name, read / write through plcmem (public API)
 *   console_mem.c   get / set / dump: value formats (hex, signed, float), operand errors
 *   console_diag.c  diag / status, FB state and event names (public API) */
#ifndef MODCP_CONSOLE_INTERNAL_H
#define MODCP_CONSOLE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/console.h"

#define MAX_TOKENS 8u

/* The answer being built in the caller's buffer. */
typedef struct {
    char *buf;
    size_t cap;
    size_t len;
    bool overflow;
} out_t;

/* One command line split into words. */
typedef struct {
    char *tok[MAX_TOKENS];
    size_t n;
    const char *rest; /* text after the first token (for echo) */
} args_t;

/* ---- answer buffer (console_out.c) ---- */
void con_out_init(out_t *o, char *buf, size_t cap);
/* Append; on overflow nothing more is added and con_finish() marks the cut. */
void con_printf(out_t *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Start a new line (a '\n' separator unless the output is empty). */
void con_nl(out_t *o);
/* Cut an overflowed answer at a line boundary and end it with "...". */
void con_finish(out_t *o);
/* Replace the answer with one line "error: ..."; returns MODCP_CONSOLE_ERROR. */
int con_fail(out_t *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* ---- scanning (console_out.c) ---- */
static inline char up(char c)
{
    return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c;
}

static inline bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* Case-insensitive equality. */
bool con_ieq(const char *a, const char *b);
/* Decimal number 0..65535 at *s; advances *s. */
bool con_parse_u16(const char **s, uint16_t *v);
/* An integer for a field of `bits` bits: decimal, 0x.., 16#.., negative as two's
 * complement. */
bool con_parse_int(const char *s, unsigned bits, uint32_t *out);
/* 1 / true / on, 0 / false / off. */
bool con_parse_bool(const char *s, uint32_t *out);

/* ---- commands (console_mem.c, console_diag.c) ---- */
int con_cmd_get(modcp_console_env_t *env, const args_t *a, out_t *o);
int con_cmd_set(modcp_console_env_t *env, const args_t *a, out_t *o);
int con_cmd_dump(modcp_console_env_t *env, const args_t *a, out_t *o);
int con_cmd_diag(modcp_console_env_t *env, out_t *o);
int con_cmd_status(modcp_console_env_t *env, out_t *o);

#endif
