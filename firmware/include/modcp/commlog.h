/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the Modbus communication event log, event counter, diagnostic register and
 * listen-only state (Modbus Application Protocol V1.1b3 §6.9 FC11, §6.10 FC12, §6.8
 * FC08; Modbus over Serial Line V1.02 §6.1). Part of the diagnostics store
 * (modcp_diag_t.comm); the FC08 / FC11 / FC12 handlers read it.
 *
 * Event bytes (FC12), newest first, at most MODCP_COMM_LOG_LEN:
 *   receive event  1xxx xxxx: 0x80 | 0x02 communication error | 0x10 character overrun
 *                  | 0x20 in listen-only mode | 0x40 broadcast received
 *   send event     01xx xxxx: 0x40 | 0x01 exception 1..3 sent | 0x02 exception 4
 *                  | 0x04 exception 5..6 | 0x08 exception 7 | 0x10 write timeout
 *                  | 0x20 in listen-only mode
 *   0x04           entered listen-only mode (FC08 sub 04)
 *   0x00           communication restart (FC08 sub 01; with FF00 the log is cleared
 *                  first, so the log then holds exactly this byte)
 *
 * Decisions of modcp (the specifications are silent):
 *  - A frame discarded for a CRC / LRC error or a character error (parity, framing,
 *    overrun, BREAK, t1.5) is logged as a receive event with the communication-error
 *    bit (0x82), since the CP cannot tell whom a damaged frame was for. The overrun
 *    bit goes with the frame that had the overrun (or, if that frame was already
 *    counted as damaged, with the next receive event).
 *  - Diagnostic register (FC08 sub 02): bit 0 a character overrun happened (latched,
 *    cleared by sub 0A, 01 and 14); bit 1 comm-loss supervision expired (live); bit 2
 *    the last CPU job timed out, the CPU side is not answering (live). */
/* Public for layout only: modcp_cp_t embeds modcp_comm_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/commlog_internal.h). */
#ifndef MODCP_COMMLOG_H
#define MODCP_COMMLOG_H

#include <stdbool.h>
#include <stdint.h>

#define MODCP_COMM_LOG_LEN 64u

#define MODCP_COMM_RX 0x80u
#define MODCP_COMM_RX_COMM_ERROR 0x02u
#define MODCP_COMM_RX_OVERRUN 0x10u
#define MODCP_COMM_RX_LISTEN 0x20u
#define MODCP_COMM_RX_BROADCAST 0x40u
#define MODCP_COMM_TX 0x40u
#define MODCP_COMM_TX_READ_EXC 0x01u /* exception 1..3 */
#define MODCP_COMM_TX_ABORT_EXC 0x02u /* exception 4 */
#define MODCP_COMM_TX_BUSY_EXC 0x04u /* exception 5..6 */
#define MODCP_COMM_TX_NAK_EXC 0x08u /* exception 7 */
#define MODCP_COMM_TX_WRITE_TIMEOUT 0x10u
#define MODCP_COMM_TX_LISTEN 0x20u
#define MODCP_COMM_LISTEN_ENTERED 0x04u
#define MODCP_COMM_RESTART 0x00u

/* Diagnostic register bits (FC08 sub 02). */
#define MODCP_DREG_OVERRUN 0x0001u /* latched */
#define MODCP_DREG_COMMLOSS 0x0002u /* live */
#define MODCP_DREG_CPU_STALLED 0x0004u /* live */

typedef struct {
    uint16_t event_count;              /* FC11: successful completions, wraps */
    uint8_t log[MODCP_COMM_LOG_LEN];   /* FC12: a ring, newest at log[log_head]; read
                                          it with modcp_comm_log_at() */
    uint8_t log_len;
    uint8_t log_head;
    uint16_t diag_reg;                 /* latched MODCP_DREG_* bits */
    bool listen_only;                  /* FC08 sub 04 until sub 01 */
    bool overrun_pending;              /* overrun not yet reported in an event byte */
} modcp_comm_t;

#endif
