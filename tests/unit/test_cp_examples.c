/* SPDX-License-Identifier: Apache-2.0 */
/* End to end through the core: frame in -> link -> PDU -> mapping -> job over the
 * backplane -> FB against controller memory -> reply out. Every worked example of
 * [RTU-2003] §6 with the [RTU-2003] §9 frames (CRC included), the 4.6.4 negative tests, every
 * exception code and event of docs/diagnostics.md, broadcast, and the not-ready states.
 * Built twice: unit.test_cp_examples against modcp_core, and unit.test_cp_manual
 * against modcp_core_manual (the feature switches of modcp/features.h off), where
 * MODCP_TEST_MANUAL adds the checks that the switched-off features are refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "world.h"
#include "backplane_internal.h"
#include "params_internal.h"

static world_t *started(const modcp_params_t *p)
{
    world_t *w = world_new(p);
    assert_true(world_start(w, 1000));
    assert_true(modcp_cp_ready(&w->cp));
    return w;
}

static void expect_reply(world_t *w, const char *req, const char *reply)
{
    uint16_t n = world_request(w, req, 100);
    assert_true(n > 0);
    assert_string_equal(world_reply_hex(w), reply);
}

static void expect_silence(world_t *w, const char *req)
{
    assert_int_equal(world_request(w, req, 100), 0);
}

/* Build a request (CRC appended) and expect exception `code` with event ev. */
static void expect_exception(world_t *w, const uint8_t *pdu_with_addr, size_t len, uint8_t code,
                             modcp_event_t ev)
{
    uint16_t n = world_request_raw(w, pdu_with_addr, len, 2000);
    assert_int_equal(n, 5);
    assert_int_equal(w->fake.tx[0], pdu_with_addr[0]);
    assert_int_equal(w->fake.tx[1], pdu_with_addr[1] | 0x80);
    assert_int_equal(w->fake.tx[2], code);
    assert_int_equal(world_last_event(w), ev);
}

/* [RTU-2003] §6.1 FC01 example: M 1008.0 .. M 1011.7 */
static void test_fc01_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    memcpy(&w->m[1008], "\x01\x17\x02\x18", 4);
    expect_reply(w, "05 01 00 40 00 20 3D 82", "05 01 04 01 17 02 18 0E 83");
    world_free(w);
}

/* FC01 with a start that is not byte-aligned: first addressed bit = bit 0 of byte 1 */
static void test_fc01_unaligned(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->m[1000] = 0xF0; /* M1000.4..7 = 1 */
    w->m[1001] = 0x05; /* M1001.0, .2 = 1 */
    /* coils 4..13 (10 bits): 1 1 1 1 1 0 1 0 0 0 */
    uint8_t req[] = {5, 1, 0x00, 0x04, 0x00, 0x0A};
    assert_int_equal(world_request_raw(w, req, sizeof req, 100), 7);
    assert_int_equal(w->fake.tx[2], 2);
    assert_int_equal(w->fake.tx[3], 0x5F);
    assert_int_equal(w->fake.tx[4], 0x00); /* unused high bits are zero */
    world_free(w);
}

/* FC01 on timers: whole words, high byte first (T 101 = 0x1234) */
static void test_fc01_timers(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->t[101] = 0x1234;
    w->t[102] = 0xABCD;
    /* 8.1: 1010H -> T 101; 32 bits = T101, T102 */
    uint8_t req[] = {5, 1, 0x10, 0x10, 0x00, 0x20};
    assert_int_equal(world_request_raw(w, req, sizeof req, 100), 9);
    assert_int_equal(w->fake.tx[2], 4);
    assert_memory_equal(&w->fake.tx[3], "\x12\x34\xAB\xCD", 4);
    world_free(w);
}

/* [RTU-2003] §6.2 FC02 example: I 134.0 .. I 136.7 */
static void test_fc02_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    memcpy(&w->i[134], "\x12\x34\x56", 3);
    expect_reply(w, "05 02 10 30 00 18 7D 4B", "05 02 03 12 34 56 4F 31");
    world_free(w);
}

