/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — quantity limits by limit set (manual / spec), framing and register width;
 * register width of a holding register in the 32-bit scheme. See modcp/quantity.h for
 * the table. */
#include "modcp/quantity.h"

#include <stdbool.h>
#include <stddef.h>
#include "quantity_internal.h"

uint8_t modcp_regs32_kind(const modcp_params_t *p, uint8_t fc, uint16_t reg)
{
    if (p->regs32 == 0u || fc == 4u) {
        return 0u; /* FC04 is never 32-bit ([ASCII-32] §4.4) */
    }
    for (size_t k = 0; k < 3u; k++) {
        const modcp_r32range_t *r = &p->r32[k];
        /* an all-zero range is unused: inside [from, to] it could only hold register 0 */
        if (r->from <= reg && reg <= r->to && (r->to != 0u || r->db != 0u)) {
            return (uint8_t)(k + 1u);
        }
    }
    return 0u;
}

/*                                 RTU    ASCII  spec   RTU32  ASCII32 spec32 */
const uint16_t modcp_qty_limits[MODCP_QLIM_ROWS - 1u][6] = {
    [MODCP_QLIM_READ_BITS - 1u] = {2040u, 2008u, 2000u, 2040u, 2008u, 2000u},
    [MODCP_QLIM_WRITE_BITS - 1u] = {2040u, 1976u, 1968u, 2040u, 1976u, 1968u},
    [MODCP_QLIM_READ_REGS - 1u] = {127u, 125u, 125u, 63u, 62u, 62u},
    [MODCP_QLIM_WRITE_REGS - 1u] = {127u, 123u, 123u, 63u, 61u, 61u},
#if MODCP_WITH_EXTENDED
    [MODCP_QLIM_RW_READ - 1u] = {125u, 125u, 125u, 62u, 62u, 62u},
    [MODCP_QLIM_RW_WRITE - 1u] = {121u, 121u, 121u, 60u, 60u, 60u},
#endif
};
