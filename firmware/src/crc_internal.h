/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of crc.c (modcp/crc.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_CRC_INTERNAL_H
#define MODCP_CRC_INTERNAL_H

#include "modcp/crc.h"

/* The 256-entry table (crc.c), for the one-step update below. */
extern const uint16_t modcp_crc16_table[256];

/* One byte into a running CRC: what the receive path does per byte (rtu.c). */
static inline uint16_t modcp_crc16_byte(uint16_t crc, uint8_t b)
{
    return (uint16_t)((crc >> 8) ^ modcp_crc16_table[(crc ^ b) & 0xFFu]);
}
uint16_t modcp_crc16_update(uint16_t crc, const uint8_t *p, size_t n);
/* The CRC of p[0 .. n) appended at p[n] (low byte first): returns n + 2 (an RTU frame's
 * length; rtu_encode tail-calls it). */
uint16_t modcp_crc16_append(uint8_t *p, uint16_t n);

#endif
