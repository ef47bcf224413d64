/* SPDX-License-Identifier: Apache-2.0 */
/* Controller memory model: bytes, T/C words high byte first, bit read-modify-write,
 * access events (0E)38H / (0E)39H ([RTU-2003] §7.5), DB lookup. Memory laid out for the
 * manual's example parameter set ([RTU-2003] §9): MB 1000.., QB 256.., T 100.., C 200..,
 * DB 800 / DB 900. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "modcp/plcmem.h"
#include "plcmem_internal.h"

typedef struct {
    uint8_t i[256], q[512], m[2048];
    uint16_t t[256], c[256];
    uint8_t db1[16], db80[64], db800[1024], db900[64], db65535[4];
    modcp_db_t dbs[5];
    modcp_plcmem_t mem;
} world_t;

static int setup(void **state)
{
    world_t *w = test_calloc(1, sizeof *w);
    w->dbs[0] = (modcp_db_t){1, sizeof w->db1, w->db1};
    w->dbs[1] = (modcp_db_t){80, sizeof w->db80, w->db80};
    w->dbs[2] = (modcp_db_t){800, sizeof w->db800, w->db800};
    w->dbs[3] = (modcp_db_t){900, sizeof w->db900, w->db900};
    w->dbs[4] = (modcp_db_t){65535, sizeof w->db65535, w->db65535};
    w->mem = (modcp_plcmem_t){.i = w->i, .q = w->q, .m = w->m, .t = w->t, .c = w->c,
                              .i_size = sizeof w->i, .q_size = sizeof w->q, .m_size = sizeof w->m,
                              .t_count = 256, .c_count = 256, .dbs = w->dbs, .db_count = 5};
    *state = w;
    return 0;
}

static int teardown(void **state)
{
    test_free(*state);
    return 0;
}

static modcp_operand_t opnd(uint8_t area, uint16_t db, uint16_t offset, uint8_t bit, uint16_t count)
{
    modcp_operand_t o = {.area = area, .bit = bit, .db = db, .offset = offset, .count = count};
    return o;
}

static void test_db_lookup(void **state)
{
    world_t *w = *state;
    assert_ptr_equal(modcp_plcmem_db(&w->mem, 1), &w->dbs[0]);
    assert_ptr_equal(modcp_plcmem_db(&w->mem, 80), &w->dbs[1]);
    assert_ptr_equal(modcp_plcmem_db(&w->mem, 800), &w->dbs[2]);
    assert_ptr_equal(modcp_plcmem_db(&w->mem, 900), &w->dbs[3]);
    assert_ptr_equal(modcp_plcmem_db(&w->mem, 65535), &w->dbs[4]);
    assert_null(modcp_plcmem_db(&w->mem, 0));
    assert_null(modcp_plcmem_db(&w->mem, 2));
    assert_null(modcp_plcmem_db(&w->mem, 801));
    assert_null(modcp_plcmem_db(&w->mem, 65534));
    for (uint16_t n = 1; n <= 5; n++) { /* every prefix of the list */
        w->mem.db_count = n;
        assert_ptr_equal(modcp_plcmem_db(&w->mem, w->dbs[n - 1].number), &w->dbs[n - 1]);
        assert_ptr_equal(modcp_plcmem_db(&w->mem, 1), &w->dbs[0]);
    }
    w->mem.db_count = 0;
    assert_null(modcp_plcmem_db(&w->mem, 1));
    w->mem.dbs = NULL;
    assert_null(modcp_plcmem_db(&w->mem, 1));
}

static void test_areas(void **state)
{
    world_t *w = *state;
    modcp_areas_t a;
    memset(&a, 0xFF, sizeof a);
    modcp_plcmem_areas(&w->mem, &a);
    assert_int_equal(a.i_bytes, 256);
    assert_int_equal(a.q_bytes, 512);
    assert_int_equal(a.m_bytes, 2048);
    assert_int_equal(a.timers, 256);
    assert_int_equal(a.counters, 256);
    assert_int_equal(a.work_db, 0);
}

