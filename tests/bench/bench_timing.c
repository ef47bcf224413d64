/* SPDX-License-Identifier: Apache-2.0 */
/* Benchmark: the RTU timing table (docs/timing.md), measured on a simulated line at the
 * core's boundary with an injected clock, exact to the microsecond; nothing asserted.
 *
 *   bench_timing [--cycle-us N]     the markdown tables of docs/timing.md (N: the CPU
 *                                   side's cycle, default 10000)
 *
 * The line: character k of the request ends (its stop bit) at a chosen time; the core
 * gets modcp_cp_on_rx(byte, end of its stop bit), as a UART receive interrupt sees it.
 * The one-shot timer the core arms (hal.timer_arm) fires at its deadline; at equal
 * times the timer comes before a character (as tools/sim orders them).
 * The reply's first start bit is the moment the core calls hal.uart_tx (the line is
 * idle); its last stop bit ends len x character time later, when the harness calls
 * modcp_cp_on_tx_done (transmission complete). The CPU side's user program calls the
 * FB once per cycle (modcp_fb_call, then modcp_cp_poll for the backplane interrupt);
 * the CP task (modcp_cp_poll) also runs after every other event. Nothing takes time but
 * the line and the cycle: the FB and the CP answer at the instant they are called.
 *
 * Every row: RTU 8E1 (11 bits a character), slave 5, end-of-frame timing by the
 * manual's table (eof_timing = manual; three rows: the Modbus rule, eof_timing =
 * modbus, with the t1.5 check), f_MUL 1, interface RS485 two-wire with the
 * operating-mode selection enabled (so that normal mode runs on it; the driver enable
 * exists only there; the interface changes which line errors are reported, not the
 * timing), turnaround 0; the request is FC03 of 10 registers (8 characters), the reply
 * 25 characters.
 *
 * Measured per row (baud rate, operating mode, t1.5 check, eof_timing):
 *  - close: the end of the request's last stop bit -> the request is handed to the CPU
 *    side (its job block published on the backplane);
 *  - eof interval: the smallest interval between two received characters (the end of a
 *    stop bit -> the end of the next stop bit, what the receive interrupt sees) before
 *    the request's last character that ends the frame there (the first 7 characters
 *    are a frame of their own: (08)36H), by bisection on the clock; compared with t3.5.
 *    The silence before that character (end of a stop bit -> the next start bit) is the
 *    interval - 1 character, printed beside it and not compared (docs/timing.md, "Why
 *    the silence is one character shorter");
 *  - t1.5 silence: with the t1.5 check on, the smallest silence that discards the
 *    request (t15_discards), by bisection below the eof interval; compared with t1.5;
 *  - response start: the end of the request's last stop bit -> the reply's first start
 *    bit, for the request's end at every microsecond of the CPU cycle: p50 and p99;
 *  - DE: the driver enable switched on -> the reply's first start bit, and the end of
 *    the reply's last stop bit -> DE released.
 * Each is printed with the reference it is compared with (the manual's TIME_OUT table
 * or the Modbus rule for t3.5, the Modbus serial-line rule for t1.5, the model
 * t3.5 + q x cycle for the response) and the difference in bit times. */
#include <math.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/crc.h"
#include "modcp/events.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"

#define BITS_PER_CHAR 11u /* 8E1: start, 8 data, parity, stop */
#define REQ_LEN 8u
#define REPLY_LEN 25u
#define NEVER 0xFFFFFFFFu

typedef struct {
    modcp_backplane_t bp;
    modcp_cp_t cp;
    modcp_fb_t fb;
    modcp_fb_in_t in;
    modcp_plcmem_t mem;
    modcp_db_t db;
    uint8_t db800[256];
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    modcp_hal_t hal;
    uint32_t now;
    uint32_t cycle_us, next_cycle;
    uint32_t char_us;
    bool timer_on;
    uint32_t timer_at;
    bool tx_on;
    uint32_t tx_start, tx_end;
    uint16_t tx_len;
    unsigned tx_count;
    bool de;
    uint32_t de_on_at, de_off_at;
    uint32_t head_seen, job_at; /* to_cpu.head at the last look; when a job went out */
} line_t;

typedef struct {
    uint32_t baud;
    bool suppress;
    bool t15;
    bool modbus_eof; /* eof_timing = modbus (else manual) */
} row_t;

static int32_t diff(uint32_t a, uint32_t b)
{
    return (int32_t)(a - b);
}

