/* SPDX-License-Identifier: Apache-2.0 */
/* diff_transcript — what one core does with seeded random input, one line per fact a
 * port or the CPU side can observe, so that tools/diffcore can compare two cores (the
 * working tree's and another commit's) line by line. Only the public API is used
 * (modcp/cp.h, fb.h, backplane.h, params.h, plcmem.h, crc.h, hal.h), plus the core's
 * parameter validation through tests/fuzz/fuzz_cfg.c, so that it builds against both.
 *
 *   diff_transcript [--seed S] [--inputs N] [--first K]
 *
 * Input k (K <= k < K + N) depends only on (S, k): a parameter set and controller
 * memory built field by field from 48 random bytes (fuzz_cfg.c: framing, baud, modem
 * mode, RS485 / RS232 signals, t1.5, windows, limits, 32-bit ranges, function set,
 * job limit, timeouts, DB sizes that make jobs fail), a CPU cycle time, then steps:
 * requests (requests.c) character by character or as blocks, with gaps at and around
 * t1.5, t3.5 and the ASCII timeout inside them and after them, corrupted frames, noise,
 * line errors, a stalled CPU side (jobs time out), a stalled CP task, CP_START dropped
 * (the FB initialises the CP again), CTS / DSR changes, SYSTAT requests, comm-loss resets,
 * long silences, a late transmission complete. The CPU side runs one FB call and one
 * CP poll per cycle throughout, the timer fires when it is due, the transmission
 * completes len characters after uart_tx.
 *
 * Every line is "<us since the input started> <fact>":
 *   cfg / set     the input's parameter bytes, the set the core accepted (its record's
 *                 CRC), whether the CP became ready
 *   rx ...        what the line carried (input, the same for both cores)
 *   tx HEX        a reply frame;  arm US  a timer arm;  de / led / sig / rx-preset /
 *                 tx-abort  the HAL outputs (levels when they change)
 *   ev +N E...    new events (events_total grew by N; the newest, oldest first)
 *   st ...        the status area when it changed: flags, LEDs, signals, the serial-line
 *                 and error counters, STATUS word, parameter event, diagnostic
 *                 interrupt, SYSTAT answer
 *   fb ...        the FB's outputs when they changed;  mem H  the controller memory's hash
 *                 when it changed (after a write job, after each step, at the end) */
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_cfg.h"
#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "transcript.h"

#define NDB 5
static const uint16_t db_numbers[NDB] = {80, 700, 800, 801, 900}; /* fuzz_cfg.c's world */

typedef struct {
    modcp_backplane_t bp;
    modcp_cp_t cp;
    modcp_fb_t fb;
    modcp_plcmem_t plc;
    modcp_db_t dbs[NDB];
    uint8_t db_data[NDB][1024];
    uint8_t i[256], q[320], m[2600];
    uint16_t t[240], c[240];
    modcp_hal_t hal;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    modcp_params_t p;
    fuzz_mem_t mem;
    uint32_t t0, now_us, timer_at, tx_done_at, next_cycle; /* 0: none */
    uint32_t char_us, t15_us, t35_us, cycle_us, stall_until, tx_extra_us;
    bool stalled, restart;
    uint32_t cp_stall_until; /* the CP task does not run (no modcp_cp_poll) until then */
    modcp_fb_in_t fb_in;
    modcp_fb_out_t fb_out, fb_last;
    bool rts, cts_stuck_off, dsr_off, signals_changed; /* the partner's CTS / DSR */
    int de, led[3], sig[2];
    modcp_cp_status_t st_last; /* status_fields() of the last one printed */
    uint32_t ev_total;
    uint32_t mem_hash;
} world_t;

static world_t W;

static void say(const char *fmt, ...)
{
    va_list ap;
    printf("%u ", (unsigned)(W.now_us - W.t0));
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
}

static const char *hex(const uint8_t *b, size_t n)
{
    static char s[2 * 1200 + 1];
    static const char hx[] = "0123456789abcdef";
    n = n > 1200u ? 1200u : n;
    for (size_t k = 0; k < n; k++) {
        s[2 * k] = hx[b[k] >> 4];
        s[2 * k + 1] = hx[b[k] & 15u];
    }
    s[2 * n] = 0;
    return s;
}