/* [RTU-2003] §6.1 FC01 example: M 1008.0 .. 1011.7 hold 01 17 02 18 (read whole bytes). */
static void test_read_write_bytes(void **state)
{
    world_t *w = *state;
    const uint8_t fc01[] = {0x01, 0x17, 0x02, 0x18};
    modcp_operand_t o = opnd(MODCP_AREA_M, 0, 1008, 0, 4);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, fc01, 4), MODCP_EV_NONE);
    assert_memory_equal(w->m + 1008, fc01, 4);
    uint8_t out[8] = {0};
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 4), MODCP_EV_NONE);
    assert_memory_equal(out, fc01, 4);

    /* [RTU-2003] §6.2 FC02 example: IB 130 .. 132 = 12 34 56 */
    w->i[130] = 0x12, w->i[131] = 0x34, w->i[132] = 0x56;
    o = opnd(MODCP_AREA_I, 0, 130, 0, 3);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 3), MODCP_EV_NONE);
    assert_memory_equal(out, ((const uint8_t[]){0x12, 0x34, 0x56}), 3);

    /* [RTU-2003] §6.9 FC16 example: DB 800 DBW 100..104 = CD09 DE1A EF2B, big-endian as stored */
    const uint8_t fc16[] = {0xCD, 0x09, 0xDE, 0x1A, 0xEF, 0x2B};
    o = opnd(MODCP_AREA_DB, 800, 100, 0, 6);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, fc16, 6), MODCP_EV_NONE);
    assert_memory_equal(w->db800 + 100, fc16, 6);
    assert_int_equal(w->db800[99], 0);
    assert_int_equal(w->db800[106], 0);
    memset(out, 0, sizeof out);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 6), MODCP_EV_NONE);
    assert_memory_equal(out, fc16, 6);

    /* Q, and the last byte of an area */
    o = opnd(MODCP_AREA_Q, 0, 511, 0, 1);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, fc16, 1), MODCP_EV_NONE);
    assert_int_equal(w->q[511], 0xCD);
    /* the whole DB, bit ignored for byte access */
    o = opnd(MODCP_AREA_DB, 900, 0, 5, 64);
    w->db900[63] = 0x77;
    uint8_t all[64];
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, all, 64), MODCP_EV_NONE);
    assert_int_equal(all[63], 0x77);
}

/* [RTU-2003] §6.1 / §9: T and C words travel high byte first (controller byte order). */
static void test_timers_counters(void **state)
{
    world_t *w = *state;
    w->t[100] = 0x1234;
    w->t[101] = 0xABCD;
    uint8_t out[4] = {0};
    modcp_operand_t o = opnd(MODCP_AREA_T, 0, 100, 0, 2);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 4), MODCP_EV_NONE);
    assert_memory_equal(out, ((const uint8_t[]){0x12, 0x34, 0xAB, 0xCD}), 4);

    o = opnd(MODCP_AREA_C, 0, 200, 0, 2);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, (const uint8_t[]){0x0F, 0x01, 0x80, 0x02}, 4),
                     MODCP_EV_NONE);
    assert_int_equal(w->c[200], 0x0F01);
    assert_int_equal(w->c[201], 0x8002);
    assert_int_equal(w->c[199], 0);
    assert_int_equal(w->c[202], 0);

    /* last element; one past it; half an element */
    o = opnd(MODCP_AREA_C, 0, 255, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 2), MODCP_EV_NONE);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 4), MODCP_EV_AREA_ACCESS);
    o = opnd(MODCP_AREA_T, 0, 100, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 3), MODCP_EV_AREA_ACCESS);
    o = opnd(MODCP_AREA_T, 0, 256, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, out, 2), MODCP_EV_AREA_ACCESS);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, out, 2), MODCP_EV_AREA_ACCESS);
}

