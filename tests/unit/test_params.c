/* SPDX-License-Identifier: Apache-2.0 */
/* Parameter record: defaults (docs/parameters.md), validation events ([RTU-2003] §7.5 class 0EH, [ASCII-32] §8.6),
 * the effective copy, the binary record, the job limit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/crc.h"
#include "modcp/events.h"
#include "modcp/params.h"
#include "world.h"
#include "params_fields.h"
#include "params_internal.h"

#define RECORD_LEN 321u /* 8 header + 311 payload + 2 CRC */

static void set_win(modcp_bitwin_t *w, uint8_t area, uint16_t from, uint16_t to, uint16_t start,
                    uint16_t db)
{
    w->area = area;
    w->from = from;
    w->to = to;
    w->start = start;
    w->db = db;
}

/* [RTU-2003] §9 parameter set (slave 5, coils M/Q/T/C, inputs M/I, base DB 800 / 900) */
static void params_004_9(modcp_params_t *p)
{
    world_example_params(p);
    /* [RTU-2003] §3.5 example 4.6.4 limits */
    p->lim_db = (modcp_limit_t){600, 699};
    p->lim_m = (modcp_limit_t){1000, 1127};
    p->lim_q = (modcp_limit_t){256, 319};
}

/* Validates p and asserts exactly one issue with these contents. */
static void expect_one(const modcp_params_t *p, modcp_param_field_t field, uint8_t index,
                       modcp_event_t ev, bool fatal, uint32_t value)
{
    modcp_param_issue_t is[8];
    memset(is, 0xEE, sizeof is);
    size_t n = modcp_params_validate(p, is, 8);
    if (n != 1) {
        for (size_t i = 0; i < n && i < 8; i++) {
            print_message("issue %zu: field %u index %u event %04X value %u\n", i, is[i].field,
                          is[i].index, is[i].event, (unsigned)is[i].value);
        }
    }
    assert_int_equal(n, 1);
    assert_int_equal(is[0].field, field);
    assert_int_equal(is[0].index, index);
    assert_int_equal(is[0].event, ev);
    assert_int_equal(is[0].fatal, fatal);
    assert_int_equal(is[0].value, value);
    /* apply agrees */
    modcp_params_t eff;
    modcp_event_t warn = 0x1234;
    modcp_event_t fat = modcp_params_apply(p, &eff, &warn);
    assert_int_equal(fat, fatal ? ev : MODCP_EV_NONE);
    assert_int_equal(warn, fatal ? MODCP_EV_NONE : ev);
}

/* ---- defaults ---------------------------------------------------------------- */

static void test_defaults(void **state)
{
    (void)state;
    /* docs/parameters.md defaults */
    modcp_params_t p;
    memset(&p, 0x5A, sizeof p);
    modcp_params_defaults(&p);
    assert_int_equal(p.baud, 9600);
    assert_int_equal(p.data_bits, 8);
    assert_int_equal(p.parity, MODCP_PARITY_EVEN);
    assert_int_equal(p.stop_bits, 1);
    assert_int_equal(p.slave_addr, 222); /* [RTU-2003] §2.2 as printed */
    assert_int_equal(p.framing, MODCP_FRAMING_RTU);
    assert_int_equal(p.opmode, MODCP_OPMODE_NORMAL);
    assert_int_equal(p.f_mul, 1);
    assert_int_equal(p.eof_timing, MODCP_EOF_MANUAL);
    assert_int_equal(p.t15_check, 0);
    assert_int_equal(p.ascii_timeout_ms, 1000);
    assert_int_equal(p.iface, MODCP_IFACE_RS232);
    assert_int_equal(p.turnaround_ms, 0);
    assert_int_equal(p.rs232_auto, 0);
    assert_int_equal(p.rts_on_delay_ms, 10); /* VIPA CP 341 manual §1.6: 10 ms each */
    assert_int_equal(p.rts_off_delay_ms, 10);
    assert_int_equal(p.rx_preset, MODCP_RXP_DEFAULT); /* [RTU-2009] Table 5-8: by interface */
    assert_int_equal(p.commloss_auto, 0); /* latched, as the Altivar's SLF1 */
    for (size_t i = 0; i < MODCP_COIL_WINDOWS; i++) {
        assert_int_equal(p.coils[i].area, MODCP_AREA_NONE);
    }
    for (size_t i = 0; i < MODCP_INPUT_WINDOWS; i++) {
        assert_int_equal(p.inputs[i].area, MODCP_AREA_NONE);
    }
    assert_int_equal(p.hr_base_db, 0);
    assert_int_equal(p.ir_base_db, 0);
    assert_int_equal(p.regs32, 0);
    assert_int_equal(p.lim_db.max, 0);
    assert_int_equal(p.lim_m.max, 0);
    assert_int_equal(p.lim_q.max, 0);
    assert_int_equal(p.lim_db.min, 0);
    assert_int_equal(p.fset, MODCP_FSET_EXTENDED);
    assert_int_equal(p.rs485_sel, 0); /* [RTU-2009] Table 5-2: "Non" */
    assert_int_equal(p.qty_limits, MODCP_QLIMITS_MANUAL);
    assert_int_equal(p.cpu_model, MODCP_CPU_CP341);
    assert_int_equal(p.job_limit, 0);
    assert_int_equal(p.cpu_timeout_ms, 1000);
    assert_int_equal(p.start_time_ms, 5000);
    assert_int_equal(p.commloss_ms, 0);
    assert_int_equal(p.scan_count, 0);
    assert_string_equal(p.vendor, "modcp");
    assert_string_equal(p.product, "modcp-cp");
    assert_string_equal(p.revision, ""); /* FC17 / FC43: modcp's version (devid.c) */
    assert_string_equal(p.app_name, "");
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    modcp_params_t eff;
    modcp_event_t warn = 0x1234;
    assert_int_equal(modcp_params_apply(&p, &eff, &warn), MODCP_EV_NONE);
    assert_int_equal(warn, MODCP_EV_NONE);
    assert_int_equal(eff.slave_addr, 222);
}

/* The core walks a group's structs member by member as the record lays them out: one
 * after the other, 2 bytes wide except a 1-byte first member (in a 2-byte slot unless the
 * structs are packed, params_fields.h); the rows must list the members in that order. */
static void test_group_members_in_slot_order(void **state)
{
    (void)state;
#define SLOT_S(...)
#define SLOT_G(member, count, type, members, field) {0xFFu, (uint8_t)(members), sizeof(type)},
#define SLOT_M(type, member, width, count) {(uint8_t)offsetof(type, member), (uint8_t)(width), 0u},
    static const struct {
        uint8_t off;
        uint8_t width; /* a group's row: the number of members */
        uint8_t size;  /* a group's row: the size of one struct */
    } slots[] = {MODCP_PARAM_ROWS(SLOT_S, SLOT_G, SLOT_M)};
    size_t members = 0;
    size_t size = 0;
    size_t j = 0;
    size_t at = 0;
    for (size_t i = 0; i <= sizeof slots / sizeof slots[0]; i++) {
        if (i == sizeof slots / sizeof slots[0] || slots[i].off == 0xFFu) {
            assert_int_equal(j, members); /* the previous group's members all listed */
            assert_int_equal(at, size);   /* and nothing else in its struct */
            members = i < sizeof slots / sizeof slots[0] ? slots[i].width : 0u;
            size = i < sizeof slots / sizeof slots[0] ? slots[i].size : 0u;
            j = 0;
            at = 0;
            continue;
        }
        assert_int_equal(slots[i].off, at);
        assert_true(slots[i].width == 2u || (j == 0u && slots[i].width == 1u));
        at += MODCP_PARAM_SLOT(slots[i].width); /* a 1-byte member: 2 unless packed */
        j++;
    }
}

