/* SPDX-License-Identifier: Apache-2.0 */
/* Backplane rings and header encoders (docs/cpu-cp-interface.md: 32-byte blocks, request/acknowledge
 * per block with sequence numbers). */
#include <pthread.h>
#include <sched.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/backplane.h"
#include "backplane_internal.h"

static modcp_block_t blk(uint8_t kind, uint8_t first_byte, uint8_t len)
{
    modcp_block_t b;
    memset(&b, 0, sizeof b);
    b.kind = kind;
    b.len = len;
    b.tag = 7;
    b.flags = MODCP_BLK_FIRST;
    for (uint8_t k = 0; k < len; k++) {
        b.data[k] = (uint8_t)(first_byte + k);
    }
    b.seq = 0xEE; /* must be overwritten by the ring */
    return b;
}

static void test_init(void **state)
{
    (void)state;
    modcp_backplane_t bp;
    memset(&bp, 0xA5, sizeof bp);
    modcp_bp_init(&bp);
    assert_int_equal(atomic_load(&bp.abort_tag), 0x100);
    assert_int_equal(atomic_load(&bp.to_cpu.head), 0);
    assert_int_equal(atomic_load(&bp.to_cpu.tail), 0);
    assert_int_equal(atomic_load(&bp.to_cp.head), 0);
    assert_int_equal(atomic_load(&bp.to_cp.tail), 0);
    assert_int_equal(modcp_ring_space(&bp.to_cpu), MODCP_BP_DEPTH);
    assert_int_equal(modcp_ring_space(&bp.to_cp), MODCP_BP_DEPTH);
}

static void test_empty_full_space(void **state)
{
    (void)state;
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    modcp_ring_t *r = &bp.to_cpu;
    modcp_block_t out;
    uint8_t seq = 0;

    assert_false(modcp_ring_get(r, &out)); /* empty */
    for (uint32_t k = 0; k < MODCP_BP_DEPTH; k++) {
        assert_int_equal(modcp_ring_space(r), MODCP_BP_DEPTH - k);
        modcp_block_t b = blk(MODCP_BP_JOB, (uint8_t)(10u * k), 32);
        assert_true(modcp_ring_put(r, &b, &seq));
    }
    assert_int_equal(modcp_ring_space(r), 0);
    assert_int_equal(seq, MODCP_BP_DEPTH);
    /* full: refused, nothing written, seq untouched */
    modcp_block_t extra = blk(MODCP_BP_JOB, 0xF0, 3);
    assert_false(modcp_ring_put(r, &extra, &seq));
    assert_int_equal(seq, MODCP_BP_DEPTH);
    assert_int_equal(atomic_load(&r->head), MODCP_BP_DEPTH);

    /* FIFO order, seq 0, 1, 2, ... stamped by the producer, contents intact */
    for (uint32_t k = 0; k < MODCP_BP_DEPTH; k++) {
        assert_true(modcp_ring_get(r, &out));
        assert_int_equal(out.seq, k);
        assert_int_equal(out.len, 32);
        assert_int_equal(out.kind, MODCP_BP_JOB);
        assert_int_equal(out.tag, 7);
        assert_int_equal(out.data[0], (uint8_t)(10u * k));
        assert_int_equal(out.data[31], (uint8_t)(10u * k + 31u));
        assert_int_equal(modcp_ring_space(r), k + 1u);
    }
    assert_false(modcp_ring_get(r, &out));
    /* the other direction is independent */
    assert_int_equal(modcp_ring_space(&bp.to_cp), MODCP_BP_DEPTH);
}

/* Zero-copy use: the producer fills the free slot in place and publishes it, the
 * consumer reads it in place and releases it. A full ring offers no slot (the producer
 * produces nothing, so nothing fails); the consumer's block stays put until released. */
