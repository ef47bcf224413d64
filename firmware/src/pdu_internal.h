/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — internal interface of the PDU engine: the function-code table's handler
 * type, the named exception codes, and the handlers the table (pdu.c) points at.
 * Not for other modules.
 *
 * Call structure (no cycles): pdu.c (table, dispatch, exceptions, reply encoding,
 * end-of-request accounting) calls the handlers in pdu_rw.c (manual set), pdu_ext.c
 * (FC22, FC23, scanner: job sequences), serial_diag.c (FC08 extended, FC11, FC12) and
 * devid.c (FC17, FC43). A handler never calls back into pdu.c: it returns
 *   MODCP_PDU_JOB    s->job (and wdata / rdata) set up: run it;
 *   MODCP_PDU_REPLY  a CP-local reply is ready in place, length in *out_len;
 *   MODCP_PDU_DONE   nothing (more) to run: pdu.c encodes the reply described by
 *                    s->x.echo / s->x.rbytes (s->bits: align a bit string);
 *   MODCP_PDU_FAIL   refused: pdu.c records s->err and answers exception s->x.exc
 *                    (modcp_pdu_err below), or stays silent for a broadcast. */
#ifndef MODCP_PDU_INTERNAL_H
#define MODCP_PDU_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/pdu.h"
#include "fc_table_internal.h"

/* Modbus exception codes ([MB-APP] §7); unsigned macros, not an anonymous
 * enum (MISRA rules 5.7 and 10.4, docs/misra.md). */
#define MODCP_EXC_NONE 0u             /* s->x.exc: no exception (yet) */
#define MODCP_EXC_OF_MAP 0u           /* modcp_pdu_map_err: the mapping event's code */
#define MODCP_EXC_ILLEGAL_FUNCTION 1u
#define MODCP_EXC_ILLEGAL_ADDRESS 2u
#define MODCP_EXC_ILLEGAL_VALUE 3u
#define MODCP_EXC_DEVICE_FAILURE 4u
#define MODCP_EXC_ACKNOWLEDGE 5u
#define MODCP_EXC_BUSY 6u
#define MODCP_EXC_NAK 7u

/* The flags of a function-code table row (F_*, fc_table_internal.h) the handlers see
 * in s->fcflags. */
/* A handler of the function-code table: the request is pdu[0 .. len) (pdu[0] = fc),
 * its length already checked against the table's minimum / maximum, s->addr and
 * s->qty set for function codes with a quantity field (checked against the table's
 * limit class), cap bytes of room for the reply in place. */
typedef modcp_pdu_action_t (*modcp_pdu_handler_t)(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                                  uint8_t *pdu, uint16_t len, uint16_t cap,
                                                  uint16_t *out_len);

/* Bytes of modcp_pdu_t cleared for every request: fc .. x.rbytes (and x.seq). */
#if MODCP_WITH_EXTENDED
#define MODCP_PDU_CLEARED ((size_t)offsetof(modcp_pdu_t, x) + (size_t)offsetof(modcp_pdu_x_t, phase))
#else
#define MODCP_PDU_CLEARED ((size_t)offsetof(modcp_pdu_t, x) + sizeof(modcp_pdu_x_t))
#endif

/* Refuse the request with event ev and exception exc (MODCP_EXC_*). */
static inline modcp_pdu_action_t modcp_pdu_err(modcp_pdu_t *s, modcp_event_t ev, uint8_t exc)
{
    s->err = ev;
    s->x.exc = exc;
    return MODCP_PDU_FAIL;
}

/* Refuse the request with event ev of the mapping (map.c, scanner.c); pdu.c answers
 * with the exception of the event's row, modcp_event_exception() ((08)32H: 03; (0E)39H,
 * (0E)50H..55H: 02). */
static inline modcp_pdu_action_t modcp_pdu_map_err(modcp_pdu_t *s, modcp_event_t ev)
{
    return modcp_pdu_err(s, ev, MODCP_EXC_OF_MAP);
}

static inline uint16_t modcp_get16(const uint8_t *p)
{
    return (uint16_t)(((unsigned)p[0] << 8) | p[1]);
}

