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
#include <string.h>

#include "map_internal.h"
#include "quantity_internal.h"

/* The areas as the uint8_t the operands and windows hold them in (MISRA C:2012 10.4). */
#define AREA_I ((uint8_t)MODCP_AREA_I)
#define AREA_Q ((uint8_t)MODCP_AREA_Q)
#define AREA_M ((uint8_t)MODCP_AREA_M)
#define AREA_T ((uint8_t)MODCP_AREA_T)
#define AREA_C ((uint8_t)MODCP_AREA_C)
#define AREA_DB ((uint8_t)MODCP_AREA_DB)

#define TC_MAX_CP341 16u   /* [RTU-2003] §3.3: CP 341 reads at most 16 timers / counters */
#define WORDS_PER_DB 512u  /* [RTU-2003] §3.4 */
/* The function codes on registers: FC03 / 06 / 16 / 22 / 23 holding, FC04 input. */
#define REG_FCS ((1u << 3) | (1u << 4) | (1u << 6) | (1u << 16) | (1u << 22) | (1u << 23))

/* After the function code was checked (01 / 02 / 05 / 15, 03 / 04 / 06 / 16 / 22 / 23):
 * every one but the reads (01 .. 04) writes. */
static bool is_write_fc(uint8_t fc)
{
    return fc > 4u;
}

static bool is_tc(uint8_t area)
{
    return area == AREA_T || area == AREA_C;
}

#define AREA_BIT(a) (1u << (unsigned)(a))
/* The areas a coil window (FC01/05/15) or an input window (FC02) may map onto. */
#define COIL_AREAS                                                                         \
    (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_Q) | AREA_BIT(MODCP_AREA_T) |            \
     AREA_BIT(MODCP_AREA_C) | AREA_BIT(MODCP_AREA_DB))
#define INPUT_AREAS (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_I) | AREA_BIT(MODCP_AREA_DB))

/* The sizes of I, Q, M, T, C are consecutive fields of modcp_areas_t, in area order. */
_Static_assert(((int)MODCP_AREA_I == 1) && ((int)MODCP_AREA_Q == 2) && ((int)MODCP_AREA_M == 3) &&
                   ((int)MODCP_AREA_T == 4) && ((int)MODCP_AREA_C == 5),
               "area order");
_Static_assert(((size_t)offsetof(modcp_areas_t, i_bytes) == 0u) &&
                   ((size_t)offsetof(modcp_areas_t, q_bytes) == 2u) &&
                   ((size_t)offsetof(modcp_areas_t, m_bytes) == 4u) &&
                   ((size_t)offsetof(modcp_areas_t, timers) == 6u) &&
                   ((size_t)offsetof(modcp_areas_t, counters) == 8u),
               "modcp_areas_t: the sizes in area order");

/* The size of area (I, Q, M, T, C or DB: the caller knows it is one of them). */
static inline uint32_t area_size(const modcp_areas_t *a, uint8_t area)
{
    if (a == NULL || area == AREA_DB) {
        return 0x10000u;
    }
    uint16_t n;
    (void)memcpy((uint8_t *)&n, &((const uint8_t *)a)[2u * ((unsigned)area - (unsigned)AREA_I)],
                 sizeof n);
    return n;
}

uint32_t modcp_map_area_size(const modcp_areas_t *a, uint8_t area)
{
    if (a != NULL && area != AREA_DB && (area < AREA_I || area > AREA_C)) {
        return 0u;
    }
    return area_size(a, area);
}

static bool limit_ok(const modcp_limit_t *l, uint32_t first, uint32_t last)
{
    return l->max != 0u && first >= l->min && last <= l->max;
}