/* ---- the HAL: every call is a line (levels only when they change) ---- */

static void h_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    (void)ctx;
    say("tx %s", hex(buf, len));
    W.tx_done_at = W.now_us + (uint32_t)len * W.char_us + W.tx_extra_us;
}

static void h_arm(void *ctx, uint32_t us)
{
    (void)ctx;
    say("arm %u", (unsigned)us);
    W.timer_at = us != 0u ? W.now_us + us : 0u;
}

static void level(int *cur, bool on, const char *what)
{
    if (*cur != (int)on) {
        *cur = on;
        say("%s %d", what, (int)on);
    }
}

static void h_de(void *ctx, bool on)
{
    (void)ctx;
    level(&W.de, on, "de");
}

static void h_led(void *ctx, modcp_led_t led, bool on)
{
    static const char *names[3] = {"led-sf", "led-txd", "led-rxd"};
    (void)ctx;
    if ((unsigned)led < 3u) {
        level(&W.led[led], on, names[led]);
    }
}

static void h_signal(void *ctx, modcp_signal_t sig, bool on)
{
    (void)ctx;
    if ((unsigned)sig < 2u) {
        level(&W.sig[sig], on, sig == MODCP_SIG_RTS ? "rts" : "dtr");
    }
    if (sig == MODCP_SIG_RTS) {
        W.rts = on;
        W.signals_changed = true;
    }
}

static void h_tx_abort(void *ctx)
{
    (void)ctx;
    say("tx-abort");
    W.tx_done_at = 0;
}

static void h_rx_preset(void *ctx, uint8_t preset)
{
    (void)ctx;
    say("rx-preset %u", (unsigned)preset);
}

/* ---- observation ---- */

static uint32_t fnv(uint32_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t k = 0; k < n; k++) {
        h = (h ^ b[k]) * 16777619u;
    }
    return h;
}

static void observe_mem(void)
{
    uint32_t h = fnv(2166136261u, W.i, sizeof W.i);
    h = fnv(h, W.q, sizeof W.q);
    h = fnv(h, W.m, sizeof W.m);
    h = fnv(h, W.t, sizeof W.t);
    h = fnv(h, W.c, sizeof W.c);
    h = fnv(h, W.db_data, sizeof W.db_data);
    if (h != W.mem_hash) {
        W.mem_hash = h;
        say("mem %08x", (unsigned)h);
    }
}

static void observe_fb(void)
{
    const modcp_fb_out_t *o = &W.fb_out;
    if (o->cp_start_ok != W.fb_last.cp_start_ok || o->cp_start_error != W.fb_last.cp_start_error ||
        o->cp_start_ndr != W.fb_last.cp_start_ndr || o->error_nr != W.fb_last.error_nr ||
        o->error_info != W.fb_last.error_info) {
        W.fb_last = *o;
        say("fb ok %d err %d ndr %d nr %u info %04x start %d", o->cp_start_ok, o->cp_start_error,
            o->cp_start_ndr, o->error_nr, o->error_info, W.fb_in.cp_start);
    }
}

static void print_events(const modcp_cp_status_t *s, uint32_t n)
{
    char line[16 * 6];
    size_t len = 0;
    uint32_t shown = n < s->buffer_len ? n : s->buffer_len;
    line[0] = 0;
    for (uint32_t k = shown; k-- > 0;) { /* oldest first */
        len += (size_t)snprintf(line + len, sizeof line - len, " %04x", s->buffer[k]);
    }
    say("ev +%u%s", (unsigned)n, line);
}

static void print_status(const modcp_cp_status_t *s)
{
    char c[8 * 6 + 1];
    size_t len = 0;
    for (unsigned k = 0; k < 8u; k++) {
        len += (size_t)snprintf(c + len, sizeof c - len, "%s%u", k ? "," : "", s->counters[k]);
    }
    say("st flags %x leds %x sig %x aborts %u cnt %s long %u chr %u brk %u t15 %u status %04x "
        "param %04x irq %s/%u systat %u:%s",
        (unsigned)s->flags, s->leds, s->signals, s->signal_aborts, c, s->frames_too_long,
        s->char_errors, s->breaks, s->t15_discards, s->status, s->param_event,
        hex(s->diag_irq, sizeof s->diag_irq), (unsigned)s->diag_irq_count,
        (unsigned)s->systat_ack, hex(s->systat, sizeof s->systat));
}