/* Set up one job: op on operand o, len data bytes (written from wdata, or read into
 * rdata with rcap bytes of room). */
static inline modcp_pdu_action_t modcp_pdu_job(modcp_pdu_t *s, uint8_t op,
                                               const modcp_operand_t *o, uint16_t len,
                                               const uint8_t *wdata, uint8_t *rdata,
                                               uint16_t rcap)
{
    s->job.op = op;
    s->job.opnd = *o;
    s->job.len = len;
    s->wdata = wdata;
    s->rdata = rdata;
    s->rcap = rcap;
    return MODCP_PDU_JOB;
}

/* pdu_rw.c: the manual's function set ([RTU-2003] §6): FC01 / 02 / 05 / 15 and FC03 / 04 /
 * 06 / 16 (one handler, told apart by s->fc and s->fcflags), FC08 sub 0000. */
modcp_pdu_action_t modcp_pdu_rw(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                uint16_t len, uint16_t cap, uint16_t *out_len);
/* The FC01 / FC02 reply data read from byte boundaries: drop `shift` low bits of the
 * first byte, keep qty bits, clear the unused high bits of the last byte. */
void modcp_pdu_align_bits(uint8_t *d, uint8_t shift, uint16_t qty);
modcp_pdu_action_t modcp_pdu_diag0(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                   uint16_t len, uint16_t cap, uint16_t *out_len);

/* pdu_ext.c: FC22, FC23 and FC03 / 06 / 16 on scanner addresses (job sequences). */
modcp_pdu_action_t modcp_pdu_scan(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc22(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc23(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
/* The job of a sequence (s->x.seq != 0) succeeded: the next job, or DONE / FAIL. */
modcp_pdu_action_t modcp_pdu_seq_next(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu);

/* serial_diag.c: FC08 (extended), FC11, FC12. */
modcp_pdu_action_t modcp_pdu_fc08(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc11(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc12(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);

/* devid.c: FC17, FC43/14. */
modcp_pdu_action_t modcp_pdu_fc17(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);
modcp_pdu_action_t modcp_pdu_fc43(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len);

/* Moved from modcp/pdu.h: the core's own interface. */
/* Handle a request PDU (pdu[0] = function code) received for addr (0 = broadcast).
 * The buffer has room for cap bytes of reply PDU; replies are written in place. */
modcp_pdu_action_t modcp_pdu_request(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t addr,
                                     uint8_t *pdu, uint16_t len, uint16_t cap, uint16_t *out_len);
/* Built for speed (-O2) with the extended set, modcp_pdu_complete accounts for the
 * request it ends itself (modcp_pdu_finished's body inline there: no call of its own);
 * built for size (-Os) the CP calls modcp_pdu_finished for every request (one copy, and
 * modcp_pdu_complete needs no stack frame: 17 instructions less per FC05 / FC06). */
#if MODCP_WITH_EXTENDED && !defined(__OPTIMIZE_SIZE__)
#define MODCP_PDU_COMPLETE_FINISHES 1
#else
#define MODCP_PDU_COMPLETE_FINISHES 0
#endif
/* The job started for the current request finished with ev (NONE = success; rlen
 * data bytes landed at s->rdata). Encodes the reply or exception 04, or starts the next
 * job (MODCP_PDU_JOB); with MODCP_PDU_COMPLETE_FINISHES a request that ends here is
 * accounted (modcp_pdu_finished). */
modcp_pdu_action_t modcp_pdu_complete(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                      modcp_event_t ev, uint8_t *pdu, uint16_t *out_len,
                                      uint32_t now_us);
/* Encode an exception reply for fc with code; returns the PDU length (2). */
uint16_t modcp_pdu_exception(uint8_t *pdu, uint8_t fc, uint8_t code);
/* The request ended with action a (REPLY or NO_REPLY): FC11 event counter, FC12 send
 * event, comm-loss supervision, FC08 sub 01 / 0A effects. Once per request, right
 * before the reply goes out: the CP calls it (with MODCP_PDU_COMPLETE_FINISHES only for
 * a request that ends without a job; built with the extended set only). */
void modcp_pdu_finished(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_pdu_action_t a,
                        uint32_t now_us);

#endif