static void h_tx(void *ctx, const uint8_t *b, uint16_t n)
{
    line_t *s = ctx;
    (void)b;
    s->tx_on = true;
    s->tx_start = s->now;
    s->tx_len = n;
    s->tx_end = s->now + (uint32_t)n * s->char_us;
    s->tx_count++;
}

static void h_arm(void *ctx, uint32_t us)
{
    line_t *s = ctx;
    s->timer_on = us != 0u;
    s->timer_at = s->now + us;
}

static void h_de(void *ctx, bool on)
{
    line_t *s = ctx;
    if (on && !s->de) {
        s->de_on_at = s->now;
    } else if (!on && s->de) {
        s->de_off_at = s->now;
    }
    s->de = on;
}

/* The CP task after an event; notes when a job block left for the CPU side. */
static void after_event(line_t *s)
{
    modcp_cp_poll(&s->cp, s->now);
    uint32_t h = atomic_load(&s->bp.to_cpu.head);
    if (h != s->head_seen) {
        s->head_seen = h;
        if (s->job_at == NEVER) {
            s->job_at = s->now;
        }
    }
}

static void cpu_cycle(line_t *s)
{
    modcp_fb_out_t out;
    modcp_fb_call(&s->fb, &s->in, &out, s->now / 1000u);
    after_event(s);
    s->next_cycle += s->cycle_us;
}

static void params_of(const row_t *r, modcp_params_t *p)
{
    modcp_params_defaults(p);
    p->slave_addr = 5;
    p->baud = r->baud;
    p->opmode = r->suppress ? (uint8_t)MODCP_OPMODE_SUPPRESS : (uint8_t)MODCP_OPMODE_NORMAL;
    p->t15_check = r->t15 ? 1u : 0u;
    p->eof_timing = r->modbus_eof ? (uint8_t)MODCP_EOF_MODBUS : (uint8_t)MODCP_EOF_MANUAL;
    p->iface = (uint8_t)MODCP_IFACE_RS485;
    p->rs485_sel = 1;
    p->turnaround_ms = 0;
    p->hr_base_db = 800;
}

/* One character time on the row's line, in whole us (the core's own value). */
static uint32_t char_us_of(const row_t *r)
{
    modcp_params_t p;
    params_of(r, &p);
    return modcp_params_char_us(&p);
}

/* A fresh CP and FB for the row, run until ready; the clock starts at 1 s. */
static void line_setup(line_t *s, const row_t *r, uint32_t cycle_us)
{
    memset(s, 0, sizeof *s);
    modcp_params_t p;
    params_of(r, &p);
    s->hal = (modcp_hal_t){.ctx = s, .uart_tx = h_tx, .timer_arm = h_arm, .set_de = h_de};
    s->db = (modcp_db_t){800, sizeof s->db800, s->db800};
    s->mem = (modcp_plcmem_t){.dbs = &s->db, .db_count = 1};
    uint16_t n = (uint16_t)modcp_params_encode(&p, s->record, sizeof s->record);
    modcp_bp_init(&s->bp);
    modcp_fb_init(&s->fb, &s->bp, &s->mem, s->record, n, 0, 5000);
    modcp_cp_init(&s->cp, &s->hal, &s->bp);
    s->in.cp_start = true;
    s->cycle_us = cycle_us;
    s->now = 1000000u;
    s->next_cycle = s->now;
    s->char_us = modcp_params_char_us(&p);
    s->job_at = NEVER;
    for (int k = 0; k < 200 && !modcp_cp_ready(&s->cp); k++) {
        s->now = s->next_cycle;
        cpu_cycle(s);
    }
    if (!modcp_cp_ready(&s->cp)) {
        fprintf(stderr, "bench_timing: CP not ready (%lu baud)\n", (unsigned long)r->baud);
        exit(1);
    }
}

/* The line from now to `until`: the n characters b[] ending at end[], the timer, the
 * end of a transmission and the CPU cycles, each at its time (ties: transmission
 * complete, timer, character, cycle). */
