/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of the events (modcp/events.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_EVENTS_INTERNAL_H
#define MODCP_EVENTS_INTERNAL_H

#include "modcp/events.h"

/* Modbus exception code (1..4) for an event raised while *validating and mapping* a
 * request (PDU engine, mapping engine): the column exc of the event rows
 * (modcp/event_rows.h; pdu.c). Errors reported by the CPU side while executing a job are
 * always answered with 4, whatever their event. Returns 0 for the other events (link,
 * parameter and CPU-side events). */
uint8_t modcp_event_exception(modcp_event_t ev);

#endif
