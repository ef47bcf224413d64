/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — mapping engine: Modbus addresses -> controller operands ([RTU-2003] §3, [ASCII-32] §4).
 *
 * Bits (FC01/05/15 on the coil windows, FC02 on the input windows), checked in
 * this order:
 *   1. the window holding addr ......................... else (0E)51H
 *   2. FC05/15 on a T/C window ........................... (0E)55H
 *   3. T/C: (addr - from) % 16 != 0 ...................... (0E)50H
 *   4. T/C: qty % 16 != 0, or more than 16 elements with the CP 341 model
 *      ................................................... (08)32H
 *   5. addr + qty - 1 > to, or the last byte / element beyond the controller's
 *      area (modcp_areas_t; DB bits: beyond byte 65535) .. (0E)54H
 *   6. writes: every touched M / Q byte inside lim_m / lim_q (max 0 = not
 *      writable); a DB-bit window: its DB inside lim_db and not the FB's work DB
 *      ................................................... (0E)52H
 *   docs/mapping.md ("every byte or DB that a write touches must lie inside its MIN/MAX")
 *   decides over [ASCII-32] §4.6, where DB-bit coils ignore the DB limits.
 *
 * Registers, 16-bit scheme ([RTU-2003] §3.4): base 0 (not configured) -> (0E)51H;
 * DB = base + (reg >> 9) > 65535 -> (0E)53H; word + qty > 512 -> (0E)39H;
 * writes (FC06/16/22/23) outside lim_db or to the work DB -> (0E)52H.
 *
 * Registers, 32-bit scheme ([ASCII-32] §4.5; params.regs32, FC03/06/16/23):
 * the range holding reg (an all-zero range is unused) -> else (0E)51H;
 * reg + qty - 1 > to -> (0E)54H; writes: the work DB -> (0E)52H; lim_db only with
 * params.r32_lim_db ([ASCII-32] §3.7, §5.4: the DB limits are the standard mode's, the three
 * DBs stay writable; r32_lim_db = 1 keeps modcp's earlier, stricter rule).
 * int16: DBW = (reg - from) * 2, 2 bytes per register; int32 / float:
 * DBD = (reg - from) * 4, 4 bytes per register. out->bit = kind + 1.
 * FC22 (mask write, a 16-bit operation) with regs32 set: decision of modcp, the
 * int16 range only; an address in the int32 / float range -> (0E)51H.
 *
 * modcp_map_bits / modcp_map_regs (the tests, tools): qty 0 -> (08)32H; an fc the
 * function does not serve -> (08)31H. The PDU engine never passes either and calls
 * modcp_map_bits_valid / modcp_map_regs_kind, which skip both checks. a == NULL: controller sizes and work DB unknown, not checked. */
#include "modcp/map.h"

#include <stddef.h>

#include "map_internal.h"
#include "quantity_internal.h"

/* The function codes on registers: FC03 / 06 / 16 / 22 / 23 holding, FC04 input. */
#define REG_FCS ((1u << 3) | (1u << 4) | (1u << 6) | (1u << 16) | (1u << 22) | (1u << 23))

uint32_t modcp_map_area_size(const modcp_areas_t *a, uint8_t area)
{
    if (a != NULL && area != MODCP_MAP_DB && (area < MODCP_MAP_I || area > MODCP_MAP_C)) {
        return 0u;
    }
    return modcp_map_size_in(a, area);
}

bool modcp_map_db_write_ok(const modcp_params_t *p, const modcp_areas_t *a, uint32_t db)
{
    return modcp_map_db_writable(p, a, db);
}

modcp_event_t modcp_map_bits(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t addr, uint16_t qty, modcp_operand_t *out)
{
    if (fc != 1u && fc != 2u && fc != 5u && fc != 15u) {
        return MODCP_EV_ILLEGAL_FC;
    }
    if (qty == 0u) {
        return MODCP_EV_QUANTITY;
    }
    return modcp_map_bits_valid(p, a, fc, addr, qty, out);
}

modcp_event_t modcp_map_bits_valid(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                                   uint16_t addr, uint16_t qty, modcp_operand_t *out)
{
    return modcp_map_bits_in(p, a, fc, addr, qty, out);
}

modcp_event_t modcp_map_regs(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                             uint16_t reg, uint16_t qty, modcp_operand_t *out)
{
    if (fc > 23u || ((1u << fc) & REG_FCS) == 0u) {
        return MODCP_EV_ILLEGAL_FC;
    }
    if (qty == 0u) {
        return MODCP_EV_QUANTITY;
    }
    out->bit = modcp_regs32_kind(p, fc, reg);
    return modcp_map_regs_kind(p, a, fc, reg, qty, out);
}

modcp_event_t modcp_map_regs_kind(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                                  uint16_t reg, uint16_t qty, modcp_operand_t *out)
{
    return modcp_map_regs_in(p, a, fc, reg, qty, out);
}

modcp_event_t modcp_map_regs32(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                               uint16_t reg, uint16_t qty, modcp_operand_t *out)
{
    const uint8_t k1 = out->bit; /* the range's kind + 1, 0: none */
#if MODCP_WITH_EXTENDED
    if (fc == 22u && k1 != ((uint8_t)MODCP_R32_INT16 + 1u)) {
        return MODCP_EV_NO_WINDOW;
    }
#endif
    if (k1 == 0u) {
        return MODCP_EV_NO_WINDOW;
    }
    const modcp_r32range_t *r = &p->r32[k1 - 1u];
    const uint32_t per = modcp_reg_bytes(k1);
    const uint32_t offset = ((uint32_t)reg - (uint32_t)r->from) * per;
    const uint32_t bytes = (uint32_t)qty * per;
    if ((uint32_t)reg + (uint32_t)qty - 1u > r->to || offset + bytes > 0x10000u ||
        bytes > 0xFFFFu) {
        return MODCP_EV_PAST_END;
    }
    /* writes: the work DB; lim_db only with r32_lim_db ([ASCII-32] §3.7, §5.4: the DB
     * limits are standard mode's) */
    if (fc > 4u && (p->r32_lim_db != 0u ? !modcp_map_db_writable(p, a, r->db)
                                          : a != NULL && r->db == a->work_db)) {
        return MODCP_EV_WRITE_DENIED;
    }
    out->area = MODCP_MAP_DB;
    out->db = r->db;
    out->offset = (uint16_t)offset;
    out->count = (uint16_t)bytes;
    return MODCP_EV_NONE;
}

bool modcp_map_reg_of(uint16_t base_db, uint16_t db, uint16_t dbw, uint16_t *reg)
{
    if (base_db == 0u || db < base_db) {
        return false;
    }
    const uint32_t off = (uint32_t)db - (uint32_t)base_db;
    if (off > 127u || (dbw & 1u) != 0u || dbw > 1022u) {
        return false;
    }
    if (reg != NULL) {
        *reg = (uint16_t)(off * MODCP_MAP_WORDS_PER_DB + (uint32_t)dbw / 2u);
    }
    return true;
}
