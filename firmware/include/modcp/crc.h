/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — Modbus CRC-16 (poly 0xA001 reflected, init 0xFFFF, low byte first on the
 * wire; by the 256-entry table, with the slice-by-4 tables too when built for speed, crc.c) and the ASCII
 * LRC (two's complement of the byte sum). */
#ifndef MODCP_CRC_H
#define MODCP_CRC_H

#include <stddef.h>
#include <stdint.h>

#define MODCP_CRC_INIT 0xFFFFu

/* CRC-16 of n bytes, from MODCP_CRC_INIT (sent low byte first). */
uint16_t modcp_crc16(const uint8_t *p, size_t n);
/* LRC of n bytes (ASCII framing). */
uint8_t modcp_lrc(const uint8_t *p, size_t n);

#endif
