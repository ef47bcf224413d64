/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — controller memory model (CPU side only): I, Q, M bytes, T and C words and
 * data blocks, with their real sizes and the list of existing DBs. The storage is the
 * caller's (static arrays on a board, anything on the host); this module only checks
 * and copies. T and C elements are 16-bit values; on the wire and in jobs they are
 * high byte first (controller byte order). */
#ifndef MODCP_PLCMEM_H
#define MODCP_PLCMEM_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/events.h"
#include "modcp/map.h"

typedef struct {
    uint16_t number; /* 1 ... 65535 */
    uint16_t size;   /* bytes */
    uint8_t *data;
} modcp_db_t;

typedef struct {
    uint8_t *i;
    uint8_t *q;
    uint8_t *m;
    uint16_t *t;
    uint16_t *c;
    uint16_t i_size, q_size, m_size; /* bytes */
    uint16_t t_count, c_count;       /* elements */
    modcp_db_t *dbs;                 /* sorted by number, ascending */
    uint16_t db_count;
} modcp_plcmem_t;

/* The DB with this number, or NULL. */
modcp_db_t *modcp_plcmem_db(const modcp_plcmem_t *mem, uint16_t number);

/* Read len bytes of the operand into out: M/I/Q/DB bytes from op->offset (op->bit
 * ignored: whole bytes), or T/C elements from op->offset (2 bytes each, high first).
 * Returns (0E)38H for I/Q/M/T/C out of range, (0E)39H for a missing or short DB. */
modcp_event_t modcp_plcmem_read(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                uint8_t *out, uint16_t len);

/* Write len bytes (M, Q, I, DB, or T/C elements high byte first). Same events. */
modcp_event_t modcp_plcmem_write(modcp_plcmem_t *mem, const modcp_operand_t *op,
                                 const uint8_t *in, uint16_t len);

/* Read-modify-write of op->count bits starting at op->offset / op->bit; bit k of the
 * request is bit (k % 8) of bits[k / 8]. Other bits of the touched bytes are untouched.
 * Only M, Q, I and DB. Works a byte at a time: whole bytes are stored, masks only at
 * the first and last byte. */
modcp_event_t modcp_plcmem_write_bits(modcp_plcmem_t *mem, const modcp_operand_t *op,
                                      const uint8_t *bits);

#endif
