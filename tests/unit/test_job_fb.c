/* SPDX-License-Identifier: Apache-2.0 */
/* The CP-side job module and the CPU-side FB together over one backplane, single
 * thread: the test alternates modcp_job_poll() (the CP task) and modcp_fb_call() (the
 * CPU cycle). [RTU-2003] §4.2 init handshake, §4.4 / §4.5 job limits and 32-byte blocks,
 * §4.6 generic handshake, §6.5 / §6.8 / §6.9 examples, §7.5 events, §7.6 ERROR_NR. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/backplane.h"
#include "modcp/crc.h"
#include "modcp/fb.h"
#include "modcp/job.h"
#include "modcp/plcmem.h"
#include "backplane_internal.h"
#include "job_internal.h"

#define WORK_DB 80
#define RECORD_LEN 150 /* 5 PARAMS blocks: 4 x 32 + 22 */
#define START_TIME_MS 5000u
#define TIMEOUT_US 1000000u

typedef struct {
    modcp_backplane_t bp;
    uint8_t i[128], q[512], m[2048];
    uint16_t t[256], c[256];
    uint8_t db80[64], db800[1024], db900[64];
    modcp_db_t dbs[3];
    modcp_plcmem_t mem;
    uint8_t record[RECORD_LEN];
    modcp_fb_t fb;
    modcp_fb_out_t out;
    modcp_job_t job;
    modcp_bp_init_t init; /* the last INIT's payload (modcp_job_poll) */
    modcp_bp_job_t hdr;   /* the running job's header (start) */
    uint8_t msgbuf[400];
    uint8_t rbuf[1200];
    uint8_t wbuf[1200];
    uint32_t now_us; /* CP clock */
    uint32_t now_ms; /* CPU clock */
    unsigned ndr_calls;
} fx_t;

static void fx_fb_init(fx_t *f, uint16_t work_db)
{
    modcp_fb_init(&f->fb, &f->bp, &f->mem, f->record, RECORD_LEN, work_db, START_TIME_MS);
}

static int setup(void **state)
{
    fx_t *f = test_calloc(1, sizeof *f);
    modcp_bp_init(&f->bp);
    f->dbs[0] = (modcp_db_t){WORK_DB, sizeof f->db80, f->db80};
    f->dbs[1] = (modcp_db_t){800, sizeof f->db800, f->db800};
    f->dbs[2] = (modcp_db_t){900, sizeof f->db900, f->db900};
    f->mem = (modcp_plcmem_t){.i = f->i, .q = f->q, .m = f->m, .t = f->t, .c = f->c,
                              .i_size = sizeof f->i, .q_size = sizeof f->q, .m_size = sizeof f->m,
                              .t_count = 256, .c_count = 200, .dbs = f->dbs, .db_count = 3};
    for (unsigned k = 0; k < RECORD_LEN; k++) {
        f->record[k] = (uint8_t)(k * 13u + 1u);
    }
    fx_fb_init(f, WORK_DB);
    modcp_job_init(&f->job, &f->bp, f->msgbuf, sizeof f->msgbuf);
    f->now_us = 1000;
    f->now_ms = 0;
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    test_free(*state);
    return 0;
}

/* One CPU cycle with CP_START = start. */
static void fb(fx_t *f, bool start)
{
    modcp_fb_in_t in = {.cp_start = start};
    modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
    if (f->out.cp_start_ndr) {
        f->ndr_calls++;
    }
}

static modcp_jobp_t poll(fx_t *f)
{
    return modcp_job_poll(&f->job, f->now_us, &f->init);
}

/* Init handshake, the happy path (used by every job test). */
static void init_ok(fx_t *f)
{
    fb(f, true);
    modcp_jobp_t r;
    int guard = 0;
    while ((r = poll(f)) != MODCP_JOBP_INIT) {
        if (r == MODCP_JOBP_NOTHING) {
            fb(f, true);
        }
        assert_true(++guard < 20);
    }
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    fb(f, true);
    assert_true(f->out.cp_start_ok);
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
}

/* Alternate CP poll and FB call until the job is done; returns the number of FB calls. */
static int run_job(fx_t *f)
{
    for (int calls = 0; calls < 200; calls++) {
        modcp_jobp_t r = poll(f);
        if (r == MODCP_JOBP_DONE) {
            assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
            return calls;
        }
        assert_int_equal(r, MODCP_JOBP_NOTHING);
        fb(f, true);
    }
    fail_msg("job did not finish");
    return -1;
}

static modcp_event_t start(fx_t *f, uint8_t op, uint8_t area, uint16_t db, uint16_t offset,
                           uint8_t bit, uint16_t count, uint16_t len, uint16_t limit)
{
    /* the job keeps a pointer to its header: f->hdr, unless a job runs (refused then) */
    modcp_bp_job_t busy_hdr;
    modcp_bp_job_t *h = modcp_job_busy(&f->job) ? &busy_hdr : &f->hdr;
    *h = (modcp_bp_job_t){.op = op,
                          .opnd = {.area = area, .bit = bit, .db = db, .offset = offset, .count = count},
                          .len = len};
    modcp_job_configure(&f->job, limit, TIMEOUT_US);
    return modcp_job_start(&f->job, h, f->wbuf, f->rbuf, sizeof f->rbuf, f->now_us);
}

/* ---- initialisation ([RTU-2003] §4.2) ------------------------------------------------------ */

/* The FB hands the CP its parameters at the first call, before any CP_START. */
static void test_params_at_first_call(void **state)
{
    fx_t *f = *state;
    fb(f, false);
    int guard = 0;
    modcp_jobp_t r;
    while ((r = poll(f)) == MODCP_JOBP_NOTHING) {
        fb(f, false);
        assert_true(++guard < 10);
    }
    assert_int_equal(r, MODCP_JOBP_PARAMS);
    assert_int_equal(f->job.msglen, RECORD_LEN);
    assert_memory_equal(f->msgbuf, f->record, RECORD_LEN);
    /* no INIT without CP_START, and nothing more is sent */
    for (int k = 0; k < 5; k++) {
        f->now_ms += 100;
        fb(f, false);
        assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    }
    assert_int_equal(atomic_load(&f->bp.to_cp.head), 5);
    assert_false(f->out.cp_start_ok);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->fb.state, MODCP_FBST_STOPPED);
}

static void test_init_happy_path(void **state)
{
    fx_t *f = *state;
    fb(f, true); /* rising edge at the first call: PARAMS once, then INIT */
    assert_false(f->out.cp_start_ok);
    assert_int_equal(atomic_load(&f->bp.to_cp.head), MODCP_BP_DEPTH); /* 4 PARAMS blocks */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);                    /* 4 of 5 in */
    f->now_ms = 1;
    fb(f, true); /* 5th PARAMS block + INIT */
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_int_equal(f->job.msglen, RECORD_LEN);
    assert_memory_equal(f->msgbuf, f->record, RECORD_LEN);
    assert_int_equal(poll(f), MODCP_JOBP_INIT);
    assert_int_equal(f->init.areas.i_bytes, 128);
    assert_int_equal(f->init.areas.q_bytes, 512);
    assert_int_equal(f->init.areas.m_bytes, 2048);
    assert_int_equal(f->init.areas.timers, 256);
    assert_int_equal(f->init.areas.counters, 200);
    assert_int_equal(f->init.areas.work_db, WORK_DB);
    assert_int_equal(f->init.record_crc, modcp_crc16(f->record, RECORD_LEN - 2u)); /* record id */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(f->job.proto_errors, 0);

    f->now_ms = 2;
    fb(f, true);
    assert_false(f->out.cp_start_ok); /* no answer yet */
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    f->now_ms = 3;
    fb(f, true);
    assert_true(f->out.cp_start_ok);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
    /* nothing is re-sent once running */
    f->now_ms = 1000;
    fb(f, true);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(atomic_load(&f->bp.to_cp.head), 6);
}

