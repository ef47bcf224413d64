/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console (S7 notation): one command line. Portable C11: no OS, no heap,
 * no globals.
 *
 * The console is split by responsibility (console_internal.h lists the files); this
 * one takes a line apart and runs the command. Decisions on formats and limits are
 * documented in docs/simulator.md and console_mem.c. */
#include "console_internal.h"

#include <stdio.h>
#include <string.h>

#define LINE_MAX_CHARS 256u

static const char *const help_lines[] = {
    "commands (operands in S7 notation, numbers decimal, 0x.. or 16#..):",
    "  get OP [float]      OP: MB1000 MW MD M1000.3 IB128 I0.1 QB256 Q.. T100 C200",
    "                      DB800.DBB0 DBW0 DBD4 DBX0.1; float: show a D operand as float",
    "  set OP VALUE        e.g. set IB128 0x5A, set M1000.3 1, set DB800.DBD4 1.5",
    "  dump AREA [START [LEN]]  hex dump, AREA = M I Q T C DBn (e.g. dump DB800 0 32)",
    "  diag                diagnostic buffer: events in words, newest first",
    "  status              FB init state and outputs, CP state, serial-line counters",
    "  pause | resume      stop / restart the cyclic user program (FB calls)",
    "  start 0|1           set the FB's CP_START input (a rising edge re-initialises)",
    "  commloss reset      reset a latched comm loss (the CPU side's fault reset)",
    "  echo TEXT           print TEXT",
    "  help                this text",
};

static int cmd_help(out_t *o)
{
    for (size_t i = 0; i < sizeof help_lines / sizeof help_lines[0]; i++) {
        con_nl(o);
        con_printf(o, "%s", help_lines[i]);
    }
    return MODCP_CONSOLE_OK;
}

static int cmd_pause(modcp_console_env_t *env, bool pause, out_t *o)
{
    if (env->paused == NULL) {
        return con_fail(o, "pause/resume not available");
    }
    *env->paused = pause;
    con_printf(o, "user program %s", pause ? "paused" : "running");
    return MODCP_CONSOLE_OK;
}

static int cmd_start(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    uint32_t v = 0;
    if (env->cp_start == NULL) {
        return con_fail(o, "CP_START not available");
    }
    if (a->n != 2u || !con_parse_bool(a->tok[1], &v)) {
        return con_fail(o, "usage: start 0|1");
    }
    *env->cp_start = v != 0u;
    con_printf(o, "CP_START = %u", (unsigned)v);
    return MODCP_CONSOLE_OK;
}

static int cmd_commloss(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    if (env->bp == NULL) {
        return con_fail(o, "commloss reset not available");
    }
    if (a->n != 2u || !con_ieq(a->tok[1], "reset")) {
        return con_fail(o, "usage: commloss reset");
    }
    modcp_bp_commloss_reset(env->bp); /* the CP clears a latched loss at its next poll */
    con_printf(o, "comm loss reset");
    return MODCP_CONSOLE_OK;
}

/* Split buf (a copy of line) into a->tok in place; a->rest: line from the second token
 * on (echo prints it as typed). False when there are too many arguments. */
static bool tokenize(char *buf, const char *line, args_t *a)
{
    a->n = 0;
    a->rest = "";
    char *p = buf;
    while (*p != '\0') {
        while (*p == ' ' || *p == '\t') {
            p++;
        }
        if (*p == '\0') {
            break;
        }
        if (a->n == 1u) {
            a->rest = line + (p - buf);
        }
        if (a->n == MAX_TOKENS) {
            return con_ieq(a->tok[0], "echo");
        }
        a->tok[a->n++] = p;
        while (*p != '\0' && *p != ' ' && *p != '\t') {
            p++;
        }
        if (*p != '\0') {
            *p++ = '\0';
        }
    }
    return true;
}

static int cmd_echo(const args_t *a, out_t *o)
{
    size_t rl = strlen(a->rest);
    while (rl > 0u && (a->rest[rl - 1u] == '\n' || a->rest[rl - 1u] == '\r')) {
        rl--;
    }
    con_printf(o, "%.*s", (int)rl, a->rest);
    return MODCP_CONSOLE_OK;
}

static int dispatch(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    const char *c = a->tok[0];
    if (con_ieq(c, "get")) {
        return con_cmd_get(env, a, o);
    }
    if (con_ieq(c, "set")) {
        return con_cmd_set(env, a, o);
    }
    if (con_ieq(c, "dump")) {
        return con_cmd_dump(env, a, o);
    }
    if (con_ieq(c, "diag")) {
        return a->n == 1u ? con_cmd_diag(env, o) : con_fail(o, "usage: diag");
    }
    if (con_ieq(c, "status")) {
        return a->n == 1u ? con_cmd_status(env, o) : con_fail(o, "usage: status");
    }
    if (con_ieq(c, "pause") || con_ieq(c, "resume")) {
        return a->n == 1u ? cmd_pause(env, con_ieq(c, "pause"), o) : con_fail(o, "usage: %s", c);
    }
    if (con_ieq(c, "start")) {
        return cmd_start(env, a, o);
    }
    if (con_ieq(c, "commloss")) {
        return cmd_commloss(env, a, o);
    }
    if (con_ieq(c, "echo")) {
        return cmd_echo(a, o);
    }
    if (con_ieq(c, "help") || con_ieq(c, "?")) {
        return cmd_help(o);
    }
    char name[40];
    (void)snprintf(name, sizeof name, "%s", c);
    return con_fail(o, "unknown command '%s' (try help)", name);
}

int modcp_console_exec(modcp_console_env_t *env, const char *line, char *out, size_t cap)
{
    out_t o;
    char buf[LINE_MAX_CHARS];
    args_t a;
    con_out_init(&o, out, cap);
    if (line == NULL || env == NULL) {
        return con_fail(&o, "no command");
    }
    size_t len = strlen(line);
    while (len > 0u && (line[len - 1u] == '\n' || line[len - 1u] == '\r')) {
        len--;
    }
    if (len >= sizeof buf) {
        return con_fail(&o, "line too long (at most %u characters)", (unsigned)(sizeof buf - 1u));
    }
    memcpy(buf, line, len);
    buf[len] = '\0';
    if (!tokenize(buf, line, &a)) {
        return con_fail(&o, "too many arguments");
    }
    if (a.n == 0u || a.tok[0][0] == '#' || a.tok[0][0] == ';') {
        return MODCP_CONSOLE_OK; /* blank line or comment */
    }
    int rc = dispatch(env, &a, &o);
    if (rc == MODCP_CONSOLE_OK) {
        con_finish(&o);
    }
    return rc;
}
