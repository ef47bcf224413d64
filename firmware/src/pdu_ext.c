/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — handlers of the extended function set (docs/extended-functions.md) that run CPU jobs in
 * sequence: FC22 mask write register, FC23 read/write multiple registers, and FC03 /
 * FC06 / FC16 on the indirection scanner's addresses (one job per scattered operand).
 *
 * A handler checks everything the CP can check (lengths, quantities, byte counts,
 * every range and every operand, the CPU job limit) and then returns the first job;
 * modcp_pdu_seq_next() returns the next one until the reply can be encoded (pdu.c).
 *
 * An exception means that nothing was written (docs/extended-functions.md). A single
 * CPU job is atomic: the CPU side refuses it before it writes. What only the CPU side
 * can check - a DB that is missing or too short - is therefore checked, for requests
 * with several jobs, before the first write. The jobs run as
 *   1. early reads (FC23): reads of DB operands that no write of the request touches;
 *      their values are the same before and after the writes, and their jobs check
 *      the DBs. Only when the reply and the write data both fit into the buffer (the
 *      write data move to its end);
 *   2. check reads: a 2-byte read of the last word of every other DB operand that a
 *      job after the first write touches;
 *   3. the writes, DB operands first (the first one checks its own DB), then M / Q
 *      (checked by the CP against the sizes the CPU side reported);
 *   4. the other reads (they see the written values: Application Protocol §6.17).
 * A failing job stops the sequence with exception 04. Only a CPU side that stops
 * answering between a write and a later job (timeout) leaves a write done behind an
 * exception.
 *
 * Limits (registers, quantity.c): FC23 read 1..125, write 1..121 (Modbus Application
 * Protocol); with 32-bit registers (int32 / float range, 4 bytes each) read 1..62,
 * write 1..60. Scanner requests (16-bit operands) have the FC03 / FC16 limits of the
 * framing, checked by the function-code table. */
#include <stddef.h>
#include <string.h>

#include "modcp/quantity.h"
#include "pdu_internal.h"
#include "ext_internal.h"
#include "map_internal.h"
#include "params_internal.h"
#include "quantity_internal.h"

/* The phases of a job sequence (modcp_pdu_x_t.phase), in order. */
#define PH_EARLY 0u
#define PH_CHECK 1u
#define PH_WRITE 2u
#define PH_READ 3u

/* The read data's place in the reply: after fc and byte count. */
#define ROFF 2u

/* Operand k of the write part (write) or the read part. */
/* Out of line (also under LTO): the sequence's loop and the early-read test call it. */
__attribute__((noinline)) static modcp_event_t operand(const modcp_pdu_t *s,
                                                       const modcp_pdu_env_t *env, bool write,
                                                       uint16_t k, modcp_operand_t *o)
{
    const modcp_pdu_x_t *x = &s->x;
    if (write ? !x->wscan : !x->rscan) {
        *o = write ? x->wdir : x->rdir;
        return MODCP_EV_NONE;
    }
    const uint16_t start = write ? x->wstart : x->rstart;
    return modcp_scan_map(env->p, env->areas, (uint16_t)(start + k), write, o);
}

static uint16_t write_jobs(const modcp_pdu_x_t *x)
{
    return x->wop == 0u ? 0u : (x->wscan ? x->wqty : 1u);
}

static uint16_t read_jobs(const modcp_pdu_x_t *x)
{
    return x->rqty == 0u ? 0u : (x->rscan ? x->rqty : 1u);
}

static bool overlap(const modcp_operand_t *a, const modcp_operand_t *b)
{
    return a->area == b->area && a->db == b->db &&
           (uint32_t)a->offset < (uint32_t)b->offset + b->count &&
           (uint32_t)b->offset < (uint32_t)a->offset + a->count;
}

/* A DB read of FC23 that no write of the request touches runs before the writes: its
 * data are the same before and after them, and its job checks the DB. */
static bool early_read(const modcp_pdu_t *s, const modcp_pdu_env_t *env,
                       const modcp_operand_t *o)
{
    const modcp_pdu_x_t *x = &s->x;
    if (x->early == 0u || o->area != (uint8_t)MODCP_AREA_DB) {
        return false;
    }
    for (uint16_t k = 0; k < write_jobs(x); k++) {
        modcp_operand_t w;
        if (operand(s, env, true, k, &w) != MODCP_EV_NONE || overlap(o, &w)) {
            return false;
        }
    }
    return true;
}

