/* SPDX-License-Identifier: Apache-2.0 */
/* FC12's send event of a request whose CPU job timed out ([MB-APP] §6.10, send event
 * byte: bit 6 = 1, bit 1 "slave abort exception" (exception 04), bit 4 "write timeout"
 * for a write that timed out): the write-timeout bit is set for each kind of write
 * job (FC06 register write, FC15 bit write by read-modify-write, FC22 mask write) and
 * not for a read (FC03), nor for a write the CPU side executed in time. The CPU side
 * stalls (the user program stops calling the FB) for longer than the CPU job timeout. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"
#include "world.h"

#define S 5

static world_t *started(void)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_EXTENDED;
    p.cpu_timeout_ms = 50;
    return ext_started(&p);
}

/* The send event of the request before the FC12 that reads the log: the log is newest
 * first, "0C n ss ss ee ee mm mm" then FC12's own receive event (80), then that one. */
static unsigned previous_send_event(world_t *w)
{
    assert_true(ext_request(w, S, "0C", 200) >= 10u);
    const char *r = ext_reply(w);
    unsigned b[12];
    int n = sscanf(r, "%x %x %x %x %x %x %x %x %x %x", &b[0], &b[1], &b[2], &b[3], &b[4], &b[5],
                   &b[6], &b[7], &b[8], &b[9]);
    assert_int_equal(n, 10);
    assert_int_equal(b[8], 0x80); /* FC12's receive event */
    return b[9];
}

/* The request with the CPU side stalled: exception 04 and ev ((0E)3BH for an FB bit
 * write, (0E)31H for the other jobs: docs/diagnostics.md); then the CPU side runs
 * again. */
static void timed_out(world_t *w, const char *pdu, modcp_event_t ev)
{
    w->fb_paused = true;
    uint8_t fc = (uint8_t)strtoul(pdu, NULL, 16);
    ext_expect_exception(w, S, pdu, 4, ev);
    assert_int_equal(strtoul(ext_reply(w), NULL, 16), fc | 0x80u);
    w->fb_paused = false;
    world_run(w, 20000);
}

static void test_timed_out_writes_log_a_write_timeout(void **state)
{
    (void)state;
    world_t *w = started();
    timed_out(w, "06 00 50 AB CD", MODCP_EV_XFER_TIMEOUT); /* FC06: a register write job */
    assert_int_equal(previous_send_event(w), 0x52);
    timed_out(w, "0F 00 08 00 03 01 05", MODCP_EV_FB_TIMEOUT); /* FC15: MB1001 bits 0..2, read-modify-write */
    assert_int_equal(previous_send_event(w), 0x52);
    timed_out(w, "16 00 50 FF 00 00 12", MODCP_EV_XFER_TIMEOUT); /* FC22: mask write of DB800.DBW160 */
    assert_int_equal(previous_send_event(w), 0x52);
    world_free(w);
}

static void test_timed_out_read_and_writes_in_time_do_not(void **state)
{
    (void)state;
    world_t *w = started();
    timed_out(w, "03 00 50 00 02", MODCP_EV_XFER_TIMEOUT); /* FC03: a read job */
    assert_int_equal(previous_send_event(w), 0x42);
    ext_expect(w, S, "06 00 50 AB CD", "06 00 50 AB CD"); /* executed in time */
    assert_int_equal(previous_send_event(w), 0x40);
    ext_expect(w, S, "0F 00 08 00 03 01 05", "0F 00 08 00 03");
    assert_int_equal(previous_send_event(w), 0x40);
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_timed_out_writes_log_a_write_timeout),
        cmocka_unit_test(test_timed_out_read_and_writes_in_time_do_not),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
