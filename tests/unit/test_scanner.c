/* SPDX-License-Identifier: Apache-2.0 */
/* Indirection scanner (docs/extended-functions.md, [ALTIVAR] §11): consecutive holding registers that each
 * point at a word operand; FC03/06/16/22/23 on them act on the operands, one CPU job
 * per operand, the reply after all jobs came back; the access rules of direct access. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"

#define S 5

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)v;
}

/* [ALTIVAR] §11 worked example, byte for byte: FC23 to slave 20 reads the 8 monitoring
 * scanner registers NM1..NM8 (W12741.. = 31C5H) and writes 6 command words NC1..NC6
 * (W12761.. = 31D9H). Here NM1..NM8 are scanner registers pointing at MW100, IW10,
 * DB801.DBW0, T5, C7, QW4, DB802.DBW10 and an unused entry (LFT = 0000); the command
 * words are ordinary registers: base DB 776, so 12761 = DB 800 DBW 946. */
static void test_altivar_fc23_scanner_example(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.slave_addr = 20;
    p.hr_base_db = 776;
    p.scan_start = 12741;
    p.scan_count = 8;
    p.scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 100};
    p.scan[1] = (modcp_operand_ref_t){MODCP_AREA_I, 0, 10};
    p.scan[2] = (modcp_operand_ref_t){MODCP_AREA_DB, 801, 0};
    p.scan[3] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 5};
    p.scan[4] = (modcp_operand_ref_t){MODCP_AREA_C, 0, 7};
    p.scan[5] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 4};
    p.scan[6] = (modcp_operand_ref_t){MODCP_AREA_DB, 802, 10};
    p.scan[7] = (modcp_operand_ref_t){MODCP_AREA_NONE, 0, 0};
    world_t *w = ext_started(&p);
    put16(&w->m[100], 0x0007);       /* ETA */
    put16(&w->i[10], 0x1388);        /* RFRD */
    put16(world_db(w, 801), 0x0064); /* LCR */
    w->t[5] = 0x0045;                /* OTR */
    w->c[7] = 0x00F0;                /* ULN */
    put16(&w->q[4], 0x0065);         /* THD */
    put16(world_db(w, 802) + 10, 0x0032); /* THR */
    uint32_t jobs = w->fb.jobs_done;
    uint16_t n = world_request(w, "14 17 31 C5 00 08 31 D9 00 06 0C 00 0F 13 88 1F 40 01 F4 04 "
                                  "B0 02 58 56 3D",
                               2000);
    assert_int_equal(n, 21);
    assert_string_equal(world_reply_hex(w),
                        "14 17 10 00 07 13 88 00 64 00 45 00 F0 00 65 00 32 00 00 E4 90");
    assert_memory_equal(world_db(w, 800) + 946,
                        "\x00\x0F\x13\x88\x1F\x40\x01\xF4\x04\xB0\x02\x58", 12);
    assert_int_equal(w->fb.jobs_done - jobs, 1 + 7); /* the write, 7 scattered reads */
    world_free(w);
}

static void scan_params(modcp_params_t *p)
{
    world_example_params(p);
    p->scan_start = 0x0050; /* over DB 800 DBW 160: the scanner has priority */
    p->scan_count = 8;
    p->scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 100};
    p->scan[1] = (modcp_operand_ref_t){MODCP_AREA_I, 0, 10};
    p->scan[2] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 4};
    p->scan[3] = (modcp_operand_ref_t){MODCP_AREA_DB, 801, 0};
    p->scan[4] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 5};
    p->scan[5] = (modcp_operand_ref_t){MODCP_AREA_C, 0, 7};
    p->scan[6] = (modcp_operand_ref_t){MODCP_AREA_NONE, 0, 0};
    p->scan[7] = (modcp_operand_ref_t){MODCP_AREA_DB, 900, 2};
}

