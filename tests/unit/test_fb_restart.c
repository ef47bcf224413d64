/* SPDX-License-Identifier: Apache-2.0 */
/* An FB restart is not a re-parameterisation (Siemens "MODBUS, RTU format, S7 is slave"
 * CP 341 / CP 441-2 driver manual §5.5: a CP_START edge makes the FB send the work area
 * and "initialisation done" to the CP; VIPA CP 341 manual §7.2: event (00)04H
 * "parameters already on the CP"). A CP_START edge, or the same record sent again,
 * keeps the diagnostic buffer, a wire break, comm-loss arming and listen-only mode and
 * the request in progress; only a changed record re-parameterises (and clears the
 * buffer, VIPA §8.3). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "frames.h"
#include "world.h"
#include "modcp/backplane.h"
#include "modcp/link.h"
#include "backplane_internal.h"

#define FC08_SUB04 "05 08 00 04 00 00" /* force listen-only (CRC appended) */

/* CP_START falls for one cycle, then rises: the FB restarts. */
static void fb_restart(world_t *w)
{
    modcp_fb_in_t in = {false};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    w->now_us += 1000;
    assert_true(world_start(w, 2000));
}

/* PARAMS blocks the FB has put towards the CP and the CP has not taken yet. */
static unsigned params_blocks_queued(world_t *w)
{
    unsigned n = 0;
    modcp_ring_t *r = &w->bp.to_cp;
    for (uint32_t t = atomic_load(&r->tail); t != atomic_load(&r->head); t++) {
        if (r->slot[t % MODCP_BP_DEPTH].kind == MODCP_BP_PARAMS) {
            n++;
        }
    }
    return n;
}

/* The diagnostic buffer, a wire break and (extended set) comm-loss arming and
 * listen-only mode survive a CP_START edge; the FB sends INIT alone (no PARAMS). */
static void test_fb_restart_keeps_diagnostics(void **state)
{
    (void)state;
    modcp_params_t p;
    world_example_params(&p);
#if MODCP_WITH_EXTENDED
    p.commloss_ms = 5000;
#endif
    world_t *w = world_new(&p);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* (08)36H */
#if MODCP_WITH_EXTENDED
    uint8_t wr[] = {0x05, 0x06, 0x00, 0x00, 0x12, 0x34};
    assert_int_equal(world_request_raw(w, wr, sizeof wr, 100), 8); /* arms comm loss */
    assert_true(w->cp.ext.cl_armed);
#endif
#if MODCP_WITH_EXTENDED
    uint8_t lo[] = {0x05, 0x08, 0x00, 0x04, 0x00, 0x00};
    assert_int_equal(world_request_raw(w, lo, sizeof lo, 20), 0); /* listen-only: silent */
    assert_true(w->cp.diag.comm.listen_only);
#endif
    modcp_cp_on_line_error(&w->cp, MODCP_LINE_BREAK, w->now_us); /* (08)0DH, wire break */
    assert_true(w->cp.cpdiag.wire_break);
    world_run(w, 10000);
    uint8_t len = w->cp.diag.buffer_len;
    assert_true(len >= 2);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_BREAK);

    /* CP_START falls for a cycle and rises: the FB sends INIT only */
    modcp_fb_in_t in = {false};
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    in.cp_start = true;
    modcp_fb_call(&w->fb, &in, &w->fb_out, w->now_us / 1000u);
    assert_int_equal(params_blocks_queued(w), 0);
    assert_true(world_start(w, 2000));

    assert_int_equal(w->cp.diag.buffer_len, len); /* nothing cleared, nothing added */
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_BREAK);
    assert_true(w->cp.cpdiag.wire_break);
#if MODCP_WITH_EXTENDED
    assert_true(w->cp.ext.cl_armed);
    assert_true(w->cp.diag.comm.listen_only);
#endif
    world_free(w);
}

/* The same record sent again (the CPU side re-sends it at a start, or an FB retry
 * does) while a request waits for its CPU job: the request is kept and answered, the
 * buffer kept. With MODCP_SHARED_PARAMS_BUFFER the record needs the frame buffer: the
 * request is dropped there, the rest kept. */
static void test_same_record_keeps_request_in_progress(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* (08)36H */
    w->fb_paused = true;
    unsigned sent = w->fake.tx_count;
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9E", 5), 0);
    assert_true(w->cp.request_pending);

    /* the FB's PARAMS of a retry, pushed straight into the ring */
    modcp_fb_t *fb = &w->fb;
    for (uint16_t pos = 0; pos < w->record_len;) {
        unsigned rest = (unsigned)w->record_len - pos;
        uint16_t n = (uint16_t)(rest > MODCP_BLOCK_SIZE ? MODCP_BLOCK_SIZE : rest);
        uint8_t flags = (uint8_t)((pos == 0 ? MODCP_BLK_FIRST : 0) |
                                  (pos + n == w->record_len ? MODCP_BLK_LAST : 0));
        if (modcp_ring_put_data(&w->bp.to_cp, &fb->tx_seq, MODCP_BP_PARAMS, flags, 0,
                                w->record + pos, (uint8_t)n)) {
            pos = (uint16_t)(pos + n);
        }
        w->now_us += 100;
        modcp_cp_poll(&w->cp, w->now_us);
    }
    modcp_cp_poll(&w->cp, w->now_us);
    assert_true(w->cp.configured);
    assert_true(modcp_cp_ready(&w->cp));
    assert_int_equal(w->cp.diag.buffer_len, 2); /* kept, and (00)04H on top */
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_PARAMS_SAME);
    assert_int_equal(w->cp.diag.buffer[0], 0x0004);
    assert_int_equal(w->cp.diag.buffer[1], MODCP_EV_CRC);