static void line_run(line_t *s, const uint8_t *b, const uint32_t *end, unsigned n, uint32_t until)
{
    unsigned i = 0;
    for (;;) {
        uint32_t t = s->next_cycle;
        int ev = 3;
        if (i < n && diff(end[i], t) <= 0) {
            t = end[i];
            ev = 2;
        }
        if (s->timer_on && diff(s->timer_at, t) <= 0) {
            t = s->timer_at;
            ev = 1;
        }
        if (s->tx_on && diff(s->tx_end, t) <= 0) {
            t = s->tx_end;
            ev = 0;
        }
        if (diff(t, until) > 0) {
            s->now = until;
            return;
        }
        s->now = t;
        switch (ev) {
        case 0:
            s->tx_on = false;
            modcp_cp_on_tx_done(&s->cp, t);
            after_event(s);
            break;
        case 1:
            s->timer_on = false;
            modcp_cp_on_timer(&s->cp, t);
            after_event(s);
            break;
        case 2:
            modcp_cp_on_rx(&s->cp, b[i++], t);
            after_event(s);
            break;
        default:
            cpu_cycle(s);
            break;
        }
    }
}

static void make_request(uint8_t req[REQ_LEN])
{
    static const uint8_t head[6] = {0x05, 0x03, 0x00, 0x00, 0x00, 0x0A};
    memcpy(req, head, sizeof head);
    uint16_t crc = modcp_crc16(req, sizeof head);
    req[6] = (uint8_t)(crc & 0xFFu);
    req[7] = (uint8_t)(crc >> 8);
}

/* The request back to back, except that its last character ends `interval` us after
 * the one before it (interval >= 1 character: the silence between them is interval - 1
 * character); the line run until everything is over. */
static void send_with_interval(line_t *s, uint32_t interval)
{
    uint8_t req[REQ_LEN];
    uint32_t end[REQ_LEN];
    make_request(req);
    uint32_t t = s->now + 10u * s->char_us;
    for (unsigned k = 0; k < REQ_LEN; k++) {
        t += k == REQ_LEN - 1u ? interval : s->char_us;
        end[k] = t;
    }
    line_run(s, req, end, REQ_LEN, t + 100000u + 3u * s->cycle_us);
}

static unsigned events_of(const line_t *s, uint32_t before, modcp_event_t ev)
{
    const modcp_diag_t *d = &s->cp.diag;
    uint32_t n = d->events_total - before;
    unsigned found = 0;
    for (uint32_t k = 0; k < n && k < d->buffer_len; k++) {
        found += d->buffer[k] == ev ? 1u : 0u;
    }
    return found;
}

/* What an interval of `interval` us between the ends of the request's last two
 * characters does: 'E' the frame ended there ((08)36H for its first part), 'D'
 * discarded by the t1.5 check, 'A' answered as one request, '?' anything else. */
static char interval_outcome(const row_t *r, uint32_t cycle_us, uint32_t interval)
{
    static line_t s;
    line_setup(&s, r, cycle_us);
    uint32_t ev0 = s.cp.diag.events_total;
    uint16_t t15_0 = s.cp.diag.t15_discards;
    send_with_interval(&s, interval);
    if (events_of(&s, ev0, MODCP_EV_CRC) > 0u && s.tx_count == 0u) {
        return 'E';
    }
    if (s.cp.diag.t15_discards != t15_0 && s.tx_count == 0u) {
        return 'D';
    }
    if (s.tx_count == 1u && s.tx_len == REPLY_LEN) {
        return 'A';
    }
    return '?';
}

/* The smallest interval in [lo, hi] with outcome `want` when every interval below it has
 * another (bisection on the clock; lo's outcome must differ, hi's must be `want`); NEVER
 * if hi's is not. */
