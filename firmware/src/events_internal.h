/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of events.c (modcp/events.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_EVENTS_INTERNAL_H
#define MODCP_EVENTS_INTERNAL_H

#include "modcp/events.h"

/* Modbus exception code (1..4) for an event raised while *validating and mapping* a
 * request (PDU engine, mapping engine): (08)31H -> 1; (08)32H..35H -> 3; (0E)39H
 * (DB boundary crossed), (0E)50H..55H -> 2; (0E)56H -> 4. Errors reported by the
 * CPU side while executing a job are always answered with 4, whatever their event.
 * Returns 0 for events that are not request errors (link and parameter events). */
uint8_t modcp_event_exception(modcp_event_t ev);

#endif
