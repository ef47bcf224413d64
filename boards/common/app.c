/* SPDX-License-Identifier: Apache-2.0 */
/* modcp boards — the application every board runs.
 *
 *   CP side   UART / timer interrupts of the board's HAL call modcp_cp_on_*(); the CP
 *             task (PendSV, requested by the main loop and by the 1 ms tick) calls
 *             modcp_cp_poll(). All of them run at PRIO_CP, so they never preempt each
 *             other.
 *   CPU side  the main loop is the cyclic user program: modcp_fb_call() once per cycle
 *             ([cpu] cycle_ms; 0 = at every wake-up, i.e. at least every 1 ms tick
 *             and again at once whenever a block moved), then the monitor console
 *             on the second UART, then sleep until the next interrupt.
 * The two sides share only the backplane (lock-free rings). The parameter record and
 * the controller memory come from the generated configuration (modcp/cfg_gen.h). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "board/board.h"
#include "board/cortexm.h"
#include "modcp/backplane.h"
#include "modcp/cfg_gen.h"
#include "modcp/console.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/version.h"

#define LINE_MAX 128u

static modcp_backplane_t bp;
static modcp_cp_t cp;
static modcp_fb_t fb;
static modcp_params_t line_params; /* the record as the board reads it: line settings */

/* user program state */
static bool paused;
static bool cp_start = true; /* the FB's CP_START input: rising edge at the first call */
static uint32_t cycles;
static modcp_fb_out_t fb_out;

/* console state */
static char con_line[LINE_MAX];
static size_t con_len;
static bool con_last_cr;
static char con_out[MODCP_CONSOLE_OUT_MAX];
static modcp_diag_t diag_copy;

static volatile bool cp_started; /* modcp_cp_init() done: the CP task may run */

void app_cp_task(void)
{
    if (cp_started) {
        modcp_cp_poll(&cp, board_now_us());
    }
}

static void con_puts(const char *s)
{
    board_console_write(s, strlen(s));
}

/* Write text with '\n' line ends as "\r\n" for a terminal. */
static void con_put_text(const char *s)
{
    const char *start = s;
    for (; *s != '\0'; s++) {
        if (*s == '\n') {
            board_console_write(start, (size_t)(s - start));
            board_console_write("\r\n", 2u);
            start = s + 1;
        }
    }
    board_console_write(start, (size_t)(s - start));
}

static void put_u32(uint32_t v)
{
    char buf[11];
    size_t i = sizeof buf;
    buf[--i] = '\0';
    do {
        buf[--i] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v != 0u && i > 0u);
    con_puts(&buf[i]);
}

static void board_command(void)
{
    con_puts("board ");
    con_puts(board_name());
    con_puts("\r\nversion " MODCP_VERSION "\r\nconfig "); /* modcp/version.h, as the banner */
    con_puts(modcp_cfg_name);
    con_puts(", slave ");
    put_u32(modcp_cfg_slave_addr);
    con_puts(", ");
    put_u32(line_params.baud);
    con_puts(" baud\r\nuptime_ms ");
    put_u32(board_now_ms());
    con_puts("\r\ncycles ");
    put_u32(cycles);
    con_puts("\r\n");
}

static void execute_line(void)
{
    con_line[con_len] = '\0';
    if (strcmp(con_line, "board") == 0) {
        board_command();
    } else {
        modcp_console_env_t env = {0};
        /* A consistent copy of the CP's state: mask the CP's interrupts for the copy. */
        cm_set_basepri(PRIO_CP);
        diag_copy = cp.diag;
        env.cp_configured = cp.configured;
        env.cp_ready = modcp_cp_ready(&cp);
        env.cp_param_event = cp.param_event;
        cm_set_basepri(0u);
        env.mem = &modcp_cfg_mem;
        env.diag = &diag_copy;
        env.fb = &fb;
        env.paused = &paused;
        env.cp_start = &cp_start;
        env.cycles = cycles;
        modcp_cp_status_t cst; /* the CP's status area, read from the backplane */
        for (int k = 0; k < 100; k++) {
            if (modcp_bp_read_status(&bp, &cst)) {
                env.cp_status = &cst;
                break;
            }
        }
        con_out[0] = '\0';
        (void)modcp_console_exec(&env, con_line, con_out, sizeof con_out);
        if (con_out[0] != '\0') {
            con_put_text(con_out);
            con_puts("\r\n");
        }
        if (strcmp(con_line, "help") == 0 || strcmp(con_line, "?") == 0) {
            con_puts("  board               this board, its configuration, uptime, cycles\r\n");
        }
    }
    con_puts("> ");
    con_len = 0u;
}

