/* SPDX-License-Identifier: Apache-2.0 */
/* cmocka: the monitor console (firmware/console) — operands in S7 notation, exact
 * answers, errors as one line, truncation, and garbage that must never crash. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "modcp/console.h"
#include "modcp/hal.h"
#include "modcp/signals.h"
#include "modcp/version.h"
#include "diag_internal.h"

typedef struct {
    uint8_t i[16], q[16], m[32];
    uint16_t t[8], c[8];
    uint8_t db5[8], db800[16];
    modcp_db_t dbs[2];
    modcp_plcmem_t mem;
    modcp_diag_t diag;
    modcp_fb_t fb;
    bool paused, cp_start;
    modcp_console_env_t env;
    char out[MODCP_CONSOLE_OUT_MAX];
} fx_t;

static int setup(void **state)
{
    fx_t *f = calloc(1, sizeof *f);
    f->dbs[0] = (modcp_db_t){5, sizeof f->db5, f->db5};
    f->dbs[1] = (modcp_db_t){800, sizeof f->db800, f->db800};
    f->mem = (modcp_plcmem_t){f->i, f->q, f->m, f->t, f->c, sizeof f->i, sizeof f->q, sizeof f->m,
                              8, 8, f->dbs, 2};
    f->env.mem = &f->mem;
    f->env.diag = &f->diag;
    f->env.fb = &f->fb;
    f->env.paused = &f->paused;
    f->env.cp_start = &f->cp_start;
    f->m[8] = 0x01;
    f->m[9] = 0x17;
    f->m[10] = 0x02;
    f->m[11] = 0x18;
    f->t[1] = 0x1234;
    f->db800[0] = 0x87;
    f->db800[1] = 0x65;
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    free(*state);
    return 0;
}

static const char *run(fx_t *f, const char *line, int expect_rc)
{
    int rc = modcp_console_exec(&f->env, line, f->out, sizeof f->out);
    if (rc != expect_rc) {
        print_error("'%s' -> rc %d, '%s'\n", line, rc, f->out);
    }
    assert_int_equal(rc, expect_rc);
    return f->out;
}

static void ok_line(fx_t *f, const char *line, const char *answer)
{
    assert_string_equal(run(f, line, MODCP_CONSOLE_OK), answer);
}

static void err_line(fx_t *f, const char *line, const char *answer)
{
    assert_string_equal(run(f, line, MODCP_CONSOLE_ERROR), answer);
}

static void test_get_set_bytes(void **state)
{
    fx_t *f = *state;
    ok_line(f, "get MB8", "MB8 = 0x01 (1)");
    ok_line(f, "get mw8", "MW8 = 0x0117 (279)");
    ok_line(f, "GET MD8", "MD8 = 0x01170218 (18285080)");
    ok_line(f, "get M9.0", "M9.0 = 1");
    ok_line(f, "get M9.3", "M9.3 = 0");
    ok_line(f, "set M9.3 1", "M9.3 = 1");
    assert_int_equal(f->m[9], 0x1F);
    ok_line(f, "set M9.0 off", "M9.0 = 0");
    assert_int_equal(f->m[9], 0x1E);
    ok_line(f, "set IB12 0x5A", "IB12 = 0x5A (90)");
    assert_int_equal(f->i[12], 0x5A);
    ok_line(f, "set QW2 16#BEEF", "QW2 = 0xBEEF (48879)");
    assert_int_equal(f->q[2], 0xBE);
    assert_int_equal(f->q[3], 0xEF);
    ok_line(f, "set MW20 -2", "MW20 = 0xFFFE (65534)");
    ok_line(f, "set MD20 -1", "MD20 = 0xFFFFFFFF (-1)");
    ok_line(f, "set MD20 0x80000000", "MD20 = 0x80000000 (-2147483648)");
    ok_line(f, "get I0.1", "I0.1 = 0");
    ok_line(f, "get Q3.7", "Q3.7 = 1");
    ok_line(f, "set MB0 255", "MB0 = 0xFF (255)");
    ok_line(f, "set MB0 -128", "MB0 = 0x80 (128)");
}

static void test_db_and_float(void **state)
{
    fx_t *f = *state;
    ok_line(f, "get DB800.DBW0", "DB800.DBW0 = 0x8765 (34661)");
    ok_line(f, "get DB800.DBB1", "DB800.DBB1 = 0x65 (101)");
    ok_line(f, "get DB800.DBX0.7", "DB800.DBX0.7 = 1");
    ok_line(f, "set DB800.DBX0.7 0", "DB800.DBX0.7 = 0");
    assert_int_equal(f->db800[0], 0x07);
    ok_line(f, "set DB800.DBD4 1.5", "DB800.DBD4 = 1.5 (0x3FC00000)");
    assert_memory_equal(&f->db800[4], "\x3F\xC0\x00\x00", 4);
    ok_line(f, "get DB800.DBD4", "DB800.DBD4 = 0x3FC00000 (1069547520)");
    ok_line(f, "get DB800.DBD4 float", "DB800.DBD4 = 1.5 (0x3FC00000)");
    ok_line(f, "set DB800.DBD8 -0.1", "DB800.DBD8 = -0.1 (0xBDCCCCCD)");
    ok_line(f, "set DB800.DBD8 3 float", "DB800.DBD8 = 3 (0x40400000)");
    ok_line(f, "set DB5.DBW6 4660", "DB5.DBW6 = 0x1234 (4660)");
    err_line(f, "get DB800.DBW15", "error: DB800.DBW15: outside DB800 (16 bytes)");
    err_line(f, "get DB801.DBW0", "error: DB801.DBW0: DB801 does not exist");
    err_line(f, "get DB800.DBW0 float", "error: 'float': only a D operand can be shown as float");
    err_line(f, "set DB800.DBW0 1.5", "error: bad value '1.5': floats need a D operand");
}

static void test_timers_counters(void **state)
{
    fx_t *f = *state;
    ok_line(f, "get T1", "T1 = 0x1234 (4660)");
    ok_line(f, "set T1 0x4321", "T1 = 0x4321 (17185)");
    assert_int_equal(f->t[1], 0x4321);
    ok_line(f, "set C7 65535", "C7 = 0xFFFF (65535)");
    err_line(f, "get T8", "error: T8: outside T (8 timers)");
    err_line(f, "get C200", "error: C200: outside C (8 counters)");
    err_line(f, "set T1 65536", "error: bad value '65536' for a 16-bit operand");
}

static void test_dump_lines(void **state)
{
    fx_t *f = *state;
    ok_line(f, "dump DB800 0 16", "DB800.DBB0: 87 65 00 00 00 00 00 00 00 00 00 00 00 00 00 00");
    ok_line(f, "dump M 0 20",
            "MB0: 00 00 00 00 00 00 00 00 01 17 02 18 00 00 00 00\nMB16: 00 00 00 00");
    ok_line(f, "dump T 0 3", "T0: 0000 1234 0000");
    err_line(f, "dump DB800 0 17", "error: DB800: 0..16 outside the DB (16 bytes)");
    err_line(f, "dump X 0 1", "error: bad area 'X' (M, I, Q, T, C or DBn)");
    err_line(f, "dump M 0 300", "error: length 300 too large (at most 256)");
}

static void test_errors(void **state)
{
    fx_t *f = *state;
    err_line(f, "frobnicate", "error: unknown command 'frobnicate' (try help)");
    err_line(f, "get", "error: usage: get OPERAND [float]");
    err_line(f, "get MX1", "error: bad operand 'MX1' (e.g. MB1000, M1000.3, DB800.DBW0, T100)");
    err_line(f, "get M1.8", "error: bad operand 'M1.8' (e.g. MB1000, M1000.3, DB800.DBW0, T100)");
    err_line(f, "get MB70000", "error: bad operand 'MB70000' (e.g. MB1000, M1000.3, DB800.DBW0, T100)");
    err_line(f, "get DB0.DBW0", "error: bad operand 'DB0.DBW0' (e.g. MB1000, M1000.3, DB800.DBW0, T100)");
    err_line(f, "get MB32", "error: MB32: outside M (32 bytes)");
    err_line(f, "get MD30", "error: MD30: outside M (32 bytes)");
    err_line(f, "set MB0 256", "error: bad value '256' for a 8-bit operand");
    err_line(f, "set MB0 -129", "error: bad value '-129' for a 8-bit operand");
    err_line(f, "set M0.0 2", "error: bad value '2' for a bit (0 or 1)");
    err_line(f, "set MB0 zz", "error: bad value 'zz' for a 8-bit operand");
    err_line(f, "set MB0", "error: usage: set OPERAND VALUE [float]");
    err_line(f, "a b c d e f g h i", "error: too many arguments");
    ok_line(f, "", "");
    ok_line(f, "   ", "");
    ok_line(f, "# a comment", "");
    ok_line(f, "echo hello  world", "hello  world");
}

static void test_diag_status_pause(void **state)
{
    fx_t *f = *state;
    ok_line(f, "diag", "diag: 0 events (newest first), total 0, STATUS 0x0000, SYSTAT -");
    modcp_diag_event(&f->diag, MODCP_EV_CRC);
    modcp_diag_event(&f->diag, MODCP_EV_XFER_TIMEOUT);
    const char *d = run(f, "diag", MODCP_CONSOLE_OK);
    char want[512];
    snprintf(want, sizeof want,
             "diag: 2 events (newest first), total 2, STATUS 0x0E31, SYSTAT F\n"
             "event 1: (0E)31H class 0EH driver processing error, number 31H: %s. Remedy: %s\n"
             "event 2: (08)36H class 08H receive error, number 36H: %s. Remedy: %s",
             modcp_event_text(MODCP_EV_XFER_TIMEOUT), modcp_event_remedy(MODCP_EV_XFER_TIMEOUT),
             modcp_event_text(MODCP_EV_CRC), modcp_event_remedy(MODCP_EV_CRC));
    assert_string_equal(d, want);

    f->fb.state = MODCP_FBST_RUN;
    f->fb.out.cp_start_ok = true;
    f->fb.jobs_done = 7;
    f->env.cp_configured = true;
    f->env.cp_ready = true;
    f->env.cycles = 42;
    f->diag.counters[MODCP_CNT_BUS_CRC] = 3;
    const char *s = run(f, "status", MODCP_CONSOLE_OK);
    assert_non_null(strstr(s, "status: fb=RUN cp_start_ok=1 cp_start_error=0 cp_start_ndr=0 "
                              "error_nr=0 error_info=0x0000 jobs=7 paused=0 cycles=42 cp=ready "
                              "param_event=none bus_msg=0 bus_crc=3 "));
    assert_null(strchr(s, '\n'));

    ok_line(f, "pause", "user program paused");
    assert_true(f->paused);
    assert_non_null(strstr(run(f, "status", MODCP_CONSOLE_OK), " paused=1 "));
    ok_line(f, "resume", "user program running");
    assert_false(f->paused);
    ok_line(f, "start 0", "CP_START = 0");
    assert_false(f->cp_start);
    ok_line(f, "start 1", "CP_START = 1");
    assert_true(f->cp_start);

    f->env.cp_ready = false;
    f->env.cp_configured = false;
    f->env.cp_param_event = MODCP_EV_SLAVE_ADDR;
    assert_non_null(strstr(run(f, "status", MODCP_CONSOLE_OK), " cp=not-configured param_event=(0E)23H "));
}

/* The CP's status area (read from the backplane): LEDs, RS232 signals, line state and
 * the last diagnostic interrupt record, in words (issue 7). */