static void test_manual_sets_are_valid(void **state)
{
    (void)state;
    /* [RTU-2003] §9 parameter set with the 4.6.4 limits */
    modcp_params_t p;
    params_004_9(&p);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* [RTU-2003] §3.1 4.6.2: two DB-bit windows on top, [ASCII-32] §4.1 / §4.2 */
    set_win(&p.coils[4], MODCP_AREA_DB, 8192, 8511, 0, 111);
    set_win(&p.coils[5], MODCP_AREA_DB, 9000, 9000, 0, 111);
    set_win(&p.inputs[2], MODCP_AREA_DB, 8192, 8351, 0, 112);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* [ASCII-32] ASCII: 7 data bits; 8 allowed as an extension */
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 7;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.data_bits = 8;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* [ASCII-32] §4.5 32-bit ranges */
    p.regs32 = 1;
    p.r32[0] = (modcp_r32range_t){3000, 4999, 2};
    p.r32[1] = (modcp_r32range_t){5000, 5099, 3};
    p.r32[2] = (modcp_r32range_t){7000, 9999, 4};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* boundaries that are legal */
    p.baud = 115200;
    p.f_mul = 10;
    p.ascii_timeout_ms = 6500;
    p.turnaround_ms = 100;
    p.iface = MODCP_IFACE_RS485;
    p.opmode = MODCP_OPMODE_SUPPRESS; /* two-wire: modem mode ([RTU-2009] Table 5-2) */
    p.commloss_ms = 30000;
    p.job_limit = 1024;
    p.scan_count = 16;
    p.scan_start = 65520;
    p.scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 10};
    p.scan[1] = (modcp_operand_ref_t){MODCP_AREA_DB, 5, 20};
    p.scan[2] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 3};
    p.scan[3] = (modcp_operand_ref_t){MODCP_AREA_I, 0, 65534};
    p.scan[4] = (modcp_operand_ref_t){MODCP_AREA_C, 0, 65535};
    p.scan[5] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 0};
    memcpy(p.vendor, "0123456789ABCDEF", 17); /* 16 characters + NUL */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.commloss_ms = 100;
    p.f_mul = 1;
    p.ascii_timeout_ms = 1;
    p.job_limit = 32;
    p.baud = 300;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

/* ---- the manual's own events -------------------------------------------------- */

static void test_data_bits(void **state)
{
    (void)state;
    /* [RTU-2003] §2.1: RTU 8 only -> (0E)20H fatal; [ASCII-32] §3.1 ASCII 7 */
    modcp_params_t p;
    params_004_9(&p);
    p.data_bits = 7;
    expect_one(&p, MODCP_PF_DATA_BITS, 0, MODCP_EV_DATA_BITS, true, 7);
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 6;
    expect_one(&p, MODCP_PF_DATA_BITS, 0, MODCP_EV_DATA_BITS, true, 6);
    p.data_bits = 9;
    expect_one(&p, MODCP_PF_DATA_BITS, 0, MODCP_EV_DATA_BITS, true, 9);
}

/* [ASCII-32] §3.1 (CP 341 MODBUS ASCII slave, transmission parameters): "With Modbus ASCII 7
 * data bits are mandatory." "With even or odd parity 1 stop bit is pre-defined. None
 * parity effects two stop bits." The ASCII frame is 7E1, 7O1 or 7N2; 7N1, 7E2, 7O2 are
 * refused on the stop bits ((0E)2EH: the manual gives the rule no event of its own).
 * The 8-bit extension of docs/parameters.md follows the same rule (8E1, 8O1, 8N2). */
static void test_ascii_frame_7e1_7o1_7n2_accepted(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.framing = MODCP_FRAMING_ASCII;
    static const struct {
        uint8_t data, parity, stop;
        bool ok;
    } frames[] = {
        {7, MODCP_PARITY_EVEN, 1, true},  {7, MODCP_PARITY_ODD, 1, true},
        {7, MODCP_PARITY_NONE, 2, true},  {7, MODCP_PARITY_NONE, 1, false},
        {7, MODCP_PARITY_EVEN, 2, false}, {7, MODCP_PARITY_ODD, 2, false},
        {8, MODCP_PARITY_EVEN, 1, true},  {8, MODCP_PARITY_ODD, 1, true},
        {8, MODCP_PARITY_NONE, 2, true},  {8, MODCP_PARITY_NONE, 1, false},
        {8, MODCP_PARITY_EVEN, 2, false}, {8, MODCP_PARITY_ODD, 2, false},
    };
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        p.data_bits = frames[i].data;
        p.parity = frames[i].parity;
        p.stop_bits = frames[i].stop;
        if (frames[i].ok) {
            assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
        } else {
            expect_one(&p, MODCP_PF_STOP_BITS, 0, MODCP_EV_PARAM_RECORD, true, frames[i].stop);
        }
    }
    /* an out-of-range value is one issue, as before */
    p.stop_bits = 3;
    expect_one(&p, MODCP_PF_STOP_BITS, 0, MODCP_EV_PARAM_RECORD, true, 3);
    /* 6 data bits: the data-bits event alone (the stop bits fit the parity) */
    p.data_bits = 6;
    p.parity = MODCP_PARITY_EVEN;
    p.stop_bits = 1;
    expect_one(&p, MODCP_PF_DATA_BITS, 0, MODCP_EV_DATA_BITS, true, 6);
}

/* [RTU-2003] §2.1 Table 5-1: RTU keeps the manual's free choice of 1 or 2 stop bits with any
 * parity (8N1, 8E2 ...): the ASCII rule is for ASCII only. */
static void test_rtu_stop_bits_free_with_any_parity(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    for (uint8_t par = 0; par <= MODCP_PARITY_EVEN; par++) {
        for (uint8_t stop = 1; stop <= 2; stop++) {
            p.parity = par;
            p.stop_bits = stop;
            assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
        }
    }
}

/* [ASCII-32] §3.1: the CP refuses a 7N1 ASCII record at start-up (driver not ready; FB:
 * CP_START_ERROR, ERROR_INFO (0E)2EH); the same record as 7N2 starts. */
static void test_ascii_7n1_refused_by_cp(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 7;
    p.parity = MODCP_PARITY_NONE;
    p.stop_bits = 1;
    p.start_time_ms = 500;
    world_t *w = world_new(&p);
    assert_false(world_start(w, 2000));
    assert_true(w->fb_out.cp_start_error);
    assert_int_equal(w->fb_out.error_info, MODCP_EV_PARAM_RECORD);
    assert_false(w->cp.configured);
    world_free(w);
    p.stop_bits = 2;
    w = world_new(&p);
    assert_true(world_start(w, 2000));
    assert_true(w->cp.configured);
    world_free(w);
}

