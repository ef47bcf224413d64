/* SPDX-License-Identifier: Apache-2.0 */
/* The order in which the PDU engine checks a request (docs/diagnostics.md "Order of
 * checks"): address -> CRC -> CPU side initialised (docs/cpu-cp-interface.md) -> broadcast rule
 * (docs/diagnostics.md) -> function code -> length -> quantity -> values -> addresses and write
 * limits -> CPU job. Each test sends a request that fails two adjacent steps at once
 * and asserts that the earlier step answers (reply and event), and that nothing ran. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "world.h"

/* A world whose PARAMS arrived but whose FB was never started (CP_START stays low). */
static world_t *not_initialised(modcp_fset_t fset)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = (uint8_t)fset;
    world_t *w = world_new(&p);
    modcp_fb_in_t in = {false};
    for (int k = 0; k < 20; k++) {
        modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
        modcp_cp_poll(&w->cp, w->now_us);
        w->now_us += 1000;
    }
    assert_true(w->cp.configured);
    assert_false(w->cp.env.fb_ready);
    w->fb_paused = true;
    return w;
}

static world_t *started(modcp_fset_t fset)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = (uint8_t)fset;
    world_t *w = world_new(&p);
    assert_true(world_start(w, 1000));
    return w;
}

/* Send frame (address + PDU, CRC appended) and expect exception code with event ev. */
static void expect_exc(world_t *w, const uint8_t *frame, size_t len, uint8_t code,
                       modcp_event_t ev)
{
    assert_int_equal(world_request_raw(w, frame, len, 2000), 5);
    assert_int_equal(w->fake.tx[0], frame[0]);
    assert_int_equal(w->fake.tx[1], frame[1] | 0x80);
    assert_int_equal(w->fake.tx[2], code);
    assert_int_equal(world_last_event(w), ev);
}

static void expect_quiet(world_t *w, const uint8_t *frame, size_t len, modcp_event_t ev)
{
    assert_int_equal(world_request_raw(w, frame, len, 100), 0);
    assert_int_equal(world_last_event(w), ev);
}

/* 1. address before everything: a frame for another slave is not looked at, even
 * before the initialisation (no reply, no event). */
static void test_spec31_order_address_before_not_initialised(void **state)
{
    (void)state;
    world_t *w = not_initialised(MODCP_FSET_CP341);
    unsigned before = w->cp.diag.buffer_len;
    uint8_t other[] = {6, 0x07};
    assert_int_equal(world_request_raw(w, other, sizeof other, 100), 0);
    assert_int_equal(w->cp.diag.buffer_len, before);
    world_free(w);
}

/* 2. CRC before the initialisation: a damaged frame is dropped with (08)36H. */
static void test_spec31_order_crc_before_not_initialised(void **state)
{
    (void)state;
    world_t *w = not_initialised(MODCP_FSET_CP341);
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* bad CRC */
    assert_int_equal(world_last_event(w), MODCP_EV_CRC);
    world_free(w);
}

/* 3. docs/cpu-cp-interface.md: until the FB's initialisation completes *every* request gets 04 /
 * (0E)56H: an unsupported function code, a request of the wrong length, a quantity
 * out of range, an address outside every window too - in both function sets. */
static void test_spec6_not_initialised_before_function_code(void **state)
{
    (void)state;
    for (int set = 0; set < 2; set++) {
        world_t *w = not_initialised(set ? MODCP_FSET_EXTENDED : MODCP_FSET_CP341);
        uint8_t fc07[] = {5, 0x07};                   /* never supported */
        expect_exc(w, fc07, sizeof fc07, 4, MODCP_EV_FB_NOT_RUNNING);
        uint8_t fc41[] = {5, 0x41, 0x00, 0x00};       /* user-defined code */
        expect_exc(w, fc41, sizeof fc41, 4, MODCP_EV_FB_NOT_RUNNING);
        uint8_t fc17[] = {5, 0x17, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x02, 0, 0};
        expect_exc(w, fc17, sizeof fc17, 4, MODCP_EV_FB_NOT_RUNNING); /* cp341: not in it */
        world_free(w);
    }
}

