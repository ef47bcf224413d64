/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of backplane.c (modcp/backplane.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_BACKPLANE_INTERNAL_H
#define MODCP_BACKPLANE_INTERNAL_H

#include <stddef.h>

#include "modcp/backplane.h"

/* On a little-endian target the backplane's headers are laid out as their structs lie
 * in memory (static asserts at each codec): encoding and decoding them are copies. Any
 * other target encodes them field by field; a build may ask for that path with
 * MODCP_BP_LE=0 (modcp_core_natural: the unit tests run it on the host). */
#ifndef MODCP_BP_LE
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define MODCP_BP_LE 1
#else
#define MODCP_BP_LE 0
#endif
#endif

/* CP side: publish the status area. */
void modcp_bp_publish_status(modcp_backplane_t *bp, const modcp_cp_status_t *st);
/* CP side: write the status area in place — begin (the seqlock turns odd) returns it,
 * fill in every field, end (even again) publishes it. */
static inline modcp_cp_status_t *modcp_bp_status_begin(modcp_backplane_t *bp)
{
    uint32_t seq = atomic_load_explicit(&bp->status_seq, memory_order_relaxed);
    atomic_store_explicit(&bp->status_seq, seq + 1u, memory_order_relaxed);
    atomic_thread_fence(memory_order_release);
    return &bp->status;
}
static inline void modcp_bp_status_end(modcp_backplane_t *bp)
{
    uint32_t seq = atomic_load_explicit(&bp->status_seq, memory_order_relaxed);
    atomic_store_explicit(&bp->status_seq, seq + 1u, memory_order_release);
}
/* Zero-copy block transfer: the producer writes a block straight into its slot and the
 * consumer reads it there, so data crosses the backplane with one copy in and one out.
 * Producer: modcp_ring_slot() gives the free slot (NULL when the ring is full: the
 * producer produces nothing and tries again later, so a put never fails), it fills
 * data / len / kind / flags / tag, then modcp_ring_publish() stamps the sequence number
 * and hands the slot over. Consumer: modcp_ring_peek() gives the oldest block,
 * modcp_ring_release() hands its slot back when the consumer is done with it. */
static inline modcp_block_t *modcp_ring_slot(modcp_ring_t *r)
{
    uint32_t head = atomic_load_explicit(&r->head, memory_order_relaxed);
    uint32_t tail = atomic_load_explicit(&r->tail, memory_order_acquire);
    if ((uint32_t)(head - tail) >= MODCP_BP_DEPTH) {
        return (modcp_block_t *)0;
    }
    return &r->slot[head & (MODCP_BP_DEPTH - 1u)];
}
/* b: the slot modcp_ring_slot() gave. */
static inline void modcp_ring_publish(modcp_ring_t *r, modcp_block_t *b, uint8_t *seq)
{
    uint32_t head = atomic_load_explicit(&r->head, memory_order_relaxed);
    b->seq = *seq;
    *seq = (uint8_t)(*seq + 1u);
    atomic_store_explicit(&r->head, head + 1u, memory_order_release);
}
static inline void modcp_ring_release(modcp_ring_t *r)
{
    uint32_t tail = atomic_load_explicit(&r->tail, memory_order_relaxed);
    atomic_store_explicit(&r->tail, tail + 1u, memory_order_release);
}
/* Copy the n (<= 32) data bytes of a block (dst and src apart): a whole block as one
 * fixed-size copy (a few word moves instead of a byte-count loop); built for speed
 * (-O2), a shorter one as two fixed-size copies that overlap (the first and the last
 * 16 / 8 / 4 / 2 bytes: no call), else (-Os) as it is. */
static inline void modcp_block_copy(uint8_t *dst, const uint8_t *src, uint32_t n)
{
    if (n == MODCP_BLOCK_SIZE) {
        (void)memcpy(dst, src, MODCP_BLOCK_SIZE);
#if !defined(__OPTIMIZE_SIZE__)
    } else if (n >= 16u) {
        (void)memcpy(dst, src, 16);
        (void)memcpy(dst + n - 16u, src + n - 16u, 16);
    } else if (n >= 8u) {
        (void)memcpy(dst, src, 8);
        (void)memcpy(dst + n - 8u, src + n - 8u, 8);
    } else if (n >= 4u) {
        (void)memcpy(dst, src, 4);
        (void)memcpy(dst + n - 4u, src + n - 4u, 4);
    } else if (n >= 2u) {
        (void)memcpy(dst, src, 2);
        (void)memcpy(dst + n - 2u, src + n - 2u, 2);
    } else if (n == 1u) {
        dst[0] = src[0];
#endif
    } else if (n != 0u) {
        (void)memcpy(dst, src, n);
    } else {
        /* nothing to copy (src may be NULL then) */
    }
}
/* A block's len, kind, flags and tag as one word (modcp_block_word), written by
 * modcp_block_stamp: one store on a little-endian target. */
_Static_assert((size_t)offsetof(modcp_block_t, kind) == (size_t)offsetof(modcp_block_t, len) + 1u &&
                   (size_t)offsetof(modcp_block_t, flags) == (size_t)offsetof(modcp_block_t, len) + 2u &&
                   (size_t)offsetof(modcp_block_t, tag) == (size_t)offsetof(modcp_block_t, len) + 3u,
               "modcp_block_t: len, kind, flags, tag in a row");
static inline uint32_t modcp_block_word(uint32_t len, uint32_t kind, uint32_t flags, uint32_t tag)
{
    return len | kind << 8 | flags << 16 | tag << 24;
}
static inline void modcp_block_stamp(modcp_block_t *b, uint32_t word)
{
#if MODCP_BP_LE
    memcpy((uint8_t *)b + offsetof(modcp_block_t, len), &word, 4);
#else
    b->len = (uint8_t)word;
    b->kind = (uint8_t)(word >> 8);
    b->flags = (uint8_t)(word >> 16);
    b->tag = (uint8_t)(word >> 24);
#endif
}
/* The word modcp_block_stamp wrote: a block's len, kind, flags and tag compared in one go
 * (with modcp_block_word). */
static inline uint32_t modcp_block_peek_word(const modcp_block_t *b)
{
#if MODCP_BP_LE
    uint32_t word;
    memcpy(&word, (const uint8_t *)b + offsetof(modcp_block_t, len), 4);
    return word;
#else
    return modcp_block_word(b->len, b->kind, b->flags, b->tag);
#endif
}
/* Copying forms (tests, and messages built elsewhere). Producer side: publish one
 * block (seq is filled in from *seq, which is then incremented). Returns false (nothing
 * written) when the ring is full. */
bool modcp_ring_put(modcp_ring_t *r, const modcp_block_t *b, uint8_t *seq);
/* Producer side: a block from its parts, written into the free slot and published;
 * false (nothing written) when the ring is full or len > 32. */
bool modcp_ring_put_data(modcp_ring_t *r, uint8_t *seq, uint8_t kind, uint8_t flags, uint8_t tag,
                         const uint8_t *data, uint8_t len);
/* Consumer side: copy out and acknowledge the oldest block. Returns false when empty. */
bool modcp_ring_get(modcp_ring_t *r, modcp_block_t *b);
/* Consumer side: the oldest block without taking it (NULL when empty). It stays valid
 * until the consumer takes it. */
static inline const modcp_block_t *modcp_ring_peek(const modcp_ring_t *r)
{
    uint32_t tail = atomic_load_explicit(&r->tail, memory_order_relaxed);
    uint32_t head = atomic_load_explicit(&r->head, memory_order_acquire);
    if (head == tail) {
        return (const modcp_block_t *)0;
    }
    return &r->slot[tail & (MODCP_BP_DEPTH - 1u)];
}
/* Blocks free for the producer. */
static inline uint32_t modcp_ring_space(const modcp_ring_t *r)
{
    uint32_t head = atomic_load_explicit(&r->head, memory_order_acquire);
    uint32_t tail = atomic_load_explicit(&r->tail, memory_order_acquire);
    uint32_t used = head - tail;
    return used >= MODCP_BP_DEPTH ? 0u : MODCP_BP_DEPTH - used;
}
static inline void modcp_bp_put16(uint8_t *d, uint16_t v)
{
    d[0] = (uint8_t)(v & 0xFFu);
    d[1] = (uint8_t)(v >> 8);
}
static inline uint16_t modcp_bp_get16(const uint8_t *d)
{
    return (uint16_t)((unsigned)d[0] | ((unsigned)d[1] << 8));
}
/* The JOB header's wire layout (backplane.c) is op followed by the operand and len as
 * modcp_bp_job_t holds them (opnd without gaps, then len), little-endian: on a
 * little-endian target the codec is the op byte and two copies. */
#if MODCP_BP_LE
_Static_assert(offsetof(modcp_operand_t, area) == 0u &&
                   offsetof(modcp_operand_t, bit) == 1u && offsetof(modcp_operand_t, db) == 2u &&
                   offsetof(modcp_operand_t, offset) == 4u &&
                   offsetof(modcp_operand_t, count) == 6u && sizeof(modcp_operand_t) == 8u &&
                   MODCP_BP_JOB_HDR_LEN == 11u,
               "modcp_operand_t is the JOB header's bytes 1..8");
#endif
static inline uint8_t modcp_bp_job_encode(const modcp_bp_job_t *j, uint8_t *d)
{
    d[0] = j->op;
#if MODCP_BP_LE
    memcpy(d + 1, &j->opnd, sizeof j->opnd);
    memcpy(d + 9, &j->len, sizeof j->len);
#else
    d[1] = j->opnd.area;
    d[2] = j->opnd.bit;
    modcp_bp_put16(d + 3, j->opnd.db);
    modcp_bp_put16(d + 5, j->opnd.offset);
    modcp_bp_put16(d + 7, j->opnd.count);
    modcp_bp_put16(d + 9, j->len);
#endif
    return (uint8_t)MODCP_BP_JOB_HDR_LEN;
}
static inline bool modcp_bp_job_decode(const uint8_t *d, uint8_t len, modcp_bp_job_t *j)
{
    if (len < MODCP_BP_JOB_HDR_LEN) {
        return false;
    }
    j->op = d[0];
#if MODCP_BP_LE
    memcpy(&j->opnd, d + 1, sizeof j->opnd);
    memcpy(&j->len, d + 9, sizeof j->len);
#else
    j->opnd.area = d[1];
    j->opnd.bit = d[2];
    j->opnd.db = modcp_bp_get16(d + 3);
    j->opnd.offset = modcp_bp_get16(d + 5);
    j->opnd.count = modcp_bp_get16(d + 7);
    j->len = modcp_bp_get16(d + 9);
#endif
    return true;
}
/* The REPLY header is modcp_bp_reply_t as it lies in memory on a little-endian target. */
#if MODCP_BP_LE
_Static_assert(sizeof(modcp_event_t) == 2u && offsetof(modcp_bp_reply_t, event) == 0u &&
                   offsetof(modcp_bp_reply_t, error_nr) == 2u &&
                   offsetof(modcp_bp_reply_t, len) == 4u &&
                   sizeof(modcp_bp_reply_t) == MODCP_BP_REPLY_HDR_LEN,
               "modcp_bp_reply_t is the REPLY header's layout");
#endif
static inline uint8_t modcp_bp_reply_encode(const modcp_bp_reply_t *r, uint8_t *d)
{
#if MODCP_BP_LE
    memcpy(d, r, MODCP_BP_REPLY_HDR_LEN);
#else
    modcp_bp_put16(d, r->event);
    modcp_bp_put16(d + 2, r->error_nr);
    modcp_bp_put16(d + 4, r->len);
#endif
    return (uint8_t)MODCP_BP_REPLY_HDR_LEN;
}
static inline bool modcp_bp_reply_decode(const uint8_t *d, uint8_t len, modcp_bp_reply_t *r)
{
    if (len < MODCP_BP_REPLY_HDR_LEN) {
        return false;
    }
    r->event = modcp_bp_get16(d);
    r->error_nr = modcp_bp_get16(d + 2);
    r->len = modcp_bp_get16(d + 4);
    return true;
}
uint8_t modcp_bp_init_encode(const modcp_bp_init_t *i, uint8_t *d);
bool modcp_bp_init_decode(const uint8_t *d, uint8_t len, modcp_bp_init_t *i);

#endif
