/* SPDX-License-Identifier: Apache-2.0 */
#include "world.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "example_params.h"
#include "frames.h"
#include "diag_internal.h"

static const uint16_t db_numbers[WORLD_DBS] = {WORLD_WORK_DB, 800, 801, 802, 900, 901, 910};

static void fake_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    fake_hal_t *f = ctx;
    assert_true(len <= sizeof f->tx);
    memcpy(f->tx, buf, len);
    f->tx_len = len;
    f->tx_count++;
}

static void fake_arm(void *ctx, uint32_t us)
{
    ((fake_hal_t *)ctx)->timer_us = us;
}

static void fake_de(void *ctx, bool on)
{
    fake_hal_t *f = ctx;
    f->de = on;
    if (on) {
        f->de_on_count++;
    }
}

static void fake_rx_preset(void *ctx, uint8_t preset)
{
    ((fake_hal_t *)ctx)->rx_preset = preset;
}

void world_example_params(modcp_params_t *p)
{
    example_params(p);
}

world_t *world_new(const modcp_params_t *p)
{
    world_t *w = calloc(1, sizeof *w);
    assert_non_null(w);
    if (p != NULL) {
        w->params = *p;
    } else {
        world_example_params(&w->params);
    }
    for (unsigned k = 0; k < WORLD_DBS; k++) {
        w->dbs[k].number = db_numbers[k];
        w->dbs[k].size = k == 0 ? 64 : 1024;
        w->dbs[k].data = w->db_data[k];
    }
    w->mem = (modcp_plcmem_t){.i = w->i, .q = w->q, .m = w->m, .t = w->t, .c = w->c,
                              .i_size = sizeof w->i, .q_size = sizeof w->q, .m_size = sizeof w->m,
                              .t_count = 240, .c_count = 240, .dbs = w->dbs,
                              .db_count = WORLD_DBS};
    w->hal = (modcp_hal_t){.ctx = &w->fake, .uart_tx = fake_tx, .timer_arm = fake_arm,
                           .set_de = fake_de, .set_rx_preset = fake_rx_preset};
    w->fake.rx_preset = -1;
    size_t n = modcp_params_encode(&w->params, w->record, sizeof w->record);
    assert_true(n > 0);
    w->record_len = (uint16_t)n;
    modcp_bp_init(&w->bp);
    modcp_fb_init(&w->fb, &w->bp, &w->mem, w->record, w->record_len, WORLD_WORK_DB,
                  w->params.start_time_ms ? w->params.start_time_ms : 5000u);
    modcp_cp_init(&w->cp, &w->hal, &w->bp);
    w->now_us = 1000000; /* not at zero: catches time-origin assumptions */
    return w;
}

void world_free(world_t *w)
{
    free(w);
}

static void step(world_t *w, bool cp_start)
{
    if (!w->fb_paused) {
        modcp_fb_in_t in = {cp_start};
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    }
    modcp_cp_poll(&w->cp, w->now_us);
}

bool world_start_keep(world_t *w, uint32_t max_ms)
{
    for (uint32_t ms = 0; ms < max_ms; ms++) {
        step(w, true);
        if (w->fb_out.cp_start_ok || w->fb_out.cp_start_error) {
            break;
        }
        w->now_us += 1000;
    }
    return w->fb_out.cp_start_ok;
}

bool world_start(world_t *w, uint32_t max_ms)
{
    bool ok = world_start_keep(w, max_ms);
    if (w->cp.diag.buffer_len == 1u && w->cp.diag.buffer[0] == MODCP_EV_PARAMS_TAKEN) {
        modcp_diag_clear_buffer(&w->cp.diag); /* a plain start's (00)03H: see world.h */
    }
    return ok;
}

void world_run(world_t *w, uint32_t us)
{
    uint32_t end = w->now_us + us;
    while ((int32_t)(end - w->now_us) > 0) {
        uint32_t d = end - w->now_us < 1000u ? end - w->now_us : 1000u;
        w->now_us += d;
        step(w, true);
    }
}

uint16_t world_request_raw(world_t *w, const uint8_t *frame, size_t len, uint32_t max_ms)
{
    uint8_t buf[700];
    assert_true(len + 2 <= sizeof buf);
    memcpy(buf, frame, len);
    len = add_crc(buf, len);
    char hex[2200];
    size_t o = 0;
    for (size_t k = 0; k < len; k++) {
        o += (size_t)snprintf(hex + o, sizeof hex - o, "%02X ", buf[k]);
    }
    return world_request(w, hex, max_ms);
}

uint16_t world_request(world_t *w, const char *hex, uint32_t max_ms)
{
    uint8_t frame[700];
    size_t n = hex_frame(hex, frame, sizeof frame);
    unsigned before = w->fake.tx_count;
    w->fake.tx_len = 0;
    for (size_t k = 0; k < n; k++) {
        modcp_cp_on_rx(&w->cp, frame[k], w->now_us);
        w->now_us += 10; /* bytes back to back, well inside t1.5 */
    }
    /* end of frame: the timer the link armed expires */
    uint32_t t35 = w->fake.timer_us;
    w->now_us += t35;
    modcp_cp_on_timer(&w->cp, w->now_us);
    for (uint32_t ms = 0; ms < max_ms && w->fake.tx_count == before; ms++) {
        w->now_us += 1000;
        step(w, true);
    }
    if (w->fake.tx_count == before) {
        return 0;
    }
    modcp_cp_on_tx_done(&w->cp, w->now_us);
    return w->fake.tx_len;
}

const char *world_reply_hex(const world_t *w)
{
    static char s[2000];
    size_t o = 0;
    s[0] = 0;
    for (uint16_t k = 0; k < w->fake.tx_len; k++) {
        o += (size_t)snprintf(s + o, sizeof s - o, k ? " %02X" : "%02X", w->fake.tx[k]);
    }
    return s;
}

modcp_event_t world_last_event(const world_t *w)
{
    return w->cp.diag.buffer_len ? w->cp.diag.buffer[0] : MODCP_EV_NONE;
}

uint8_t *world_db(world_t *w, uint16_t number)
{
    for (unsigned k = 0; k < WORLD_DBS; k++) {
        if (w->dbs[k].number == number) {
            return w->dbs[k].data;
        }
    }
    return NULL;
}