/* The status area's fields into a copy without padding (what a core leaves in the
 * padding is no behaviour), events_total and the diagnostic buffer apart. */
static void status_fields(const modcp_cp_status_t *s, modcp_cp_status_t *o)
{
    memset(o, 0, sizeof *o);
    o->flags = s->flags;
    o->leds = s->leds;
    o->signals = s->signals;
    o->signal_aborts = s->signal_aborts;
    memcpy(o->counters, s->counters, sizeof o->counters);
    o->frames_too_long = s->frames_too_long;
    o->char_errors = s->char_errors;
    o->breaks = s->breaks;
    o->t15_discards = s->t15_discards;
    o->status = s->status;
    o->param_event = s->param_event;
    memcpy(o->diag_irq, s->diag_irq, sizeof o->diag_irq);
    o->diag_irq_count = s->diag_irq_count;
    o->systat_ack = s->systat_ack;
    memcpy(o->systat, s->systat, sizeof o->systat);
}

/* The status area as the CPU side reads it, after every CP poll. */
static void observe_status(void)
{
    modcp_cp_status_t s, f;
    if (!modcp_bp_read_status(&W.bp, &s)) {
        say("st busy");
        return;
    }
    if (s.events_total != W.ev_total) {
        print_events(&s, s.events_total - W.ev_total);
        W.ev_total = s.events_total;
    }
    status_fields(&s, &f);
    if (memcmp(&f, &W.st_last, sizeof f) != 0) {
        W.st_last = f;
        print_status(&f);
    }
}

/* ---- the world's clock: timer, transmission complete, CPU cycles ---- */

static void partner_signals(void)
{
    if (W.signals_changed) {
        W.signals_changed = false;
        bool cts = (W.p.rts_on_delay_ms == 0u || W.rts) && !W.cts_stuck_off;
        modcp_cp_on_signals(&W.cp, cts, !W.dsr_off, W.now_us);
    }
}

/* One cycle of the user program (FB call, unless the CPU side stalls) and the CP task. */
static void cpu_cycle(void)
{
    W.next_cycle = W.now_us + W.cycle_us;
    if (!W.stalled || (int32_t)(W.now_us - W.stall_until) >= 0) {
        W.stalled = false;
        if (W.restart) {
            W.fb_in.cp_start = false;
            W.restart = false;
        } else if (!W.fb_in.cp_start) {
            W.fb_in.cp_start = true; /* a rising edge (also after CP_START_ERROR) */
        }
        modcp_fb_call(&W.fb, &W.fb_in, &W.fb_out, W.now_us / 1000u);
        observe_fb();
        if (W.fb_out.cp_start_ndr) {
            observe_mem();
        }
    }
    if (W.cp_stall_until == 0u || (int32_t)(W.now_us - W.cp_stall_until) >= 0) {
        W.cp_stall_until = 0;
        modcp_cp_poll(&W.cp, W.now_us);
        observe_status();
    }
}

static bool due(uint32_t at, uint32_t end)
{
    return at != 0u && (int32_t)(at - end) <= 0;
}

/* Run the world until `end`; hold_timer: a timer due meanwhile fires only after (the
 * receive interrupt of a block comes first). */
static void advance_to(uint32_t end, bool hold_timer)
{
    for (;;) {
        partner_signals();
        int what = 0;
        uint32_t at = end;
        if (!hold_timer && due(W.timer_at, at)) {
            what = 1, at = W.timer_at;
        }
        if (due(W.tx_done_at, at) && (what == 0 || (int32_t)(W.tx_done_at - at) < 0)) {
            what = 2, at = W.tx_done_at;
        }
        if (due(W.next_cycle, at) && (what == 0 || (int32_t)(W.next_cycle - at) < 0)) {
            what = 3, at = W.next_cycle;
        }
        if (what == 0) {
            break;
        }
        if ((int32_t)(at - W.now_us) > 0) {
            W.now_us = at;
        }
        if (what == 1) {
            W.timer_at = 0;
            modcp_cp_on_timer(&W.cp, W.now_us);
        } else if (what == 2) {
            W.tx_done_at = 0;
            modcp_cp_on_tx_done(&W.cp, W.now_us);
        } else {
            cpu_cycle();
        }
    }
    if ((int32_t)(end - W.now_us) > 0) {
        W.now_us = end;
    }
}

