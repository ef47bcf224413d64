/* modcp — quantity limits by framing and register width; register width of a holding
 * register in the 32-bit scheme. See modcp/quantity.h for the table. */
#include "modcp/quantity.h"

#include <stdbool.h>
#include <stddef.h>

uint8_t modcp_regs32_kind(const modcp_params_t *p, uint8_t fc, uint16_t reg)
{
    if (p->regs32 == 0u || fc == 4u) {
        return 0u; /* FC04 is never 32-bit (003 §4.4) */
    }
    for (size_t k = 0; k < 3u; k++) {
        const modcp_r32range_t *r = &p->r32[k];
        bool unused = r->from == 0u && r->to == 0u && r->db == 0u;
        if (!unused && r->from <= reg && reg <= r->to) {
            return (uint8_t)(k + 1u);
        }
    }
    return 0u;
}

uint8_t modcp_reg_bytes(uint8_t r32_kind)
{
    return (r32_kind == (uint8_t)(MODCP_R32_INT32 + 1u) ||
            r32_kind == (uint8_t)(MODCP_R32_FLOAT + 1u))
               ? 4u
               : 2u;
}

uint16_t modcp_qty_max(const modcp_params_t *p, uint8_t fc, uint8_t r32_kind)
{
    const bool ascii = p->framing == (uint8_t)MODCP_FRAMING_ASCII;
    const bool wide = modcp_reg_bytes(r32_kind) == 4u;
    switch (fc) {
    case 1u:
    case 2u:
        return ascii ? 2008u : 2040u;
    case 15u:
        return ascii ? 1976u : 2040u;
    case 3u:
    case 4u:
        if (wide) {
            return ascii ? 62u : 63u;
        }
        return ascii ? 125u : 127u;
    case 16u:
        if (wide) {
            return ascii ? 61u : 63u;
        }
        return ascii ? 123u : 127u;
    default:
        return 0u;
    }
}
