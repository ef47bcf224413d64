/* SPDX-License-Identifier: Apache-2.0 */
/* A UART line error in a request reaches the link in every build of the core (also the
 * manual's, built without RS232 signals, whose reception is always allowed): the frame
 * is discarded unanswered, the character error counted and entered as an event; the
 * next clean request is answered. Built against modcp_core (unit.test_line_errors) and
 * modcp_core_manual (unit.test_line_errors_manual). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "modcp/hal.h"
#include "world.h"

static void test_parity_error_discards_the_request_and_is_counted(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    uint8_t f[16] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x01};
    size_t n = add_crc(f, 6);
    unsigned before = w->fake.tx_count;
    for (size_t k = 0; k < n; k++) {
        modcp_cp_on_rx(&w->cp, f[k], w->now_us);
        if (k == 2) {
            modcp_cp_on_line_error(&w->cp, MODCP_LINE_PARITY, w->now_us);
        }
        w->now_us += 10;
    }
    w->now_us += w->fake.timer_us;
    modcp_cp_on_timer(&w->cp, w->now_us);
    world_run(w, 100000);
    assert_int_equal(w->fake.tx_count, before); /* no reply */
    assert_int_equal(w->cp.diag.char_errors, 1);
    assert_int_equal(world_last_event(w), MODCP_EV_CHAR_ERROR);
    /* the same request without the error is answered */
    assert_int_equal(world_request_raw(w, f, 6, 2000), 7);
    assert_int_equal(w->fake.tx[1], 0x03);
    assert_int_equal(w->cp.diag.char_errors, 1);
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parity_error_discards_the_request_and_is_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
