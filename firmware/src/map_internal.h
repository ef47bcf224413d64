/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of map.c (modcp/map.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_MAP_INTERNAL_H
#define MODCP_MAP_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "modcp/map.h"

/* ---- the mapping the PDU engine runs, inline ([RTU-2003] §3; map.c for the rules) ---- */

/* The areas as the uint8_t the operands and windows hold them in (MISRA C:2012 10.4). */
#define MODCP_MAP_I ((uint8_t)MODCP_AREA_I)
#define MODCP_MAP_Q ((uint8_t)MODCP_AREA_Q)
#define MODCP_MAP_M ((uint8_t)MODCP_AREA_M)
#define MODCP_MAP_T ((uint8_t)MODCP_AREA_T)
#define MODCP_MAP_C ((uint8_t)MODCP_AREA_C)
#define MODCP_MAP_DB ((uint8_t)MODCP_AREA_DB)

#define MODCP_MAP_TC_MAX_CP341 16u  /* [RTU-2003] §3.3: CP 341 reads at most 16 timers / counters */
#define MODCP_MAP_WORDS_PER_DB 512u /* [RTU-2003] §3.4 */

#define MODCP_MAP_AREA_BIT(a) (1u << (unsigned)(a))
/* The areas a coil window (FC01/05/15) or an input window (FC02) may map onto. */
#define MODCP_MAP_COIL_AREAS                                                               \
    (MODCP_MAP_AREA_BIT(MODCP_AREA_M) | MODCP_MAP_AREA_BIT(MODCP_AREA_Q) |                  \
     MODCP_MAP_AREA_BIT(MODCP_AREA_T) | MODCP_MAP_AREA_BIT(MODCP_AREA_C) |                  \
     MODCP_MAP_AREA_BIT(MODCP_AREA_DB))
#define MODCP_MAP_INPUT_AREAS                                                              \
    (MODCP_MAP_AREA_BIT(MODCP_AREA_M) | MODCP_MAP_AREA_BIT(MODCP_AREA_I) |                  \
     MODCP_MAP_AREA_BIT(MODCP_AREA_DB))

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

static inline bool modcp_map_is_tc(uint8_t area)
{
    return area == MODCP_MAP_T || area == MODCP_MAP_C;
}

/* The size of area (I, Q, M, T, C or DB: the caller knows it is one of them). */
static inline uint32_t modcp_map_size_in(const modcp_areas_t *a, uint8_t area)
{
    if (a == NULL || area == MODCP_MAP_DB) {
        return 0x10000u;
    }
    uint16_t n;
    (void)memcpy((uint8_t *)&n,
                 &((const uint8_t *)a)[2u * ((unsigned)area - (unsigned)MODCP_MAP_I)], sizeof n);
    return n;
}

/* first .. last inside limit l (max 0: nothing writable). */
static inline bool modcp_map_limit_ok(const modcp_limit_t *l, uint32_t first, uint32_t last)
{
    return l->max != 0u && first >= l->min && last <= l->max;
}

/* modcp_map_db_write_ok, inline. */
static inline bool modcp_map_db_writable(const modcp_params_t *p, const modcp_areas_t *a,
                                         uint32_t db)
{
    if (a != NULL && db == a->work_db) {
        return false; /* the FB's work area is never writable ([RTU-2003] §3.5); work_db 0 (none):
                         db 0 is refused anyway */
    }
    return db >= 1u && modcp_map_limit_ok(&p->lim_db, db, db);
}

/* modcp_map_bits_valid, inline (the PDU engine's copy). */
static inline modcp_event_t modcp_map_bits_in(const modcp_params_t *p, const modcp_areas_t *a,
                                               uint8_t fc, uint16_t addr, uint16_t qty,
                                               modcp_operand_t *out)
{
    const modcp_bitwin_t *w = p->coils;
    unsigned n = MODCP_COIL_WINDOWS;
    unsigned usable = MODCP_MAP_COIL_AREAS; /* MODCP_MAP_AREA_BIT set */
    if (fc == 2u) {
        w = p->inputs;
        n = MODCP_INPUT_WINDOWS;
        usable = MODCP_MAP_INPUT_AREAS;
    }
    while ((w->area >= 8u) || ((usable & MODCP_MAP_AREA_BIT(w->area)) == 0u) ||
           (w->from > addr) || (addr > w->to)) { /* the first window holding addr */
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
    if (modcp_map_is_tc(area)) {
        if (write) {
            return MODCP_EV_AREA_READONLY;
        }
        if (rel % 16u != 0u) {
            return MODCP_EV_TC_ALIGN;
        }
        if (qty % 16u != 0u || (p->cpu_model == (uint8_t)MODCP_CPU_CP341 &&
                                (uint32_t)qty / 16u > MODCP_MAP_TC_MAX_CP341)) {
            return MODCP_EV_QUANTITY;
        }
        per = 4u;
    }
    /* first / last byte, or element for T / C (rel and qty then multiples of 16) */
    const uint32_t first = (uint32_t)w->start + (rel >> per);
    const uint32_t last = (uint32_t)w->start + ((rel + (uint32_t)qty - 1u) >> per);
    if ((uint32_t)addr + (uint32_t)qty - 1u > w->to || last >= modcp_map_size_in(a, area)) {
        return MODCP_EV_PAST_END;
    }

    if (write) { /* a coil window: M, Q or DB (T / C refused above) */
        const bool ok =
            (area == MODCP_MAP_DB)
                ? modcp_map_db_writable(p, a, w->db)
                : modcp_map_limit_ok((area == MODCP_MAP_M) ? &p->lim_m : &p->lim_q, first, last);
        if (!ok) {
            return MODCP_EV_WRITE_DENIED;
        }
    }

    out->area = area;
    out->db = (area == MODCP_MAP_DB) ? w->db : 0u;
    out->offset = (uint16_t)first;
    out->bit = (uint8_t)(rel % 8u); /* 0 for T / C */
    out->count = (uint16_t)(qty >> (per - 3u) * 4u); /* bits, or elements for T / C */
    return MODCP_EV_NONE;
}

/* Registers of the 32-bit scheme ([ASCII-32] §4.5; map.c): fc 03 / 06 / 16 / 22 / 23
 * with params.regs32 set, out->bit the kind + 1 of the range holding reg. */
modcp_event_t modcp_map_regs32(const modcp_params_t *p, const modcp_areas_t *a, uint8_t fc,
                               uint16_t reg, uint16_t qty, modcp_operand_t *out);

/* modcp_map_regs_kind, inline (the PDU engine's copy): the 16-bit scheme here. */
static inline modcp_event_t modcp_map_regs_in(const modcp_params_t *p, const modcp_areas_t *a,
                                              uint8_t fc, uint16_t reg, uint16_t qty,
                                              modcp_operand_t *out)
{
    if (fc != 4u && p->regs32 != 0u) { /* the 32-bit scheme (never FC04, [ASCII-32] §4.4) */
        return modcp_map_regs32(p, a, fc, reg, qty, out);
    }
    const uint16_t base = fc == 4u ? p->ir_base_db : p->hr_base_db;
    if (base == 0u) {
        return MODCP_EV_NO_WINDOW; /* register functions not configured */
    }
    const uint32_t db = (uint32_t)base + ((uint32_t)reg >> 9);
    const uint32_t word = (uint32_t)reg & 0x1FFu;
    if (db > 0xFFFFu) {
        return MODCP_EV_DB_OVERFLOW;
    }
    if (word + (uint32_t)qty > MODCP_MAP_WORDS_PER_DB) {
        return MODCP_EV_DB_ACCESS; /* would cross into the next DB */
    }
    out->bit = 0u;
    if (fc > 4u && !modcp_map_db_writable(p, a, db)) { /* a write: every fc but the reads */
        return MODCP_EV_WRITE_DENIED;
    }
    out->area = MODCP_MAP_DB;
    out->db = (uint16_t)db;
    out->offset = (uint16_t)(word * 2u);
    out->count = (uint16_t)(qty * 2u);
    return MODCP_EV_NONE;
}

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
