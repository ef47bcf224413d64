/* SPDX-License-Identifier: Apache-2.0 */
/* Extended function set (docs/extended-functions.md), end to end through the core with the [RTU-2003] §9
 * example parameters (slave 5, holding registers from DB 800, DB writes 800..899):
 * FC08 sub-functions with the Serial Line V1.02 counter semantics, FC11, FC12 with the
 * event byte encoding, FC17, FC22, FC23, FC43/14, listen-only, the `cp341` set.
 * Frames are written as PDUs; address and CRC are added and checked by ext_support. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "ascii_world.h"
#include "ext_support.h"
#include "modcp/hal.h"
#include "modcp/version.h"
#include "commlog_internal.h"
#include "diag_internal.h"
#include "pdu_internal.h"

#define S 5 /* slave address of the example set */

/* MODCP_VERSION (modcp/version.h, generated from the top-level CMakeLists.txt) as the hex
 * bytes of an expected reply: the revision object when the parameters leave it empty. */
#define VLEN ((unsigned)sizeof MODCP_VERSION - 1u)
static const char *version_hex(void)
{
    static char hex[3u * sizeof MODCP_VERSION];
    size_t n = 0;
    for (unsigned i = 0; i < VLEN; i++) {
        n += (size_t)sprintf(hex + n, i == 0u ? "%02X" : " %02X", (unsigned)MODCP_VERSION[i]);
    }
    return hex;
}

/* ---- function set cp341 ------------------------------------------------------------ */

/* docs/parameters.md function set `cp341`: exactly 01-06, 08 sub 0000, 15, 16; every FC of the
 * extended set -> exception 01, (08)31H; FC08 sub-functions other than 0000 -> 03,
 * (08)35H as in the manual ([RTU-2003] §6.7); the scanner is off. */
/* The FC12 event log is a ring: newest first, at most 64, the oldest drops out; a
 * clear empties it and the next event is the newest (and only) one. */
static void test_comm_log_ring(void **state)
{
    (void)state;
    modcp_comm_t c;
    memset(&c, 0, sizeof c);
    for (unsigned k = 0; k < 70u; k++) {
        modcp_comm_log(&c, (uint8_t)k);
        assert_int_equal(modcp_comm_log_at(&c, 0), k);
    }
    assert_int_equal(c.log_len, MODCP_COMM_LOG_LEN);
    for (unsigned i = 0; i < MODCP_COMM_LOG_LEN; i++) {
        assert_int_equal(modcp_comm_log_at(&c, i), 69u - i); /* 69 ... 6: 0..5 dropped */
    }
    modcp_comm_clear_log(&c);
    assert_int_equal(c.log_len, 0);
    modcp_comm_log(&c, 0x80);
    modcp_comm_log(&c, 0x40);
    assert_int_equal(c.log_len, 2);
    assert_int_equal(modcp_comm_log_at(&c, 0), 0x40);
    assert_int_equal(modcp_comm_log_at(&c, 1), 0x80);
}

static void test_cp341_set(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_CP341;
    p.scan_start = 0x0050;
    p.scan_count = 2;
    p.scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 100};
    world_t *w = ext_started(&p);
    const char *ext_fcs[] = {"0B", "0C", "11", "16 00 04 00 F2 00 25",
                             "17 00 00 00 01 00 00 00 01 02 12 34", "2B 0E 01 00"};
    for (size_t k = 0; k < sizeof ext_fcs / sizeof ext_fcs[0]; k++) {
        ext_expect_exception(w, S, ext_fcs[k], 1, MODCP_EV_ILLEGAL_FC);
    }
    const char *subs[] = {"08 00 01 00 00", "08 00 04 00 00", "08 00 0A 00 00", "08 00 0B 00 00",
                          "08 00 12 00 00", "08 00 14 00 00"};
    for (size_t k = 0; k < sizeof subs / sizeof subs[0]; k++) {
        ext_expect_exception(w, S, subs[k], 3, MODCP_EV_DIAG_SUBFC);
    }
    ext_expect(w, S, "08 00 00 A5 C3", "08 00 00 A5 C3");
    /* no scanner: register 0x0050 is DB 800 DBW 160 */
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    w->m[100] = 0x11;
    ext_expect(w, S, "03 00 50 00 02", "03 04 87 65 43 21");
    assert_false(w->cp.diag.comm.listen_only);
    world_free(w);
}

/* ---- FC08 ---------------------------------------------------------------------------- */

/* Serial Line V1.02 §6.1 counters after known traffic: 3 good requests, 1 frame for
 * another slave, 1 broadcast write, 2 CRC errors, 1 exception. Every counter read is
 * itself a message for us, counted before it is answered. */
