/* SPDX-License-Identifier: Apache-2.0 */
/* Block reception (modcp_cp_on_rx_block, for UARTs with DMA or a FIFO): n characters
 * back to back handed over at the end of the last one have exactly the effect of the
 * same characters one by one (modcp_cp_on_rx at each character's end). Every case runs
 * twice on the simulated line (lineworld.h, exact time, 9600 baud 8E1: one character
 * = 1146 us, t3.5 = 4000 us), byte by byte and in blocks, and asserts
 *   - the same HAL calls at the same times (replies, DE, transmission; left out: the
 *     one-shot's arming, less often in blocks while the frame still ends at the same
 *     time, and the LEDs: the RXD LED, read at poll time, sees a block only when it is
 *     handed over; RTS / DTR are compared without their times, see same_log),
 *   - the same reply bytes, diagnostic buffer, counters and controller memory,
 * and, besides, what the case must give (reply, event, counter), so that both cannot
 * be wrong together. A block holds no silence: it never contains the end of one frame
 * and the start of the next (blocks are cut where the line was silent). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "lineworld.h"
#include "world.h"
#include "link_internal.h"

#define FC03_REQ "05 03 00 50 00 02 C5 9E" /* [RTU-2003] §6.3 */
#define FC03_RSP "05 03 04 87 65 43 21 76 70"
#define T35_US 4000u
#define T15_US 1719u

/* Where a new block starts: at byte `at`, after `gap_us` of silence on the line (more
 * than the character time that separates back-to-back characters). */
typedef struct {
    size_t at;
    uint32_t gap_us;
} cut_t;

typedef struct {
    uint8_t b[1200];
    size_t n;
    cut_t cuts[300];
    size_t ncuts;
} line_t;

/* A new block after gap_us of silence (none before the line's first byte). */
static void cut(line_t *l, uint32_t gap_us)
{
    if (l->n > 0 || gap_us > 0) {
        l->cuts[l->ncuts++] = (cut_t){l->n, gap_us};
    }
}

static void add_hex(line_t *l, const char *hex, uint32_t gap_us)
{
    cut(l, gap_us);
    l->n += hex_frame(hex, &l->b[l->n], sizeof l->b - l->n);
}

static void add_bytes(line_t *l, const uint8_t *b, size_t n, uint32_t gap_us)
{
    assert_true(n <= sizeof l->b - l->n);
    cut(l, gap_us);
    memcpy(&l->b[l->n], b, n);
    l->n += n;
}

static void add_text(line_t *l, const char *text, uint32_t gap_us)
{
    add_bytes(l, (const uint8_t *)text, strlen(text), gap_us);
}

/* Split the last block at byte `at` (no silence: the port handed it over in parts). */
static void split(line_t *l, size_t at)
{
    l->cuts[l->ncuts++] = (cut_t){at, 0};
}

static uint32_t gap_before(const line_t *l, size_t i, bool *cut)
{
    *cut = false;
    for (size_t c = 0; c < l->ncuts; c++) {
        if (l->cuts[c].at == i) {
            *cut = true;
            return l->cuts[c].gap_us;
        }
    }
    return 0;
}

/* Feed the line from the current time, then run `ms` milliseconds. */
static void feed(lw_t *x, const line_t *l, bool blocks, uint32_t ms)
{
    uint32_t t = lw_now(x);
    size_t start = 0;
    for (size_t i = 0; i < l->n; i++) {
        bool cut;
        uint32_t gap = gap_before(l, i, &cut);
        if (i > 0) {
            t += x->char_us;
        }
        t += gap;
        if (!blocks) {
            lw_advance(x, t);
            lw_byte(x, l->b[i]);
            continue;
        }
        assert_true(!cut || i == start); /* the block before it was handed over */
        bool last = i + 1 == l->n;
        bool next_cut;
        (void)gap_before(l, i + 1, &next_cut);
        if (last || next_cut) {
            lw_advance(x, t);
            modcp_cp_on_rx_block(&x->w->cp, &l->b[start], (uint16_t)(i + 1 - start), t);
            start = i + 1;
        }
    }
    lw_advance(x, t + ms * 1000u);
}

