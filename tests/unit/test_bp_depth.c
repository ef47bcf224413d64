/* SPDX-License-Identifier: Apache-2.0 */
/* The consistency a backplane ring depth guarantees (docs/cpu-cp-interface.md "Jobs and
 * consistency"), for the depth this core is built with: unit.test_bp_depth at
 * modcp_core's (MODCP_BP_DEPTH, default 4), unit.test_bp_depth_manual at the manual
 * core's (MODCP_MANUAL_BP_DEPTH, 2). A write job of up to MODCP_BP_DEPTH blocks, header
 * included ((MODCP_BP_DEPTH - 1) x 32 data bytes: depth 2 = 32 bytes = 16 registers or
 * 256 bits, as the manuals ask; depth 4 = 96 bytes), is executed in one FB call; a read
 * of as many data bytes is answered in one FB call; one block more spans calls. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/backplane.h"
#include "modcp/fb.h"
#include "modcp/job.h"
#include "modcp/plcmem.h"
#include "backplane_internal.h"
#include "job_internal.h"

#define RECORD_LEN 40u
#define CONSISTENT ((MODCP_BP_DEPTH - 1u) * MODCP_BLOCK_SIZE) /* data bytes */

typedef struct {
    modcp_backplane_t bp;
    uint8_t m[100 + CONSISTENT + MODCP_BLOCK_SIZE]; /* the job at 100, one block longer */
    modcp_plcmem_t mem;
    uint8_t record[RECORD_LEN];
    modcp_fb_t fb;
    modcp_fb_out_t out;
    modcp_job_t job;
    uint8_t msgbuf[64];
    uint8_t rbuf[CONSISTENT + MODCP_BLOCK_SIZE];
    uint8_t wbuf[CONSISTENT + MODCP_BLOCK_SIZE];
    modcp_bp_job_t hdr;
} fx_t;

_Static_assert(MODCP_BP_DEPTH >= 2u, "a job header and a data block");

static void fb(fx_t *f)
{
    modcp_fb_in_t in = {.cp_start = true};
    modcp_fb_call(&f->fb, &in, &f->out, 0);
}

static modcp_jobp_t poll(fx_t *f)
{
    modcp_bp_init_t init;
    modcp_jobp_t r = modcp_job_poll(&f->job, 0, &init);
#if MODCP_SHARED_PARAMS_BUFFER
    if (r == MODCP_JOBP_PARAMS_START) {
        modcp_job_params_grant(&f->job);
        r = modcp_job_poll(&f->job, 0, &init);
    }
#endif
    return r;
}

static int setup(void **state)
{
    fx_t *f = test_calloc(1, sizeof *f);
    modcp_bp_init(&f->bp);
    f->mem = (modcp_plcmem_t){.m = f->m, .m_size = sizeof f->m};
    modcp_fb_init(&f->fb, &f->bp, &f->mem, f->record, RECORD_LEN, 0, 5000);
    modcp_job_init(&f->job, &f->bp, f->msgbuf, sizeof f->msgbuf);
    modcp_job_configure(&f->job, 1024, 1000000u);
    /* PARAMS + INIT, INIT_ACK: the FB runs */
    for (int guard = 0; poll(f) != MODCP_JOBP_INIT; guard++) {
        fb(f);
        assert_true(guard < 20);
    }
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    fb(f);
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    test_free(*state);
    return 0;
}

static void start(fx_t *f, uint8_t op, uint16_t len)
{
    f->hdr = (modcp_bp_job_t){.op = op,
                              .opnd = {.area = MODCP_AREA_M, .offset = 100, .count = len},
                              .len = len};
    for (unsigned k = 0; k < len; k++) {
        f->wbuf[k] = (uint8_t)(k + 1u);
        f->m[100 + k] = (uint8_t)(0x80u + k);
    }
    assert_int_equal(modcp_job_start(&f->job, &f->hdr, f->wbuf, f->rbuf, sizeof f->rbuf, 0),
                     MODCP_EV_NONE);
}

/* Up to MODCP_BP_DEPTH blocks: all of the job in one FB call, and its reply. */
static void test_write_consistent(void **state)
{
    fx_t *f = *state;
    start(f, MODCP_JOB_WRITE, CONSISTENT);
    assert_int_equal(modcp_ring_space(&f->bp.to_cpu), 0); /* header + data: the ring */
    fb(f);
    assert_memory_equal(f->m + 100, f->wbuf, CONSISTENT);
    assert_true(f->out.cp_start_ndr);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
}

/* One block more: the first call writes what the ring held, the rest follows. */
static void test_write_longer_spans_calls(void **state)
{
    fx_t *f = *state;
    uint16_t len = (uint16_t)(CONSISTENT + 1u);
    start(f, MODCP_JOB_WRITE, len);
    fb(f);
    assert_memory_equal(f->m + 100, f->wbuf, CONSISTENT);
    assert_int_equal(f->m[100 + CONSISTENT], (uint8_t)(0x80u + CONSISTENT)); /* not yet */
    assert_false(f->out.cp_start_ndr);
    int calls = 1;
    modcp_jobp_t r;
    while ((r = poll(f)) != MODCP_JOBP_DONE) {
        assert_int_equal(r, MODCP_JOBP_NOTHING);
        fb(f);
        assert_true(++calls < 10);
    }
    assert_int_equal(calls, 2);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_memory_equal(f->m + 100, f->wbuf, len);
}

/* A read of as many data bytes: its reply (header + data blocks) in one FB call. */
static void test_read_consistent(void **state)
{
    fx_t *f = *state;
    start(f, MODCP_JOB_READ, CONSISTENT);
    fb(f);
    assert_int_equal(modcp_ring_space(&f->bp.to_cp), 0); /* the whole reply */
    f->m[100] = 0; /* changed after the call: not in the reply */
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->job.rlen, CONSISTENT);
    for (unsigned k = 0; k < CONSISTENT; k++) {
        assert_int_equal(f->rbuf[k], (uint8_t)(0x80u + k));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_write_consistent, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_longer_spans_calls, setup, teardown),
        cmocka_unit_test_setup_teardown(test_read_consistent, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
