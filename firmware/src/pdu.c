/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — PDU engine: decode a request, check it against the function-code table,
 * hand it to its handler, encode the reply or the exception; the end-of-request
 * accounting of the extended set.
 *
 * Order of checks (docs/diagnostics.md "Order of checks"; Modbus Application Protocol
 * §6 state diagrams, [RTU-2003] ch. 7, docs/cpu-cp-interface.md). The link layer has already dropped frames
 * for other addresses and frames with a bad CRC / LRC.
 *   (extended set) FC12 receive event; listen-only mode takes the request
 *   1. CPU side not initialised     -> (0E)56H, exception 04 (every request)
 *   2. broadcast rule                -> (08)30H, silence
 *   3. function code of the set      -> (08)31H, exception 01
 *   4. length (table min / max)      -> (08)33H, exception 03
 *   5. quantity (table limit class)  -> (08)32H, exception 03
 *      form: FC06's value width, FC15 / FC16's byte count -> (08)33H, exception 03
 *   6. handler: values ((08)34H..35H, 03), then addresses, windows,
 *      write limits ((0E)5xH, 02); every check before the first job
 *   7. CPU job                       -> exception 04 on any error it reports
 * Replies are built in place in the request buffer. */
#include "modcp/pdu.h"

#include <stddef.h>
#include <string.h>

#include "modcp/quantity.h"
#include "pdu_internal.h"
#include "commlog_internal.h"
#include "diag_internal.h"
#include "events_internal.h"
#include "fc_table_internal.h"
#include "ext_internal.h"
#include "quantity_internal.h"
#include "inline_internal.h"
#include "pdu_rw_internal.h"

/* ---- the function-code table (fc_table.c) ------------------------------------------ */

/* The handlers, by the index a row of the table holds (fc_table_internal.h: H_*). */
static const modcp_pdu_handler_t handlers[] = {
    [H_RW] = modcp_pdu_rw, [H_DIAG0] = modcp_pdu_diag0,
#if MODCP_WITH_EXTENDED
    [H_FC08] = modcp_pdu_fc08, [H_FC11] = modcp_pdu_fc11, [H_FC12] = modcp_pdu_fc12,
    [H_FC17] = modcp_pdu_fc17, [H_FC43] = modcp_pdu_fc43, [H_FC22] = modcp_pdu_fc22,
    [H_FC23] = modcp_pdu_fc23,
#endif
};

/* The row of fc in the function set of p (NULL: not in it). Built without the
 * extended set, the engine is the cp341 set whatever p says. */
static const modcp_fc_row_t *row_of(const modcp_params_t *p, uint8_t fc)
{
#if MODCP_WITH_EXTENDED
    const uint8_t set = p->fset == (uint8_t)MODCP_FSET_EXTENDED ? F_EXT : F_CP341;
#else
    (void)p;
    const uint8_t set = F_CP341;
#endif
    size_t i = fc; /* the rows by function code up to 17H, then FC43 (fc_table_internal.h) */
    if (fc >= MODCP_FC_ROW_FC43) {
        if (fc != 0x2Bu) {
            return NULL;
        }
        i = MODCP_FC_ROW_FC43;
    }
    const modcp_fc_row_t *r = &modcp_fc_table[i];
    if ((r->flags & set) != 0u) { /* no flags: no function code */
        return r;
    }
#if MODCP_WITH_EXTENDED
    if (fc == 0x08u && set == F_EXT) {
        return &modcp_fc_table[MODCP_FC_ROW_FC08_EXT];
    }
#endif
    return NULL; /* no such fc, or not in this set */
}

/* ---- exceptions, reply encoding ----------------------------------------------------- */

uint16_t modcp_pdu_exception(uint8_t *pdu, uint8_t fc, uint8_t code)
{
    pdu[0] = (uint8_t)(fc | 0x80u);
    pdu[1] = code;
    return 2;
}

