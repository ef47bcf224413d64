/* SPDX-License-Identifier: Apache-2.0 */
/* Comm-loss supervision (docs/parameters.md, §5.3; [ALTIVAR] §7): armed by the first accepted write for
 * our address; no valid request for our address within commloss_ms -> event (0E)60H
 * once and MODCP_CPST_COMMLOSS in the backplane status area, latched until the CPU side
 * resets it (the Altivar's resettable fault SLF1); with commloss_auto_clear the next
 * valid request for our address clears it. Time is simulated: the CP is polled every
 * 1 ms. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"

#define S 5

static world_t *cl_world_mode(uint16_t ms, uint8_t auto_clear)
{
    modcp_params_t p;
    world_example_params(&p);
    p.commloss_ms = ms;
    p.commloss_auto = auto_clear;
    return ext_started(&p);
}

static world_t *cl_world(uint16_t ms)
{
    return cl_world_mode(ms, 0);
}

static bool lost(world_t *w)
{
    return (ext_status(w).flags & MODCP_CPST_COMMLOSS) != 0u;
}

static unsigned commloss_events(const world_t *w)
{
    unsigned n = 0;
    for (unsigned k = 0; k < w->cp.diag.buffer_len; k++) {
        n += w->cp.diag.buffer[k] == MODCP_EV_COMMLOSS;
    }
    return n;
}

/* Not armed before the first write: reads alone never raise it. */
static void test_not_armed_before_first_write(void **state)
{
    (void)state;
    world_t *w = cl_world(200);
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00");
    world_run(w, 1000000);
    assert_false(lost(w));
    /* a write refused with an exception does not arm it either */
    ext_expect_exception(w, S, "06 C8 00 00 01", 2, MODCP_EV_WRITE_DENIED);
    world_run(w, 1000000);
    assert_false(lost(w));
    /* nor a broadcast write */
    assert_int_equal(ext_request(w, 0, "06 01 80 2B 1A", 100), 0);
    world_run(w, 1000000);
    assert_false(lost(w));
    assert_int_equal(commloss_events(w), 0);
    world_free(w);
}

/* The exact threshold: lost when commloss_ms have passed since the last valid request
 * (the moment its reply was handed to the line); commloss_auto_clear = on: the next
 * valid request clears it. */
static void test_threshold_and_refresh(void **state)
{
    (void)state;
    world_t *w = cl_world_mode(200, 1);
    ext_expect(w, S, "06 01 80 2B 1A", "06 01 80 2B 1A"); /* arms */
    world_run(w, 150000);
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00"); /* a read restarts the time */
    world_run(w, 199000);
    assert_false(w->cp.ext.cl_lost);
    world_run(w, 1000);
    assert_true(w->cp.ext.cl_lost);
    assert_int_equal(world_last_event(w), MODCP_EV_COMMLOSS);
    modcp_cp_status_t st = ext_status(w);
    assert_true(st.flags & MODCP_CPST_COMMLOSS);
    assert_int_equal(st.buffer[0], MODCP_EV_COMMLOSS);
    world_run(w, 2000000);
    assert_int_equal(commloss_events(w), 1); /* reported once */
    /* FC08 sub 02 shows it (bit 1) in the reply; the request itself clears it */
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 02");
    assert_false(lost(w));
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 00");
    /* still armed: it comes back */
    world_run(w, 200000);
    assert_true(lost(w));
    assert_int_equal(commloss_events(w), 2);
    world_free(w);
}

/* What does not count as a valid request for our address: other slaves, broadcasts,
 * frames with CRC errors. Exceptions and listen-only requests do count. */
