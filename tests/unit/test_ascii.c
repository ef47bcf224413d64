/* SPDX-License-Identifier: Apache-2.0 */
/* Modbus ASCII framing ([ASCII-32] §2 = manual §8.1, docs/ascii-and-32bit.md), end to end through the core:
 * characters in -> ascii.c -> PDU engine -> mapping -> job -> FB -> reply out as text.
 * Every ASCII frame of [ASCII-32] §2 (the telegram example of §8.1 and the vectors worked out
 * from the §9 examples), every receive error with its event, the ASCII quantity limits
 * of [ASCII-32] §5 / §8.5 (08)32H, the character delay time, and the encoder at the largest
 * reply. The 32-bit frames of the list are in test_regs32.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "ascii_world.h"
#include "fake_hal_log.h"
#include "frames.h"
#include "modcp/crc.h"
#include "modcp/link.h"
#include "diag_internal.h"
#include "link_internal.h"

static world_t *ascii_started(void)
{
    modcp_params_t p;
    ascii_example_params(&p);
    return ascii_world_started(&p);
}

static void expect_ascii(world_t *w, const char *req, const char *reply)
{
    uint16_t n = ascii_request(w, req, 200);
    assert_int_equal(n, strlen(reply));
    assert_string_equal(ascii_reply(w), reply);
}

static void expect_ascii_silence(world_t *w, const char *req)
{
    assert_int_equal(ascii_request(w, req, 200), 0);
}

/* ---- [ASCII-32] §2 frames ------------------------------------------------------------- */

/* [ASCII-32] §8.1 telegram example: FC08 echo to slave 5, LRC 8B (computed in [ASCII-32] §2);
 * [ASCII-32] (A) 4: accepted and echoed byte-identically. */
static void test_telegram_example_fc08(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    /* the bytes on the line: 3A 30 35 30 38 ... 0D 0A */
    assert_memory_equal(w->fake.tx, "\x3A\x30\x35\x30\x38\x30\x30\x30\x30\x41\x35\x43\x33",
                        13);
    assert_int_equal(w->fake.tx[15], 0x0D);
    assert_int_equal(w->fake.tx[16], 0x0A);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_SLAVE_MSG], 1);
    ascii_world_free(w);
}

/* [ASCII-32] §9.3 FC03 (base DB 800): 0050H -> DB800.DBW160, 162 */
static void test_fc03_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    expect_ascii(w, ":050300500002A6\r\n", ":05030487654321A4\r\n");
    ascii_world_free(w);
}

/* [ASCII-32] §8.2 exception example `05 85 02`: FC05 to coil 3000 (no window) */
static void test_exception_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ascii_frame_hex("05 05 0B B8 FF 00"), ":05850274\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_NO_WINDOW);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], 1);
    ascii_world_free(w);
}

/* [ASCII-32] §9.6 FC05: 2057 -> Q257.1 set; the reply is the echo */
static void test_fc05_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    w->q[257] = 0x40;
    expect_ascii(w, ":05050809FF00E6\r\n", ":05050809FF00E6\r\n");
    assert_int_equal(w->q[257], 0x42);
    ascii_world_free(w);
}

/* [ASCII-32] §9.10 FC15: 1153 -> M1144.1 ... M1145.4 (12 bits), other bits untouched */
static void test_fc15_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    w->m[1144] = 0x01; /* M1144.0 outside the request: kept */
    w->m[1145] = 0xE0; /* M1145.5..7 outside: kept */
    expect_ascii(w, ":050F0481000C02CD0983\r\n", ":050F0481000C5B\r\n");
    /* bits 1..8 of the stream = CD (1100 1101), bits 9..12 = 9 (1001) low nibble */
    /* M1144.1.. <- CD bits 0..6, M1145.0 <- CD bit 7, M1145.1..4 <- 09 bits 0..3 */
    assert_int_equal(w->m[1144], (uint8_t)(0x01 | (0xCD << 1)));
    assert_int_equal(w->m[1145], (uint8_t)(0xE0 | (0xCD >> 7) | (0x09 << 1)));
    ascii_world_free(w);
}

