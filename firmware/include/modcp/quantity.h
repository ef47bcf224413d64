/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — quantity limits of the bit and register functions by framing and register
 * width (docs/mapping.md, §5.1; [ASCII-32] §4.5, §5, §8.5 event (08)32H), and the register width of
 * a holding-register address in the 32-bit scheme ([ASCII-32] §4.5).
 *
 *                      RTU                      ASCII (003: 252 data bytes per frame)
 *   FC01 / FC02        1 ... 2040 bits          1 ... 2008 bits
 *   FC15               1 ... 2040 bits          1 ... 1976 bits
 *   FC03 / FC04        1 ... 127 registers      1 ... 125
 *   FC16               1 ... 127                1 ... 123
 *   FC03, 32-bit       1 ... 63                 1 ... 62
 *   FC16, 32-bit       1 ... 63                 1 ... 61
 *   FC23 read / write  1 ... 125 / 121          (the same; extended set)
 *   FC23, 32-bit       1 ... 62 / 60            (the same)
 * "32-bit" is the int32 and float range of the 32-bit scheme; its int16 range has
 * the 16-bit limits. The RTU 32-bit limit (the manual has none: the 32-bit extension
 * exists only in the ASCII driver) is a decision of modcp: the largest count whose
 * byte count 4 x n fits the one-byte byte count and the 127-word budget of RTU
 * (4 x 63 = 252 bytes = 126 words).
 *
 * quantity_limits = spec (p->qty_limits, both framings): the Modbus application
 * protocol's limits (V1.1b3 §6.1-6.4, 6.11, 6.12, 6.17), so that no RTU reply (and no
 * request) exceeds the 256-byte ADU / 253-byte PDU:
 *   FC01 / FC02 1 ... 2000 bits, FC15 1 ... 1968, FC03 / FC04 1 ... 125 registers,
 *   FC16 1 ... 123, FC23 read / write 1 ... 125 / 121 (as above);
 *   32-bit: FC03 1 ... 62 (248 bytes), FC16 1 ... 61 (244 bytes), FC23 62 / 60.
 * These are also at or below every ASCII limit above. */
/* Public: constants only: the limit functions are internal (firmware/src/quantity_internal.h). */
#ifndef MODCP_QUANTITY_H
#define MODCP_QUANTITY_H

#include <stdint.h>

#include "modcp/params.h"

/* Limit classes: the function-code table (fc_table.c) names one per function code. */
#define MODCP_QLIM_NONE 0u       /* no quantity field */
#define MODCP_QLIM_READ_BITS 1u  /* FC01 / FC02 */
#define MODCP_QLIM_WRITE_BITS 2u /* FC15 */
#define MODCP_QLIM_READ_REGS 3u  /* FC03 / FC04, the scanner's FC03 */
#define MODCP_QLIM_WRITE_REGS 4u /* FC16, the scanner's FC16 */
#define MODCP_QLIM_RW_READ 5u    /* FC23 read part: 125, 32-bit 62 (both framings) */
#define MODCP_QLIM_RW_WRITE 6u   /* FC23 write part: 121, 32-bit 60 (both framings) */
#define MODCP_QLIM_COUNT 7u

/* The limits: [class - 1][column] (no row for MODCP_QLIM_NONE; the FC23 rows only with
 * the extended set), columns RTU, ASCII, spec (either framing), then the same three
 * for 32-bit registers. */
#define MODCP_QCOL_RTU 0u
#define MODCP_QCOL_ASCII 1u
#define MODCP_QCOL_SPEC 2u
#define MODCP_QCOL_R32 3u
#if MODCP_WITH_EXTENDED
#define MODCP_QLIM_ROWS MODCP_QLIM_COUNT
#else
#define MODCP_QLIM_ROWS MODCP_QLIM_RW_READ
#endif
extern const uint16_t modcp_qty_limits[MODCP_QLIM_ROWS - 1u][6];

#endif
