/* SPDX-License-Identifier: Apache-2.0 */
/* The controller area sizes at the edge of the area numbers: an area that is not one
 * of I, Q, M, T, C or DB has size 0 (nothing is read beside the reported sizes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/map.h"
#include "modcp/params.h"
#include "map_internal.h"

static void test_area_outside_the_controller_areas_has_size_zero(void **state)
{
    (void)state;
    struct {
        uint16_t before;
        modcp_areas_t a;
        uint16_t after;
    } s = {0xAAAAu, {.i_bytes = 128, .q_bytes = 64, .m_bytes = 2048, .timers = 256,
                     .counters = 200, .work_db = 80}, 0xBBBBu};
    assert_int_equal(modcp_map_area_size(&s.a, MODCP_AREA_NONE), 0);
    assert_int_equal(modcp_map_area_size(&s.a, MODCP_AREA_DB + 1u), 0);
    /* the areas themselves, and a DB (64 KiB) */
    assert_int_equal(modcp_map_area_size(&s.a, MODCP_AREA_I), 128);
    assert_int_equal(modcp_map_area_size(&s.a, MODCP_AREA_C), 200);
    assert_int_equal(modcp_map_area_size(&s.a, MODCP_AREA_DB), 0x10000u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_area_outside_the_controller_areas_has_size_zero),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
