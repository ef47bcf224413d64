/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — CP side of the backplane (docs/cpu-cp-interface.md, [RTU-2003] §4.6).
 *
 * A job goes out as one header block (kind JOB, FIRST, the job's tag, data = the
 * encoded modcp_bp_job_t) and, when its write data fits after the header (up to
 * MODCP_BP_JOB_INLINE bytes) or there is none (READ), that is the whole job, flagged
 * LAST too; else ceil(len / 32) data blocks of 32 bytes follow (the last one shorter
 * and flagged LAST). The start and each poll push as many blocks as the ring has free
 * slots, each written in place into its slot (the write data is copied once, from the
 * request into the slot); nothing is produced when no slot is free, so no put ever
 * fails. REPLY blocks are read in place and released (read data: one copy, from the
 * slot into the caller's buffer; a header flagged LAST carries the data after it).
 *
 * The header of a new job is only pushed once the CPU-bound ring is empty, i.e. once
 * the CPU side has consumed every block of the previous job. In normal operation this
 * costs nothing (the previous job was answered, so it was consumed); after a timeout
 * it guarantees that at most one job's blocks are ever queued, so the single
 * abort_tag cancels every job the CP gave up on. Because of that, a new job's tag
 * that equals abort_tag (255 jobs later) may clear abort_tag safely.
 *
 * Incoming blocks: the sequence number is checked (the first block seen syncs, a gap
 * counts a protocol error and resyncs); REPLY blocks are accepted only with the tag
 * of the job that is waiting, everything else (stale replies after a timeout) is
 * dropped. PARAMS / INIT messages from the CPU side are independent of the job and
 * may interleave with its blocks. */
#include "modcp/job.h"

#include <stddef.h>
#include <string.h>
#include "backplane_internal.h"
#include "job_internal.h"
#include "inline_internal.h"

#define JOB_NO_ABORT 0x100u

/* j is zeroed (modcp_cp_init clears the CP object it lives in) */
void modcp_job_init(modcp_job_t *j, modcp_backplane_t *bp, uint8_t *msgbuf, uint16_t msgcap)
{
    j->bp = bp;
    j->msgbuf = msgbuf;
    j->msgcap = msgbuf != NULL ? msgcap : 0u;
}
_Static_assert((int)MODCP_JOBST_IDLE == 0, "a zeroed job is idle");

bool modcp_job_busy(const modcp_job_t *j)
{
    return j->state != (uint8_t)MODCP_JOBST_IDLE;
}

static MODCP_SPEED_INLINE void push_blocks(modcp_job_t *j);

/* An unexpected block (kind: MODCP_JOB_ERR_*): counted, and its kind kept for the owner. */
static MODCP_NOINLINE void proto_error(modcp_job_t *j, unsigned kind)
{
    j->proto_errors++;
    j->new_errors = (uint8_t)(j->new_errors | kind);
}

void modcp_job_configure(modcp_job_t *j, uint16_t limit, uint32_t timeout_us)
{
    j->limit = limit;
    j->timeout_us = timeout_us;
}

modcp_event_t modcp_job_start(modcp_job_t *j, const modcp_bp_job_t *hdr, const uint8_t *wdata,
                              uint8_t *rbuf, uint16_t rcap, uint32_t now_us)
{
    if (modcp_job_busy(j)) {
        return MODCP_EV_INTERNAL_SEND;
    }
    if (hdr->len > j->limit) {
        return MODCP_EV_JOB_LENGTH;
    }
    if (hdr->op == MODCP_JOB_READ) {
        if (rcap < hdr->len || (rbuf == NULL && hdr->len > 0u)) {
            return MODCP_EV_JOB_LENGTH;
        }
    } else if (wdata == NULL && hdr->len > 0u) {
        return MODCP_EV_INTERNAL_SEND; /* nothing to send: the caller's mistake */
    } else {
        /* a write with its data */
    }
    uint32_t tag = j->tag + 1u; /* 1 ... 255, then 1 again (0 is no job's) */
    j->tag = (uint8_t)(tag + (tag >> 8));
    j->hdr = hdr;
    j->hdr_sent = false;
    j->wdata = wdata;
    j->wpos = 0;
    j->rbuf = rbuf;
    j->rcap = rbuf != NULL ? rcap : 0u;
    j->t0_us = now_us;
    j->state = MODCP_JOBST_SENDING; /* rlen / rexpect: on the REPLY header; event /
                                       error_nr: when the job finishes */
    push_blocks(j); /* the first blocks go out at once */
    return MODCP_EV_NONE;
}

/* Tell the CPU side not to execute the current job. Only needed when its header went
 * out: otherwise nothing of it is queued, and abort_tag keeps cancelling the job that
 * may still sit in the ring. */
static void cancel(modcp_job_t *j)
{
    if (j->hdr_sent) {
        atomic_store_explicit(&j->bp->abort_tag, (uint32_t)j->tag, memory_order_release);
    }
}

void modcp_job_abort(modcp_job_t *j)
{
    if (modcp_job_busy(j)) {
        cancel(j);
    }
    j->state = MODCP_JOBST_IDLE;
}

/* A job crosses as its header block — with the write data after the header when it
 * fits (up to MODCP_BP_JOB_INLINE bytes: every FC05 / FC06 / FC22, FC15 up to 168
 * coils, FC16 up to 10 registers) and for every read job: then that one block is the
 * whole job, flagged FIRST and LAST — and else as many 32-byte data blocks as there are
 * free slots. Each block is written straight into its slot (the write data: one copy
 * from the request) and published at once. */

/* Stamp block b, the free slot at the head of the ring towards the CPU side (word:
 * modcp_block_word), and hand it over (the compiler places it: a fixed placement
 * measured no difference, tools/size and tools/bench). */
static void hand_over(modcp_job_t *j, modcp_block_t *b, uint32_t word)
{
    modcp_block_stamp(b, word);
    modcp_ring_publish(&j->bp->to_cpu, b, &j->tx_seq);
}

bool modcp_job_send_ack(modcp_job_t *j, modcp_event_t ev)
{
    modcp_block_t *b = modcp_ring_slot(&j->bp->to_cpu);
    if (b == NULL) {
        return false;
    }
    b->data[0] = (uint8_t)(ev & 0xFFu);
    b->data[1] = (uint8_t)(ev >> 8);
    hand_over(j, b, modcp_block_word(2, MODCP_BP_INIT_ACK, MODCP_BLK_FIRST | MODCP_BLK_LAST, 0));
    return true;
}

/* The data blocks of a job whose header is out. */
static void push_data(modcp_job_t *j)
{
    modcp_ring_t *r = &j->bp->to_cpu;
    modcp_block_t *b;
    while (j->state == (uint8_t)MODCP_JOBST_SENDING && (b = modcp_ring_slot(r)) != NULL) {
        uint32_t rest = (uint32_t)j->hdr->len - j->wpos;
#if !defined(__OPTIMIZE_SIZE__) /* -O2: a whole block that is not the last, without the
                                   arithmetic of the last one (-Os: the general form) */
        if (rest > MODCP_BLOCK_SIZE) {
            (void)memcpy(b->data, j->wdata + j->wpos, MODCP_BLOCK_SIZE);
            j->wpos = (uint16_t)(j->wpos + MODCP_BLOCK_SIZE);
            hand_over(j, b, modcp_block_word(MODCP_BLOCK_SIZE, MODCP_BP_JOB, 0, j->tag));
            continue;
        }
#endif
        uint32_t n = rest > MODCP_BLOCK_SIZE ? MODCP_BLOCK_SIZE : rest;
        uint8_t flags = 0;
        modcp_block_copy(b->data, j->wdata + j->wpos, n);
        j->wpos = (uint16_t)(j->wpos + n);
        if (n == rest) {
            flags = MODCP_BLK_LAST; /* nothing more to send */
            j->state = MODCP_JOBST_WAITING;
        }
        hand_over(j, b, modcp_block_word(n, MODCP_BP_JOB, flags, j->tag));
    }
}

/* The header block, once the ring is empty (see the top of this file), then the data. */
static MODCP_SPEED_INLINE void push_blocks(modcp_job_t *j)
{
    modcp_ring_t *r = &j->bp->to_cpu;
    if (!j->hdr_sent) {
        uint32_t head = atomic_load_explicit(&r->head, memory_order_relaxed);
        if (atomic_load_explicit(&r->tail, memory_order_acquire) != head) {
            return; /* previous blocks not consumed yet */
        }
        if (atomic_load_explicit(&j->bp->abort_tag, memory_order_acquire) == (uint32_t)j->tag) {
            atomic_store_explicit(&j->bp->abort_tag, JOB_NO_ABORT, memory_order_release);
        }
        modcp_block_t *b = &r->slot[head & (MODCP_BP_DEPTH - 1u)];
        uint32_t n = modcp_bp_job_encode(j->hdr, b->data);
        uint32_t len = j->hdr->len;
        uint8_t flags = MODCP_BLK_FIRST;
        j->hdr_sent = true;
        if (j->hdr->op == MODCP_JOB_READ || len <= MODCP_BP_JOB_INLINE) {
            if (j->hdr->op != MODCP_JOB_READ) { /* the write data with the header */
#if defined(__OPTIMIZE_SIZE__) /* -Os: a call (16 B less than the loop, Cortex-M3) */
                modcp_block_copy(b->data + n, j->wdata, len);
                n += len;
#else /* -O2: the 1 or 2 bytes of FC05 / FC06 without a call or a chain of tests */
                const uint8_t *w = j->wdata;
                for (; n < MODCP_BP_JOB_HDR_LEN + len; n++) {
                    b->data[n] = *w++;
                }
#endif
            }
            flags = MODCP_BLK_FIRST | MODCP_BLK_LAST; /* the whole job */
            j->state = MODCP_JOBST_WAITING;
        }
        hand_over(j, b, modcp_block_word(n, MODCP_BP_JOB, flags, j->tag));
    }
#if !defined(__OPTIMIZE_SIZE__) /* -O2: no call when the header block held the whole job
                                   (-Os: push_data is inline here, its loop tests it) */
    if (j->state != (uint8_t)MODCP_JOBST_SENDING) {
        return;
    }
#endif
    push_data(j);
}

static modcp_jobp_t finish(modcp_job_t *j, modcp_event_t ev, uint16_t error_nr)
{
    j->event = ev;
    j->error_nr = error_nr;
    j->state = MODCP_JOBST_IDLE;
    return MODCP_JOBP_DONE;
}

/* The REPLY's data is complete: exactly the announced bytes, and for a read exactly
 * the bytes the job asked for, all of them stored. */
static modcp_jobp_t finish_reply(modcp_job_t *j)
{
    bool ok = j->rlen == j->rexpect && j->rlen <= j->rcap &&
              (j->hdr->op != MODCP_JOB_READ || j->rexpect == j->hdr->len);
    return finish(j, ok ? MODCP_EV_NONE : MODCP_EV_XFER_STATE, 0);
}

/* A REPLY block out of order (a second header, a short one, data before the header):
 * a protocol error, and the job ends with (0E)33H. */
static MODCP_NOINLINE modcp_jobp_t reply_out_of_order(modcp_job_t *j)
{
    proto_error(j, MODCP_JOB_ERR_PROTO);
    return finish(j, MODCP_EV_XFER_STATE, 0);
}

static modcp_jobp_t rx_reply(modcp_job_t *j, const modcp_block_t *b)
{
    if (!modcp_job_busy(j) || b->tag != j->tag) {
        return MODCP_JOBP_NOTHING; /* stale reply of a job we gave up on */
    }
    const uint8_t *d = b->data;
    uint32_t n = b->len;
    if ((b->flags & MODCP_BLK_FIRST) != 0u) {
        if (j->state == (uint8_t)MODCP_JOBST_RECEIVING || n < MODCP_BP_REPLY_HDR_LEN) {
            return reply_out_of_order(j);
        }
        /* the header's fields read where they are: modcp_bp_reply_decode into a local
         * costs 44 B flash (Cortex-M3 -Os, LTO) and 2 instructions per job */
        modcp_event_t ev = modcp_bp_get16(d);
        if (ev != MODCP_EV_NONE) {
            return finish(j, ev, modcp_bp_get16(d + 2));
        }
        j->rexpect = modcp_bp_get16(d + 4);
        j->rlen = 0;
        j->state = MODCP_JOBST_RECEIVING;
        if ((b->flags & MODCP_BLK_LAST) == 0u) {
            return MODCP_JOBP_NOTHING; /* data blocks follow */
        }
        d += MODCP_BP_REPLY_HDR_LEN; /* the whole reply in one block: data after the header */
        n -= MODCP_BP_REPLY_HDR_LEN;
    } else if (j->state != (uint8_t)MODCP_JOBST_RECEIVING) {
        return reply_out_of_order(j); /* data before the header */
    } else {
        /* a data block of the reply being received */
    }
    if (n > 0u) { /* count everything that arrived (saturating), store only what fits */
        uint32_t room = j->rlen < j->rcap ? (uint32_t)j->rcap - j->rlen : 0u;
        modcp_block_copy(j->rbuf + j->rlen, d, n < room ? n : room);
        uint32_t total = (uint32_t)j->rlen + n;
        j->rlen = (uint16_t)(total > 0xFFFFu ? 0xFFFFu : total);
    }
    if ((b->flags & MODCP_BLK_LAST) != 0u) {
        return finish_reply(j);
    }
    return MODCP_JOBP_NOTHING;
}

static modcp_jobp_t rx_params(modcp_job_t *j, const modcp_block_t *b)
{
    if ((b->flags & MODCP_BLK_FIRST) != 0u) {
        j->msgkind = MODCP_BP_PARAMS;
        j->msglen = 0;
        j->msg_overflow = false;
    } else if (j->msgkind != MODCP_BP_PARAMS) {
        proto_error(j, MODCP_JOB_ERR_PROTO); /* continuation without a start */
        return MODCP_JOBP_NOTHING;
    } else {
        /* the next block of the record being received */
    }
    if ((uint32_t)j->msglen + b->len > j->msgcap) {
        j->msg_overflow = true;
    } else if (b->len > 0u) {
        (void)memcpy(j->msgbuf + j->msglen, b->data, b->len);
        j->msglen = (uint16_t)(j->msglen + b->len);
    } else {
        /* an empty block: nothing to store */
    }
    if ((b->flags & MODCP_BLK_LAST) == 0u) {
        return MODCP_JOBP_NOTHING;
    }
    j->msgkind = 0;
    if (j->msg_overflow) {
        j->msglen = 0;
    }
    return MODCP_JOBP_PARAMS;
}

#if !defined(__OPTIMIZE_SIZE__)
/* The common block of a long read: a whole data block of the reply being received, in
 * sequence, with room for it. Taken in one word compare and three more; rx_block and
 * rx_reply would do exactly the same with it (in RECEIVING the sequence is synced: the
 * reply's header went through rx_block). Built for speed only (-O2; FC01 / FC03 with
 * 125 registers: 190 instructions less per request, callgrind); built for size (-Os,
 * the MCU builds) the general path takes it (68 B less, Cortex-M3). */
static MODCP_ALWAYS_INLINE bool rx_reply_data(modcp_job_t *j, const modcp_block_t *b)
{
    if (j->state != (uint8_t)MODCP_JOBST_RECEIVING ||
        modcp_block_peek_word(b) != modcp_block_word(MODCP_BLOCK_SIZE, MODCP_BP_REPLY, 0, j->tag) ||
        b->seq != j->rx_seq || (uint32_t)j->rlen + MODCP_BLOCK_SIZE > j->rcap) {
        return false;
    }
    (void)memcpy(j->rbuf + j->rlen, b->data, MODCP_BLOCK_SIZE);
    j->rlen = (uint16_t)(j->rlen + MODCP_BLOCK_SIZE);
    j->rx_seq = (uint8_t)(j->rx_seq + 1u);
    return true;
}
#endif

#if !defined(__OPTIMIZE_SIZE__)
/* The reply of a write (or of a refused job): its header alone, FIRST and LAST, in
 * sequence, while the job waits for it. Taken in one word compare and two more;
 * rx_block, rx_reply and finish_reply would do exactly the same with it. Built for speed
 * only, as rx_reply_data (FC05 / FC06: 20 instructions less per request). */
static MODCP_ALWAYS_INLINE bool rx_reply_alone(const modcp_job_t *j, const modcp_block_t *b)
{
    return j->state == (uint8_t)MODCP_JOBST_WAITING &&
           modcp_block_peek_word(b) == modcp_block_word(MODCP_BP_REPLY_HDR_LEN, MODCP_BP_REPLY,
                                                        MODCP_BLK_FIRST | MODCP_BLK_LAST, j->tag) &&
           b->seq == j->rx_seq && j->rx_synced;
}
#endif

#if !defined(__OPTIMIZE_SIZE__)
/* Take the reply rx_reply_alone found: the job is done. */
static MODCP_ALWAYS_INLINE modcp_jobp_t take_reply_alone(modcp_job_t *j, const modcp_block_t *b)
{
    j->rx_seq = (uint8_t)(j->rx_seq + 1u);
    modcp_event_t ev = modcp_bp_get16(b->data);
    if (ev != MODCP_EV_NONE) {
        return finish(j, ev, modcp_bp_get16(b->data + 2));
    }
    j->rexpect = modcp_bp_get16(b->data + 4);
    j->rlen = 0;
    return finish_reply(j);
}
#endif

static modcp_jobp_t rx_block(modcp_job_t *j, const modcp_block_t *b, modcp_bp_init_t *init)
{
#if !defined(__OPTIMIZE_SIZE__)
    if (rx_reply_data(j, b)) {
        return MODCP_JOBP_NOTHING;
    }
    if (rx_reply_alone(j, b)) {
        return take_reply_alone(j, b);
    }
#endif
    if (b->seq != j->rx_seq && j->rx_synced) { /* (the first block seen syncs) */
        proto_error(j, MODCP_JOB_ERR_PROTO);
        if (j->msgkind != 0u) {
            j->msg_overflow = true; /* a message lost a block: report it empty */
        }
    }
    j->rx_synced = true;
    j->rx_seq = (uint8_t)(b->seq + 1u);
    if (b->len > MODCP_BLOCK_SIZE) {
        proto_error(j, MODCP_JOB_ERR_PROTO);
        return MODCP_JOBP_NOTHING;
    }
    if (b->kind == MODCP_BP_REPLY) { /* the common one: first */
        return rx_reply(j, b);
    }
    switch (b->kind) {
    case MODCP_BP_PARAMS:
        return rx_params(j, b);
    case MODCP_BP_INIT:
        if (!modcp_bp_init_decode(b->data, b->len, init)) {
            proto_error(j, MODCP_JOB_ERR_PROTO);
            return MODCP_JOBP_NOTHING;
        }
        return MODCP_JOBP_INIT;
    default:
        proto_error(j, MODCP_JOB_ERR_ILLEGAL); /* JOB / INIT_ACK travel the other way */
        return MODCP_JOBP_NOTHING;
    }
}

#if MODCP_SHARED_PARAMS_BUFFER
void modcp_job_params_grant(modcp_job_t *j)
{
    j->msg_granted = true;
}

/* msgbuf is shared with its owner (the CP's frame buffer): the first block of a
 * PARAMS record (next, the block at the ring's tail) stays in the ring until the owner
 * has granted it. */
static bool params_wait(const modcp_job_t *j, const modcp_block_t *next)
{
    return !j->msg_granted && next->kind == MODCP_BP_PARAMS &&
           (next->flags & MODCP_BLK_FIRST) != 0u;
}
#endif

/* modcp_job_poll's loop over the blocks in, then the timeout and the blocks out. */
static MODCP_SPEED_NOINLINE modcp_jobp_t poll_blocks(modcp_job_t *j, uint32_t now_us,
                                                     modcp_bp_init_t *init)
{
    modcp_ring_t *in = &j->bp->to_cp;
    const modcp_block_t *b;
    while ((b = modcp_ring_peek(in)) != NULL) {
#if MODCP_SHARED_PARAMS_BUFFER
        if (params_wait(j, b)) {
            return MODCP_JOBP_PARAMS_START;
        }
        j->msg_granted = false; /* a grant covers the one block it was asked for */
#endif
        modcp_jobp_t r = rx_block(j, b, init); /* read in place (one copy out for REPLY data) */
        modcp_ring_release(in);
        if (r != MODCP_JOBP_NOTHING) {
            return r;
        }
    }
    if (modcp_job_busy(j) && (uint32_t)(now_us - j->t0_us) >= j->timeout_us) {
        cancel(j);
        return finish(j, j->hdr->op == MODCP_JOB_BITWRITE ? MODCP_EV_FB_TIMEOUT
                                                         : MODCP_EV_XFER_TIMEOUT,
                      0);
    }
    if (j->state == (uint8_t)MODCP_JOBST_SENDING) {
        push_blocks(j);
    }
    return MODCP_JOBP_NOTHING;
}

modcp_jobp_t modcp_job_poll(modcp_job_t *j, uint32_t now_us, modcp_bp_init_t *init)
{
#if !defined(__OPTIMIZE_SIZE__)
    /* built for speed, the reply of a write (FC05 / FC06) at the ring's tail is taken
     * before anything else, as poll_blocks would take it first, without its stack frame
     * (-Os: poll_blocks takes it) */
    modcp_ring_t *in = &j->bp->to_cp;
    const modcp_block_t *b = modcp_ring_peek(in);
    if (b != NULL && rx_reply_alone(j, b)) {
#if MODCP_SHARED_PARAMS_BUFFER
        j->msg_granted = false; /* a grant covers the one block it was asked for */
#endif
        modcp_jobp_t r = take_reply_alone(j, b); /* the job is done */
        modcp_ring_release(in);
        return r;
    }
#endif
    return poll_blocks(j, now_us, init);
}
