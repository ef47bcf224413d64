/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the text trace as an observer of the line (see trace_obs.c; the lines'
 * format: trace.h). */
#ifndef MODCP_SIM_TRACE_OBS_H
#define MODCP_SIM_TRACE_OBS_H

#include <stdatomic.h>
#include <stdbool.h>

#include "line.h"
#include "trace.h"

typedef struct sim_trace_obs sim_trace_obs_t;

/* After the line's members are named. on: print frames and events (a console answer,
 * SIM_NOTE_OUTPUT, is printed either way); solo: one slave, its replies "slave 5", a
 * request for another address "not for us" (else "@a slave 5", every address decoded).
 * print: one line (thread-safe). NULL: out of memory. */
sim_trace_obs_t *sim_trace_obs_new(const sim_line_t *line, const atomic_bool *on, bool solo,
                                   void (*print)(void *user, const char *line), void *user);
/* Its observer, for sim_line_observe. */
sim_observer_t *sim_trace_obs_observer(sim_trace_obs_t *o);
/* After sim_line_close. */
void sim_trace_obs_free(sim_trace_obs_t *o);

#endif