static void test_slave_addr(void **state)
{
    (void)state;
    /* [RTU-2003] §2.2: own address 0 -> (0E)23H, driver not ready; 255 legal */
    modcp_params_t p;
    params_004_9(&p);
    p.slave_addr = 0;
    expect_one(&p, MODCP_PF_SLAVE_ADDR, 0, MODCP_EV_SLAVE_ADDR, true, 0);
    p.slave_addr = 255;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

static void test_opmode(void **state)
{
    (void)state;
    /* [RTU-2003] §2.2: illegal operating mode -> (0E)22H fatal */
    modcp_params_t p;
    params_004_9(&p);
    p.opmode = 2;
    expect_one(&p, MODCP_PF_OPMODE, 0, MODCP_EV_OPMODE, true, 2);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

/* [RTU-2009] §5.6.1 Table 5-2 "Activer la sélection du mode de fonctionnement pour RS485"
 * (default "Non") and "Mode de fonctionnement" (default: full duplex RS422 4-wire
 * normal, half duplex RS485 2-wire modem): without the selection, two-wire RS485 runs in
 * modem (interference suppression) mode only; "normal" there is refused with (0E)22H
 * "selected operating mode not allowed", the driver is not ready. */
static void test_rs485_normal_needs_mode_select(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.iface = MODCP_IFACE_RS485;
    p.opmode = MODCP_OPMODE_NORMAL;
    expect_one(&p, MODCP_PF_OPMODE, 0, MODCP_EV_OPMODE, true, MODCP_OPMODE_NORMAL);
    p.rs485_sel = 1; /* selection enabled: normal allowed */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.rs485_sel = 0; /* modem on two-wire: always legal */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.rs485_sel = 2;
    expect_one(&p, MODCP_PF_RS485_SEL, 0, MODCP_EV_PARAM_RECORD, true, 2);
}

/* [RTU-2009] Table 5-2 / Table 5-8: full duplex RS422 4-wire (and RS232) default to normal and
 * may choose either mode without the RS485 selection. */
static void test_four_wire_normal_or_modem(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    static const uint8_t ifaces[] = {MODCP_IFACE_RS232, MODCP_IFACE_RS422};
    for (size_t i = 0; i < sizeof ifaces; i++) {
        p.iface = ifaces[i];
        p.rs485_sel = 0;
        p.opmode = MODCP_OPMODE_NORMAL;
        assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
        p.opmode = MODCP_OPMODE_SUPPRESS;
        assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    }
    modcp_params_defaults(&p);
    assert_int_equal(p.iface, MODCP_IFACE_RS232);
    assert_int_equal(p.opmode, MODCP_OPMODE_NORMAL);
}

/* [RTU-2009] §10 event (0E)22H, driver not ready: the CP refuses such a record at start-up
 * (FB: CP_START_ERROR, ERROR_INFO 0E22H) and answers nothing; with the selection the
 * same record starts and answers. */
static void test_rs485_normal_refused_by_cp(void **state)
{
    (void)state;
    modcp_params_t p;
    params_004_9(&p);
    p.iface = MODCP_IFACE_RS485;
    p.opmode = MODCP_OPMODE_NORMAL;
    p.start_time_ms = 500;
    world_t *w = world_new(&p);
    assert_false(world_start(w, 2000));
    assert_true(w->fb_out.cp_start_error);
    assert_int_equal(w->fb_out.error_info, MODCP_EV_OPMODE);
    assert_false(w->cp.configured);
    assert_int_equal(w->cp.param_event, MODCP_EV_OPMODE);
    assert_int_equal(world_request(w, "05 08 00 00 A5 C3 DA 8E", 50), 0);
    world_free(w);

    p.rs485_sel = 1;
    w = world_new(&p);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 08 00 00 A5 C3 DA 8E", 50), 8);
    world_free(w);
}

static void test_fmul_corrected(void **state)
{
    (void)state;
    /* [RTU-2003] §2.2: f_MUL outside 1..10 -> (0E)21H, the driver runs with 1 */
    modcp_params_t p;
    params_004_9(&p);
    p.f_mul = 0;
    expect_one(&p, MODCP_PF_FMUL, 0, MODCP_EV_FMUL, false, 0);
    p.f_mul = 11;
    expect_one(&p, MODCP_PF_FMUL, 0, MODCP_EV_FMUL, false, 11);
    modcp_params_t eff;
    modcp_event_t warn = 0;
    assert_int_equal(modcp_params_apply(&p, &eff, &warn), MODCP_EV_NONE);
    assert_int_equal(warn, MODCP_EV_FMUL);
    assert_int_equal(eff.f_mul, 1);
    assert_int_equal(p.f_mul, 11); /* the input is not touched */
    assert_int_equal(eff.slave_addr, 5);
    assert_int_equal(eff.coils[0].start, 1000);
    /* NULL warning pointer is allowed */
    assert_int_equal(modcp_params_apply(&p, &eff, NULL), MODCP_EV_NONE);
    /* in place */
    assert_int_equal(modcp_params_apply(&p, &p, NULL), MODCP_EV_NONE);
    assert_int_equal(p.f_mul, 1);
}

static void test_ascii_timeout_corrected(void **state)
{
    (void)state;
    /* [ASCII-32] §3.2: character delay time outside 1..6500 ms -> driver runs with 1000 ms */
    modcp_params_t p;
    params_004_9(&p);
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 7;
    p.ascii_timeout_ms = 0;
    expect_one(&p, MODCP_PF_ASCII_TIMEOUT, 0, MODCP_EV_FMUL, false, 0);
    p.ascii_timeout_ms = 6501;
    expect_one(&p, MODCP_PF_ASCII_TIMEOUT, 0, MODCP_EV_FMUL, false, 6501);
    modcp_params_t eff;
    modcp_event_t warn = 0;
    assert_int_equal(modcp_params_apply(&p, &eff, &warn), MODCP_EV_NONE);
    assert_int_equal(warn, MODCP_EV_FMUL);
    assert_int_equal(eff.ascii_timeout_ms, 1000);
}

static void test_write_limits(void **state)
{
    (void)state;
    /* [RTU-2003] §3.5: illegal write limits -> (0E)24H fatal; value = min << 16 | max */
    modcp_params_t p;
    params_004_9(&p);
    p.lim_m = (modcp_limit_t){1128, 1127};
    expect_one(&p, MODCP_PF_LIM_M, 0, MODCP_EV_WRITE_LIMITS, true, (1128u << 16) | 1127u);
    params_004_9(&p);
    p.lim_q = (modcp_limit_t){320, 319};
    expect_one(&p, MODCP_PF_LIM_Q, 0, MODCP_EV_WRITE_LIMITS, true, (320u << 16) | 319u);
    params_004_9(&p);
    p.lim_db = (modcp_limit_t){700, 699};
    expect_one(&p, MODCP_PF_LIM_DB, 0, MODCP_EV_WRITE_LIMITS, true, (700u << 16) | 699u);
    /* DB MIN range is 1..65535 */
    p.lim_db = (modcp_limit_t){0, 699};
    expect_one(&p, MODCP_PF_LIM_DB, 0, MODCP_EV_WRITE_LIMITS, true, 699u);
    /* MAX = 0 disables the area whatever MIN says; M/Q MIN 0 is legal */
    p.lim_db = (modcp_limit_t){700, 0};
    p.lim_m = (modcp_limit_t){0, 10};
    p.lim_q = (modcp_limit_t){5, 0};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.lim_m = (modcp_limit_t){10, 10}; /* one byte */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

static void test_coil_windows_illegal(void **state)
{
    (void)state;
    /* [RTU-2003] §3.1: illegal from/to for FC01/05/15 -> (0E)25H fatal */
    modcp_params_t p;
    params_004_9(&p);
    p.coils[1].area = MODCP_AREA_I; /* inputs are not coils */
    expect_one(&p, MODCP_PF_COILS, 1, MODCP_EV_COIL_FROMTO, true, MODCP_AREA_I);
    params_004_9(&p);
    p.coils[4].area = 7; /* no such area */
    expect_one(&p, MODCP_PF_COILS, 4, MODCP_EV_COIL_FROMTO, true, 7);
    params_004_9(&p);
    set_win(&p.coils[0], MODCP_AREA_M, 2047, 0, 1000, 0); /* from > to */
    expect_one(&p, MODCP_PF_COILS, 0, MODCP_EV_COIL_FROMTO, true, (2047u << 16) | 0u);
    params_004_9(&p);
    set_win(&p.coils[4], MODCP_AREA_DB, 8192, 8255, 0, 0); /* [ASCII-32] §4.1: DB 0 */
    expect_one(&p, MODCP_PF_COILS, 4, MODCP_EV_COIL_FROMTO, true, 0);
    params_004_9(&p);
    set_win(&p.coils[2], MODCP_AREA_T, 4096, 4195, 100, 0); /* 100 bits: not whole words */
    expect_one(&p, MODCP_PF_COILS, 2, MODCP_EV_COIL_FROMTO, true, 100);
    params_004_9(&p);
    set_win(&p.coils[3], MODCP_AREA_C, 4608, 4615, 200, 0); /* 8 bits */
    expect_one(&p, MODCP_PF_COILS, 3, MODCP_EV_COIL_FROMTO, true, 8);
    params_004_9(&p);
    set_win(&p.coils[0], MODCP_AREA_M, 0, 2047, 65280, 0); /* 256 bytes from MB 65280: ok */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.coils[0].start = 65281; /* last byte 65536 */
    expect_one(&p, MODCP_PF_COILS, 0, MODCP_EV_COIL_FROMTO, true, 65536);
    params_004_9(&p);
    p.coils[2].start = 65505; /* 32 timers from T 65505: last T 65536 */
    expect_one(&p, MODCP_PF_COILS, 2, MODCP_EV_COIL_FROMTO, true, 65536);
    params_004_9(&p);
    set_win(&p.coils[5], MODCP_AREA_DB, 0, 65535, 60000, 9); /* 8192 bytes from DBB 60000 */
    p.coils[0].area = MODCP_AREA_NONE;
    p.coils[1].area = MODCP_AREA_NONE;
    p.coils[2].area = MODCP_AREA_NONE;
    p.coils[3].area = MODCP_AREA_NONE;
    expect_one(&p, MODCP_PF_COILS, 5, MODCP_EV_COIL_FROMTO, true, 60000u + 8191u);
}

static void test_coil_windows_overlap(void **state)
{
    (void)state;
    /* [RTU-2003] §3.1: overlapping from/to FC01/05/15 -> (0E)27H fatal; gaps are legal */
    modcp_params_t p;
    params_004_9(&p);
    p.coils[1].from = 2047; /* Q window now starts inside the M window */
    expect_one(&p, MODCP_PF_COILS, 1, MODCP_EV_COIL_OVERLAP, true, 0);
    params_004_9(&p);
    set_win(&p.coils[5], MODCP_AREA_DB, 5000, 5200, 0, 111); /* into the C window */
    expect_one(&p, MODCP_PF_COILS, 5, MODCP_EV_COIL_OVERLAP, true, 3);
    params_004_9(&p);
    set_win(&p.coils[4], MODCP_AREA_DB, 5120, 5200, 0, 111); /* adjacent: legal */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* a disabled window (area NONE) never overlaps */
    set_win(&p.coils[5], MODCP_AREA_NONE, 0, 65535, 0, 0);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    /* FC02 windows are independent: the same addresses are legal there */
    params_004_9(&p);
    assert_int_equal(p.inputs[0].from, p.coils[0].from);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

static void test_input_windows(void **state)
{
    (void)state;
    /* [RTU-2003] §3.2: FC02 illegal -> (0E)26H, overlap -> (0E)28H, both fatal */
    modcp_params_t p;
    params_004_9(&p);
    p.inputs[1].area = MODCP_AREA_Q;
    expect_one(&p, MODCP_PF_INPUTS, 1, MODCP_EV_INPUT_FROMTO, true, MODCP_AREA_Q);
    params_004_9(&p);
    set_win(&p.inputs[2], MODCP_AREA_T, 8192, 8207, 0, 0); /* timers are FC01 only */
    expect_one(&p, MODCP_PF_INPUTS, 2, MODCP_EV_INPUT_FROMTO, true, MODCP_AREA_T);
    params_004_9(&p);
    set_win(&p.inputs[1], MODCP_AREA_I, 5119, 4096, 128, 0);
    expect_one(&p, MODCP_PF_INPUTS, 1, MODCP_EV_INPUT_FROMTO, true, (5119u << 16) | 4096u);
    params_004_9(&p);
    set_win(&p.inputs[3], MODCP_AREA_DB, 8192, 8351, 0, 0);
    expect_one(&p, MODCP_PF_INPUTS, 3, MODCP_EV_INPUT_FROMTO, true, 0);
    params_004_9(&p);
    p.inputs[1].start = 65535; /* 128 bytes from IB 65535 */
    expect_one(&p, MODCP_PF_INPUTS, 1, MODCP_EV_INPUT_FROMTO, true, 65535u + 127u);
    params_004_9(&p);
    p.inputs[1].from = 4000; /* I window overlaps the M window */
    expect_one(&p, MODCP_PF_INPUTS, 1, MODCP_EV_INPUT_OVERLAP, true, 0);
    params_004_9(&p);
    set_win(&p.inputs[3], MODCP_AREA_DB, 5119, 5119, 0, 112);
    expect_one(&p, MODCP_PF_INPUTS, 3, MODCP_EV_INPUT_OVERLAP, true, 1);
}

/* ---- fields without their own event: (0E)2EH ------------------------------------ */

static void test_record_field_errors(void **state)
{
    (void)state;
    const modcp_event_t rec = MODCP_EV_PARAM_RECORD;
    modcp_params_t p;

    params_004_9(&p);
    p.baud = 14400; /* not in the table */
    expect_one(&p, MODCP_PF_BAUD, 0, rec, true, 14400);
    p.baud = 0; /* no rate at all: 0 / 300 passed the power-of-two test once */
    expect_one(&p, MODCP_PF_BAUD, 0, rec, true, 0);
    params_004_9(&p);
    p.parity = 3;
    expect_one(&p, MODCP_PF_PARITY, 0, rec, true, 3);
    params_004_9(&p);
    p.stop_bits = 0;
    expect_one(&p, MODCP_PF_STOP_BITS, 0, rec, true, 0);
    p.stop_bits = 3;
    expect_one(&p, MODCP_PF_STOP_BITS, 0, rec, true, 3);
    params_004_9(&p);
    p.framing = 2;
    expect_one(&p, MODCP_PF_FRAMING, 0, rec, true, 2);
    params_004_9(&p);
    p.eof_timing = 2;
    expect_one(&p, MODCP_PF_EOF_TIMING, 0, rec, true, 2);
    params_004_9(&p);
    p.t15_check = 2;
    expect_one(&p, MODCP_PF_T15_CHECK, 0, rec, true, 2);
    params_004_9(&p);
    p.iface = 3;
    expect_one(&p, MODCP_PF_IFACE, 0, rec, true, 3);
    params_004_9(&p);
    p.turnaround_ms = 101;
    expect_one(&p, MODCP_PF_TURNAROUND, 0, rec, true, 101);
    params_004_9(&p);
    p.rs232_auto = 2;
    expect_one(&p, MODCP_PF_RS232_AUTO, 0, rec, true, 2);
    p.rs232_auto = 1; /* [RTU-2003] §2.4: RS232 only */
    p.iface = MODCP_IFACE_RS485;
    p.opmode = MODCP_OPMODE_SUPPRESS; /* two-wire: modem mode ([RTU-2009] Table 5-2) */
    expect_one(&p, MODCP_PF_RS232_AUTO, 0, rec, true, 1);
    p.iface = MODCP_IFACE_RS232;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    params_004_9(&p);
    p.regs32 = 2;
    expect_one(&p, MODCP_PF_REGS32, 0, rec, true, 2);
    params_004_9(&p);
    p.fset = 2;
    expect_one(&p, MODCP_PF_FSET, 0, rec, true, 2);
    params_004_9(&p);
    p.qty_limits = 2;
    expect_one(&p, MODCP_PF_QTY_LIMITS, 0, rec, true, 2);
    params_004_9(&p);
    p.cpu_model = 2;
    expect_one(&p, MODCP_PF_CPU_MODEL, 0, rec, true, 2);
    params_004_9(&p);
    p.job_limit = 31;
    expect_one(&p, MODCP_PF_JOB_LIMIT, 0, rec, true, 31);
    p.job_limit = 1025; /* CP 341 model limit 1024 */
    expect_one(&p, MODCP_PF_JOB_LIMIT, 0, rec, true, 1025);
    p.cpu_model = MODCP_CPU_CP441;
    p.job_limit = 451; /* CP 441-2 model limit 450 */
    expect_one(&p, MODCP_PF_JOB_LIMIT, 0, rec, true, 451);
    p.job_limit = 450;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    params_004_9(&p);
    p.cpu_timeout_ms = 0;
    expect_one(&p, MODCP_PF_CPU_TIMEOUT, 0, rec, true, 0);
    params_004_9(&p);
    p.start_time_ms = 0;
    expect_one(&p, MODCP_PF_START_TIME, 0, rec, true, 0);
    params_004_9(&p);
    p.commloss_ms = 99;
    expect_one(&p, MODCP_PF_COMMLOSS, 0, rec, true, 99);
    p.commloss_ms = 30001;
    expect_one(&p, MODCP_PF_COMMLOSS, 0, rec, true, 30001);
}

/* VIPA CP 341 manual §1.6 / §7.1: RTS off delay and data output waiting time 0 ... 65535
 * ms in steps of 10 ms, default 10 ms ([RTU-2003] §2.4 and [RTU-2009] give no values); the receive-line
 * preset of [RTU-2009] Table 5-8: R(A) 5 V / R(B) 0 V (BREAK detection) only on four-wire RS422
 * (note 1), refused on two-wire RS485. Each with (0E)2EH naming the field and value. */
static void test_rts_steps_and_receive_preset(void **state)
{
    (void)state;
    const modcp_event_t rec = MODCP_EV_PARAM_RECORD;
    modcp_params_t p;
    params_004_9(&p);
    p.rs232_auto = 1;
    p.rts_on_delay_ms = 15;
    expect_one(&p, MODCP_PF_RTS_ON_DELAY, 0, rec, true, 15);
    p.rts_on_delay_ms = 65530;
    p.rts_off_delay_ms = 65535;
    expect_one(&p, MODCP_PF_RTS_OFF_DELAY, 0, rec, true, 65535);
    p.rts_off_delay_ms = 0;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);

    params_004_9(&p);
    p.iface = MODCP_IFACE_RS485;
    p.opmode = MODCP_OPMODE_SUPPRESS;
    p.rx_preset = MODCP_RXP_BREAK;
    expect_one(&p, MODCP_PF_RX_PRESET, 0, rec, true, MODCP_RXP_BREAK);
    p.rx_preset = MODCP_RXP_HIGH;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.iface = MODCP_IFACE_RS422;
    p.rx_preset = MODCP_RXP_BREAK;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.rx_preset = 4;
    expect_one(&p, MODCP_PF_RX_PRESET, 0, rec, true, 4);
}

static void test_scanner_errors(void **state)
{
    (void)state;
    const modcp_event_t rec = MODCP_EV_PARAM_RECORD;
    modcp_params_t p;
    params_004_9(&p);
    p.scan_count = 17;
    expect_one(&p, MODCP_PF_SCANNER, 0xFF, rec, true, 17);
    p.scan_count = 2;
    p.scan_start = 65535; /* registers 65535, 65536 */
    expect_one(&p, MODCP_PF_SCANNER, 0xFF, rec, true, 2);
    p.scan_start = 100;
    p.scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 10};
    p.scan[1] = (modcp_operand_ref_t){8, 0, 10}; /* no such area */
    expect_one(&p, MODCP_PF_SCANNER, 1, rec, true, 8);
    p.scan[1] = (modcp_operand_ref_t){MODCP_AREA_DB, 0, 20}; /* DB 0 */
    expect_one(&p, MODCP_PF_SCANNER, 1, rec, true, 0);
    p.scan[1] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 65535}; /* no room for a word */
    expect_one(&p, MODCP_PF_SCANNER, 1, rec, true, 65535);
    /* entries beyond scan_count are not checked */
    p.scan_count = 1;
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

static void test_id_strings(void **state)
{
    (void)state;
    /* ID strings ([ALTIVAR] §10.5) must be NUL-terminated within 17 bytes */
    modcp_params_t p;
    params_004_9(&p);
    memset(p.revision, 'x', sizeof p.revision);
    expect_one(&p, MODCP_PF_ID_STRING, 2, MODCP_EV_PARAM_RECORD, true, 'x');
    params_004_9(&p);
    memset(p.app_name, 'y', sizeof p.app_name);
    expect_one(&p, MODCP_PF_ID_STRING, 3, MODCP_EV_PARAM_RECORD, true, 'y');
}

static void test_r32_ranges(void **state)
{
    (void)state;
    /* [ASCII-32] §4.5 / §8.6 32-bit range errors: event numbers illegible -> (0E)2EH */
    const modcp_event_t rec = MODCP_EV_PARAM_RECORD;
    modcp_params_t p;
    params_004_9(&p);
    p.r32[0] = (modcp_r32range_t){4999, 3000, 2}; /* not checked while regs32 is off */
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.regs32 = 1;
    expect_one(&p, MODCP_PF_R32, 0, rec, true, (4999u << 16) | 3000u);
    p.r32[0] = (modcp_r32range_t){3000, 4999, 0}; /* DB 0 */
    expect_one(&p, MODCP_PF_R32, 0, rec, true, 0);
    /* a DB holds 32768 16-bit or 16384 32-bit registers ([ASCII-32] §4.5: DBW 65534 / DBD 65532) */
    p.r32[0] = (modcp_r32range_t){0, 32767, 2};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.r32[0] = (modcp_r32range_t){0, 32768, 2};
    expect_one(&p, MODCP_PF_R32, 0, rec, true, 65538);
    p.r32[0] = (modcp_r32range_t){0, 0, 0};
    p.r32[1] = (modcp_r32range_t){40000, 56383, 3};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    p.r32[1] = (modcp_r32range_t){40000, 56384, 3};
    expect_one(&p, MODCP_PF_R32, 1, rec, true, 65540);
    p.r32[1] = (modcp_r32range_t){0, 0, 0};
    p.r32[2] = (modcp_r32range_t){0, 65535, 4};
    expect_one(&p, MODCP_PF_R32, 2, rec, true, 65536u * 4u);
    /* overlapping ranges: reported on the later range, value = the earlier one */
    p.r32[0] = (modcp_r32range_t){3000, 4999, 2};
    p.r32[1] = (modcp_r32range_t){5000, 5099, 3};
    p.r32[2] = (modcp_r32range_t){5099, 9999, 4};
    expect_one(&p, MODCP_PF_R32, 2, rec, true, 1);
    /* the same DB twice */
    p.r32[2] = (modcp_r32range_t){7000, 9999, 2};
    expect_one(&p, MODCP_PF_R32, 2, rec, true, 2);
    p.r32[2] = (modcp_r32range_t){7000, 9999, 4};
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
}

/* The rule each issue names (modcp_param_rule_t): what tools/conf turns into words
 * without deciding again. */
static uint8_t only_rule(const modcp_params_t *p, uint8_t *other)
{
    modcp_param_issue_t is[2];
    assert_int_equal(modcp_params_validate(p, is, 2), 1);
    *other = is[0].other;
    return is[0].rule;
}

static void test_issue_rules(void **state)
{
    (void)state;
    modcp_params_t p;
    uint8_t other = 0;
    params_004_9(&p);
    p.slave_addr = 0; /* outside 1..255 */
    assert_int_equal(only_rule(&p, &other), MODCP_PR_RANGE);
    assert_int_equal(other, 0xFF);
    params_004_9(&p);
    p.framing = MODCP_FRAMING_ASCII; /* 8 data bits, parity even: 1 stop bit */
    p.stop_bits = 2;                 /* in 1..2, not for this ASCII frame */
    assert_int_equal(only_rule(&p, &other), MODCP_PR_RULE);
    params_004_9(&p);
    p.coils[1].area = MODCP_AREA_I;
    assert_int_equal(only_rule(&p, &other), MODCP_PR_AREA);
    params_004_9(&p);
    set_win(&p.coils[0], MODCP_AREA_M, 2047, 0, 1000, 0);
    assert_int_equal(only_rule(&p, &other), MODCP_PR_FROM_TO);
    params_004_9(&p);
    set_win(&p.coils[4], MODCP_AREA_DB, 8192, 8255, 0, 0);
    assert_int_equal(only_rule(&p, &other), MODCP_PR_DB_ZERO);
    params_004_9(&p);
    set_win(&p.coils[2], MODCP_AREA_T, 4096, 4195, 100, 0);
    assert_int_equal(only_rule(&p, &other), MODCP_PR_TC_SIZE);
    params_004_9(&p);
    p.inputs[1].start = 65535;
    assert_int_equal(only_rule(&p, &other), MODCP_PR_EXTENT);
    params_004_9(&p);
    p.inputs[1].from = 4000; /* into the M window (0) */
    assert_int_equal(only_rule(&p, &other), MODCP_PR_OVERLAP);
    assert_int_equal(other, 0);
    params_004_9(&p);
    p.lim_db = (modcp_limit_t){700, 699};
    assert_int_equal(only_rule(&p, &other), MODCP_PR_FROM_TO);
    p.lim_db = (modcp_limit_t){0, 699};
    assert_int_equal(only_rule(&p, &other), MODCP_PR_DB_ZERO);
    /* 32-bit ranges: an unusable range (int16, more than one DB) is left out of the
     * overlap checks, the overlap names the range validation compared with */
    params_004_9(&p);
    p.regs32 = 1;
    p.r32[0] = (modcp_r32range_t){0, 40000, 2};
    p.r32[1] = (modcp_r32range_t){1000, 1999, 3};
    p.r32[2] = (modcp_r32range_t){1500, 2500, 4};
    modcp_param_issue_t is[3];
    assert_int_equal(modcp_params_validate(&p, is, 3), 2);
    assert_int_equal(is[0].rule, MODCP_PR_EXTENT);
    assert_int_equal(is[0].value, 80002);
    assert_int_equal(is[1].index, 2);
    assert_int_equal(is[1].rule, MODCP_PR_OVERLAP);
    assert_int_equal(is[1].other, 1);
    p.r32[2] = (modcp_r32range_t){3000, 3999, 3};
    assert_int_equal(modcp_params_validate(&p, is, 3), 2);
    assert_int_equal(is[1].rule, MODCP_PR_SAME_DB);
    assert_int_equal(is[1].value, 3);
    assert_int_equal(is[1].other, 1);
}

static void test_many_issues(void **state)
{
    (void)state;
    /* several bad fields: one issue each, counted even past max; first fatal wins */
    modcp_params_t p;
    params_004_9(&p);
    p.slave_addr = 0; /* (0E)23H */
    p.opmode = 5;     /* (0E)22H */
    p.f_mul = 0;      /* (0E)21H warning */
    p.lim_m = (modcp_limit_t){5, 4}; /* (0E)24H */
    modcp_params_t copy;
    memcpy(&copy, &p, sizeof p);
    modcp_param_issue_t is[2];
    assert_int_equal(modcp_params_validate(&p, is, 2), 4);
    assert_memory_equal(&p, &copy, sizeof p); /* never modifies p */
    assert_int_equal(is[0].event, MODCP_EV_SLAVE_ADDR);
    assert_int_equal(is[1].event, MODCP_EV_OPMODE);
    modcp_param_issue_t all[8];
    assert_int_equal(modcp_params_validate(&p, all, 8), 4);
    assert_int_equal(all[2].event, MODCP_EV_FMUL);
    assert_false(all[2].fatal);
    assert_int_equal(all[3].event, MODCP_EV_WRITE_LIMITS);
    assert_true(all[3].fatal);
    modcp_event_t warn = 0;
    modcp_params_t eff;
    assert_int_equal(modcp_params_apply(&p, &eff, &warn), MODCP_EV_SLAVE_ADDR);
    assert_int_equal(warn, MODCP_EV_FMUL);
    /* a window with two problems is one issue */
    params_004_9(&p);
    set_win(&p.coils[4], MODCP_AREA_DB, 9000, 8000, 0, 0);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 1);
}

/* ---- binary record -------------------------------------------------------------- */

/* Every field set to a distinct non-default value. */
static void params_all_fields(modcp_params_t *p)
{
    params_004_9(p);
    p->baud = 76800;
    p->data_bits = 7;
    p->parity = MODCP_PARITY_ODD;
    p->stop_bits = 2;
    p->framing = MODCP_FRAMING_ASCII;
    p->opmode = MODCP_OPMODE_SUPPRESS;
    p->f_mul = 7;
    p->eof_timing = MODCP_EOF_MODBUS;
    p->t15_check = 1;
    p->ascii_timeout_ms = 0x1234;
    p->iface = MODCP_IFACE_RS485;
    p->turnaround_ms = 0x0063;
    p->rs232_auto = 1;
    p->rts_on_delay_ms = 0xA1B2;
    p->rts_off_delay_ms = 0xC3D4;
    p->rx_preset = MODCP_RXP_HIGH;
    set_win(&p->coils[4], MODCP_AREA_DB, 0x2000, 0x21FF, 0x0102, 0x0304);
    set_win(&p->coils[5], MODCP_AREA_DB, 0x3000, 0x30FF, 0x0506, 0x0708);
    set_win(&p->inputs[2], MODCP_AREA_DB, 0x2000, 0x2FFF, 0x090A, 0x0B0C);
    set_win(&p->inputs[3], MODCP_AREA_DB, 0x4000, 0x4001, 0x0D0E, 0x0F10);
    p->hr_base_db = 0xBEEF;
    p->ir_base_db = 0xCAFE;
    p->regs32 = 1;
    p->r32[0] = (modcp_r32range_t){0x1111, 0x2222, 0x3333};
    p->r32[1] = (modcp_r32range_t){0x4444, 0x5555, 0x6666};
    p->r32[2] = (modcp_r32range_t){0x7777, 0x8888, 0x9999};
    p->lim_db = (modcp_limit_t){0x0A0B, 0x0C0D};
    p->lim_m = (modcp_limit_t){0x1A1B, 0x1C1D};
    p->lim_q = (modcp_limit_t){0x2A2B, 0x2C2D};
    p->fset = MODCP_FSET_CP341;
    p->rs485_sel = 1;
    p->qty_limits = MODCP_QLIMITS_SPEC;
    p->r32_lim_db = 1;
    p->cpu_model = MODCP_CPU_CP441;
    p->job_limit = 0x01C2;
    p->cpu_timeout_ms = 0xEEEE;
    p->start_time_ms = 0xDDDD;
    p->commloss_ms = 0x7530;
    p->commloss_auto = 1;
    p->scan_start = 0xFF00;
    p->scan_count = 16;
    for (uint16_t i = 0; i < MODCP_SCANNER_MAX; i++) {
        p->scan[i].area = (uint8_t)(1 + i % 6);
        p->scan[i].db = (uint16_t)(0x100 + i);
        p->scan[i].offset = (uint16_t)(0x8000 + 2 * i);
    }
    memcpy(p->vendor, "ACME Automation!", 17);
    strcpy(p->product, "CP-1");
    strcpy(p->revision, "");
    strcpy(p->app_name, "pump station 7");
    p->diag_irq = 1;
}

static void assert_window_equal(const modcp_bitwin_t *a, const modcp_bitwin_t *b)
{
    assert_int_equal(a->area, b->area);
    assert_int_equal(a->from, b->from);
    assert_int_equal(a->to, b->to);
    assert_int_equal(a->start, b->start);
    assert_int_equal(a->db, b->db);
}

static void assert_params_equal(const modcp_params_t *a, const modcp_params_t *b)
{
    assert_int_equal(a->baud, b->baud);
    assert_int_equal(a->data_bits, b->data_bits);
    assert_int_equal(a->parity, b->parity);
    assert_int_equal(a->stop_bits, b->stop_bits);
    assert_int_equal(a->slave_addr, b->slave_addr);
    assert_int_equal(a->framing, b->framing);
    assert_int_equal(a->opmode, b->opmode);
    assert_int_equal(a->f_mul, b->f_mul);
    assert_int_equal(a->eof_timing, b->eof_timing);
    assert_int_equal(a->t15_check, b->t15_check);
    assert_int_equal(a->ascii_timeout_ms, b->ascii_timeout_ms);
    assert_int_equal(a->iface, b->iface);
    assert_int_equal(a->turnaround_ms, b->turnaround_ms);
    assert_int_equal(a->rs232_auto, b->rs232_auto);
    assert_int_equal(a->rts_on_delay_ms, b->rts_on_delay_ms);
    assert_int_equal(a->rts_off_delay_ms, b->rts_off_delay_ms);
    assert_int_equal(a->rx_preset, b->rx_preset);
    assert_int_equal(a->commloss_auto, b->commloss_auto);
    for (size_t i = 0; i < MODCP_COIL_WINDOWS; i++) {
        assert_window_equal(&a->coils[i], &b->coils[i]);
    }
    for (size_t i = 0; i < MODCP_INPUT_WINDOWS; i++) {
        assert_window_equal(&a->inputs[i], &b->inputs[i]);
    }
    assert_int_equal(a->hr_base_db, b->hr_base_db);
    assert_int_equal(a->ir_base_db, b->ir_base_db);
    assert_int_equal(a->regs32, b->regs32);
    assert_int_equal(a->r32_lim_db, b->r32_lim_db);
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(a->r32[i].from, b->r32[i].from);
        assert_int_equal(a->r32[i].to, b->r32[i].to);
        assert_int_equal(a->r32[i].db, b->r32[i].db);
    }
    assert_int_equal(a->lim_db.min, b->lim_db.min);
    assert_int_equal(a->lim_db.max, b->lim_db.max);
    assert_int_equal(a->lim_m.min, b->lim_m.min);
    assert_int_equal(a->lim_m.max, b->lim_m.max);
    assert_int_equal(a->lim_q.min, b->lim_q.min);
    assert_int_equal(a->lim_q.max, b->lim_q.max);
    assert_int_equal(a->fset, b->fset);
    assert_int_equal(a->rs485_sel, b->rs485_sel);
    assert_int_equal(a->qty_limits, b->qty_limits);
    assert_int_equal(a->cpu_model, b->cpu_model);
    assert_int_equal(a->job_limit, b->job_limit);
    assert_int_equal(a->cpu_timeout_ms, b->cpu_timeout_ms);
    assert_int_equal(a->start_time_ms, b->start_time_ms);
    assert_int_equal(a->commloss_ms, b->commloss_ms);
    assert_int_equal(a->scan_start, b->scan_start);
    assert_int_equal(a->scan_count, b->scan_count);
    for (size_t i = 0; i < MODCP_SCANNER_MAX; i++) {
        assert_int_equal(a->scan[i].area, b->scan[i].area);
        assert_int_equal(a->scan[i].db, b->scan[i].db);
        assert_int_equal(a->scan[i].offset, b->scan[i].offset);
    }
    assert_string_equal(a->vendor, b->vendor);
    assert_string_equal(a->product, b->product);
    assert_string_equal(a->revision, b->revision);
    assert_string_equal(a->app_name, b->app_name);
    assert_int_equal(a->diag_irq, b->diag_irq);
}

