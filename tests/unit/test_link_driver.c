/* SPDX-License-Identifier: Apache-2.0 */
/* The RS485 driver (DE) around configuration: configuring the link leaves the driver
 * off — the CP listens — and the first time it is switched on is for a reply. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "world.h"

static void test_configured_rs485_link_keeps_the_driver_off_until_a_reply(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.iface = MODCP_IFACE_RS485;
    p.rs485_sel = 1; /* mode normal allowed on two-wire RS485 ([RTU-2009] Table 5-2) */
    world_t *w = world_new(&p);
    w->fake.de = true; /* whatever the pin was before the CP took it */
    assert_true(world_start(w, 2000));
    assert_false(w->fake.de);
    assert_int_equal(w->fake.de_on_count, 0);
    const uint8_t req[] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x01};
    assert_int_equal(world_request_raw(w, req, sizeof req, 2000), 7);
    assert_int_equal(w->fake.de_on_count, 1); /* on for the reply, and only then */
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_configured_rs485_link_keeps_the_driver_off_until_a_reply),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