/* Event word -> Modbus exception code, the column exc of the event rows
 * (modcp/event_rows.h; [RTU-2003] ch. 7, docs/diagnostics.md); 0 for events that name no code. The engine
 * names the code itself where it refuses (modcp_pdu_err); fail() answers the mapping's
 * events (modcp_pdu_map_err) with this code. Kept as one 16-bit word per row with a code
 * (exc << 12 | class << 8 | number; the rows with exc 0 leave no entry): 28 bytes and a
 * loop, smaller than a switch over the rows. */
#define EXC_ENTRY_0(cls, num)
#define EXC_ENTRY_1(cls, num) (uint16_t)(1u << 12 | (cls) << 8 | (num)),
#define EXC_ENTRY_2(cls, num) (uint16_t)(2u << 12 | (cls) << 8 | (num)),
#define EXC_ENTRY_3(cls, num) (uint16_t)(3u << 12 | (cls) << 8 | (num)),
#define EXC_ENTRY_4(cls, num) (uint16_t)(4u << 12 | (cls) << 8 | (num)),
#define EXC_ROW(NAME, cls, num, exc, ...) EXC_ENTRY_##exc(cls, num)
static const uint16_t exc_rows[] = {MODCP_EVENT_ROWS(EXC_ROW)};
#undef EXC_ROW
#define EXC_CLASS_ROW(NAME, cls, num, ...) _Static_assert((unsigned)(cls) < 16u, #NAME ": class < 10H");
MODCP_EVENT_ROWS(EXC_CLASS_ROW)
#undef EXC_CLASS_ROW

uint8_t modcp_event_exception(modcp_event_t ev)
{
    for (size_t i = 0; i < sizeof exc_rows / sizeof exc_rows[0]; i++) {
        if ((exc_rows[i] & 0x0FFFu) == ev) {
            return (uint8_t)(exc_rows[i] >> 12);
        }
    }
    return MODCP_EXC_NONE;
}

/* A refused request (s->err, s->x.exc): record the event, count the exception (also
 * for a broadcast, Serial Line V1.02 §6.1 counter 3), answer it or, for a broadcast,
 * count the missing response. */
static modcp_pdu_action_t fail(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                               uint16_t *out_len)
{
    const modcp_event_t ev = s->err;
    modcp_diag_t *d = env->diag;
    s->same = false; /* the reply is an exception */
    modcp_diag_event(d, ev);
    uint8_t code = s->x.exc;
    if (code == (uint8_t)MODCP_EXC_OF_MAP) {
        code = modcp_event_exception(ev);
        s->x.exc = code;
    }
#if MODCP_WITH_EXTENDED
    if (ev == MODCP_EV_XFER_TIMEOUT || ev == MODCP_EV_FB_TIMEOUT) {
        s->x.timeout = 1; /* FC12 send event, FC17 run indicator (modcp_pdu_finished) */
    }
#endif
    /* the error count (out of line in diag.c). The engine answers 01 .. 04 only, so the
     * NAK and BUSY counters (Serial Line V1.02 §6.1 counters 10, 11) stay 0 */
    modcp_diag_count_error(d, MODCP_CNT_EXCEPTION);
    if (s->broadcast) {
        modcp_diag_count_error(d, MODCP_CNT_NO_RESPONSE);
        return MODCP_PDU_NO_REPLY;
    }
    *out_len = modcp_pdu_exception(pdu, s->fc, code);
    return MODCP_PDU_REPLY;
}

/* Every job of the request is done: the reply is the echo of the request's first
 * s->x.echo bytes, or fc, byte count and the s->x.rbytes data read to pdu + 2. */
static inline modcp_pdu_action_t encode(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                 uint16_t *out_len)
{
    if (s->broadcast) {
        modcp_diag_t *const d = env->diag;
        modcp_diag_count(d, MODCP_CNT_NO_RESPONSE);
        return MODCP_PDU_NO_REPLY;
    }
    if (s->x.echo != 0u) {
        *out_len = s->x.echo;
        return MODCP_PDU_REPLY;
    }
    if (s->bits != 0u) {
        modcp_pdu_align_bits(pdu + 2, (uint8_t)(s->bits - 1u), s->qty); /* FC01 / FC02 */
    }
    pdu[0] = s->fc;
    pdu[1] = (uint8_t)s->x.rbytes;
    *out_len = (uint16_t)(2u + s->x.rbytes);
    return MODCP_PDU_REPLY;
}