static void test_fc08_counters_after_known_traffic(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    for (int k = 0; k < 3; k++) {
        ext_expect(w, S, "03 00 50 00 02", "03 04 00 00 00 00");
    }
    assert_int_equal(ext_request(w, 6, "03 00 50 00 02", 100), 0); /* another slave */
    assert_int_equal(ext_request(w, 0, "06 01 80 2B 1A", 100), 0); /* broadcast */
    assert_int_equal(world_db(w, 800)[768], 0x2B);
    ext_bad_crc(w, S, "03 00 50 00 02");
    ext_bad_crc(w, S, "03 00 50 00 02");
    ext_expect_exception(w, S, "03 00 50 00 00", 3, MODCP_EV_QUANTITY);

    assert_int_equal(ext_counter(w, S, 0x0B), 7); /* 3 + other slave + bcast + exc + itself */
    assert_int_equal(ext_counter(w, S, 0x0C), 2); /* the two CRC errors */
    assert_int_equal(ext_counter(w, S, 0x0D), 1); /* the exception */
    assert_int_equal(ext_counter(w, S, 0x0E), 9); /* 3 + bcast + exc + 0B 0C 0D 0E */
    assert_int_equal(ext_counter(w, S, 0x0F), 1); /* the broadcast */
    assert_int_equal(ext_counter(w, S, 0x10), 0); /* NAK: never sent */
    assert_int_equal(ext_counter(w, S, 0x11), 0); /* busy: never sent */
    assert_int_equal(ext_counter(w, S, 0x12), 0); /* no overrun */
    /* FC11: successful completions: 3 reads, the broadcast, 8 counter reads */
    ext_expect(w, S, "0B", "0B 00 00 00 0C");
    ext_expect(w, S, "0B", "0B 00 00 00 0C"); /* FC11 does not count itself */

    /* 0A clears after its echo: what follows counts from zero */
    ext_expect(w, S, "08 00 0A 00 00", "08 00 0A 00 00");
    assert_int_equal(w->cp.diag.comm.event_count, 0);
    assert_int_equal(ext_counter(w, S, 0x0B), 1);
    assert_int_equal(ext_counter(w, S, 0x0E), 2);
    assert_int_equal(ext_counter(w, S, 0x0D), 0);
    assert_int_equal(ext_counter(w, S, 0x0C), 0);
    assert_int_equal(ext_counter(w, S, 0x0F), 0);
    ext_expect(w, S, "0B", "0B 00 00 00 05");
    /* the backplane status area shows the same counters */
    modcp_cp_status_t st = ext_status(w);
    assert_int_equal(st.counters[MODCP_CNT_BUS_MSG], 6);
    assert_int_equal(st.counters[MODCP_CNT_SLAVE_MSG], 6);
    world_free(w);
}

/* [ALTIVAR] §8: message counters wrap 65535 -> 0, error counters saturate at 65535. */
static void test_fc08_wrap_and_saturation(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    w->cp.diag.counters[MODCP_CNT_BUS_MSG] = 0xFFFE;
    w->cp.diag.counters[MODCP_CNT_SLAVE_MSG] = 0xFFFE;
    w->cp.diag.counters[MODCP_CNT_BUS_CRC] = 0xFFFE;
    w->cp.diag.counters[MODCP_CNT_EXCEPTION] = 0xFFFF;
    assert_int_equal(ext_counter(w, S, 0x0B), 0xFFFF);
    assert_int_equal(ext_counter(w, S, 0x0B), 0x0000);
    assert_int_equal(ext_counter(w, S, 0x0E), 0x0001);
    ext_bad_crc(w, S, "08 00 0C 00 00");
    ext_bad_crc(w, S, "08 00 0C 00 00");
    assert_int_equal(ext_counter(w, S, 0x0C), 0xFFFF);
    ext_expect_exception(w, S, "03 00 50 00 00", 3, MODCP_EV_QUANTITY);
    assert_int_equal(ext_counter(w, S, 0x0D), 0xFFFF);
    w->cp.diag.comm.event_count = 0xFFFF;
    ext_expect(w, S, "08 00 00 12 34", "08 00 00 12 34");
    ext_expect(w, S, "0B", "0B 00 00 00 00");
    world_free(w);
}

/* Character overrun: counter 12, diagnostic register bit 0; sub 14 clears both. A
 * frame damaged by a character error counts as a bus communication error (0C). */
static void test_fc08_overrun_and_diag_register(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 00");
    ext_line_error(w, MODCP_LINE_OVERRUN);
    assert_int_equal(ext_counter(w, S, 0x12), 1);
    assert_int_equal(ext_counter(w, S, 0x0C), 1);
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 01");
    ext_expect(w, S, "08 00 14 00 00", "08 00 14 00 00");
    assert_int_equal(ext_counter(w, S, 0x12), 0);
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 00");
    assert_int_equal(ext_counter(w, S, 0x0C), 1); /* 14 clears only the overrun count */
    /* parity error: a communication error, not an overrun */
    ext_line_error(w, MODCP_LINE_PARITY);
    assert_int_equal(ext_counter(w, S, 0x0C), 2);
    assert_int_equal(ext_counter(w, S, 0x12), 0);
    world_free(w);
}

/* Sub-function and data checks: unsupported sub-function -> 01 (Application Protocol
 * FC08 diagram), data not allowed or wrong length -> 03. */
static void test_fc08_exceptions(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect_exception(w, S, "08 00 05 00 00", 1, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 09 00 00", 1, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 13 00 00", 1, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 15 00 00", 1, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 01 00 00 00", 1, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 0B 00 01", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 0A FF 00", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 01 12 34", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 04 00 01", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 0B 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "08 00 0B 00 00 00 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "08 00", 3, MODCP_EV_BYTE_COUNT);
    /* sub 00 echoes any amount of data */
    ext_expect(w, S, "08 00 00 01 02 03 04 05 06", "08 00 00 01 02 03 04 05 06");
    ext_expect(w, S, "08 00 00", "08 00 00");
    assert_false(w->cp.diag.comm.listen_only);
    /* broadcast FC08: silence, (08)30H, counted as exception and no response */
    uint16_t exc = w->cp.diag.counters[MODCP_CNT_EXCEPTION];
    ext_expect_silence(w, 0, "08 00 04 00 00");
    assert_int_equal(world_last_event(w), MODCP_EV_BCAST_FC);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], exc + 1);
    assert_false(w->cp.diag.comm.listen_only);
    world_free(w);
}

