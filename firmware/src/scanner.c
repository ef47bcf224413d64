/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — indirection scanner (docs/extended-functions.md, [ALTIVAR] §11 "scanner de communication").
 *
 * scan_count (1..16) consecutive holding registers from scan_start; register
 * scan_start + k stands for the word operand params.scan[k]:
 *   M / I / Q   byte offset n: the word MWn / IWn / QWn (bytes n, n+1, high first)
 *   DB          DBdb.DBWn (bytes n, n+1 of DB db)
 *   T / C       element n (16 bits, controller byte order, as FC01 sends them)
 *   NONE        unused: reads give 0000, writes are discarded
 * FC03, FC06, FC16, FC22 and FC23 on these addresses act on the operands; the scanner
 * has priority over the DB-offset scheme and the 32-bit ranges for its addresses.
 * FC04 (input registers) is not affected.
 *
 * Access rules are those of direct access: reads need the operand inside the
 * controller's area ((0E)54H; DB existence and length are checked by the CPU side,
 * (0E)39H -> exception 04); writes only to M (lim_m), Q (lim_q) and DB (lim_db, not
 * the FB's work DB) -> else (0E)52H, never to I, T, C -> (0E)55H. */
#include <stddef.h>

#include "modcp/ext.h"
#include "ext_internal.h"
#include "map_internal.h"

static bool scanner_on(const modcp_params_t *p)
{
    return p->fset == (uint8_t)MODCP_FSET_EXTENDED && p->scan_count > 0u &&
           p->scan_count <= (uint8_t)MODCP_SCANNER_MAX;
}

bool modcp_scan_touches(const modcp_params_t *p, uint16_t reg, uint16_t qty)
{
    if (!scanner_on(p) || qty == 0u) {
        return false;
    }
    uint32_t first = reg;
    uint32_t last = (uint32_t)reg + qty - 1u;
    uint32_t s_first = p->scan_start;
    uint32_t s_last = (uint32_t)p->scan_start + p->scan_count - 1u;
    return first <= s_last && last >= s_first;
}

modcp_event_t modcp_scan_map(const modcp_params_t *p, const modcp_areas_t *a, uint16_t reg,
                             bool write, modcp_operand_t *out)
{
    if (!modcp_scan_touches(p, reg, 1u)) {
        return MODCP_EV_NO_WINDOW;
    }
    const modcp_operand_ref_t *e = &p->scan[reg - p->scan_start];
    out->area = MODCP_AREA_NONE;
    out->bit = 0u;
    out->db = 0u;
    out->offset = e->offset;
    out->count = 0u;
    const uint32_t first = e->offset;
    switch (e->area) {
    case MODCP_AREA_NONE:
        return MODCP_EV_NONE;
    case MODCP_AREA_T:
    case MODCP_AREA_C:
        if (write) {
            return MODCP_EV_AREA_READONLY;
        }
        if (first >= modcp_map_area_size(a, e->area)) {
            return MODCP_EV_PAST_END;
        }
        out->count = 1u; /* one element, 2 bytes */
        break;
    case MODCP_AREA_I:
    case MODCP_AREA_Q:
    case MODCP_AREA_M:
        if (first + 1u >= modcp_map_area_size(a, e->area)) {
            return MODCP_EV_PAST_END;
        }
        if (write) {
            if (e->area == (uint8_t)MODCP_AREA_I) {
                return MODCP_EV_AREA_READONLY;
            }
            const modcp_limit_t *l = e->area == (uint8_t)MODCP_AREA_M ? &p->lim_m : &p->lim_q;
            if (!modcp_map_limit_ok(l, first, first + 1u)) {
                return MODCP_EV_WRITE_DENIED;
            }
        }
        out->count = 2u;
        break;
    case MODCP_AREA_DB:
        if (e->db == 0u) {
            return MODCP_EV_WRITE_DENIED; /* DB < 1 (validation refuses it already) */
        }
        if (first + 1u > 0xFFFFu) {
            return MODCP_EV_PAST_END;
        }
        if (write && !modcp_map_db_write_ok(p, a, e->db)) {
            return MODCP_EV_WRITE_DENIED;
        }
        out->db = e->db;
        out->count = 2u;
        break;
    default:
        return MODCP_EV_NO_WINDOW;
    }
    out->area = e->area;
    return MODCP_EV_NONE;
}

modcp_event_t modcp_scan_check(const modcp_params_t *p, const modcp_areas_t *a, uint16_t reg,
                               uint16_t qty, bool write)
{
    if (!modcp_scan_touches(p, reg, qty)) {
        return MODCP_EV_NO_WINDOW;
    }
    const uint32_t last = (uint32_t)reg + qty - 1u;
    if (reg < p->scan_start || last > (uint32_t)p->scan_start + p->scan_count - 1u) {
        return MODCP_EV_PAST_END; /* crosses the scanner's edge */
    }
    bool used = false;
    for (uint32_t r = reg; r <= last; r++) {
        modcp_operand_t o;
        modcp_event_t ev = modcp_scan_map(p, a, (uint16_t)r, write, &o);
        if (ev != MODCP_EV_NONE) {
            return ev;
        }
        used |= o.area != (uint8_t)MODCP_AREA_NONE;
    }
    return used ? MODCP_EV_NONE : MODCP_EV_NO_WINDOW;
}
