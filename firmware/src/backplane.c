/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CPU–CP backplane: two SPSC rings of 32-byte blocks and the message
 * header (de)serialisers (docs/cpu-cp-interface.md).
 *
 * Ring protocol. head counts the blocks the producer has published, tail the blocks
 * the consumer has acknowledged; both only grow and wrap at 2^32, the slot of block n
 * is n % MODCP_BP_DEPTH (a power of two, so the wrap is seamless). Only the producer
 * writes head and the slot contents, only the consumer writes tail:
 *   put: read tail (acquire: the consumer is done with the slot), fill the slot,
 *        publish head + 1 (release: the slot contents become visible with it);
 *   get: read head (acquire: pairs with the producer's release), copy the slot out,
 *        acknowledge tail + 1 (release: the slot may now be reused).
 * The hot path does not copy whole blocks: the producer fills the free slot in place
 * (modcp_ring_slot, then modcp_ring_publish = head + 1) and the consumer reads the
 * oldest slot in place (modcp_ring_peek, then modcp_ring_release = tail + 1), so the
 * data of a block is copied once into the slot and once out of it.
 *
 * Header layouts in block data[], all fields little-endian, fixed offsets:
 *   JOB   (11 bytes)  0 op | 1 area | 2 bit | 3..4 db | 5..6 offset | 7..8 count |
 *                     9..10 len
 *   REPLY (6 bytes)   0..1 event | 2..3 error_nr | 4..5 len
 *   INIT  (14 bytes)  0..1 i_bytes | 2..3 q_bytes | 4..5 m_bytes | 6..7 timers |
 *                     8..9 counters | 10..11 work_db | 12..13 record_crc
 *   INIT_ACK (2 bytes) 0..1 event       (written/read by job.c and fb.c)
 * A JOB / REPLY header block flagged LAST carries the message's data right after the
 * header (JOB: up to 21 bytes from offset 11, REPLY: up to 26 from offset 6).
 * Decoders accept a longer block (trailing bytes ignored) and refuse a shorter one. */
#include "modcp/backplane.h"

#include <string.h>

#include "modcp/crc.h"
#include "backplane_internal.h"

#define BP_INIT_LEN 14u
#define BP_NO_ABORT 0x100u

_Static_assert((MODCP_BP_DEPTH & (MODCP_BP_DEPTH - 1u)) == 0u && MODCP_BP_DEPTH > 0u,
               "MODCP_BP_DEPTH must be a power of two");

void modcp_bp_init(modcp_backplane_t *bp)
{
    (void)memset(bp, 0, sizeof *bp); /* empty rings (head = tail = 0), status area zero */
    atomic_store_explicit(&bp->abort_tag, BP_NO_ABORT, memory_order_release);
}

bool modcp_ring_put(modcp_ring_t *r, const modcp_block_t *b, uint8_t *seq)
{
    modcp_block_t *slot = modcp_ring_slot(r);
    if (slot == NULL) {
        return false;
    }
    *slot = *b;
    modcp_ring_publish(r, slot, seq);
    return true;
}

bool modcp_ring_get(modcp_ring_t *r, modcp_block_t *b)
{
    const modcp_block_t *slot = modcp_ring_peek(r);
    if (slot == NULL) {
        return false;
    }
    *b = *slot;
    modcp_ring_release(r);
    return true;
}

#define put16 modcp_bp_put16
#define get16 modcp_bp_get16

/* The INIT payload is modcp_bp_init_t as it lies in memory on a little-endian target:
 * seven 16-bit fields in wire order, no gaps. */
#if MODCP_BP_LE
_Static_assert(sizeof(modcp_bp_init_t) == BP_INIT_LEN &&
                   offsetof(modcp_bp_init_t, areas) == 0u &&
                   offsetof(modcp_areas_t, i_bytes) == 0u &&
                   offsetof(modcp_areas_t, q_bytes) == 2u &&
                   offsetof(modcp_areas_t, m_bytes) == 4u &&
                   offsetof(modcp_areas_t, timers) == 6u &&
                   offsetof(modcp_areas_t, counters) == 8u &&
                   offsetof(modcp_areas_t, work_db) == 10u &&
                   offsetof(modcp_bp_init_t, record_crc) == 12u,
               "modcp_bp_init_t is the INIT payload's layout");
#endif

uint16_t modcp_bp_record_id(const uint8_t *record, uint16_t len)
{
    return modcp_crc16(record, len > 2u ? len - 2u : len);
}

uint8_t modcp_bp_init_encode(const modcp_bp_init_t *i, uint8_t *d)
{
#if MODCP_BP_LE
    memcpy(d, i, BP_INIT_LEN);
#else
    put16(d, i->areas.i_bytes);
    put16(d + 2, i->areas.q_bytes);
    put16(d + 4, i->areas.m_bytes);
    put16(d + 6, i->areas.timers);
    put16(d + 8, i->areas.counters);
    put16(d + 10, i->areas.work_db);
    put16(d + 12, i->record_crc);
#endif
    return (uint8_t)BP_INIT_LEN;
}

bool modcp_bp_init_decode(const uint8_t *d, uint8_t len, modcp_bp_init_t *i)
{
    if (len < BP_INIT_LEN) {
        return false;
    }
#if MODCP_BP_LE
    memcpy(i, d, BP_INIT_LEN);
#else
    i->areas.i_bytes = get16(d);
    i->areas.q_bytes = get16(d + 2);
    i->areas.m_bytes = get16(d + 4);
    i->areas.timers = get16(d + 6);
    i->areas.counters = get16(d + 8);
    i->areas.work_db = get16(d + 10);
    i->record_crc = get16(d + 12);
#endif
    return true;
}

bool modcp_ring_put_data(modcp_ring_t *r, uint8_t *seq, uint8_t kind, uint8_t flags, uint8_t tag,
                         const uint8_t *data, uint8_t len)
{
    modcp_block_t *b = len <= MODCP_BLOCK_SIZE ? modcp_ring_slot(r) : NULL;
    if (b == NULL) {
        return false;
    }
    if (len > 0u) {
        (void)memcpy(b->data, data, len);
    }
    b->len = len;
    b->kind = kind;
    b->flags = flags;
    b->tag = tag;
    modcp_ring_publish(r, b, seq);
    return true;
}
