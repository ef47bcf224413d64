/* SPDX-License-Identifier: Apache-2.0 */
/* Mapping engine: every worked example of [RTU-2003] §3.1, §3.3, §3.4, §6 and of [ASCII-32] §4,
 * the 4.6.4 write limits, every event of map.h, and the event -> exception table. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/events.h"
#include "modcp/map.h"
#include "modcp/params.h"
#include "world.h"
#include "events_internal.h"
#include "map_internal.h"
#include "pdu_internal.h"
#include "params_internal.h"

/* ---- fixtures ------------------------------------------------------------------ */

static void set_win(modcp_bitwin_t *w, uint8_t area, uint16_t from, uint16_t to, uint16_t start,
                    uint16_t db)
{
    w->area = area;
    w->from = from;
    w->to = to;
    w->start = start;
    w->db = db;
}

/* [RTU-2003] §9: the parameter set that reproduces all the §6 examples. Limits admit the
 * examples (QB 257, MB 1144-1145, DB 800). */
static void params_004_9(modcp_params_t *p)
{
    world_example_params(p);
}

/* A controller big enough for every example; work DB 80 as the manual's OB1 call. */
static const modcp_areas_t big_cpu = {
    .i_bytes = 1024, .q_bytes = 1024, .m_bytes = 8192, .timers = 512, .counters = 512,
    .work_db = 80};

static void expect_bits(const modcp_params_t *p, uint8_t fc, uint16_t addr, uint16_t qty,
                        uint8_t area, uint16_t offset, uint8_t bit, uint16_t count)
{
    modcp_operand_t op;
    memset(&op, 0xAA, sizeof op);
    assert_int_equal(modcp_map_bits(p, &big_cpu, fc, addr, qty, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, area);
    assert_int_equal(op.offset, offset);
    assert_int_equal(op.bit, bit);
    assert_int_equal(op.count, count);
    assert_int_equal(op.db, 0);
}

static void expect_regs(const modcp_params_t *p, uint8_t fc, uint16_t reg, uint16_t qty,
                        uint16_t db, uint16_t dbw, uint16_t bytes)
{
    modcp_operand_t op;
    memset(&op, 0xAA, sizeof op);
    assert_int_equal(modcp_map_regs(p, &big_cpu, fc, reg, qty, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, MODCP_AREA_DB);
    assert_int_equal(op.db, db);
    assert_int_equal(op.offset, dbw);
    assert_int_equal(op.count, bytes);
    assert_int_equal(op.bit, 0);
}

static modcp_event_t bits_ev(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t addr, uint16_t qty)
{
    modcp_operand_t op;
    return modcp_map_bits(p, a, fc, addr, qty, &op);
}

static modcp_event_t regs_ev(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t reg, uint16_t qty)
{
    modcp_operand_t op;
    return modcp_map_regs(p, a, fc, reg, qty, &op);
}

/* ---- [RTU-2003] §3.1 (4.6.2) -------------------------------------------------------- */

static void test_4_6_2_coil_windows(void **state)
{
    (void)state;
    /* [RTU-2003] §3.1 worked example 4.6.2 */
    modcp_params_t p;
    modcp_params_defaults(&p);
    set_win(&p.coils[0], MODCP_AREA_M, 0, 2047, 1000, 0);
    set_win(&p.coils[1], MODCP_AREA_Q, 2048, 2559, 256, 0);
    set_win(&p.coils[2], MODCP_AREA_T, 4096, 4255, 100, 0);
    set_win(&p.coils[3], MODCP_AREA_C, 4256, 4415, 120, 0);
    p.cpu_model = MODCP_CPU_CP441; /* whole T window = 10 words in one request */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);

    expect_bits(&p, 1, 0, 1, MODCP_AREA_M, 1000, 0, 1);      /* first flag M 1000.0 */
    expect_bits(&p, 1, 2047, 1, MODCP_AREA_M, 1255, 7, 1);   /* last flag M 1255.7 */
    expect_bits(&p, 1, 0, 2040, MODCP_AREA_M, 1000, 0, 2040); /* 255 bytes of 256 */
    expect_bits(&p, 1, 2048, 1, MODCP_AREA_Q, 256, 0, 1);
    expect_bits(&p, 1, 2559, 1, MODCP_AREA_Q, 319, 7, 1);    /* last output Q 319.7 */
    expect_bits(&p, 1, 2048, 512, MODCP_AREA_Q, 256, 0, 512); /* 64 bytes */
    expect_bits(&p, 1, 4096, 160, MODCP_AREA_T, 100, 0, 10); /* 10 words T 100..109 */
    expect_bits(&p, 1, 4240, 16, MODCP_AREA_T, 109, 0, 1);   /* last timer T 109 */
    expect_bits(&p, 1, 4256, 160, MODCP_AREA_C, 120, 0, 10);
    expect_bits(&p, 1, 4400, 16, MODCP_AREA_C, 129, 0, 1);   /* last counter C 129 */
    /* 2560..4095 is a (legal) gap */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 2560, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4095, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4416, 16), MODCP_EV_NO_WINDOW);
}