/* Sub 03: the ASCII end-of-frame character; hex digits and ':' refused. */
static void test_fc08_ascii_delimiter(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    assert_int_equal(w->cp.ext.ascii_delimiter, 0x0A);
    ext_expect(w, S, "08 00 03 3B 00", "08 00 03 3B 00");
    assert_int_equal(w->cp.ext.ascii_delimiter, ';');
    assert_int_equal(w->cp.link.ascii_delim, ';');
    ext_expect_exception(w, S, "08 00 03 41 00", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 03 3A 00", 3, MODCP_EV_DIAG_SUBFC);
    ext_expect_exception(w, S, "08 00 03 0D 01", 3, MODCP_EV_DIAG_SUBFC);
    assert_int_equal(w->cp.ext.ascii_delimiter, ';');
    /* a restart brings back LF */
    ext_expect(w, S, "08 00 01 00 00", "08 00 01 00 00");
    assert_int_equal(w->cp.ext.ascii_delimiter, 0x0A);
    assert_int_equal(w->cp.link.ascii_delim, 0x0A);
    world_free(w);
}

/* Sub 03 in ASCII framing: the frames after it end with CR ';' (replies keep CR LF);
 * sub 01 brings back LF. */
static void test_fc08_ascii_delimiter_end_to_end(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    world_t *w = ascii_world_started(&p);
    const uint8_t set[] = {S, 0x08, 0x00, 0x03, 0x3B, 0x00};
    char req[64];
    strcpy(req, ascii_frame(set, sizeof set));
    assert_true(ascii_request(w, req, 200) > 0);
    assert_string_equal(ascii_reply(w), req);
    assert_int_equal(w->cp.link.ascii_delim, ';');
    const uint8_t echo[] = {S, 0x08, 0x00, 0x00, 0x12, 0x34};
    char lf[64], semi[64];
    strcpy(lf, ascii_frame(echo, sizeof echo));
    strcpy(semi, lf);
    semi[strlen(semi) - 1] = ';';
    assert_true(ascii_request(w, semi, 200) > 0);
    assert_string_equal(ascii_reply(w), lf); /* replies end with CR LF */
    const uint8_t restart[] = {S, 0x08, 0x00, 0x01, 0x00, 0x00};
    strcpy(req, ascii_frame(restart, sizeof restart));
    req[strlen(req) - 1] = ';';
    assert_true(ascii_request(w, req, 200) > 0);
    assert_int_equal(w->cp.link.ascii_delim, '\n');
    assert_true(ascii_request(w, lf, 200) > 0);
    assert_string_equal(ascii_reply(w), lf);
    ascii_world_free(w);
}

/* Sub 03 in ASCII with 7 data bits: a delimiter above 7FH could never be received (the
 * eighth bit is masked), so it is refused like a hex digit and LF stays in force
 * (found by fuzz_ascii: the CP answered nothing after ":050800038D00..."). */
static void test_fc08_ascii_delimiter_7bit(void **state)
{
    (void)state;
    modcp_params_t p;
    ascii_example_params(&p);
    assert_int_equal(p.data_bits, 7);
    world_t *w = ascii_world_started(&p);
    const uint8_t set[] = {S, 0x08, 0x00, 0x03, 0x8D, 0x00};
    const uint8_t exc[] = {S, 0x88, 0x03};
    char expect[32];
    strcpy(expect, ascii_frame(exc, sizeof exc));
    assert_true(ascii_request(w, ascii_frame(set, sizeof set), 200) > 0);
    assert_string_equal(ascii_reply(w), expect);
    assert_int_equal(world_last_event(w), MODCP_EV_DIAG_SUBFC);
    assert_int_equal(w->cp.link.ascii_delim, '\n');
    const uint8_t echo[] = {S, 0x08, 0x00, 0x00, 0x12, 0x34};
    char lf[64];
    strcpy(lf, ascii_frame(echo, sizeof echo));
    assert_true(ascii_request(w, lf, 200) > 0);
    assert_string_equal(ascii_reply(w), lf);
    ascii_world_free(w);
}

/* Sub 04 listen-only: nothing answered or executed, counting goes on, the CPU side
 * sees MODCP_CPST_LISTEN_ONLY; only sub 01 is processed (no reply) and leaves it. */
static void test_fc08_listen_only(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect_silence(w, S, "08 00 04 00 00");
    assert_true(w->cp.diag.comm.listen_only);
    assert_true(ext_status(w).flags & MODCP_CPST_LISTEN_ONLY);
    ext_expect_silence(w, S, "06 00 50 AB CD");
    assert_int_equal(world_db(w, 800)[160], 0x00); /* not executed */
    ext_expect_silence(w, S, "08 00 00 A5 C3");
    ext_expect_silence(w, S, "08 00 01 12 34"); /* not a valid restart: stays */
    assert_true(w->cp.diag.comm.listen_only);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_NO_RESPONSE], 4);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_SLAVE_MSG], 4);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], 0);
    /* restart: processed, no reply, listen-only left, counters cleared, log kept */
    ext_expect_silence(w, S, "08 00 01 00 00");
    assert_false(w->cp.diag.comm.listen_only);
    assert_false(ext_status(w).flags & MODCP_CPST_LISTEN_ONLY);
    ext_expect(w, S, "08 00 00 A5 C3", "08 00 00 A5 C3");
    /* log, oldest first: 80 04 (sub 04), A0 x3 (in listen-only), A0 00 (restart),
     * 80 40 (echo), 80 (this FC12); event count 1, message count 2 */
    ext_expect(w, S, "0C", "0C 10 00 00 00 01 00 02 80 40 80 00 A0 A0 A0 A0 04 80");
    world_free(w);
}

