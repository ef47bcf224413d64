/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of job.c (modcp/job.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_JOB_INTERNAL_H
#define MODCP_JOB_INTERNAL_H

#include "modcp/job.h"

/* modcp_job_t.new_errors: a block of a kind the CPU side must not send (JOB,
 * INIT_ACK); any other unexpected block (sequence gap, data without its header,
 * continuation without a start, bad length, short INIT). Each one counts in proto_errors
 * too. */
#define MODCP_JOB_ERR_PROTO 1u
#define MODCP_JOB_ERR_ILLEGAL 2u

/* j zeroed (inside the CP object, which modcp_cp_init clears). */
void modcp_job_init(modcp_job_t *j, modcp_backplane_t *bp, uint8_t *msgbuf, uint16_t msgcap);
/* The CPU transfer limit in bytes and the CPU side's time to answer, for every job
 * from now on (the CP's parameters: set when they are taken). */
void modcp_job_configure(modcp_job_t *j, uint16_t limit, uint32_t timeout_us);
/* Start a job and push its first blocks at once. *hdr is not copied: it must stay as it
 * is until the job ends (the CP passes its pdu.job). hdr->len bytes of wdata are sent for
 * WRITE / BITWRITE; for READ, hdr->len bytes are expected back into rbuf (rcap >=
 * hdr->len). Returns MODCP_EV_JOB_LENGTH when hdr->len is above the limit
 * (modcp_job_configure), MODCP_EV_INTERNAL_SEND if a job is already running; else NONE. */
modcp_event_t modcp_job_start(modcp_job_t *j, const modcp_bp_job_t *hdr, const uint8_t *wdata,
                              uint8_t *rbuf, uint16_t rcap, uint32_t now_us);
/* Move blocks; detect completion and timeout ((0E)31H for READ/WRITE, (0E)3BH for
 * BITWRITE; the job's tag is then written to abort_tag). For MODCP_JOBP_INIT the INIT
 * payload is decoded into *init (the caller's; untouched otherwise). */
modcp_jobp_t modcp_job_poll(modcp_job_t *j, uint32_t now_us, modcp_bp_init_t *init);
/* Drop the current job without waiting (CP re-parameterised). */
void modcp_job_abort(modcp_job_t *j);
#if MODCP_SHARED_PARAMS_BUFFER
/* After MODCP_JOBP_PARAMS_START: msgbuf is free, the PARAMS record may be stored. */
void modcp_job_params_grant(modcp_job_t *j);
#endif
/* The MODCP_JOB_ERR_* kinds seen since the last call (new_errors), cleared (the CP's
 * poll, every time: inline). */
static inline uint8_t modcp_job_take_errors(modcp_job_t *j)
{
    const uint8_t e = j->new_errors;
    if (e != 0u) {
        j->new_errors = 0;
    }
    return e;
}
/* Answer an INIT (NONE = ready). False if the ring is full (call again later). */
bool modcp_job_send_ack(modcp_job_t *j, modcp_event_t ev);

#endif