static void test_4_6_2_input_windows(void **state)
{
    (void)state;
    /* [RTU-2003] §3.2 example 4.6.2: M 0-4095 @ M 0.0 (last M 511.7), I 4096-5119 @ I 128.0
     * (last I 255.7) */
    modcp_params_t p;
    modcp_params_defaults(&p);
    set_win(&p.inputs[0], MODCP_AREA_M, 0, 4095, 0, 0);
    set_win(&p.inputs[1], MODCP_AREA_I, 4096, 5119, 128, 0);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    expect_bits(&p, 2, 4095, 1, MODCP_AREA_M, 511, 7, 1);
    expect_bits(&p, 2, 5119, 1, MODCP_AREA_I, 255, 7, 1);
    expect_bits(&p, 2, 4096, 1024, MODCP_AREA_I, 128, 0, 1024);
    /* FC02 windows are independent of FC01: no coil windows configured */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 0, 1), MODCP_EV_NO_WINDOW);
}

/* ---- [RTU-2003] §3.3 tables 8.1 / 8.2 ----------------------------------------------- */

static void test_8_1_fc01_table(void **state)
{
    (void)state;
    /* [RTU-2003] §3.3 FC 01 worked table (8.1), every row */
    modcp_params_t p;
    params_004_9(&p);
    expect_bits(&p, 1, 0x0000, 1, MODCP_AREA_M, 1000, 0, 1);
    expect_bits(&p, 1, 0x0021, 1, MODCP_AREA_M, 1004, 1, 1);
    expect_bits(&p, 1, 0x0400, 1, MODCP_AREA_M, 1128, 0, 1);
    expect_bits(&p, 1, 0x0606, 1, MODCP_AREA_M, 1192, 6, 1);
    expect_bits(&p, 1, 0x0840, 1, MODCP_AREA_Q, 264, 0, 1);
    expect_bits(&p, 1, 0x09E4, 1, MODCP_AREA_Q, 316, 4, 1);
    expect_bits(&p, 1, 0x1010, 16, MODCP_AREA_T, 101, 0, 1);
    expect_bits(&p, 1, 0x10C0, 16, MODCP_AREA_T, 112, 0, 1);
    expect_bits(&p, 1, 0x1200, 16, MODCP_AREA_C, 200, 0, 1);
    expect_bits(&p, 1, 0x13E0, 16, MODCP_AREA_C, 230, 0, 1);
}

static void test_8_2_fc02_table(void **state)
{
    (void)state;
    /* [RTU-2003] §3.3 FC 02 worked table (8.2), every row */
    modcp_params_t p;
    params_004_9(&p);
    expect_bits(&p, 2, 0x0000, 1, MODCP_AREA_M, 2000, 0, 1);
    expect_bits(&p, 2, 0x0071, 1, MODCP_AREA_M, 2014, 1, 1);
    expect_bits(&p, 2, 0x0800, 1, MODCP_AREA_M, 2256, 0, 1);
    expect_bits(&p, 2, 0x0D05, 1, MODCP_AREA_M, 2416, 5, 1);
    expect_bits(&p, 2, 0x1000, 1, MODCP_AREA_I, 128, 0, 1);
    expect_bits(&p, 2, 0x10A4, 1, MODCP_AREA_I, 148, 4, 1);
}

/* ---- [RTU-2003] §3.4 tables 8.3 / 8.4 / 8.6 ------------------------------------------ */

static void test_8_3_fc03_table(void **state)
{
    (void)state;
    /* [RTU-2003] §3.4 FC 03/06/16 worked table (8.3), base DB 800, every row */
    modcp_params_t p;
    params_004_9(&p);
    expect_regs(&p, 3, 0x0000, 1, 800, 0, 2);
    expect_regs(&p, 3, 0x01F4, 1, 800, 1000, 2);
    expect_regs(&p, 3, 0x0200, 1, 801, 0, 2);
    expect_regs(&p, 3, 0x02FF, 1, 801, 510, 2);
    expect_regs(&p, 3, 0x0300, 1, 801, 512, 2);
    expect_regs(&p, 3, 0x03FF, 1, 801, 1022, 2);
    expect_regs(&p, 3, 0x0400, 1, 802, 0, 2);
    /* [RTU-2003] §3.4 4.6.3: from register 512 on -> DB 801 */
    expect_regs(&p, 3, 511, 1, 800, 1022, 2);
    expect_regs(&p, 3, 512, 1, 801, 0, 2);
}

static void test_8_4_fc04_table(void **state)
{
    (void)state;
    /* [RTU-2003] §3.4 FC 04 worked table (8.4), base DB 900, every row */
    modcp_params_t p;
    params_004_9(&p);
    expect_regs(&p, 4, 0x0000, 1, 900, 0, 2);
    expect_regs(&p, 4, 0x0064, 1, 900, 200, 2);
    expect_regs(&p, 4, 0x00C8, 1, 900, 400, 2);
    expect_regs(&p, 4, 0x0190, 1, 900, 800, 2);
    expect_regs(&p, 4, 0x1400, 1, 910, 0, 2);
    expect_regs(&p, 4, 0x1464, 1, 910, 200, 2);
    expect_regs(&p, 4, 0x14C8, 1, 910, 400, 2);
    /* [RTU-2003] §3.4 other example: FC 04 base 1200, registers 0 / 512 / 1024 */
    p.ir_base_db = 1200;
    expect_regs(&p, 4, 0, 1, 1200, 0, 2);
    expect_regs(&p, 4, 512, 1, 1201, 0, 2);
    expect_regs(&p, 4, 1024, 1, 1202, 0, 2);
}

