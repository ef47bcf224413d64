/* SPDX-License-Identifier: Apache-2.0 */
#include "ext_support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "modcp/crc.h"
#include "modcp/hal.h"

uint16_t ext_request(world_t *w, uint8_t addr, const char *pdu_hex, uint32_t max_ms)
{
    uint8_t f[700];
    f[0] = addr;
    size_t n = 1 + hex_frame(pdu_hex, f + 1, sizeof f - 3);
    uint16_t len = world_request_raw(w, f, n, max_ms);
    if (len == 0) {
        return 0;
    }
    assert_true(len >= 4);
    assert_int_equal(w->fake.tx[0], addr);
    assert_int_equal(modcp_crc16(w->fake.tx, len), 0);
    return (uint16_t)(len - 3);
}

const char *ext_reply(const world_t *w)
{
    static char s[2000];
    size_t o = 0;
    s[0] = 0;
    for (uint16_t k = 1; k + 2 < w->fake.tx_len; k++) {
        o += (size_t)snprintf(s + o, sizeof s - o, k > 1 ? " %02X" : "%02X", w->fake.tx[k]);
    }
    return s;
}

void ext_expect(world_t *w, uint8_t addr, const char *pdu_hex, const char *reply_pdu_hex)
{
    uint16_t n = ext_request(w, addr, pdu_hex, 2000);
    assert_true(n > 0);
    assert_string_equal(ext_reply(w), reply_pdu_hex);
}

void ext_expect_exception(world_t *w, uint8_t addr, const char *pdu_hex, uint8_t code,
                          modcp_event_t ev)
{
    uint8_t pdu[300];
    hex_frame(pdu_hex, pdu, sizeof pdu);
    uint16_t n = ext_request(w, addr, pdu_hex, 2000);
    assert_int_equal(n, 2);
    assert_int_equal(w->fake.tx[1], pdu[0] | 0x80);
    assert_int_equal(w->fake.tx[2], code);
    assert_int_equal(world_last_event(w), ev);
}

void ext_expect_silence(world_t *w, uint8_t addr, const char *pdu_hex)
{
    assert_int_equal(ext_request(w, addr, pdu_hex, 100), 0);
}

void ext_bad_crc(world_t *w, uint8_t addr, const char *pdu_hex)
{
    uint8_t f[700];
    f[0] = addr;
    size_t n = 1 + hex_frame(pdu_hex, f + 1, sizeof f - 3);
    n = add_crc(f, n);
    f[n - 1] ^= 0x5A;
    char hex[2200];
    size_t o = 0;
    for (size_t k = 0; k < n; k++) {
        o += (size_t)snprintf(hex + o, sizeof hex - o, "%02X ", f[k]);
    }
    assert_int_equal(world_request(w, hex, 100), 0);
}

void ext_line_error(world_t *w, uint8_t flags)
{
    modcp_cp_on_line_error(&w->cp, flags, w->now_us);
    w->now_us += w->fake.timer_us;
    modcp_cp_on_timer(&w->cp, w->now_us);
    world_run(w, 1000);
}

uint16_t ext_counter(world_t *w, uint8_t addr, uint8_t sub)
{
    char req[32];
    snprintf(req, sizeof req, "08 00 %02X 00 00", sub);
    assert_int_equal(ext_request(w, addr, req, 2000), 5);
    assert_int_equal(w->fake.tx[1], 0x08);
    assert_int_equal(w->fake.tx[3], sub);
    return (uint16_t)((w->fake.tx[4] << 8) | w->fake.tx[5]);
}

world_t *ext_started(const modcp_params_t *p)
{
    world_t *w = world_new(p);
    assert_true(world_start(w, 1000));
    assert_true(modcp_cp_ready(&w->cp));
    return w;
}

modcp_cp_status_t ext_status(world_t *w)
{
    modcp_cp_status_t st;
    world_run(w, 1000); /* the CP publishes in its poll */
    assert_true(modcp_bp_read_status(&w->bp, &st));
    return st;
}
