/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CPU side's communication FB (FB 80 / FB 180 model, [RTU-2003] §4, §7.6).
 *
 * One call per CPU cycle does, in this order:
 *   1. CP_START edge: clear the outputs (ERROR_NR / ERROR_INFO included) and start the
 *      initialisation (INIT, preceded by PARAMS unless the CP holds the record: it
 *      acknowledged an INIT for it before); a failed initialisation resets CP_START
 *      (in/out);
 *   2. continue pushing a pending REPLY (as many blocks as there are free slots);
 *   3. read CP blocks in place: INIT_ACK while waiting for it; a JOB header is checked
 *      completely (operation, amount, area, range) before any data: a READ is answered
 *      at once, its data read from controller memory straight into each reply slot (up
 *      to MODCP_BP_REPLY_INLINE bytes into the header's own); a write job's data is
 *      written straight from the slots into controller memory as it arrives (a
 *      one-block job's, after its header, at once), and the job is answered after its
 *      LAST block (no new blocks are read while a reply is still going out);
 *   4. initialisation (fb_init.c): START_TIME check, retry every MODCP_FB_RETRY_MS
 *      while the CP answers "not ready" or is silent, push PARAMS then INIT.
 *
 * Data crosses the backplane once per 32-byte block each way: no job buffer, one copy
 * between a slot and controller memory. Consistency guarantee (docs/cpu-cp-interface.md):
 * every block is written or read within one call, so each block is consistent (a one-block
 * job or reply as a whole); a job whose blocks are all handled in one FB call is consistent
 * as a whole: a write job of up to MODCP_BP_DEPTH blocks, header included, is executed only
 * when all of them are in (job_in_ring); a read's reply of up to MODCP_BP_DEPTH blocks goes
 * out in the call that answers it when the ring towards the CP is empty (as in normal
 * operation); a longer job whenever the other side keeps pace during the call.
 *
 * Job validation by the FB ([RTU-2003] §7.6), replied as (0E)57H + ERROR_NR and shown on
 * ERROR_NR / ERROR_INFO (they stay until the next CP_START edge): 10 unknown op (INFO = op)
 * · 12 count or len 0 (INFO = count) · 13 len above MODCP_FB_JOB_MAX, or fewer data bytes
 * than the bit count needs (INFO = len / count), or a MASKWRITE (FC22) that is not 4 data
 * bytes on one word (INFO = len) · 18 area not allowed for the op: READ I Q M T C DB, WRITE
 * / MASKWRITE Q M DB, BITWRITE M Q DB (INFO 0) · 11 BITWRITE start bit > 7 (INFO = start
 * byte) · 14 / 15 BITWRITE past the end of M / Q (INFO = last byte). Other replies: (0E)56H
 * FB not in RUN, (0E)3AH BITWRITE with the work DB missing, (0E)38H / (0E)39H from plcmem
 * (checked on the header: nothing is written), (0E)33H write data not as announced (a data
 * block of another size than announced, a header flagged LAST for a write without exactly
 * its data after it, or not LAST for a read: nothing more of the job is written). A job
 * whose tag is the backplane's abort_tag was given up by the CP: nothing (more) of it is
 * executed and it is not answered; a job that loses a block (sequence gap) is not continued
 * and not answered (the CP times out). */
#include "modcp/fb.h"

#include <stddef.h>
#include <string.h>

#include "backplane_internal.h"
#include "fb_internal.h"
#include "inline_internal.h"
#include "plcmem_internal.h"

void modcp_fb_init(modcp_fb_t *fb, modcp_backplane_t *bp, modcp_plcmem_t *mem,
                   const uint8_t *record, uint16_t record_len, uint16_t work_db,
                   uint32_t start_time_ms)
{
    (void)memset(fb, 0, sizeof *fb);
    fb->bp = bp;
    fb->mem = mem;
    fb->record = record;
    fb->record_len = record != NULL ? record_len : 0u;
    fb->work_db = work_db;
    fb->start_time_ms = start_time_ms;
    fb->state = MODCP_FBST_STOPPED;
    fb->params_pending = fb->record_len > 0u; /* the CPU sends the CP parameters at start */
    fb->err_changed = true; /* the first call writes ERROR_NR / ERROR_INFO (0) */
}

/* The part of a job's operand that starts `pos` data bytes into the job: byte areas
 * advance by bytes, T / C by 2-byte elements; a bit write keeps its start bit (a data
 * block holds 256 bits, whole bytes of the area). */
static modcp_operand_t opnd_at(const modcp_operand_t *o, uint16_t pos)
{
    modcp_operand_t r = *o;
    bool words = o->area == (uint8_t)MODCP_AREA_T || o->area == (uint8_t)MODCP_AREA_C;
    r.offset = (uint16_t)(o->offset + (words ? pos / 2u : pos));
    return r;
}

/* ---- replies ---------------------------------------------------------------------- */

/* Push the pending REPLY into the free slots: its header — followed by a READ's data
 * when all of it fits (MODCP_BP_REPLY_INLINE: the reply is that one block) —, then the
 * data blocks; the data is read from controller memory straight into each slot (one
 * copy). */
static void read_data(modcp_fb_t *fb, uint8_t *dst, uint32_t pos, uint32_t n)
{
    if (fb->job_mem != NULL) {
        modcp_block_copy(dst, fb->job_mem + pos, n);
    } else { /* T / C elements; the range was checked on the header */
        modcp_operand_t o = opnd_at(&fb->job.opnd, (uint16_t)pos);
        (void)modcp_plcmem_read(fb->mem, &o, dst, (uint16_t)n);
    }
}

static void pump_reply(modcp_fb_t *fb)
{
    modcp_ring_t *r = &fb->bp->to_cp;
    modcp_block_t *b;
    if (!fb->reply_hdr_sent) {
        if ((b = modcp_ring_slot(r)) == NULL) {
            return;
        }
        uint32_t len = fb->reply.len;
        uint32_t n = modcp_bp_reply_encode(&fb->reply, b->data);
        uint8_t flags = MODCP_BLK_FIRST;
        fb->reply_hdr_sent = true;
        if (len <= MODCP_BP_REPLY_INLINE) { /* the whole reply in this block */
            if (len > 0u) {
                read_data(fb, b->data + n, 0, len);
            }
            n += len;
            flags = MODCP_BLK_FIRST | MODCP_BLK_LAST;
            fb->reply_pending = false;
        }
        modcp_block_stamp(b, modcp_block_word(n, MODCP_BP_REPLY, flags, fb->job_tag));
        modcp_ring_publish(r, b, &fb->tx_seq);
    }
    while (fb->reply_pending && (b = modcp_ring_slot(r)) != NULL) {
        uint32_t rest = (uint32_t)fb->reply.len - fb->reply_pos;
#if !defined(__OPTIMIZE_SIZE__) /* -O2: a whole block of bytes at once (-Os: the general
                                   form; as job.c) */
        if (rest > MODCP_BLOCK_SIZE && fb->job_mem != NULL) {
            (void)memcpy(b->data, fb->job_mem + fb->reply_pos, MODCP_BLOCK_SIZE);
            fb->reply_pos = (uint16_t)(fb->reply_pos + MODCP_BLOCK_SIZE);
            modcp_block_stamp(b, modcp_block_word(MODCP_BLOCK_SIZE, MODCP_BP_REPLY, 0, fb->job_tag));
            modcp_ring_publish(r, b, &fb->tx_seq);
            continue;
        }
#endif
        uint32_t n = rest > MODCP_BLOCK_SIZE ? MODCP_BLOCK_SIZE : rest;
        uint32_t flags = 0;
        read_data(fb, b->data, fb->reply_pos, n);
        fb->reply_pos = (uint16_t)(fb->reply_pos + n);
        if (n == rest) {
            flags = MODCP_BLK_LAST;
            fb->reply_pending = false;
        }
        modcp_block_stamp(b, modcp_block_word(n, MODCP_BP_REPLY, flags, fb->job_tag));
        modcp_ring_publish(r, b, &fb->tx_seq);
    }
}

static void reply(modcp_fb_t *fb, modcp_event_t ev, uint16_t error_nr, uint16_t len)
{
    fb->job_active = false;
    fb->reply.event = ev;
    fb->reply.error_nr = error_nr;
    fb->reply.len = ev == MODCP_EV_NONE ? len : 0u;
    fb->reply_pos = 0;
    fb->reply_hdr_sent = false;
    fb->reply_pending = true;
    fb->jobs_done++;
}

static void reply_fb_error(modcp_fb_t *fb, uint16_t error_nr, uint32_t info)
{
    fb->out.error_nr = error_nr;
    fb->out.error_info = (uint16_t)(info > 0xFFFFu ? 0xFFFFu : info);
    fb->err_changed = true;
    reply(fb, MODCP_EV_FB_ERROR, error_nr, 0);
}

/* ---- job execution ---------------------------------------------------------------- */

static bool area_allowed(uint8_t op, uint8_t area)
{
    switch (area) {
    case MODCP_AREA_Q:
    case MODCP_AREA_M:
    case MODCP_AREA_DB:
        return true;
    case MODCP_AREA_I:
    case MODCP_AREA_T:
    case MODCP_AREA_C:
        return op == MODCP_JOB_READ;
    default:
        return false;
    }
}

/* BITWRITE checks on the header; false when the job was answered. */
static bool check_bitwrite(modcp_fb_t *fb)
{
    const modcp_operand_t *o = &fb->job.opnd;
    if (o->bit > 7u) {
        reply_fb_error(fb, MODCP_FB_ERR_START, o->offset);
        return false;
    }
    if (fb->job.len < ((uint32_t)o->count + 7u) / 8u) {
        reply_fb_error(fb, MODCP_FB_ERR_AMOUNT, o->count);
        return false;
    }
    uint32_t end = (uint32_t)o->offset + ((uint32_t)o->bit + o->count - 1u) / 8u;
    uint8_t *base = NULL;
    if (o->area == (uint8_t)MODCP_AREA_M) {
        if (end >= fb->mem->m_size) {
            reply_fb_error(fb, MODCP_FB_ERR_M_END, end);
            return false;
        }
        base = fb->mem->m;
    }
    if (o->area == (uint8_t)MODCP_AREA_Q) {
        if (end >= fb->mem->q_size) {
            reply_fb_error(fb, MODCP_FB_ERR_Q_END, end);
            return false;
        }
        base = fb->mem->q;
    }
    if (base != NULL) { /* M / Q: every byte addressed is inside (end checked above) */
        fb->job_mem = base + o->offset;
        return true;
    }
    /* a DB, or M / Q without storage: plcmem checks it (and says why not) */
    modcp_event_t ev = modcp_plcmem_locate_bits(fb->mem, o, &fb->job_mem);
    if (ev != MODCP_EV_NONE) {
        reply(fb, ev, 0, 0);
        return false;
    }
    return true;
}

static MODCP_ALWAYS_INLINE void exec_data(modcp_fb_t *fb, const uint8_t *d, uint32_t n, bool last);

/* modcp_plcmem_locate into job_mem, its byte areas' lookup inline (plcmem_internal.h). */
static MODCP_ALWAYS_INLINE modcp_event_t locate(modcp_fb_t *fb, const modcp_operand_t *o, uint32_t len)
{
    if ((o->area == (uint8_t)MODCP_AREA_T) || (o->area == (uint8_t)MODCP_AREA_C)) { /* elements */
        return modcp_plcmem_locate(fb->mem, o, (uint16_t)len, &fb->job_mem);
    }
    modcp_event_t ev;
    fb->job_mem = modcp_plcmem_byte_area(fb->mem, o, len, &ev);
    return ev;
}

/* A job's FIRST block b arrived, its header decoded into job (its tag in job_tag): check
 * everything that can be checked before the data — nothing is written by a job that
 * is refused. A READ is answered at once (its data follows from memory, pump_reply); a
 * write job whose data came with the header (FIRST and LAST: the whole job in one
 * block) is executed at once, else it becomes active and its data blocks are executed
 * as they arrive (rx_data). */
static void start_job(modcp_fb_t *fb, const modcp_block_t *b)
{
    if (atomic_load_explicit(&fb->bp->abort_tag, memory_order_acquire) == (uint32_t)fb->job_tag) {
        return; /* the CP timed out on this job: nothing is written, nobody waits */
    }
    if (fb->state != (uint8_t)MODCP_FBST_RUN) {
        reply(fb, MODCP_EV_FB_NOT_RUNNING, 0, 0);
        return;
    }
    const modcp_bp_job_t *jb = &fb->job;
    uint8_t op = jb->op;
    if (op != MODCP_JOB_READ && op != MODCP_JOB_WRITE && op != MODCP_JOB_BITWRITE &&
        op != MODCP_JOB_MASKWRITE) {
        reply_fb_error(fb, MODCP_FB_ERR_PROC_CODE, op);
        return;
    }
    if (op == MODCP_JOB_BITWRITE && fb->work_db != 0u &&
        modcp_plcmem_db(fb->mem, fb->work_db) == NULL) {
        reply(fb, MODCP_EV_WORK_DB, 0, 0); /* the job cannot be placed in the work area */
        return;
    }
    if (jb->opnd.count == 0u || (uint32_t)jb->len - 1u >= MODCP_FB_JOB_MAX) {
        if (jb->opnd.count == 0u || jb->len == 0u) {
            reply_fb_error(fb, MODCP_FB_ERR_AMOUNT0, jb->opnd.count);
        } else { /* len above MODCP_FB_JOB_MAX */
            reply_fb_error(fb, MODCP_FB_ERR_AMOUNT, jb->len);
        }
        return;
    }
    /* a READ is its header alone (LAST); a write's header is LAST exactly when all of
     * its data follows it in the block */
    const bool last = (b->flags & MODCP_BLK_LAST) != 0u;
    const bool read = op == (uint8_t)MODCP_JOB_READ;
    if (last ? (!read && ((uint32_t)b->len != ((uint32_t)MODCP_BP_JOB_HDR_LEN + jb->len))) : read) {
        reply(fb, MODCP_EV_XFER_STATE, 0, 0); /* data not as announced: execute nothing */
        return;
    }
    if (!area_allowed(op, jb->opnd.area)) {
        reply_fb_error(fb, MODCP_FB_ERR_AREA, 0);
        return;
    }
    modcp_event_t ev = MODCP_EV_NONE;
    if (op == MODCP_JOB_BITWRITE) {
        if (!check_bitwrite(fb)) {
            return;
        }
    } else {
        uint32_t n = jb->len;
        if (op == MODCP_JOB_MASKWRITE) {
            if (jb->len != 4u || jb->opnd.count != 2u) {
                reply_fb_error(fb, MODCP_FB_ERR_AMOUNT, jb->len);
                return;
            }
            n = 2u; /* the word the masks apply to */
        }
        ev = locate(fb, &jb->opnd, n);
        if (op == MODCP_JOB_READ) {
            reply(fb, ev, 0, jb->len); /* the data follows from memory (pump_reply) */
            return;
        }
    }
    if (ev != MODCP_EV_NONE) {
        reply(fb, ev, 0, 0);
        return;
    }
    fb->job_pos = 0;
    if (last) {
        exec_data(fb, b->data + MODCP_BP_JOB_HDR_LEN, jb->len, true); /* the whole job */
    } else {
        fb->job_active = true;
    }
}

/* FC22 mask write (MODCP_JOB_MASKWRITE): the word is read, masked and written back in
 * this one call, so nothing of the user program runs in between (atomic). */
static modcp_event_t exec_maskwrite(modcp_fb_t *fb, const uint8_t *masks)
{
    const modcp_operand_t *o = &fb->job.opnd;
    uint8_t w[2];
    modcp_event_t ev = modcp_plcmem_read(fb->mem, o, w, 2);
    if (ev == MODCP_EV_NONE) {
        for (unsigned k = 0; k < 2u; k++) {
            uint8_t and_mask = masks[k];
            uint8_t or_mask = masks[2u + k];
            w[k] = (uint8_t)((w[k] & and_mask) | (or_mask & (uint8_t)~and_mask));
        }
        ev = modcp_plcmem_write(fb->mem, o, w, 2);
    }
    return ev;
}

/* n bytes of the active write job's data at job_pos, read in place and written
 * straight into controller memory (one copy); last: the job's last bytes (CP_START_NDR
 * and the reply). */
static MODCP_ALWAYS_INLINE void exec_data(modcp_fb_t *fb, const uint8_t *d, uint32_t n, bool last)
{
    const modcp_bp_job_t *jb = &fb->job;
    /* WRITE / BITWRITE: only Q, M, DB (area_allowed), so job_mem is the storage */
    uint8_t *dst = fb->job_mem + fb->job_pos;
    modcp_event_t ev = MODCP_EV_NONE;
    switch (jb->op) {
    case MODCP_JOB_WRITE:
        if (n == 2u) { /* one register (FC06, FC16): no call */
            (void)memcpy(dst, d, 2);
        } else {
            modcp_block_copy(dst, d, n);
        }
        break;
    case MODCP_JOB_MASKWRITE:
        ev = exec_maskwrite(fb, d);
        break;
    default: { /* BITWRITE: this piece's bits, 8 per byte (whole bytes of dst) */
        uint32_t done = (uint32_t)fb->job_pos * 8u;
        if (done < jb->opnd.count) {
            uint32_t k = jb->opnd.count - done;
            if (k == 1u) { /* one coil (FC05): bit 0 of the data, start bit <= 7 */
                unsigned m = 1u << jb->opnd.bit;
                dst[0] = (uint8_t)((dst[0] & ~m) | (((unsigned)d[0] << jb->opnd.bit) & m));
            } else if (jb->opnd.bit == 0u && k >= n * 8u) {
                modcp_block_copy(dst, d, n); /* whole bytes of the area */
            } else {
                modcp_bits_put(dst, jb->opnd.bit, k > n * 8u ? n * 8u : k, d);
            }
        }
        break;
    }
    }
    fb->job_pos = (uint16_t)(fb->job_pos + n);
    if (ev != MODCP_EV_NONE || last) {
        if (ev == MODCP_EV_NONE) {
            fb->out.cp_start_ndr = true;
        }
        reply(fb, ev, 0, 0);
    }
}

/* A data block of the active write job. It must be exactly the next piece the header
 * announced (32 bytes, the last one shorter and flagged LAST); otherwise the job ends
 * with (0E)33H and nothing more of it is written. */
static void rx_data(modcp_fb_t *fb, const modcp_block_t *b)
{
    if (atomic_load_explicit(&fb->bp->abort_tag, memory_order_acquire) == (uint32_t)fb->job_tag) {
        fb->job_active = false; /* given up by the CP: nothing more is written */
        return;
    }
    uint32_t rest = (uint32_t)fb->job.len - fb->job_pos;
    uint32_t n = rest > MODCP_BLOCK_SIZE ? MODCP_BLOCK_SIZE : rest;
    bool last = n == rest;
    if (b->len != n || ((b->flags & MODCP_BLK_LAST) != 0u) != last) {
        reply(fb, MODCP_EV_XFER_STATE, 0, 0); /* data not as announced */
        return;
    }
    exec_data(fb, b->data, n, last);
}

/* A write job whose blocks all fit the ring waits until all of them are in, so it is
 * executed within one call however the CP side's publishing interleaves with this
 * call (two threads). The CP side publishes such a job completely into an empty ring
 * (job.c), so it never waits for long. b: a JOB header block not flagged LAST. */
static bool job_in_ring(const modcp_fb_t *fb, const modcp_block_t *b)
{
    uint32_t len = modcp_bp_get16(b->data + 9); /* the header's len (backplane.c) */
    uint32_t need = 1u + (len + MODCP_BLOCK_SIZE - 1u) / MODCP_BLOCK_SIZE;
    return b->data[0] == MODCP_JOB_READ || need > MODCP_BP_DEPTH ||
           MODCP_BP_DEPTH - modcp_ring_space(&fb->bp->to_cpu) >= need ||
           /* given up by the CP (it never comes complete): take it, it is dropped */
           atomic_load_explicit(&fb->bp->abort_tag, memory_order_acquire) == (uint32_t)b->tag;
}

static void rx_ack(modcp_fb_t *fb, const modcp_block_t *b)
{
    if (fb->state == (uint8_t)MODCP_FBST_INIT_WAIT) {
        modcp_event_t ev = b->len >= 2u ? modcp_bp_get16(b->data) : MODCP_EV_XFER_STATE;
        fb->cp_has_params = ev == MODCP_EV_NONE;
        if (ev == MODCP_EV_NONE) {
            fb->state = MODCP_FBST_RUN;
            fb->out.cp_start_ok = true;
            fb->out.cp_start_error = false;
        } else {
            fb->init_event = ev; /* not ready: retried on the next interval */
        }
    }
}

/* A reply without data (a write's, an error's): its header alone, at once, when the
 * ring has room; false when it has none. */
static MODCP_ALWAYS_INLINE bool reply_header(modcp_fb_t *fb)
{
    modcp_ring_t *out = &fb->bp->to_cp;
    modcp_block_t *rb = modcp_ring_slot(out);
    if (rb == NULL) {
        return false;
    }
    modcp_block_stamp(rb, modcp_block_word(modcp_bp_reply_encode(&fb->reply, rb->data),
                                           MODCP_BP_REPLY, MODCP_BLK_FIRST | MODCP_BLK_LAST,
                                           fb->job_tag));
    fb->reply_hdr_sent = true;
    fb->reply_pending = false;
    modcp_ring_publish(out, rb, &fb->tx_seq);
    return true;
}

#if !defined(__OPTIMIZE_SIZE__)
/* The common block of a long write: a whole data block of the active job, in sequence,
 * not its last, straight into memory (a WRITE's bytes, or a BITWRITE's from bit 0 with
 * at least 256 bits to go: whole bytes of the area). Taken in one word compare (len,
 * kind, flags, tag) and a few more; rx_blocks, rx_data and exec_data would do exactly
 * the same with it (an active job's header went through rx_blocks: the sequence is
 * synced). False: the general path decides. Built for speed only, as job.c's fast paths
 * (-Os: the general path, 188 B less with pump_reply's whole blocks, Cortex-M3). */
static MODCP_ALWAYS_INLINE bool rx_write_data(modcp_fb_t *fb, const modcp_block_t *b)
{
    const modcp_bp_job_t *jb = &fb->job;
    if (!fb->job_active ||
        modcp_block_peek_word(b) != modcp_block_word(MODCP_BLOCK_SIZE, MODCP_BP_JOB, 0, fb->job_tag) ||
        b->seq != fb->rx_seq || (uint32_t)jb->len - fb->job_pos <= MODCP_BLOCK_SIZE) {
        return false;
    }
    if (jb->op != MODCP_JOB_WRITE &&
        (jb->op != MODCP_JOB_BITWRITE || jb->opnd.bit != 0u ||
         (uint32_t)jb->opnd.count < (uint32_t)fb->job_pos * 8u + MODCP_BLOCK_SIZE * 8u)) {
        return false;
    }
    if (atomic_load_explicit(&fb->bp->abort_tag, memory_order_acquire) == (uint32_t)fb->job_tag) {
        return false; /* given up by the CP: rx_data drops it */
    }
    (void)memcpy(fb->job_mem + fb->job_pos, b->data, MODCP_BLOCK_SIZE);
    fb->job_pos = (uint16_t)(fb->job_pos + MODCP_BLOCK_SIZE);
    fb->rx_seq = (uint8_t)(fb->rx_seq + 1u);
    return true;
}
#endif

static void rx_blocks(modcp_fb_t *fb)
{
    modcp_ring_t *r = &fb->bp->to_cpu;
    const modcp_block_t *b;
    while (!fb->reply_pending && (b = modcp_ring_peek(r)) != NULL) {
#if !defined(__OPTIMIZE_SIZE__) /* built for speed only (-Os: the general path) */
        if (rx_write_data(fb, b)) {
            modcp_ring_release(r);
            continue;
        }
#endif
        uint8_t kind = b->kind;
        uint8_t flags = b->flags;
        uint8_t len = b->len;
        if (kind == MODCP_BP_JOB &&
            (flags & (MODCP_BLK_FIRST | MODCP_BLK_LAST)) == MODCP_BLK_FIRST &&
            len >= MODCP_BP_JOB_HDR_LEN && !job_in_ring(fb, b)) {
            break; /* a job header whose blocks are not all in yet */
        }
        if (b->seq != fb->rx_seq && fb->rx_synced) {
            fb->job_active = false; /* a block went missing: nothing more of that job */
        }
        fb->rx_synced = true;
        fb->rx_seq = (uint8_t)(b->seq + 1u);
        if (len > MODCP_BLOCK_SIZE) {
            fb->job_active = false;
        } else if (kind == MODCP_BP_JOB) {
            if ((flags & MODCP_BLK_FIRST) != 0u) {
                fb->job_active = false; /* a new FIRST abandons an unfinished job */
                if (len >= MODCP_BP_JOB_HDR_LEN) {
                    (void)modcp_bp_job_decode(b->data, len, &fb->job);
                    fb->job_tag = b->tag;
                    start_job(fb, b);
                }
            } else if (fb->job_active && b->tag == fb->job_tag) {
                rx_data(fb, b);
            } else {
                /* remainder of a job we never saw the start of, or that was answered */
            }
        } else if (kind == MODCP_BP_INIT_ACK) {
            rx_ack(fb, b);
        } else {
            /* PARAMS / INIT / REPLY travel the other way: ignored */
        }
        modcp_ring_release(r);
        if (fb->reply_pending && (fb->reply.len != 0u || !reply_header(fb))) {
            pump_reply(fb);
        }
    }
}

void modcp_fb_call(modcp_fb_t *fb, modcp_fb_in_t *in, modcp_fb_out_t *out, uint32_t now_ms)
{
    bool start = in != NULL && in->cp_start;
    fb->out.cp_start_ndr = false;
    if (start && !fb->last_start) {
        (void)memset(&fb->out, 0, sizeof fb->out);
        fb->err_changed = true;
        fb->init_event = MODCP_EV_NONE;
        fb->init_t0_ms = now_ms;
        /* the PARAMS of the first call may still be going out (params_pending) */
        modcp_fb_start_attempt(fb, now_ms, !fb->cp_has_params);
    }
    fb->last_start = start;

    if (fb->reply_pending) {
        pump_reply(fb); /* the rest of a reply the ring had no room for */
    }
    rx_blocks(fb);
    if (!modcp_fb_init_step(fb, now_ms) && in != NULL) {
        in->cp_start = false; /* [RTU-2003] §5.5: CP_START is reset, CP_START_ERROR = 1 */
    }

    if (out != NULL) {
        out->cp_start_ok = fb->out.cp_start_ok;
        out->cp_start_error = fb->out.cp_start_error;
        out->cp_start_ndr = fb->out.cp_start_ndr;
        if (fb->err_changed) { /* else the user program's value stays (it may clear it) */
            out->error_nr = fb->out.error_nr;
            out->error_info = fb->out.error_info;
            fb->err_changed = false;
        }
    }
}
