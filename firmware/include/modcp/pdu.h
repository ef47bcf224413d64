/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — PDU engine: decode and validate requests, decide between an immediate reply
 * (FC08, exceptions), a CPU job, or silence (broadcast); encode replies. */
/* Public for layout only: modcp_cp_t embeds modcp_pdu_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/pdu_internal.h). */
#ifndef MODCP_PDU_H
#define MODCP_PDU_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/diag.h"
#include "modcp/ext.h"
#include "modcp/features.h"
#include "modcp/map.h"
#include "modcp/params.h"

typedef enum {
    MODCP_PDU_NO_REPLY = 0, /* nothing to send (broadcast, silent discard) */
    MODCP_PDU_REPLY,        /* reply PDU ready in place, length in *out_len */
    MODCP_PDU_JOB,          /* start the job in s->job (see wdata / rdata) */
    /* inside the engine only (pdu_internal.h), never returned to the caller: */
    MODCP_PDU_FAIL,         /* a handler refused the request: s->err, s->x.exc */
    MODCP_PDU_DONE,         /* all jobs done: encode the reply s->x describes */
} modcp_pdu_action_t;

/* What the engine reads from the CP. */
typedef struct {
    const modcp_params_t *p;
    const modcp_areas_t *areas;
    modcp_diag_t *diag;
    bool fb_ready; /* CPU side initialised */
#if MODCP_WITH_EXTENDED
    modcp_ext_t *ext; /* extended set: persistent state (may be NULL) */
#endif
} modcp_pdu_env_t;

typedef struct {
    /* the request in progress; fc .. x's head are cleared for every request
       (modcp_pdu_request: MODCP_PDU_CLEARED bytes, pdu_internal.h), with job.op */
    uint8_t fc;
    uint8_t fcflags;     /* the function-code table's flags of fc (pdu.c) */
    bool broadcast;
    bool same;           /* the reply is the request's PDU, unchanged (FC05 / FC06 echo:
                            the job reads nothing into the buffer); cleared by an
                            exception. The link may send the request's frame as it is */
    uint8_t bits;        /* FC01/02 on I / Q / M: the read data are a bit string to align,
                            1 + the offset of the first bit in the first byte read; 0: no */
    uint8_t r32_kind;    /* 32-bit scheme: modcp_r32_kind_t + 1, 0 = 16-bit */
    modcp_pdu_x_t x;     /* reply description (echo / rbytes), exception, job sequence */
    /* set before use */
    uint16_t addr;
    uint16_t qty;
    modcp_event_t err;   /* the event of a refused request (MODCP_PDU_FAIL) */
    uint16_t rcap;
    modcp_bp_job_t job;  /* the job to run for MODCP_PDU_JOB (op: 0 = none yet) */
    const uint8_t *wdata; /* job write data (inside the request) */
    uint8_t *rdata;      /* where the job's read data must land (inside the PDU buffer) */
} modcp_pdu_t;

#endif