/* Line editing: echo, backspace, CR / LF / CR LF end a line. */
static bool console_poll(void)
{
    bool any = false;
    int c;
    while ((c = board_console_getc()) >= 0) {
        any = true;
        if (c == '\n' && con_last_cr) {
            con_last_cr = false;
            continue;
        }
        con_last_cr = c == '\r';
        if (c == '\r' || c == '\n') {
            con_puts("\r\n");
            execute_line();
        } else if (c == 0x7F || c == 0x08) {
            if (con_len > 0u) {
                con_len--;
                con_puts("\b \b");
            }
        } else if (c >= 0x20 && c < 0x7F && con_len + 1u < LINE_MAX) {
            char ch = (char)c;
            con_line[con_len++] = ch;
            board_console_write(&ch, 1u);
        }
    }
    return any;
}

/* Sum of the backplane's producer / consumer counters: changes whenever a block moves. */
static uint32_t bp_signature(void)
{
    return atomic_load(&bp.to_cpu.head) + atomic_load(&bp.to_cpu.tail) +
           atomic_load(&bp.to_cp.head) + atomic_load(&bp.to_cp.tail);
}

int main(void)
{
    board_init();
    con_puts("\r\nmodcp " MODCP_VERSION " "); /* modcp/version.h */
    con_puts(board_name());
    con_puts("\r\n");

    modcp_params_defaults(&line_params);
    if (modcp_params_decode(modcp_cfg_record, modcp_cfg_record_len, &line_params) !=
        MODCP_EV_NONE) {
        con_puts("parameter record unreadable: the CP stays not ready\r\n");
        modcp_params_defaults(&line_params);
    }

    modcp_bp_init(&bp);
    modcp_cp_init(&cp, board_modbus_hal(), &bp);
    modcp_fb_init(&fb, &bp, &modcp_cfg_mem, modcp_cfg_record, modcp_cfg_record_len,
                  modcp_cfg_work_db, modcp_cfg_start_time_ms);
    board_modbus_start(&cp, &line_params);
    cp_started = true;
    cm_enable_irqs();

    board_command();
    con_puts("> ");

    uint32_t last_cycle_ms = board_now_ms();
    for (;;) {
        uint32_t now_ms = board_now_ms();
        bool ran = false;
        uint32_t seen = 0u;
        if (!paused && (modcp_cfg_cycle_ms == 0u || now_ms - last_cycle_ms >= modcp_cfg_cycle_ms)) {
            modcp_fb_in_t in = {.cp_start = cp_start};
            last_cycle_ms = now_ms;
            modcp_fb_call(&fb, &in, &fb_out, now_ms);
            cp_start = in.cp_start; /* CP_START is in/out: a failed init resets it */
            cycles++;
            ran = true;
            seen = bp_signature();   /* the rings as the FB left them */
            board_cp_task_request(); /* the CP picks up what the FB produced, now */
        }
        bool typed = console_poll();

        /* Sleep until the next interrupt (at the latest the 1 ms tick) unless, with the
         * cycle free-running, a block moved after the FB looked: then the FB runs again
         * at once. Interrupts are masked between the test and WFI, so no wake-up is lost. */
        cm_disable_irqs();
        bool work = ran && modcp_cfg_cycle_ms == 0u && bp_signature() != seen;
        if (!typed && !work) {
            cm_wfi();
        }
        cm_enable_irqs();
    }
}