/* The CP answers "not ready" (it was still testing itself); the FB repeats PARAMS +
 * INIT every MODCP_FB_RETRY_MS until START_TIME ([RTU-2003] §4.2 step 6). */
static void test_init_retry_then_success(void **state)
{
    fx_t *f = *state;
    fb(f, true);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true);
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_int_equal(poll(f), MODCP_JOBP_INIT);
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_PARAM_RECORD));
    uint32_t head = atomic_load(&f->bp.to_cp.head);
    for (f->now_ms = 1; f->now_ms < MODCP_FB_RETRY_MS; f->now_ms++) {
        fb(f, true);
        assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    }
    assert_int_equal(atomic_load(&f->bp.to_cp.head), head); /* no retry before 200 ms */
    assert_int_equal(f->fb.init_event, MODCP_EV_PARAM_RECORD);
    assert_false(f->out.cp_start_ok);
    assert_false(f->out.cp_start_error);

    fb(f, true); /* t = 200 ms: second attempt */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true);
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_memory_equal(f->msgbuf, f->record, RECORD_LEN);
    assert_int_equal(poll(f), MODCP_JOBP_INIT);
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    f->now_ms++;
    fb(f, true);
    assert_true(f->out.cp_start_ok);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->job.proto_errors, 0);
}

/* CP silent: CP_START_ERROR with ERROR_NR 2 exactly at START_TIME, not 1 ms before
 * ([RTU-2003] §7.6 10.1.1). ERROR_INFO 0: the CP never reported an event. */
static void test_init_timeout_cp_silent(void **state)
{
    fx_t *f = *state;
    f->now_ms = 0xFFFFF000u; /* the edge shortly before the clock wraps */
    uint32_t t0 = f->now_ms;
    for (; f->now_ms != t0 + START_TIME_MS - 1u; f->now_ms++) {
        fb(f, true);
        assert_false(f->out.cp_start_error);
        assert_false(f->out.cp_start_ok);
    }
    fb(f, true); /* START_TIME - 1 */
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    f->now_ms++;
    fb(f, true); /* START_TIME */
    assert_true(f->out.cp_start_error);
    assert_false(f->out.cp_start_ok);
    assert_int_equal(f->out.error_nr, 2);
    assert_int_equal(f->out.error_info, 0);
    assert_int_equal(f->fb.state, MODCP_FBST_FAILED);
    /* outputs stay; a job now is answered (0E)56H ([RTU-2003] §4.2 step 7) */
    f->now_ms += 1000;
    fb(f, true);
    assert_true(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 2);
}

/* CP consumes but keeps answering "not ready": retries every 200 ms, then error 2 with
 * ERROR_INFO = the CP's event; a new CP_START edge clears the outputs and succeeds. */
static void test_init_nak_until_timeout(void **state)
{
    fx_t *f = *state;
    unsigned inits = 0;
    for (f->now_ms = 0; f->now_ms < START_TIME_MS; f->now_ms++) {
        fb(f, true);
        assert_false(f->out.cp_start_error);
        modcp_jobp_t r;
        while ((r = poll(f)) != MODCP_JOBP_NOTHING) {
            if (r == MODCP_JOBP_INIT) {
                inits++;
                assert_true(modcp_job_send_ack(&f->job, MODCP_EV_SLAVE_ADDR));
            }
        }
    }
    assert_int_equal(inits, START_TIME_MS / MODCP_FB_RETRY_MS); /* 0, 200, ... 4800 */
    fb(f, true);
    assert_true(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_INIT);
    assert_int_equal(f->out.error_info, MODCP_EV_SLAVE_ADDR);

    /* CP_START falls and rises again: outputs cleared, init runs again */
    fb(f, false);
    while (poll(f) != MODCP_JOBP_NOTHING) {
    }
    init_ok(f);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
}

/* PARAMS larger than the CP's buffer: reported with msglen 0. */
static void test_params_overflow(void **state)
{
    fx_t *f = *state;
    modcp_job_init(&f->job, &f->bp, f->msgbuf, 100);
    fb(f, false);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, false);
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_int_equal(f->job.msglen, 0);
}

/* Before init completes every job is answered (0E)56H ([RTU-2003] §4.2 step 7, §4.6 e). */
static void test_job_before_init(void **state)
{
    fx_t *f = *state;
    fb(f, false);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, false);
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 4, 4, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_FB_NOT_RUNNING);
}

/* ---- jobs: 32-byte blocks, limits ([RTU-2003] §4.4, §4.5) ------------------------------------ */

/* The CP side alone: header block, then ceil(len/32) data blocks, the last shorter. */
static void test_job_block_layout(void **state)
{
    fx_t *f = *state;
    for (unsigned k = 0; k < 1000; k++) {
        f->wbuf[k] = (uint8_t)(k ^ 0x5A);
    }
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 24, 0, 1000, 1000, 1024),
                     MODCP_EV_NONE);
    assert_true(modcp_job_busy(&f->job));
    uint8_t got[1000];
    unsigned blocks = 0, pos = 0;
    uint8_t seq = 0;
    bool last = false;
    while (!last) {
        assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
        modcp_block_t b;
        while (modcp_ring_get(&f->bp.to_cpu, &b)) {
            assert_int_equal(b.seq, seq);
            seq++;
            assert_int_equal(b.kind, MODCP_BP_JOB);
            assert_int_equal(b.tag, 1); /* the first tag */
            if (blocks == 0) {
                assert_int_equal(b.flags, MODCP_BLK_FIRST);
                modcp_bp_job_t h;
                assert_true(modcp_bp_job_decode(b.data, b.len, &h));
                assert_int_equal(h.op, MODCP_JOB_WRITE);
                assert_int_equal(h.opnd.area, MODCP_AREA_DB);
                assert_int_equal(h.opnd.db, 800);
                assert_int_equal(h.opnd.offset, 24);
                assert_int_equal(h.len, 1000);
            } else {
                last = (b.flags & MODCP_BLK_LAST) != 0;
                assert_int_equal(b.flags & MODCP_BLK_FIRST, 0);
                assert_int_equal(b.len, last ? 1000 - 31 * 32 : 32); /* 8 */
                memcpy(got + pos, b.data, b.len);
                pos += b.len;
            }
            blocks++;
        }
    }
    assert_int_equal(blocks, 1 + 32);
    assert_int_equal(pos, 1000);
    assert_memory_equal(got, f->wbuf, 1000);
    assert_int_equal(f->job.state, MODCP_JOBST_WAITING);

    /* the test answers as the CPU side */
    modcp_bp_reply_t rep = {.event = MODCP_EV_NONE, .error_nr = 0, .len = 0};
    modcp_block_t b = {.kind = MODCP_BP_REPLY, .flags = MODCP_BLK_FIRST | MODCP_BLK_LAST, .tag = 1};
    b.len = modcp_bp_reply_encode(&rep, b.data);
    uint8_t tx = 0;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &tx));
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_false(modcp_job_busy(&f->job));
}

