/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CPU side's communication FB (FB 80 / FB 180 model, [RTU-2003] §4, [VIPA-341] §2).
 *
 * The user program calls modcp_fb_call() once per cycle. The FB
 *  - sends the parameter record (PARAMS) at its first call, like the CPU re-sending
 *    the CP parameters at every start;
 *  - on a rising edge of CP_START: clears its outputs (ERROR_NR / ERROR_INFO included:
 *    "a rising edge also clears the errors", [VIPA-341] FB table), records the real area
 *    sizes, sends INIT (preceded by PARAMS unless the CP acknowledged an INIT for this
 *    record before: an FB restart is no re-parameterisation, [RTU-2003] §4.2 step 4) and waits
 *    for INIT_ACK; retries (PARAMS + INIT) every retry interval
 *    while the CP answers "not ready" or does not answer, until START_TIME; then
 *    CP_START_OK, or CP_START_ERROR with ERROR_NR 2 / ERROR_INFO = the CP's event, and
 *    CP_START reset ([RTU-2003] §5.5: "CP_START is reset and CP_START_ERROR = 1"), so that the
 *    caller's next rising edge retries;
 *  - ERROR_NR / ERROR_INFO keep the last error (initialisation or job, [RTU-2003] §7.6) until
 *    the next rising edge of CP_START; the FB writes them into the caller's out only
 *    when they change (a new error, the edge's clearing, the first call), so the user
 *    program may clear them at any time and they stay cleared until the next error
 *    ([RTU-2003] §7.6, [RTU-2009] §11: "the user may also clear them");
 *  - executes jobs: reads and register writes against plcmem, FC05/15 bit writes by
 *    read-modify-write; sets CP_START_NDR for one call when a write job was executed.
 *
 * Data crosses the backplane once per 32-byte block: a write job's data blocks are
 * written from their slots straight into controller memory as they arrive, a read's
 * reply blocks are read from memory straight into their slots (no job buffer). Every
 * job is checked completely on its header, before anything is written.
 * Consistency: each block is consistent; the whole job is consistent when the FB
 * handles all of its blocks in one call (see docs/cpu-cp-interface.md). */
#ifndef MODCP_FB_H
#define MODCP_FB_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/plcmem.h"

#ifndef MODCP_FB_JOB_MAX
#define MODCP_FB_JOB_MAX 1024u /* the largest job the FB accepts (CP 341 transfer limit) */
#endif
#define MODCP_FB_RETRY_MS 200u /* init retry interval */

/* FB error numbers ([RTU-2003] §7.6). */
enum modcp_fb_error {
    MODCP_FB_ERR_NONE = 0,
    MODCP_FB_ERR_INIT = 2,       /* CP initialisation timeout or error */
    MODCP_FB_ERR_PROC_CODE = 10, /* illegal processing code */
    MODCP_FB_ERR_START = 11,     /* illegal start address */
    MODCP_FB_ERR_AMOUNT0 = 12,   /* amount = 0 */
    MODCP_FB_ERR_AMOUNT = 13,    /* amount too large */
    MODCP_FB_ERR_M_END = 14,
    MODCP_FB_ERR_Q_END = 15,
    MODCP_FB_ERR_T_END = 16,
    MODCP_FB_ERR_C_END = 17,
    MODCP_FB_ERR_AREA = 18, /* illegal memory area */
};

/* The FB's in/out parameters (CP_START is IN_OUT in the manual, [VIPA-341] FB table): the
 * caller keeps this struct from call to call, like the memory bit CP_START is kept in
 * (M180.0 in [RTU-2003] §5.4's example). */
typedef struct {
    bool cp_start; /* IN_OUT: a rising edge starts the initialisation; the FB resets it
                      (writes false) when the initialisation fails */
} modcp_fb_in_t;

typedef struct {
    bool cp_start_ok;
    bool cp_start_error;
    bool cp_start_ndr; /* a write job was executed in this call */
    uint16_t error_nr;
    uint16_t error_info;
} modcp_fb_out_t;

typedef enum {
    MODCP_FBST_STOPPED = 0, /* no init yet */
    MODCP_FBST_INIT_SEND,   /* (re)sending PARAMS + INIT */
    MODCP_FBST_INIT_WAIT,   /* waiting for INIT_ACK */
    MODCP_FBST_RUN,         /* initialised, executing jobs */
    MODCP_FBST_FAILED,      /* CP_START_ERROR */
} modcp_fbst_t;

typedef struct {
    modcp_backplane_t *bp;
    modcp_plcmem_t *mem;
    const uint8_t *record; /* parameter record handed to the CP */
    uint16_t record_len;
    uint16_t work_db; /* the FB's work area (instance DB number), 0 = none */
    uint32_t start_time_ms;
    /* state */
    uint8_t state; /* modcp_fbst_t */
    bool last_start;
    bool params_pending; /* PARAMS still to send */
    uint16_t params_pos;
    bool init_sent;
    bool cp_has_params; /* the CP acknowledged an INIT with this record's identity */
    uint32_t init_t0_ms;  /* CP_START edge */
    uint32_t retry_t0_ms; /* last attempt */
    modcp_fb_out_t out;
    bool err_changed; /* out.error_nr / error_info not yet written to the caller's out */
    uint8_t tx_seq, rx_seq;
    bool rx_synced;
    /* job being executed / reply being sent */
    modcp_bp_job_t job;
    uint8_t job_tag;
    bool job_active; /* header accepted, write data blocks being executed */
    uint16_t job_pos;  /* write data bytes executed so far */
    uint8_t *job_mem;  /* controller memory of the job's operand (I Q M DB bytes), NULL
                          for T / C: located once, on the header */
    bool reply_pending;
    modcp_bp_reply_t reply;
    uint16_t reply_pos; /* read data bytes sent so far */
    bool reply_hdr_sent;
    uint32_t jobs_done; /* jobs answered */
    modcp_event_t init_event; /* last event the CP answered INIT with (ERROR_INFO of 2) */
} modcp_fb_t;

/* CPU side: the FB on its backplane and controller memory, with the PARAMS record. */
void modcp_fb_init(modcp_fb_t *fb, modcp_backplane_t *bp, modcp_plcmem_t *mem,
                   const uint8_t *record, uint16_t record_len, uint16_t work_db,
                   uint32_t start_time_ms);

/* One call per CPU cycle. in may be NULL (CP_START false); in->cp_start is written
 * false in the call in which the initialisation fails. out (may be NULL) is the FB's
 * outputs, kept by the caller from call to call like an instance DB: CP_START_OK /
 * _ERROR / _NDR are written at every call, ERROR_NR / ERROR_INFO only when they
 * change in the FB (see above). */
void modcp_fb_call(modcp_fb_t *fb, modcp_fb_in_t *in, modcp_fb_out_t *out, uint32_t now_ms);

#endif
