/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP's diagnostic channels towards the CPU side ([RTU-2003] §7, [VIPA-341] §8; docs/diagnostics.md),
 * besides the diagnostic buffer and the STATUS word that diag.c keeps:
 *
 *  - wire break: a BREAK reported in normal mode ((08)0DH) means "receive line to the
 *    partner interrupted". The state lasts until the next correctly received character
 *    (the line is back) or re-parameterisation; it lights SF. In interference
 *    suppression, and on two-wire RS485 outside a frame, BREAK is ignored ([RTU-2003] §2.2,
 *    §2.3, [RTU-2009] §5.6.5) and never a wire break.
 *  - diagnostic interrupt ([VIPA-341] §8.4), only with params.diag_irq (default off): 4 bytes,
 *      wire break on RxD          25 0C 02 00  (coming)
 *      parameterisation error     83 0C 00 00  (coming: a PARAMS record was rejected)
 *      fault gone                 00 0C 00 00  (going: the wire break ended, or valid
 *                                              parameters arrived; modcp extension,
 *                                              S7 convention: byte 0 bit 0 = module fault)
 *    Published in the status area as the last record plus a counter that advances with
 *    every interrupt; the CPU side reacts to a change of the counter. Only changes of
 *    state raise an interrupt (a record rejected again, e.g. at the FB's retries, does
 *    not). For a record that cannot be decoded at all (CRC, length) the setting of the
 *    last decodable record applies.
 *  - SYSTAT service ([RTU-2003] §7.4, read with SFB STATUS, clears it): the CPU side writes a
 *    request number to the backplane (modcp_bp_systat_request); the CP answers at its
 *    next poll by publishing the 16-byte SYSTAT image with that number and clearing
 *    SYSTAT (modcp_diag_read_systat). Events after that go into the fresh SYSTAT; no
 *    event is lost between image and clear.
 *  - backplane protocol errors seen by job.c become events (0E)30H / (0E)3CH. */
/* Public for layout only: modcp_cp_t embeds modcp_cpdiag_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/cpdiag_internal.h). */
#ifndef MODCP_CPDIAG_H
#define MODCP_CPDIAG_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/diag.h"

#define MODCP_DIAG_IRQ_BYTES 4u

/* From irq to systat_ack the fields are in the order of the CP status area
 * (modcp/backplane.h): cp.c publishes them as one copy (static asserts in cp.c). */
typedef struct {
    uint8_t irq[MODCP_DIAG_IRQ_BYTES]; /* last diagnostic interrupt record */
    uint32_t irq_count; /* interrupts raised since start */
    uint32_t systat_ack; /* number of the last SYSTAT request answered (the image given
                            with it is in the status area only: modcp_cpdiag_systat) */
    bool wire_break;    /* BREAK in normal mode, until the next good character */
    bool param_error;   /* the last PARAMS record was rejected */
    bool irq_enabled;   /* params.diag_irq of the last decodable record */
} modcp_cpdiag_t;

#endif