/* 1024-byte write (CP 341 limit) into DB 800: 1 + 32 blocks, reassembled byte-exact,
 * CP_START_NDR in exactly one call. */
static void test_write_1024(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    for (unsigned k = 0; k < 1024; k++) {
        f->wbuf[k] = (uint8_t)(k * 7u + 3u);
    }
    uint32_t head0 = atomic_load(&f->bp.to_cpu.head);
    f->ndr_calls = 0;
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 1024, 1024, 1024),
                     MODCP_EV_NONE);
    int calls = run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(atomic_load(&f->bp.to_cpu.head) - head0, 33);
    assert_int_equal(calls, 9); /* 4 blocks per CPU cycle: 33 blocks */
    assert_memory_equal(f->db800, f->wbuf, 1024);
    assert_int_equal(f->ndr_calls, 1);
    fb(f, true);
    assert_false(f->out.cp_start_ndr);
    assert_int_equal(f->fb.jobs_done, 1);
}

/* 1024-byte read: the reply is 1 + 32 blocks; rlen and the data exact. */
static void test_read_1024(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    for (unsigned k = 0; k < 1024; k++) {
        f->db800[k] = (uint8_t)(k * 11u + 5u);
    }
    uint32_t head0 = atomic_load(&f->bp.to_cp.head);
    f->ndr_calls = 0;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 1024, 1024, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->job.rlen, 1024);
    assert_memory_equal(f->rbuf, f->db800, 1024);
    assert_int_equal(atomic_load(&f->bp.to_cp.head) - head0, 33);
    assert_int_equal(f->ndr_calls, 0); /* a read is not new data */
}

/* [RTU-2003] §6.3 FC03 / §9: DB 800 DBW 160 = 8765 4321 read as 4 bytes; [RTU-2003] §6.1 T/C words
 * high byte first. */
static void test_read_small(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->db800[160] = 0x87, f->db800[161] = 0x65, f->db800[162] = 0x43, f->db800[163] = 0x21;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 160, 0, 4, 4, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->job.rlen, 4);
    assert_memory_equal(f->rbuf, ((const uint8_t[]){0x87, 0x65, 0x43, 0x21}), 4);

    f->t[100] = 0x1234;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_T, 0, 100, 0, 1, 2, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_memory_equal(f->rbuf, ((const uint8_t[]){0x12, 0x34}), 2);
}

/* CP 441-2 model: the transfer limit is 450 bytes ([RTU-2003] §4.5). */
static void test_job_limit_450(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 451, 451, 450),
                     MODCP_EV_JOB_LENGTH);
    assert_false(modcp_job_busy(&f->job));
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 451, 451, 450),
                     MODCP_EV_JOB_LENGTH);
    assert_false(modcp_job_busy(&f->job));
    /* a read that does not fit the caller's buffer */
    modcp_bp_job_t h = {.op = MODCP_JOB_READ, .opnd = {.area = MODCP_AREA_DB, .db = 800, .count = 8}, .len = 8};
    modcp_job_configure(&f->job, 450, TIMEOUT_US);
    assert_int_equal(modcp_job_start(&f->job, &h, NULL, f->rbuf, 7, f->now_us),
                     MODCP_EV_JOB_LENGTH);
    /* 450 is fine */
    memset(f->wbuf, 0x3C, 450);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 450, 450, 450),
                     MODCP_EV_NONE);
    /* one job at a time */
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 4, 4, 450),
                     MODCP_EV_INTERNAL_SEND);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->db800[449], 0x3C);
    assert_int_equal(f->db800[450], 0x00);
}

/* [RTU-2003] §6.8 FC15 example executed by the FB: CD 09 for 12 bits at M 1144.0, M 1145.4..7
 * preset to 1 stay 1; CP_START_NDR for exactly the executing call. */
static void test_bitwrite_fc15_ndr(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->m[1145] = 0xF0;
    f->wbuf[0] = 0xCD;
    f->wbuf[1] = 0x09;
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 1144, 0, 12, 2, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true);
    assert_true(f->out.cp_start_ndr);
    assert_int_equal(f->m[1144], 0xCD);
    assert_int_equal(f->m[1145], 0xF9);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    fb(f, true);
    assert_false(f->out.cp_start_ndr);

    /* [RTU-2003] §6.5 FC05 example: Q 257.1 set */
    f->q[257] = 0x80;
    f->wbuf[0] = 0x01;
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_Q, 0, 257, 1, 1, 1, 1024),
                     MODCP_EV_NONE);
    f->ndr_calls = 0;
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->q[257], 0x82);
    assert_int_equal(f->ndr_calls, 1);
}

/* ---- timeouts and cancellation ([RTU-2003] §4.3, (0E)31H / (0E)3BH) ------------------------- */

/* FC16 example data ([RTU-2003] §6.9) for DB 800 DBW 100; the FB is not called: (0E)31H at
 * exactly timeout_us; afterwards the cancelled write is not executed. */
static void test_write_timeout_not_executed(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    const uint8_t fc16[] = {0xCD, 0x09, 0xDE, 0x1A, 0xEF, 0x2B};
    memcpy(f->wbuf, fc16, 6);
    uint32_t t0 = f->now_us;
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 100, 0, 6, 6, 1024),
                     MODCP_EV_NONE);
    uint8_t tag = f->job.tag;
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING); /* header + data pushed */
    f->now_us = t0 + TIMEOUT_US - 1u;
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_true(modcp_job_busy(&f->job));
    f->now_us = t0 + TIMEOUT_US;
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_XFER_TIMEOUT);
    assert_false(modcp_job_busy(&f->job));
    assert_int_equal(atomic_load(&f->bp.abort_tag), tag);

    /* the CPU cycle comes back: the job's blocks are consumed, nothing is written */
    uint32_t cp_head = atomic_load(&f->bp.to_cp.head);
    f->ndr_calls = 0;
    fb(f, true);
    fb(f, true);
    assert_int_equal(atomic_load(&f->bp.to_cpu.tail), atomic_load(&f->bp.to_cpu.head));
    uint8_t zero[6] = {0};
    assert_memory_equal(f->db800 + 100, zero, 6);
    assert_int_equal(f->ndr_calls, 0);
    assert_int_equal(atomic_load(&f->bp.to_cp.head), cp_head); /* no reply for it */

    /* the next job works; a stale REPLY with the old tag arriving meanwhile is dropped */
    f->db800[0] = 0x42;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    assert_int_not_equal(f->job.tag, tag);
    modcp_bp_reply_t stale = {.event = MODCP_EV_NONE, .len = 0};
    modcp_block_t b = {.kind = MODCP_BP_REPLY, .flags = MODCP_BLK_FIRST | MODCP_BLK_LAST, .tag = tag};
    b.len = modcp_bp_reply_encode(&stale, b.data);
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &f->fb.tx_seq));
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_true(modcp_job_busy(&f->job));
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->rbuf[0], 0x42);
    assert_int_equal(f->job.proto_errors, 0);
}