/* [RTU-2003] §6.3 FC03 example: DB 800 DBW 160, 162 */
static void test_fc03_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    expect_reply(w, "05 03 00 50 00 02 C5 9E", "05 03 04 87 65 43 21 76 70");
    world_free(w);
}

/* [RTU-2003] §6.4 FC04 example: DB 901 DBW 384, 386, 388 */
static void test_fc04_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    memcpy(world_db(w, 901) + 384, "\xA1\xA2\xA3\xA4\xA5\xA6", 6);
    expect_reply(w, "05 04 02 C0 00 03 B0 0B", "05 04 06 A1 A2 A3 A4 A5 A6 2A 76");
    world_free(w);
}

/* [RTU-2003] §6.5 FC05 example: Q 257.1 set, other bits untouched */
static void test_fc05_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->q[257] = 0x80;
    expect_reply(w, "05 05 08 09 FF 00 5F DC", "05 05 08 09 FF 00 5F DC");
    assert_int_equal(w->q[257], 0x82);
    /* and reset again */
    uint8_t off[] = {5, 5, 0x08, 0x09, 0x00, 0x00};
    assert_int_equal(world_request_raw(w, off, sizeof off, 100), 8);
    assert_int_equal(w->q[257], 0x80);
    world_free(w);
}

/* [RTU-2003] §6.6 FC06 example: DB 800 DBW 768 = 2B1A */
static void test_fc06_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    expect_reply(w, "05 06 01 80 2B 1A 17 61", "05 06 01 80 2B 1A 17 61");
    assert_int_equal(world_db(w, 800)[768], 0x2B);
    assert_int_equal(world_db(w, 800)[769], 0x1A);
    world_free(w);
}

/* [RTU-2003] §6.7 FC08 example: echo */
static void test_fc08_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    world_free(w);
}

/* [RTU-2003] §6.8 FC15 example: M 1144 = CD, M 1145.0..3 = 1001, M 1145.4..7 untouched */
static void test_fc15_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->m[1145] = 0xF0;
    expect_reply(w, "05 0F 04 80 00 0C 02 CD 09 19 E6", "05 0F 04 80 00 0C 54 92");
    assert_int_equal(w->m[1144], 0xCD);
    assert_int_equal(w->m[1145], 0xF9);
    assert_true(w->fb_out.cp_start_ok);
    world_free(w);
}

/* [RTU-2003] §6.9 FC16 example: DB 800 DBW 100, 102, 104 */
static void test_fc16_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    expect_reply(w, "05 10 00 32 00 03 06 CD 09 DE 1A EF 2B 92 ED", "05 10 00 32 00 03 20 43");
    assert_memory_equal(world_db(w, 800) + 100, "\xCD\x09\xDE\x1A\xEF\x2B", 6);
    world_free(w);
}

/* [RTU-2003] §5.4 exception example: slave 5, FC 05, code 02 -> 05 85 02 82 90 */
static void test_exception_frame_example(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    uint8_t req[] = {5, 5, 0x14, 0x00, 0xFF, 0x00}; /* coil 5120: outside every window */
    assert_int_equal(world_request_raw(w, req, sizeof req, 100), 5);
    assert_string_equal(world_reply_hex(w), "05 85 02 82 90");
    assert_int_equal(world_last_event(w), MODCP_EV_NO_WINDOW);
    world_free(w);
}

/* [RTU-2003] §3.5 / 4.6.4 limits (DB 600-699, MB 1000-1127, QB 256-319) reject the FC15
 * example at MB 1144 and the FC06/16 examples in DB 800: exception 02, (0E)52H,
 * nothing written. */