static void test_record_layout(void **state)
{
    (void)state;
    modcp_params_t p;
    params_all_fields(&p);
    uint8_t buf[MODCP_PARAMS_RECORD_MAX];
    size_t n = modcp_params_encode(&p, buf, sizeof buf);
    assert_int_equal(n, RECORD_LEN);
    assert_true(n <= MODCP_PARAMS_RECORD_MAX);
    /* "MCPR", u16 version LE, u16 payload length LE */
    assert_memory_equal(buf, "MCPR", 4);
    assert_int_equal(buf[4], MODCP_PARAMS_VERSION & 0xFF);
    assert_int_equal(buf[5], MODCP_PARAMS_VERSION >> 8);
    assert_int_equal(buf[6] | (buf[7] << 8), RECORD_LEN - 10);
    /* payload starts with baud u32 LE: 76800 = 0x00012C00 */
    assert_int_equal(buf[8], 0x00);
    assert_int_equal(buf[9], 0x2C);
    assert_int_equal(buf[10], 0x01);
    assert_int_equal(buf[11], 0x00);
    assert_int_equal(buf[12], 7);  /* data bits */
    assert_int_equal(buf[13], 1);  /* parity odd */
    assert_int_equal(buf[14], 2);  /* stop bits */
    assert_int_equal(buf[15], 5);  /* slave */
    assert_int_equal(buf[21], 0x34); /* ascii timeout 0x1234 LE */
    assert_int_equal(buf[22], 0x12);
    /* first coil window at offset 8 + 24 (after the receive preset): area M, from 0, to
     * 2047, start 1000, db 0 */
    static const uint8_t win0[9] = {MODCP_AREA_M, 0x00, 0x00, 0xFF, 0x07, 0xE8, 0x03, 0, 0};
    assert_int_equal(buf[31], MODCP_RXP_HIGH);
    assert_memory_equal(&buf[32], win0, sizeof win0);
    /* the ID strings are the 64 payload bytes before diag_irq: vendor uses all 16 */
    assert_memory_equal(&buf[RECORD_LEN - 3 - 64], "ACME Automation!", 16);
    assert_memory_equal(&buf[RECORD_LEN - 3 - 48], "CP-1\0\0\0\0\0\0\0\0\0\0\0\0", 16);
    assert_int_equal(buf[RECORD_LEN - 3], 1); /* diag_irq: the last payload byte */
    /* CRC-16 over everything before it, low byte first */
    uint16_t crc = modcp_crc16(buf, RECORD_LEN - 2);
    assert_int_equal(buf[RECORD_LEN - 2], crc & 0xFF);
    assert_int_equal(buf[RECORD_LEN - 1], crc >> 8);
    /* too small a buffer: nothing written */
    memset(buf, 0x77, sizeof buf);
    assert_int_equal(modcp_params_encode(&p, buf, RECORD_LEN - 1), 0);
    assert_int_equal(buf[0], 0x77);
    assert_int_equal(modcp_params_encode(&p, buf, RECORD_LEN), RECORD_LEN);
}

