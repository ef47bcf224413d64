/* SPDX-License-Identifier: Apache-2.0 */
/* The diagnostic counters and the CP status area at their bounds: a counter number
 * past the last counter changes nothing; the CPU side never takes a status the CP side
 * is writing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/backplane.h"
#include "modcp/diag.h"
#include "backplane_internal.h"
#include "diag_internal.h"

static void test_error_count_past_the_last_counter_changes_nothing(void **state)
{
    (void)state;
    modcp_diag_t d;
    modcp_diag_init(&d);
    modcp_diag_t before;
    memcpy(&before, &d, sizeof d);
    modcp_diag_count_error(&d, MODCP_CNT_COUNT);
    assert_memory_equal(&d, &before, sizeof d);
    assert_int_equal(d.frames_too_long, 0);
    /* the last counter itself is counted */
    modcp_diag_count_error(&d, MODCP_CNT_CHAR_OVERRUN);
    assert_int_equal(d.counters[MODCP_CNT_CHAR_OVERRUN], 1);
}

static void test_status_is_not_read_while_being_written(void **state)
{
    (void)state;
    static modcp_backplane_t bp;
    modcp_bp_init(&bp);
    modcp_cp_status_t st;
    memset(&st, 0, sizeof st);
    st.counters[0] = 7;
    modcp_bp_publish_status(&bp, &st);
    modcp_cp_status_t got;
    memset(&got, 0, sizeof got);
    assert_true(modcp_bp_read_status(&bp, &got));
    assert_int_equal(got.counters[0], 7);
    /* the CP side is between begin and end: the CPU side gets nothing */
    modcp_cp_status_t *w = modcp_bp_status_begin(&bp);
    w->counters[0] = 8;
    memset(&got, 0, sizeof got);
    assert_false(modcp_bp_read_status(&bp, &got));
    modcp_bp_status_end(&bp);
    assert_true(modcp_bp_read_status(&bp, &got));
    assert_int_equal(got.counters[0], 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_error_count_past_the_last_counter_changes_nothing),
        cmocka_unit_test(test_status_is_not_read_while_being_written),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