static void test_manual_464_limits_reject(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.lim_db = (modcp_limit_t){600, 699};
    p.lim_m = (modcp_limit_t){1000, 1127};
    p.lim_q = (modcp_limit_t){256, 319};
    world_t *w = started(&p);
    uint8_t fc15[] = {5, 0x0F, 0x04, 0x80, 0x00, 0x0C, 0x02, 0xCD, 0x09};
    expect_exception(w, fc15, sizeof fc15, 2, MODCP_EV_WRITE_DENIED);
    assert_int_equal(w->m[1144], 0);
    uint8_t fc06[] = {5, 0x06, 0x01, 0x80, 0x2B, 0x1A};
    expect_exception(w, fc06, sizeof fc06, 2, MODCP_EV_WRITE_DENIED);
    uint8_t fc16[] = {5, 0x10, 0x00, 0x32, 0x00, 0x03, 0x06, 0xCD, 0x09, 0xDE, 0x1A, 0xEF, 0x2B};
    expect_exception(w, fc16, sizeof fc16, 2, MODCP_EV_WRITE_DENIED);
    assert_int_equal(world_db(w, 800)[768], 0);
    assert_int_equal(world_db(w, 800)[100], 0);
    /* the FC05 example (Q 257) is inside QB 256-319 and still works */
    expect_reply(w, "05 05 08 09 FF 00 5F DC", "05 05 08 09 FF 00 5F DC");
    assert_int_equal(w->q[257], 0x02);
    world_free(w);
}

/* docs/diagnostics.md exception 01 */
static void test_exception_01(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_CP341;
    world_t *w = started(&p);
    uint8_t fc41[] = {5, 0x41, 0x00};
    expect_exception(w, fc41, sizeof fc41, 1, MODCP_EV_ILLEGAL_FC);
    uint8_t fc07[] = {5, 0x07};
    expect_exception(w, fc07, sizeof fc07, 1, MODCP_EV_ILLEGAL_FC);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], 2);
    world_free(w);
}

/* docs/diagnostics.md exception 02 with each event */
static void test_exception_02(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    uint8_t no_window[] = {5, 0x01, 0x0A, 0x00, 0x00, 0x01}; /* coil 2560: gap */
    expect_exception(w, no_window, sizeof no_window, 2, MODCP_EV_NO_WINDOW);
    uint8_t tc_align[] = {5, 0x01, 0x10, 0x01, 0x00, 0x10}; /* 4097: not on a T word */
    expect_exception(w, tc_align, sizeof tc_align, 2, MODCP_EV_TC_ALIGN);
    uint8_t t_write[] = {5, 0x05, 0x10, 0x00, 0xFF, 0x00}; /* FC05 on T 100 */
    expect_exception(w, t_write, sizeof t_write, 2, MODCP_EV_AREA_READONLY);
    uint8_t past_end[] = {5, 0x01, 0x07, 0xF8, 0x00, 0x10}; /* 2040 + 16 > 2047 */
    expect_exception(w, past_end, sizeof past_end, 2, MODCP_EV_PAST_END);
    uint8_t cross_db[] = {5, 0x03, 0x01, 0xFE, 0x00, 0x03}; /* word 510 + 3 > 512 */
    expect_exception(w, cross_db, sizeof cross_db, 2, MODCP_EV_DB_ACCESS);
    uint8_t inside[] = {5, 0x05, 0x00, 0x00, 0xFF, 0x00}; /* M 1000.0: inside the limits */
    assert_int_equal(world_request_raw(w, inside, sizeof inside, 100), 8);
    assert_int_equal(w->m[1000], 0x01);
    world_free(w);

    /* DB overflow: base 65500, register 0x8000 -> DB 65564 */
    modcp_params_t p;
    world_example_params(&p);
    p.hr_base_db = 65500;
    w = started(&p);
    uint8_t overflow[] = {5, 0x03, 0x80, 0x00, 0x00, 0x01};
    expect_exception(w, overflow, sizeof overflow, 2, MODCP_EV_DB_OVERFLOW);
    world_free(w);

    /* write to the FB's work area: holding base = work DB */
    world_example_params(&p);
    p.hr_base_db = WORLD_WORK_DB;
    p.lim_db = (modcp_limit_t){1, 1000};
    w = started(&p);
    uint8_t wd[] = {5, 0x06, 0x00, 0x00, 0x12, 0x34};
    expect_exception(w, wd, sizeof wd, 2, MODCP_EV_WRITE_DENIED);
    /* reading it is allowed */
    uint8_t rd[] = {5, 0x03, 0x00, 0x00, 0x00, 0x01};
    assert_int_equal(world_request_raw(w, rd, sizeof rd, 100), 7);
    world_free(w);
}