bool modcp_map_db_write_ok(const modcp_params_t *p, const modcp_areas_t *a, uint32_t db)
{
    if (a != NULL && db == a->work_db) {
        return false; /* the FB's work area is never writable ([RTU-2003] §3.5); work_db 0 (none):
                         db 0 is refused anyway */
    }
    return db >= 1u && limit_ok(&p->lim_db, db, db);
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
    const modcp_bitwin_t *w = p->coils;
    unsigned n = MODCP_COIL_WINDOWS;
    unsigned usable = COIL_AREAS; /* AREA_BIT set */
    if (fc == 2u) {
        w = p->inputs;
        n = MODCP_INPUT_WINDOWS;
        usable = INPUT_AREAS;
    }
    while ((w->area >= 8u) || ((usable & AREA_BIT(w->area)) == 0u) || (w->from > addr) ||
           (addr > w->to)) { /* the first window holding addr */
        n--;
        if (n == 0u) {
            return MODCP_EV_NO_WINDOW;
        }
        w++;
    }

    const bool write = fc >= 5u; /* FC05 / FC15 */
    const uint8_t area = w->area;
    const uint32_t rel = (uint32_t)addr - (uint32_t)w->from;
    unsigned per = 3u; /* log2 of the bits per byte, or per element for T / C */
    if (is_tc(area)) {
        if (write) {
            return MODCP_EV_AREA_READONLY;
        }
        if (rel % 16u != 0u) {
            return MODCP_EV_TC_ALIGN;
        }
        if (qty % 16u != 0u ||
            (p->cpu_model == (uint8_t)MODCP_CPU_CP341 && (uint32_t)qty / 16u > TC_MAX_CP341)) {
            return MODCP_EV_QUANTITY;
        }
        per = 4u;
    }
    /* first / last byte, or element for T / C (rel and qty then multiples of 16) */
    const uint32_t first = (uint32_t)w->start + (rel >> per);
    const uint32_t last = (uint32_t)w->start + ((rel + (uint32_t)qty - 1u) >> per);
    if ((uint32_t)addr + (uint32_t)qty - 1u > w->to || last >= area_size(a, area)) {
        return MODCP_EV_PAST_END;
    }

    if (write) { /* a coil window: M, Q or DB (T / C refused above) */
        const bool ok = (area == AREA_DB)
                            ? modcp_map_db_write_ok(p, a, w->db)
                            : limit_ok((area == AREA_M) ? &p->lim_m : &p->lim_q, first, last);
        if (!ok) {
            return MODCP_EV_WRITE_DENIED;
        }
    }

    out->area = area;
    out->db = (area == AREA_DB) ? w->db : 0u;
    out->offset = (uint16_t)first;
    out->bit = (uint8_t)(rel % 8u); /* 0 for T / C */
    out->count = (uint16_t)(qty >> (per - 3u) * 4u); /* bits, or elements for T / C */
    return MODCP_EV_NONE;
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
    uint32_t db;
    uint32_t offset;
    uint32_t bytes;
    bool db_limits = true; /* writes: lim_db applies (else only the work DB is refused) */
    if (fc != 4u && p->regs32 != 0u) { /* the 32-bit scheme (never FC04, [ASCII-32] §4.4) */
        const uint8_t k1 = out->bit;    /* the range's kind + 1, 0: none */
        db_limits = p->r32_lim_db != 0u; /* [ASCII-32] §3.7, §5.4: the DB limits are standard mode's */
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
        offset = ((uint32_t)reg - (uint32_t)r->from) * per;
        bytes = (uint32_t)qty * per;
        if ((uint32_t)reg + (uint32_t)qty - 1u > r->to || offset + bytes > 0x10000u ||
            bytes > 0xFFFFu) {
            return MODCP_EV_PAST_END;
        }
        db = r->db;
    } else {
        const uint16_t base = fc == 4u ? p->ir_base_db : p->hr_base_db;
        if (base == 0u) {
            return MODCP_EV_NO_WINDOW; /* register functions not configured */
        }
        db = (uint32_t)base + ((uint32_t)reg >> 9);
        const uint32_t word = (uint32_t)reg & 0x1FFu;
        if (db > 0xFFFFu) {
            return MODCP_EV_DB_OVERFLOW;
        }
        if (word + (uint32_t)qty > WORDS_PER_DB) {
            return MODCP_EV_DB_ACCESS; /* would cross into the next DB */
        }
        out->bit = 0u;
        offset = word * 2u;
        bytes = (uint32_t)qty * 2u;
    }
    if (is_write_fc(fc) && (db_limits ? !modcp_map_db_write_ok(p, a, db)
                                      : a != NULL && db == a->work_db)) {
        return MODCP_EV_WRITE_DENIED;
    }
    out->area = AREA_DB;
    out->db = (uint16_t)db;
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
        *reg = (uint16_t)(off * WORDS_PER_DB + (uint32_t)dbw / 2u);
    }
    return true;
}
