/* SPDX-License-Identifier: Apache-2.0 */
/* The link on a frame buffer too small for its framing (a port's choice: modcp_link_init
 * takes the buffer and its size). ASCII runs only when the buffer holds the shortest
 * reply it must be able to send, the exception reply ":AAFFEELL" CR LF of 11 characters
 * ([ASCII-32] §8.1: address, function, exception code, LRC as hex pairs between ':' and
 * CR LF), and a request's address, function and LRC (3 bytes); with less the link stays
 * off and ignores the line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal_log.h"
#include "link_internal.h"
#include "modcp/diag.h"
#include "modcp/link.h"
#include "world.h"

/* Timer arms (not disarms) among the recorded HAL calls. */
static size_t arms(const fake_hal_log_t *f)
{
    size_t n = 0;
    for (size_t k = 0; k < f->n; k++) {
        n += f->log[k].kind == FHL_ARM && f->log[k].value != 0u;
    }
    return n;
}

/* An ASCII link on a buffer of `size` bytes receives an FC08 echo request; true when
 * the frame was received and handed over (address 5, the PDU's 5 bytes). */
static bool ascii_link_receives(uint16_t size, size_t *arm_count, uint32_t *events)
{
    static fake_hal_log_t f;
    static modcp_diag_t d;
    modcp_hal_t hal;
    modcp_link_t l;
    uint8_t buf[64];
    memset(&d, 0, sizeof d);
    fake_hal_log_init(&f, &hal, false);
    modcp_link_init(&l, &hal, &d, buf, size);
    modcp_params_t p;
    world_example_params(&p);
    p.framing = MODCP_FRAMING_ASCII;
    p.data_bits = 7;
    p.parity = MODCP_PARITY_EVEN;
    modcp_link_configure(&l, &p);
    fake_hal_log_clear(&f);
    uint32_t t = 1000;
    for (const char *c = ":05080000A5C38B\r\n"; *c; c++) {
        f.now = t;
        modcp_link_on_byte(&l, (uint8_t)*c, t);
        t += 1000;
    }
    modcp_frame_t fr;
    memset(&fr, 0, sizeof fr);
    bool got = modcp_link_on_timer(&l, t + 1000u, &fr);
    *arm_count = arms(&f);
    *events = d.events_total;
    return got && fr.addr == 5u && fr.pdu_len == 5u && memcmp(fr.pdu, "\x08\x00\x00\xA5\xC3", 5) == 0;
}

static void test_ascii_needs_room_for_the_shortest_reply(void **state)
{
    (void)state;
    size_t n;
    uint32_t ev;
    /* 11 bytes: the exception reply fits, the link runs */
    assert_true(ascii_link_receives(11, &n, &ev));
    assert_true(n >= 1u); /* the ':' armed the character delay time */
    assert_int_equal(ev, 0);
    /* 10 bytes (room for the request's 3 bytes, not for the reply): off, the line is
     * ignored: no timer, no event, no frame */
    assert_false(ascii_link_receives(10, &n, &ev));
    assert_int_equal(n, 0);
    assert_int_equal(ev, 0);
    /* 2 bytes: off */
    assert_false(ascii_link_receives(2, &n, &ev));
    assert_int_equal(n, 0);
    assert_int_equal(ev, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ascii_needs_room_for_the_shortest_reply),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
