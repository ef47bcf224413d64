/* SPDX-License-Identifier: Apache-2.0 */
/* Property (issue 13 item 9, Application Protocol §7: an exception reply means the
 * request was not executed): for random write requests FC05, 06, 15, 16, 22 and 23 -
 * direct and through the indirection scanner, good and bad lengths, quantities,
 * byte counts, values, addresses, write limits, missing and too short DBs, a small
 * CPU job limit - every exception reply leaves the controller memory exactly as it
 * was. Seeded (MODCP_PROP_SEED, default 1) and sized (MODCP_PROP_N requests per
 * world, default 80000) from the environment; a failure prints the seed, the request
 * number and the frame. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "world.h"

#define S 5

typedef struct {
    uint8_t i[256], q[320], m[2600];
    uint16_t t[240], c[240];
    uint8_t db[WORLD_DBS][1024];
} memory_t;

static void snapshot(const world_t *w, memory_t *s)
{
    memcpy(s->i, w->i, sizeof s->i);
    memcpy(s->q, w->q, sizeof s->q);
    memcpy(s->m, w->m, sizeof s->m);
    memcpy(s->t, w->t, sizeof s->t);
    memcpy(s->c, w->c, sizeof s->c);
    memcpy(s->db, w->db_data, sizeof s->db);
}

static uint32_t rng_state;

static uint32_t rnd(void)
{
    uint32_t x = rng_state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    rng_state = x;
    return x;
}

static uint32_t below(uint32_t n)
{
    return rnd() % n;
}

static unsigned env_or(const char *name, unsigned dflt)
{
    const char *v = getenv(name);
    return v != NULL && *v != '\0' ? (unsigned)strtoul(v, NULL, 0) : dflt;
}

/* A register start address: the DB-offset scheme (DB 800..803, 803 missing), the
 * scanner, DB 900 (outside the write limits), DB 807 (allowed, missing), anywhere. */
static uint16_t reg_addr(void)
{
    switch (below(8)) {
    case 0:
    case 1:
        return (uint16_t)below(0x0400);            /* DB 800, 801 */
    case 2:
        return (uint16_t)(0x0400 + below(0x0400)); /* DB 802, 803 (missing) */
    case 3:
        return (uint16_t)(0x1000 - 4 + below(16)); /* the scanner and its edges */
    case 4:
        return (uint16_t)(0x0E00 + below(0x0200)); /* DB 807: allowed, missing */
    case 5:
        return (uint16_t)(0xC800 + below(0x0200)); /* DB 900: not writable */
    case 6:
        return (uint16_t)(0x01F0 + below(0x20));   /* around the DB boundary */
    default:
        return (uint16_t)rnd();
    }
}

static uint16_t coil_addr(void)
{
    switch (below(4)) {
    case 0:
        return (uint16_t)below(2048);          /* M */
    case 1:
        return (uint16_t)(2048 + below(512));  /* Q */
    case 2:
        return (uint16_t)(4096 + below(1100)); /* T, C: not writable; beyond */
    default:
        return (uint16_t)rnd();
    }
}

static uint16_t small_qty(uint16_t max)
{
    switch (below(6)) {
    case 0:
        return 0;
    case 1:
        return (uint16_t)(max + below(3));
    default:
        return (uint16_t)(1 + below(below(3) == 0 ? max : 8u));
    }
}

static size_t put16(uint8_t *p, size_t o, uint16_t v)
{
    p[o] = (uint8_t)(v >> 8);
    p[o + 1] = (uint8_t)v;
    return o + 2;
}

/* A random write request for slave S into f (address byte first); returns its length. */
static size_t make_request(uint8_t *f)
{
    static const uint8_t fcs[] = {0x05, 0x06, 0x0F, 0x10, 0x16, 0x17};
    const uint8_t fc = fcs[below(sizeof fcs)];
    size_t o = 0;
    f[o++] = S;
    f[o++] = fc;
    switch (fc) {
    case 0x05:
        o = put16(f, o, coil_addr());
        o = put16(f, o, below(5) == 0 ? (uint16_t)rnd() : (below(2) ? 0xFF00u : 0x0000u));
        break;
    case 0x06:
        o = put16(f, o, reg_addr());
        o = put16(f, o, (uint16_t)rnd());
        break;
    case 0x0F: {
        const uint16_t qty = small_qty(2040);
        o = put16(f, o, coil_addr());
        o = put16(f, o, qty);
        uint8_t bc = (uint8_t)((qty + 7u) / 8u);
        if (below(8) == 0) {
            bc = (uint8_t)(bc + 1u);
        }
        f[o++] = bc;
        for (unsigned k = 0; k < bc && o < 250; k++) {
            f[o++] = (uint8_t)rnd();
        }
        break;
    }
    case 0x10: {
        const uint16_t qty = small_qty(127);
        o = put16(f, o, reg_addr());
        o = put16(f, o, qty);
        uint8_t bc = (uint8_t)(2u * qty);
        if (below(8) == 0) {
            bc = (uint8_t)(bc + 2u);
        }
        f[o++] = bc;
        for (unsigned k = 0; k < bc && o < 250; k++) {
            f[o++] = (uint8_t)rnd();
        }
        break;
    }
    case 0x16:
        o = put16(f, o, reg_addr());
        o = put16(f, o, (uint16_t)rnd());
        o = put16(f, o, (uint16_t)rnd());
        break;
    default: { /* FC23 */
        const uint16_t rqty = small_qty(125);
        const uint16_t wqty = small_qty(121);
        o = put16(f, o, reg_addr());
        o = put16(f, o, rqty);
        o = put16(f, o, reg_addr());
        o = put16(f, o, wqty);
        uint8_t bc = (uint8_t)(2u * wqty);
        if (below(8) == 0) {
            bc = (uint8_t)(bc + 2u);
        }
        f[o++] = bc;
        for (unsigned k = 0; k < bc && o < 250; k++) {
            f[o++] = (uint8_t)rnd();
        }
        break;
    }
    }
    if (below(16) == 0 && o > 2) {
        o -= 1u + below(2); /* truncated */
    }
    return o;
}