static lw_t *world(const modcp_params_t *p)
{
    lw_t *x = lw_new(p);
    memcpy(world_db(x->w, 800) + 160, "\x87\x65\x43\x21", 4); /* DBW160/162 for FC03 */
    if (p->rs232_auto) {
        lw_signals(x, true, true); /* CTS and DSR ON */
    }
    lw_clear(x);
    return x;
}

static void same_diag(const modcp_diag_t *a, const modcp_diag_t *b)
{
    assert_int_equal(a->buffer_len, b->buffer_len);
    assert_memory_equal(a->buffer, b->buffer, a->buffer_len * sizeof a->buffer[0]);
    assert_memory_equal(a->counters, b->counters, sizeof a->counters);
    assert_int_equal(a->events_total, b->events_total);
    assert_int_equal(a->status, b->status);
    assert_int_equal(a->frames_too_long, b->frames_too_long);
    assert_int_equal(a->char_errors, b->char_errors);
    assert_int_equal(a->breaks, b->breaks);
    assert_int_equal(a->t15_discards, b->t15_discards);
}

/* The HAL calls but the one-shot's arming and the LEDs, in order, with their times
 * (the RXD LED, read at poll time, sees a block when it is handed over); RTS / DTR
 * without their times: a character that ends the time to RTS off switches RTS when
 * the core sees it, i.e. when its block is handed over. */
static void same_log(const lw_t *a, const lw_t *b)
{
    size_t i = 0, j = 0;
    for (;;) {
        while (i < a->n && (a->log[i].kind == LW_ARM || a->log[i].kind == LW_LED)) {
            i++;
        }
        while (j < b->n && (b->log[j].kind == LW_ARM || b->log[j].kind == LW_LED)) {
            j++;
        }
        if (i == a->n || j == b->n) {
            break;
        }
        assert_int_equal(a->log[i].kind, b->log[j].kind);
        assert_int_equal(a->log[i].value, b->log[j].value);
        if (a->log[i].kind != LW_SIG) {
            assert_int_equal(a->log[i].at, b->log[j].at);
        }
        i++;
        j++;
    }
    assert_int_equal(i, a->n);
    assert_int_equal(j, b->n);
}

/* Runs the line byte by byte and in blocks, asserts both give the same, returns the
 * block world (the caller asserts what the case must give, then frees it). */
static lw_t *both(const modcp_params_t *p, const line_t *l, uint32_t ms)
{
    lw_t *a = world(p);
    lw_t *b = world(p);
    feed(a, l, false, ms);
    feed(b, l, true, ms);
    same_log(a, b);
    assert_int_equal(a->tx_calls, b->tx_calls);
    assert_int_equal(a->tx_len, b->tx_len);
    assert_memory_equal(a->tx, b->tx, a->tx_len);
    same_diag(&a->w->cp.diag, &b->w->cp.diag);
    assert_memory_equal(a->w->db_data, b->w->db_data, sizeof a->w->db_data);
    assert_memory_equal(a->w->m, b->w->m, sizeof a->w->m);
    assert_int_equal(a->w->cp.link.state, b->w->cp.link.state);
    assert_int_equal(a->w->cp.link.last_us, b->w->cp.link.last_us);
    lw_free(a);
    return b;
}

static modcp_params_t example(void)
{
    modcp_params_t p;
    world_example_params(&p);
    return p;
}

static const uint16_t *cnt(const lw_t *x)
{
    return x->w->cp.diag.counters;
}

/* A request for us in one block: the manual's reply. */
static void test_frame_for_us(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    add_hex(&l, FC03_REQ, 0);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_int_equal(cnt(x)[MODCP_CNT_SLAVE_MSG], 1);
    lw_free(x);
}

