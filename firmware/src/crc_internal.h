/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of crc.c (modcp/crc.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_CRC_INTERNAL_H
#define MODCP_CRC_INTERNAL_H

#include "modcp/crc.h"

/* The tables (crc.c): 256 entries, a byte per step, in the builds for speed (-O2);
 * 16 entries, a nibble per step, in the builds for size (-Os, __OPTIMIZE_SIZE__: the MCU
 * images, 480 B less flash; the linker keeps only the one a build uses). */
extern const uint16_t modcp_crc16_table[256];
extern const uint16_t modcp_crc16_nibble[16];

/* One byte into a running CRC (rtu.c: the characters of a frame that is not ours). */
static inline uint16_t modcp_crc16_byte(uint16_t crc, uint8_t b)
{
#if defined(__OPTIMIZE_SIZE__)
    crc = (uint16_t)((crc >> 4) ^ modcp_crc16_nibble[(crc ^ b) & 0xFu]);
    return (uint16_t)((crc >> 4) ^ modcp_crc16_nibble[(crc ^ ((unsigned)b >> 4)) & 0xFu]);
#else
    return (uint16_t)((crc >> 8) ^ modcp_crc16_table[(crc ^ b) & 0xFFu]);
#endif
}
uint16_t modcp_crc16_update(uint16_t crc, const uint8_t *p, size_t n);
/* The CRC of p[0 .. n) appended at p[n] (low byte first): returns n + 2 (an RTU frame's
 * length; rtu_encode tail-calls it). */
uint16_t modcp_crc16_append(uint8_t *p, uint16_t n);

#endif