static modcp_pdu_action_t settle(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                 modcp_pdu_action_t a, uint8_t *pdu, uint16_t *out_len)
{
    if (a == MODCP_PDU_FAIL) {
        return fail(s, env, pdu, out_len);
    }
    if (a == MODCP_PDU_DONE) {
        return encode(s, env, pdu, out_len);
    }
    return a;
}

/* ---- requests ----------------------------------------------------------------------- */

#if MODCP_WITH_EXTENDED
/* FC12 receive event; in listen-only mode (Application Protocol §6.8 sub 04) requests
 * are monitored and counted, neither executed nor answered; only FC08 sub 01 is
 * processed (without a reply). True when the request is taken here. */
static bool listen_only(modcp_pdu_t *s, const modcp_pdu_env_t *env, const uint8_t *pdu,
                        uint16_t len)
{
    modcp_comm_t *c = &env->diag->comm;
    modcp_comm_rx(c, s->broadcast);
    if (!c->listen_only) {
        return false;
    }
    s->x.quiet = 1;
    modcp_diag_t *const d = env->diag;
    modcp_diag_count(d, MODCP_CNT_NO_RESPONSE);
    if (!s->broadcast && s->fc == 0x08u && len == 5u && modcp_get16(pdu + 1) == 0x0001u) {
        uint16_t data = modcp_get16(pdu + 3);
        if (data == 0x0000u) {
            s->x.after = MODCP_X_AFTER_RESTART;
        } else if (data == 0xFF00u) {
            s->x.after = MODCP_X_AFTER_RESTART_CLEAR;
        } else {
            /* another value: the request is monitored only */
        }
    }
    return true;
}
#endif

/* The form of a request with an address (the row's F_ADDR), after its quantity: FC06's
 * value has the width of its register (2 bytes, 4 for an int32 / float register of the
 * 32-bit scheme, [ASCII-32] §4.5); FC15 / FC16's byte count is that of the quantity and
 * the data follow it to the end. Scanner addresses are 16-bit (s->r32_kind 0). */
static bool form_ok(const modcp_fc_row_t *r, const modcp_pdu_t *s, const uint8_t *pdu,
                    uint16_t len)
{
    const uint8_t form = r->form;
    if ((form & (FC_COUNT | FC_PLUS2)) == 0u) {
        return true; /* FC01 .. 05: the length is the table's */
    }
    const uint32_t width = modcp_reg_bytes(s->r32_kind);
    if ((form & FC_COUNT) == 0u) {
        return len == 3u + width; /* FC06 */
    }
    const uint32_t bc = pdu[5]; /* FC15, FC16 */
    const uint32_t want = (form & FC_LIM) == (uint8_t)MODCP_QLIM_WRITE_BITS
                              ? ((uint32_t)s->qty + 7u) / 8u
                              : width * s->qty;
    return bc == want && len == 6u + bc;
}

