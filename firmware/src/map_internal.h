/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of map.c (modcp/map.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_MAP_INTERNAL_H
#define MODCP_MAP_INTERNAL_H

#include "modcp/map.h"

/* Bit access for FC01 (coils, read), FC05/FC15 (coils, write) or FC02 (inputs).
 * qty is the bit count as on the wire (already range-checked by the PDU engine).
 * For T/C windows (FC01 only) the operand is in elements (qty / 16).
 * Events: (0E)51H no window, (0E)50H T/C misaligned, (08)32H T/C qty not a multiple
 * of 16, (0E)54H past the window end or the controller area, (0E)55H write to T/C,
 * (0E)52H write outside the M/Q limits. */
modcp_event_t modcp_map_bits(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t addr, uint16_t qty, modcp_operand_t *out);
/* The same for a request the PDU engine has checked: fc is 01, 02, 05 or 15, qty >= 1
 * (no (08)31H, no (08)32H for qty 0). */
modcp_event_t modcp_map_bits_valid(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                                   uint16_t addr, uint16_t qty, modcp_operand_t *out);
/* Register access (16-bit scheme): FC03/06/16 use hr_base_db, FC04 ir_base_db.
 * DB = base + (reg >> 9), DBW = (reg & 0x1FF) * 2; out->count = 2 * qty bytes.
 * With params.regs32 set, FC03/06/16 use the three 32-bit ranges instead
 * (count = 4 * qty bytes; int16 range: 2 bytes per register) and out->bit carries
 * the modcp_r32_kind_t + 1 (0 = 16-bit scheme).
 * Events: (0E)52H DB < 1 or write outside the DB limits or to the work area,
 * (0E)53H DB > 65535, (0E)39H request crosses a DB boundary, (0E)51H no 32-bit range. */
modcp_event_t modcp_map_regs(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t reg, uint16_t qty, modcp_operand_t *out);
/* The same with the register kind already known, for a request the PDU engine has
 * checked (fc one of 03, 04, 06, 16, 22, 23; qty >= 1): on entry out->bit holds
 * modcp_regs32_kind(p, fc, reg) (the engine has it from the function-code table's
 * check of the quantity). */
modcp_event_t modcp_map_regs_kind(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                                  uint16_t reg, uint16_t qty, modcp_operand_t *out);
/* Size of a controller area in bytes (M, Q, I) or elements (T, C) as reported at init;
 * DB (and areas == NULL): 65536, since DB sizes are checked by the CPU side. */
uint32_t modcp_map_area_size(const modcp_areas_t *a, uint8_t area);
/* May the master write to DB db? Inside the parameters' DB limits (lim_db, db >= 1)
 * and not the FB's work DB (a == NULL: unknown, not checked). */
bool modcp_map_db_write_ok(const modcp_params_t *p, const modcp_areas_t *a, uint32_t db);
/* Inverse of the register scheme (8.6): register number of DB db, byte offset dbw
 * relative to base. Returns false when not addressable. */
bool modcp_map_reg_of(uint16_t base_db, uint16_t db, uint16_t dbw, uint16_t *reg);

#endif
