/* SPDX-License-Identifier: Apache-2.0 */
/* The FB at the edges of the controller memory and of its initialisation, through the
 * whole CP + FB world (support/world.c, the [RTU-2003] §9 parameter set):
 *  - a bit write may end in the last byte of an area: the FB's area check counts the
 *    bytes the bits touch, no more ([RTU-2003] §7.6: ERROR_NR 14..17 only for an operand
 *    beyond the area's end);
 *  - after CP_START_ERROR the FB transfers nothing until the next rising edge of
 *    CP_START ([RTU-2003] §5.5: "CP_START is reset and CP_START_ERROR = 1"; the caller's next
 *    edge retries), so a CP that comes up late does not assemble the record the failed
 *    start left half sent. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "world.h"

/* A request given without its CRC; returns the reply without its CRC ("" if none). */
static const char *ask(world_t *w, const char *hex)
{
    uint8_t f[300];
    size_t n = hex_frame(hex, f, sizeof f);
    static char r[2000];
    r[0] = 0;
    if (world_request_raw(w, f, n, 200) >= 2u) {
        snprintf(r, sizeof r, "%s", world_reply_hex(w));
        r[strlen(r) - 6] = 0; /* " CC CC" */
    }
    return r;
}

/* Coils 2048..2559 are QB256..QB319 and Q has 320 bytes: the window's last byte is the
 * area's last byte. */
static void test_bit_writes_end_in_the_last_byte_of_q(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 500));
    /* FC15: the 8 coils 2552..2559 = QB319 bit 0..7 */
    assert_string_equal(ask(w, "05 0F 09 F8 00 08 01 A5"), "05 0F 09 F8 00 08");
    assert_int_equal(w->q[319], 0xA5);
    assert_int_equal(w->fb_out.error_nr, 0);
    /* FC05: coil 2559 = Q319.7 alone */
    assert_string_equal(ask(w, "05 05 09 FF 00 00"), "05 05 09 FF 00 00");
    assert_int_equal(w->q[319], 0x25);
    /* FC15: 3 coils from 2557 = Q319.5 .. Q319.7 (bit + count - 1 = 7) */
    assert_string_equal(ask(w, "05 0F 09 FD 00 03 01 07"), "05 0F 09 FD 00 03");
    assert_int_equal(w->q[319], 0xE5);
    assert_int_equal(w->fb_out.error_nr, 0);
    world_free(w);
}

/* One FB call and no CP poll (the CP is not running yet). */
static void fb_only(world_t *w, bool cp_start)
{
    modcp_fb_in_t in = {cp_start};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    w->now_us += 1000;
}

static void test_nothing_is_sent_after_cp_start_error(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
    p.start_time_ms = 300;
    world_t *w = world_new(&p);
    /* the CP does not run during START_TIME: the record (longer than the ring) stays
     * half sent, INIT is never sent, CP_START_ERROR with ERROR_NR 2 */
    for (unsigned ms = 0; ms < 400u && !w->fb_out.cp_start_error; ms++) {
        fb_only(w, true);
    }
    assert_true(w->fb_out.cp_start_error);
    assert_false(w->fb_out.cp_start_ok);
    assert_int_equal(w->fb_out.error_nr, MODCP_FB_ERR_INIT);
    /* the CP comes up, the user program keeps CP_START low: the FB sends nothing, so
     * the CP never holds a whole record and stays unconfigured */
    for (unsigned ms = 0; ms < 200u; ms++) {
        fb_only(w, false);
        modcp_cp_poll(&w->cp, w->now_us);
    }
    modcp_cp_status_t st;
    assert_true(modcp_bp_read_status(&w->bp, &st));
    assert_int_equal(st.flags & (MODCP_CPST_CONFIGURED | MODCP_CPST_READY), 0);
    assert_false(modcp_cp_ready(&w->cp));
    assert_true(w->fb_out.cp_start_error);
    /* the next rising edge starts the CP from the record's beginning */
    assert_true(world_start(w, 500));
    assert_true(modcp_cp_ready(&w->cp));
    assert_string_equal(ask(w, "05 03 00 00 00 01"), "05 03 02 00 00");
    world_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bit_writes_end_in_the_last_byte_of_q),
        cmocka_unit_test(test_nothing_is_sent_after_cp_start_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
