/* SPDX-License-Identifier: Apache-2.0 */
/* Every function code the CP does not implement is answered with exception 01, illegal
 * function, and event (08)31H ([MB-APP] §7: "the function code received in the query is
 * not an allowable action for the server"; docs/extended-functions.md "Order of checks"
 * step 4), in the extended set and in the cp341 set, whatever follows the code.
 * The codes between the implemented ones and right after them (FC24 after FC23, the
 * rows the function-code table keeps past FC23 for FC43 and the extended FC08; FC17
 * right after the manual core's last row, FC16) are the ones a table lookup can get
 * wrong. Built twice: against the whole core (unit.test_pdu_unsupported) and against
 * the manual core (modcp_core_manual, MODCP_TEST_MANUAL: the cp341 set only,
 * unit.test_pdu_unsupported_manual). */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "world.h"

#ifndef MODCP_TEST_MANUAL
#define MODCP_TEST_MANUAL 0
#endif

static bool implemented(uint8_t fc, bool extended)
{
    static const uint8_t cp341[] = {1, 2, 3, 4, 5, 6, 8, 15, 16};
    static const uint8_t ext[] = {11, 12, 17, 22, 23, 43};
    for (size_t k = 0; k < sizeof cp341; k++) {
        if (fc == cp341[k]) {
            return true;
        }
    }
    for (size_t k = 0; extended && k < sizeof ext; k++) {
        if (fc == ext[k]) {
            return true;
        }
    }
    return false;
}

static void every_other_code_is_illegal(uint8_t fset)
{
    modcp_params_t p;
    world_example_params(&p);
    p.fset = fset;
    world_t *w = world_new(&p);
    assert_true(world_start(w, 500));
    unsigned asked = 0;
    for (unsigned fc = 1; fc < 0x80u; fc++) {
        if (implemented((uint8_t)fc, fset == MODCP_FSET_EXTENDED)) {
            continue;
        }
        /* with the data of a read request (FC43's MEI type 0E too) */
        uint8_t req[6] = {5, (uint8_t)fc, 0x0E, 0x01, 0x00, 0x01};
        assert_int_equal(world_request_raw(w, req, sizeof req, 200), 5);
        char want[16];
        snprintf(want, sizeof want, "05 %02X 01", fc | 0x80u);
        if (strncmp(world_reply_hex(w), want, 8) != 0) {
            fail_msg("FC %02X: reply %s, expected %s ..", fc, world_reply_hex(w), want);
        }
        assert_int_equal(world_last_event(w), MODCP_EV_ILLEGAL_FC);
        asked++;
    }
    assert_int_equal(asked, 127u - (fset == MODCP_FSET_EXTENDED ? 15u : 9u));
    world_free(w);
}

#if !MODCP_TEST_MANUAL
static void test_unimplemented_codes_extended_set(void **state)
{
    (void)state;
    every_other_code_is_illegal(MODCP_FSET_EXTENDED);
}
#endif

static void test_unimplemented_codes_cp341_set(void **state)
{
    (void)state;
    every_other_code_is_illegal(MODCP_FSET_CP341);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
#if !MODCP_TEST_MANUAL
        cmocka_unit_test(test_unimplemented_codes_extended_set),
#endif
        cmocka_unit_test(test_unimplemented_codes_cp341_set),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