/* Sub 01 with FF00 clears the log; the echo goes out before the restart. */
static void test_fc08_restart_clear_log(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00");
    ext_bad_crc(w, S, "03 00 50 00 01");
    ext_expect(w, S, "08 00 01 00 00", "08 00 01 00 00"); /* keep the log */
    assert_int_equal(w->cp.diag.comm.log_len, 6);         /* 80 40 82 80 40 00 */
    assert_int_equal(modcp_comm_log_at(&w->cp.diag.comm, 0), 0x00);
    assert_int_equal(modcp_comm_log_at(&w->cp.diag.comm, 1), 0x40);
    assert_int_equal(ext_counter(w, S, 0x0C), 0);
    ext_expect(w, S, "08 00 01 FF 00", "08 00 01 FF 00");
    assert_int_equal(w->cp.diag.comm.log_len, 1);
    ext_expect(w, S, "0C", "0C 08 00 00 00 00 00 01 80 00");
    world_free(w);
}

/* ---- FC11 / FC12 ------------------------------------------------------------------ */

/* Application Protocol §6.10 event bytes: receive 80 | 40 broadcast | 02 comm error,
 * send 40 | 01 exception 1-3 | 02 exception 4; newest first; message count = 0B. */
static void test_fc12_event_log(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00");          /* 80 40 */
    ext_expect_exception(w, S, "06 C8 00 00 01", 2, MODCP_EV_WRITE_DENIED); /* 80 41 */
    assert_int_equal(ext_request(w, 0, "06 01 80 2B 1A", 100), 0); /* C0 40 */
    ext_bad_crc(w, S, "03 00 50 00 01");                         /* 82 */
    ext_expect_exception(w, S, "03 0E 00 00 01", 4, MODCP_EV_DB_ACCESS); /* DB 807: 80 42 */
    ext_expect(w, S, "0C", "0C 10 00 00 00 02 00 05 80 42 80 82 40 C0 41 80 40 80");
    ext_expect(w, S, "0B", "0B 00 00 00 02");
    ext_expect_exception(w, S, "0C 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "0B 00 00", 3, MODCP_EV_BYTE_COUNT);
    world_free(w);
}

/* The log keeps the newest 64 event bytes. */
static void test_fc12_log_wraps_at_64(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    for (int k = 0; k < 40; k++) {
        ext_expect(w, S, "08 00 00 00 00", "08 00 00 00 00");
    }
    assert_int_equal(ext_request(w, S, "0C", 100), 72);
    assert_int_equal(w->fake.tx[2], 70); /* 6 + 64 events */
    assert_int_equal(w->fake.tx[5] << 8 | w->fake.tx[6], 40); /* event count */
    assert_int_equal(w->fake.tx[7] << 8 | w->fake.tx[8], 41); /* message count */
    for (int k = 0; k < 64; k++) {
        assert_int_equal(w->fake.tx[9 + k], k % 2 == 0 ? 0x80 : 0x40);
    }
    world_free(w);
}

/* ---- FC17 ------------------------------------------------------------------------ */

static void test_fc17_report_slave_id(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    /* slave id = address 5, run indicator FF, "modcp modcp-cp " and, the default revision
     * being empty, modcp's version */
    char want[200];
    sprintf(want, "11 %02X 05 FF 6D 6F 64 63 70 20 6D 6F 64 63 70 2D 63 70 20 %s", 17u + VLEN,
            version_hex());
    ext_expect(w, S, "11", want);
    ext_expect_exception(w, S, "11 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_silence(w, 0, "11");
    /* the CPU side stops answering: run indicator 00 until a job succeeds again */
    w->fb_paused = true;
    ext_expect_exception(w, S, "03 00 50 00 01", 4, MODCP_EV_XFER_TIMEOUT);
    want[9] = '0'; /* run indicator 00 */
    want[10] = '0';
    ext_expect(w, S, "11", want);
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 04");
    w->fb_paused = false;
    world_run(w, 5000);
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00");
    assert_int_equal(ext_request(w, S, "11", 100), 19 + (int)VLEN);
    assert_int_equal(w->fake.tx[4], 0xFF);
    world_free(w);
}

static void test_fc17_strings_from_params(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    strcpy(p.vendor, "ACME");
    strcpy(p.product, "");
    strcpy(p.revision, "V2");
    world_t *w = ext_started(&p);
    ext_expect(w, S, "11", "11 09 05 FF 41 43 4D 45 20 56 32"); /* "ACME V2" */
    world_free(w);
}

/* ---- FC22 ------------------------------------------------------------------------ */

/* Application Protocol §6.16 example: current 0012, AND 00F2, OR 0025 -> 0017. */
static void test_fc22_mask_write(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    uint8_t *db = world_db(w, 800);
    db[8] = 0x00;
    db[9] = 0x12;
    ext_expect(w, S, "16 00 04 00 F2 00 25", "16 00 04 00 F2 00 25");
    assert_int_equal(db[8], 0x00);
    assert_int_equal(db[9], 0x17);
    /* AND FFFF keeps, AND 0000 takes OR */
    db[10] = 0xA5;
    db[11] = 0x5A;
    ext_expect(w, S, "16 00 05 FF 00 12 34", "16 00 05 FF 00 12 34");
    assert_int_equal(db[10], 0xA5);
    assert_int_equal(db[11], 0x34);
    /* write limits (DB 900 is outside 800..899), length, broadcast */
    ext_expect_exception(w, S, "16 C8 00 00 00 FF FF", 2, MODCP_EV_WRITE_DENIED);
    ext_expect_exception(w, S, "16 00 04 00 F2 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "16 00 04 00 F2 00 25 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_silence(w, 0, "16 00 04 00 00 FF FF");
    assert_int_equal(world_last_event(w), MODCP_EV_BCAST_FC);
    assert_int_equal(db[9], 0x17);
    /* DB 807 inside the limits but missing: the CPU side refuses -> 04 */
    ext_expect_exception(w, S, "16 0E 00 00 00 FF FF", 4, MODCP_EV_DB_ACCESS);
    world_free(w);
}

/* ---- FC23 ------------------------------------------------------------------------ */

static void test_fc23_write_before_read(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    uint8_t *db = world_db(w, 800);
    memcpy(db, "\x11\x11\x22\x22", 4);
    /* read 0..1, write 1 = ABCD: the read sees the written value */
    ext_expect(w, S, "17 00 00 00 02 00 01 00 01 02 AB CD", "17 04 11 11 AB CD");
    assert_int_equal(db[2], 0xAB);
    /* different places: write DB 801 word 3, read DB 800 word 0 */
    ext_expect(w, S, "17 00 00 00 01 02 03 00 02 04 01 02 03 04", "17 02 11 11");
    assert_memory_equal(world_db(w, 801) + 6, "\x01\x02\x03\x04", 4);
    world_free(w);
}

static void test_fc23_limits_and_checks(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    uint8_t *db = world_db(w, 800);
    /* quantities: read 1..125, write 1..121 */
    ext_expect_exception(w, S, "17 00 00 00 00 00 00 00 01 02 00 00", 3, MODCP_EV_QUANTITY);
    ext_expect_exception(w, S, "17 00 00 00 7E 00 00 00 01 02 00 00", 3, MODCP_EV_QUANTITY);
    ext_expect_exception(w, S, "17 00 00 00 01 00 00 00 7A 02 00 00", 3, MODCP_EV_QUANTITY);
    ext_expect_exception(w, S, "17 00 00 00 01 00 00 00 00 00", 3, MODCP_EV_QUANTITY);
    /* byte count */
    ext_expect_exception(w, S, "17 00 00 00 01 00 00 00 01 04 00 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "17 00 00 00 01 00 00 00 01 02 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "17 00 00 00 01 00 00 00 01", 3, MODCP_EV_BYTE_COUNT);
    /* both ranges checked before anything is written: a bad read range (crossing the
     * end of DB 800) with a good write range writes nothing */
    ext_expect_exception(w, S, "17 01 FF 00 02 00 00 00 01 02 AB CD", 2, MODCP_EV_DB_ACCESS);
    assert_int_equal(db[0], 0x00);
    ext_expect_exception(w, S, "17 00 00 00 01 C8 00 00 01 02 AB CD", 2, MODCP_EV_WRITE_DENIED);
    /* the read range is a read: DB 900 (outside the write limits) may be read */
    ext_expect(w, S, "17 C8 00 00 01 00 00 00 01 02 AB CD", "17 02 00 00");
    assert_int_equal(db[0], 0xAB);
    /* the read part hits a missing DB (only the CPU side knows): 04, and the write is
     * not done either (issue 13 item 9: an exception means nothing was written) */
    ext_expect_exception(w, S, "17 0E 00 00 01 00 00 00 01 02 12 34", 4, MODCP_EV_DB_ACCESS);
    assert_int_equal(db[0], 0xAB);
    /* broadcast: not allowed, nothing written */
    ext_expect_silence(w, 0, "17 00 00 00 01 00 00 00 01 02 55 55");
    assert_int_equal(db[0], 0xAB);
    world_free(w);
}

static void test_fc23_maximum_quantities(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    uint8_t *db = world_db(w, 801);
    for (int k = 0; k < 250; k++) {
        db[k] = (uint8_t)k;
    }
    /* read 125 of DB 801, write 121 to DB 802 */
    char req[1000];
    size_t o = (size_t)sprintf(req, "17 02 00 00 7D 04 00 00 79 F2");
    for (int k = 0; k < 242; k++) {
        o += (size_t)sprintf(req + o, " %02X", (unsigned)(255 - k));
    }
    assert_int_equal(ext_request(w, S, req, 2000), 252);
    assert_int_equal(w->fake.tx[1], 0x17);
    assert_int_equal(w->fake.tx[2], 250);
    for (int k = 0; k < 250; k++) {
        assert_int_equal(w->fake.tx[3 + k], k);
    }
    assert_int_equal(world_db(w, 802)[0], 255);
    assert_int_equal(world_db(w, 802)[241], 255 - 241);
    world_free(w);
}

/* 32-bit registers ([ASCII-32] §4.5): FC22 on the int16 range only; FC23 counts 32-bit
 * entities in the int32 / float ranges. */
static void test_fc22_fc23_regs32(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.regs32 = 1;
    p.r32[MODCP_R32_INT16] = (modcp_r32range_t){1000, 1099, 801};
    p.r32[MODCP_R32_INT32] = (modcp_r32range_t){2000, 2099, 802};
    world_t *w = ext_started(&p);
    world_db(w, 801)[4] = 0xFF;
    world_db(w, 801)[5] = 0xFF;
    ext_expect(w, S, "16 03 EA 00 FF 00 00", "16 03 EA 00 FF 00 00"); /* reg 1002 */
    assert_int_equal(world_db(w, 801)[4], 0x00);
    assert_int_equal(world_db(w, 801)[5], 0xFF);
    ext_expect_exception(w, S, "16 07 D0 00 FF 00 00", 2, MODCP_EV_NO_WINDOW);
    /* write int32 2001 = 11223344, read int32 2000..2001 */
    ext_expect(w, S, "17 07 D0 00 02 07 D1 00 01 04 11 22 33 44",
               "17 08 00 00 00 00 11 22 33 44");
    ext_expect_exception(w, S, "17 07 D0 00 02 07 D1 00 01 02 11 22", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "17 07 D0 00 3F 07 D1 00 01 04 11 22 33 44", 3,
                         MODCP_EV_QUANTITY); /* 63 int32 > 62 */
    world_free(w);
}

/* ---- FC43 / 14 --------------------------------------------------------------------- */

static void test_fc43_basic_default(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    /* the default revision is empty: object 02 is modcp's version */
    char basic[200], rev[64];
    sprintf(rev, "02 %02X %s", VLEN, version_hex());
    sprintf(basic, "2B 0E 01 82 00 00 03 00 05 6D 6F 64 63 70 01 08 6D 6F 64 63 70 2D 63 70 %s",
            rev);
    ext_expect(w, S, "2B 0E 01 00", basic);
    ext_expect(w, S, "2B 0E 01 06", basic); /* not a basic object: restart at 00 */
    ext_expect(w, S, "2B 0E 01 7F", basic);
    char want[200];
    sprintf(want, "2B 0E 01 82 00 00 01 %s", rev);
    ext_expect(w, S, "2B 0E 01 02", want);
    sprintf(want, "2B 0E 04 82 00 00 01 %s", rev);
    ext_expect(w, S, "2B 0E 04 02", want);
    /* regular without a user application name: the basic objects */
    basic[7] = '2';
    ext_expect(w, S, "2B 0E 02 00", basic);
    ext_expect_exception(w, S, "2B 0E 04 06", 2, MODCP_EV_NO_WINDOW);
    world_free(w);
}

/* The [ALTIVAR] §10.5 identification strings; regular stream access gives the Altivar's
 * 55-byte frame with our conformity level 82H and ReadDevId 02. */
static void test_fc43_regular_altivar_strings(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.slave_addr = 2;
    strcpy(p.vendor, "Telemecanique");
    strcpy(p.product, "ATV71HU15M3");
    strcpy(p.revision, "0201");
    strcpy(p.app_name, "MACHINE 4");
    world_t *w = ext_started(&p);
    const char *objs = "00 0D 54 65 6C 65 6D 65 63 61 6E 69 71 75 65 01 0B 41 54 56 37 31 48 55 "
                       "31 35 4D 33 02 04 30 32 30 31 06 09 4D 41 43 48 49 4E 45 20 34";
    char want[400];
    sprintf(want, "2B 0E 02 82 00 00 04 %s", objs);
    assert_int_equal(ext_request(w, 2, "2B 0E 02 00", 100), 52);
    assert_int_equal(w->fake.tx_len, 55);
    assert_string_equal(ext_reply(w), want);
    sprintf(want, "2B 0E 03 82 00 00 04 %s", objs); /* extended: answered as regular */
    ext_expect(w, 2, "2B 0E 03 00", want);
    ext_expect(w, 2, "2B 0E 02 06", "2B 0E 02 82 00 00 01 06 09 4D 41 43 48 49 4E 45 20 34");
    ext_expect(w, 2, "2B 0E 04 06", "2B 0E 04 82 00 00 01 06 09 4D 41 43 48 49 4E 45 20 34");
    ext_expect(w, 2, "2B 0E 04 01",
               "2B 0E 04 82 00 00 01 01 0B 41 54 56 37 31 48 55 31 35 4D 33");
    /* basic: objects 00..02 only */
    ext_expect(w, 2, "2B 0E 01 00",
               "2B 0E 01 82 00 00 03 00 0D 54 65 6C 65 6D 65 63 61 6E 69 71 75 65 01 0B 41 54 "
               "56 37 31 48 55 31 35 4D 33 02 04 30 32 30 31");
    world_free(w);
}

static void test_fc43_exceptions(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    ext_expect_exception(w, S, "2B 0E 00 00", 3, MODCP_EV_MEI_CODE);
    ext_expect_exception(w, S, "2B 0E 05 00", 3, MODCP_EV_MEI_CODE);
    ext_expect_exception(w, S, "2B 0E 04 03", 2, MODCP_EV_NO_WINDOW);
    ext_expect_exception(w, S, "2B 0E 04 80", 2, MODCP_EV_NO_WINDOW);
    ext_expect_exception(w, S, "2B 0D 01 00", 1, MODCP_EV_ILLEGAL_FC);
    ext_expect_exception(w, S, "2B 0E 01", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "2B 0E 01 00 00", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "2B", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_silence(w, 0, "2B 0E 01 00");
    world_free(w);
}

/* More follows / next object id, with a reply buffer too small for all objects. */
static void test_fc43_more_follows(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    strcpy(p.vendor, "Telemecanique");
    strcpy(p.product, "ATV71HU15M3");
    strcpy(p.revision, "0201");
    strcpy(p.app_name, "MACHINE 4");
    modcp_areas_t areas = {0};
    modcp_diag_t d;
    modcp_diag_init(&d);
    modcp_pdu_env_t env = {&p, &areas, &d, true, NULL};
    modcp_pdu_t s;
    uint8_t buf[64];
    uint16_t out = 0;
    /* 7 header + (2 + 13) + (2 + 11) = 35: the revision does not fit */
    memcpy(buf, "\x2B\x0E\x02\x00", 4);
    assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 4, 35, &out), MODCP_PDU_REPLY);
    assert_int_equal(out, 35);
    assert_int_equal(buf[4], 0xFF); /* more follows */
    assert_int_equal(buf[5], 0x02); /* next object id */
    assert_int_equal(buf[6], 2);
    memcpy(buf, "\x2B\x0E\x02\x02", 4);
    assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 4, 35, &out), MODCP_PDU_REPLY);
    assert_int_equal(out, 7 + 6 + 11);
    assert_int_equal(buf[4], 0x00);
    assert_int_equal(buf[5], 0x00);
    assert_int_equal(buf[6], 2);
    assert_int_equal(buf[7], 0x02);
    assert_int_equal(buf[13], 0x06);
}