static void advance(uint32_t us)
{
    advance_to(W.now_us + us, false);
}

/* ---- the input ---- */

static uint32_t pick_gap(drng_t *r)
{
    uint32_t d = drng_below(r, 4) == 0 ? 1u : 1u + drng_below(r, W.char_us / 2u + 1u);
    uint32_t ascii = 1000u * W.p.ascii_timeout_ms;
    switch (drng_below(r, 7)) {
    case 0: return W.t15_us > d ? W.t15_us - d : 0u;
    case 1: return W.t15_us + d;
    case 2: return W.t35_us > d ? W.t35_us - d : 0u;
    case 3: return W.t35_us + d;
    case 4: return W.p.framing == MODCP_FRAMING_ASCII ? ascii - d : d;
    case 5: return W.p.framing == MODCP_FRAMING_ASCII ? ascii + d : 2u * d;
    default: return drng_below(r, 3u * W.t35_us);
    }
}

/* Long enough for a frame to end, its jobs to run and its reply to be out. */
static uint32_t quiet_us(void)
{
    const modcp_params_t *p = &W.p;
    return 20000u + 2u * W.t35_us + 270u * W.char_us + 8u * W.cycle_us +
           1000u * ((uint32_t)p->turnaround_ms + p->rts_on_delay_ms + p->rts_off_delay_ms);
}

static void rx_chars(const uint8_t *b, size_t n, bool block)
{
    if (block && n > 0u) {
        advance_to(W.now_us + (uint32_t)n * W.char_us, true);
        modcp_cp_on_rx_block(&W.cp, b, (uint16_t)n, W.now_us);
        return;
    }
    for (size_t k = 0; k < n; k++) {
        advance(W.char_us);
        modcp_cp_on_rx(&W.cp, b[k], W.now_us);
    }
}

static void line_error(uint8_t err)
{
    advance(W.char_us);
    modcp_cp_on_line_error(&W.cp, err, W.now_us);
}

/* A request on the line: a gap inside it (at g, 0 = none), a character lost to a line
 * error (at e, 0 = none), as characters or blocks; then the master waits (or not). */
static void step_frame(drng_t *r)
{
    static const uint8_t errs[4] = {MODCP_LINE_PARITY, MODCP_LINE_FRAMING, MODCP_LINE_OVERRUN,
                                    MODCP_LINE_BREAK};
    uint8_t adu[300], fr[700];
    size_t n = diff_request(r, &W.p, adu, sizeof adu);
    size_t m = diff_encode(&W.p, adu, n, fr, sizeof fr);
    m = diff_corrupt(r, fr, m, sizeof fr);
    size_t g = drng_below(r, 5) == 0 ? 1u + drng_below(r, (uint32_t)m) : 0u;
    uint32_t gap = g ? pick_gap(r) : 0u;
    size_t e = drng_below(r, 20) == 0 ? 1u + drng_below(r, (uint32_t)m) : 0u;
    uint8_t err = errs[drng_below(r, 4)];
    bool block = drng_below(r, 8) == 0;
    bool wait = drng_below(r, 4) != 0;
    uint32_t after = wait ? quiet_us() : pick_gap(r);
    say("rx %s gap %u@%u err %u@%u%s after %u", hex(fr, m), (unsigned)gap, (unsigned)g, err,
        (unsigned)e, block ? " block" : "", (unsigned)after);
    for (size_t k = 0; k < m;) {
        size_t end = m;
        end = g > k && g < end ? g : end;
        end = e > k && e - 1u < end ? e - 1u : end;
        rx_chars(fr + k, end - k, block);
        k = end;
        if (k == g && gap != 0u) {
            advance(gap);
            gap = 0;
        }
        if (e != 0u && k == e - 1u) {
            line_error(err);
            k++;
            e = 0;
        }
    }
    advance(after);
}