/* [RTU-2003] §6.8 FC15 example: CD 09 for 12 bits at M 1144.0; M 1145.4..7 preset to 1 stay 1. */
static void test_write_bits_fc15_example(void **state)
{
    world_t *w = *state;
    w->m[1144] = 0x32; /* every bit of 1144 is overwritten */
    w->m[1145] = 0xF6; /* 1145.4..7 = 1 untouched, 1145.0..3 become 1001 */
    w->m[1143] = 0xAA;
    w->m[1146] = 0x55;
    modcp_operand_t o = opnd(MODCP_AREA_M, 0, 1144, 0, 12);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0xCD, 0x09}),
                     MODCP_EV_NONE);
    assert_int_equal(w->m[1144], 0xCD);
    assert_int_equal(w->m[1145], 0xF9);
    assert_int_equal(w->m[1143], 0xAA);
    assert_int_equal(w->m[1146], 0x55);

    /* the same with M 1145.4..7 = 0: stay 0 */
    w->m[1145] = 0x00;
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0xCD, 0xF9}),
                     MODCP_EV_NONE);
    assert_int_equal(w->m[1145], 0x09); /* bits 4..7 of the data byte are not part of the write */
}

/* [RTU-2003] §6.5 FC05 example: Q 257.1 set, the other bits of QB 257 untouched; then reset. */
static void test_write_bits_fc05_example(void **state)
{
    world_t *w = *state;
    w->q[257] = 0x81;
    modcp_operand_t o = opnd(MODCP_AREA_Q, 0, 257, 1, 1);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0x01}), MODCP_EV_NONE);
    assert_int_equal(w->q[257], 0x83);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0xFE}), MODCP_EV_NONE);
    assert_int_equal(w->q[257], 0x81);
}

/* Unaligned start, crossing two byte boundaries: M 10.5 .. 12.2 (14 bits). */
static void test_write_bits_unaligned(void **state)
{
    world_t *w = *state;
    w->m[10] = 0x1F; /* bits 0..4 keep 1 */
    w->m[11] = 0xFF;
    w->m[12] = 0xF8; /* bits 3..7 keep 1 */
    modcp_operand_t o = opnd(MODCP_AREA_M, 0, 10, 5, 14);
    /* request bits k = 0..13: 0b10_0000_0000_0101 -> k0 = 1, k2 = 1, k13 = 1 */
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0x05, 0x20}),
                     MODCP_EV_NONE);
    /* k0 -> 10.5, k1 -> 10.6, k2 -> 10.7; k3..10 -> 11.0..7; k11..13 -> 12.0..2 */
    assert_int_equal(w->m[10], 0xBF);
    assert_int_equal(w->m[11], 0x00);
    assert_int_equal(w->m[12], 0xFC);

    /* DB bits ([ASCII-32] DB-bit windows), bit index beyond 7 counts on into the next bytes */
    o = opnd(MODCP_AREA_DB, 900, 2, 9, 2); /* DBX 3.1 .. 3.2 */
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0x03}), MODCP_EV_NONE);
    assert_int_equal(w->db900[2], 0x00);
    assert_int_equal(w->db900[3], 0x06);
    /* count 0 touches nothing */
    o = opnd(MODCP_AREA_M, 0, 11, 0, 0);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0xFF}), MODCP_EV_NONE);
    assert_int_equal(w->m[11], 0x00);
}

/* (0E)38H: I, Q, M, T, C out of range or no such area; nothing is written. */
/* Reference for modcp_bits_put: one bit at a time. */
static void bits_put_ref(uint8_t *dst, uint32_t first, uint32_t count, const uint8_t *bits)
{
    for (uint32_t k = 0; k < count; k++) {
        uint32_t pos = first + k;
        uint8_t mask = (uint8_t)(1u << (pos & 7u));
        if ((bits[k / 8u] >> (k & 7u)) & 1u) {
            dst[pos / 8u] = (uint8_t)(dst[pos / 8u] | mask);
        } else {
            dst[pos / 8u] = (uint8_t)(dst[pos / 8u] & (uint8_t)~mask);
        }
    }
}

