/* SPDX-License-Identifier: Apache-2.0 */
#define _POSIX_C_SOURCE 200809L
/* Benchmark: the receive path per byte. Feeds the frames of an FC16 request with 123
 * registers (255 bytes, slave 5, 9600 baud 8E1: one byte every 1146 us) with an
 * injected clock; the one-shot timer the core arms is fired when due, between bytes,
 * as a port's timer interrupt would.
 *
 *   bench_rx link FRAMES   bytes into modcp_link_on_byte() (the link and its framing)
 *   bench_rx link-t15 FRAMES  the same with the t1.5 check on
 *   bench_rx cp FRAMES     bytes into modcp_cp_on_rx() (the port's entry: CP hooks too)
 *   bench_rx link-modem FRAMES  link mode in interference suppression (modem mode)
 *   bench_rx link-block FRAMES  each frame in one block into modcp_link_on_block()
 *                          (characters back to back, a UART with DMA or a FIFO)
 *   bench_rx slave-time N  the slave time (end of the request's last character to the
 *                          end of the reply's first) of N FC03 x10 requests at every
 *                          phase of the CPU cycle, normal and modem mode, 9600 baud /
 *                          10 ms cycle and 115200 / 1 ms: p50 and the model value, as
 *                          key=value lines (injected clock, no callgrind)
 *   bench_rx --summary     runs tests/bench/bench_rx.sh (from the source root) for
 *                          tools/bench --summary
 *
 * Instructions per byte, under callgrind (nothing else is counted):
 *   valgrind --tool=callgrind --callgrind-out-file=/dev/null \
 *     --toggle-collect=modcp_link_on_byte build/host/tests/bench/bench_rx link 200
 * and divide "Collected" by the byte count the program prints (FRAMES x 255). With
 * --toggle-collect=modcp_link_on_timer (link mode) the same run counts the timer
 * expiries while the frames arrive and the end of each frame. Alone it prints the
 * byte count and wall time per byte. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/crc.h"
#include "modcp/fb.h"
#include "modcp/link.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "diag_internal.h"
#include "link_internal.h"

#define NREGS 123u
#define FRAME_LEN (7u + 2u * NREGS + 2u) /* 255 */

static uint32_t now_us = 1000000u, timer_at;
static int timer_on, tx_done;
static uint16_t tx_len;
static uint8_t frame[FRAME_LEN];

static uint32_t tx_at;

static void f_tx(void *ctx, const uint8_t *b, uint16_t n)
{
    (void)ctx;
    (void)b;
    tx_len = n;
    tx_done = 1;
    tx_at = now_us;
}

static void f_arm(void *ctx, uint32_t us)
{
    (void)ctx;
    timer_on = us != 0u;
    timer_at = now_us + us;
}

static const modcp_hal_t hal = {.ctx = NULL, .uart_tx = f_tx, .timer_arm = f_arm};

static int due(void)
{
    return timer_on && (int32_t)(now_us - timer_at) >= 0;
}

static void make_frame(void)
{
    const uint8_t head[7] = {0x05, 0x10, 0x00, 0x00, 0x00, (uint8_t)NREGS, (uint8_t)(2u * NREGS)};
    memcpy(frame, head, sizeof head);
    for (unsigned k = 0; k < 2u * NREGS; k++) {
        frame[7u + k] = (uint8_t)(k * 7u + 1u);
    }
    uint16_t crc = modcp_crc16(frame, FRAME_LEN - 2u);
    frame[FRAME_LEN - 2u] = (uint8_t)(crc & 0xFFu);
    frame[FRAME_LEN - 1u] = (uint8_t)(crc >> 8);
}

/* ---- link mode ------------------------------------------------------------------ */

static modcp_link_t link_;
static modcp_diag_t diag;
static uint8_t buf[MODCP_LINK_BUF_MAX];
static modcp_frame_t fr;
static uint32_t char_us;