static void test_slot_in_place(void **state)
{
    (void)state;
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    modcp_ring_t *r = &bp.to_cp;
    uint8_t seq = 200;
    assert_null(modcp_ring_peek(r));
    for (uint32_t k = 0; k < MODCP_BP_DEPTH; k++) {
        modcp_block_t *b = modcp_ring_slot(r);
        assert_non_null(b);
        assert_ptr_equal(b, &r->slot[k]);
        assert_ptr_equal(modcp_ring_slot(r), b); /* not taken until published */
        b->len = 1;
        b->data[0] = (uint8_t)(0x40 + k);
        b->kind = MODCP_BP_REPLY;
        b->flags = 0;
        b->tag = 9;
        modcp_ring_publish(r, b, &seq);
        assert_int_equal(atomic_load(&r->head), k + 1u);
    }
    assert_int_equal(seq, (uint8_t)(200 + MODCP_BP_DEPTH));
    assert_null(modcp_ring_slot(r)); /* full */
    assert_int_equal(modcp_ring_space(r), 0);
    const modcp_block_t *c = modcp_ring_peek(r);
    assert_ptr_equal(c, &r->slot[0]);
    assert_ptr_equal(modcp_ring_peek(r), c); /* peeking does not take it */
    assert_int_equal(c->seq, 200);
    assert_int_equal(c->data[0], 0x40);
    assert_null(modcp_ring_slot(r)); /* still full until released */
    modcp_ring_release(r);
    assert_int_equal(atomic_load(&r->tail), 1);
    assert_ptr_equal(modcp_ring_slot(r), &r->slot[0]); /* the released slot is next */
    c = modcp_ring_peek(r);
    assert_int_equal(c->seq, 201);
    assert_int_equal(c->data[0], 0x41);
    /* put_data builds in the free slot; a block longer than 32 bytes is refused */
    uint8_t d[33] = {0};
    assert_false(modcp_ring_put_data(r, &seq, MODCP_BP_REPLY, 0, 1, d, 33));
    assert_true(modcp_ring_put_data(r, &seq, MODCP_BP_REPLY, MODCP_BLK_LAST, 1, d, 32));
    assert_false(modcp_ring_put_data(r, &seq, MODCP_BP_REPLY, 0, 1, d, 1)); /* full */
}

static void test_sequence_wraps(void **state)
{
    (void)state;
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    uint8_t seq = 254;
    const uint8_t want[] = {254, 255, 0, 1};
    /* in groups of MODCP_BP_DEPTH blocks (depth 4: all four, then all four out) */
    for (int g = 0; g < 4; g += (int)MODCP_BP_DEPTH) {
        for (int k = g; k < 4 && k < g + (int)MODCP_BP_DEPTH; k++) {
            modcp_block_t b = blk(MODCP_BP_REPLY, (uint8_t)k, 1);
            assert_true(modcp_ring_put(&bp.to_cp, &b, &seq));
        }
        for (int k = g; k < 4 && k < g + (int)MODCP_BP_DEPTH; k++) {
            modcp_block_t out;
            assert_true(modcp_ring_get(&bp.to_cp, &out));
            assert_int_equal(out.seq, want[k]);
            assert_int_equal(out.data[0], k);
        }
    }
    assert_int_equal(seq, 2);
}

/* head / tail are free-running 32-bit counters: crossing 2^32 must be seamless. */
static void test_counter_wrap(void **state)
{
    (void)state;
    modcp_backplane_t bp;
    modcp_bp_init(&bp);
    modcp_ring_t *r = &bp.to_cpu;
    atomic_store(&r->head, 0xFFFFFFFDu);
    atomic_store(&r->tail, 0xFFFFFFFDu);
    assert_int_equal(modcp_ring_space(r), MODCP_BP_DEPTH);
    uint8_t seq = 0;
    uint8_t next_out = 0;
    for (uint8_t k = 0; k < 20; k++) {
        modcp_block_t b = blk(MODCP_BP_JOB, k, 1);
        while (!modcp_ring_put(r, &b, &seq)) {
            modcp_block_t out;
            assert_true(modcp_ring_get(r, &out));
            assert_int_equal(out.data[0], next_out);
            assert_int_equal(out.seq, next_out);
            next_out++;
        }
    }
    assert_int_equal(modcp_ring_space(r), 0); /* full across the wrap */
    modcp_block_t out;
    while (modcp_ring_get(r, &out)) {
        assert_int_equal(out.data[0], next_out);
        next_out++;
    }
    assert_int_equal(next_out, 20);
    assert_int_equal(atomic_load(&r->head), 20u - 3u);
    assert_int_equal(atomic_load(&r->tail), 20u - 3u);
    assert_int_equal(modcp_ring_space(r), MODCP_BP_DEPTH);
}

