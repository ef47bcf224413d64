/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of cpdiag.c (modcp/cpdiag.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_CPDIAG_INTERNAL_H
#define MODCP_CPDIAG_INTERNAL_H

#include "modcp/backplane.h"
#include "modcp/cpdiag.h"

void modcp_cpdiag_init(modcp_cpdiag_t *d);
/* A line error reached the link; reported: the link reports it ((08)0CH / (08)0DH), i.e.
 * it is enabled and in normal mode. */
void modcp_cpdiag_line_error(modcp_cpdiag_t *d, uint8_t line_errors, bool reported);
/* A character was received correctly. */
void modcp_cpdiag_good_char(modcp_cpdiag_t *d);
/* A PARAMS record was taken: ok (applied) or rejected; irq_setting: its diag_irq field
 * (-1 when the record could not be decoded). Clears the wire break. */
void modcp_cpdiag_params(modcp_cpdiag_t *d, bool ok, int irq_setting);
/* Backplane protocol errors seen by job.c since the last call (errors: its new_errors,
 * MODCP_JOB_ERR_* bits, job_internal.h): blocks of a kind the CPU side must not send ->
 * (0E)3CH "illegal job"; other unexpected blocks (sequence gap, data without its header,
 * continuation without a start, short INIT) -> (0E)30H "unexpected acknowledgement". At
 * most one of each per call (per poll). */
void modcp_cpdiag_backplane(modcp_diag_t *diag, unsigned errors);
/* Serve a new SYSTAT request (number req, not systat_ack): the image straight into the
 * status area's systat[] (under its seqlock; the CP publishes systat_ack = req with the
 * rest of the status area) + clear. run: CP in RUN. */
void modcp_cpdiag_systat(modcp_cpdiag_t *d, modcp_diag_t *diag, modcp_backplane_t *bp,
                         uint32_t req, bool run);

#endif