/* docs/diagnostics.md exception 03 with each event */
static void test_exception_03(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_CP341;
    world_t *w = started(&p);
    uint8_t qty0[] = {5, 0x03, 0x00, 0x00, 0x00, 0x00};
    expect_exception(w, qty0, sizeof qty0, 3, MODCP_EV_QUANTITY);
    uint8_t regs128[] = {5, 0x03, 0x00, 0x00, 0x00, 0x80};
    expect_exception(w, regs128, sizeof regs128, 3, MODCP_EV_QUANTITY);
    uint8_t bits2041[] = {5, 0x01, 0x00, 0x00, 0x07, 0xF9};
    expect_exception(w, bits2041, sizeof bits2041, 3, MODCP_EV_QUANTITY);
    uint8_t tc_qty[] = {5, 0x01, 0x10, 0x00, 0x00, 0x08}; /* 8 bits of T */
    expect_exception(w, tc_qty, sizeof tc_qty, 3, MODCP_EV_QUANTITY);
    uint8_t bc[] = {5, 0x0F, 0x04, 0x80, 0x00, 0x0C, 0x01, 0xCD}; /* 12 bits, 1 byte */
    expect_exception(w, bc, sizeof bc, 3, MODCP_EV_BYTE_COUNT);
    uint8_t bc16[] = {5, 0x10, 0x00, 0x32, 0x00, 0x02, 0x02, 0xCD, 0x09};
    expect_exception(w, bc16, sizeof bc16, 3, MODCP_EV_BYTE_COUNT);
    uint8_t coil_value[] = {5, 0x05, 0x08, 0x09, 0x12, 0x34};
    expect_exception(w, coil_value, sizeof coil_value, 3, MODCP_EV_COIL_VALUE);
    uint8_t sub[] = {5, 0x08, 0x00, 0x01, 0x00, 0x00};
    expect_exception(w, sub, sizeof sub, 3, MODCP_EV_DIAG_SUBFC);
    assert_int_equal(w->q[257], 0);
    world_free(w);
}

/* docs/diagnostics.md exception 04: FB not initialised */
static void test_exception_04_not_initialised(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    /* PARAMS arrive with the FB's first call, but no CP_START yet */
    modcp_fb_in_t in = {false};
    for (int k = 0; k < 20; k++) {
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        modcp_cp_poll(&w->cp, w->now_us);
        w->now_us += 1000;
    }
    assert_true(w->cp.configured);
    assert_false(w->cp.env.fb_ready);
    w->fb_paused = true;
    uint8_t fc03[] = {5, 0x03, 0x00, 0x50, 0x00, 0x02};
    expect_exception(w, fc03, sizeof fc03, 4, MODCP_EV_FB_NOT_RUNNING);
    uint8_t fc08[] = {5, 0x08, 0x00, 0x00, 0xA5, 0xC3};
    expect_exception(w, fc08, sizeof fc08, 4, MODCP_EV_FB_NOT_RUNNING);
    world_free(w);
}

/* docs/diagnostics.md exception 04: CPU job timeouts (0E)31H (read) and (0E)3BH (FB bit write) */
static void test_exception_04_timeouts(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->fb_paused = true; /* the user program stopped calling the FB */
    uint8_t fc03[] = {5, 0x03, 0x00, 0x50, 0x00, 0x02};
    uint32_t t0 = w->now_us;
    expect_exception(w, fc03, sizeof fc03, 4, MODCP_EV_XFER_TIMEOUT);
    uint32_t waited = w->now_us - t0;
    assert_true(waited >= 1000000u && waited < 1100000u); /* cpu_timeout 1000 ms */
    uint8_t fc05[] = {5, 0x05, 0x08, 0x09, 0xFF, 0x00};
    expect_exception(w, fc05, sizeof fc05, 4, MODCP_EV_FB_TIMEOUT);
    /* the FB runs again: the cancelled write is not executed afterwards */
    w->fb_paused = false;
    world_run(w, 50000);
    assert_int_equal(w->q[257], 0);
    /* and the next good request is served normally */
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    expect_reply(w, "05 03 00 50 00 02 C5 9E", "05 03 04 87 65 43 21 76 70");
    world_free(w);
}