static void test_8_6_inverse(void **state)
{
    (void)state;
    /* [RTU-2003] §3.4 inverse (8.6): start_register = (DB - base) * 512 + DBW / 2 */
    uint16_t reg = 0;
    assert_true(modcp_map_reg_of(800, 800, 768, &reg)); /* FC06 example: DB 800 DBW 768 */
    assert_int_equal(reg, 0x0180);
    /* every row of 8.3 backwards */
    static const uint16_t t83[][3] = {{0x0000, 800, 0},   {0x01F4, 800, 1000}, {0x0200, 801, 0},
                                      {0x02FF, 801, 510}, {0x0300, 801, 512},  {0x03FF, 801, 1022},
                                      {0x0400, 802, 0}};
    for (size_t i = 0; i < sizeof t83 / sizeof t83[0]; i++) {
        assert_true(modcp_map_reg_of(800, t83[i][1], t83[i][2], &reg));
        assert_int_equal(reg, t83[i][0]);
    }
    /* every row of 8.4 backwards */
    static const uint16_t t84[][3] = {{0x0000, 900, 0},   {0x0064, 900, 200}, {0x00C8, 900, 400},
                                      {0x0190, 900, 800}, {0x1400, 910, 0},   {0x1464, 910, 200},
                                      {0x14C8, 910, 400}};
    for (size_t i = 0; i < sizeof t84 / sizeof t84[0]; i++) {
        assert_true(modcp_map_reg_of(900, t84[i][1], t84[i][2], &reg));
        assert_int_equal(reg, t84[i][0]);
    }
    assert_true(modcp_map_reg_of(900, 901, 384, &reg)); /* FC04 example 02C0H */
    assert_int_equal(reg, 0x02C0);
    assert_true(modcp_map_reg_of(1, 128, 1022, &reg)); /* last register 0xFFFF */
    assert_int_equal(reg, 0xFFFF);
    /* not addressable */
    reg = 0x1234;
    assert_false(modcp_map_reg_of(0, 1, 0, &reg));      /* base not configured */
    assert_false(modcp_map_reg_of(800, 799, 0, &reg));  /* below the base */
    assert_false(modcp_map_reg_of(800, 928, 0, &reg));  /* offset 128 */
    assert_false(modcp_map_reg_of(800, 800, 1024, &reg)); /* beyond DBW 1022 */
    assert_false(modcp_map_reg_of(800, 800, 101, &reg)); /* odd byte offset */
    assert_int_equal(reg, 0x1234);
}

/* ---- [RTU-2003] §6 examples ----------------------------------------------------------- */

static void test_section6_operands(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    /* [RTU-2003] §6.1 FC01 example: 05 01 00 40 00 20 -> M 1008.0 .. M 1011.7, 32 bits */
    expect_bits(&p, 1, 0x0040, 0x0020, MODCP_AREA_M, 1008, 0, 32);
    /* [RTU-2003] §6.2 FC02 example: 05 02 10 30 00 18 -> I 134.0 .. I 136.7, 24 bits */
    expect_bits(&p, 2, 0x1030, 0x0018, MODCP_AREA_I, 134, 0, 24);
    /* [RTU-2003] §6.3 FC03 example: 05 03 00 50 00 02 -> DB 800 DBW 160, 2 registers */
    expect_regs(&p, 3, 0x0050, 2, 800, 160, 4);
    /* [RTU-2003] §6.4 FC04 example: 05 04 02 C0 00 03 -> DB 901 DBW 384, 3 registers */
    expect_regs(&p, 4, 0x02C0, 3, 901, 384, 6);
    /* [RTU-2003] §6.5 FC05 example: 05 05 08 09 FF 00 -> Q 257.1 */
    expect_bits(&p, 5, 0x0809, 1, MODCP_AREA_Q, 257, 1, 1);
    /* [RTU-2003] §6.6 FC06 example: 05 06 01 80 2B 1A -> DB 800 DBW 768 */
    expect_regs(&p, 6, 0x0180, 1, 800, 768, 2);
    /* [RTU-2003] §6.8 FC15 example: 05 0F 04 80 00 0C 02 CD 09 -> M 1144.0, 12 bits */
    expect_bits(&p, 15, 0x0480, 0x000C, MODCP_AREA_M, 1144, 0, 12);
    /* [RTU-2003] §6.9 FC16 example: 05 10 00 32 00 03 ... -> DB 800 DBW 100, 3 registers */
    expect_regs(&p, 16, 0x0032, 3, 800, 100, 6);
}