/* The same request handed over in three parts (DMA half / full / idle line). */
static void test_frame_split_over_blocks(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    add_hex(&l, FC03_REQ, 0);
    split(&l, 3);
    split(&l, 6);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

/* Another slave's frame: counted on the bus, not answered. */
static void test_other_address(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    uint8_t f[8] = {6, 3, 0x00, 0x50, 0x00, 0x02};
    add_crc(f, 6);
    add_bytes(&l, f, 8, 0);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(cnt(x)[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(cnt(x)[MODCP_CNT_SLAVE_MSG], 0);
    lw_free(x);
}

/* Broadcast FC06 (DB 800 DBW160 := 1234H): executed, not answered. */
static void test_broadcast(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    uint8_t f[8] = {0, 6, 0x00, 0x50, 0x12, 0x34};
    add_crc(f, 6);
    add_bytes(&l, f, 8, 0);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 0);
    assert_memory_equal(world_db(x->w, 800) + 160, "\x12\x34", 2);
    assert_int_equal(cnt(x)[MODCP_CNT_NO_RESPONSE], 1);
    lw_free(x);
}

/* A CRC error: (08)36H, counted, no reply. */
static void test_crc_error(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    add_hex(&l, "05 03 00 50 00 02 C5 9F", 0);
    split(&l, 5);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 0);
    assert_int_equal(world_last_event(x->w), MODCP_EV_CRC);
    assert_int_equal(cnt(x)[MODCP_CNT_BUS_CRC], 1);
    lw_free(x);
}

/* A frame for us longer than the buffer, in one block and in parts (the first one
 * 254 characters, then blocks of 3: each handed over before t3.5 could pass after the
 * one before, see docs/porting.md): (08)16H. */
static void test_overflow(void **state)
{
    (void)state;
    modcp_params_t p = example();
    for (int parts = 0; parts < 2; parts++) {
        line_t l = {0};
        char hex[3 * 300 + 1];
        for (size_t i = 0; i < 300; i++) {
            snprintf(&hex[3 * i], 4, "%02X ", i == 0 ? 5u : (unsigned)(i & 0xFFu));
        }
        add_hex(&l, hex, 0);
        for (size_t at = 254; parts && at < 300; at += 3) {
            split(&l, at);
        }
        lw_t *x = both(&p, &l, 50);
        assert_int_equal(x->tx_calls, 0);
        assert_int_equal(world_last_event(x->w), MODCP_EV_FRAME_TOO_LONG);
        assert_int_equal(x->w->cp.diag.frames_too_long, 1);
        lw_free(x);
    }
}

/* The t1.5 check: a silence of exactly t1.5 between two blocks is accepted, 1 us more
 * discards the frame ((08)06H, counted); inside a block there is no silence at all.
 * After the silence one character, then the last three (each block handed over
 * before t3.5 could pass after the one before). */
static void test_t15(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.t15_check = 1;
    for (uint32_t extra = 0; extra < 2; extra++) {
        line_t l = {0};
        add_hex(&l, FC03_REQ, 0);
        l.cuts[l.ncuts++] = (cut_t){4, T15_US + extra};
        split(&l, 5);
        lw_t *x = both(&p, &l, 50);
        if (extra == 0) {
            assert_int_equal(x->tx_calls, 1);
            assert_string_equal(lw_tx_hex(x), FC03_RSP);
        } else {
            assert_int_equal(x->tx_calls, 0);
            assert_int_equal(world_last_event(x->w), MODCP_EV_ZVZ);
            assert_int_equal(x->w->cp.diag.t15_discards, 1);
        }
        lw_free(x);
    }
    /* a request in one block with the check on */
    line_t l = {0};
    add_hex(&l, FC03_REQ, 0);
    lw_t *x = both(&p, &l, 50);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_int_equal(x->w->cp.diag.t15_discards, 0);
    lw_free(x);
}

/* Two requests in a row, the second one's block after the first one's t3.5 while the
 * first is still being processed: (08)37H, as byte by byte; then a third one, later,
 * is answered. */
static void test_frames_in_a_row(void **state)
{
    (void)state;
    modcp_params_t p = example();
    line_t l = {0};
    add_hex(&l, FC03_REQ, 0);
    add_hex(&l, FC03_REQ, T35_US + 100u);
    add_hex(&l, FC03_REQ, 60000u);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 2);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    assert_true(x->w->cp.diag.events_total >= 1);
    bool seq = false;
    for (size_t i = 0; i < x->w->cp.diag.buffer_len; i++) {
        seq = seq || x->w->cp.diag.buffer[i] == MODCP_EV_SEQUENCE;
    }
    assert_true(seq);
    lw_free(x);
}