/* A 1024-byte read times out while its reply is crossing ((0E)31H in RECEIVING); the
 * rest of the stale reply is dropped by the CP, and the next job is answered normally. */
static void test_read_timeout_stale_reply_dropped(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    memset(f->db800, 0x11, 1024);
    uint32_t t0 = f->now_us;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 1024, 1024, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true); /* executes, pushes 4 of 33 reply blocks */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(f->job.state, MODCP_JOBST_RECEIVING);
    assert_int_equal(f->job.rlen, 96);
    f->now_us = t0 + TIMEOUT_US; /* the CPU is stuck for a second */
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_XFER_TIMEOUT);

    memset(f->rbuf, 0, sizeof f->rbuf);
    for (int k = 0; k < 20 && (f->fb.reply_pending || atomic_load(&f->bp.to_cp.head) !=
                                                          atomic_load(&f->bp.to_cp.tail));
         k++) {
        fb(f, true);
        assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    }
    assert_false(f->fb.reply_pending);
    assert_int_equal(f->rbuf[0], 0); /* nothing stored */
    assert_false(modcp_job_busy(&f->job));
    assert_int_equal(f->job.proto_errors, 0);

    f->db800[5] = 0x99;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 5, 0, 1, 1, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->rbuf[0], 0x99);
}

/* FC05 ([RTU-2003] §6.5) with the FB not called: (0E)3BH; the wrap of the CP clock is harmless;
 * the cancelled bit write is never executed. */
static void test_bitwrite_timeout(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->now_us = 0xFFFF0000u;
    uint32_t t0 = f->now_us;
    f->wbuf[0] = 0x01;
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_Q, 0, 257, 1, 1, 1, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    f->now_us = t0 + TIMEOUT_US - 1u; /* wrapped past 0 */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    f->now_us = t0 + TIMEOUT_US;
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_FB_TIMEOUT);
    f->ndr_calls = 0;
    fb(f, true);
    assert_int_equal(f->q[257], 0x00);
    assert_int_equal(f->ndr_calls, 0);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
}

/* Tags run 1..255 and never 0; a tag that was cancelled is usable again 255 jobs later. */
static void test_tags_cycle_and_reuse(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    /* job with tag 1 times out while the FB sleeps */
    uint32_t t0 = f->now_us;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    assert_int_equal(f->job.tag, 1);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    f->now_us = t0 + TIMEOUT_US;
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(atomic_load(&f->bp.abort_tag), 1);
    f->m[0] = 0x5A;
    for (unsigned n = 0; n < 300; n++) {
        uint8_t want = (uint8_t)((n + 1u) % 255u + 1u); /* 2 .. 255, 1, 2 ... */
        assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
        assert_int_equal(f->job.tag, want);
        f->rbuf[0] = 0;
        run_job(f);
        assert_int_equal(f->job.event, MODCP_EV_NONE);
        assert_int_equal(f->rbuf[0], 0x5A);
    }
}

/* modcp_job_abort (CP re-parameterised): the queued job is not executed. */
static void test_job_abort(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->wbuf[0] = 0x77;
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 10, 0, 1, 1, 1024), MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    modcp_job_abort(&f->job);
    assert_false(modcp_job_busy(&f->job));
    assert_int_equal(atomic_load(&f->bp.abort_tag), f->job.tag);
    fb(f, true);
    assert_int_equal(f->m[10], 0);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
}

/* ---- errors reported by the FB ([RTU-2003] §7.5 (0E)38H/39H/3AH/57H, §7.6 10..18) ----------- */

static void expect_fb_error(fx_t *f, uint16_t nr, uint16_t info)
{
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_FB_ERROR);
    assert_int_equal(f->job.error_nr, nr);
    assert_int_equal(f->out.error_nr, nr);
    assert_int_equal(f->out.error_info, info);
    assert_int_equal(f->ndr_calls, 0);
}

static void test_fb_errors(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->ndr_calls = 0;
    memset(f->wbuf, 0xFF, 64);

    /* 10: illegal processing code, ERROR_INFO = the code */
    assert_int_equal(start(f, 9, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_PROC_CODE, 9);
    /* 12: amount 0 */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 0, 0, 0, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AMOUNT0, 0);
    /* 18: bit write to a timer (illegal area for the FB), ERROR_INFO 0 */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_T, 0, 0, 0, 16, 2, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AREA, 0);
    /* 18: register write to inputs */
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_I, 0, 0, 0, 2, 2, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AREA, 0);
    /* 14: M 2047.4, 8 bits -> ends in MB 2048 (M has 2048 bytes); ERROR_INFO = end */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 2047, 4, 8, 1, 1024),
                     MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_M_END, 2048);
    assert_int_equal(f->m[2047], 0x00);
    /* 15: Q 511.0, 9 bits -> QB 512 */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_Q, 0, 511, 0, 9, 2, 1024),
                     MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_Q_END, 512);
    assert_int_equal(f->q[511], 0x00);
    /* 13: fewer data bytes than the bit count needs */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 0, 0, 9, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AMOUNT, 9);
    /* 13: longer than the FB's job buffer (CP allowed 2000): 1100 bytes cross, nothing
     * is written */
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 1100, 1100, 2000),
                     MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AMOUNT, 1100);
    assert_int_equal(f->db800[0], 0x00);

    /* later jobs continue ([RTU-2003] §7.6: 10..19 do not stop the FB); outputs keep the error */
    f->m[3] = 0x0F;
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_M, 0, 3, 0, 1, 1, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->rbuf[0], 0x0F);
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_AMOUNT);
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
}

/* ---- FB outputs ([RTU-2003] FB table and §5.5, [VIPA-341] FB table) ---------------------------------- */

/* [RTU-2003] §5.5 step 5: "If the SEND fails -> CP_START is reset and CP_START_ERROR = 1".
 * CP_START is in/out (001: IN_OUT): the FB writes it false in the call that fails, the
 * error outputs stay until the caller's next rising edge, which retries. */