static void test_record_round_trip(void **state)
{
    (void)state;
    modcp_params_t p;
    params_all_fields(&p);
    uint8_t buf[MODCP_PARAMS_RECORD_MAX + 8];
    size_t n = modcp_params_encode(&p, buf, sizeof buf);
    assert_int_equal(n, RECORD_LEN);
    modcp_params_t q;
    memset(&q, 0xA5, sizeof q);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_NONE);
    assert_params_equal(&p, &q);
    /* trailing bytes after the record (a padded block) are ignored */
    memset(&buf[n], 0xEE, 8);
    memset(&q, 0xA5, sizeof q);
    assert_int_equal(modcp_params_decode(buf, n + 8, &q), MODCP_EV_NONE);
    assert_params_equal(&p, &q);
    /* the defaults and the §9 set survive too */
    modcp_params_defaults(&p);
    n = modcp_params_encode(&p, buf, sizeof buf);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_NONE);
    assert_params_equal(&p, &q);
    params_004_9(&p);
    n = modcp_params_encode(&p, buf, sizeof buf);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_NONE);
    assert_params_equal(&p, &q);
    assert_int_equal(modcp_params_validate(&q, NULL, 0), 0);
}

static void test_record_damaged(void **state)
{
    (void)state;
    modcp_params_t p;
    params_all_fields(&p);
    uint8_t good[MODCP_PARAMS_RECORD_MAX];
    uint8_t buf[MODCP_PARAMS_RECORD_MAX];
    size_t n = modcp_params_encode(&p, good, sizeof good);
    modcp_params_t q, untouched;
    memset(&q, 0x3C, sizeof q);
    memcpy(&untouched, &q, sizeof q);

    /* every single flipped byte is caught (CRC, or magic/version/length first) */
    for (size_t i = 0; i < n; i++) {
        memcpy(buf, good, n);
        buf[i] ^= 0x01;
        assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_PARAM_RECORD);
        assert_memory_equal(&q, &untouched, sizeof q);
    }
    /* truncated records */
    assert_int_equal(modcp_params_decode(good, n - 1, &q), MODCP_EV_PARAM_RECORD);
    assert_int_equal(modcp_params_decode(good, 10, &q), MODCP_EV_PARAM_RECORD);
    assert_int_equal(modcp_params_decode(good, 0, &q), MODCP_EV_PARAM_RECORD);
    assert_memory_equal(&q, &untouched, sizeof q);

    /* bad magic / version / length with a CRC that matches them */
    memcpy(buf, good, n);
    buf[3] = 'X';
    uint16_t crc = modcp_crc16(buf, n - 2);
    buf[n - 2] = (uint8_t)crc;
    buf[n - 1] = (uint8_t)(crc >> 8);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_PARAM_RECORD);
    memcpy(buf, good, n);
    buf[4] = (uint8_t)(MODCP_PARAMS_VERSION + 1);
    crc = modcp_crc16(buf, n - 2);
    buf[n - 2] = (uint8_t)crc;
    buf[n - 1] = (uint8_t)(crc >> 8);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_PARAM_RECORD);
    /* a shorter payload length, CRC placed where that length says */
    memcpy(buf, good, n);
    buf[6] = (uint8_t)(buf[6] - 1);
    crc = modcp_crc16(buf, n - 3);
    buf[n - 3] = (uint8_t)crc;
    buf[n - 2] = (uint8_t)(crc >> 8);
    assert_int_equal(modcp_params_decode(buf, n - 1, &q), MODCP_EV_PARAM_RECORD);
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_PARAM_RECORD);
    assert_memory_equal(&q, &untouched, sizeof q);
    /* NULL buffer */
    assert_int_equal(modcp_params_decode(NULL, n, &q), MODCP_EV_PARAM_RECORD);
}

