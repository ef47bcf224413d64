/* SPDX-License-Identifier: Apache-2.0 */
/* Interference suppression ([RTU-2003] §2.2, [RTU-2009] §5.6.1): a line error inside a
 * candidate frame drops it and counts once in FC08's bus error counter (sub 0C) as soon
 * as the candidate has its function code (2 characters); after a lone address character
 * it is an error before the frame: ignored, not counted. No event in either case. On a
 * simulated line with exact time (lineworld.h), 9600 baud 8E1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "lineworld.h"

#define CHAR_US 1146u /* 9600 baud 8E1 */

static lw_t *modem(void)
{
    modcp_params_t p;
    world_example_params(&p);
    p.opmode = MODCP_OPMODE_SUPPRESS;
    lw_t *x = lw_new(&p);
    lw_clear(x);
    return x;
}

/* The characters of hex one character time apart, then a parity error in the next
 * character's place, then silence; the bus error counter (FC08 sub 0C) and the
 * diagnostic buffer as the status area shows them. */
static modcp_cp_status_t error_after(const char *hex)
{
    lw_t *x = modem();
    uint8_t b[16];
    size_t n = hex_frame(hex, b, sizeof b);
    uint32_t t = lw_now(x);
    for (size_t k = 0; k < n; k++) {
        t += CHAR_US;
        lw_advance(x, t);
        lw_byte(x, b[k]);
    }
    lw_advance(x, t + CHAR_US);
    lw_error(x, MODCP_LINE_PARITY);
    lw_advance(x, t + 30000u);
    assert_int_equal(x->tx_calls, 0);
    modcp_cp_status_t st = lw_status(x);
    lw_free(x);
    return st;
}

static void test_modem_error_counts_once_the_function_code_is_in(void **state)
{
    (void)state;
    modcp_cp_status_t st = error_after("05");
    assert_int_equal(st.counters[MODCP_CNT_BUS_CRC], 0); /* a lone address: not yet a frame */
    st = error_after("05 03");
    assert_int_equal(st.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(st.buffer_len, 0); /* no event in modem mode */
    st = error_after("05 03 00");
    assert_int_equal(st.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(st.buffer_len, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_modem_error_counts_once_the_function_code_is_in),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