static void link_setup(int t15, int modem)
{
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.t15_check = t15 ? 1u : 0u;
    p.opmode = modem ? (uint8_t)MODCP_OPMODE_SUPPRESS : (uint8_t)MODCP_OPMODE_NORMAL;
    modcp_diag_init(&diag);
    modcp_link_init(&link_, &hal, &diag, buf, (uint16_t)sizeof buf);
    modcp_link_configure(&link_, &p);
    char_us = modcp_params_char_us(&p);
}

/* The end of a frame: the timer's expiries until the link hands it over (1) or gives
 * up (0), then a pause before the next frame. */
static int link_frame_end(void)
{
    int got = 0;
    while (timer_on && !got) {
        timer_on = 0;
        now_us = timer_at;
        got = modcp_link_on_timer(&link_, now_us, &fr) ? 1 : 0;
    }
    if (got) {
        modcp_link_done(&link_);
    }
    now_us += 10000u;
    return got;
}

/* One frame into the link; returns 1 when it was delivered as a request. */
static int link_frame(void)
{
    for (unsigned k = 0; k < FRAME_LEN; k++) {
        if (due()) {
            timer_on = 0;
            now_us = timer_at;
            (void)modcp_link_on_timer(&link_, now_us, &fr);
        }
        modcp_link_on_byte(&link_, frame[k], now_us);
        now_us += char_us;
    }
    return link_frame_end();
}

/* The same frame handed over in one block at the end of its last character. */
static int link_block_frame(void)
{
    now_us += (uint32_t)(FRAME_LEN - 1u) * char_us;
    modcp_link_on_block(&link_, frame, (uint16_t)FRAME_LEN, now_us);
    now_us += char_us;
    return link_frame_end();
}

/* ---- cp mode --------------------------------------------------------------------- */

static modcp_backplane_t bp;
static modcp_cp_t cp;
static modcp_fb_t fb;
static modcp_plcmem_t mem;
static modcp_db_t dbs[1];
static uint8_t db800[1024];
static uint8_t record[MODCP_PARAMS_RECORD_MAX];

static void cp_setup(void)
{
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.hr_base_db = 800;
    p.lim_db = (modcp_limit_t){800, 899};
    dbs[0] = (modcp_db_t){800, sizeof db800, db800};
    mem = (modcp_plcmem_t){.dbs = dbs, .db_count = 1};
    uint16_t n = (uint16_t)modcp_params_encode(&p, record, sizeof record);
    modcp_bp_init(&bp);
    modcp_fb_init(&fb, &bp, &mem, record, n, 0, 5000);
    modcp_cp_init(&cp, &hal, &bp);
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    for (int k = 0; k < 20 && !modcp_cp_ready(&cp); k++) {
        modcp_fb_call(&fb, &in, &out, now_us / 1000u);
        modcp_cp_poll(&cp, now_us);
        now_us += 1000u;
    }
    if (!modcp_cp_ready(&cp)) {
        fprintf(stderr, "bench_rx: CP not ready\n");
        exit(1);
    }
    char_us = modcp_params_char_us(&p);
}

/* One request through the CP, served by the FB; returns 1 when it was answered. */
static int cp_frame(void)
{
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    tx_done = 0;
    for (unsigned k = 0; k < FRAME_LEN; k++) {
        if (due()) {
            timer_on = 0;
            now_us = timer_at;
            modcp_cp_on_timer(&cp, now_us);
        }
        modcp_cp_on_rx(&cp, frame[k], now_us);
        now_us += char_us;
    }
    for (int k = 0; k < 1000 && !tx_done; k++) {
        if (due()) {
            timer_on = 0;
            now_us = timer_at;
            modcp_cp_on_timer(&cp, now_us);
            continue;
        }
        modcp_fb_call(&fb, &in, &out, now_us / 1000u);
        modcp_cp_poll(&cp, now_us);
        now_us += 1000u;
    }
    if (tx_done) {
        modcp_cp_on_tx_done(&cp, now_us);
    }
    now_us += 10000u;
    return tx_done;
}