/* Needs operand o (of the write part: write) a check read before the first write?
 * The writes run DB operands first, so the first DB write checks itself; the other
 * areas are checked by the CP against the sizes the CPU side reported. */
static bool needs_check(modcp_pdu_x_t *x, bool write, const modcp_operand_t *o)
{
    if (o->area != (uint8_t)MODCP_AREA_DB) {
        return false;
    }
    if (write && x->wfirst == 0u) {
        x->wfirst = 1;
        return false;
    }
    if (!write && !x->wscan && x->wdir.area == (uint8_t)MODCP_AREA_DB && o->db == x->wdir.db &&
        (uint32_t)o->offset + o->count <= (uint32_t)x->wdir.offset + x->wdir.count) {
        return false; /* the write job proves the DB at least this long */
    }
    return true;
}

/* The read job of operand o (read part, entry k) into its place in the reply. */
static modcp_pdu_action_t read_job(modcp_pdu_t *s, const modcp_operand_t *o, uint16_t k,
                                   uint8_t *pdu)
{
    const modcp_pdu_x_t *x = &s->x;
    uint16_t n = o->count; /* direct: all of it */
    uint16_t off = ROFF;
    uint16_t room = (uint16_t)(x->cap - ROFF);
    const bool scan = x->rscan;
    if (scan) { /* scanner: the entry's word */
        n = 2u;
        off = (uint16_t)(off + 2u * k);
        room = 2u;
    }
    return modcp_pdu_job(s, MODCP_JOB_READ, o, n, NULL, pdu + off, room);
}

/* The steps of the phase: early / other reads: the read part; check reads: the write
 * part, then the read part; writes: the write part twice (DB operands first, in
 * request order, then the others). */
static uint16_t phase_steps(const modcp_pdu_x_t *x, uint16_t nw, uint16_t nr)
{
    uint16_t n = nr;
    if (x->phase == PH_CHECK) {
        n = (uint16_t)(nw + nr);
    } else if (x->phase == PH_WRITE) {
        n = (uint16_t)(2u * nw);
    } else {
        /* early reads, other reads: the read part */
    }
    return n;
}

/* A write step: operand o (entry k) in its pass (second: the non-DB operands). */
static bool write_step(modcp_pdu_t *s, const modcp_operand_t *o, uint16_t k, bool second,
                       uint8_t *pdu, modcp_pdu_action_t *a)
{
    const modcp_pdu_x_t *x = &s->x;
    if ((o->area == (uint8_t)MODCP_AREA_DB) == second) {
        return false; /* not in this pass */
    }
    /* direct: the whole data; scanner: the entry's word, or FC22's masks */
    uint16_t len = x->wlen;
    uint16_t off = x->woff;
    const bool scan = x->wscan;
    if (scan) {
        if (x->wop == MODCP_JOB_MASKWRITE) {
            len = 4u;
        } else {
            len = 2u;
            off = (uint16_t)(off + (2u * k));
        }
    }
    *a = modcp_pdu_job(s, x->wop, o, len, pdu + off, NULL, 0);
    return true;
}

/* Step x->idx of the phase: true with its job (or the exception) in *a, false when the
 * step has none. */
static bool seq_step(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu, uint16_t nw,
                     modcp_pdu_action_t *a)
{
    modcp_pdu_x_t *x = &s->x;
    const uint16_t i = x->idx;
    x->idx++;
    const bool second = ((x->phase == PH_CHECK) || (x->phase == PH_WRITE)) && (i >= nw);
    const bool write = (x->phase == PH_WRITE) || ((x->phase == PH_CHECK) && !second);
    const uint16_t k = second ? (uint16_t)(i - nw) : i;
    modcp_operand_t o;
    const modcp_event_t ev = operand(s, env, write, k, &o);
    if (ev != MODCP_EV_NONE) {
        *a = modcp_pdu_map_err(s, ev);
        return true;
    }
    if (o.area == (uint8_t)MODCP_AREA_NONE) {
        if (x->phase == PH_READ) {
            uint8_t *r = &pdu[ROFF + (2u * k)];
            r[0] = 0; /* unused scanner entry: reads 0000 */
            r[1] = 0;
        }
        return false; /* (writes: the value is discarded) */
    }
    if (x->phase == PH_WRITE) {
        return write_step(s, &o, k, second, pdu, a);
    }
    const bool early = !write && early_read(s, env, &o);
    if (x->phase != PH_CHECK) { /* early reads: the early ones; other reads: the rest */
        if ((x->phase == PH_EARLY) ? !early : early) {
            return false;
        }
        *a = read_job(s, &o, k, pdu);
        return true;
    }
    if (early || !needs_check(x, write, &o)) {
        return false;
    }
    o.offset = (uint16_t)(o.offset + o.count - 2u); /* check read: the last word */
    o.count = 2;
    o.bit = 0;
    *a = modcp_pdu_job(s, MODCP_JOB_READ, &o, 2, NULL, x->probe, sizeof x->probe);
    return true;
}