/* docs/diagnostics.md exception 04: DB missing, job longer than the transfer limit */
static void test_exception_04_cpu_errors(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.job_limit = 32; /* one block per job */
    world_t *w = started(&p);
    uint8_t db803[] = {5, 0x03, 0x06, 0x00, 0x00, 0x01}; /* register 1536 -> DB 803 */
    expect_exception(w, db803, sizeof db803, 4, MODCP_EV_DB_ACCESS);
    uint8_t big[] = {5, 0x03, 0x00, 0x00, 0x00, 0x11}; /* 17 registers = 34 bytes */
    expect_exception(w, big, sizeof big, 4, MODCP_EV_JOB_LENGTH);
    uint8_t ok[] = {5, 0x03, 0x00, 0x00, 0x00, 0x10}; /* 16 registers = 32 bytes */
    assert_int_equal(world_request_raw(w, ok, sizeof ok, 100), 37);
    world_free(w);
}

/* Broadcast: FC 05/06/15/16 executed and never answered; others dropped, (08)30H */
static void test_broadcast(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    uint8_t fc06[] = {0, 0x06, 0x01, 0x80, 0x2B, 0x1A};
    assert_int_equal(world_request_raw(w, fc06, sizeof fc06, 100), 0);
    world_run(w, 20000);
    assert_int_equal(world_db(w, 800)[768], 0x2B);
    uint8_t fc05[] = {0, 0x05, 0x08, 0x09, 0xFF, 0x00};
    assert_int_equal(world_request_raw(w, fc05, sizeof fc05, 100), 0);
    world_run(w, 20000);
    assert_int_equal(w->q[257], 0x02);
    uint8_t fc15[] = {0, 0x0F, 0x04, 0x80, 0x00, 0x0C, 0x02, 0xCD, 0x09};
    assert_int_equal(world_request_raw(w, fc15, sizeof fc15, 100), 0);
    uint8_t fc16[] = {0, 0x10, 0x00, 0x32, 0x00, 0x01, 0x02, 0xBE, 0xEF};
    assert_int_equal(world_request_raw(w, fc16, sizeof fc16, 100), 0);
    world_run(w, 20000);
    assert_int_equal(w->m[1144], 0xCD);
    assert_int_equal(world_db(w, 800)[100], 0xBE);
    /* a broadcast read is dropped with (08)30H, no reply */
    uint8_t fc03[] = {0, 0x03, 0x00, 0x50, 0x00, 0x02};
    assert_int_equal(world_request_raw(w, fc03, sizeof fc03, 100), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_BCAST_FC);
    /* a broadcast write with an error is not answered either */
    uint8_t bad[] = {0, 0x05, 0x08, 0x09, 0x12, 0x34};
    assert_int_equal(world_request_raw(w, bad, sizeof bad, 100), 0);
    assert_int_equal(world_last_event(w), MODCP_EV_COIL_VALUE);
    world_free(w);
}

/* Frames for another address and CRC errors: silence */
static void test_other_address_and_crc(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    uint8_t other[] = {6, 0x03, 0x00, 0x50, 0x00, 0x02}; /* slave 6, valid CRC */
    assert_int_equal(world_request_raw(w, other, sizeof other, 100), 0);
    assert_int_equal(w->cp.diag.buffer_len, 0); /* not checked, no event */
    expect_silence(w, "05 03 00 50 00 02 C5 9F"); /* bad CRC */
    assert_int_equal(world_last_event(w), MODCP_EV_CRC);
    /* the CPU side sees it in the status area of the backplane */
    world_run(w, 1000);
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    assert_int_equal(st.buffer[0], MODCP_EV_CRC);
    assert_int_equal(st.status, 0x0836);
    assert_int_equal(st.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(st.counters[MODCP_CNT_BUS_MSG], 1);   /* the frame for slave 6 */
    assert_int_equal(st.counters[MODCP_CNT_SLAVE_MSG], 0);
    assert_true(st.flags & MODCP_CPST_READY);
    assert_false(st.flags & MODCP_CPST_SF);
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4);
    expect_reply(w, "05 03 00 50 00 02 C5 9E", "05 03 04 87 65 43 21 76 70");
    world_free(w);
}