static void test_4_6_4_limits_reject_examples(void **state)
{
    (void)state;
    /* [RTU-2003] §3.5 example 4.6.4 limits: DB 600-699, MB 1000-1127, QB 256-319; [RTU-2003] §9 says
     * they reject the FC15 example at MB 1144 and the FC06/16 examples in DB 800 */
    modcp_params_t p;
    params_004_9(&p);
    p.lim_db = (modcp_limit_t){600, 699};
    p.lim_m = (modcp_limit_t){1000, 1127};
    p.lim_q = (modcp_limit_t){256, 319};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 0x0480, 12), MODCP_EV_WRITE_DENIED); /* §6.8 */
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0x0180, 1), MODCP_EV_WRITE_DENIED);   /* §6.6 */
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 0x0032, 3), MODCP_EV_WRITE_DENIED);  /* §6.9 */
    assert_int_equal(modcp_event_exception(MODCP_EV_WRITE_DENIED), 2);
    /* the FC05 example Q 257.1 lies inside QB 256-319 and passes */
    expect_bits(&p, 5, 0x0809, 1, MODCP_AREA_Q, 257, 1, 1);
    /* reads are not limited */
    expect_regs(&p, 3, 0x0050, 2, 800, 160, 4);
    expect_bits(&p, 1, 0x0480, 12, MODCP_AREA_M, 1144, 0, 12);
    /* every touched byte counts: M 1127.4 .. 1128.3 touches MB 1128 */
    assert_int_equal(bits_ev(&p, &big_cpu, 15, (1127 - 1000) * 8 + 4, 8), MODCP_EV_WRITE_DENIED);
    expect_bits(&p, 15, (1127 - 1000) * 8 + 4, 4, MODCP_AREA_M, 1127, 4, 4);
    /* below MIN */
    p.lim_m = (modcp_limit_t){1001, 1127};
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 7, 1), MODCP_EV_WRITE_DENIED); /* M 1000.7 */
    expect_bits(&p, 5, 8, 1, MODCP_AREA_M, 1001, 0, 1);
    /* DB limits are resulting DB numbers: 600..699 with base 800 never reachable, base
     * 600 makes register 0x0180 (DB 600) writable and 0xC800 (DB 700) not */
    p.hr_base_db = 600;
    expect_regs(&p, 6, 0x0180, 1, 600, 768, 2);
    expect_regs(&p, 16, (99u << 9) | 0x32u, 3, 699, 100, 6);
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 100u << 9, 1), MODCP_EV_WRITE_DENIED);
}

static void test_limits_admitting_examples(void **state)
{
    (void)state;
    /* [RTU-2003] §9: limits that include QB 257, MB 1144-1145 and DB 800 accept §6.5/6/8/9 */
    modcp_params_t p;
    params_004_9(&p);
    p.lim_db = (modcp_limit_t){800, 800};
    p.lim_m = (modcp_limit_t){1144, 1145};
    p.lim_q = (modcp_limit_t){257, 257};
    expect_bits(&p, 5, 0x0809, 1, MODCP_AREA_Q, 257, 1, 1);
    expect_bits(&p, 15, 0x0480, 12, MODCP_AREA_M, 1144, 0, 12);
    expect_regs(&p, 6, 0x0180, 1, 800, 768, 2);
    expect_regs(&p, 16, 0x0032, 3, 800, 100, 6);
    expect_regs(&p, 22, 0x0032, 1, 800, 100, 2);
    expect_regs(&p, 23, 0x0032, 3, 800, 100, 6);
    /* one bit more reaches MB 1146 / QB 258 / DB 801 */
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 0x0480, 17), MODCP_EV_WRITE_DENIED);
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 2048 + 16, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0x0200, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 22, 0x0200, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 23, 0x0200, 1), MODCP_EV_WRITE_DENIED);
    /* MAX = 0 disables the whole area ([RTU-2003] §3.5) */
    p.lim_q = (modcp_limit_t){0, 0};
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 0x0809, 1), MODCP_EV_WRITE_DENIED);
    p.lim_db = (modcp_limit_t){0, 0};
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0x0180, 1), MODCP_EV_WRITE_DENIED);
    /* defaults: everything write-protected */
    modcp_params_t d;
    modcp_params_defaults(&d);
    d.coils[0] = p.coils[0];
    d.hr_base_db = 800;
    assert_int_equal(bits_ev(&d, &big_cpu, 5, 0, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&d, &big_cpu, 6, 0, 1), MODCP_EV_WRITE_DENIED);
}

static void test_work_db_never_writable(void **state)
{
    (void)state;
    /* [RTU-2003] §3.5: writing into the FB's instance DB is always refused with (0E)52H */
    modcp_params_t p;
    params_004_9(&p);
    p.hr_base_db = 80;
    p.lim_db = (modcp_limit_t){1, 65535};
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0, 1), MODCP_EV_WRITE_DENIED);  /* DB 80 */
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 0, 2), MODCP_EV_WRITE_DENIED);
    expect_regs(&p, 3, 0, 2, 80, 0, 4);        /* reading it is allowed */
    expect_regs(&p, 6, 0x0200, 1, 81, 0, 2);   /* DB 81 is not the work area */
    /* a DB-bit coil window on the work DB */
    set_win(&p.coils[4], MODCP_AREA_DB, 8192, 8255, 0, 80);
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 8192, 1), MODCP_EV_WRITE_DENIED);
    modcp_operand_t op;
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 1, 8192, 8, &op), MODCP_EV_NONE);
    assert_int_equal(op.db, 80);
}

/* ---- every event of map.h ------------------------------------------------------ */