modcp_pdu_action_t modcp_pdu_seq_next(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu)
{
    modcp_pdu_x_t *x = &s->x;
    const uint16_t nw = write_jobs(x);
    const uint16_t nr = read_jobs(x);
    modcp_pdu_action_t a = MODCP_PDU_DONE;
    bool more = true;
    while (more) {
        if (x->idx < phase_steps(x, nw, nr)) {
            more = !seq_step(s, env, pdu, nw, &a);
        } else if (x->phase == PH_READ) {
            more = false; /* MODCP_PDU_DONE */
        } else { /* early reads -> check reads -> writes -> reads */
            x->phase = (nw == 0u) ? PH_READ : (uint8_t)(x->phase + 1u);
            x->idx = 0;
        }
    }
    return a;
}

/* Start the sequence described in s->x. */
static modcp_pdu_action_t start(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                uint16_t cap)
{
    modcp_pdu_x_t *x = &s->x;
    x->seq = 1; /* completions come to modcp_pdu_seq_next() */
    x->cap = cap;
    x->phase = PH_CHECK;
    if (write_jobs(x) == 0u) {
        x->phase = PH_READ;
    } else if (x->early != 0u) {
        x->phase = PH_EARLY;
    } else {
        /* writes without early reads: check reads first */
    }
    return modcp_pdu_seq_next(s, env, pdu);
}

/* The sequence's state (s->x from phase on: not cleared by pdu.c) starts at zero. */
static void seq_clear(modcp_pdu_t *s)
{
    (void)memset(&s->x.phase, 0, sizeof s->x - (size_t)offsetof(modcp_pdu_x_t, phase));
}

/* The write part (write) or the read part of s->x checked and mapped: through the
 * scanner when it touches it (wscan / rscan), else directly with the rules of fc (the
 * operand's width noted in the mapping cleared: the write data / reply have it). */
static modcp_event_t map_part(modcp_pdu_t *s, const modcp_pdu_env_t *env, bool write,
                              uint8_t fc)
{
    modcp_pdu_x_t *x = &s->x;
    const uint16_t start = write ? x->wstart : x->rstart;
    const uint16_t qty = write ? x->wqty : x->rqty;
    const bool scan = write ? x->wscan : x->rscan;
    if (scan) {
        return modcp_scan_check(env->p, env->areas, start, qty, write);
    }
    modcp_operand_t *o = write ? &x->wdir : &x->rdir;
    o->bit = modcp_regs32_kind(env->p, fc, start); /* fc 03, 22, 23; qty >= 1 */
    const modcp_event_t ev = modcp_map_regs_kind(env->p, env->areas, fc, start, qty, o);
    o->bit = 0;
    return ev;
}

/* ---- scanner: FC03, FC06, FC16 on scanner addresses ------------------------------- */

modcp_pdu_action_t modcp_pdu_scan(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)out_len;
    seq_clear(s);
    modcp_pdu_x_t *x = &s->x;
    const bool write = s->fc != 0x03u; /* FC06 / FC16 */
    if (write) { /* the form is checked (pdu.c): the data end the request */
        x->woff = (uint16_t)(len - 2u * s->qty); /* FC06: 3, FC16: 6 */
        x->wop = MODCP_JOB_WRITE;
        x->wscan = true;
        x->wstart = s->addr;
        x->wqty = s->qty;
        x->echo = 5; /* FC06: the whole request; FC16: fc, start, quantity */
    } else {
        x->rscan = true;
        x->rstart = s->addr;
        x->rqty = s->qty;
        x->rbytes = (uint16_t)(2u * s->qty);
    }
    modcp_event_t ev = map_part(s, env, write, s->fc);
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_map_err(s, ev);
    }
    if (!write && 2u + x->rbytes > cap) {
        return modcp_pdu_err(s, MODCP_EV_JOB_LENGTH, MODCP_EXC_DEVICE_FAILURE);
    }
    return start(s, env, pdu, cap);
}