/* The function-code table is indexed by fc (pdu.c): every fc without a row in the
 * function set answers exception 01, (08)31H - also the two rows kept after fc 17H
 * (FC43 and the extended set's FC08) - and FC08 reaches each set's own handler. */
static void test_fc_table_lookup(void **state)
{
    (void)state;
    static const uint8_t ext_fcs[] = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x08, 0x0B,
                                      0x0C, 0x0F, 0x10, 0x11, 0x16, 0x17, 0x2B};
    for (int set = 0; set < 2; set++) {
        modcp_params_t p;
        world_example_params(&p);
        p.fset = set ? MODCP_FSET_EXTENDED : MODCP_FSET_CP341;
        modcp_areas_t areas = {0};
        modcp_diag_t d;
        modcp_diag_init(&d);
        modcp_pdu_env_t env = {&p, &areas, &d, true, NULL};
        modcp_pdu_t s;
        uint8_t buf[260];
        uint16_t out = 0;
        for (unsigned fc = 0; fc < 256u; fc++) {
            bool known = false;
            for (size_t i = 0; i < sizeof ext_fcs; i++) {
                /* the cp341 set: FC01 .. 06, 08, 0F, 10 */
                known |= ext_fcs[i] == fc && (set || fc <= 0x08u || fc == 0x0Fu || fc == 0x10u);
            }
            memset(buf, 0, sizeof buf);
            buf[0] = (uint8_t)fc;
            modcp_diag_init(&d); /* the event below is this request's */
            modcp_pdu_action_t a = modcp_pdu_request(&s, &env, 5, buf, 1, sizeof buf, &out);
            const bool exc01 = a == MODCP_PDU_REPLY && out == 2u && buf[0] == (uint8_t)(fc | 0x80u) &&
                               buf[1] == 0x01u;
            assert_int_equal(exc01, !known);
            if (!known) {
                assert_int_equal(d.buffer_len, 1);
                assert_int_equal(d.buffer[0], MODCP_EV_ILLEGAL_FC);
            }
        }
        /* FC08 sub 02 (diagnostic register): the extended set only */
        memcpy(buf, "\x08\x00\x02\x00\x00", 5);
        assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 5, sizeof buf, &out), MODCP_PDU_REPLY);
        if (set) {
            assert_int_equal(out, 5);
            assert_int_equal(buf[0], 0x08);
        } else {
            assert_int_equal(out, 2);
            assert_int_equal(buf[0], 0x88);
            assert_int_equal(buf[1], 0x03);
            assert_int_equal(d.buffer[0], MODCP_EV_DIAG_SUBFC);
        }
    }
}