static void test_record_id_strings(void **state)
{
    (void)state;
    /* an ID string is 16 raw bytes in the record; the decoder terminates it */
    modcp_params_t p;
    modcp_params_defaults(&p);
    memset(p.product, 'Z', sizeof p.product); /* invalid: no NUL in 17 bytes */
    uint8_t buf[MODCP_PARAMS_RECORD_MAX];
    size_t n = modcp_params_encode(&p, buf, sizeof buf);
    modcp_params_t q;
    assert_int_equal(modcp_params_decode(buf, n, &q), MODCP_EV_NONE);
    assert_string_equal(q.product, "ZZZZZZZZZZZZZZZZ");
    assert_string_equal(q.vendor, "modcp");
    /* garbage after the NUL is not serialised */
    modcp_params_defaults(&p);
    memcpy(p.vendor, "ab\0cdefghijklmno", 17);
    n = modcp_params_encode(&p, buf, sizeof buf);
    static const uint8_t want[16] = {'a', 'b'};
    assert_memory_equal(&buf[n - 3 - 64], want, 16); /* before diag_irq and the CRC */
}

static void test_job_limit(void **state)
{
    (void)state;
    /* [RTU-2003] §6.10: CP 341 job length <= 1024 B, CP 441-2 <= 450 B */
    modcp_params_t p;
    modcp_params_defaults(&p);
    assert_int_equal(modcp_params_job_limit(&p), 1024);
    p.cpu_model = MODCP_CPU_CP441;
    assert_int_equal(modcp_params_job_limit(&p), 450);
    p.job_limit = 200;
    assert_int_equal(modcp_params_job_limit(&p), 200);
    p.cpu_model = MODCP_CPU_CP341;
    assert_int_equal(modcp_params_job_limit(&p), 200);
}