/* Two threads, one producer and one consumer: every block arrives once, in order,
 * with the contents it was published with. */
#define STRESS_N 200000u
static void *producer(void *arg)
{
    modcp_ring_t *r = arg;
    uint8_t seq = 0;
    for (uint32_t n = 0; n < STRESS_N; n++) {
        modcp_block_t b;
        memset(&b, 0, sizeof b);
        b.len = 32;
        for (int k = 0; k < 32; k++) {
            b.data[k] = (uint8_t)(n + (uint32_t)k);
        }
        b.tag = (uint8_t)(n >> 8);
        while (!modcp_ring_put(r, &b, &seq)) {
            sched_yield(); /* full: let the consumer run (one core, busy machine) */
        }
    }
    return NULL;
}

static void test_two_threads(void **state)
{
    (void)state;
    static modcp_backplane_t bp; /* test-local, shared with the producer thread */
    modcp_bp_init(&bp);
    pthread_t th;
    assert_int_equal(pthread_create(&th, NULL, producer, &bp.to_cpu), 0);
    uint32_t errors = 0;
    for (uint32_t n = 0; n < STRESS_N; n++) {
        modcp_block_t out;
        while (!modcp_ring_get(&bp.to_cpu, &out)) {
            sched_yield(); /* empty: let the producer run */
        }
        if (out.seq != (uint8_t)n || out.tag != (uint8_t)(n >> 8) || out.len != 32) {
            errors++;
        }
        for (int k = 0; k < 32; k++) {
            if (out.data[k] != (uint8_t)(n + (uint32_t)k)) {
                errors++;
            }
        }
    }
    assert_int_equal(pthread_join(th, NULL), 0);
    assert_int_equal(errors, 0);
    assert_int_equal(modcp_ring_space(&bp.to_cpu), MODCP_BP_DEPTH);
}

/* JOB header: 0 op | 1 area | 2 bit | 3..4 db | 5..6 offset | 7..8 count | 9..10 len,
 * little-endian. [RTU-2003] §6.8 FC15 example: M 1144.0, 12 bits, 2 data bytes. */
static void test_job_header(void **state)
{
    (void)state;
    modcp_bp_job_t j = {.op = MODCP_JOB_BITWRITE,
                        .opnd = {.area = MODCP_AREA_M, .bit = 0, .db = 0, .offset = 1144, .count = 12},
                        .len = 2};
    uint8_t d[MODCP_BLOCK_SIZE];
    memset(d, 0xCC, sizeof d);
    uint8_t n = modcp_bp_job_encode(&j, d);
    const uint8_t want[] = {0x03, 0x03, 0x00, 0x00, 0x00, 0x78, 0x04, 0x0C, 0x00, 0x02, 0x00};
    assert_int_equal(n, sizeof want);
    assert_memory_equal(d, want, sizeof want);
    assert_int_equal(d[n], 0xCC); /* nothing written past the header */

    modcp_bp_job_t back;
    memset(&back, 0, sizeof back);
    assert_true(modcp_bp_job_decode(d, n, &back));
    assert_int_equal(back.op, j.op);
    assert_int_equal(back.opnd.area, j.opnd.area);
    assert_int_equal(back.opnd.bit, 0);
    assert_int_equal(back.opnd.db, 0);
    assert_int_equal(back.opnd.offset, 1144);
    assert_int_equal(back.opnd.count, 12);
    assert_int_equal(back.len, 2);
    assert_false(modcp_bp_job_decode(d, (uint8_t)(n - 1u), &back)); /* short */

    /* [RTU-2003] §6.6 FC06 example: DB 800, DBW 768, high field values round-trip */
    modcp_bp_job_t w = {.op = MODCP_JOB_WRITE,
                        .opnd = {.area = MODCP_AREA_DB, .bit = 7, .db = 0xFFFF, .offset = 768, .count = 2},
                        .len = 0xFEDC};
    n = modcp_bp_job_encode(&w, d);
    const uint8_t want2[] = {0x02, 0x06, 0x07, 0xFF, 0xFF, 0x00, 0x03, 0x02, 0x00, 0xDC, 0xFE};
    assert_memory_equal(d, want2, sizeof want2);
    assert_true(modcp_bp_job_decode(d, 32, &back)); /* longer block: trailing bytes ignored */
    assert_int_equal(back.opnd.db, 0xFFFF);
    assert_int_equal(back.opnd.bit, 7);
    assert_int_equal(back.opnd.offset, 768);
    assert_int_equal(back.len, 0xFEDC);
}