static void test_fb_outputs_5_5_init_failure_resets_cp_start(void **state)
{
    fx_t *f = *state;
    modcp_fb_in_t in = {.cp_start = true}; /* kept from call to call, like M180.0 */
    for (f->now_ms = 0; f->now_ms < START_TIME_MS; f->now_ms += 10u) {
        modcp_fb_call(&f->fb, &in, &f->out, f->now_ms); /* the CP stays silent */
        assert_true(in.cp_start);
        assert_false(f->out.cp_start_error);
    }
    modcp_fb_call(&f->fb, &in, &f->out, f->now_ms); /* START_TIME */
    assert_false(in.cp_start); /* reset by the FB */
    assert_true(f->out.cp_start_error);
    assert_false(f->out.cp_start_ok);
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_INIT);
    assert_int_equal(f->fb.state, MODCP_FBST_FAILED);

    /* the outputs keep the error while CP_START stays reset */
    for (int k = 0; k < 50; k++) {
        f->now_ms += 100u;
        modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
        assert_false(in.cp_start);
        assert_true(f->out.cp_start_error);
        assert_int_equal(f->out.error_nr, MODCP_FB_ERR_INIT);
        assert_int_equal(f->fb.state, MODCP_FBST_FAILED);
    }

    /* the user program sets CP_START again: a rising edge, the errors are cleared and
     * the initialisation runs again, this time with the CP answering */
    while (poll(f) != MODCP_JOBP_NOTHING) {
    }
    in.cp_start = true;
    f->now_ms += 100u;
    modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
    modcp_jobp_t r;
    int guard = 0;
    while ((r = poll(f)) != MODCP_JOBP_INIT) {
        if (r == MODCP_JOBP_NOTHING) {
            modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
        }
        assert_true(++guard < 20);
    }
    assert_true(modcp_job_send_ack(&f->job, MODCP_EV_NONE));
    modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
    assert_true(f->out.cp_start_ok);
    assert_false(f->out.cp_start_error);
    assert_true(in.cp_start); /* a successful initialisation leaves CP_START alone */
    assert_int_equal(f->fb.state, MODCP_FBST_RUN);
}

/* [RTU-2003] §5.5: a failure with the CP answering "not ready" keeps ERROR_INFO = the CP's
 * last event after CP_START was reset, until the next rising edge. */
static void test_fb_outputs_5_5_error_info_kept_until_edge(void **state)
{
    fx_t *f = *state;
    modcp_fb_in_t in = {.cp_start = true};
    for (f->now_ms = 0; in.cp_start && f->now_ms < 2u * START_TIME_MS; f->now_ms++) {
        modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
        modcp_jobp_t r;
        while ((r = poll(f)) != MODCP_JOBP_NOTHING) {
            if (r == MODCP_JOBP_INIT) {
                assert_true(modcp_job_send_ack(&f->job, MODCP_EV_SLAVE_ADDR));
            }
        }
    }
    assert_false(in.cp_start);
    assert_int_equal(f->now_ms, START_TIME_MS + 1u); /* reset in the call at START_TIME */
    for (int k = 0; k < 20; k++) {
        f->now_ms += 1000u;
        modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
        assert_true(f->out.cp_start_error);
        assert_int_equal(f->out.error_nr, MODCP_FB_ERR_INIT);
        assert_int_equal(f->out.error_info, MODCP_EV_SLAVE_ADDR);
    }
    in.cp_start = true; /* rising edge: errors cleared */
    modcp_fb_call(&f->fb, &in, &f->out, f->now_ms);
    assert_false(f->out.cp_start_error);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
}

/* [VIPA-341] FB table: "a rising edge [of CP_START] also clears the errors"; [RTU-2003] §7.6: a job
 * error (10..19) does not stop the FB. ERROR_NR / ERROR_INFO show the last error: kept
 * through later successful jobs and while CP_START stays set, replaced by a newer error,
 * cleared only by a rising edge of CP_START. */
static void test_fb_outputs_001_rising_edge_clears_errors(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->ndr_calls = 0;
    assert_int_equal(start(f, 9, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_PROC_CODE, 9);
    /* a successful write and many calls later: still shown */
    memset(f->wbuf, 0x5A, 4);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 4, 4, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->db800[3], 0x5A);
    for (int k = 0; k < 20; k++) {
        fb(f, true);
    }
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_PROC_CODE);
    assert_int_equal(f->out.error_info, 9);
    /* a newer error replaces it */
    f->ndr_calls = 0;
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 0, 0, 0, 1, 1024),
                     MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_AMOUNT0, 0);
    /* CP_START falls: nothing cleared yet */
    fb(f, false);
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_AMOUNT0);
    assert_true(f->out.cp_start_ok);
    /* rising edge: ERROR_NR / ERROR_INFO cleared (and the FB initialises again) */
    init_ok(f);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
    assert_false(f->out.cp_start_error);
}

/* Siemens MODBUS slave driver manual ch. 10 (FB diagnostics, "Clearing"): "the user may
 * also clear them [ERROR_NR / ERROR_INFO] at any time". Cleared by the user program, they
 * stay cleared through later calls and successful jobs; the next error writes them
 * again (the same error number too). */
static void test_fb_outputs_ch10_user_clears_error(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    f->ndr_calls = 0;
    assert_int_equal(start(f, 9, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_PROC_CODE, 9);
    f->out.error_nr = 0; /* the user program clears them */
    f->out.error_info = 0;
    for (int k = 0; k < 20; k++) {
        fb(f, true);
    }
    memset(f->wbuf, 0x5A, 4);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 4, 4, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->out.error_nr, 0);
    assert_int_equal(f->out.error_info, 0);
    assert_true(f->out.cp_start_ok); /* the other outputs are written at every call */
    f->ndr_calls = 0;
    assert_int_equal(start(f, 9, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    expect_fb_error(f, MODCP_FB_ERR_PROC_CODE, 9); /* the next error: written again */
}

/* (0E)38H / (0E)39H come from the memory model and are not FB error numbers. */
static void test_access_errors(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    /* [RTU-2003] §7.5 (0E)39H: DB 801 does not exist */
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 801, 0, 0, 4, 4, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_DB_ACCESS);
    assert_int_equal(f->job.error_nr, 0);
    assert_int_equal(f->job.rlen, 0);
    /* DB 900 too short for 8 bytes at 60 */
    memset(f->wbuf, 0xAB, 8);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 900, 60, 0, 8, 8, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_DB_ACCESS);
    assert_int_equal(f->db900[60], 0);
    /* bit write into a missing DB */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_DB, 801, 0, 0, 1, 1, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_DB_ACCESS);
    /* (0E)38H: inputs past the end (FC02) and counters past the end (FC01) */
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_I, 0, 120, 0, 16, 16, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_AREA_ACCESS);
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_C, 0, 199, 0, 2, 4, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_AREA_ACCESS);
    assert_int_equal(f->out.error_nr, 0); /* not an FB error */
}

/* (0E)3AH: the FB's work DB does not exist ([RTU-2003] §7.5) — bit writes cannot be placed. */
static void test_work_db_missing(void **state)
{
    fx_t *f = *state;
    fx_fb_init(f, 81);
    init_ok(f);
    assert_int_equal(f->init.areas.work_db, 81);
    f->wbuf[0] = 0x01;
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 5, 0, 1, 1, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_WORK_DB);
    assert_int_equal(f->m[5], 0);
    /* reads and register writes do not need the work DB */
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 5, 0, 1, 1, 1024), MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->m[5], 0x01);
}

/* ---- ring protocol checks on the CP side ------------------------------------------- */

static void put_reply(fx_t *f, uint8_t *seq, uint8_t flags, uint8_t tag, const uint8_t *d,
                      uint8_t len)
{
    modcp_block_t b;
    memset(&b, 0, sizeof b);
    b.kind = MODCP_BP_REPLY;
    b.flags = flags;
    b.tag = tag;
    b.len = len;
    memcpy(b.data, d, len);
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, seq));
}

/* The test consumes what the CP sent, as the CPU side would. */
static void drain_to_cpu(fx_t *f)
{
    modcp_block_t b;
    while (modcp_ring_get(&f->bp.to_cpu, &b)) {
    }
}

