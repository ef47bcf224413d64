/* SPDX-License-Identifier: Apache-2.0 */
/* The FB's job length limit (MODCP_FB_JOB_MAX, the CP 341 transfer limit) at its edge:
 * a write of exactly MODCP_FB_JOB_MAX bytes is executed, one byte more is refused with
 * an FB error and writes nothing. The CP side and the FB over one backplane, single
 * thread (as test_job_fb.c), the CP allowing longer jobs than the FB. */
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
#include "job_internal.h"

#define DB_SIZE (MODCP_FB_JOB_MAX + 64u)

typedef struct {
    modcp_backplane_t bp;
    uint8_t db[DB_SIZE];
    modcp_db_t dbs[1];
    modcp_plcmem_t mem;
    modcp_fb_t fb;
    modcp_fb_out_t out;
    modcp_job_t job;
    modcp_bp_init_t init;
    modcp_bp_job_t hdr;
    uint8_t msgbuf[64];
    uint8_t wbuf[DB_SIZE];
    uint32_t now_us;
} fx_t;

static void fb(fx_t *f)
{
    modcp_fb_in_t in = {.cp_start = true};
    modcp_fb_call(&f->fb, &in, &f->out, 0);
}

static fx_t *started(void)
{
    static fx_t fx;
    fx_t *f = &fx;
    memset(f, 0, sizeof *f);
    modcp_bp_init(&f->bp);
    f->dbs[0] = (modcp_db_t){800, sizeof f->db, f->db};
    f->mem = (modcp_plcmem_t){.dbs = f->dbs, .db_count = 1};
    modcp_fb_init(&f->fb, &f->bp, &f->mem, NULL, 0, 0, 5000);
    modcp_job_init(&f->job, &f->bp, f->msgbuf, sizeof f->msgbuf);
    f->now_us = 1000;
    fb(f);
    modcp_jobp_t r;
    for (int guard = 0; (r = modcp_job_poll(&f->job, f->now_us, &f->init)) != MODCP_JOBP_INIT;) {
        if (r == MODCP_JOBP_NOTHING) {
            fb(f);
        }
        assert_true(++guard < 20);
    }
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    fb(f);
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
    return f;
}

/* A WRITE of len bytes of 0x5A to DB800.DBB0, the CP allowing 2000; run to its end. */
static modcp_event_t write_db(fx_t *f, uint16_t len)
{
    memset(f->wbuf, 0x5A, sizeof f->wbuf);
    f->hdr = (modcp_bp_job_t){.op = MODCP_JOB_WRITE,
                              .opnd = {.area = MODCP_AREA_DB, .db = 800, .offset = 0, .count = len},
                              .len = len};
    modcp_job_configure(&f->job, 2000, 1000000u);
    assert_int_equal(modcp_job_start(&f->job, &f->hdr, f->wbuf, NULL, 0, f->now_us),
                     MODCP_EV_NONE);
    for (int calls = 0; calls < 400; calls++) {
        modcp_jobp_t r = modcp_job_poll(&f->job, f->now_us, &f->init);
        if (r == MODCP_JOBP_DONE) {
            return f->job.event;
        }
        assert_int_equal(r, MODCP_JOBP_NOTHING);
        fb(f);
    }
    fail_msg("job did not finish");
    return MODCP_EV_NONE;
}

static void test_fb_refuses_a_job_one_byte_over_its_limit(void **state)
{
    (void)state;
    fx_t *f = started();
    assert_int_equal(write_db(f, MODCP_FB_JOB_MAX + 1u), MODCP_EV_FB_ERROR);
    for (unsigned k = 0; k < DB_SIZE; k++) {
        assert_int_equal(f->db[k], 0x00); /* nothing written */
    }
    /* the limit itself is executed */
    assert_int_equal(write_db(f, MODCP_FB_JOB_MAX), MODCP_EV_NONE);
    assert_int_equal(f->db[0], 0x5A);
    assert_int_equal(f->db[MODCP_FB_JOB_MAX - 1u], 0x5A);
    assert_int_equal(f->db[MODCP_FB_JOB_MAX], 0x00);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fb_refuses_a_job_one_byte_over_its_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
