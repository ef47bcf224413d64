/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of plcmem.c (modcp/plcmem.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_PLCMEM_INTERNAL_H
#define MODCP_PLCMEM_INTERNAL_H

#include <stddef.h>

#include "modcp/plcmem.h"

/* The DB lookup, behind modcp_plcmem_byte_area (every DB job) and modcp_plcmem_db. */
static inline modcp_db_t *modcp_plcmem_find_db(const modcp_plcmem_t *mem, uint16_t number)
{
    if (mem->dbs == NULL) {
        return NULL;
    }
    if (mem->db_count <= 4u) { /* a few DBs: in order, no halving */
        for (uint32_t k = 0; k < mem->db_count; k++) {
            if (mem->dbs[k].number == number) {
                return &mem->dbs[k];
            }
        }
        return NULL;
    }
    uint32_t lo = 0;
    uint32_t hi = mem->db_count; /* search [lo, hi) */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u;
        uint16_t n = mem->dbs[mid].number;
        if (n == number) {
            return &mem->dbs[mid];
        }
        if (n < number) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return NULL;
}

/* The byte storage of an I / Q / M / DB operand covering [offset, offset + len), or
 * NULL with *ev set. The FB locates every job's bytes with it (fb.c), plcmem.c every
 * access; where it is inlined is the compiler's choice (always inlined: 328 B more in
 * the FB image at -Os, no instruction less per request at -O2). */
static inline uint8_t *modcp_plcmem_byte_area(const modcp_plcmem_t *mem,
                                              const modcp_operand_t *op, uint32_t len,
                                              modcp_event_t *ev)
{
    uint8_t *base = NULL;
    uint32_t size = 0;
    modcp_event_t err = MODCP_EV_AREA_ACCESS;
    switch (op->area) {
    case MODCP_AREA_I:
        base = mem->i;
        size = mem->i_size;
        break;
    case MODCP_AREA_Q:
        base = mem->q;
        size = mem->q_size;
        break;
    case MODCP_AREA_M:
        base = mem->m;
        size = mem->m_size;
        break;
    case MODCP_AREA_DB: {
        const modcp_db_t *db = modcp_plcmem_find_db(mem, op->db);
        err = MODCP_EV_DB_ACCESS;
        if (db != NULL) {
            base = db->data;
            size = db->size;
        }
        break;
    }
    default:
        break;
    }
    if (base == NULL || (uint32_t)op->offset + len > size) {
        *ev = err;
        return NULL;
    }
    *ev = MODCP_EV_NONE;
    return base + op->offset;
}

/* Area sizes as the CPU side reports them at init (work_db left 0). */
void modcp_plcmem_areas(const modcp_plcmem_t *mem, modcp_areas_t *out);
/* Check an access of len bytes at op as modcp_plcmem_read / _write would (same
 * events), copying nothing; *bytes = the storage of those bytes for I / Q / M / DB
 * (valid while the memory layout stays), NULL for T / C (elements: use read / write)
 * or on an error. */
modcp_event_t modcp_plcmem_locate(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                  uint16_t len, uint8_t **bytes);
/* The same for a bit write of op->count bits from op->offset / op->bit (same events as
 * modcp_plcmem_write_bits); *bytes = the storage at op->offset. */
modcp_event_t modcp_plcmem_locate_bits(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                       uint8_t **bytes);
/* Bit k (k < count) of bits (bit k % 8 of bits[k / 8]) into bit first + k of dst (bit
 * (first + k) % 8 of dst[(first + k) / 8]); the other bits of dst are untouched. A byte at
 * a time: whole bytes are stored, masks only at the first and the last byte. */
void modcp_bits_put(uint8_t *dst, uint32_t first, uint32_t count, const uint8_t *bits);

#endif