/* [ASCII-32] §9.1 FC01: 64 -> M1008.0, 32 bits */
static void test_fc01_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    memcpy(&w->m[1008], "\x01\x17\x02\x18", 4);
    expect_ascii(w, ":0501004000209A\r\n", ":05010401170218C4\r\n");
    ascii_world_free(w);
}

/* [ASCII-32] §9.2 FC02: 4144 -> I134.0, 24 bits */
static void test_fc02_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    memcpy(&w->i[134], "\x12\x34\x56", 3);
    expect_ascii(w, ":050210300018A1\r\n", ":0502031234565A\r\n");
    ascii_world_free(w);
}

/* [ASCII-32] §9.5 FC04 (base DB 900): 02C0H -> DB901.DBW384, 3 registers */
static void test_fc04_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    memcpy(world_db(w, 901) + 384, "\xA1\xA2\xA3\xA4\xA5\xA6", 6);
    expect_ascii(w, ":050402C0000332\r\n", ":050406A1A2A3A4A5A61C\r\n");
    ascii_world_free(w);
}

/* [ASCII-32] §9.7 FC06 standard: 0180H -> DB800.DBW768 */
static void test_fc06_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ":050601802B1A2F\r\n", ":050601802B1A2F\r\n");
    assert_memory_equal(world_db(w, 800) + 768, "\x2B\x1A", 2);
    ascii_world_free(w);
}

/* [ASCII-32] §9.11 FC16 standard: 0A32H -> DB805.DBW100, 102, 104 */
static void test_fc16_vector(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ":05100A32000306CD09DE1AEF2BBE\r\n", ":05100A320003AC\r\n");
    assert_memory_equal(world_db(w, 805) + 100, "\xCD\x09\xDE\x1A\xEF\x2B", 6);
    ascii_world_free(w);
}