static void test_status_line_area(void **state)
{
    fx_t *f = *state;
    modcp_cp_status_t st;
    memset(&st, 0, sizeof st);
    f->env.cp_status = &st;
    assert_non_null(strstr(run(f, "status", MODCP_CONSOLE_OK),
                           " leds=off signals=off line=ok signal_aborts=0 diag_irq=none"));
    st.leds = (uint8_t)((1u << MODCP_LED_SF) | (1u << MODCP_LED_RXD));
    st.signals = MODCP_SIGBIT_RTS | MODCP_SIGBIT_DTR | MODCP_SIGBIT_DSR | MODCP_SIGBIT_AUTO;
    st.flags = MODCP_CPST_WIRE_BREAK;
    st.signal_aborts = 2;
    memcpy(st.diag_irq, "\x25\x0C\x02\x00", 4);
    st.diag_irq_count = 1;
    assert_non_null(strstr(run(f, "status", MODCP_CONSOLE_OK),
                           " leds=SF,RXD signals=RTS,DTR,DSR(auto) line=wire-break signal_aborts=2"
                           " diag_irq=25.0C.02.00(#1)"));
}

static void test_missing_env(void **state)
{
    (void)state;
    modcp_console_env_t env;
    char out[128];
    memset(&env, 0, sizeof env);
    assert_int_equal(modcp_console_exec(&env, "get MB0", out, sizeof out), MODCP_CONSOLE_ERROR);
    assert_string_equal(out, "error: controller memory not available");
    assert_int_equal(modcp_console_exec(&env, "diag", out, sizeof out), MODCP_CONSOLE_ERROR);
    assert_string_equal(out, "error: diagnostics not available");
    assert_int_equal(modcp_console_exec(&env, "pause", out, sizeof out), MODCP_CONSOLE_ERROR);
    assert_string_equal(out, "error: pause/resume not available");
    assert_int_equal(modcp_console_exec(&env, "status", out, sizeof out), MODCP_CONSOLE_OK);
    assert_string_equal(out, "status: cycles=0 cp=not-configured param_event=none version=" MODCP_VERSION);
}

