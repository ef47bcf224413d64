/* SPDX-License-Identifier: Apache-2.0 */
#include "ascii_world.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "modcp/crc.h"

#define DB2_SIZE 4000u  /* 2000 int16 registers: last DB2.DBW3998 */
#define DB3_SIZE 400u   /* 100 int32 registers: last DB3.DBD396 */
#define DB4_SIZE 12000u /* 3000 float registers: last DB4.DBD11996 */

void ascii_example_params(modcp_params_t *p)
{
    world_example_params(p);
    p->framing = MODCP_FRAMING_ASCII;
    p->data_bits = 7;
    p->parity = MODCP_PARITY_EVEN;
    p->stop_bits = 1;
}

void regs32_example_ranges(modcp_params_t *p)
{
    p->regs32 = 1;
    p->r32[MODCP_R32_INT16] = (modcp_r32range_t){3000, 4999, 2};
    p->r32[MODCP_R32_INT32] = (modcp_r32range_t){5000, 5099, 3};
    p->r32[MODCP_R32_FLOAT] = (modcp_r32range_t){7000, 9999, 4};
    p->lim_db = (modcp_limit_t){2, 899};
}

world_t *ascii_world_started(const modcp_params_t *p)
{
    world_t *w = world_new(p);
    uint8_t *big = calloc(1, DB2_SIZE + DB3_SIZE + DB4_SIZE);
    assert_non_null(big);
    /* the harness's DBs are {80, 800, 801, 802, 900, 901, 910} (sorted): keep the
     * storage of 80, 800, 901 and 802 (as 805); DB2..4 come from `big` */
    modcp_db_t dbs[WORLD_DBS] = {
        {2, DB2_SIZE, big},
        {3, DB3_SIZE, big + DB2_SIZE},
        {4, DB4_SIZE, big + DB2_SIZE + DB3_SIZE},
        {WORLD_WORK_DB, 64, w->db_data[0]},
        {800, 1024, w->db_data[1]},
        {805, 1024, w->db_data[3]},
        {901, 1024, w->db_data[5]},
    };
    memcpy(w->dbs, dbs, sizeof dbs);
    assert_true(world_start(w, 1000));
    assert_true(modcp_cp_ready(&w->cp));
    return w;
}

void ascii_world_free(world_t *w)
{
    free(w->dbs[0].data);
    world_free(w);
}

void ascii_feed_bytes(world_t *w, const uint8_t *b, size_t n, uint32_t gap_us)
{
    for (size_t k = 0; k < n; k++) {
        w->now_us += gap_us;
        modcp_cp_on_rx(&w->cp, b[k], w->now_us);
    }
}

void ascii_feed(world_t *w, const char *text, uint32_t gap_us)
{
    ascii_feed_bytes(w, (const uint8_t *)text, strlen(text), gap_us);
}

bool ascii_fire(world_t *w)
{
    uint32_t us = w->fake.timer_us;
    if (us == 0u) {
        return false;
    }
    w->fake.timer_us = 0; /* one-shot */
    w->now_us += us;
    modcp_cp_on_timer(&w->cp, w->now_us);
    return true;
}

uint16_t ascii_finish(world_t *w, uint32_t max_ms)
{
    unsigned before = w->fake.tx_count;
    (void)ascii_fire(w);
    for (uint32_t ms = 0; ms < max_ms && w->fake.tx_count == before; ms++) {
        world_run(w, 1000);
    }
    if (w->fake.tx_count == before) {
        return 0;
    }
    modcp_cp_on_tx_done(&w->cp, w->now_us);
    return w->fake.tx_len;
}

uint16_t ascii_request(world_t *w, const char *text, uint32_t max_ms)
{
    w->fake.tx_len = 0;
    ascii_feed(w, text, ASCII_CHAR_US);
    return ascii_finish(w, max_ms);
}

const char *ascii_reply(const world_t *w)
{
    static char s[2400];
    size_t o = 0;
    for (uint16_t k = 0; k < w->fake.tx_len && o + 5 < sizeof s; k++) {
        uint8_t c = w->fake.tx[k];
        if (c >= 0x20u && c < 0x7Fu) {
            s[o++] = (char)c;
        } else if (c == '\r') {
            s[o++] = '\r';
        } else if (c == '\n') {
            s[o++] = '\n';
        } else {
            o += (size_t)snprintf(s + o, sizeof s - o, "\\x%02X", c);
        }
    }
    s[o] = 0;
    return s;
}

const char *ascii_frame(const uint8_t *bin, size_t n)
{
    static char s[2 * 300 + 8];
    assert_true(n <= 300);
    size_t o = 0;
    s[o++] = ':';
    for (size_t k = 0; k < n; k++) {
        o += (size_t)snprintf(s + o, sizeof s - o, "%02X", bin[k]);
    }
    o += (size_t)snprintf(s + o, sizeof s - o, "%02X\r\n", modcp_lrc(bin, n));
    return s;
}

const char *ascii_frame_hex(const char *hex)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b);
    return ascii_frame(b, n);
}

bool world_has_event(const world_t *w, modcp_event_t ev)
{
    for (uint8_t k = 0; k < w->cp.diag.buffer_len; k++) {
        if (w->cp.diag.buffer[k] == ev) {
            return true;
        }
    }
    return false;
}
