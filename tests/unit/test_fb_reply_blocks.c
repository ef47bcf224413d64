/* SPDX-License-Identifier: Apache-2.0 */
/* The FB's reply over several backplane blocks: a read of timers or counters longer
 * than one block continues, in each block, at the element the previous one ended on
 * (T / C advance by 2-byte elements, not by bytes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"
#include "modcp/backplane.h"

#define S 5 /* slave address of the example set */

/* Coils 4096.. are timers T100.. (16 coils each, [RTU-2003] §9 example set). A read of 25
 * timers (400 coils, 50 data bytes; the CP 441 model: the CP 341 reads at most 16) is
 * sent in two data blocks after the reply's header; each timer's two bytes in it are
 * the bytes a read of that timer alone returns. */
static void test_timer_coil_read_spanning_blocks_matches_per_timer_reads(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.cpu_model = MODCP_CPU_CP441;
    world_t *w = ext_started(&p);
    enum { TIMERS = 25 };
    _Static_assert(TIMERS * 2 > MODCP_BLOCK_SIZE, "the data spans two blocks");
    for (unsigned j = 0; j < TIMERS; j++) {
        w->t[100 + j] = (uint16_t)(0x0101u * (j + 1u) ^ 0x8000u);
    }
    uint8_t single[TIMERS][2];
    for (unsigned j = 0; j < TIMERS; j++) {
        char req[40];
        snprintf(req, sizeof req, "01 %02X %02X 00 10", (4096u + 16u * j) >> 8,
                 (4096u + 16u * j) & 0xFFu);
        assert_int_equal(ext_request(w, S, req, 2000), 4); /* 01 02 lo hi */
        single[j][0] = w->fake.tx[3];
        single[j][1] = w->fake.tx[4];
    }
    uint16_t n = ext_request(w, S, "01 10 00 01 90", 2000);
    assert_int_equal(n, 2 + 2 * TIMERS);
    assert_int_equal(w->fake.tx[2], 2 * TIMERS);
    for (unsigned j = 0; j < TIMERS; j++) {
        assert_int_equal(w->fake.tx[3 + 2 * j], single[j][0]);
        assert_int_equal(w->fake.tx[4 + 2 * j], single[j][1]);
    }
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_timer_coil_read_spanning_blocks_matches_per_timer_reads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