static void test_bit_events(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.lim_m = (modcp_limit_t){0, 65535};
    p.lim_q = (modcp_limit_t){0, 65535};

    /* (0E)51H: outside every window (gap 2560..4095 and beyond C) */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 2560, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 5120, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(bits_ev(&p, &big_cpu, 2, 5120, 1), MODCP_EV_NO_WINDOW);
    /* (0E)55H: FC05 / FC15 on T or C ([RTU-2003] §6.5, §6.8), before alignment checks */
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 4096, 1), MODCP_EV_AREA_READONLY);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 4608, 16), MODCP_EV_AREA_READONLY);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 4609, 3), MODCP_EV_AREA_READONLY);
    /* (0E)50H: T/C start not on a 16-bit boundary ([RTU-2003] §3.3) */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4104, 16), MODCP_EV_TC_ALIGN);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4609, 16), MODCP_EV_TC_ALIGN);
    /* (08)32H: T/C bit count not a multiple of 16 */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4096, 8), MODCP_EV_QUANTITY);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4608, 17), MODCP_EV_QUANTITY);
    /* (08)32H: CP 341 reads at most 16 T/C per request */
    expect_bits(&p, 1, 4096, 256, MODCP_AREA_T, 100, 0, 16);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4096, 272), MODCP_EV_QUANTITY);
    p.cpu_model = MODCP_CPU_CP441;
    expect_bits(&p, 1, 4096, 272, MODCP_AREA_T, 100, 0, 17);
    p.cpu_model = MODCP_CPU_CP341;
    /* (0E)54H: past the window end */
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 2040, 9), MODCP_EV_PAST_END);
    expect_bits(&p, 1, 2040, 8, MODCP_AREA_M, 1255, 0, 8);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 2047, 2), MODCP_EV_PAST_END);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4592, 32), MODCP_EV_PAST_END);  /* T 131/132 */
    assert_int_equal(bits_ev(&p, &big_cpu, 2, 5112, 16), MODCP_EV_PAST_END);
    /* (0E)54H: past the controller's real area ([RTU-2003] §3.3, sizes from the CPU side) */
    modcp_areas_t small = big_cpu;
    small.m_bytes = 1100; /* MB 0..1099 */
    assert_int_equal(bits_ev(&p, &small, 1, 99 * 8, 8), MODCP_EV_NONE); /* MB 1099 */
    assert_int_equal(bits_ev(&p, &small, 1, 99 * 8, 9), MODCP_EV_PAST_END);
    assert_int_equal(bits_ev(&p, &small, 1, 100 * 8, 1), MODCP_EV_PAST_END);
    assert_int_equal(bits_ev(&p, &small, 15, 100 * 8, 1), MODCP_EV_PAST_END);
    small = big_cpu;
    small.timers = 101; /* T 0..100 */
    assert_int_equal(bits_ev(&p, &small, 1, 4096, 16), MODCP_EV_NONE);
    assert_int_equal(bits_ev(&p, &small, 1, 4096, 32), MODCP_EV_PAST_END);
    small = big_cpu;
    small.counters = 0;
    assert_int_equal(bits_ev(&p, &small, 1, 4608, 16), MODCP_EV_PAST_END);
    small = big_cpu;
    small.q_bytes = 256; /* no Q 256 */
    assert_int_equal(bits_ev(&p, &small, 5, 0x0809, 1), MODCP_EV_PAST_END);
    small = big_cpu;
    small.i_bytes = 136; /* I 0..135: FC02 example reaches I 136 */
    assert_int_equal(bits_ev(&p, &small, 2, 0x1030, 24), MODCP_EV_PAST_END);
    assert_int_equal(bits_ev(&p, &small, 2, 0x1030, 16), MODCP_EV_NONE);
    /* (0E)54H is checked before the write limits; (0E)52H after it */
    p.lim_m = (modcp_limit_t){0, 0};
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 2047, 2), MODCP_EV_PAST_END);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 2047, 1), MODCP_EV_WRITE_DENIED);
    /* (08)31H: not a bit function; qty 0 */
    assert_int_equal(bits_ev(&p, &big_cpu, 3, 0, 1), MODCP_EV_ILLEGAL_FC);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 0, 0), MODCP_EV_QUANTITY);
    /* map.h: a == NULL skips the controller checks */
    modcp_operand_t op;
    assert_int_equal(modcp_map_bits(&p, NULL, 1, 0x0040, 32, &op), MODCP_EV_NONE);
    assert_int_equal(op.offset, 1008);
}

static void test_register_events(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.lim_db = (modcp_limit_t){1, 65535};

    /* (0E)51H: register functions not configured (base 0) */
    modcp_params_t d;
    modcp_params_defaults(&d);
    assert_int_equal(regs_ev(&d, &big_cpu, 3, 0, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&d, &big_cpu, 4, 0, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&d, &big_cpu, 16, 0, 1), MODCP_EV_NO_WINDOW);
    /* (0E)39H: no crossing of a DB boundary ([RTU-2003] §3.4; [ASCII-32] §4.3 example base DB 1,
     * start 510: lengths 1 and 2 accepted, 3 rejected) */
    p.hr_base_db = 1;
    expect_regs(&p, 3, 510, 1, 1, 1020, 2);
    expect_regs(&p, 3, 510, 2, 1, 1020, 4);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 510, 3), MODCP_EV_DB_ACCESS);
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 510, 3), MODCP_EV_DB_ACCESS);
    assert_int_equal(regs_ev(&p, &big_cpu, 4, 0x03FF, 2), MODCP_EV_DB_ACCESS);
    expect_regs(&p, 3, 0x0200, 127, 2, 0, 254); /* 127 words from word 0 */
    assert_int_equal(modcp_event_exception(MODCP_EV_DB_ACCESS), 2);
    /* (0E)53H: resulting DB > 65535 */
    p.hr_base_db = 65500;
    expect_regs(&p, 3, 35u << 9, 1, 65535, 0, 2);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 36u << 9, 1), MODCP_EV_DB_OVERFLOW);
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0xFFFF, 1), MODCP_EV_DB_OVERFLOW);
    p.ir_base_db = 65535;
    expect_regs(&p, 4, 0x01FF, 1, 65535, 1022, 2);
    assert_int_equal(regs_ev(&p, &big_cpu, 4, 0x0200, 1), MODCP_EV_DB_OVERFLOW);
    /* (0E)52H: write outside the DB limits (FC 06, 16, 22, 23; not 03 / 04) */
    p.hr_base_db = 800;
    p.lim_db = (modcp_limit_t){801, 900};
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 0, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 0, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 22, 0, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 23, 0, 1), MODCP_EV_WRITE_DENIED);
    expect_regs(&p, 3, 0, 1, 800, 0, 2);
    expect_regs(&p, 6, 0x0200, 1, 801, 0, 2);
    /* (08)31H: not a register function; qty 0 */
    assert_int_equal(regs_ev(&p, &big_cpu, 1, 0, 1), MODCP_EV_ILLEGAL_FC);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 0, 0), MODCP_EV_QUANTITY);
}