/* Invalid parameter record: not ready, never half-configured; FB init fails with
 * ERROR_NR 2 and ERROR_INFO = the CP's event. */
static void test_bad_params_not_ready(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.slave_addr = 0;
    p.start_time_ms = 500;
    world_t *w = world_new(&p);
    assert_false(world_start(w, 2000));
    assert_true(w->fb_out.cp_start_error);
    assert_int_equal(w->fb_out.error_nr, 2);
    assert_int_equal(w->fb_out.error_info, MODCP_EV_SLAVE_ADDR);
    assert_false(w->cp.configured);
    /* the line is ignored: nothing answers, not even address 222 or 0 */
    expect_silence(w, "05 08 00 00 A5 C3 DA 8E");
    bool found = false;
    for (unsigned k = 0; k < w->cp.diag.buffer_len; k++) {
        found |= w->cp.diag.buffer[k] == MODCP_EV_SLAVE_ADDR;
    }
    assert_true(found);
    world_free(w);
}

/* f_MUL out of range: (0E)21H, runs with 1 (t3.5 = 4 ms at 9600) */
static void test_fmul_corrected(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.f_mul = 11;
    world_t *w = started(&p);
    bool found = false;
    for (unsigned k = 0; k < w->cp.diag.buffer_len; k++) {
        found |= w->cp.diag.buffer[k] == MODCP_EV_FMUL;
    }
    assert_true(found);
    assert_int_equal(w->cp.params.f_mul, 1);
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    assert_int_equal(w->fake.timer_us, 4000);
    world_free(w);
}

#if defined(MODCP_TEST_MANUAL)
/* ---- the core built for the manual's function set (modcp_core_manual) ------------- */

_Static_assert(!MODCP_WITH_EXTENDED && !MODCP_WITH_ASCII && !MODCP_WITH_RS232_SIGNALS &&
                   MODCP_SHARED_PARAMS_BUFFER,
               "unit.test_cp_manual must be built against modcp_core_manual");

/* A record asking for a feature compiled out of the image: refused with (0E)2EH and
 * the field, the CP stays not ready (FB: CP_START_ERROR, ERROR_INFO 0E2EH). */
static void refused(const modcp_params_t *p, modcp_param_field_t field)
{
    modcp_param_issue_t issues[8];
    size_t n = modcp_params_validate(p, issues, 8);
    assert_int_equal(n, 1);
    assert_int_equal(issues[0].field, field);
    assert_true(issues[0].fatal);
    assert_int_equal(issues[0].event, MODCP_EV_PARAM_RECORD);

    modcp_params_t q = *p;
    q.start_time_ms = 500;
    world_t *w = world_new(&q);
    assert_false(world_start(w, 2000));
    assert_true(w->fb_out.cp_start_error);
    assert_int_equal(w->fb_out.error_info, MODCP_EV_PARAM_RECORD);
    assert_false(w->cp.configured);
    assert_int_equal(w->cp.param_event, MODCP_EV_PARAM_RECORD);
    expect_silence(w, "05 08 00 00 A5 C3 DA 8E");
    world_free(w);
}

static void test_manual_refuses_compiled_out(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    assert_int_equal(p.fset, MODCP_FSET_CP341); /* the default of this build */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);

    modcp_params_t q = p;
    q.framing = MODCP_FRAMING_ASCII;
    refused(&q, MODCP_PF_FRAMING);
    q = p;
    q.fset = MODCP_FSET_EXTENDED;
    refused(&q, MODCP_PF_FSET);
    q = p;
    q.commloss_ms = 1000;
    refused(&q, MODCP_PF_COMMLOSS);
    q = p;
    q.scan_start = 9000;
    q.scan_count = 1; /* (the entries themselves are not kept without the extended set) */
    refused(&q, MODCP_PF_SCANNER);
    q = p;
    q.iface = MODCP_IFACE_RS232;
    q.rs232_auto = 1;
    refused(&q, MODCP_PF_RS232_AUTO);
}

/* The extended function codes and FC08 sub-functions answer as in the cp341 set; the
 * frame buffer is the RTU ADU. */