/* Interference suppression (modem mode): the same block path as normal operation. */
static void test_modem_mode(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.opmode = MODCP_OPMODE_SUPPRESS;
    line_t l = {0};
    add_hex(&l, "FF 00", 0); /* noise before the request */
    add_hex(&l, FC03_REQ, 2000u);
    split(&l, 2 + 5);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 1);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}

#if MODCP_WITH_ASCII
/* ASCII: per character through its backend (FC08 sub-function 0, answered by the CP). */
static void test_ascii(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 7;
    p.parity = MODCP_PARITY_EVEN;
    p.stop_bits = 1;
    line_t l = {0};
    add_text(&l, ":05080000A5C38B\r\n", 0);
    split(&l, 9);
    lw_t *x = both(&p, &l, 50);
    assert_int_equal(x->tx_calls, 1);
    assert_int_equal(x->tx_len, 17);
    assert_memory_equal(x->tx, ":05080000A5C38B\r\n", 17);
    lw_free(x);
}
#endif

#if MODCP_WITH_RS232_SIGNALS
/* RS232 automatic signals: per character through the signal logic. The second request
 * comes while RTS is still ON after the first reply (time to RTS off): RTS goes OFF
 * and the request is received normally. */
static void test_rs232_signals(void **state)
{
    (void)state;
    modcp_params_t p = example();
    p.rs232_auto = 1;
    p.rts_on_delay_ms = 10;
    p.rts_off_delay_ms = 20;
    line_t l = {0};
    add_hex(&l, FC03_REQ, 0);
    add_hex(&l, FC03_REQ, 30000u);
    split(&l, 8 + 3);
    split(&l, 8 + 6);
    lw_t *x = both(&p, &l, 100);
    assert_int_equal(x->tx_calls, 2);
    assert_string_equal(lw_tx_hex(x), FC03_RSP);
    lw_free(x);
}
#endif

/* Random lines, byte by byte and in blocks: requests for us, for another slave,
 * broadcasts, CRC errors and noise, with silences inside a frame (below and above
 * t1.5) and between frames, t1.5 check and interference suppression on or off; cut
 * into blocks at random wherever the port contract allows (each block handed over
 * less than t3.5 after the character before it). */
static uint32_t rnd_state = 12345u;
static uint32_t rnd(uint32_t n)
{
    rnd_state ^= rnd_state << 13;
    rnd_state ^= rnd_state >> 17;
    rnd_state ^= rnd_state << 5;
    return rnd_state % n;
}