/* ---- [ASCII-32] §4: DB-bit windows, examples of the ASCII manual ---------------------- */

static void test_db_bit_windows_map_bits_of_a_db(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    /* [ASCII-32] §5 FC01 examples table: 4096-4607 -> DB111 (replaces T/C) */
    memset(&p.coils[2], 0, sizeof p.coils[2] * 2);
    set_win(&p.coils[4], MODCP_AREA_DB, 4096, 4607, 0, 111);
    /* [ASCII-32] §4.2 example: 8192-8512 -> DB112 (the §5 FC02 table header prints 8192-8351,
     * which would not hold its own row 20C2H = 8386) */
    set_win(&p.inputs[2], MODCP_AREA_DB, 8192, 8512, 0, 112);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);

    modcp_operand_t op;
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 1, 0x1010, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, MODCP_AREA_DB); /* DB111.DBX2.0 */
    assert_int_equal(op.db, 111);
    assert_int_equal(op.offset, 2);
    assert_int_equal(op.bit, 0);
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 1, 0x10C2, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.db, 111); /* DB111.DBX24.2 */
    assert_int_equal(op.offset, 24);
    assert_int_equal(op.bit, 2);
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 2, 0x2000, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.db, 112); /* DB112.DBX0.0 */
    assert_int_equal(op.offset, 0);
    assert_int_equal(op.bit, 0);
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 2, 8386, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.db, 112); /* "2011" = 20C2H -> DB112.DBX24.2 */
    assert_int_equal(op.offset, 24);
    assert_int_equal(op.bit, 2);
    /* [ASCII-32] §4.1: 4096-4415 -> DB111, 320 bits = 40 bytes, last DBX39.7 */
    set_win(&p.coils[4], MODCP_AREA_DB, 4096, 4415, 0, 111);
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 1, 4415, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.offset, 39);
    assert_int_equal(op.bit, 7);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 4415, 2), MODCP_EV_PAST_END);
    /* DB-bit writes: the DB must lie inside lim_db (docs/mapping.md) */
    p.lim_db = (modcp_limit_t){800, 899};
    assert_int_equal(bits_ev(&p, &big_cpu, 5, 4096, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(bits_ev(&p, &big_cpu, 15, 4096, 16), MODCP_EV_WRITE_DENIED);
    p.lim_db = (modcp_limit_t){111, 111};
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 15, 4097, 12, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, MODCP_AREA_DB);
    assert_int_equal(op.db, 111);
    assert_int_equal(op.offset, 0);
    assert_int_equal(op.bit, 1);
    assert_int_equal(op.count, 12);
    /* a DB-bit window reaching beyond DB byte 65535 -> (0E)54H */
    set_win(&p.coils[5], MODCP_AREA_DB, 10000, 10015, 65535, 111);
    assert_int_equal(modcp_map_bits(&p, &big_cpu, 1, 10000, 8, &op), MODCP_EV_NONE);
    assert_int_equal(op.offset, 65535);
    assert_int_equal(bits_ev(&p, &big_cpu, 1, 10000, 9), MODCP_EV_PAST_END);
}

static void test_ascii_manual_examples_16bit(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    /* [ASCII-32] §5 FC15 example: 05 0F 04 81 00 0C -> M1144.1 .. M1145.4 (12 bits) */
    expect_bits(&p, 15, 0x0481, 12, MODCP_AREA_M, 1144, 1, 12);
    /* [ASCII-32] §5 FC16 example: 05 10 0A 32 00 03 -> offset 5, word 50 -> DB805.DBW100 */
    expect_regs(&p, 16, 0x0A32, 3, 805, 100, 6);
    /* [ASCII-32] §4.4: FC04 stays on its own base in every mode */
    p.regs32 = 1;
    expect_regs(&p, 4, 0x02C0, 3, 901, 384, 6);
}

/* ---- [ASCII-32] §4.5: 32-bit registers ---------------------------------------------- */

