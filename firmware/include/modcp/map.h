/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — mapping engine: Modbus addresses -> controller operands ([RTU-2003] §3, [ASCII-32] §4).
 * Pure functions over the parameters and the controller's area sizes. */
/* Public: the mapping functions are internal (firmware/src/map_internal.h); the types are
 * here because modcp_params_t, the FB and the controller memory use them. */
#ifndef MODCP_MAP_H
#define MODCP_MAP_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/events.h"
#include "modcp/params.h"

/* A resolved controller operand.
 *  - bit access (M, Q, I, DB bits): offset = first byte, bit = first bit, count = bits
 *  - T / C:                          offset = first element, bit = 0, count = elements
 *  - byte access (DB words, MW...):  offset = first byte, bit = 0, count = bytes */
typedef struct {
    uint8_t area; /* modcp_area_t */
    uint8_t bit;
    uint16_t db;
    uint16_t offset;
    uint16_t count;
} modcp_operand_t;

/* The controller's real area sizes, reported by the CPU side at init. */
typedef struct {
    uint16_t i_bytes;
    uint16_t q_bytes;
    uint16_t m_bytes;
    uint16_t timers;
    uint16_t counters;
    uint16_t work_db; /* the FB's work area (instance DB): never writable by the master */
} modcp_areas_t;

#endif
