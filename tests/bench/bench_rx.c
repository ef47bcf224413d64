#define _POSIX_C_SOURCE 200809L
/* Benchmark: the receive path per byte. Feeds the frames of an FC16 request with 123
 * registers (255 bytes, slave 5, 9600 baud 8E1: one byte every 1146 us) with an
 * injected clock; the one-shot timer the core arms is fired when due, between bytes,
 * as a port's timer interrupt would.
 *
 *   bench_rx link FRAMES   bytes into modcp_link_on_byte() (the link and its framing)
 *   bench_rx link-t15 FRAMES  the same with the t1.5 check on
 *   bench_rx cp FRAMES     bytes into modcp_cp_on_rx() (the port's entry: CP hooks too)
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

#define NREGS 123u
#define FRAME_LEN (7u + 2u * NREGS + 2u) /* 255 */

static uint32_t now_us = 1000000u, timer_at;
static int timer_on, tx_done;
static uint16_t tx_len;
static uint8_t frame[FRAME_LEN];

static void f_tx(void *ctx, const uint8_t *b, uint16_t n)
{
    (void)ctx;
    (void)b;
    tx_len = n;
    tx_done = 1;
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

static void link_setup(int t15)
{
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.t15_check = t15 ? 1u : 0u;
    modcp_diag_init(&diag);
    modcp_link_init(&link_, &hal, &diag, buf, (uint16_t)sizeof buf);
    modcp_link_configure(&link_, &p);
    char_us = modcp_params_char_us(&p);
}

/* One frame into the link; returns 1 when it was delivered as a request. */
static int link_frame(void)
{
    int got = 0;
    for (unsigned k = 0; k < FRAME_LEN; k++) {
        if (due()) {
            timer_on = 0;
            now_us = timer_at;
            (void)modcp_link_on_timer(&link_, now_us, &fr);
        }
        modcp_link_on_byte(&link_, frame[k], now_us);
        now_us += char_us;
    }
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

int main(int argc, char **argv)
{
    if (argc < 3 || (strcmp(argv[1], "link") != 0 && strcmp(argv[1], "link-t15") != 0 &&
                     strcmp(argv[1], "cp") != 0)) {
        fprintf(stderr, "usage: bench_rx link|link-t15|cp FRAMES\n");
        return 2;
    }
    const int link_mode = strcmp(argv[1], "cp") != 0;
    unsigned n = (unsigned)strtoul(argv[2], NULL, 0);
    make_frame();
    if (link_mode) {
        link_setup(strcmp(argv[1], "link-t15") == 0);
    } else {
        cp_setup();
    }
    int (*one)(void) = link_mode ? link_frame : cp_frame;
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