/* Lower-case hex is accepted (modcp decision); the reply is upper case */
static void test_lower_case_hex(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ":05080000a5c38b\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* ---- receive errors ([ASCII-32] §8.1 "Error Handling", §8.5) -------------------------- */

/* LRC incorrect: (08)36H, no reply, BUS_CRC counted */
static void test_bad_lrc(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii_silence(w, ":05080000A5C38C\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_CRC);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_SLAVE_MSG], 0);
    /* a frame with only address and LRC (no function) is no message either */
    expect_ascii_silence(w, ":05FB\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_CRC);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 2);
    /* the next good frame is answered */
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* ':' inside a frame: (08)39H, the first part is discarded, reception restarts with
 * the second start character, and that frame is answered */
static void test_colon_restarts(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii(w, ":0503005:05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    assert_true(world_has_event(w, MODCP_EV_ASCII_RESTART));
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_MSG], 1);
    /* also after the CR (LF missing) */
    expect_ascii(w, ":050300500002A6\r:05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 2);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_ASCII_RESTART);
    ascii_world_free(w);
}

/* a character that is not 0-9 / A-F: (08)3AH, no reply; one event per frame */
static void test_not_hex(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii_silence(w, ":0508G000A5C38B\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_NOT_HEX);
    expect_ascii_silence(w, ":05 080000A5C38B\r\n"); /* a blank */
    assert_int_equal(w->cp.diag.buffer_len, 2);
    const uint8_t nul[] = ":0508" "\x00" "0000A5C38B\r\n"; /* a NUL */
    ascii_feed_bytes(w, nul, sizeof nul - 1, ASCII_CHAR_US);
    assert_int_equal(ascii_finish(w, 100), 0);
    assert_int_equal(w->cp.diag.buffer_len, 3); /* one event per frame */
    /* odd number of hex characters before CR */
    expect_ascii_silence(w, ":05080000A5C38\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_NOT_HEX);
    /* CR not followed by LF: the LF is missing */
    expect_ascii_silence(w, ":05080000A5C38B\rX\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_NOT_HEX);
    assert_int_equal(w->fake.tx_count, 0);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_SLAVE_MSG], 0);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 5); /* once per frame, as RTU */
    ascii_world_free(w);
}

/* wrong start character: (08)38H once for a run of stray characters (modcp decision:
 * one event, not one per character), e.g. an RTU master on an ASCII slave */
static void test_wrong_start(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    uint8_t rtu[] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x02, 0xC5, 0x9E};
    ascii_feed_bytes(w, rtu, sizeof rtu, ASCII_CHAR_US);
    assert_int_equal(ascii_finish(w, 100), 0);
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_START);
    /* a ':' after the stray characters starts a frame at once */
    ascii_feed(w, "XY", ASCII_CHAR_US);
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 2); /* 38H again after the silence */
    ascii_world_free(w);
}

/* interference suppression: stray characters before ':' are not reported */
static void test_wrong_start_suppressed(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    world_t *w = ascii_world_started(&p);
    expect_ascii(w, "\x7F\r\n:05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 0);
    ascii_world_free(w);
}

/* parity / framing error or BREAK inside a frame: (08)0CH / 0DH, no reply; with
 * interference suppression the frame is discarded silently; an error after CR LF
 * does not touch the frame */
static void test_line_errors(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    ascii_feed(w, ":050800", ASCII_CHAR_US);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_PARITY, w->now_us += ASCII_CHAR_US);
    expect_ascii_silence(w, "00A5C38B\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_CHAR_ERROR);
    assert_int_equal(w->cp.diag.char_errors, 1);

    ascii_feed(w, ":0508", ASCII_CHAR_US);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_BREAK, w->now_us += ASCII_CHAR_US);
    expect_ascii_silence(w, "0000A5C38B\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_BREAK);
    assert_int_equal(w->cp.diag.buffer_len, 2);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 2);

    /* after CR LF: the frame stands */
    ascii_feed(w, ":05080000A5C38B\r\n", ASCII_CHAR_US);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_FRAMING, w->now_us);
    assert_int_equal(ascii_finish(w, 100), 17);
    assert_string_equal(ascii_reply(w), ":05080000A5C38B\r\n");
    ascii_world_free(w);

    modcp_params_t p;
    ascii_example_params(&p);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    w = ascii_world_started(&p);
    ascii_feed(w, ":050800", ASCII_CHAR_US);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_PARITY, w->now_us += ASCII_CHAR_US);
    expect_ascii_silence(w, "00A5C38B\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 0);
    assert_int_equal(w->cp.diag.char_errors, 1);
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* RS485 two-wire in normal mode (Siemens driver manual 2009, Table 5-2, §5.6.5), ASCII: an
 * error inside a frame (after ':') is reported, (08)0CH, the frame discarded; an error
 * or BREAK between frames and a wrong start character are ignored. */
static void test_rs485_normal_line_errors(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1;
    p.opmode = MODCP_OPMODE_NORMAL;
    world_t *w = ascii_world_started(&p);
    ascii_feed(w, ":050800", ASCII_CHAR_US);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_PARITY, w->now_us += ASCII_CHAR_US);
    expect_ascii_silence(w, "00A5C38B\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_CHAR_ERROR);
    assert_int_equal(w->cp.diag.buffer_len, 1);
    world_run(w, 5000);
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_BREAK, w->now_us); /* between frames */
    world_run(w, 5000);
    ascii_feed(w, "x", ASCII_CHAR_US); /* a stray character: no (08)38H on RS485 */
    world_run(w, 200000);
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_false(w->cp.cpdiag.wire_break);
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* character delay time ([ASCII-32] §3.2): a gap longer than the ASCII timeout inside a frame
 * discards it with (08)06H; a gap just shorter does not */
static void test_character_delay_time(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    p.ascii_timeout_ms = 50;
    world_t *w = ascii_world_started(&p);
    assert_int_equal(w->cp.link.silence_us, 50000);

    /* 49.999 ms between the characters: answered */
    ascii_feed(w, ":", ASCII_CHAR_US);
    ascii_feed(w, "05080000A5C38B\r\n", 49999);
    assert_int_equal(ascii_finish(w, 100), 17);
    assert_int_equal(w->cp.diag.buffer_len, 0);

    /* the timer expires 50 ms after the last character: discarded, (08)06H */
    w->fake.tx_len = 0;
    ascii_feed(w, ":050800", ASCII_CHAR_US);
    assert_int_equal(w->fake.timer_us, 50000);
    assert_true(ascii_fire(w));
    assert_int_equal(world_last_event(w), MODCP_EV_ZVZ);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 1);
    /* the rest of that frame is a run of stray characters (08)38H, no reply */
    ascii_feed(w, "00A5C38B\r\n", ASCII_CHAR_US);
    assert_int_equal(ascii_finish(w, 100), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_START);
    assert_int_equal(w->cp.diag.buffer_len, 2);

    /* an expiry that raced a character (arrives early) re-arms for the rest */
    ascii_feed(w, ":0508", ASCII_CHAR_US);
    w->now_us += 20000;
    modcp_cp_on_timer(&w->cp, w->now_us);
    assert_int_equal(w->fake.timer_us, 30000);
    assert_int_equal(w->cp.diag.buffer_len, 2);
    expect_ascii(w, "0000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* an invalid character delay time runs with 1000 ms and reports (0E)21H ([ASCII-32] §8.6) */
static void test_invalid_timeout_default(void **state)
{
    (void)state;
    const uint16_t bad[] = {0, 6501};
    for (size_t k = 0; k < 2; k++) {
        modcp_params_t p;
        ascii_example_params(&p);
        p.ascii_timeout_ms = bad[k];
        world_t *w = ascii_world_started(&p);
        assert_int_equal(w->cp.params.ascii_timeout_ms, 1000);
        assert_int_equal(w->cp.link.silence_us, 1000000);
        assert_true(world_has_event(w, MODCP_EV_FMUL));
        ascii_feed(w, ":0508", ASCII_CHAR_US);
        assert_int_equal(w->fake.timer_us, 1000000);
        expect_ascii(w, "0000A5C38B\r\n", ":05080000A5C38B\r\n");
        ascii_world_free(w);
    }
    /* 1 and 6500 are valid */
    modcp_params_t p;
    ascii_example_params(&p);
    p.ascii_timeout_ms = 6500;
    world_t *w = ascii_world_started(&p);
    assert_int_equal(w->cp.link.silence_us, 6500000);
    assert_false(world_has_event(w, MODCP_EV_FMUL));
    ascii_world_free(w);
}

/* data bits: 7 (the eighth bit of a character is masked, e.g. a port that leaves the
 * parity bit in), 8 accepted as an extension, anything else refused (0E)20H */
static void test_data_bits(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    const char *req = ":05080000A5C38B\r\n";
    uint8_t hi[32];
    size_t n = strlen(req);
    for (size_t k = 0; k < n; k++) {
        hi[k] = (uint8_t)(req[k] | 0x80);
    }
    w->fake.tx_len = 0;
    ascii_feed_bytes(w, hi, n, ASCII_CHAR_US);
    assert_int_equal(ascii_finish(w, 100), 17);
    assert_string_equal(ascii_reply(w), req);
    ascii_world_free(w);

    modcp_params_t p;
    ascii_example_params(&p);
    p.data_bits = 8;
    w = ascii_world_started(&p);
    expect_ascii(w, req, req);
    ascii_feed_bytes(w, hi, n, ASCII_CHAR_US); /* 0xBA is no ':' with 8 data bits */
    assert_int_equal(ascii_finish(w, 100), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_START);
    ascii_world_free(w);

    ascii_example_params(&p);
    p.data_bits = 6;
    w = world_new(&p);
    world_start(w, 100);
    assert_false(modcp_cp_ready(&w->cp));
    assert_int_equal(w->cp.param_event, MODCP_EV_DATA_BITS);
    world_free(w);
}

/* frames for another slave: not answered, no event, counted as bus messages */
static void test_other_address(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii_silence(w, ":06080000A5C38A\r\n");
    expect_ascii_silence(w, ":06080000A5C38B\r\n"); /* bad LRC: not checked */
    assert_int_equal(w->cp.diag.buffer_len, 0);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_SLAVE_MSG], 0);
    /* a ':' inside someone else's frame restarts silently (counted as damaged) */
    expect_ascii(w, ":0603:05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 0);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 2);
    /* a non-hex character in someone else's frame: counted, no event */
    expect_ascii_silence(w, ":06080000A5C3XX\r\n");
    assert_int_equal(w->cp.diag.buffer_len, 0);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_BUS_CRC], 3);
    ascii_world_free(w);
}

