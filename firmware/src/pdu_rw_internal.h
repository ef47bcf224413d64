/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the handler of reads and writes of bits and registers (pdu_rw.c's
 * modcp_pdu_rw) as an inline function: the one source of that handler. pdu_rw.c builds
 * modcp_pdu_rw from it (the function-code table's handler, the one copy built for
 * size); built for speed, pdu.c's dispatch inlines it too (no call through the table,
 * no stack frame of its own per request). Internal to the core. */
#ifndef MODCP_PDU_RW_INTERNAL_H
#define MODCP_PDU_RW_INTERNAL_H

#include <stddef.h>

#include "modcp/quantity.h"
#include "inline_internal.h"
#include "pdu_internal.h"
#include "map_internal.h"
#include "quantity_internal.h"

/* The job of a handler: op on the operand its mapping left in s->job.opnd, len data
 * bytes (written from wdata, or read into rdata with rcap bytes of room). */
static inline modcp_pdu_action_t pdu_rw_job(modcp_pdu_t *s, uint8_t op, uint16_t len,
                                            const uint8_t *wdata, uint8_t *rdata, uint16_t rcap)
{
    s->job.op = op;
    s->job.len = len;
    s->wdata = wdata;
    s->rdata = rdata;
    s->rcap = rcap;
    return MODCP_PDU_JOB;
}

/* A read job whose data land after the reply's function code and byte count (the
 * reply is built in place: cap >= len >= 5). */
static inline modcp_pdu_action_t pdu_rw_read_job(modcp_pdu_t *s, uint16_t len, uint8_t *pdu,
                                                 uint16_t cap)
{
    return pdu_rw_job(s, MODCP_JOB_READ, len, NULL, pdu + 2, (uint16_t)(cap - 2u));
}

/* The mapping: inline in the builds for speed (-O2: the host; no call per request), the
 * one copy in map.c in the builds for size (-Os: the MCU images; with the extended set
 * the scanner, FC22 and FC23 call it too). */
#if defined(__GNUC__) && defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__)
#define MAP_BITS modcp_map_bits_in
#define MAP_REGS modcp_map_regs_in
#else
#define MAP_BITS modcp_map_bits_valid
#define MAP_REGS modcp_map_regs_kind
#endif

/* The function codes on bits (FC01, 02, 05, 15; the others of the handler: FC03, 04,
 * 06, 16), as bits of a mask by function code. */
#define BIT_FCS 0x8026u /* 1 << 1 | 1 << 2 | 1 << 5 | 1 << 15 */

/* FC01 / FC02 / FC03 / FC04 (read), FC05 / FC06 / FC15 / FC16 (write): map the bits or
 * registers s->addr .. + s->qty onto their operand (s->job.opnd; refused: s->err), then
 * one job. FC06's reply is the echo: 5 bytes, 7 for an int32 / float register of the
 * 32-bit scheme ([ASCII-32] §4.5). */
static MODCP_ALWAYS_INLINE modcp_pdu_action_t modcp_pdu_rw_inline(modcp_pdu_t *s,
                                                                  const modcp_pdu_env_t *env,
                                                                  uint8_t *pdu, uint16_t len,
                                                                  uint16_t cap)
{
    const uint8_t fc = s->fc;
    /* FC01 / 02 / 05 / 15 (fc: a row of the table, <= 16; FC16: bit 0, clear) */
    const bool bits = ((BIT_FCS >> (fc & 0x0Fu)) & 1u) != 0u;
    modcp_operand_t *o = &s->job.opnd;
    modcp_event_t ev;
    uint8_t op = MODCP_JOB_WRITE;
    if (bits) {
        if (fc == 0x05u) {
            const uint16_t value = modcp_get16(pdu + 3);
            if (value != 0xFF00u && value != 0x0000u) {
                return modcp_pdu_err(s, MODCP_EV_COIL_VALUE, MODCP_EXC_ILLEGAL_VALUE);
            }
        }
        ev = MAP_BITS(env->p, env->areas, fc, s->addr, s->qty, o);
        op = MODCP_JOB_BITWRITE;
    } else {
        /* the mapping's byte count is the request's: the width comes from the same range */
        o->bit = s->r32_kind;
        ev = MAP_REGS(env->p, env->areas, fc, s->addr, s->qty, o);
    }
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_map_err(s, ev);
    }
    if (!bits) {
        o->bit = 0; /* = s->r32_kind */
    }
    uint16_t n = o->count; /* registers: bytes */
    if ((s->fcflags & F_WRITE) != 0u) {
        uint16_t off = 6u; /* FC15 / FC16: the data after the byte count */
        s->x.echo = 5;     /* FC15 / FC16: fc, start, quantity */
        if (fc <= 0x06u) { /* FC05 / FC06: the request is the reply */
            off = 3u;
            s->x.echo = len;
            s->same = true;
        }
        if (bits) {
            /* FC05: the 1-bit job's data, the value's high byte, FF or 00 (its bit 0);
             * FC15: the byte count's bytes (the table's check) */
            n = fc == 0x05u ? 1u : pdu[5];
        }
        return pdu_rw_job(s, op, n, pdu + off, NULL, 0);
    }
    s->x.rbytes = n; /* registers: the bytes read */
    if (bits) {
        if (o->area == (uint8_t)MODCP_AREA_T || o->area == (uint8_t)MODCP_AREA_C) {
            n = (uint16_t)(n * 2u); /* whole words, high byte first */
            s->x.rbytes = n;
        } else {
            n = (uint16_t)((o->bit + s->qty + 7u) / 8u);
            s->bits = (uint8_t)(1u + o->bit); /* pdu.c aligns the bit string */
            s->x.rbytes = (uint16_t)((s->qty + 7u) / 8u);
            o->count = n; /* the job reads whole bytes */
            o->bit = 0;
        }
    }
    return pdu_rw_read_job(s, n, pdu, cap);
}

#endif