static uint32_t bisect(const row_t *r, uint32_t cycle_us, uint32_t lo, uint32_t hi, char want)
{
    if (interval_outcome(r, cycle_us, hi) != want) {
        return NEVER;
    }
    if (interval_outcome(r, cycle_us, lo) == want) {
        fprintf(stderr, "bench_timing: an interval of %lu us already gives '%c'\n",
                (unsigned long)lo, want);
        exit(1);
    }
    while (hi - lo > 1u) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (interval_outcome(r, cycle_us, mid) == want) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    return hi;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* nearest rank */
static uint32_t pct(const uint32_t *v, size_t n, unsigned p)
{
    size_t k = (n * p + 99u) / 100u;
    return v[k > 0u ? k - 1u : 0u];
}

typedef struct {
    uint32_t close, p50, p99, de_lead, de_off;
    int ok;
} resp_t;

/* The request at every microsecond of the CPU cycle (its last stop bit k us after a
 * cycle start), one after the other on one CP; each reply checked. */
static resp_t response(const row_t *r, uint32_t cycle_us)
{
    static line_t s;
    static uint32_t st[100000];
    resp_t res = {0, 0, 0, 0, 0, 1};
    uint32_t n = cycle_us < 100000u ? cycle_us : 100000u;
    uint8_t req[REQ_LEN];
    uint32_t end[REQ_LEN];
    make_request(req);
    line_setup(&s, r, cycle_us);
    uint32_t close_min = NEVER, close_max = 0, lead_max = 0, off_max = 0, off_min = NEVER;
    for (uint32_t k = 0; k < n; k++) {
        /* a few cycles ahead, far enough for the whole request */
        uint32_t ahead = (2u + (REQ_LEN * s.char_us) / cycle_us + 1u) * cycle_us;
        uint32_t last = s.next_cycle + ahead + k * (cycle_us / n);
        for (unsigned c = 0; c < REQ_LEN; c++) {
            end[c] = last - (REQ_LEN - 1u - c) * s.char_us;
        }
        unsigned tx0 = s.tx_count;
        s.job_at = NEVER;
        s.de_on_at = s.de_off_at = NEVER;
        line_run(&s, req, end, REQ_LEN, last + 100000u + 3u * cycle_us);
        if (s.tx_count != tx0 + 1u || s.tx_len != REPLY_LEN || s.job_at == NEVER ||
            s.de_on_at == NEVER || s.de_off_at == NEVER || s.de) {
            res.ok = 0;
            return res;
        }
        uint32_t close = s.job_at - last;
        close_min = close < close_min ? close : close_min;
        close_max = close > close_max ? close : close_max;
        st[k] = s.tx_start - last;
        uint32_t lead = s.tx_start - s.de_on_at, off = s.de_off_at - s.tx_end;
        lead_max = lead > lead_max ? lead : lead_max;
        off_max = off > off_max ? off : off_max;
        off_min = off < off_min ? off : off_min;
    }
    if (close_min != close_max || off_min != off_max) {
        res.ok = 0; /* the table has one value: say so instead of printing it */
        return res;
    }
    qsort(st, n, sizeof st[0], cmp_u32);
    res.close = close_min;
    res.p50 = pct(st, n, 50u);
    res.p99 = pct(st, n, 99u);
    res.de_lead = lead_max;
    res.de_off = off_max;
    return res;
}

/* ---- references -------------------------------------------------------------------- */

/* The manual's t3.5 (CP 341 manual, "End-of-frame detection": TIME_OUT by baud rate, the
 * time of 3.5 characters); 115200 is not in its table: 3.5 characters of 11 bits, the
 * rule the table follows. */
static double manual_t35_us(uint32_t baud)
{
    static const struct {
        uint32_t baud;
        double us;
    } tab[] = {{300u, 128000.0}, {600u, 64000.0},  {1200u, 32000.0}, {2400u, 16000.0},
               {4800u, 8000.0},  {9600u, 4000.0},  {19200u, 2000.0}, {38400u, 1000.0},
               {76800u, 500.0}};
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++) {
        if (tab[i].baud == baud) {
            return tab[i].us;
        }
    }
    return 3.5 * BITS_PER_CHAR * 1e6 / baud;
}

/* MODBUS over Serial Line V1.02 §2.5.1.1: 1.5 and 3.5 characters; above 19200 baud
 * 750 and 1750 us. */
static double modbus_t15_us(uint32_t baud)
{
    return baud > 19200u ? 750.0 : 1.5 * BITS_PER_CHAR * 1e6 / baud;
}

static double modbus_t35_us(uint32_t baud)
{
    return baud > 19200u ? 1750.0 : 3.5 * BITS_PER_CHAR * 1e6 / baud;
}

/* The t3.5 a row is compared with: the manual's, or the Modbus rule (eof_timing). */
static double t35_rule_us(const row_t *r)
{
    return r->modbus_eof ? modbus_t35_us(r->baud) : manual_t35_us(r->baud);
}

static const char *mode_name(const row_t *r)
{
    return r->suppress ? "suppress" : "normal";
}

static void bits_cell(char *out, size_t cap, double d, double bit_us)
{
    double b = d / bit_us;
    snprintf(out, cap, "%+.2f %s", fabs(b) < 0.005 ? 0.0 : b, fabs(b) <= 1.0 ? "✓" : "✗");
}