/* broadcast ([ASCII-32] §8.1): FC06 executed, no reply; FC03 ignored with (08)30H */
static void test_broadcast(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    expect_ascii_silence(w, ascii_frame_hex("00 06 01 80 2B 1A"));
    assert_memory_equal(world_db(w, 800) + 768, "\x2B\x1A", 2);
    expect_ascii_silence(w, ascii_frame_hex("00 03 00 50 00 02"));
    assert_int_equal(world_last_event(w), MODCP_EV_BCAST_FC);
    assert_int_equal(w->fake.tx_count, 0);
    ascii_world_free(w);
}

/* a new request before the reply was sent: (08)37H ([ASCII-32] §8.5) */
static void test_sequence_error(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    w->fb_paused = true; /* the job waits */
    ascii_feed(w, ":050300500002A6\r\n", ASCII_CHAR_US);
    assert_true(ascii_fire(w));
    world_run(w, 5000);
    assert_int_equal(w->fake.tx_count, 0);
    ascii_feed(w, ":06080000A5C38A\r\n", ASCII_CHAR_US); /* another slave: no event */
    assert_int_equal(w->cp.diag.buffer_len, 0);
    ascii_feed(w, ":05080000A5C38B\r\n", ASCII_CHAR_US);
    assert_int_equal(world_last_event(w), MODCP_EV_SEQUENCE);
    /* a broadcast in the same position ([RTU-2003] §7.5): (08)37H too, not executed */
    ascii_feed(w, ":000600001234B4\r\n", ASCII_CHAR_US);
    assert_int_equal(w->cp.diag.buffer_len, 2);
    assert_int_equal(world_last_event(w), MODCP_EV_SEQUENCE);
    assert_int_equal(world_db(w, 800)[0], 0);
    w->fb_paused = false;
    assert_int_equal(ascii_finish(w, 200), 19);
    assert_string_equal(ascii_reply(w), ":05030487654321A4\r\n");
    /* the frame that came while busy was not taken for a request */
    assert_int_equal(ascii_finish(w, 100), 0);
    ascii_world_free(w);
}