/* modcp_pdu_request clears only the request's own state (fc .. x's head, job.op): a
 * request never inherits the previous one's reply description, echo or job. */
static void test_pdu_state_per_request(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_EXTENDED;
    modcp_areas_t areas = {.i_bytes = 1024, .q_bytes = 1024, .m_bytes = 4096,
                           .timers = 256, .counters = 256};
    modcp_diag_t d;
    modcp_diag_init(&d);
    modcp_pdu_env_t env = {&p, &areas, &d, true, NULL};
    modcp_pdu_t s;
    memset(&s, 0xA5, sizeof s); /* whatever was there before */
    uint8_t buf[260];
    uint16_t out = 0;
    /* FC01 from coil 3 (M 1000.3): a bit string to align */
    memcpy(buf, "\x01\x00\x03\x00\x0A", 5);
    assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 5, sizeof buf, &out), MODCP_PDU_JOB);
    assert_int_equal(s.bits, 1u + 3u);
    assert_int_equal(s.job.op, MODCP_JOB_READ);
    /* FC05: an echo, the request's frame unchanged */
    memcpy(buf, "\x05\x00\x03\xFF\x00", 5);
    assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 5, sizeof buf, &out), MODCP_PDU_JOB);
    assert_int_equal(s.bits, 0);
    assert_true(s.same);
    assert_int_equal(s.x.echo, 5);
    assert_int_equal(s.job.op, MODCP_JOB_BITWRITE);
    assert_ptr_equal(s.wdata, buf + 3); /* bit 0 of FF: the coil's value */
    /* FC11: a CP-local reply, no job, nothing of the FC05 left */
    buf[0] = 0x0B;
    assert_int_equal(modcp_pdu_request(&s, &env, 5, buf, 1, sizeof buf, &out), MODCP_PDU_REPLY);
    assert_int_equal(out, 5);
    assert_false(s.same);
    assert_int_equal(s.x.echo, 0);
    assert_int_equal(s.x.exc, 0);
    assert_int_equal(s.x.seq, 0);
    assert_int_equal(s.job.op, 0);
    assert_int_equal(s.r32_kind, 0);
}