/* A reply shorter than announced, or shorter than the read asked for: (0E)33H. A
 * sequence gap is counted and resynchronised. */
static void test_reply_checks(void **state)
{
    fx_t *f = *state;
    uint8_t seq = 10;
    uint8_t hdr[8];
    modcp_bp_reply_t r = {.event = MODCP_EV_NONE, .len = 4};
    const uint8_t two[2] = {1, 2};

    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_M, 0, 0, 0, 4, 4, 1024), MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    drain_to_cpu(f);
    put_reply(f, &seq, MODCP_BLK_FIRST, f->job.tag, hdr, modcp_bp_reply_encode(&r, hdr));
    put_reply(f, &seq, MODCP_BLK_LAST, f->job.tag, two, 2); /* 2 of 4 */
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_XFER_STATE);
    assert_int_equal(f->job.proto_errors, 0); /* first block synced at seq 10 */

    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_M, 0, 0, 0, 4, 4, 1024), MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    r.len = 2; /* announces fewer bytes than the read asked for */
    put_reply(f, &seq, MODCP_BLK_FIRST, f->job.tag, hdr, modcp_bp_reply_encode(&r, hdr));
    put_reply(f, &seq, MODCP_BLK_LAST, f->job.tag, two, 2);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_XFER_STATE);

    /* FB error carried by the header ends the job at once */
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 0, 0, 1, 1, 1024), MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    drain_to_cpu(f);
    modcp_bp_reply_t e = {.event = MODCP_EV_FB_ERROR, .error_nr = 14, .len = 0};
    seq++; /* gap: one sequence number skipped */
    put_reply(f, &seq, MODCP_BLK_FIRST | MODCP_BLK_LAST, f->job.tag, hdr,
              modcp_bp_reply_encode(&e, hdr));
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_FB_ERROR);
    assert_int_equal(f->job.error_nr, 14);
    assert_int_equal(f->job.proto_errors, 1);
    /* resynchronised: the next block in sequence is no error; a reply without a job is
     * dropped silently */
    put_reply(f, &seq, MODCP_BLK_FIRST | MODCP_BLK_LAST, f->job.tag, hdr,
              modcp_bp_reply_encode(&e, hdr));
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(f->job.proto_errors, 1);
}

/* The test plays the CP towards the FB (blocks pushed by hand). */
static void cp_put(fx_t *f, uint8_t kind, uint8_t flags, uint8_t tag, const uint8_t *d, uint8_t len)
{
    modcp_block_t b;
    memset(&b, 0, sizeof b);
    b.kind = kind;
    b.flags = flags;
    b.tag = tag;
    b.len = len;
    memcpy(b.data, d, len);
    assert_true(modcp_ring_put(&f->bp.to_cpu, &b, &f->job.tx_seq));
}

static void cp_put_job(fx_t *f, uint8_t tag, uint8_t op, uint8_t area, uint16_t offset, uint8_t bit,
                       uint16_t count, uint16_t len, bool last)
{
    modcp_bp_job_t h = {.op = op, .opnd = {.area = area, .bit = bit, .offset = offset, .count = count},
                        .len = len};
    uint8_t d[MODCP_BLOCK_SIZE];
    uint8_t n = modcp_bp_job_encode(&h, d);
    cp_put(f, MODCP_BP_JOB, (uint8_t)(MODCP_BLK_FIRST | (last ? MODCP_BLK_LAST : 0)), tag, d, n);
}

/* The FB's reply header as the CP would see it; false if there is none. */
static bool fb_reply(fx_t *f, uint8_t *tag, modcp_bp_reply_t *r)
{
    modcp_block_t b;
    if (!modcp_ring_get(&f->bp.to_cp, &b)) {
        return false;
    }
    assert_int_equal(b.kind, MODCP_BP_REPLY);
    assert_true(b.flags & MODCP_BLK_FIRST);
    *tag = b.tag;
    assert_true(modcp_bp_reply_decode(b.data, b.len, r));
    return true;
}

/* docs/cpu-cp-interface.md: nothing is executed from a job whose data did not arrive complete. */
static void test_fb_incomplete_jobs(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    const uint8_t data[4] = {1, 2, 3, 4};
    uint8_t tag;
    modcp_bp_reply_t r;

    /* announced 4 bytes, 2 arrive: (0E)33H, memory untouched */
    cp_put_job(f, 10, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 4, 4, false);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 10, data, 2);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 10);
    assert_int_equal(r.event, MODCP_EV_XFER_STATE);
    assert_int_equal(f->m[0], 0);
    assert_int_equal(f->ndr_calls, 0);

    /* a block lost on the way (sequence gap): the job is dropped without a reply */
    cp_put_job(f, 11, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 4, 4, false);
    f->job.tx_seq++;
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 11, data, 4);
    fb(f, true);
    assert_false(fb_reply(f, &tag, &r));
    assert_int_equal(f->m[0], 0);
    /* data of a job whose header was never seen is ignored, too */
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 12, data, 4);
    fb(f, true);
    assert_false(fb_reply(f, &tag, &r));

    /* a new FIRST abandons an unfinished job; the new one runs */
    cp_put_job(f, 13, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 4, 4, false);
    cp_put_job(f, 14, MODCP_JOB_WRITE, MODCP_AREA_M, 8, 0, 4, 4, false);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 14, data, 4);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 14);
    assert_int_equal(r.event, MODCP_EV_NONE);
    assert_int_equal(f->m[0], 0);
    assert_memory_equal(f->m + 8, data, 4);
    assert_int_equal(f->ndr_calls, 1);

    /* 11: illegal start address (bit 8), ERROR_INFO = start byte */
    cp_put_job(f, 15, MODCP_JOB_BITWRITE, MODCP_AREA_M, 33, 8, 1, 1, false);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 15, data, 1);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(r.event, MODCP_EV_FB_ERROR);
    assert_int_equal(r.error_nr, MODCP_FB_ERR_START);
    assert_int_equal(f->out.error_nr, MODCP_FB_ERR_START);
    assert_int_equal(f->out.error_info, 33);
    /* 18: no such area */
    cp_put_job(f, 16, MODCP_JOB_READ, 0, 0, 0, 1, 1, true);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(r.error_nr, MODCP_FB_ERR_AREA);
}

/* Data crosses once per block: a write job's data blocks are written into controller
 * memory as they arrive, each block within one FB call (each block consistent); a job
 * whose blocks all arrive in one call is consistent as a whole. CP_START_NDR and the
 * reply come with the LAST block. */
static void test_write_streamed_per_block(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    for (unsigned k = 0; k < 200; k++) {
        f->wbuf[k] = (uint8_t)(k + 1u);
    }
    f->ndr_calls = 0;
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_DB, 800, 0, 0, 200, 200, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING); /* header + 3 data blocks */
    fb(f, true);
    assert_memory_equal(f->db800, f->wbuf, 96); /* the 3 blocks that crossed */
    assert_int_equal(f->db800[96], 0);
    assert_int_equal(f->ndr_calls, 0);
    assert_null(modcp_ring_peek(&f->bp.to_cp)); /* no reply yet */
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING); /* the other 4 data blocks */
    fb(f, true);
    assert_memory_equal(f->db800, f->wbuf, 200);
    assert_int_equal(f->db800[200], 0);
    assert_int_equal(f->ndr_calls, 1);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);

    /* a job of up to 4 blocks crosses in one call: written whole in that call */
    memset(f->wbuf, 0x77, 96);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 100, 0, 96, 96, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true);
    assert_memory_equal(f->m + 100, f->wbuf, 96);
    assert_int_equal(f->ndr_calls, 2);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
}