static void step_noise(drng_t *r)
{
    uint8_t b[48];
    size_t n = drng_below(r, 48);
    for (size_t k = 0; k < n; k++) {
        b[k] = (uint8_t)drng_next(r);
    }
    say("rx-noise %s", hex(b, n));
    for (size_t k = 0; k < n; k++) {
        if (drng_below(r, 6) == 0) {
            advance(pick_gap(r));
        }
        rx_chars(b + k, 1, false);
    }
}

/* The rarer steps: line errors, silences, the CPU side, the partner's signals. */
static void step_other(drng_t *r, uint32_t k)
{
    if (k < 10u) {
        uint8_t err = (uint8_t)(1u << drng_below(r, 4));
        say("line-error %u", err);
        line_error(err);
    } else if (k < 30u) {
        uint32_t gap = pick_gap(r);
        say("gap %u", (unsigned)gap);
        advance(gap);
    } else if (k < 45u) {
        W.stalled = true;
        W.stall_until = W.now_us + 1000u * drng_below(r, 2u * W.p.cpu_timeout_ms + 20u);
        say("cpu-stall until %u", (unsigned)(W.stall_until - W.t0));
    } else if (k < 50u) {
        W.restart = true;
        say("cp-start-drop");
    } else if (k < 55u) {
        W.cp_stall_until = W.now_us + 1000u * (1u + drng_below(r, 3u * W.p.cpu_timeout_ms + 20u));
        say("cp-task-stall until %u", (unsigned)(W.cp_stall_until - W.t0));
    } else if (k < 70u) {
        if (drng_below(r, 2) == 0) {
            W.cts_stuck_off = !W.cts_stuck_off;
        } else {
            W.dsr_off = !W.dsr_off;
        }
        W.signals_changed = true;
        say("partner cts-stuck-off %d dsr-off %d", W.cts_stuck_off, W.dsr_off);
    } else if (k < 80u) {
        say("systat-request %u", (unsigned)modcp_bp_systat_request(&W.bp));
    } else if (k < 86u) {
        say("commloss-reset");
        modcp_bp_commloss_reset(&W.bp);
    } else if (k < 92u) {
        uint32_t ms = W.p.commloss_ms > W.p.cpu_timeout_ms ? W.p.commloss_ms : W.p.cpu_timeout_ms;
        ms = W.p.ascii_timeout_ms > ms ? W.p.ascii_timeout_ms : ms;
        say("silence %u ms", (unsigned)(ms + 2u));
        advance(1000u * (ms + 2u));
    } else {
        W.tx_extra_us = drng_below(r, 2) ? 0u : drng_below(r, 4u * W.char_us);
        say("tx-complete-late %u", (unsigned)W.tx_extra_us);
    }
}

static void fill_memory(void)
{
    for (unsigned k = 0; k < sizeof W.m; k++) W.m[k] = (uint8_t)(k * 7u);
    for (unsigned k = 0; k < sizeof W.i; k++) W.i[k] = (uint8_t)(k * 3u);
    for (unsigned k = 0; k < sizeof W.q; k++) W.q[k] = (uint8_t)(k * 5u);
    for (unsigned k = 0; k < 240u; k++) {
        W.t[k] = (uint16_t)(k * 257u);
        W.c[k] = (uint16_t)~k;
    }
    for (unsigned d = 0; d < NDB; d++)
        for (unsigned k = 0; k < sizeof W.db_data[d]; k++) W.db_data[d][k] = (uint8_t)(k ^ d);
}