static void test_scanner_reads(void **state)
{
    (void)state;
    modcp_params_t p;
    scan_params(&p);
    world_t *w = ext_started(&p);
    memcpy(world_db(w, 800) + 160, "\x87\x65\x43\x21", 4); /* hidden by the scanner */
    put16(&w->m[100], 0x1111);
    put16(&w->i[10], 0x2222);
    put16(&w->q[4], 0x3333);
    put16(world_db(w, 801), 0x4444);
    w->t[5] = 0x5555;
    w->c[7] = 0x6666;
    put16(world_db(w, 900) + 2, 0x7777);
    uint32_t jobs = w->fb.jobs_done;
    ext_expect(w, S, "03 00 50 00 08", "03 10 11 11 22 22 33 33 44 44 55 55 66 66 00 00 77 77");
    assert_int_equal(w->fb.jobs_done - jobs, 7); /* the unused entry needs no job */
    ext_expect(w, S, "03 00 53 00 02", "03 04 44 44 55 55");
    /* the request must lie inside the scanner */
    ext_expect_exception(w, S, "03 00 4F 00 02", 2, MODCP_EV_PAST_END);
    ext_expect_exception(w, S, "03 00 57 00 02", 2, MODCP_EV_PAST_END);
    ext_expect_exception(w, S, "03 00 00 00 7F", 2, MODCP_EV_PAST_END);
    /* only unused entries: nothing to read */
    ext_expect_exception(w, S, "03 00 56 00 01", 2, MODCP_EV_NO_WINDOW);
    ext_expect_exception(w, S, "03 00 50 00 80", 3, MODCP_EV_QUANTITY);
    ext_expect_exception(w, S, "03 00 50 00 01 00", 3, MODCP_EV_BYTE_COUNT);
    /* outside the scanner the DB scheme is unchanged; FC04 is never scanned */
    ext_expect(w, S, "03 00 4E 00 02", "03 04 00 00 00 00");
    memcpy(world_db(w, 900) + 160, "\xAB\xCD", 2);
    ext_expect(w, S, "04 00 50 00 01", "04 02 AB CD");
    world_free(w);
}

/* Operands beyond the controller's areas, and a DB the CPU side does not have. */
static void test_scanner_read_errors(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.scan_start = 0x1000;
    p.scan_count = 4;
    p.scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 2599}; /* MW2599 needs MB2600 */
    p.scan[1] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 240};
    p.scan[2] = (modcp_operand_ref_t){MODCP_AREA_DB, 807, 0};
    p.scan[3] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 2598};
    world_t *w = ext_started(&p);
    ext_expect_exception(w, S, "03 10 00 00 01", 2, MODCP_EV_PAST_END);
    ext_expect_exception(w, S, "03 10 01 00 01", 2, MODCP_EV_PAST_END);
    ext_expect_exception(w, S, "03 10 02 00 01", 4, MODCP_EV_DB_ACCESS);
    put16(&w->m[2598], 0xBEEF);
    ext_expect(w, S, "03 10 03 00 01", "03 02 BE EF");
    world_free(w);
}

static void write_params(modcp_params_t *p)
{
    world_example_params(p);
    p->lim_db = (modcp_limit_t){80, 899}; /* includes the work DB 80: refused anyway */
    p->scan_start = 0x1000;
    p->scan_count = 11;
    p->scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 1000};
    p->scan[1] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 256};
    p->scan[2] = (modcp_operand_ref_t){MODCP_AREA_DB, 801, 20};
    p->scan[3] = (modcp_operand_ref_t){MODCP_AREA_NONE, 0, 0};
    p->scan[4] = (modcp_operand_ref_t){MODCP_AREA_I, 0, 10};
    p->scan[5] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 5};
    p->scan[6] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 10};   /* below lim_m 1000 */
    p->scan[7] = (modcp_operand_ref_t){MODCP_AREA_DB, 900, 0}; /* above lim_db */
    p->scan[8] = (modcp_operand_ref_t){MODCP_AREA_DB, WORLD_WORK_DB, 0};
    p->scan[9] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 319};  /* QW319 needs QB320 */
    p->scan[10] = (modcp_operand_ref_t){MODCP_AREA_C, 0, 1};
}