/* ---- FC22 mask write register ----------------------------------------------------- */

modcp_pdu_action_t modcp_pdu_fc22(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)len;
    (void)out_len;
    seq_clear(s);
    modcp_pdu_x_t *x = &s->x;
    s->addr = modcp_get16(pdu + 1);
    s->qty = 1;
    x->wstart = s->addr;
    x->wqty = 1;
    x->wscan = modcp_scan_touches(env->p, s->addr, 1u);
    x->wlen = 4; /* direct: and mask, or mask */
    modcp_event_t ev = map_part(s, env, true, s->fc);
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_map_err(s, ev);
    }
    x->wop = MODCP_JOB_MASKWRITE;
    x->woff = 3;
    x->echo = 7; /* the request, unchanged */
    return start(s, env, pdu, cap);
}

/* ---- FC23 read/write multiple registers ----------------------------------------- */

modcp_pdu_action_t modcp_pdu_fc23(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)out_len;
    seq_clear(s);
    modcp_pdu_x_t *x = &s->x;
    x->rstart = modcp_get16(pdu + 1);
    x->rqty = modcp_get16(pdu + 3);
    x->wstart = modcp_get16(pdu + 5);
    x->wqty = modcp_get16(pdu + 7);
    const uint8_t bc = pdu[9];
    s->addr = x->rstart;
    s->qty = x->rqty;
    x->rscan = modcp_scan_touches(env->p, x->rstart, x->rqty);
    x->wscan = modcp_scan_touches(env->p, x->wstart, x->wqty);
    /* quantities and byte count (exception 03) before any address (02) */
    const uint8_t rk = x->rscan ? 0u : modcp_regs32_kind(env->p, 3u, x->rstart);
    const uint8_t wk = x->wscan ? 0u : modcp_regs32_kind(env->p, 23u, x->wstart);
    if (x->rqty < 1u || x->rqty > modcp_qty_limit(env->p, MODCP_QLIM_RW_READ, rk) ||
        x->wqty < 1u || x->wqty > modcp_qty_limit(env->p, MODCP_QLIM_RW_WRITE, wk)) {
        return modcp_pdu_err(s, MODCP_EV_QUANTITY, MODCP_EXC_ILLEGAL_VALUE);
    }
    if (bc != (uint32_t)x->wqty * modcp_reg_bytes(wk) || len != 10u + bc) {
        return modcp_pdu_err(s, MODCP_EV_BYTE_COUNT, MODCP_EXC_ILLEGAL_VALUE);
    }
    /* both ranges are checked before anything is written; the read range is mapped
     * like FC03's (read rules, no write limits) */
    modcp_event_t ev = map_part(s, env, true, 23u);
    if (ev == MODCP_EV_NONE) {
        ev = map_part(s, env, false, 3u);
    }
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_map_err(s, ev);
    }
    x->rbytes = x->rscan ? (uint16_t)(2u * x->rqty) : x->rdir.count;
    if (x->rbytes > 250u || 2u + (uint32_t)x->rbytes > cap) {
        return modcp_pdu_err(s, MODCP_EV_QUANTITY, MODCP_EXC_ILLEGAL_VALUE);
    }
    /* the CPU job limit would refuse the read after the write: refuse both now */
    const uint16_t limit = modcp_params_job_limit(env->p);
    if ((!x->wscan && bc > limit) || (!x->rscan && x->rbytes > limit)) {
        return modcp_pdu_err(s, MODCP_EV_JOB_LENGTH, MODCP_EXC_DEVICE_FAILURE);
    }
    x->wop = MODCP_JOB_WRITE;
    x->woff = 10;
    x->wlen = bc;
    if (2u + (uint32_t)x->rbytes + bc <= cap) {
        /* room for both: the write data move to the buffer's end, so reads that no
         * write touches can land in the reply before the writes run */
        (void)memmove(pdu + cap - bc, pdu + 10, bc);
        x->woff = (uint16_t)(cap - bc);
        x->early = 1;
    }
    return start(s, env, pdu, cap);
}
