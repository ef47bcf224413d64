/* SPDX-License-Identifier: Apache-2.0 */
/* cmocka: the C source that `modcp-conf c configs/default.ini` generates (the contract
 * of modcp/cfg_gen.h for the firmware images): record, memory with the initial values,
 * sorted DB table, work DB, cycle time. Linked with the generated cfg_default.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "modcp/cfg_gen.h"
#include "modcp/params.h"
#include "params_internal.h"

static void test_record(void **state)
{
    (void)state;
    modcp_params_t p;
    assert_int_equal(modcp_params_decode(modcp_cfg_record, modcp_cfg_record_len, &p), MODCP_EV_NONE);
    assert_int_equal(p.slave_addr, 5);
    assert_int_equal(p.baud, 9600);
    assert_int_equal(p.parity, MODCP_PARITY_EVEN);
    assert_int_equal(p.hr_base_db, 800);
    assert_int_equal(p.ir_base_db, 900);
    assert_int_equal(p.coils[0].area, MODCP_AREA_M);
    assert_int_equal(p.coils[0].to, 2047);
    assert_int_equal(p.coils[0].start, 1000);
    assert_int_equal(p.coils[2].area, MODCP_AREA_T);
    assert_int_equal(p.inputs[1].area, MODCP_AREA_I);
    assert_int_equal(p.inputs[1].start, 128);
    assert_int_equal(p.lim_db.min, 800);
    assert_int_equal(p.lim_db.max, 899);
    assert_int_equal(modcp_params_validate(&p, NULL, 0), 0);
    assert_int_equal(modcp_cfg_slave_addr, 5);
    assert_int_equal(modcp_cfg_baud, 9600);
    assert_int_equal(modcp_cfg_start_time_ms, 5000);
    assert_string_equal(modcp_cfg_name, "default.ini");
}

static void test_memory(void **state)
{
    (void)state;
    const modcp_plcmem_t *m = &modcp_cfg_mem;
    assert_int_equal(m->i_size, 256);
    assert_int_equal(m->q_size, 320);
    assert_int_equal(m->m_size, 2600);
    assert_int_equal(m->t_count, 240);
    assert_int_equal(m->c_count, 240);
    assert_memory_equal(&m->m[1008], "\x01\x17\x02\x18", 4);
    assert_int_equal(m->m[1007], 0);
    assert_int_equal(m->m[1012], 0);
    assert_memory_equal(&m->i[134], "\x12\x34\x56", 3);
    assert_int_equal(m->t[100], 0x1234);
    assert_int_equal(m->t[101], 0x5678);
    assert_int_equal(m->c[200], 0x9ABC);
    static const uint16_t numbers[] = {80, 800, 801, 802, 900, 901, 910};
    assert_int_equal(m->db_count, 7);
    for (unsigned i = 0; i < 7; i++) {
        assert_int_equal(m->dbs[i].number, numbers[i]);
    }
    assert_int_equal(m->dbs[0].size, 64);
    const modcp_db_t *db800 = modcp_plcmem_db(m, 800);
    assert_non_null(db800);
    assert_int_equal(db800->size, 1024);
    assert_memory_equal(&db800->data[160], "\x87\x65\x43\x21", 4);
    const modcp_db_t *db901 = modcp_plcmem_db(m, 901);
    assert_non_null(db901);
    assert_memory_equal(&db901->data[384], "\xA1\xA2\xA3\xA4\xA5\xA6", 6);
    assert_null(modcp_plcmem_db(m, 803));
    assert_int_equal(modcp_cfg_work_db, 80);
    assert_int_equal(modcp_cfg_cycle_ms, 10);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_record),
        cmocka_unit_test(test_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