#if MODCP_SHARED_PARAMS_BUFFER
    assert_false(w->cp.request_pending);
    (void)sent;
#else
    assert_true(w->cp.request_pending); /* still waiting for its job */
    w->fb_paused = false;
    for (int ms = 0; ms < 20 && w->fake.tx_count == sent; ms++) {
        world_run(w, 1000);
    }
    assert_int_equal(w->fake.tx_count, sent + 1);
    assert_int_equal(w->fake.tx[1], 0x03); /* the FC03 reply, not an exception */
    assert_int_equal(w->fake.tx[2], 4);
#endif
    world_free(w);
}

/* A changed record re-parameterises: the FB's INIT carries the new record's identity,
 * the CP answers "not my record" ((0E)2EH's record event), the FB's retry sends PARAMS
 * + INIT, the CP takes them and the diagnostic buffer is cleared (VIPA §8.3). */
static void test_changed_record_reparameterises(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start(w, 2000));
    assert_int_equal(world_request(w, "05 03 00 50 00 02 C5 9F", 100), 0); /* (08)36H */
    world_run(w, 100);
    assert_int_equal(w->cp.diag.buffer_len, 1);

    w->params.cpu_timeout_ms = 1500; /* any field */
    w->record_len = (uint16_t)modcp_params_encode(&w->params, w->record, sizeof w->record);
    fb_restart(w);
    assert_int_equal(w->cp.params.cpu_timeout_ms, 1500);
    assert_int_equal(w->cp.diag.buffer_len, 0);
    world_free(w);
}

/* VIPA CP 341 manual §7.2 / §8.2 class 00H: (00)03H "parameters taken over" after a good
 * parameter set, the first entry of the emptied buffer, before the record's warnings;
 * a start-up event is no error: not in SYSTAT (F clear, no event), not in the STATUS
 * word. */
static void test_start_up_events(void **state)
{
    (void)state;
    world_t *w = world_new(NULL);
    assert_true(world_start_keep(w, 2000));
    assert_int_equal(w->cp.diag.buffer_len, 1);
    assert_int_equal(w->cp.diag.buffer[0], 0x0003);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_PARAMS_TAKEN);
    assert_int_equal(w->cp.diag.status, 0);
    assert_int_equal(w->cp.diag.systat_len, 0);
    assert_int_equal(w->cp.diag.systat_flags, 0);
    world_free(w);

    modcp_params_t p;
    world_example_params(&p);
    p.f_mul = 11; /* (0E)21H: warning, runs with 1 */
    w = world_new(&p);
    assert_true(world_start_keep(w, 2000));
    assert_int_equal(w->cp.diag.buffer_len, 2);
    assert_int_equal(w->cp.diag.buffer[0], MODCP_EV_FMUL);
    assert_int_equal(w->cp.diag.buffer[1], MODCP_EV_PARAMS_TAKEN);
    world_free(w);

    /* a rejected record: no (00)03H */
    world_example_params(&p);
    p.slave_addr = 0;
    p.start_time_ms = 300;
    w = world_new(&p);
    assert_false(world_start_keep(w, 1000));
    for (unsigned i = 0; i < w->cp.diag.buffer_len; i++) {
        assert_int_equal(w->cp.diag.buffer[i], MODCP_EV_SLAVE_ADDR);
    }
    world_free(w);
}

/* The record identity the INIT carries: the CRC of the record without its own CRC (the
 * whole record's CRC would be 0 for every record). */
static void test_record_identity(void **state)
{
    (void)state;
    modcp_params_t p;
    modcp_params_defaults(&p);
    uint8_t a[MODCP_PARAMS_RECORD_MAX], b[MODCP_PARAMS_RECORD_MAX];
    uint16_t na = (uint16_t)modcp_params_encode(&p, a, sizeof a);
    p.slave_addr = 9;
    uint16_t nb = (uint16_t)modcp_params_encode(&p, b, sizeof b);
    assert_int_equal(na, nb);
    assert_int_equal(modcp_bp_record_id(a, na), a[na - 2] | a[na - 1] << 8);
    assert_int_not_equal(modcp_bp_record_id(a, na), modcp_bp_record_id(b, nb));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fb_restart_keeps_diagnostics),
        cmocka_unit_test(test_same_record_keeps_request_in_progress),
        cmocka_unit_test(test_changed_record_reparameterises),
        cmocka_unit_test(test_record_identity),
        cmocka_unit_test(test_start_up_events),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