/* ---- not initialised, broadcast -------------------------------------------------- */

/* docs/cpu-cp-interface.md: until the FB's INIT every request gets 04 / (0E)56H, the extended set too. */
static void test_extended_not_initialised(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    modcp_fb_in_t in = {false};
    for (int k = 0; k < 20; k++) {
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        modcp_cp_poll(&w->cp, w->now_us);
        w->now_us += 1000;
    }
    assert_true(w->cp.configured);
    w->fb_paused = true;
    ext_expect_exception(w, S, "0B", 4, MODCP_EV_FB_NOT_RUNNING);
    ext_expect_exception(w, S, "11", 4, MODCP_EV_FB_NOT_RUNNING);
    ext_expect_exception(w, S, "2B 0E 01 00", 4, MODCP_EV_FB_NOT_RUNNING);
    ext_expect_exception(w, S, "08 00 0B 00 00", 4, MODCP_EV_FB_NOT_RUNNING);
    world_free(w);
}

static void test_broadcast_of_extended_fcs(void **state)
{
    (void)state;
    world_t *w = ext_started(NULL);
    const char *reqs[] = {"0B", "0C", "11", "2B 0E 01 00", "08 00 00 12 34",
                          "16 00 04 00 F2 00 25", "17 00 00 00 01 00 00 00 01 02 12 34"};
    for (size_t k = 0; k < sizeof reqs / sizeof reqs[0]; k++) {
        ext_expect_silence(w, 0, reqs[k]);
        assert_int_equal(world_last_event(w), MODCP_EV_BCAST_FC);
    }
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], 7);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_NO_RESPONSE], 7);
    assert_int_equal(world_db(w, 800)[1], 0x00);
    /* send events of broadcasts with an exception: 41, receive C0 */
    assert_int_equal(modcp_comm_log_at(&w->cp.diag.comm, 0), 0x41);
    assert_int_equal(modcp_comm_log_at(&w->cp.diag.comm, 1), 0xC0);
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_comm_log_ring),
        cmocka_unit_test(test_cp341_set),
        cmocka_unit_test(test_fc08_counters_after_known_traffic),
        cmocka_unit_test(test_fc08_wrap_and_saturation),
        cmocka_unit_test(test_fc08_overrun_and_diag_register),
        cmocka_unit_test(test_fc08_exceptions),
        cmocka_unit_test(test_fc08_ascii_delimiter),
        cmocka_unit_test(test_fc08_ascii_delimiter_end_to_end),
        cmocka_unit_test(test_fc08_ascii_delimiter_7bit),
        cmocka_unit_test(test_fc08_listen_only),
        cmocka_unit_test(test_fc08_restart_clear_log),
        cmocka_unit_test(test_fc12_event_log),
        cmocka_unit_test(test_fc12_log_wraps_at_64),
        cmocka_unit_test(test_fc17_report_slave_id),
        cmocka_unit_test(test_fc17_strings_from_params),
        cmocka_unit_test(test_fc22_mask_write),
        cmocka_unit_test(test_fc23_write_before_read),
        cmocka_unit_test(test_fc23_limits_and_checks),
        cmocka_unit_test(test_fc23_maximum_quantities),
        cmocka_unit_test(test_fc22_fc23_regs32),
        cmocka_unit_test(test_fc43_basic_default),
        cmocka_unit_test(test_fc43_regular_altivar_strings),
        cmocka_unit_test(test_fc43_exceptions),
        cmocka_unit_test(test_fc43_more_follows),
        cmocka_unit_test(test_fc_table_lookup),
        cmocka_unit_test(test_pdu_state_per_request),
        cmocka_unit_test(test_extended_not_initialised),
        cmocka_unit_test(test_broadcast_of_extended_fcs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