static void hex(const uint8_t *f, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        fprintf(stderr, "%02X ", f[k]);
    }
    fprintf(stderr, "\n");
}

/* Run n random requests against w; count exceptions by code (exc[0] = no exception). */
static void run(world_t *w, uint32_t seed, unsigned n, unsigned exc[8])
{
    static memory_t before;
    uint8_t f[260];
    rng_state = seed != 0u ? seed : 1u;
    for (unsigned r = 0; r < n; r++) {
        const size_t len = make_request(f);
        snapshot(w, &before);
        uint16_t got = world_request_raw(w, f, len, 2000);
        if (got == 0) {
            fprintf(stderr, "seed %u request %u: no reply to ", seed, r);
            hex(f, len);
            fail();
        }
        const bool is_exc = got == 5 && (w->fake.tx[1] & 0x80u) != 0u;
        if (!is_exc) {
            exc[0]++;
            continue;
        }
        exc[w->fake.tx[2] & 7u]++;
        static memory_t after;
        snapshot(w, &after);
        if (memcmp(&before, &after, sizeof before) != 0) {
            fprintf(stderr, "seed %u request %u: exception %02X but memory changed: ", seed,
                    r, w->fake.tx[2]);
            hex(f, len);
            fail();
        }
    }
}

static void prop_params(modcp_params_t *p)
{
    world_example_params(p);
    p->fset = MODCP_FSET_EXTENDED;
    p->lim_db = (modcp_limit_t){800, 899}; /* DB 803 and 807 writable but missing */
    p->scan_start = 0x1000;
    p->scan_count = 10;
    p->scan[0] = (modcp_operand_ref_t){MODCP_AREA_M, 0, 1000};
    p->scan[1] = (modcp_operand_ref_t){MODCP_AREA_DB, 801, 20};
    p->scan[2] = (modcp_operand_ref_t){MODCP_AREA_DB, 807, 0};   /* missing */
    p->scan[3] = (modcp_operand_ref_t){MODCP_AREA_Q, 0, 256};
    p->scan[4] = (modcp_operand_ref_t){MODCP_AREA_NONE, 0, 0};
    p->scan[5] = (modcp_operand_ref_t){MODCP_AREA_DB, 802, 10};
    p->scan[6] = (modcp_operand_ref_t){MODCP_AREA_T, 0, 5};
    p->scan[7] = (modcp_operand_ref_t){MODCP_AREA_DB, 800, 1022}; /* the last word */
    p->scan[8] = (modcp_operand_ref_t){MODCP_AREA_DB, 803, 4};   /* missing */
    p->scan[9] = (modcp_operand_ref_t){MODCP_AREA_DB, WORLD_WORK_DB, 100}; /* too short */
}

static void check_world(const modcp_params_t *p, uint32_t seed)
{
    world_t *w = world_new(p);
    assert_true(world_start(w, 1000));
    unsigned exc[8] = {0};
    run(w, seed, env_or("MODCP_PROP_N", 80000), exc);
    fprintf(stderr, "seed %u: %u executed, exceptions 01 %u, 02 %u, 03 %u, 04 %u\n", seed,
            exc[0], exc[1], exc[2], exc[3], exc[4]);
    /* the generator reaches every outcome, the CPU side's refusals included */
    assert_true(exc[0] > 0 && exc[2] > 0 && exc[3] > 0 && exc[4] > 0);
    world_free(w);
}

/* Application Protocol §7: exception => not executed; the world of the [RTU-2003] §9 example
 * set with the scanner over missing and short DBs. */
static void test_mbap7_exception_means_nothing_written(void **state)
{
    (void)state;
    modcp_params_t p;
    prop_params(&p);
    check_world(&p, env_or("MODCP_PROP_SEED", 1));
}

/* The same with a CPU job limit of 64 bytes: FC23 parts beyond it are refused before
 * either part runs. */
static void test_mbap7_exception_means_nothing_written_job_limit(void **state)
{
    (void)state;
    modcp_params_t p;
    prop_params(&p);
    p.job_limit = 64;
    check_world(&p, env_or("MODCP_PROP_SEED", 1) + 1000u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mbap7_exception_means_nothing_written),
        cmocka_unit_test(test_mbap7_exception_means_nothing_written_job_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