static void test_truncation(void **state)
{
    fx_t *f = *state;
    char small[40];
    memset(small, 'x', sizeof small);
    int rc = modcp_console_exec(&f->env, "help", small, sizeof small);
    assert_int_equal(rc, MODCP_CONSOLE_OK);
    assert_true(strlen(small) < sizeof small);
    assert_non_null(strstr(small, "..."));
    rc = modcp_console_exec(&f->env, "frobnicate-with-a-long-name-that-does-not-fit", small, 20);
    assert_int_equal(rc, MODCP_CONSOLE_ERROR);
    assert_true(strlen(small) < 20);
    assert_int_equal(modcp_console_exec(&f->env, "help", small, 0), MODCP_CONSOLE_OK);
    char line[400];
    memset(line, 'a', sizeof line - 1);
    line[sizeof line - 1] = '\0';
    err_line(f, line, "error: line too long (at most 255 characters)");
}

static void test_operand_parse_name(void **state)
{
    (void)state;
    static const char *const good[] = {"MB0", "MW65534", "MD4", "M1000.3", "IB128", "I0.1", "QB256",
                                       "Q7.7", "IW2", "QD8", "T100", "C200", "DB800.DBB0",
                                       "DB800.DBW160", "DB1.DBD4", "DB65535.DBX65535.7"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        modcp_s7op_t op;
        char name[40];
        assert_true(modcp_s7op_parse(good[i], &op));
        modcp_s7op_name(&op, name, sizeof name);
        assert_string_equal(name, good[i]);
    }
    static const char *const bad[] = {"", "M", "MB", "MX1", "M1", "M1.", "M1.9", "MB1.0", "DB1",
                                      "DB1.DBW", "DB1.W2", "DB1.DBX2", "DB70000.DBW0", "T", "T1.0",
                                      "Z1", "MB 1", "MB1x", "IB-1", "E1.0", "DB1.DBW2.3"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        modcp_s7op_t op;
        if (modcp_s7op_parse(bad[i], &op)) {
            print_error("'%s' parsed\n", bad[i]);
        }
        assert_false(modcp_s7op_parse(bad[i], &op));
    }
}