/* A read's reply blocks are read from controller memory into their slots when the
 * slots are free: each block is a consistent snapshot of its own call. */
static void test_read_streamed_per_block(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    memset(f->db800, 0x11, 200);
    assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 0, 0, 200, 200, 1024),
                     MODCP_EV_NONE);
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    fb(f, true); /* REPLY header + 3 data blocks (bytes 0 .. 95) */
    memset(f->db800, 0x22, 200); /* the user program changes the data meanwhile */
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_int_equal(f->job.rlen, 200);
    assert_int_equal(f->rbuf[0], 0x11);
    assert_int_equal(f->rbuf[95], 0x11);
    assert_int_equal(f->rbuf[96], 0x22);
    assert_int_equal(f->rbuf[199], 0x22);
}

/* Data blocks after the header: a block of another size than announced ends the job
 * with (0E)33H and nothing more of it is written; a block of a job the CP gave up on
 * (abort_tag) is not written and the job is not answered. */
static void test_fb_data_checks_per_block(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    uint8_t d[MODCP_BLOCK_SIZE];
    memset(d, 0x5A, sizeof d);
    uint8_t tag;
    modcp_bp_reply_t r;

    /* 70 bytes announced: 32 + 32 + 6; the second block has 20 bytes */
    cp_put_job(f, 30, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 70, 70, false);
    cp_put(f, MODCP_BP_JOB, 0, 30, d, 32);
    cp_put(f, MODCP_BP_JOB, 0, 30, d, 20);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 30, d, 6);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 30);
    assert_int_equal(r.event, MODCP_EV_XFER_STATE);
    assert_int_equal(f->m[31], 0x5A); /* the first block was in order */
    assert_int_equal(f->m[32], 0);
    assert_int_equal(f->ndr_calls, 0);
    assert_false(fb_reply(f, &tag, &r)); /* the rest of the job is dropped */

    /* cancelled between two blocks (a job longer than the ring: 1 + 5 blocks) */
    memset(f->m, 0, 200);
    cp_put_job(f, 31, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 136, 136, false);
    cp_put(f, MODCP_BP_JOB, 0, 31, d, 32);
    fb(f, true);
    assert_int_equal(f->m[0], 0x5A);
    atomic_store(&f->bp.abort_tag, 31);
    cp_put(f, MODCP_BP_JOB, 0, 31, d, 32);
    fb(f, true);
    assert_int_equal(f->m[32], 0);
    assert_false(fb_reply(f, &tag, &r));
    assert_int_equal(f->ndr_calls, 0);

    /* a write job that fits the ring waits until all of its blocks are in */
    memset(f->m, 0, 200);
    cp_put_job(f, 33, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 40, 40, false);
    cp_put(f, MODCP_BP_JOB, 0, 33, d, 32);
    fb(f, true);
    assert_int_equal(f->m[0], 0); /* 2 of its 3 blocks in: not started */
    assert_non_null(modcp_ring_peek(&f->bp.to_cpu));
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 33, d, 8);
    fb(f, true);
    assert_int_equal(f->m[0], 0x5A);
    assert_int_equal(f->m[39], 0x5A);
    assert_int_equal(f->m[40], 0);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 33);
    assert_int_equal(r.event, MODCP_EV_NONE);
    assert_int_equal(f->ndr_calls, 1);
    f->ndr_calls = 0;

    /* a header flagged LAST for a write that announces data: (0E)33H */
    cp_put_job(f, 32, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 0, 4, 4, true);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 32);
    assert_int_equal(r.event, MODCP_EV_XFER_STATE);
}

/* FC15 over several blocks: 600 bits from M 10.3, 256 per block, the edges masked. */
static void test_bitwrite_multi_block(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    for (unsigned k = 0; k < 75; k++) {
        f->wbuf[k] = (uint8_t)(k * 37u + 11u);
    }
    memset(f->m, 0xFF, 100);
    assert_int_equal(start(f, MODCP_JOB_BITWRITE, MODCP_AREA_M, 0, 10, 3, 600, 75, 1024),
                     MODCP_EV_NONE);
    run_job(f);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    for (unsigned k = 0; k < 600; k++) {
        unsigned want = (f->wbuf[k / 8u] >> (k % 8u)) & 1u;
        unsigned pos = 3u + k;
        unsigned got = (f->m[10u + pos / 8u] >> (pos % 8u)) & 1u;
        if (want != got) {
            fail_msg("bit %u", k);
        }
    }
    assert_int_equal(f->m[10] & 0x07, 0x07); /* M 10.0 .. 10.2 untouched */
    assert_int_equal(f->m[10 + (3 + 600) / 8] & 0xF8, 0xF8); /* after the last bit */
    assert_int_equal(f->m[9], 0xFF);
    assert_int_equal(f->m[86], 0xFF);
}

/* A job whose write data fits after its header (up to 21 bytes) crosses as that one
 * block, FIRST and LAST; so does a reply whose read data fits after its header (up to
 * 26 bytes). One byte more and the data follows in a block of its own. */
static void test_one_block_jobs(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    for (unsigned k = 0; k < 32; k++) {
        f->wbuf[k] = (uint8_t)(0xA0u + k);
    }
    /* write of 21 bytes: one block = 11-byte header + the data */
    uint32_t head0 = atomic_load(&f->bp.to_cpu.head);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 40, 0, 21, 21, 1024), MODCP_EV_NONE);
    assert_int_equal(atomic_load(&f->bp.to_cpu.head) - head0, 1); /* pushed by the start */
    const modcp_block_t *b = modcp_ring_peek(&f->bp.to_cpu);
    assert_non_null(b);
    assert_int_equal(b->flags, MODCP_BLK_FIRST | MODCP_BLK_LAST);
    assert_int_equal(b->len, MODCP_BP_JOB_HDR_LEN + 21);
    assert_memory_equal(b->data + MODCP_BP_JOB_HDR_LEN, f->wbuf, 21);
    assert_int_equal(f->job.state, MODCP_JOBST_WAITING);
    f->ndr_calls = 0;
    fb(f, true);
    assert_memory_equal(f->m + 40, f->wbuf, 21);
    assert_int_equal(f->ndr_calls, 1);
    b = modcp_ring_peek(&f->bp.to_cp); /* the reply: its header alone */
    assert_non_null(b);
    assert_int_equal(b->flags, MODCP_BLK_FIRST | MODCP_BLK_LAST);
    assert_int_equal(b->len, MODCP_BP_REPLY_HDR_LEN);
    assert_int_equal(poll(f), MODCP_JOBP_DONE);
    assert_int_equal(f->job.event, MODCP_EV_NONE);

    /* write of 22 bytes: header, then one data block */
    head0 = atomic_load(&f->bp.to_cpu.head);
    assert_int_equal(start(f, MODCP_JOB_WRITE, MODCP_AREA_M, 0, 80, 0, 22, 22, 1024), MODCP_EV_NONE);
    assert_int_equal(atomic_load(&f->bp.to_cpu.head) - head0, 2);
    assert_int_equal(run_job(f), 1);
    assert_int_equal(f->job.event, MODCP_EV_NONE);
    assert_memory_equal(f->m + 80, f->wbuf, 22);

    /* read of 26 bytes: the reply is one block; of 27: header + one data block */
    for (unsigned k = 0; k < 27; k++) {
        f->db800[300 + k] = (uint8_t)(k * 3u + 1u);
    }
    for (uint16_t n = 26; n <= 27; n++) {
        memset(f->rbuf, 0, 32);
        uint32_t cp_head = atomic_load(&f->bp.to_cp.head);
        assert_int_equal(start(f, MODCP_JOB_READ, MODCP_AREA_DB, 800, 300, 0, n, n, 1024),
                         MODCP_EV_NONE);
        fb(f, true);
        assert_int_equal(atomic_load(&f->bp.to_cp.head) - cp_head, n == 26 ? 1u : 2u);
        b = modcp_ring_peek(&f->bp.to_cp);
        assert_int_equal(b->len, n == 26 ? MODCP_BP_REPLY_HDR_LEN + 26 : MODCP_BP_REPLY_HDR_LEN);
        assert_int_equal(poll(f), MODCP_JOBP_DONE);
        assert_int_equal(f->job.event, MODCP_EV_NONE);
        assert_int_equal(f->job.rlen, n);
        assert_memory_equal(f->rbuf, f->db800 + 300, n);
    }
}