/* The byte-wise bit write equals the bit-by-bit one for every start bit 0..15 and
 * every count 0..300 (edges masked, whole bytes between, bytes around untouched), and
 * never reads past ceil(count / 8) source bytes. */
static void test_bits_put_matches_bitwise(void **state)
{
    (void)state;
    uint32_t rnd = 12345u;
    for (uint32_t first = 0; first < 16u; first++) {
        for (uint32_t count = 0; count <= 300u; count++) {
            uint8_t want[48], got[48], src[48];
            for (unsigned k = 0; k < sizeof want; k++) {
                rnd = rnd * 1103515245u + 12345u;
                want[k] = got[k] = (uint8_t)(rnd >> 16);
                rnd = rnd * 1103515245u + 12345u;
                src[k] = (uint8_t)(rnd >> 16);
            }
            /* the source ends exactly after ceil(count / 8) bytes: a heap copy, so
             * ASan catches a read past it */
            size_t sn = (count + 7u) / 8u;
            uint8_t *bits = test_malloc(sn > 0u ? sn : 1u);
            memcpy(bits, src, sn);
            bits_put_ref(want, first, count, bits);
            modcp_bits_put(got, first, count, bits);
            test_free(bits);
            if (memcmp(want, got, sizeof want) != 0) {
                fail_msg("first %u count %u", (unsigned)first, (unsigned)count);
            }
        }
    }
}

/* locate: the storage the FB writes blocks into, with the events of read / write. */
static void test_locate(void **state)
{
    world_t *w = *state;
    uint8_t *p = (uint8_t *)1;
    modcp_operand_t o = opnd(MODCP_AREA_DB, 800, 100, 0, 8);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 8, &p), MODCP_EV_NONE);
    assert_ptr_equal(p, w->db800 + 100);
    o = opnd(MODCP_AREA_M, 0, 2040, 0, 8);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 8, &p), MODCP_EV_NONE);
    assert_ptr_equal(p, w->m + 2040);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 9, &p), MODCP_EV_AREA_ACCESS);
    assert_null(p);
    o = opnd(MODCP_AREA_DB, 801, 0, 0, 1);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 1, &p), MODCP_EV_DB_ACCESS);
    assert_null(p);
    o = opnd(MODCP_AREA_T, 0, 254, 0, 2);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 4, &p), MODCP_EV_NONE);
    assert_null(p); /* elements: no byte storage */
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 6, &p), MODCP_EV_AREA_ACCESS);
    assert_int_equal(modcp_plcmem_locate(&w->mem, &o, 3, &p), MODCP_EV_AREA_ACCESS);
    /* bits: M 2047.4 + 4 bits fits, + 5 does not */
    o = opnd(MODCP_AREA_M, 0, 2047, 4, 4);
    assert_int_equal(modcp_plcmem_locate_bits(&w->mem, &o, &p), MODCP_EV_NONE);
    assert_ptr_equal(p, w->m + 2047);
    o.count = 5;
    assert_int_equal(modcp_plcmem_locate_bits(&w->mem, &o, &p), MODCP_EV_AREA_ACCESS);
    o = opnd(MODCP_AREA_C, 0, 0, 0, 1);
    assert_int_equal(modcp_plcmem_locate_bits(&w->mem, &o, &p), MODCP_EV_AREA_ACCESS);
}