static void params_003_32(modcp_params_t *p)
{
    params_004_9(p);
    p->regs32 = 1;
    p->r32[MODCP_R32_INT16] = (modcp_r32range_t){3000, 4999, 2};
    p->r32[MODCP_R32_INT32] = (modcp_r32range_t){5000, 5099, 3};
    p->r32[MODCP_R32_FLOAT] = (modcp_r32range_t){7000, 9999, 4};
    p->lim_db = (modcp_limit_t){2, 4};
}

static void expect_r32(const modcp_params_t *p, uint8_t fc, uint16_t reg, uint16_t qty,
                       uint8_t kind, uint16_t db, uint16_t off, uint16_t bytes)
{
    modcp_operand_t op;
    memset(&op, 0xAA, sizeof op);
    assert_int_equal(modcp_map_regs(p, &big_cpu, fc, reg, qty, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, MODCP_AREA_DB);
    assert_int_equal(op.bit, kind + 1);
    assert_int_equal(op.db, db);
    assert_int_equal(op.offset, off);
    assert_int_equal(op.count, bytes);
}

static void test_regs32_manual_examples(void **state)
{
    (void)state;
    modcp_params_t p;
    params_003_32(&p);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* [ASCII-32] §4.5 FC03 16-bit: 05 03 0B EA 00 02 -> 3050 -> DB2.DBW100, byte_count 04 */
    expect_r32(&p, 3, 0x0BEA, 2, MODCP_R32_INT16, 2, 100, 4);
    /* [ASCII-32] §4.5 FC03 32-bit: 05 03 1B 59 00 02 -> 7001 -> DB4.DBD4 and DBD8, byte_count 08 */
    expect_r32(&p, 3, 0x1B59, 2, MODCP_R32_FLOAT, 4, 4, 8);
    /* [ASCII-32] §4.5 FC06 16-bit: 05 06 0D 37 2B 1A -> 3383 -> DB2.DBW766 */
    expect_r32(&p, 6, 0x0D37, 1, MODCP_R32_INT16, 2, 766, 2);
    /* [ASCII-32] §4.5 FC06 32-bit: 05 06 1B 5A 12 23 34 45 -> 7002 -> DB4.DBD8, 4 data bytes */
    expect_r32(&p, 6, 0x1B5A, 1, MODCP_R32_FLOAT, 4, 8, 4);
    /* [ASCII-32] §4.5 FC16 16-bit: 05 10 0C 1C 00 03 06 ... -> 3100 -> DB2.DBW200/202/204 */
    expect_r32(&p, 16, 0x0C1C, 3, MODCP_R32_INT16, 2, 200, 6);
    /* [ASCII-32] §4.5 FC16 32-bit: 05 10 13 8B 00 02 08 ... -> 5003 -> DB3.DBD12 and DBD16 */
    expect_r32(&p, 16, 0x138B, 2, MODCP_R32_INT32, 3, 12, 8);
    /* [ASCII-32] §4.5 further examples (§9.4) */
    expect_r32(&p, 3, 0x0C37, 1, MODCP_R32_INT16, 2, 254, 2);
    expect_r32(&p, 3, 0x1324, 1, MODCP_R32_INT16, 2, 3800, 2);
    expect_r32(&p, 3, 0x1388, 1, MODCP_R32_INT32, 3, 0, 4);
    expect_r32(&p, 3, 0x13E2, 1, MODCP_R32_INT32, 3, 360, 4);
    expect_r32(&p, 3, 0x1BBC, 1, MODCP_R32_FLOAT, 4, 400, 4);
    expect_r32(&p, 3, 0x26AC, 1, MODCP_R32_FLOAT, 4, 11600, 4); /* printed DBD7600: doc error */
    /* [ASCII-32] §4.5 area sizes: last DB2.DBW3998, DB3.DBD396, DB4.DBD11996 */
    expect_r32(&p, 3, 4999, 1, MODCP_R32_INT16, 2, 3998, 2);
    expect_r32(&p, 3, 5099, 1, MODCP_R32_INT32, 3, 396, 4);
    expect_r32(&p, 3, 9999, 1, MODCP_R32_FLOAT, 4, 11996, 4);
    /* FC23 uses the ranges too */
    expect_r32(&p, 23, 7000, 2, MODCP_R32_FLOAT, 4, 0, 8);
}

static void test_regs32_range_errors_events(void **state)
{
    (void)state;
    modcp_params_t p;
    params_003_32(&p);
    /* a request straddling a range end -> (0E)54H ([ASCII-32] §4.5 "access in excess of the
     * parameterised range end") */
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 4999, 2), MODCP_EV_PAST_END);
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 5098, 3), MODCP_EV_PAST_END);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 9990, 11), MODCP_EV_PAST_END);
    /* outside the three ranges -> (0E)51H; the DB offset scheme is replaced */
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 0, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 6000, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 10000, 1), MODCP_EV_NO_WINDOW);
    /* the DB write limits: not in 32-bit mode ([ASCII-32] §3.7, §5.4) ... */
    p.lim_db = (modcp_limit_t){2, 3};
    expect_r32(&p, 6, 7002, 1, MODCP_R32_FLOAT, 4, 8, 4);
    expect_r32(&p, 16, 7000, 2, MODCP_R32_FLOAT, 4, 0, 8);
    /* ... unless db_in_32bit_mode asks for them (r32_lim_db) */
    p.r32_lim_db = 1;
    assert_int_equal(regs_ev(&p, &big_cpu, 6, 7002, 1), MODCP_EV_WRITE_DENIED);
    assert_int_equal(regs_ev(&p, &big_cpu, 16, 7000, 2), MODCP_EV_WRITE_DENIED);
    expect_r32(&p, 3, 7002, 1, MODCP_R32_FLOAT, 4, 8, 4);
    expect_r32(&p, 6, 5000, 1, MODCP_R32_INT32, 3, 0, 4);
    p.r32_lim_db = 0;
    /* and the work DB is never writable */
    modcp_areas_t a = big_cpu;
    a.work_db = 3;
    modcp_operand_t op;
    assert_int_equal(modcp_map_regs(&p, &a, 6, 5000, 1, &op), MODCP_EV_WRITE_DENIED);
    /* FC22 (16-bit mask write): int16 range only */
    expect_r32(&p, 22, 3000, 1, MODCP_R32_INT16, 2, 0, 2);
    assert_int_equal(regs_ev(&p, &big_cpu, 22, 5000, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&p, &big_cpu, 22, 7000, 1), MODCP_EV_NO_WINDOW);
    /* an all-zero range is unused: register 0 does not hit it */
    memset(&p.r32[MODCP_R32_INT32], 0, sizeof p.r32[0]);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 0, 1), MODCP_EV_NO_WINDOW);
    assert_int_equal(regs_ev(&p, &big_cpu, 3, 5000, 1), MODCP_EV_NO_WINDOW);
}

