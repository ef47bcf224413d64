/* SPDX-License-Identifier: Apache-2.0 */
/* The PDU engine on a reply buffer of a given size (modcp_pdu_request's cap: a port's
 * frame buffer decides it): a read of the indirection scanner's registers
 * (docs/extended-functions.md) whose reply (function code, byte count, data) fills the
 * buffer exactly is executed; with one byte less room it is refused before its first
 * job with exception 04, (05)17H "job too long" (docs/diagnostics.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "diag_internal.h"
#include "pdu_internal.h"
#include "world.h"

typedef struct {
    modcp_params_t p;
    modcp_areas_t areas;
    modcp_diag_t d;
    modcp_pdu_env_t env;
    modcp_pdu_t s;
    uint8_t buf[64];
    uint16_t out;
} fx_t;

static void setup_fx(fx_t *f)
{
    memset(f, 0, sizeof *f);
    world_example_params(&f->p);
    f->p.fset = MODCP_FSET_EXTENDED;
    f->p.scan_start = 0x1000;
    f->p.scan_count = 4;
    for (unsigned k = 0; k < 4u; k++) {
        f->p.scan[k] = (modcp_operand_ref_t){MODCP_AREA_M, 0, (uint16_t)(1000u + 2u * k)};
    }
    f->areas = (modcp_areas_t){.i_bytes = 256, .q_bytes = 320, .m_bytes = 2600,
                               .timers = 240, .counters = 240, .work_db = WORLD_WORK_DB};
    modcp_diag_init(&f->d);
    f->env = (modcp_pdu_env_t){&f->p, &f->areas, &f->d, true, NULL};
}

/* FC03 of 4 registers from start (reply 2 + 8 = 10 bytes) with cap bytes of room. */
static modcp_pdu_action_t read4(fx_t *f, uint16_t start, uint16_t cap)
{
    uint8_t req[5] = {0x03, (uint8_t)(start >> 8), (uint8_t)start, 0x00, 0x04};
    memcpy(f->buf, req, sizeof req);
    modcp_diag_init(&f->d);
    return modcp_pdu_request(&f->s, &f->env, 5, f->buf, sizeof req, cap, &f->out);
}

static void test_scanner_read_that_fills_the_reply_buffer(void **state)
{
    (void)state;
    const uint16_t start = 0x1000;
    fx_t f;
    setup_fx(&f);
    assert_int_equal(read4(&f, start, 10), MODCP_PDU_JOB); /* fits exactly */
    assert_int_equal(f.d.buffer_len, 0);
    assert_int_equal(read4(&f, start, 9), MODCP_PDU_REPLY); /* one byte short */
    assert_int_equal(f.out, 2);
    assert_int_equal(f.buf[0], 0x83);
    assert_int_equal(f.buf[1], 0x04);
    assert_int_equal(f.d.buffer[0], MODCP_EV_JOB_LENGTH);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scanner_read_that_fills_the_reply_buffer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
