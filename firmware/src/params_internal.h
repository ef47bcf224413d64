/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of params.c (modcp/params.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_PARAMS_INTERNAL_H
#define MODCP_PARAMS_INTERNAL_H

#include "modcp/params.h"

/* Validate. Writes up to max issues to out (may be NULL with max 0) and returns the
 * total number of issues found. Never modifies p. */
size_t modcp_params_validate(const modcp_params_t *p, modcp_param_issue_t *out, size_t max);
/* Validate and make the effective copy: corrects non-fatal fields (f_MUL -> 1, ASCII
 * timeout -> 1000 ms). Returns the first fatal event, or MODCP_EV_NONE when usable;
 * *first_warning (may be NULL) receives the first non-fatal event. */
modcp_event_t modcp_params_apply(const modcp_params_t *in, modcp_params_t *out,
                                 modcp_event_t *first_warning);
/* Effective CPU job limit in bytes (job_limit or the model's 1024 / 450). */
uint16_t modcp_params_job_limit(const modcp_params_t *p);
/* t1.5 in microseconds (1.5 character times of 11 bits; 750 us above 19200 baud). */
uint32_t modcp_params_t15_us(const modcp_params_t *p);

#endif
