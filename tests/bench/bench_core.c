/* SPDX-License-Identifier: Apache-2.0 */
#define _POSIX_C_SOURCE 200809L
/* Benchmark: instructions per request through the whole modcp core (bytes in with
 * their CRC, link, PDU, mapping, job over the backplane, FB against memory, reply out),
 * for the requests named on the command line.
 *
 *   bench_core NAME COUNT [bytes|block]
 *
 * bytes (default; what every shipped port runs, tools/bench's headline): one
 * modcp_cp_on_rx per character, every timer expiry due between two characters delivered
 * before the next one (a receive interrupt per byte); block: the request arrives as one
 * block of characters back to back (modcp_cp_on_rx_block, a UART with DMA or a FIFO;
 * libmodbus reads it from its socket in one go too; the block loop exists only at -O2).
 * tools/bench counts, under callgrind, only what runs inside modcp's entry points
 * (--toggle-collect on modcp_cp_on_rx, modcp_cp_on_rx_block, modcp_cp_on_timer,
 * modcp_cp_poll, modcp_fb_call, modcp_cp_on_tx_done), the HAL callbacks they call
 * included, the simulated clock of this harness not; alone it prints wall time. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_requests.h"
#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"

static modcp_backplane_t bp;
static modcp_cp_t cp;
static modcp_fb_t fb;
static modcp_plcmem_t mem;
static modcp_db_t dbs[2];
static uint8_t db800[1024], db900[1024], i_[256], q_[320], m_[2600];
static uint16_t t_[240], c_[240];
static uint8_t record[MODCP_PARAMS_RECORD_MAX];
static uint32_t now_us = 1000000, timer_at;
static uint16_t tx_len;
static int tx_done, timer_on, per_byte;

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

/* The one-shot timer the core arms, fired when due (as a port's timer interrupt would):
 * every expiry due at now_us is delivered, re-arms included. */
static int due(void)
{
    return timer_on && (int32_t)(now_us - timer_at) >= 0;
}

static void fire_due(void)
{
    while (due()) {
        timer_on = 0;
        uint32_t t = now_us;
        now_us = timer_at;
        modcp_cp_on_timer(&cp, now_us);
        now_us = t;
    }
}

static const modcp_hal_t hal = {.ctx = NULL, .uart_tx = f_tx, .timer_arm = f_arm};

static void setup(void)
{
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.coils[0] = (modcp_bitwin_t){MODCP_AREA_M, 0, 2047, 1000, 0};
    p.inputs[1] = (modcp_bitwin_t){MODCP_AREA_I, 4096, 5119, 128, 0};
    p.hr_base_db = 800;
    p.ir_base_db = 900;
    p.lim_db = (modcp_limit_t){800, 899};
    p.lim_m = (modcp_limit_t){1000, 1255};
    dbs[0] = (modcp_db_t){800, sizeof db800, db800};
    dbs[1] = (modcp_db_t){900, sizeof db900, db900};
    mem = (modcp_plcmem_t){.i = i_, .q = q_, .m = m_, .t = t_, .c = c_, .i_size = sizeof i_,
                           .q_size = sizeof q_, .m_size = sizeof m_, .t_count = 240,
                           .c_count = 240, .dbs = dbs, .db_count = 2};
    uint16_t n = (uint16_t)modcp_params_encode(&p, record, sizeof record);
    modcp_bp_init(&bp);
    modcp_fb_init(&fb, &bp, &mem, record, n, 0, 5000);
    modcp_cp_init(&cp, &hal, &bp);
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    for (int k = 0; k < 20 && !modcp_cp_ready(&cp); k++) {
        modcp_fb_call(&fb, &in, &out, now_us / 1000);
        modcp_cp_poll(&cp, now_us);
        now_us += 1000;
    }
    if (!modcp_cp_ready(&cp)) {
        fprintf(stderr, "bench: CP not ready\n");
        exit(1);
    }
}

/* One request: bytes in (every timer expiry due between two bytes delivered before the
 * next byte), the timer's expiries up to the end of the frame, then FB cycles until the
 * reply is out. */
static void one(const uint8_t *req, size_t len)
{
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    tx_done = 0;
    if (per_byte) {
        for (size_t k = 0; k < len; k++) {
            fire_due();
            modcp_cp_on_rx(&cp, req[k], now_us);
            now_us += 1146;
        }
    } else { /* the same characters, handed over at the end of the last one */
        now_us += (uint32_t)(len - 1u) * 1146u;
        modcp_cp_on_rx_block(&cp, req, (uint16_t)len, now_us);
        now_us += 1146;
    }
    while (timer_on) { /* the end-of-frame silence: each expiry at its time (nothing is
                          armed again once the frame is handed over) */
        timer_on = 0;
        now_us = timer_at;
        modcp_cp_on_timer(&cp, now_us);
    }
    while (!tx_done) {
        modcp_fb_call(&fb, &in, &out, now_us / 1000);
        modcp_cp_poll(&cp, now_us);
        now_us += 100;
    }
    modcp_cp_on_tx_done(&cp, now_us);
}

void bench_loop(const uint8_t *req, size_t len, unsigned n);
__attribute__((noinline)) void bench_loop(const uint8_t *req, size_t len, unsigned n)
{
    for (unsigned k = 0; k < n; k++) {
        one(req, len);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench_core NAME COUNT [bytes|block]\n");
        return 2;
    }
    if (argc > 3 && strcmp(argv[3], "bytes") != 0 && strcmp(argv[3], "block") != 0) {
        fprintf(stderr, "bench_core: mode %s: must be bytes or block\n", argv[3]);
        return 2;
    }
    const bench_request_t *r = bench_find(argv[1]);
    unsigned n = (unsigned)strtoul(argv[2], NULL, 0);
    per_byte = !(argc > 3 && strcmp(argv[3], "block") == 0);
    uint8_t frame[BENCH_FRAME_MAX];
    size_t len = bench_frame(r, frame);
    setup();
    one(frame, len); /* warm up, check */
    if (tx_len != r->reply_len) {
        fprintf(stderr, "bench_core: %s: reply length %u, expected %u\n", r->name, tx_len,
                r->reply_len);
        return 1;
    }
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    bench_loop(frame, len, n);
    clock_gettime(CLOCK_MONOTONIC, &b);
    double us = ((double)(b.tv_sec - a.tv_sec) * 1e6 + (double)(b.tv_nsec - a.tv_nsec) / 1e3) / n;
    printf("modcp %s: %.2f us per request (wall, %u requests, %s)\n", r->name, us, n,
           per_byte ? "per byte" : "one block");
    return 0;
}