static void test_manual_cp341_set(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    assert_int_equal(w->cp.link.size, MODCP_ADU_MAX);
    assert_int_equal(w->cp.link.cap, MODCP_ADU_MAX);
    static const uint8_t fc11[] = {0x05, 0x0B};
    expect_exception(w, fc11, sizeof fc11, 1, MODCP_EV_ILLEGAL_FC);
    static const uint8_t fc23[] = {0x05, 0x17, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00,
                                   0x00, 0x01, 0x02, 0x12, 0x34};
    expect_exception(w, fc23, sizeof fc23, 1, MODCP_EV_ILLEGAL_FC);
    static const uint8_t sub01[] = {0x05, 0x08, 0x00, 0x01, 0x00, 0x00};
    expect_exception(w, sub01, sizeof sub01, 3, MODCP_EV_DIAG_SUBFC);
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    modcp_cp_on_signals(&w->cp, false, false, w->now_us); /* no signals: ignored */
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    world_free(w);
}

/* ---- PARAMS record in the frame buffer (MODCP_SHARED_PARAMS_BUFFER) ---------------- */

/* The CPU side sends its record again, block by block, as the FB does (its sequence
 * numbers), without running the FB: blocks *k.. up to `blocks` of them, as many as
 * the ring takes. Returns true when the whole record is out. */
static bool push_record(world_t *w, size_t *k, size_t blocks)
{
    size_t total = (w->record_len + MODCP_BLOCK_SIZE - 1u) / MODCP_BLOCK_SIZE;
    for (size_t m = 0; m < blocks && *k < total; m++) {
        size_t off = *k * MODCP_BLOCK_SIZE;
        size_t n = w->record_len - off < MODCP_BLOCK_SIZE ? w->record_len - off : MODCP_BLOCK_SIZE;
        uint8_t flags = (uint8_t)((*k == 0 ? MODCP_BLK_FIRST : 0) | (*k + 1 == total ? MODCP_BLK_LAST : 0));
        if (!modcp_ring_put_data(&w->bp.to_cp, &w->fb.tx_seq, MODCP_BP_PARAMS, flags, 0,
                                 w->record + off, (uint8_t)n)) {
            break; /* ring full */
        }
        ++*k;
    }
    return *k == total;
}

/* Push the rest of the record, polling the CP as the ring fills. */
static void push_rest(world_t *w, size_t *k)
{
    for (int guard = 0; guard < 100; guard++) {
        bool all = push_record(w, k, 1000);
        w->now_us += 1000;
        modcp_cp_poll(&w->cp, w->now_us);
        if (all) {
            return;
        }
    }
    fail();
}

/* The FB starts the CP again (CP_START edge) and it becomes ready. */
static void restart(world_t *w)
{
    w->fb_paused = false;
    modcp_fb_in_t in = {false};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    assert_true(world_start(w, 2000));
    assert_true(modcp_cp_ready(&w->cp));
}

/* A record arriving while a request waits for its CPU job: the request is dropped
 * before the first record byte lands in the frame buffer, nothing is ever sent for it
 * (not even when the CPU side answers the old job later), the record is taken. */
static void test_shared_record_during_request(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    assert_true(w->cp.job.msgbuf == w->cp.buf);
    w->fb_paused = true;
    unsigned sent = w->fake.tx_count;
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9E", 5), 0);
    assert_true(w->cp.request_pending);
    assert_int_equal(w->cp.link.state, MODCP_LINK_BUSY);

    size_t k = 0;
    assert_false(push_record(w, &k, 1)); /* first block only */
    modcp_cp_poll(&w->cp, w->now_us);
    assert_false(w->cp.request_pending);
    assert_false(w->cp.configured);
    assert_false(w->cp.link.enabled);
    assert_false(modcp_job_busy(&w->cp.job));
    assert_memory_equal(w->cp.buf, w->record, MODCP_BLOCK_SIZE);
    /* the line is off while the record arrives */
    assert_int_equal(world_request(w, "05 08 00 00 A5 C3 DA 8E", 5), 0);

    /* the rest: the CP is configured again with the same record */
    push_rest(w, &k);
    assert_true(w->cp.configured);
    assert_int_equal(w->cp.param_event, MODCP_EV_NONE);
    assert_int_equal(w->fake.tx_count, sent);

    restart(w); /* the FB runs the old job too: its late reply is dropped */
    assert_int_equal(w->fake.tx_count, sent);
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    world_free(w);
}