/* The FB on one-block jobs: the data after a LAST header must be exactly what the header
 * announces, else (0E)33H and nothing is written; a header not flagged LAST ignores
 * bytes after it (its data follows in blocks of their own). */
static void test_fb_one_block_checks(void **state)
{
    fx_t *f = *state;
    init_ok(f);
    uint8_t tag;
    modcp_bp_reply_t r;
    modcp_bp_job_t h = {.op = MODCP_JOB_WRITE, .opnd = {.area = MODCP_AREA_M, .offset = 10, .count = 4},
                        .len = 4};
    uint8_t d[MODCP_BLOCK_SIZE];
    memset(d, 0x3C, sizeof d);
    uint8_t n = modcp_bp_job_encode(&h, d);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_FIRST | MODCP_BLK_LAST, 40, d, (uint8_t)(n + 3)); /* 3 of 4 */
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 40);
    assert_int_equal(r.event, MODCP_EV_XFER_STATE);
    assert_int_equal(f->m[10], 0);
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_FIRST | MODCP_BLK_LAST, 41, d, (uint8_t)(n + 5)); /* 5 of 4 */
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(r.event, MODCP_EV_XFER_STATE);
    assert_int_equal(f->m[10], 0);
    assert_int_equal(f->ndr_calls, 0);
    /* header not LAST with bytes after it: they are ignored, the data block counts */
    const uint8_t data[4] = {1, 2, 3, 4};
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_FIRST, 42, d, (uint8_t)(n + 4));
    cp_put(f, MODCP_BP_JOB, MODCP_BLK_LAST, 42, data, 4);
    fb(f, true);
    assert_true(fb_reply(f, &tag, &r));
    assert_int_equal(tag, 42);
    assert_int_equal(r.event, MODCP_EV_NONE);
    assert_memory_equal(f->m + 10, data, 4);
    assert_int_equal(f->ndr_calls, 1);
}

/* CP side: a PARAMS message that loses a block is reported empty; blocks of the wrong
 * kind or a short INIT are protocol errors and reported as nothing. */
static void test_cp_message_checks(void **state)
{
    fx_t *f = *state;
    uint8_t seq = 0;
    uint8_t d[MODCP_BLOCK_SIZE];
    memset(d, 0x33, sizeof d);
    modcp_block_t b;
    memset(&b, 0, sizeof b);
    b.kind = MODCP_BP_PARAMS;
    b.len = 32;
    b.flags = MODCP_BLK_FIRST;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    seq++; /* lost block */
    b.flags = MODCP_BLK_LAST;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    assert_int_equal(poll(f), MODCP_JOBP_PARAMS);
    assert_int_equal(f->job.msglen, 0);
    assert_int_equal(f->job.proto_errors, 1);
    assert_int_equal(f->job.new_errors, MODCP_JOB_ERR_PROTO); /* the kind, for the CP */
    f->job.new_errors = 0; /* (the CP clears it once reported) */

    b.kind = MODCP_BP_INIT; /* too short for an INIT */
    b.flags = MODCP_BLK_FIRST | MODCP_BLK_LAST;
    b.len = 10;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    b.kind = MODCP_BP_JOB; /* wrong direction */
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    b.kind = MODCP_BP_PARAMS; /* continuation without a start */
    b.flags = MODCP_BLK_LAST;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(f->job.proto_errors, 4);
    assert_int_equal(f->job.new_errors, MODCP_JOB_ERR_PROTO | MODCP_JOB_ERR_ILLEGAL);
    f->job.new_errors = 0;

    b.kind = MODCP_BP_JOB; /* wrong direction alone: illegal, and no other kind */
    b.flags = MODCP_BLK_FIRST | MODCP_BLK_LAST;
    assert_true(modcp_ring_put(&f->bp.to_cp, &b, &seq));
    assert_int_equal(poll(f), MODCP_JOBP_NOTHING);
    assert_int_equal(f->job.proto_errors, 5);
    assert_int_equal(f->job.new_errors, MODCP_JOB_ERR_ILLEGAL);
}

int main(void)
{
#define T(fn) cmocka_unit_test_setup_teardown(fn, setup, teardown)
    const struct CMUnitTest tests[] = {
        T(test_params_at_first_call),
        T(test_init_happy_path),
        T(test_init_retry_then_success),
        T(test_init_timeout_cp_silent),
        T(test_init_nak_until_timeout),
        T(test_params_overflow),
        T(test_job_before_init),
        T(test_job_block_layout),
        T(test_write_1024),
        T(test_read_1024),
        T(test_read_small),
        T(test_job_limit_450),
        T(test_bitwrite_fc15_ndr),
        T(test_write_timeout_not_executed),
        T(test_read_timeout_stale_reply_dropped),
        T(test_bitwrite_timeout),
        T(test_tags_cycle_and_reuse),
        T(test_job_abort),
        T(test_fb_errors),
        T(test_fb_outputs_5_5_init_failure_resets_cp_start),
        T(test_fb_outputs_5_5_error_info_kept_until_edge),
        T(test_fb_outputs_001_rising_edge_clears_errors),
        T(test_fb_outputs_ch10_user_clears_error),
        T(test_access_errors),
        T(test_work_db_missing),
        T(test_reply_checks),
        T(test_fb_incomplete_jobs),
        T(test_cp_message_checks),
        T(test_write_streamed_per_block),
        T(test_read_streamed_per_block),
        T(test_fb_data_checks_per_block),
        T(test_bitwrite_multi_block),
        T(test_one_block_jobs),
        T(test_fb_one_block_checks),
    };
#undef T
    return cmocka_run_group_tests(tests, NULL, NULL);
}