/* ---- slave time ----------------------------------------------------------------- */

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* p50 of the slave time of n FC03 x10 requests; the FB runs every cycle_us (followed by
 * a CP poll), the request starts at every phase of it. */
static uint32_t slave_time_p50(uint32_t baud, uint32_t cycle_us, int modem, unsigned n,
                               uint32_t *char_out, uint32_t *t35_out)
{
    static const uint8_t req[8] = {0x05, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC4, 0x49};
    static uint32_t st[1000];
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.baud = baud;
    p.opmode = modem ? (uint8_t)MODCP_OPMODE_SUPPRESS : (uint8_t)MODCP_OPMODE_NORMAL;
    p.hr_base_db = 800;
    p.lim_db = (modcp_limit_t){800, 899};
    dbs[0] = (modcp_db_t){800, sizeof db800, db800};
    mem = (modcp_plcmem_t){.dbs = dbs, .db_count = 1};
    uint16_t len = (uint16_t)modcp_params_encode(&p, record, sizeof record);
    modcp_bp_init(&bp);
    modcp_fb_init(&fb, &bp, &mem, record, len, 0, 5000);
    modcp_cp_init(&cp, &hal, &bp);
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    timer_on = 0;
    uint32_t next_cycle = now_us;
    for (int k = 0; k < 50 && !modcp_cp_ready(&cp); k++) {
        modcp_fb_call(&fb, &in, &out, now_us / 1000u);
        modcp_cp_poll(&cp, now_us);
        now_us += cycle_us;
        next_cycle = now_us;
    }
    if (!modcp_cp_ready(&cp) || n > sizeof st / sizeof st[0]) {
        fprintf(stderr, "bench_rx: slave-time setup failed\n");
        exit(1);
    }
    const uint32_t ch = modcp_params_char_us(&p);
    *char_out = ch;
    *t35_out = cp.link.t35_us;
    for (unsigned k = 0; k < n; k++) {
        /* the first byte somewhere in the cycle: k / n of it after a cycle start */
        uint32_t t0 = next_cycle + 3u * cycle_us + (uint32_t)((uint64_t)cycle_us * k / n);
        unsigned sent = 0;
        uint32_t last = 0;
        int tx_on = 0;
        tx_done = 0;
        for (;;) {
            /* the next event: a request byte, the timer, transmission complete, a cycle */
            uint32_t t_byte = t0 + sent * ch, t = next_cycle;
            int ev = 0;
            if (sent < sizeof req && (int32_t)(t_byte - t) < 0) {
                t = t_byte;
                ev = 1;
            }
            if (timer_on && (int32_t)(timer_at - t) < 0) {
                t = timer_at;
                ev = 2;
            }
            if (tx_on && (int32_t)(tx_at + tx_len * ch - t) < 0) {
                t = tx_at + tx_len * ch;
                ev = 3;
            }
            now_us = t;
            if (ev == 1) {
                modcp_cp_on_rx(&cp, req[sent++], now_us);
                last = now_us;
            } else if (ev == 2) {
                timer_on = 0;
                modcp_cp_on_timer(&cp, now_us);
            } else if (ev == 3) {
                modcp_cp_on_tx_done(&cp, now_us);
                break;
            } else {
                modcp_fb_call(&fb, &in, &out, now_us / 1000u);
                modcp_cp_poll(&cp, now_us);
                next_cycle += cycle_us;
            }
            if (tx_done && !tx_on) {
                tx_on = 1;
                st[k] = tx_at + ch - last;
            }
        }
    }
    qsort(st, n, sizeof st[0], cmp_u32);
    return st[n / 2u];
}