/* A record arriving while a reply is on the line: the reply is sent from the frame
 * buffer, so the record waits in the backplane until transmission complete. */
static void test_shared_record_during_reply(void **state)
{
    (void)state;
    world_t *w = started(NULL);
    w->fb_paused = true;
    static const uint8_t req[] = {0x05, 0x08, 0x00, 0x00, 0xA5, 0xC3, 0xDA, 0x8E};
    unsigned sent = w->fake.tx_count;
    for (size_t k = 0; k < sizeof req; k++) {
        modcp_cp_on_rx(&w->cp, req[k], w->now_us);
        w->now_us += 10;
    }
    w->now_us += w->fake.timer_us;
    modcp_cp_on_timer(&w->cp, w->now_us);
    assert_int_equal(w->fake.tx_count, sent + 1);
    assert_int_equal(w->cp.link.state, MODCP_LINK_TX); /* no transmission complete yet */
    uint16_t n = w->fake.tx_len;
    assert_memory_equal(w->fake.tx, req, sizeof req);

    size_t k = 0;
    (void)push_record(w, &k, 1000);
    for (int m = 0; m < 5; m++) {
        w->now_us += 1000;
        modcp_cp_poll(&w->cp, w->now_us);
    }
    /* still sending: the reply bytes in the buffer are untouched, the record waits */
    assert_int_equal(w->cp.link.state, MODCP_LINK_TX);
    assert_memory_equal(w->cp.buf, w->fake.tx, n);
    assert_true(w->cp.configured);
    assert_int_equal(w->cp.job.msgkind, 0);

    assert_non_null(modcp_ring_peek(&w->bp.to_cp)); /* the record's first block */
    modcp_cp_on_tx_done(&w->cp, w->now_us);
    push_rest(w, &k);
    assert_true(w->cp.configured); /* the record was taken */
    assert_int_equal(w->cp.param_event, MODCP_EV_NONE);
    /* the record the CP holds already: no re-parameterisation ([RTU-2003] §4.2 step 4), the
     * FB's initialisation stays */
    assert_true(w->cp.env.fb_ready);
    assert_int_equal(w->fake.tx_count, sent + 1);
    restart(w);
    expect_reply(w, "05 08 00 00 A5 C3 DA 8E", "05 08 00 00 A5 C3 DA 8E");
    world_free(w);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fc01_example),
        cmocka_unit_test(test_fc01_unaligned),
        cmocka_unit_test(test_fc01_timers),
        cmocka_unit_test(test_fc02_example),
        cmocka_unit_test(test_fc03_example),
        cmocka_unit_test(test_fc04_example),
        cmocka_unit_test(test_fc05_example),
        cmocka_unit_test(test_fc06_example),
        cmocka_unit_test(test_fc08_example),
        cmocka_unit_test(test_fc15_example),
        cmocka_unit_test(test_fc16_example),
        cmocka_unit_test(test_exception_frame_example),
        cmocka_unit_test(test_manual_464_limits_reject),
        cmocka_unit_test(test_exception_01),
        cmocka_unit_test(test_exception_02),
        cmocka_unit_test(test_exception_03),
        cmocka_unit_test(test_exception_04_not_initialised),
        cmocka_unit_test(test_exception_04_timeouts),
        cmocka_unit_test(test_exception_04_cpu_errors),
        cmocka_unit_test(test_broadcast),
        cmocka_unit_test(test_other_address_and_crc),
        cmocka_unit_test(test_bad_params_not_ready),
        cmocka_unit_test(test_fmul_corrected),
#if defined(MODCP_TEST_MANUAL)
        cmocka_unit_test(test_manual_refuses_compiled_out),
        cmocka_unit_test(test_manual_cp341_set),
        cmocka_unit_test(test_shared_record_during_request),
        cmocka_unit_test(test_shared_record_during_reply),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
