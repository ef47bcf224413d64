/* SPDX-License-Identifier: Apache-2.0 */
/* The indirection scanner at its full size: 16 entries (docs/extended-functions.md,
 * [ALTIVAR] §11: scan_count 1 ... 16); the 16th register reaches its operand, alone and
 * in a read of all 16, and is written through. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"

#define S 5

static void test_scanner_with_sixteen_entries(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.fset = MODCP_FSET_EXTENDED;
    p.scan_start = 0x1000;
    p.scan_count = MODCP_SCANNER_MAX;
    for (unsigned k = 0; k < MODCP_SCANNER_MAX; k++) {
        p.scan[k] = (modcp_operand_ref_t){MODCP_AREA_M, 0, (uint16_t)(1000u + 2u * k)};
    }
    world_t *w = ext_started(&p);
    w->m[1030] = 0x12; /* MW1030: the 16th entry's operand */
    w->m[1031] = 0x34;
    w->m[1000] = 0xAB; /* MW1000: the first's */
    w->m[1001] = 0xCD;
    ext_expect(w, S, "03 10 0F 00 01", "03 02 12 34");
    ext_expect(w, S, "03 10 00 00 10", "03 20 AB CD 00 00 00 00 00 00 00 00 00 00 00 00 00 00 "
                                       "00 00 00 00 00 00 00 00 00 00 00 00 00 00 12 34");
    ext_expect(w, S, "06 10 0F 56 78", "06 10 0F 56 78"); /* MW1030 := 5678 */
    assert_int_equal(w->m[1030], 0x56);
    assert_int_equal(w->m[1031], 0x78);
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scanner_with_sixteen_entries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