static void slave_time(unsigned n)
{
    static const struct {
        uint32_t baud, cycle_us;
    } cases[] = {{9600u, 10000u}, {115200u, 1000u}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        for (int modem = 0; modem < 2; modem++) {
            uint32_t ch, t35;
            uint32_t p50 = slave_time_p50(cases[c].baud, cases[c].cycle_us, modem, n, &ch, &t35);
            /* model: t3.5 (normal) or the 1 us timer (modem) + 1/2 cycle + 1 character */
            uint32_t model = (modem ? 1u : t35) + cases[c].cycle_us / 2u + ch;
            printf("slave_time_us_p50_%s_%lu_cycle%lums=%lu\n", modem ? "modem" : "normal",
                   (unsigned long)cases[c].baud, (unsigned long)(cases[c].cycle_us / 1000u),
                   (unsigned long)p50);
            printf("slave_time_us_model_%s_%lu_cycle%lums=%lu\n", modem ? "modem" : "normal",
                   (unsigned long)cases[c].baud, (unsigned long)(cases[c].cycle_us / 1000u),
                   (unsigned long)model);
        }
    }
}

/* tools/bench --summary: the callgrind numbers of bench_rx.sh, run from the source root
 * (tools/bench's working directory) with this binary's build directory. */
static int summary(const char *argv0)
{
    static const char tail[] = "/tests/bench/bench_rx";
    char cmd[1024];
    size_t n = strlen(argv0);
    if (n < sizeof tail || strcmp(argv0 + n - (sizeof tail - 1u), tail) != 0 ||
        n + 64u > sizeof cmd) {
        fprintf(stderr, "bench_rx --summary: run as <build>/tests/bench/bench_rx\n");
        return 2;
    }
    snprintf(cmd, sizeof cmd, "tests/bench/bench_rx.sh '%.*s'", (int)(n - (sizeof tail - 1u)),
             argv0);
    return system(cmd) == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--summary") == 0) {
        return summary(argv[0]);
    }
    if (argc == 3 && strcmp(argv[1], "slave-time") == 0) {
        slave_time((unsigned)strtoul(argv[2], NULL, 0));
        return 0;
    }
    if (argc < 3 || (strcmp(argv[1], "link") != 0 && strcmp(argv[1], "link-t15") != 0 &&
                     strcmp(argv[1], "link-modem") != 0 && strcmp(argv[1], "link-block") != 0 &&
                     strcmp(argv[1], "cp") != 0)) {
        fprintf(stderr, "usage: bench_rx link|link-t15|link-modem|link-block|cp FRAMES | "
                        "slave-time N | --summary\n");
        return 2;
    }
    const int link_mode = strcmp(argv[1], "cp") != 0;
    unsigned n = (unsigned)strtoul(argv[2], NULL, 0);
    make_frame();
    if (link_mode) {
        link_setup(strcmp(argv[1], "link-t15") == 0, strcmp(argv[1], "link-modem") == 0);
    } else {
        cp_setup();
    }
    int (*one)(void) = !link_mode                             ? cp_frame
                       : strcmp(argv[1], "link-block") == 0 ? link_block_frame
                                                            : link_frame;
    if (!one()) { /* warm up, check */
        fprintf(stderr, "bench_rx: the FC16 request was not %s\n",
                link_mode ? "delivered" : "answered");
        return 1;
    }
    if (!link_mode && tx_len != 8u) {
        fprintf(stderr, "bench_rx: reply length %u, expected 8\n", tx_len);
        return 1;
    }
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    unsigned ok = 0;
    for (unsigned k = 0; k < n; k++) {
        ok += (unsigned)one();
    }
    clock_gettime(CLOCK_MONOTONIC, &b);
    if (ok != n) {
        fprintf(stderr, "bench_rx: %u of %u frames delivered\n", ok, n);
        return 1;
    }
    double ns = ((double)(b.tv_sec - a.tv_sec) * 1e9 + (double)(b.tv_nsec - a.tv_nsec)) /
                ((double)n * FRAME_LEN);
    printf("bytes=%lu\n", (unsigned long)n * FRAME_LEN + FRAME_LEN);
    printf("bench_rx %s: %.1f ns per byte (wall, frame handling included)\n", argv[1], ns);
    return 0;
}
