/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the waveform for PulseView / sigrok: an observer of the line (vcd.c). */
#ifndef MODCP_SIM_VCD_H
#define MODCP_SIM_VCD_H

#include <stddef.h>

#include "line.h"

typedef struct sim_vcd sim_vcd_t;

/* Creates path and writes the header (the line's members must be known); NULL + err. */
sim_vcd_t *sim_vcd_open(const sim_line_t *line, const char *path, char *err, size_t cap);
sim_observer_t *sim_vcd_observer(sim_vcd_t *v);
/* After sim_line_close. */
void sim_vcd_close(sim_vcd_t *v);

#endif
