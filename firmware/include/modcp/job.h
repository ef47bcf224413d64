/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — CP side of the backplane: turns a request into a job of 32-byte blocks,
 * waits for the CPU side's reply, times out; and receives the PARAMS / INIT messages
 * the CPU side sends (docs/cpu-cp-interface.md). Polled with the current time; no clock is read. */
/* Public for layout only: modcp_cp_t embeds modcp_job_t, so the type is here; its fields
 * are private and its functions (but modcp_job_busy) are internal
 * (firmware/src/job_internal.h). */
#ifndef MODCP_JOB_H
#define MODCP_JOB_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/features.h"

typedef enum {
    MODCP_JOBST_IDLE = 0,
    MODCP_JOBST_SENDING,   /* header / write data still going out */
    MODCP_JOBST_WAITING,   /* all sent, waiting for the REPLY header */
    MODCP_JOBST_RECEIVING, /* REPLY header in, data blocks coming */
} modcp_jobst_t;

/* What one call of modcp_job_poll() has to report (at most one thing per call;
 * call again until it returns MODCP_JOBP_NOTHING). */
typedef enum {
    MODCP_JOBP_NOTHING = 0,
    MODCP_JOBP_DONE,   /* current job finished: see event (NONE = success) and rlen */
    MODCP_JOBP_PARAMS, /* a complete PARAMS record is in msgbuf[0 .. msglen) */
    MODCP_JOBP_INIT,   /* an INIT message arrived: its payload is in the caller's *init
                          (modcp_job_poll; the job keeps nothing of it) */
    MODCP_JOBP_PARAMS_START, /* MODCP_SHARED_PARAMS_BUFFER: a PARAMS record starts, its
                                first block waits in the ring, nothing is stored; free
                                msgbuf, then call modcp_job_params_grant() (reported on
                                every poll until then) */
} modcp_jobp_t;

typedef struct {
    /* (the byte and 16-bit members first, then the pointers and 32-bit ones: no padding,
     * and all within reach of Thumb's 2-byte loads / stores, see modcp_cp_t) */
    uint8_t state; /* modcp_jobst_t */
    uint8_t tag;   /* tag of the current / last job, 1..255 */
    uint8_t tx_seq;
    uint8_t rx_seq;
    bool rx_synced; /* rx_seq valid (first block seen) */
    bool hdr_sent;
    uint16_t wpos;
    uint16_t rcap;
    uint16_t rlen;      /* read data received so far / in total */
    uint16_t rexpect;   /* data bytes announced by the REPLY header */
    uint16_t limit;     /* CPU transfer limit in bytes (modcp_job_configure) */
    modcp_event_t event; /* result of the last finished job */
    uint16_t error_nr;   /* FB ERROR_NR for (0E)57H */
    /* incoming PARAMS / INIT */
    uint16_t msgcap;
    uint16_t msglen;
    uint8_t msgkind;   /* kind being reassembled, 0 = none */
    bool msg_overflow;
#if MODCP_SHARED_PARAMS_BUFFER
    bool msg_granted;  /* the owner freed msgbuf for the PARAMS block ahead */
#endif
    uint8_t new_errors; /* MODCP_JOB_ERR_* seen on the ring since the owner cleared it
                           (the CP reports them, cpdiag.c, and clears it) */
    modcp_backplane_t *bp;
    const modcp_bp_job_t *hdr; /* the caller's (modcp_job_start; the CP's pdu.job): not
                                  copied, valid until the job ends */
    const uint8_t *wdata;
    uint8_t *rbuf;
    uint8_t *msgbuf;
    uint32_t t0_us;
    uint32_t timeout_us; /* the CPU side's time to answer a job (modcp_job_configure) */
    uint32_t proto_errors; /* sequence / framing errors seen on the ring (total) */
} modcp_job_t;

/* True while a job (a request's transfer to the CPU side) is running. */
bool modcp_job_busy(const modcp_job_t *j);

#endif