static void test_start_time_minimum(void **state)
{
    (void)state;
    /* modcp-conf refuses start_time_ms <= (P - 1) x cycle_ms (tools/conf check_start_time,
     * docs/parameters.md): the FB pushes the record and INIT, P = ceil(blocks / ring depth)
     * calls, and reads INIT_ACK in the call after. Here the FB runs every 1 ms. */
    modcp_params_t p;
    params_004_9(&p);
    uint8_t buf[MODCP_PARAMS_RECORD_MAX];
    size_t n = modcp_params_encode(&p, buf, sizeof buf);
    uint32_t blocks = (uint32_t)((n + MODCP_BLOCK_SIZE - 1u) / MODCP_BLOCK_SIZE) + 1u;
    uint32_t calls = (blocks + MODCP_BP_DEPTH - 1u) / MODCP_BP_DEPTH;
    assert_int_equal(calls, 3); /* 11 blocks through 4 slots */

    p.start_time_ms = (uint16_t)(calls - 1u); /* refused by modcp-conf: always fails */
    world_t *w = world_new(&p);
    assert_false(world_start(w, 100));
    assert_true(w->fb_out.cp_start_error);
    assert_int_equal(w->fb_out.error_nr, MODCP_FB_ERR_INIT);
    assert_int_equal(w->fb_out.error_info, MODCP_EV_NONE); /* no answer yet: (00)00H */
    world_free(w);

    p.start_time_ms = (uint16_t)calls; /* the smallest value modcp-conf accepts */
    w = world_new(&p);
    assert_true(world_start(w, 100));
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_group_members_in_slot_order),
        cmocka_unit_test(test_manual_sets_are_valid),
        cmocka_unit_test(test_data_bits),
        cmocka_unit_test(test_ascii_frame_7e1_7o1_7n2_accepted),
        cmocka_unit_test(test_rtu_stop_bits_free_with_any_parity),
        cmocka_unit_test(test_ascii_7n1_refused_by_cp),
        cmocka_unit_test(test_slave_addr),
        cmocka_unit_test(test_opmode),
        cmocka_unit_test(test_rs485_normal_needs_mode_select),
        cmocka_unit_test(test_four_wire_normal_or_modem),
        cmocka_unit_test(test_rs485_normal_refused_by_cp),
        cmocka_unit_test(test_fmul_corrected),
        cmocka_unit_test(test_ascii_timeout_corrected),
        cmocka_unit_test(test_write_limits),
        cmocka_unit_test(test_coil_windows_illegal),
        cmocka_unit_test(test_coil_windows_overlap),
        cmocka_unit_test(test_input_windows),
        cmocka_unit_test(test_record_field_errors),
        cmocka_unit_test(test_rts_steps_and_receive_preset),
        cmocka_unit_test(test_scanner_errors),
        cmocka_unit_test(test_id_strings),
        cmocka_unit_test(test_r32_ranges),
        cmocka_unit_test(test_issue_rules),
        cmocka_unit_test(test_many_issues),
        cmocka_unit_test(test_record_layout),
        cmocka_unit_test(test_record_round_trip),
        cmocka_unit_test(test_record_damaged),
        cmocka_unit_test(test_record_id_strings),
        cmocka_unit_test(test_job_limit),
        cmocka_unit_test(test_start_time_minimum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