static void test_event_exception(void **state)
{
    (void)state;
    /* events.h / [RTU-2003] ch. 7 / docs/diagnostics.md */
    assert_int_equal(modcp_event_exception(MODCP_EV_ILLEGAL_FC), 1);
    assert_int_equal(modcp_event_exception(MODCP_EV_QUANTITY), 3);
    assert_int_equal(modcp_event_exception(MODCP_EV_BYTE_COUNT), 3);
    assert_int_equal(modcp_event_exception(MODCP_EV_COIL_VALUE), 3);
    assert_int_equal(modcp_event_exception(MODCP_EV_DIAG_SUBFC), 3);
    assert_int_equal(modcp_event_exception(MODCP_EV_DB_ACCESS), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_TC_ALIGN), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_NO_WINDOW), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_WRITE_DENIED), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_DB_OVERFLOW), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_PAST_END), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_AREA_READONLY), 2);
    assert_int_equal(modcp_event_exception(MODCP_EV_FB_NOT_RUNNING), 4);
    /* not request errors */
    assert_int_equal(modcp_event_exception(MODCP_EV_NONE), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_BCAST_FC), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_CRC), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_SEQUENCE), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_ZVZ), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_FMUL), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_PARAM_RECORD), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_AREA_ACCESS), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_WORK_DB), 0);
    assert_int_equal(modcp_event_exception(MODCP_EV_FB_ERROR), 0);
    assert_int_equal(modcp_event_exception(MODCP_EVENT(0x08, 0x32)), 3);
    assert_int_equal(modcp_event_exception(MODCP_EVENT(0x05, 0x32)), 0); /* class matters */
    assert_int_equal(modcp_event_exception(MODCP_EV_MEI_CODE), 3); /* devid.c names 03 too */
    /* every event the mapping and the scanner refuse with (modcp_pdu_map_err) has a code:
     * pdu.c answers it with modcp_event_exception(), never with exception 00 */
    static const modcp_event_t map_events[] = {
        MODCP_EV_QUANTITY, MODCP_EV_DB_ACCESS, MODCP_EV_TC_ALIGN, MODCP_EV_NO_WINDOW,
        MODCP_EV_WRITE_DENIED, MODCP_EV_DB_OVERFLOW, MODCP_EV_PAST_END, MODCP_EV_AREA_READONLY,
    };
    for (size_t i = 0; i < sizeof map_events / sizeof map_events[0]; i++) {
        modcp_pdu_t s;
        memset(&s, 0xA5, sizeof s); /* neither err nor x.exc holds the expected value */
        assert_int_equal(modcp_pdu_map_err(&s, map_events[i]), MODCP_PDU_FAIL);
        assert_int_equal(s.err, map_events[i]);
        assert_int_equal(s.x.exc, MODCP_EXC_OF_MAP);
        assert_in_range(modcp_event_exception(map_events[i]), 2, 3);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_4_6_2_coil_windows),
        cmocka_unit_test(test_4_6_2_input_windows),
        cmocka_unit_test(test_8_1_fc01_table),
        cmocka_unit_test(test_8_2_fc02_table),
        cmocka_unit_test(test_8_3_fc03_table),
        cmocka_unit_test(test_8_4_fc04_table),
        cmocka_unit_test(test_8_6_inverse),
        cmocka_unit_test(test_section6_operands),
        cmocka_unit_test(test_4_6_4_limits_reject_examples),
        cmocka_unit_test(test_limits_admitting_examples),
        cmocka_unit_test(test_work_db_never_writable),
        cmocka_unit_test(test_bit_events),
        cmocka_unit_test(test_register_events),
        cmocka_unit_test(test_db_bit_windows_map_bits_of_a_db),
        cmocka_unit_test(test_ascii_manual_examples_16bit),
        cmocka_unit_test(test_regs32_manual_examples),
        cmocka_unit_test(test_regs32_range_errors_events),
        cmocka_unit_test(test_event_exception),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