static void test_area_access_errors(void **state)
{
    world_t *w = *state;
    uint8_t buf[64];
    memset(buf, 0xEE, sizeof buf);
    modcp_operand_t o = opnd(MODCP_AREA_M, 0, 2047, 0, 2);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 2), MODCP_EV_AREA_ACCESS);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 2), MODCP_EV_AREA_ACCESS);
    assert_int_equal(w->m[2047], 0);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 1), MODCP_EV_NONE);
    /* the uint32 check: offset 65535 + len 65535 does not wrap */
    o = opnd(MODCP_AREA_I, 0, 0xFFFF, 0, 0);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 0xFFFF), MODCP_EV_AREA_ACCESS);
    o = opnd(MODCP_AREA_Q, 0, 512, 0, 1);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 1), MODCP_EV_AREA_ACCESS);
    o = opnd(MODCP_AREA_NONE, 0, 0, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 1), MODCP_EV_AREA_ACCESS);
    o = opnd(9, 0, 0, 0, 1);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 1), MODCP_EV_AREA_ACCESS);
    /* bits past the end: M 2047.7 + 2 bits -> byte 2048; memory untouched */
    w->m[2047] = 0x00;
    o = opnd(MODCP_AREA_M, 0, 2047, 7, 2);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, buf), MODCP_EV_AREA_ACCESS);
    assert_int_equal(w->m[2047], 0x00);
    o = opnd(MODCP_AREA_M, 0, 2047, 7, 1);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, (const uint8_t[]){0x01}), MODCP_EV_NONE);
    assert_int_equal(w->m[2047], 0x80);
    o = opnd(MODCP_AREA_Q, 0, 0xFFFF, 7, 0xFFFF);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, buf), MODCP_EV_AREA_ACCESS);
    /* T / C are never bit-written */
    o = opnd(MODCP_AREA_T, 0, 0, 0, 1);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, buf), MODCP_EV_AREA_ACCESS);
    assert_int_equal(w->t[0], 0);
    /* an area of size 0 */
    w->mem.i_size = 0;
    o = opnd(MODCP_AREA_I, 0, 0, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 1), MODCP_EV_AREA_ACCESS);
}

/* (0E)39H: DB missing or too short; nothing is written. */
static void test_db_access_errors(void **state)
{
    world_t *w = *state;
    uint8_t buf[64];
    memset(buf, 0xEE, sizeof buf);
    modcp_operand_t o = opnd(MODCP_AREA_DB, 801, 0, 0, 2); /* no DB 801 */
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 2), MODCP_EV_DB_ACCESS);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 2), MODCP_EV_DB_ACCESS);
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, buf), MODCP_EV_DB_ACCESS);
    o = opnd(MODCP_AREA_DB, 900, 62, 0, 4); /* DB 900 is 64 bytes: 62 + 4 too long */
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 4), MODCP_EV_DB_ACCESS);
    assert_int_equal(w->db900[62], 0);
    assert_int_equal(w->db900[63], 0);
    assert_int_equal(modcp_plcmem_write(&w->mem, &o, buf, 2), MODCP_EV_NONE);
    assert_int_equal(w->db900[63], 0xEE);
    o = opnd(MODCP_AREA_DB, 900, 63, 7, 2); /* DBX 63.7 + 1 bit past the end */
    assert_int_equal(modcp_plcmem_write_bits(&w->mem, &o, buf), MODCP_EV_DB_ACCESS);
    o = opnd(MODCP_AREA_DB, 0, 0, 0, 1); /* DB 0 never exists */
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 1), MODCP_EV_DB_ACCESS);
    o = opnd(MODCP_AREA_DB, 65535, 0xFFFF, 0, 1);
    assert_int_equal(modcp_plcmem_read(&w->mem, &o, buf, 0xFFFF), MODCP_EV_DB_ACCESS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_db_lookup, setup, teardown),
        cmocka_unit_test_setup_teardown(test_areas, setup, teardown),
        cmocka_unit_test_setup_teardown(test_read_write_bytes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_timers_counters, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_bits_fc15_example, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_bits_fc05_example, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_bits_unaligned, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bits_put_matches_bitwise, setup, teardown),
        cmocka_unit_test_setup_teardown(test_locate, setup, teardown),
        cmocka_unit_test_setup_teardown(test_area_access_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_db_access_errors, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
