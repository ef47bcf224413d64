/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of quantity.c (modcp/quantity.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_QUANTITY_INTERNAL_H
#define MODCP_QUANTITY_INTERNAL_H

#include "modcp/quantity.h"

/* Register width of holding register `reg` for fc: 0 = the 16-bit scheme (regs32 off,
 * FC04, or an address outside every 32-bit range: the mapping then refuses it), else
 * modcp_r32_kind_t + 1 of the range that holds it (as modcp_map_regs' out->bit). */
uint8_t modcp_regs32_kind(const modcp_params_t *p, uint8_t fc, uint16_t reg);
/* Bytes per register for a kind returned by modcp_regs32_kind(): 4 for int32 and
 * float, else 2. */
static inline uint8_t modcp_reg_bytes(uint8_t r32_kind)
{
    return r32_kind > (uint8_t)MODCP_R32_INT32 ? 4u : 2u;
}
_Static_assert((int)MODCP_R32_INT16 == 0 && (int)MODCP_R32_INT32 == 1 && (int)MODCP_R32_FLOAT == 2,
               "register kinds: int32 and float last");
/* Largest quantity of limit class lim (MODCP_QLIM_*, RW_* only with the extended set)
 * for the quantity_limits set and framing of p and the register kind (0 for bits and
 * 16-bit registers); 0 for MODCP_QLIM_NONE. */
static inline uint16_t modcp_qty_limit(const modcp_params_t *p, uint8_t lim, uint8_t r32_kind)
{
    uint8_t col = MODCP_QCOL_RTU;
    if (p->qty_limits == (uint8_t)MODCP_QLIMITS_SPEC) {
        col = MODCP_QCOL_SPEC;
    }
#if MODCP_WITH_ASCII /* (else framing ascii is refused by the validation, params.c) */
    else if (p->framing == (uint8_t)MODCP_FRAMING_ASCII) {
        col = MODCP_QCOL_ASCII;
    }
#endif
    else {
        /* RTU, the manual's limits */
    }
    if (lim == (uint8_t)MODCP_QLIM_NONE) {
        return 0u; /* no row (the callers in the core know better) */
    }
    if (modcp_reg_bytes(r32_kind) == 4u) {
        col = (uint8_t)(col + MODCP_QCOL_R32); /* 4 bytes per register */
    }
    return modcp_qty_limits[lim - 1u][col];
}
#endif