static modcp_pdu_action_t dispatch(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                   uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (!env->fb_ready) {
        return modcp_pdu_err(s, MODCP_EV_FB_NOT_RUNNING, MODCP_EXC_DEVICE_FAILURE);
    }
    const modcp_fc_row_t *r = row_of(env->p, s->fc);
    if (r == NULL || (s->broadcast && (r->flags & F_BCAST) == 0u)) {
        /* a broadcast stays silent: (08)30H, else (08)31H */
        return modcp_pdu_err(s, s->broadcast ? MODCP_EV_BCAST_FC : MODCP_EV_ILLEGAL_FC,
                             MODCP_EXC_ILLEGAL_FUNCTION);
    }
    s->fcflags = r->flags;
    modcp_pdu_handler_t h = handlers[r->run];
    if (len < r->min_len || ((r->form & FC_EXACT) != 0u && len != r->min_len)) {
        return modcp_pdu_err(s, MODCP_EV_BYTE_COUNT, MODCP_EXC_ILLEGAL_VALUE);
    }
    if ((r->flags & F_ADDR) != 0u) {
        const uint8_t lim = (uint8_t)(r->form & FC_LIM);
        s->addr = modcp_get16(pdu + 1);
        uint16_t qty = lim != (uint8_t)MODCP_QLIM_NONE ? modcp_get16(pdu + 3) : 1u;
        bool scan = false;
#if MODCP_WITH_EXTENDED
        if ((r->flags & F_SCAN) != 0u && env->p->scan_count != 0u &&
            modcp_scan_touches(env->p, s->addr, qty)) {
            scan = true; /* scanner addresses: 16-bit operands, the scanner's handlers */
            h = modcp_pdu_scan;
        }
#endif
        if (!scan && (r->flags & F_R32) != 0u && env->p->regs32 != 0u) { /* else 16-bit */
            s->r32_kind = modcp_regs32_kind(env->p, s->fc, s->addr);
        }
        s->qty = qty; /* 1 for FC05 / FC06 */
        if (lim != (uint8_t)MODCP_QLIM_NONE) {
            if ((uint16_t)(qty - 1u) >= modcp_qty_limit(env->p, lim, s->r32_kind)) { /* 1..max */
                return modcp_pdu_err(s, MODCP_EV_QUANTITY, MODCP_EXC_ILLEGAL_VALUE);
            }
        }
        if (!form_ok(r, s, pdu, len)) {
            return modcp_pdu_err(s, MODCP_EV_BYTE_COUNT, MODCP_EXC_ILLEGAL_VALUE);
        }
    }
#if defined(__GNUC__) && defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__)
    if (h == modcp_pdu_rw) { /* built for speed: the reads and writes without a call */
        return modcp_pdu_rw_inline(s, env, pdu, len, cap);
    }
#endif
    return h(s, env, pdu, len, cap, out_len);
}

modcp_pdu_action_t modcp_pdu_request(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t addr,
                                     uint8_t *pdu, uint16_t len, uint16_t cap, uint16_t *out_len)
{
    *out_len = 0;
    const size_t cleared = MODCP_PDU_CLEARED; /* the request's state; the rest is set before use */
    (void)memset(s, 0, cleared);
    s->job.op = 0;
    if (len < 1u) {
        return MODCP_PDU_NO_REPLY;
    }
    s->fc = pdu[0];
    s->broadcast = addr == 0u;
#if MODCP_WITH_EXTENDED
    if (listen_only(s, env, pdu, len)) {
        return MODCP_PDU_NO_REPLY;
    }
#endif
    modcp_pdu_action_t a = dispatch(s, env, pdu, len, cap, out_len);
    return a == MODCP_PDU_JOB ? a : settle(s, env, a, pdu, out_len);
}

/* What a job's result other than plain success means: exception 04 for an error,
 * the next job of a sequence (FC22, FC23, scanner), or done. */
static modcp_pdu_action_t job_result(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_event_t ev,
                                     bool sequence, uint8_t *pdu)
{
    (void)env; /* (the manual set has no sequence) */
    (void)pdu;
    (void)sequence;
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_err(s, ev, MODCP_EXC_DEVICE_FAILURE); /* whatever the CPU side said */
    }
    if (s->job.op == 0u) {
        return modcp_pdu_err(s, MODCP_EV_INTERNAL_SEND, MODCP_EXC_DEVICE_FAILURE); /* no job ran */
    }
#if MODCP_WITH_EXTENDED
    if (sequence) {
        return modcp_pdu_seq_next(s, env, pdu); /* FC22, FC23, scanner: next job */
    }
#endif
    return MODCP_PDU_DONE;
}