static void test_garbage_never_crashes(void **state)
{
    fx_t *f = *state;
    static const char alphabet[] = "getsdumpMBWDXIQTC.0123456789 xX-#float\t\n";
    srand(1234);
    char line[64];
    for (int n = 0; n < 20000; n++) {
        size_t len = (size_t)(rand() % 40);
        for (size_t i = 0; i < len; i++) {
            line[i] = alphabet[rand() % (int)(sizeof alphabet - 1)];
        }
        line[len] = '\0';
        size_t cap = (size_t)(rand() % 3 == 0 ? rand() % 24 : (int)sizeof f->out);
        f->out[0] = '\0';
        int rc = modcp_console_exec(&f->env, line, f->out, cap);
        assert_true(rc == MODCP_CONSOLE_OK || rc == MODCP_CONSOLE_ERROR);
        if (cap > 0) {
            assert_true(strlen(f->out) < cap);
        }
        if (rc == MODCP_CONSOLE_ERROR && cap > 8) {
            assert_memory_equal(f->out, "error: ", strlen(f->out) < 7 ? strlen(f->out) : 7);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_get_set_bytes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_db_and_float, setup, teardown),
        cmocka_unit_test_setup_teardown(test_timers_counters, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dump_lines, setup, teardown),
        cmocka_unit_test_setup_teardown(test_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_diag_status_pause, setup, teardown),
        cmocka_unit_test_setup_teardown(test_status_line_area, setup, teardown),
        cmocka_unit_test(test_missing_env),
        cmocka_unit_test_setup_teardown(test_truncation, setup, teardown),
        cmocka_unit_test(test_operand_parse_name),
        cmocka_unit_test_setup_teardown(test_garbage_never_crashes, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