/* more bytes than the receive buffer: (08)16H, no reply */
/* ":05" + function + n data bytes + LRC (all "08": not a valid request, only its
 * length matters) */
static void long_frame(char *req, unsigned data_bytes)
{
    size_t o = 0;
    req[o++] = ':';
    req[o++] = '0';
    req[o++] = '5';
    for (unsigned k = 0; k < 1u + data_bytes + 1u; k++) { /* function, data, LRC */
        req[o++] = '0';
        req[o++] = '8';
    }
    req[o++] = '\r';
    req[o++] = '\n';
    req[o] = 0;
}

/* CP 341 MODBUS ASCII slave manual §8.1: the data field holds 0 up to 2 x 252
 * characters; a frame with more is over-long, (08)16H, not answered. 252 data bytes are
 * still a frame (here: its LRC is wrong, (08)36H). */
static void test_frame_too_long(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    char req[2 * 300 + 8];
    long_frame(req, 252);
    expect_ascii_silence(w, req);
    assert_int_equal(world_last_event(w), MODCP_EV_CRC);
    assert_int_equal(w->cp.diag.frames_too_long, 0);
    long_frame(req, 253);
    expect_ascii_silence(w, req);
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    assert_int_equal(w->cp.diag.frames_too_long, 1);
    long_frame(req, MODCP_ADU_MAX);
    expect_ascii_silence(w, req);
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    assert_int_equal(w->cp.diag.frames_too_long, 2);
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

/* FC08 sub-function 03 sets the input delimiter (link field ascii_delim; the extended
 * set owns the function): frames then end with CR + that character */
static void test_input_delimiter(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    assert_int_equal(w->cp.link.ascii_delim, '\n');
    w->cp.link.ascii_delim = '!';
    expect_ascii(w, ":05080000A5C38B\r!", ":05080000A5C38B\r\n"); /* replies: CR LF */
    expect_ascii_silence(w, ":05080000A5C38B\r\n");
    assert_int_equal(world_last_event(w), MODCP_EV_ASCII_NOT_HEX);
    ascii_world_free(w);
}

/* ---- ASCII quantity limits ([ASCII-32] §5, §8.5 (08)32H) -------------------------------- */

static void expect_ascii_exception(world_t *w, const uint8_t *bin, size_t n, uint8_t code,
                                   modcp_event_t ev)
{
    char expect[16];
    uint8_t exc[3] = {bin[0], (uint8_t)(bin[1] | 0x80), code};
    snprintf(expect, sizeof expect, "%s", ascii_frame(exc, 3));
    uint16_t len = ascii_request(w, ascii_frame(bin, n), 2000);
    assert_int_equal(len, 11);
    assert_string_equal(ascii_reply(w), expect);
    assert_int_equal(world_last_event(w), ev);
}

static void test_limits_bits(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    /* FC01 2008 bits: reply 251 data bytes = the longest ASCII reply (513 chars) */
    memset(&w->m[1000], 0xA5, 251);
    uint8_t rd[] = {5, 1, 0x00, 0x00, 0x07, 0xD8};
    assert_int_equal(ascii_request(w, ascii_frame(rd, 6), 200), MODCP_ASCII_ADU_MAX);
    assert_int_equal(w->fake.tx[0], ':');
    assert_memory_equal(&w->fake.tx[1], "0501FBA5A5", 10);
    assert_int_equal(w->fake.tx[MODCP_ASCII_ADU_MAX - 2], '\r');
    rd[5] = 0xD9; /* 2009 */
    expect_ascii_exception(w, rd, 6, 3, MODCP_EV_QUANTITY);
    uint8_t rdi[] = {5, 2, 0x00, 0x00, 0x07, 0xD9}; /* FC02 2009 */
    expect_ascii_exception(w, rdi, 6, 3, MODCP_EV_QUANTITY);
    rdi[5] = 0xD8;
    assert_true(ascii_request(w, ascii_frame(rdi, 6), 200) > 0);
    assert_int_equal(w->fake.tx[4], '2'); /* FC 02, not an exception */

    /* FC15 1976 bits (247 bytes) accepted, 1977 refused */
    uint8_t wr[7 + 248];
    memcpy(wr, "\x05\x0F\x00\x00\x07\xB8\xF7", 7);
    memset(wr + 7, 0xFF, 247);
    assert_int_equal(ascii_request(w, ascii_frame(wr, 7 + 247), 200), 17);
    assert_int_equal(w->m[1246], 0xFF);
    assert_int_equal(w->m[1247], 0xA5); /* the byte after the 1976 bits: untouched */
    /* 1977 bits need 248 data bytes: 253 with start, quantity and byte count, more than
     * a frame holds ([ASCII-32] §8.1, 2 x 252 characters): over-long, (08)16H, no reply */
    wr[5] = 0xB9;
    wr[6] = 0xF8;
    assert_int_equal(ascii_request(w, ascii_frame(wr, 7 + 248), 200), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    ascii_world_free(w);
}

static void test_limits_registers(void **state)
{
    (void)state;
    world_t *w = ascii_started();
    uint8_t rd[] = {5, 3, 0x00, 0x00, 0x00, 125};
    assert_int_equal(ascii_request(w, ascii_frame(rd, 6), 200), 1 + 2 * (3 + 250 + 1) + 2);
    rd[5] = 126;
    expect_ascii_exception(w, rd, 6, 3, MODCP_EV_QUANTITY);
    uint8_t ri[] = {5, 4, 0x00, 0x00, 0x00, 126};
    expect_ascii_exception(w, ri, 6, 3, MODCP_EV_QUANTITY);

    uint8_t wr[7 + 248];
    memcpy(wr, "\x05\x10\x00\x00\x00\x7B\xF6", 7); /* 123 registers, 246 bytes */
    for (unsigned k = 0; k < 246; k++) {
        wr[7 + k] = (uint8_t)k;
    }
    assert_int_equal(ascii_request(w, ascii_frame(wr, 7 + 246), 200), 17);
    assert_int_equal(world_db(w, 800)[245], 245);
    wr[5] = 0x7C; /* 124 registers: 253 data bytes, over-long ([ASCII-32] §8.1) */
    wr[6] = 0xF8;
    assert_int_equal(ascii_request(w, ascii_frame(wr, 7 + 248), 200), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_FRAME_TOO_LONG);
    ascii_world_free(w);
}

/* ---- the link on its own: encoder in place, buffer limits ----------------------- */

static void test_encoder_in_place(void **state)
{
    (void)state;
    fake_hal_log_t f;
    modcp_hal_t hal;
    modcp_diag_t d;
    modcp_link_t l;
    uint8_t buf[MODCP_LINK_BUF_MAX + 16];
    fake_hal_log_init(&f, &hal, false);
    modcp_diag_init(&d);
    memset(buf, 0xA5, sizeof buf);
    modcp_link_init(&l, &hal, &d, buf, MODCP_LINK_BUF_MAX);
    assert_int_equal(l.cap, MODCP_ADU_MAX); /* receive: never more than RTU */
    modcp_params_t p;
    ascii_example_params(&p);
    modcp_link_configure(&l, &p);
    assert_true(l.enabled);

    const char *req = ":05080000A5C38B\r\n";
    uint32_t t = 1000;
    for (const char *c = req; *c; c++) {
        f.now = t;
        modcp_link_on_byte(&l, (uint8_t)*c, t);
        t += 1000;
    }
    assert_int_equal(l.state, MODCP_LINK_EOF);
    assert_int_equal(fake_hal_log_last(&f, FHL_ARM)->value, 1);
    modcp_frame_t fr;
    assert_true(modcp_link_on_timer(&l, t, &fr));
    assert_int_equal(fr.addr, 5);
    assert_int_equal(fr.pdu_len, 5);
    assert_memory_equal(fr.pdu, "\x08\x00\x00\xA5\xC3", 5);
    assert_int_equal(fr.pdu_cap, MODCP_ASCII_PDU_MAX);

    /* the largest reply PDU (253 bytes) fills the buffer exactly */
    for (unsigned k = 0; k < MODCP_ASCII_PDU_MAX; k++) {
        fr.pdu[k] = (uint8_t)(k * 7u);
    }
    uint8_t bin[1 + MODCP_ASCII_PDU_MAX];
    bin[0] = 5;
    memcpy(bin + 1, fr.pdu, MODCP_ASCII_PDU_MAX);
    char expect[MODCP_ASCII_ADU_MAX + 1];
    size_t o = 0;
    expect[o++] = ':';
    for (size_t k = 0; k < sizeof bin; k++) {
        o += (size_t)snprintf(expect + o, sizeof expect - o, "%02X", bin[k]);
    }
    o += (size_t)snprintf(expect + o, sizeof expect - o, "%02X\r\n", modcp_lrc(bin, sizeof bin));
    assert_int_equal(o, MODCP_ASCII_ADU_MAX);
    modcp_link_reply(&l, MODCP_ASCII_PDU_MAX, false, t);
    assert_int_equal(f.tx_len, MODCP_ASCII_ADU_MAX);
    assert_memory_equal(f.tx, expect, MODCP_ASCII_ADU_MAX);
    for (size_t k = MODCP_LINK_BUF_MAX; k < sizeof buf; k++) {
        assert_int_equal(buf[k], 0xA5); /* nothing written beyond the buffer */
    }
    modcp_link_on_tx_done(&l, t + 600000);
    assert_int_equal(l.state, MODCP_LINK_IDLE);

    /* one byte more does not fit: no transmission, (0E)10H */
    for (const char *c = req; *c; c++) {
        modcp_link_on_byte(&l, (uint8_t)*c, t);
        t += 1000;
    }
    assert_true(modcp_link_on_timer(&l, t, &fr));
    unsigned calls = f.tx_calls;
    modcp_link_reply(&l, MODCP_ASCII_PDU_MAX + 1, false, t);
    assert_int_equal(f.tx_calls, calls);
    assert_int_equal(d.buffer[0], MODCP_EV_INTERNAL_SEND);
    assert_int_equal(l.state, MODCP_LINK_IDLE);
}

/* RS485 two-wire: our own echo while transmitting is ignored; DE released on
 * transmission complete */
static void test_rs485_echo(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    world_t *w = ascii_world_started(&p);
    ascii_feed(w, ":05080000A5C38B\r\n", ASCII_CHAR_US);
    assert_true(ascii_fire(w));
    world_run(w, 2000);
    assert_int_equal(w->fake.tx_count, 1);
    assert_true(w->fake.de);
    ascii_feed(w, ":05080000A5C38B\r\n", ASCII_CHAR_US); /* the echo */
    modcp_cp_on_tx_done(&w->cp, w->now_us);
    assert_false(w->fake.de);
    assert_int_equal(w->cp.diag.buffer_len, 0);
    expect_ascii(w, ":05080000A5C38B\r\n", ":05080000A5C38B\r\n");
    ascii_world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_telegram_example_fc08),
        cmocka_unit_test(test_fc03_vector),
        cmocka_unit_test(test_exception_vector),
        cmocka_unit_test(test_fc05_vector),
        cmocka_unit_test(test_fc15_vector),
        cmocka_unit_test(test_fc01_vector),
        cmocka_unit_test(test_fc02_vector),
        cmocka_unit_test(test_fc04_vector),
        cmocka_unit_test(test_fc06_vector),
        cmocka_unit_test(test_fc16_vector),
        cmocka_unit_test(test_lower_case_hex),
        cmocka_unit_test(test_bad_lrc),
        cmocka_unit_test(test_colon_restarts),
        cmocka_unit_test(test_not_hex),
        cmocka_unit_test(test_wrong_start),
        cmocka_unit_test(test_wrong_start_suppressed),
        cmocka_unit_test(test_line_errors),
        cmocka_unit_test(test_character_delay_time),
        cmocka_unit_test(test_invalid_timeout_default),
        cmocka_unit_test(test_data_bits),
        cmocka_unit_test(test_other_address),
        cmocka_unit_test(test_broadcast),
        cmocka_unit_test(test_sequence_error),
        cmocka_unit_test(test_frame_too_long),
        cmocka_unit_test(test_rs485_normal_line_errors),
        cmocka_unit_test(test_input_delimiter),
        cmocka_unit_test(test_limits_bits),
        cmocka_unit_test(test_limits_registers),
        cmocka_unit_test(test_encoder_in_place),
        cmocka_unit_test(test_rs485_echo),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