static void test_spec6_not_initialised_before_length_quantity_address(void **state)
{
    (void)state;
    world_t *w = not_initialised(MODCP_FSET_CP341);
    uint8_t len[] = {5, 0x03, 0x00, 0x50, 0x00};                 /* one byte short */
    expect_exc(w, len, sizeof len, 4, MODCP_EV_FB_NOT_RUNNING);
    uint8_t qty[] = {5, 0x03, 0x00, 0x50, 0x00, 0x00};           /* quantity 0 */
    expect_exc(w, qty, sizeof qty, 4, MODCP_EV_FB_NOT_RUNNING);
    uint8_t value[] = {5, 0x05, 0x08, 0x09, 0x12, 0x34};         /* FC05 value */
    expect_exc(w, value, sizeof value, 4, MODCP_EV_FB_NOT_RUNNING);
    uint8_t addr[] = {5, 0x02, 0x14, 0x00, 0x00, 0x01};          /* no FC02 window */
    expect_exc(w, addr, sizeof addr, 4, MODCP_EV_FB_NOT_RUNNING);
    uint8_t diag[] = {5, 0x08, 0x00, 0x01, 0x00, 0x00};          /* sub 01 in cp341 */
    expect_exc(w, diag, sizeof diag, 4, MODCP_EV_FB_NOT_RUNNING);
    assert_int_equal(w->fb.jobs_done, 0);
    world_free(w);
}

/* A broadcast before the initialisation: never answered, (0E)56H recorded, counted
 * as an exception and a missing response (Serial Line V1.02 §6.1), nothing written -
 * whatever its function code. */
static void test_spec6_not_initialised_broadcast(void **state)
{
    (void)state;
    world_t *w = not_initialised(MODCP_FSET_CP341);
    uint16_t exc = w->cp.diag.counters[MODCP_CNT_EXCEPTION];
    uint8_t fc06[] = {0, 0x06, 0x01, 0x80, 0x2B, 0x1A};
    expect_quiet(w, fc06, sizeof fc06, MODCP_EV_FB_NOT_RUNNING);
    uint8_t fc03[] = {0, 0x03, 0x00, 0x50, 0x00, 0x02};
    expect_quiet(w, fc03, sizeof fc03, MODCP_EV_FB_NOT_RUNNING);
    assert_int_equal(w->cp.diag.counters[MODCP_CNT_EXCEPTION], exc + 2);
    assert_int_equal(world_db(w, 800)[768], 0x00);
    world_free(w);
}

/* 4. docs/diagnostics.md: the broadcast rule before the function code: a broadcast of an
 * unsupported or non-broadcast code is dropped with (08)30H, not (08)31H. */
static void test_spec52_order_broadcast_before_function_code(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint8_t fc41[] = {0, 0x41, 0x00};
    expect_quiet(w, fc41, sizeof fc41, MODCP_EV_BCAST_FC);
    uint8_t fc03[] = {0, 0x03, 0x00, 0x50};
    expect_quiet(w, fc03, sizeof fc03, MODCP_EV_BCAST_FC); /* and before the length */
    world_free(w);
}

/* 5. Application Protocol §6 / [RTU-2003] ch. 7: function code before the length: an
 * unsupported code answers 01 / (08)31H whatever follows it. In cp341 the extended
 * codes are unsupported too. */
static void test_mbap6_order_function_code_before_length(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint8_t fc07[] = {5, 0x07, 0x01, 0x02, 0x03};
    expect_exc(w, fc07, sizeof fc07, 1, MODCP_EV_ILLEGAL_FC);
    uint8_t fc16[] = {5, 0x16, 0x00};
    expect_exc(w, fc16, sizeof fc16, 1, MODCP_EV_ILLEGAL_FC);
    world_free(w);
}