static void test_scanner_writes(void **state)
{
    (void)state;
    modcp_params_t p;
    write_params(&p);
    world_t *w = ext_started(&p);
    ext_expect(w, S, "06 10 00 12 34", "06 10 00 12 34");
    assert_int_equal(w->m[1000], 0x12);
    assert_int_equal(w->m[1001], 0x34);
    uint32_t jobs = w->fb.jobs_done;
    ext_expect(w, S, "10 10 00 00 04 08 AA BB CC DD EE FF 11 22", "10 10 00 00 04");
    assert_int_equal(w->fb.jobs_done - jobs, 3); /* the unused entry discards its value */
    assert_memory_equal(&w->m[1000], "\xAA\xBB", 2);
    assert_memory_equal(&w->q[256], "\xCC\xDD", 2);
    assert_memory_equal(world_db(w, 801) + 20, "\xEE\xFF", 2);
    /* the access rules of direct writes */
    ext_expect_exception(w, S, "06 10 03 00 01", 2, MODCP_EV_NO_WINDOW);     /* unused */
    ext_expect_exception(w, S, "06 10 04 00 01", 2, MODCP_EV_AREA_READONLY); /* IW */
    ext_expect_exception(w, S, "06 10 05 00 01", 2, MODCP_EV_AREA_READONLY); /* T */
    ext_expect_exception(w, S, "06 10 0A 00 01", 2, MODCP_EV_AREA_READONLY); /* C */
    ext_expect_exception(w, S, "06 10 06 00 01", 2, MODCP_EV_WRITE_DENIED);  /* M limits */
    ext_expect_exception(w, S, "06 10 07 00 01", 2, MODCP_EV_WRITE_DENIED);  /* DB limits */
    ext_expect_exception(w, S, "06 10 08 00 01", 2, MODCP_EV_WRITE_DENIED);  /* work DB */
    ext_expect_exception(w, S, "06 10 09 00 01", 2, MODCP_EV_PAST_END);      /* Q area */
    /* a bad entry anywhere in the range: nothing is written */
    ext_expect_exception(w, S, "10 10 02 00 03 06 01 01 02 02 03 03", 2,
                         MODCP_EV_AREA_READONLY);
    assert_memory_equal(world_db(w, 801) + 20, "\xEE\xFF", 2);
    ext_expect_exception(w, S, "10 10 00 00 02 02 01 01", 3, MODCP_EV_BYTE_COUNT);
    ext_expect_exception(w, S, "10 0F FF 00 02 04 01 01 02 02", 2, MODCP_EV_PAST_END);
    /* reads of the same operands are allowed where writes are not */
    w->t[5] = 0x0102;
    ext_expect(w, S, "03 10 04 00 02", "03 04 00 00 01 02");
    /* broadcast writes through the scanner are executed, not answered */
    ext_expect_silence(w, 0, "06 10 00 56 78");
    assert_memory_equal(&w->m[1000], "\x56\x78", 2);
    world_free(w);
}

/* FC22 and FC23 through the scanner. */
static void test_scanner_fc22_fc23(void **state)
{
    (void)state;
    modcp_params_t p;
    write_params(&p);
    world_t *w = ext_started(&p);
    put16(&w->m[1000], 0x0012);
    ext_expect(w, S, "16 10 00 00 F2 00 25", "16 10 00 00 F2 00 25");
    assert_memory_equal(&w->m[1000], "\x00\x17", 2);
    ext_expect_exception(w, S, "16 10 05 00 00 FF FF", 2, MODCP_EV_AREA_READONLY);
    ext_expect_exception(w, S, "16 10 03 00 00 FF FF", 2, MODCP_EV_NO_WINDOW);
    /* FC23: write QW256 and DB801.DBW20, then read MW1000..DB801.DBW20 */
    ext_expect(w, S, "17 10 00 00 03 10 01 00 02 04 A1 A2 B1 B2",
               "17 06 00 17 A1 A2 B1 B2");
    /* scanner write range with a read-only entry: nothing written */
    ext_expect_exception(w, S, "17 10 00 00 01 10 02 00 03 06 01 01 02 02 03 03", 2,
                         MODCP_EV_AREA_READONLY);
    assert_memory_equal(world_db(w, 801) + 20, "\xB1\xB2", 2);
    world_free(w);
}

/* A CPU job timeout in the middle of a sequence ends it with exception 04. */
static void test_scanner_job_timeout(void **state)
{
    (void)state;
    modcp_params_t p;
    scan_params(&p);
    world_t *w = ext_started(&p);
    w->fb_paused = true;
    ext_expect_exception(w, S, "03 00 50 00 04", 4, MODCP_EV_XFER_TIMEOUT);
    w->fb_paused = false;
    world_run(w, 5000);
    put16(&w->m[100], 0x0A0B);
    ext_expect(w, S, "03 00 50 00 01", "03 02 0A 0B");
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_altivar_fc23_scanner_example),
        cmocka_unit_test(test_scanner_reads),
        cmocka_unit_test(test_scanner_read_errors),
        cmocka_unit_test(test_scanner_writes),
        cmocka_unit_test(test_scanner_fc22_fc23),
        cmocka_unit_test(test_scanner_job_timeout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
