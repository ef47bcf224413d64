/* modcp — the core's internal interface of plcmem.c (modcp/plcmem.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_PLCMEM_INTERNAL_H
#define MODCP_PLCMEM_INTERNAL_H

#include "modcp/plcmem.h"

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