/* A new world for the input: parameter set and memory from 48 random bytes. */
static void setup(drng_t *r)
{
    memset(&W, 0, sizeof W);
    W.now_us = W.t0 = 5000000u;
    W.de = W.led[0] = W.led[1] = W.led[2] = W.sig[0] = W.sig[1] = -1;
    uint8_t h[FUZZ_CFG_BYTES];
    static const uint32_t density[4] = {0, 8, 3, 8}; /* one byte in n is not 0 */
    uint32_t d = density[drng_below(r, 4)];
    for (unsigned k = 0; k < FUZZ_CFG_BYTES; k++) {
        h[k] = d == 0u || drng_below(r, d) != 0 ? 0u : (uint8_t)drng_next(r);
    }
    modcp_params_t base;
    fuzz_cfg_base(&base, drng_below(r, 3) == 0);
    fuzz_cfg_stats_t stats;
    fuzz_cfg_build(h, &base, &W.p, &W.mem, &stats);
    say("cfg %s", hex(h, sizeof h));
    W.char_us = modcp_params_char_us(&W.p);
    W.t35_us = modcp_params_t35_us(&W.p);
    W.t15_us = W.p.baud > 19200u ? 750u : (16500000u + W.p.baud - 1u) / W.p.baud;
    static const uint32_t cycles[6] = {1000, 1000, 1000, 2000, 3000, 10000};
    W.cycle_us = cycles[drng_below(r, 6)];
    uint16_t ndb = 0;
    for (unsigned k = 0; k < NDB; k++) {
        if (W.mem.db_size[k] != 0u) {
            W.dbs[ndb++] = (modcp_db_t){db_numbers[k], W.mem.db_size[k], W.db_data[k]};
        }
    }
    W.plc = (modcp_plcmem_t){.i = W.i, .q = W.q, .m = W.m, .t = W.t, .c = W.c,
                             .i_size = sizeof W.i, .q_size = sizeof W.q, .m_size = W.mem.m_size,
                             .t_count = 240, .c_count = 240, .dbs = W.dbs, .db_count = ndb};
    W.hal = (modcp_hal_t){.ctx = &W, .uart_tx = h_tx, .timer_arm = h_arm, .set_de = h_de,
                          .set_led = h_led, .set_signal = h_signal, .uart_tx_abort = h_tx_abort,
                          .set_rx_preset = h_rx_preset};
    size_t len = modcp_params_encode(&W.p, W.record, sizeof W.record);
    say("set framing %u baud %u addr %u rounds %u fallbacks %u whole %u cycle %u record %u:%08x",
        W.p.framing, (unsigned)W.p.baud, W.p.slave_addr, stats.rounds, stats.fallbacks,
        stats.whole, (unsigned)W.cycle_us, (unsigned)len, (unsigned)fnv(2166136261u, W.record, len));
    fill_memory();
    modcp_bp_init(&W.bp);
    modcp_fb_init(&W.fb, &W.bp, &W.plc, W.record, (uint16_t)len, W.mem.work_db, 5000);
    modcp_cp_init(&W.cp, &W.hal, &W.bp);
    modcp_cp_on_signals(&W.cp, false, true, W.now_us); /* CTS OFF (RTS is), DSR ON */
    W.signals_changed = true;
    W.fb_in.cp_start = true;
    W.next_cycle = W.now_us;
    advance(60000);
    say("ready %d", modcp_cp_ready(&W.cp));
}

static void run_input(uint64_t seed, uint64_t input)
{
    drng_t r;
    drng_seed(&r, seed, input);
    printf("== input %llu\n", (unsigned long long)input);
    setup(&r);
    observe_mem();
    unsigned steps = 1u + drng_below(&r, 12);
    for (unsigned s = 0; s < steps; s++) {
        uint32_t k = drng_below(&r, 100);
        if (k < 60u) {
            step_frame(&r);
        } else if (k < 68u) {
            step_noise(&r);
        } else {
            step_other(&r, drng_below(&r, 100));
        }
        observe_mem();
    }
    W.stalled = false;
    W.cp_stall_until = 0;
    W.cts_stuck_off = W.dsr_off = false;
    W.signals_changed = true;
    advance(quiet_us() + 1000u * W.p.cpu_timeout_ms);
    observe_mem();
    say("end");
}

int main(int argc, char **argv)
{
    uint64_t seed = 1, first = 0, count = 100;
    for (int a = 1; a + 1 < argc; a += 2) {
        uint64_t v = strtoull(argv[a + 1], NULL, 0);
        if (strcmp(argv[a], "--seed") == 0) {
            seed = v;
        } else if (strcmp(argv[a], "--inputs") == 0) {
            count = v;
        } else if (strcmp(argv[a], "--first") == 0) {
            first = v;
        } else {
            fprintf(stderr, "usage: diff_transcript [--seed S] [--inputs N] [--first K]\n");
            return 2;
        }
    }
    static char buf[1 << 20];
    setvbuf(stdout, buf, _IOFBF, sizeof buf);
    for (uint64_t k = first; k < first + count; k++) {
        run_input(seed, k);
    }
    printf("== done %llu inputs\n", (unsigned long long)count);
    return 0;
}