static void test_random_lines(void **state)
{
    (void)state;
    const uint32_t c = 1146u;
    unsigned replies = 0, frames = 0;
    for (int run = 0; run < 60; run++) {
        modcp_params_t p = example();
        p.t15_check = rnd(2) ? 1u : 0u;
        p.opmode = rnd(4) == 0 ? MODCP_OPMODE_SUPPRESS : MODCP_OPMODE_NORMAL;
        line_t l = {0};
        size_t nseg = 3u + rnd(6);
        bool answered = false; /* modem mode: the segment before ended a frame at its CRC */
        for (size_t seg = 0; seg < nseg && l.n < 900u; seg++) {
            uint8_t f[64];
            size_t n;
            uint32_t kind = rnd(6);
            switch (kind) {
            case 0: /* FC03 for us */
            case 1:
                n = hex_frame(FC03_REQ, f, sizeof f);
                break;
            case 2: /* another slave or a broadcast FC06 */
                f[0] = rnd(2) ? 6u : 0u;
                f[1] = 6u;
                f[2] = 0x00;
                f[3] = 0x50;
                f[4] = (uint8_t)rnd(256);
                f[5] = (uint8_t)rnd(256);
                n = add_crc(f, 6);
                break;
            case 3: /* a CRC error */
                n = hex_frame(FC03_REQ, f, sizeof f);
                f[n - 1u] ^= (uint8_t)(1u + rnd(255));
                break;
            default: /* noise, sometimes starting with our address */
                n = 1u + rnd(12);
                for (size_t i = 0; i < n; i++) {
                    f[i] = (uint8_t)rnd(256);
                }
                if (rnd(2)) {
                    f[0] = 5u;
                }
                break;
            }
            /* a master does not talk while we answer: in interference suppression a
             * frame ends at its valid CRC, so after one only a new frame follows (what
             * falls within a block's span is seen after it, docs/porting.md) */
            uint32_t gap;
            switch (seg == 0 || answered ? 3u : rnd(4)) {
            case 0:
                gap = 0; /* the same frame goes on */
                break;
            case 1:
                gap = rnd(T15_US + 1u); /* within t1.5 */
                break;
            case 2:
                gap = T15_US + 1u + rnd(T35_US - c - T15_US - 1u); /* over t1.5, under t3.5 */
                break;
            default:
                gap = 60000u + rnd(20000u); /* a new frame, the last one answered */
                break;
            }
            answered = p.opmode == MODCP_OPMODE_SUPPRESS && kind <= 2u;
            size_t start = l.n;
            add_bytes(&l, f, n, gap);
            /* blocks: the first one after a silence that continues the frame may span
             * less than t3.5 - gap, every later one at most 3 characters (< t3.5) */
            size_t at = start;
            size_t first_max = gap + c >= T35_US ? 30u : (T35_US - 1u - gap) / c;
            bool first = true;
            while (at < l.n) {
                size_t max = first ? first_max : 3u;
                size_t k = 1u + rnd((uint32_t)max);
                at += k;
                if (at < l.n) {
                    split(&l, at);
                }
                first = false;
            }
        }
        lw_t *x = both(&p, &l, 200);
        replies += x->tx_calls;
        frames += x->w->cp.diag.counters[MODCP_CNT_BUS_MSG] + x->w->cp.diag.counters[MODCP_CNT_BUS_CRC];
        lw_free(x);
    }
    /* the lines were not all noise: requests were answered, frames counted */
    assert_true(replies >= 20u);
    assert_true(frames >= 60u);
}

/* An empty block changes nothing. */
static void test_empty_block(void **state)
{
    (void)state;
    modcp_params_t p = example();
    lw_t *x = world(&p);
    modcp_cp_on_rx_block(&x->w->cp, (const uint8_t *)"", 0, lw_now(x));
    assert_int_equal(x->w->cp.link.state, MODCP_LINK_IDLE);
    assert_int_equal(x->n, 0);
    lw_free(x);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_for_us),
        cmocka_unit_test(test_frame_split_over_blocks),
        cmocka_unit_test(test_other_address),
        cmocka_unit_test(test_broadcast),
        cmocka_unit_test(test_crc_error),
        cmocka_unit_test(test_overflow),
        cmocka_unit_test(test_t15),
        cmocka_unit_test(test_frames_in_a_row),
        cmocka_unit_test(test_modem_mode),
#if MODCP_WITH_ASCII
        cmocka_unit_test(test_ascii),
#endif
#if MODCP_WITH_RS232_SIGNALS
        cmocka_unit_test(test_rs232_signals),
#endif
        cmocka_unit_test(test_random_lines),
        cmocka_unit_test(test_empty_block),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
