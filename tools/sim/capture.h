/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the Wireshark capture: an observer of the line (format: capture.c). */
#ifndef MODCP_SIM_CAPTURE_H
#define MODCP_SIM_CAPTURE_H

#include <stddef.h>
#include <stdint.h>

#include "line.h"

typedef struct sim_capture sim_capture_t;

/* Creates path and writes the pcap header; NULL + err on failure. */
sim_capture_t *sim_capture_open(const sim_line_t *line, const char *path, char *err, size_t cap);
/* Its observer, for sim_line_observe. */
sim_observer_t *sim_capture_observer(sim_capture_t *c);
/* After sim_line_close: closes the file; returns the records written. */
uint32_t sim_capture_close(sim_capture_t *c);

#endif
