/* SPDX-License-Identifier: Apache-2.0 */
/* Fuzz target: the monitor console's command line (firmware/console), as the simulator
 * and a board's second UART feed it, over a controller memory, the FB, a diagnostics
 * snapshot and a CP status area.
 * Input: byte 0 = size of the answer buffer (0: MODCP_CONSOLE_OUT_MAX, else 1..255:
 * truncation), bytes 1..2 = an event word entered into the diagnostics, then command
 * lines separated by '\n' (each executed in turn on the same memory; a NUL ends a line).
 * Invariants: the answer is NUL-terminated inside the buffer (allocated with exactly its
 * size, so ASan sees any write past it); an error answer starts with "error:"; the
 * result is OK or ERROR; an operand that parses has a canonical name that parses back
 * to the same operand, and reading what was written returns it. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp/backplane.h"
#include "modcp/console.h"
#include "modcp/diag.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "diag_internal.h"

#define NDB 4
static const uint16_t db_numbers[NDB] = {1, 80, 800, 65535};

typedef struct {
    modcp_backplane_t bp;
    modcp_fb_t fb;
    modcp_plcmem_t mem;
    modcp_db_t dbs[NDB];
    uint8_t db_data[NDB][300];
    uint8_t i[128], q[128], m[1024];
    uint16_t t[64], c[64];
    modcp_diag_t diag;
    modcp_cp_status_t status;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    bool paused, cp_start;
} cworld_t;

static cworld_t W;

static void die(const char *what)
{
    fprintf(stderr, "fuzz invariant violated: %s\n", what);
    abort();
}

static void check_operand(const char *s)
{
    modcp_s7op_t op, op2;
    memset(&op, 0, sizeof op);
    if (!modcp_s7op_parse(s, &op)) {
        return;
    }
    char name[64];
    size_t n = modcp_s7op_name(&op, name, sizeof name);
    if (n == 0 || n >= sizeof name || strlen(name) != n) {
        die("operand name length");
    }
    memset(&op2, 0, sizeof op2);
    if (!modcp_s7op_parse(name, &op2) || memcmp(&op, &op2, sizeof op) != 0) {
        die("operand name does not parse back to the operand");
    }
    uint32_t v, back;
    if (modcp_s7op_read(&W.mem, &op, &v) == MODCP_EV_NONE) {
        uint32_t w = ~v;
        if (op.width == MODCP_S7_BIT) w &= 1u;
        if (op.width == MODCP_S7_BYTE) w &= 0xFFu;
        if (op.width == MODCP_S7_WORD) w &= 0xFFFFu;
        if (modcp_s7op_write(&W.mem, &op, w) != MODCP_EV_NONE ||
            modcp_s7op_read(&W.mem, &op, &back) != MODCP_EV_NONE || back != w) {
            die("operand reads back other than written");
        }
        (void)modcp_s7op_write(&W.mem, &op, v);
    }
}

static void exec_line(modcp_console_env_t *env, const char *line, size_t cap)
{
    char *out = malloc(cap);
    if (out == NULL) {
        abort();
    }
    memset(out, 0x55, cap);
    int rc = modcp_console_exec(env, line, out, cap);
    if (rc != MODCP_CONSOLE_OK && rc != MODCP_CONSOLE_ERROR) {
        die("result neither OK nor ERROR");
    }
    if (memchr(out, 0, cap) == NULL) {
        die("answer not NUL-terminated inside the buffer");
    }
    if (rc == MODCP_CONSOLE_ERROR && cap >= 16u && strncmp(out, "error:", 6) != 0 &&
        strncmp(out, "error", strlen(out)) != 0) {
        die("error answer does not start with \"error:\"");
    }
    free(out);
    /* the line's first word as an operand */
    char word[64];
    size_t k = 0;
    while (line[k] == ' ' || line[k] == '\t') k++;
    size_t w = 0;
    while (line[k] && line[k] != ' ' && line[k] != '\t' && w + 1 < sizeof word) word[w++] = line[k++];
    word[w] = '\0';
    check_operand(word);
    check_operand(line);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 3) {
        return 0;
    }
    size_t cap = data[0] ? data[0] : MODCP_CONSOLE_OUT_MAX;
    modcp_event_t ev = (modcp_event_t)(data[1] | data[2] << 8);
    data += 3;
    size -= 3;

    memset(&W, 0, sizeof W);
    for (unsigned k = 0; k < NDB; k++) {
        W.dbs[k] = (modcp_db_t){db_numbers[k], (uint16_t)(k == 0 ? 0 : 100 * k), W.db_data[k]};
    }
    W.mem = (modcp_plcmem_t){.i = W.i, .q = W.q, .m = W.m, .t = W.t, .c = W.c,
                             .i_size = sizeof W.i, .q_size = sizeof W.q, .m_size = sizeof W.m,
                             .t_count = 64, .c_count = 64, .dbs = W.dbs, .db_count = NDB};
    for (unsigned k = 0; k < sizeof W.m; k++) W.m[k] = (uint8_t)(k * 7u);
    modcp_params_t p;
    modcp_params_defaults(&p);
    size_t rlen = modcp_params_encode(&p, W.record, sizeof W.record);
    modcp_bp_init(&W.bp);
    modcp_fb_init(&W.fb, &W.bp, &W.mem, W.record, (uint16_t)rlen, 80, 5000);
    modcp_diag_init(&W.diag);
    modcp_diag_event(&W.diag, ev);
    modcp_diag_event(&W.diag, MODCP_EV_PARAM_RECORD);
    W.status.systat[0] = (uint8_t)ev;

    char name[32];
    size_t n = modcp_console_event_name(ev, name, sizeof name);
    if (n >= sizeof name || strlen(name) != n) {
        die("event name length");
    }
    if (modcp_console_fb_state((uint8_t)ev) == NULL) {
        die("FB state without a name");
    }

    modcp_console_env_t env = {
        .mem = &W.mem, .diag = &W.diag, .fb = &W.fb, .paused = &W.paused,
        .cp_start = &W.cp_start, .cp_configured = (ev & 1u) != 0, .cp_ready = (ev & 2u) != 0,
        .cp_param_event = ev, .cycles = ev, .cp_status = (ev & 4u) ? &W.status : NULL,
    };
    char line[512];
    size_t len = 0;
    for (size_t k = 0; k <= size; k++) {
        if (k == size || data[k] == '\n' || data[k] == 0) {
            line[len] = '\0';
            exec_line(&env, line, cap);
            len = 0;
        } else if (len + 1 < sizeof line) {
            line[len++] = (char)data[k];
        }
    }
    return 0;
}
