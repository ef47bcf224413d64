/* SPDX-License-Identifier: Apache-2.0 */
/* FC17 (Report Slave ID) at the edges of its input: the objects it reports (vendor,
 * product, revision; never the application name of FC43's object 06) and the smallest
 * reply buffer it still answers in. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ext_support.h"
#include "modcp/diag.h"
#include "pdu_internal.h"

#define S 5 /* slave address of the example set */

static void test_fc17_reports_no_application_name(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    strcpy(p.vendor, "ACME");
    strcpy(p.product, "");
    strcpy(p.revision, "V2");
    strcpy(p.app_name, "MACHINE 4"); /* FC43 object 06 only */
    world_t *w = ext_started(&p);
    ext_expect(w, S, "11", "11 09 05 FF 41 43 4D 45 20 56 32"); /* "ACME V2" */
    world_free(w);
}

/* A buffer of 4 bytes holds the header (fc, byte count, slave id, run indicator): the
 * reply is that header with no strings, byte count 2. */
static void test_fc17_header_only_reply_in_four_bytes(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    strcpy(p.vendor, "ACME");
    modcp_diag_t d;
    memset(&d, 0, sizeof d);
    modcp_pdu_env_t env = {.p = &p, .diag = &d, .fb_ready = true};
    modcp_pdu_t s;
    memset(&s, 0, sizeof s);
    uint8_t pdu[8] = {0x11, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA};
    uint16_t out = 0;
    assert_int_equal(modcp_pdu_fc17(&s, &env, pdu, 1, 4, &out), MODCP_PDU_REPLY);
    assert_int_equal(out, 4);
    assert_int_equal(pdu[1], 2);
    assert_int_equal(pdu[2], p.slave_addr);
    assert_int_equal(pdu[4], 0xAA); /* nothing written past the buffer */
    /* three bytes: no room for the header, a device failure */
    assert_int_equal(modcp_pdu_fc17(&s, &env, pdu, 1, 3, &out), MODCP_PDU_FAIL);
    assert_int_equal(s.err, MODCP_EV_JOB_LENGTH);
    assert_int_equal(s.x.exc, MODCP_EXC_DEVICE_FAILURE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fc17_reports_no_application_name),
        cmocka_unit_test(test_fc17_header_only_reply_in_four_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
