/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the extended function set (docs/extended-functions.md, function set `extended`):
 *  - FC08 serial-line diagnostics, FC11, FC12 (serial_diag.c; log in commlog.h)
 *  - FC17 report slave ID, FC43/14 read device identification (devid.c)
 *  - FC22 mask write register, FC23 read/write multiple registers (pdu_ext.c)
 *  - the indirection scanner (scanner.c): scan_count consecutive holding registers
 *    from scan_start, each pointing at a word operand (MW, IW, QW, DBn.DBWm, T, C)
 *  - comm-loss supervision (commloss.c)
 * The PDU engine's function-code table (pdu.c) hands these requests to their
 * handlers; the CP (cp.c) keeps the persistent state below, reports every finished
 * request (modcp_pdu_finished) and polls the supervision with the time
 * (modcp_commloss_poll).
 * docs/extended-functions.md has every frame and every decision. */
/* Public for layout only: modcp_cp_t embeds modcp_ext_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/ext_internal.h). */
#ifndef MODCP_EXT_H
#define MODCP_EXT_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/diag.h"
#include "modcp/events.h"
#include "modcp/features.h"
#include "modcp/map.h"
#include "modcp/params.h"

#define MODCP_ASCII_DELIMITER_DEFAULT 0x0Au /* LF */

/* Persistent state of the extended set, one per CP (modcp_cp_t.ext). */
typedef struct {
    /* comm-loss supervision */
    bool cl_armed;       /* an accepted write for our address was seen */
    bool cl_lost;        /* expired: MODCP_CPST_COMMLOSS set */
    uint32_t cl_last_us; /* last valid request for our address */
    uint32_t cl_reset_seen; /* backplane commloss_reset as last seen (latched mode) */
    /* FC08 sub 03: end-of-frame character of ASCII framing (replaces LF); the CP takes
     * it for the link with modcp_ext_take_delimiter when it changed (sub 03, sub 01) */
    uint8_t ascii_delimiter;
    bool delimiter_changed;
    /* the last CPU job timed out and none has succeeded since (FC17 run indicator) */
    bool cpu_stalled;
} modcp_ext_t;

/* Per-request state of the PDU engine beyond the request itself (modcp_pdu_t.x): the
 * reply's description and the exception for both sets, cleared for every request (up
 * to seq); the job sequence of the extended set (FC22, FC23, scanner) only with it,
 * its fields after seq cleared by the handlers that start one (pdu_ext.c). */
typedef struct {
    uint8_t exc;     /* exception code detected for this request (0 = none) */
#if MODCP_WITH_EXTENDED
    /* the end-of-request accounting (modcp_pdu_finished) */
    uint8_t quiet;   /* listen-only: not processed, nothing more to account */
    uint8_t timeout; /* a CPU job of this request timed out */
    uint8_t after;   /* action after the reply: MODCP_X_AFTER_* */
#endif
    uint16_t echo;   /* reply = the first `echo` request bytes; 0: read reply */
    uint16_t rbytes; /* read data bytes in the reply */
#if MODCP_WITH_EXTENDED
    /* job sequence (scanner, FC22, FC23); seq 0: a single job (manual set) */
    uint8_t seq;
    /* from here on: cleared by the handlers of pdu_ext.c */
    uint8_t phase;   /* early reads, check reads, writes, reads (pdu_ext.c) */
    uint8_t idx;
    uint8_t early;   /* FC23: write data moved to the buffer's end, early reads allowed */
    uint8_t wfirst;  /* check reads: the first DB write was passed */
    uint8_t probe[2]; /* data of a check read (discarded) */
    uint8_t wop;     /* job op of the write part, 0 = none */
    bool wscan;      /* write part through the scanner */
    bool rscan;      /* read part through the scanner */
    uint16_t wstart, wqty, rstart, rqty;
    uint16_t woff;   /* write data: offset in the PDU buffer */
    uint16_t wlen;   /* direct write: data bytes */
    uint16_t cap;    /* PDU buffer capacity */
    modcp_operand_t wdir; /* write part, direct mapping */
    modcp_operand_t rdir; /* read part, direct mapping */
#endif
} modcp_pdu_x_t;

/* modcp_pdu_x_t.after: what the FC08 reply leaves to do once it is out. */
#define MODCP_X_AFTER_NONE 0u
#define MODCP_X_AFTER_CLEAR 1u         /* FC08 sub 0A: counters, event counter, diag register */
#define MODCP_X_AFTER_RESTART 2u       /* FC08 sub 01 data 0000: restart, keep the log */
#define MODCP_X_AFTER_RESTART_CLEAR 3u /* FC08 sub 01 data FF00: restart, clear the log */

/* ---- persistent state --------------------------------------------------------------- */

/* ---- comm-loss supervision (commloss.c) --------------------------------------------- */

/* ---- indirection scanner (scanner.c) ------------------------------------------------ */

#endif
