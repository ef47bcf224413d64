/* SPDX-License-Identifier: Apache-2.0 */
/* The mapping at its edges: an area that is not one of I, Q, M, T, C or DB has size 0
 * (nothing is read beside the reported sizes); a 32-bit range filling its whole DB
 * (65536 bytes) reaches its last register. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/map.h"
#include "modcp/params.h"
#include "map_internal.h"
#include "params_internal.h"
#include "world.h"

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

/* An int32 range of 16384 registers is one whole DB: its last register is the DB's last
 * four bytes (DBD 65532), one register more is past the range. */
static void test_last_register_of_a_32bit_range_filling_its_db(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.regs32 = 1;
    p.r32[MODCP_R32_INT16] = (modcp_r32range_t){0, 9, 2};
    p.r32[MODCP_R32_INT32] = (modcp_r32range_t){100, 100 + 16383, 3};
    p.r32[MODCP_R32_FLOAT] = (modcp_r32range_t){20000, 20009, 4};
    modcp_params_t eff;
    assert_int_equal(modcp_params_apply(&p, &eff, NULL), MODCP_EV_NONE); /* a legal range */
    const modcp_areas_t a = {0};
    modcp_operand_t op;
    memset(&op, 0, sizeof op);
    assert_int_equal(modcp_map_regs(&eff, &a, 3, 100 + 16383, 1, &op), MODCP_EV_NONE);
    assert_int_equal(op.area, MODCP_AREA_DB);
    assert_int_equal(op.db, 3);
    assert_int_equal(op.offset, 0xFFFCu);
    assert_int_equal(op.count, 4);
    assert_int_equal(modcp_map_regs(&eff, &a, 3, 100 + 16383, 2, &op), MODCP_EV_PAST_END);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_area_outside_the_controller_areas_has_size_zero),
        cmocka_unit_test(test_last_register_of_a_32bit_range_filling_its_db),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
