/* modcp — CP side of the backplane: turns a request into a job of 32-byte blocks,
 * waits for the CPU side's reply, times out; and receives the PARAMS / INIT messages
 * the CPU side sends (SPEC §6). Polled with the current time; no clock is read. */
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
    MODCP_JOBP_INIT,   /* an INIT message arrived: see init */
    MODCP_JOBP_PARAMS_START, /* MODCP_SHARED_PARAMS_BUFFER: a PARAMS record starts, its
                                first block waits in the ring, nothing is stored; free
                                msgbuf, then call modcp_job_params_grant() (reported on
                                every poll until then) */
} modcp_jobp_t;

typedef struct {
    modcp_backplane_t *bp;
    uint8_t state; /* modcp_jobst_t */
    uint8_t tag;   /* tag of the current / last job, 1..255 */
    uint8_t tx_seq;
    uint8_t rx_seq;
    bool rx_synced; /* rx_seq valid (first block seen) */
    modcp_bp_job_t hdr;
    bool hdr_sent;
    const uint8_t *wdata;
    uint16_t wpos;
    uint8_t *rbuf;
    uint16_t rcap;
    uint16_t rlen;      /* read data received so far / in total */
    uint16_t rexpect;   /* data bytes announced by the REPLY header */
    uint32_t t0_us;
    uint32_t timeout_us;
    modcp_event_t event; /* result of the last finished job */
    uint16_t error_nr;   /* FB ERROR_NR for (0E)57H */
    /* incoming PARAMS / INIT */
    uint8_t *msgbuf;
    uint16_t msgcap;
    uint16_t msglen;
    uint8_t msgkind;   /* kind being reassembled, 0 = none */
    bool msg_overflow;
#if MODCP_SHARED_PARAMS_BUFFER
    bool msg_granted;  /* the owner freed msgbuf for the PARAMS block ahead */
#endif
    modcp_bp_init_t init;
    uint32_t proto_errors; /* sequence / framing errors seen on the ring */
    uint32_t illegal_msgs; /* blocks of a kind the CPU side must not send (also in
                              proto_errors); the CP reports (0E)3CH, cpdiag.c */
} modcp_job_t;

void modcp_job_init(modcp_job_t *j, modcp_backplane_t *bp, uint8_t *msgbuf, uint16_t msgcap);

/* Start a job. hdr->len bytes of wdata are sent for WRITE / BITWRITE; for READ,
 * hdr->len bytes are expected back into rbuf (rcap >= hdr->len). limit is the CPU
 * transfer limit in bytes. Returns MODCP_EV_JOB_LENGTH when hdr->len > limit,
 * MODCP_EV_INTERNAL_SEND if a job is already running; else NONE. */
modcp_event_t modcp_job_start(modcp_job_t *j, const modcp_bp_job_t *hdr, const uint8_t *wdata,
                              uint8_t *rbuf, uint16_t rcap, uint16_t limit, uint32_t timeout_us,
                              uint32_t now_us);

/* Move blocks; detect completion and timeout ((0E)31H for READ/WRITE, (0E)3BH for
 * BITWRITE; the job's tag is then written to abort_tag). */
modcp_jobp_t modcp_job_poll(modcp_job_t *j, uint32_t now_us);

/* Push the current job's blocks into the free slots now (what modcp_job_poll does
 * last), without reading anything: the CP calls it right after modcp_job_start. */
void modcp_job_push(modcp_job_t *j);

/* Drop the current job without waiting (CP re-parameterised). */
void modcp_job_abort(modcp_job_t *j);

bool modcp_job_busy(const modcp_job_t *j);

#if MODCP_SHARED_PARAMS_BUFFER
/* After MODCP_JOBP_PARAMS_START: msgbuf is free, the PARAMS record may be stored. */
void modcp_job_params_grant(modcp_job_t *j);
#endif

/* Answer an INIT (NONE = ready). False if the ring is full (call again later). */
bool modcp_job_send_ack(modcp_job_t *j, modcp_event_t ev);

#endif