/* REPLY header: 0..1 event | 2..3 error_nr | 4..5 len, little-endian. */
static void test_reply_header(void **state)
{
    (void)state;
    modcp_bp_reply_t r = {.event = MODCP_EV_FB_ERROR, .error_nr = 14, .len = 300};
    uint8_t d[MODCP_BLOCK_SIZE];
    uint8_t n = modcp_bp_reply_encode(&r, d);
    const uint8_t want[] = {0x57, 0x0E, 0x0E, 0x00, 0x2C, 0x01};
    assert_int_equal(n, sizeof want);
    assert_memory_equal(d, want, sizeof want);
    modcp_bp_reply_t back;
    memset(&back, 0, sizeof back);
    assert_true(modcp_bp_reply_decode(d, n, &back));
    assert_int_equal(back.event, MODCP_EV_FB_ERROR);
    assert_int_equal(back.error_nr, 14);
    assert_int_equal(back.len, 300);
    assert_false(modcp_bp_reply_decode(d, 5, &back));
    assert_false(modcp_bp_reply_decode(d, 0, &back));
}

/* INIT: i q m timers counters work_db record_crc, 2 bytes each, little-endian. */
static void test_init_payload(void **state)
{
    (void)state;
    modcp_bp_init_t i = {.areas = {.i_bytes = 128, .q_bytes = 512, .m_bytes = 2048,
                                   .timers = 256, .counters = 0x1234, .work_db = 80},
                         .record_crc = 0xCDC5};
    uint8_t d[MODCP_BLOCK_SIZE];
    uint8_t n = modcp_bp_init_encode(&i, d);
    const uint8_t want[] = {0x80, 0x00, 0x00, 0x02, 0x00, 0x08, 0x00, 0x01,
                            0x34, 0x12, 0x50, 0x00, 0xC5, 0xCD};
    assert_int_equal(n, sizeof want);
    assert_memory_equal(d, want, sizeof want);
    modcp_bp_init_t back;
    memset(&back, 0, sizeof back);
    assert_true(modcp_bp_init_decode(d, n, &back));
    assert_int_equal(back.areas.i_bytes, 128);
    assert_int_equal(back.areas.q_bytes, 512);
    assert_int_equal(back.areas.m_bytes, 2048);
    assert_int_equal(back.areas.timers, 256);
    assert_int_equal(back.areas.counters, 0x1234);
    assert_int_equal(back.areas.work_db, 80);
    assert_int_equal(back.record_crc, 0xCDC5);
    assert_false(modcp_bp_init_decode(d, 13, &back));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init),
        cmocka_unit_test(test_empty_full_space),
        cmocka_unit_test(test_slot_in_place),
        cmocka_unit_test(test_sequence_wraps),
        cmocka_unit_test(test_counter_wrap),
        cmocka_unit_test(test_two_threads),
        cmocka_unit_test(test_job_header),
        cmocka_unit_test(test_reply_header),
        cmocka_unit_test(test_init_payload),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