/* 6. length before quantity: FC03 one byte long with quantity 0 -> (08)33H. */
static void test_mbap6_order_length_before_quantity(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint8_t fc03[] = {5, 0x03, 0x00, 0x50, 0x00, 0x00, 0x00};
    expect_exc(w, fc03, sizeof fc03, 3, MODCP_EV_BYTE_COUNT);
    uint8_t fc15[] = {5, 0x0F, 0x00, 0x00, 0x00};
    expect_exc(w, fc15, sizeof fc15, 3, MODCP_EV_BYTE_COUNT);
    world_free(w);
}

/* 7. quantity before byte count and address: quantity 0 at an address outside every
 * window -> (08)32H, not (08)33H or (0E)51H. */
static void test_mbap6_order_quantity_before_address(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint8_t fc02[] = {5, 0x02, 0x14, 0x00, 0x00, 0x00};
    expect_exc(w, fc02, sizeof fc02, 3, MODCP_EV_QUANTITY);
    uint8_t fc16[] = {5, 0x10, 0x00, 0x00, 0x00, 0x80, 0x02, 0x00, 0x00};
    expect_exc(w, fc16, sizeof fc16, 3, MODCP_EV_QUANTITY); /* 128 > 127 */
    world_free(w);
}

/* 8. values before addresses: FC05 with value 1234 on an address outside every window
 * -> (08)34H; FC15 byte count before the window -> (08)33H. */
static void test_mbap6_order_value_before_address(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint8_t fc05[] = {5, 0x05, 0x20, 0x00, 0x12, 0x34};
    expect_exc(w, fc05, sizeof fc05, 3, MODCP_EV_COIL_VALUE);
    uint8_t fc15[] = {5, 0x0F, 0x20, 0x00, 0x00, 0x08, 0x02, 0x00, 0x00};
    expect_exc(w, fc15, sizeof fc15, 3, MODCP_EV_BYTE_COUNT);
    world_free(w);
}

/* 9. addresses and write limits before the CPU job: refused by the CP, no job runs;
 * what only the CPU side can tell (a missing DB) comes last, with 04. */
static void test_mbap6_order_address_before_cpu_job(void **state)
{
    (void)state;
    world_t *w = started(MODCP_FSET_CP341);
    uint32_t jobs = w->fb.jobs_done;
    uint8_t denied[] = {5, 0x06, 0xC8, 0x00, 0x12, 0x34}; /* DB 900: outside 800..899 */
    expect_exc(w, denied, sizeof denied, 2, MODCP_EV_WRITE_DENIED);
    uint8_t cross[] = {5, 0x03, 0x01, 0xFF, 0x00, 0x02};  /* crosses into DB 801 */
    expect_exc(w, cross, sizeof cross, 2, MODCP_EV_DB_ACCESS);
    assert_int_equal(w->fb.jobs_done, jobs);
    uint8_t missing[] = {5, 0x03, 0x06, 0x00, 0x00, 0x01}; /* DB 803 does not exist */
    expect_exc(w, missing, sizeof missing, 4, MODCP_EV_DB_ACCESS);
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spec31_order_address_before_not_initialised),
        cmocka_unit_test(test_spec31_order_crc_before_not_initialised),
        cmocka_unit_test(test_spec6_not_initialised_before_function_code),
        cmocka_unit_test(test_spec6_not_initialised_before_length_quantity_address),
        cmocka_unit_test(test_spec6_not_initialised_broadcast),
        cmocka_unit_test(test_spec52_order_broadcast_before_function_code),
        cmocka_unit_test(test_mbap6_order_function_code_before_length),
        cmocka_unit_test(test_mbap6_order_length_before_quantity),
        cmocka_unit_test(test_mbap6_order_quantity_before_address),
        cmocka_unit_test(test_mbap6_order_value_before_address),
        cmocka_unit_test(test_mbap6_order_address_before_cpu_job),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