/* ---- end of a request (extended set) ------------------------------------------------ */

#if MODCP_WITH_EXTENDED
static bool write_op(uint8_t op)
{
    return op == MODCP_JOB_WRITE || op == MODCP_JOB_BITWRITE || op == MODCP_JOB_MASKWRITE;
}

/* FC12 send event (Serial Line V1.02 §6.10) of the finished request. */
static uint8_t send_event(const modcp_pdu_t *s, const modcp_comm_t *c)
{
    uint8_t ev = MODCP_COMM_TX;
    if (s->x.exc == (uint8_t)MODCP_EXC_DEVICE_FAILURE) {
        ev |= MODCP_COMM_TX_ABORT_EXC;
    } else if (s->x.exc != (uint8_t)MODCP_EXC_NONE) {
        ev |= MODCP_COMM_TX_READ_EXC; /* 01 .. 03 (the engine answers no 05 .. 07) */
    } else {
        /* no exception */
    }
    if (s->x.timeout != 0u && write_op(s->job.op)) {
        ev |= MODCP_COMM_TX_WRITE_TIMEOUT;
    }
    if (c->listen_only) {
        ev |= MODCP_COMM_TX_LISTEN;
    }
    return ev;
}

/* modcp_pdu_finished; built for speed inline in modcp_pdu_complete, where nearly every
 * request ends (no call of its own). */
static MODCP_SPEED_INLINE void finished(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint32_t now_us)
{
    modcp_diag_t *d = env->diag;
    modcp_ext_t *x = env->ext;
    if (x != NULL && !s->broadcast) {
        modcp_commloss_request(x, env->p, now_us); /* a valid request for our address */
    }
    if (s->x.quiet == 0u) {
        modcp_comm_log(&d->comm, send_event(s, &d->comm));
        if (s->x.exc == MODCP_EXC_NONE && (s->fcflags & F_NOCOUNT) == 0u) {
            modcp_comm_completed(&d->comm); /* successful completion */
        }
        if (x != NULL) {
            modcp_ext_job_result(x, s->x.timeout != 0u,
                                 s->job.op != 0u && s->x.exc == MODCP_EXC_NONE);
            if (!s->broadcast && s->x.exc == MODCP_EXC_NONE && (s->fcflags & F_WRITE) != 0u) {
                modcp_commloss_write(x, env->p, now_us);
            }
        }
    }
    switch (s->x.after) {
    case MODCP_X_AFTER_CLEAR:
        modcp_ext_clear_counters(d);
        break;
    case MODCP_X_AFTER_RESTART:
    case MODCP_X_AFTER_RESTART_CLEAR:
        modcp_ext_restart(x, d, s->x.after == MODCP_X_AFTER_RESTART_CLEAR);
        break;
    default:
        break;
    }
}

void modcp_pdu_finished(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_pdu_action_t a,
                        uint32_t now_us)
{
    (void)a;
    finished(s, env, now_us);
}
#endif

/* The job's result (MODCP_PDU_COMPLETE_FINISHES: and the request's accounting). */
modcp_pdu_action_t modcp_pdu_complete(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                      modcp_event_t ev, uint8_t *pdu, uint16_t *out_len,
                                      uint32_t now_us)
{
    *out_len = 0;
#if MODCP_WITH_EXTENDED
    const bool sequence = s->x.seq != 0u;
#else
    const bool sequence = false;
#endif
    modcp_pdu_action_t a;
    if (ev == MODCP_EV_NONE && !sequence && s->job.op != 0u) {
        a = encode(s, env, pdu, out_len); /* the single job of the manual set */
    } else {
        a = settle(s, env, job_result(s, env, ev, sequence, pdu), pdu, out_len);
    }
#if MODCP_PDU_COMPLETE_FINISHES
    if (a != MODCP_PDU_JOB) {
        finished(s, env, now_us);
    }
#else
    (void)now_us; /* the CP accounts for the request (modcp_pdu_finished) */
#endif
    return a;
}