static void test_what_refreshes(void **state)
{
    (void)state;
    world_t *w = cl_world_mode(300, 1);
    ext_expect(w, S, "10 00 00 00 01 02 12 34", "10 00 00 00 01");
    for (int k = 0; k < 4; k++) {
        world_run(w, 80000);
        assert_int_equal(ext_request(w, 6, "03 00 50 00 01", 1), 0);
        assert_int_equal(ext_request(w, 0, "06 01 80 2B 1A", 1), 0);
        ext_bad_crc(w, S, "03 00 50 00 01");
    }
    assert_true(lost(w));
    ext_expect_exception(w, S, "03 00 50 00 00", 3, MODCP_EV_QUANTITY);
    assert_false(lost(w));
    /* listen-only: not answered, but the master is alive */
    ext_expect_silence(w, S, "08 00 04 00 00");
    unsigned events = commloss_events(w);
    for (int k = 0; k < 5; k++) {
        world_run(w, 150000); /* + 100 ms of waiting for a reply = 250 ms apart */
        ext_expect_silence(w, S, "03 00 50 00 01");
        assert_false(lost(w));
    }
    assert_int_equal(commloss_events(w), events);
    world_run(w, 300000);
    assert_true(lost(w));
    assert_true(ext_status(w).flags & MODCP_CPST_LISTEN_ONLY);
    world_free(w);
}

/* Altivar 71 integrated Modbus guide §7: the communication fault SLF1 is a resettable
 * fault. By default the loss stays latched: valid requests (which still restart the
 * time) do not clear it; the CPU side's reset (modcp_bp_commloss_reset) clears it at the
 * CP's next poll, the supervision stays armed and times from the reset. */
static void test_commloss_latched_until_reset(void **state)
{
    (void)state;
    world_t *w = cl_world(200);
    ext_expect(w, S, "06 01 80 2B 1A", "06 01 80 2B 1A"); /* arms */
    world_run(w, 200000);
    assert_true(lost(w));
    ext_expect(w, S, "03 00 50 00 01", "03 02 00 00");
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 02"); /* still shown */
    world_run(w, 100000);
    assert_true(lost(w));
    assert_int_equal(commloss_events(w), 1);
    modcp_bp_commloss_reset(&w->bp);
    world_run(w, 1000); /* the CP's next poll */
    assert_false(w->cp.ext.cl_lost);
    assert_false(lost(w));
    ext_expect(w, S, "08 00 02 00 00", "08 00 02 00 00");
    world_run(w, 199000); /* timed from the last request */
    assert_false(w->cp.ext.cl_lost);
    world_run(w, 1000);
    assert_true(lost(w)); /* armed still: it comes back */
    assert_int_equal(commloss_events(w), 2);
    modcp_bp_commloss_reset(&w->bp); /* reset again */
    world_run(w, 1000);
    assert_false(w->cp.ext.cl_lost);
    world_run(w, 199000); /* timed from the reset (no request since) */
    assert_false(w->cp.ext.cl_lost);
    world_run(w, 1000);
    assert_true(w->cp.ext.cl_lost);
    assert_int_equal(commloss_events(w), 3);
    world_free(w);
}

/* commloss_ms = 0: off, whatever the traffic. */
static void test_off(void **state)
{
    (void)state;
    world_t *w = cl_world(0);
    ext_expect(w, S, "06 01 80 2B 1A", "06 01 80 2B 1A");
    world_run(w, 40000000);
    assert_false(lost(w));
    assert_false(w->cp.ext.cl_armed);
    world_free(w);
}

/* FC22 and FC23 are writes too; the largest time (30 s). */
static void test_armed_by_fc22_fc23_long_time(void **state)
{
    (void)state;
    world_t *w = cl_world(30000);
    ext_expect(w, S, "16 00 04 00 F2 00 25", "16 00 04 00 F2 00 25");
    assert_true(w->cp.ext.cl_armed);
    world_run(w, 29999000);
    assert_false(w->cp.ext.cl_lost);
    world_run(w, 1000);
    assert_true(lost(w));
    world_free(w);

    w = cl_world(100);
    ext_expect(w, S, "17 00 00 00 01 00 01 00 01 02 00 01", "17 02 00 00");
    world_run(w, 100000);
    assert_true(lost(w));
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_not_armed_before_first_write),
        cmocka_unit_test(test_threshold_and_refresh),
        cmocka_unit_test(test_commloss_latched_until_reset),
        cmocka_unit_test(test_what_refreshes),
        cmocka_unit_test(test_off),
        cmocka_unit_test(test_armed_by_fc22_fc23_long_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