int main(int argc, char **argv)
{
    uint32_t cycle_us = 10000u;
    if (argc == 3 && strcmp(argv[1], "--cycle-us") == 0) {
        cycle_us = (uint32_t)strtoul(argv[2], NULL, 0);
    } else if (argc != 1) {
        fprintf(stderr, "usage: bench_timing [--cycle-us N]\n");
        return 2;
    }
    if (cycle_us < 1000u || cycle_us > 100000u || cycle_us % 1000u != 0u) {
        fprintf(stderr, "bench_timing: --cycle-us must be whole ms, 1000 ... 100000\n");
        return 2;
    }
    static const uint32_t bauds[] = {9600u, 19200u, 115200u};
    row_t rows[15];
    size_t nrows = 0;
    for (size_t b = 0; b < 3u; b++) {
        for (int m = 0; m < 2; m++) {
            for (int t = 0; t < 2; t++) {
                rows[nrows++] = (row_t){bauds[b], m != 0, t != 0, false};
            }
        }
    }
    for (size_t b = 0; b < 3u; b++) { /* the Modbus rule, with the t1.5 check it goes with */
        rows[nrows++] = (row_t){bauds[b], false, true, true};
    }
    static resp_t rs_of[15];
    for (size_t i = 0; i < nrows; i++) {
        rs_of[i] = response(&rows[i], cycle_us);
        if (!rs_of[i].ok) {
            fprintf(stderr, "bench_timing: %lu %s: replies or times not as expected\n",
                    (unsigned long)rows[i].baud, mode_name(&rows[i]));
            return 1;
        }
    }
    char e1[32], e2[32], e3[32];
    printf("### End of frame\n\n");
    printf("| baud | mode | t1.5 check | eof_timing | bit µs | t3.5 µs | close rule µs |"
           " closed after µs | error, bits | eof interval µs | error, bits |"
           " eof silence µs (= interval − 1 char) | t1.5 µs | t1.5 silence µs | error, bits |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        const double bit = 1e6 / r->baud, t35 = t35_rule_us(r);
        const resp_t rs = rs_of[i];
        const double close_rule = r->suppress ? 0.0 : t35;
        const uint32_t ch = char_us_of(r), hi = 2u * (uint32_t)t35 + 1000u;
        /* intervals from back to back (1 character, no silence) on */
        uint32_t eof = bisect(r, cycle_us, ch, hi, 'E');
        if (eof == NEVER) {
            fprintf(stderr, "bench_timing: an interval of %lu us does not end the frame\n",
                    (unsigned long)hi);
            return 1;
        }
        bits_cell(e1, sizeof e1, (double)rs.close - close_rule, bit);
        bits_cell(e2, sizeof e2, (double)eof - t35, bit);
        printf("| %lu | %s | %s | %s | %.2f | %.1f | %.1f | %lu | %s | %lu | %s | %lu |",
               (unsigned long)r->baud, mode_name(r), r->t15 ? "on" : "off",
               r->modbus_eof ? "modbus" : "manual", bit, t35, close_rule, (unsigned long)rs.close,
               e1, (unsigned long)eof, e2, (unsigned long)(eof - ch));
        if (!r->t15) {
            printf(" — | — | — |\n");
            continue;
        }
        const double t15 = modbus_t15_us(r->baud);
        uint32_t d = bisect(r, cycle_us, ch, eof - 1u, 'D'); /* an interval */
        if (d == NEVER) {
            printf(" %.1f | none | — |\n", t15);
        } else {
            bits_cell(e3, sizeof e3, (double)(d - ch) - t15, bit);
            printf(" %.1f | %lu | %s |\n", t15, (unsigned long)(d - ch), e3);
        }
    }
    printf("\n### Response start and driver enable\n\n");
    printf("| baud | mode | t1.5 check | eof_timing | model p50 µs | p50 µs | error, bits |"
           " model p99 µs | p99 µs | error, bits | DE on before µs | DE off after µs |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        const double bit = 1e6 / r->baud;
        const double close = r->suppress ? 0.0 : t35_rule_us(r);
        const double m50 = close + 0.50 * cycle_us, m99 = close + 0.99 * cycle_us;
        const resp_t rs = rs_of[i];
        bits_cell(e1, sizeof e1, (double)rs.p50 - m50, bit);
        bits_cell(e2, sizeof e2, (double)rs.p99 - m99, bit);
        printf("| %lu | %s | %s | %s | %.1f | %lu | %s | %.1f | %lu | %s | %lu | %lu |\n",
               (unsigned long)r->baud, mode_name(r), r->t15 ? "on" : "off",
               r->modbus_eof ? "modbus" : "manual", m50,
               (unsigned long)rs.p50, e1, m99, (unsigned long)rs.p99, e2,
               (unsigned long)rs.de_lead, (unsigned long)rs.de_off);
    }
    return 0;
}
