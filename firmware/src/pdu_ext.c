/* modcp — PDU engine, extended function set (SPEC §5.3): dispatch, exception
 * accounting, listen-only, FC22 mask write, FC23 read/write multiple registers, the
 * indirection scanner's request handling, and the end-of-request accounting (FC11
 * event counter, FC12 send events, comm-loss supervision).
 *
 * modcp_pdu_fail() (exception accounting, needed by the manual set too) is in pdu.c.
 *
 * Requests that need several CPU jobs (scanner: one job per scattered operand; FC23:
 * the write, then the read) run as a sequence: modcp_pdu_ext_request() returns the
 * first job, modcp_pdu_ext_complete() the next one, until the reply is built. Every
 * range and every operand of a request is checked before its first job, so a request
 * that fails the checks writes nothing. The reply goes out only after all jobs came
 * back; a job that fails (CPU side error or timeout) stops the sequence with
 * exception 04 (what was written before stays written: FC23's write happens before its
 * read, as the Modbus Application Protocol §6.17 specifies).
 *
 * Limits (registers): FC23 read 1..125, write 1..121 (Modbus Application Protocol);
 * with 32-bit registers (int32 / float range, 4 bytes each) read 1..62, write 1..60,
 * so that the reply's byte count and an ASCII frame hold them. Scanner requests
 * (16-bit operands) have the FC03 / FC16 limits of the framing. */
#include <stddef.h>
#include <string.h>

#include "modcp/quantity.h"
#include "pdu_internal.h"

enum { PH_WRITE = 0, PH_READ = 1 };

#define FC23_READ_MAX 125u
#define FC23_WRITE_MAX 121u
#define FC23_READ_MAX32 62u
#define FC23_WRITE_MAX32 60u

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(((unsigned)p[0] << 8) | p[1]);
}

static bool extended(const modcp_pdu_env_t *env)
{
    return env->p->fset == (uint8_t)MODCP_FSET_EXTENDED;
}

/* ---- receive event, listen-only mode -------------------------------------------- */

bool modcp_pdu_ext_pre(modcp_pdu_t *s, const modcp_pdu_env_t *env, const uint8_t *pdu,
                       uint16_t len, modcp_pdu_action_t *a)
{
    modcp_comm_t *c = &env->diag->comm;
    modcp_comm_rx(c, s->broadcast);
    if (!c->listen_only) {
        return false;
    }
    /* Listen-only (Application Protocol §6.8 sub 04): requests are monitored, counted,
     * neither executed nor answered; only FC08 sub 01 is processed (without a reply). */
    *a = MODCP_PDU_NO_REPLY;
    s->x.quiet = 1;
    modcp_diag_count(env->diag, MODCP_CNT_NO_RESPONSE);
    if (!s->broadcast && s->fc == 0x08u && len == 5u && get16(pdu + 1) == 0x0001u) {
        uint16_t data = get16(pdu + 3);
        if (data == 0x0000u) {
            s->x.after = MODCP_X_AFTER_RESTART;
        } else if (data == 0xFF00u) {
            s->x.after = MODCP_X_AFTER_RESTART_CLEAR;
        }
    }
    return true;
}

/* ---- dispatch ------------------------------------------------------------------- */

bool modcp_pdu_ext_supported(const modcp_pdu_env_t *env, uint8_t fc)
{
    if (!extended(env)) {
        return false;
    }
    switch (fc) {
    case 0x08: case 0x0B: case 0x0C: case 0x11: case 0x16: case 0x17: case 0x2B:
        return true;
    default:
        return false;
    }
}

bool modcp_pdu_ext_claims(const modcp_pdu_env_t *env, const uint8_t *pdu, uint16_t len)
{
    if (len < 1u || !extended(env)) {
        return false;
    }
    switch (pdu[0]) {
    case 0x03:
    case 0x10:
        return len >= 5u && modcp_scan_touches(env->p, get16(pdu + 1), get16(pdu + 3));
    case 0x06:
        return len >= 3u && modcp_scan_touches(env->p, get16(pdu + 1), 1u);
    default:
        return modcp_pdu_ext_supported(env, pdu[0]);
    }
}

/* ---- job sequences -------------------------------------------------------------- */

static modcp_pdu_action_t job(modcp_pdu_t *s, uint8_t op, const modcp_operand_t *o, uint16_t len,
                              const uint8_t *wdata, uint8_t *rdata, uint16_t rcap)
{
    s->job.op = op;
    s->job.opnd = *o;
    s->job.len = len;
    s->wdata = wdata;
    s->rdata = rdata;
    s->rcap = rcap;
    return MODCP_PDU_JOB;
}

/* The next job of the sequence, or the reply when all are done. */
static modcp_pdu_action_t step(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                               uint16_t *out_len)
{
    modcp_pdu_x_t *x = &s->x;
    modcp_operand_t o;
    for (;;) {
        if (x->phase == PH_WRITE) {
            uint16_t n = x->wop == 0u ? 0u : (x->wscan ? x->wqty : 1u);
            if (x->idx >= n) {
                x->phase = PH_READ;
                x->idx = 0;
                continue;
            }
            uint16_t k = x->idx++;
            if (!x->wscan) {
                return job(s, x->wop, &x->wdir, x->wlen, pdu + x->woff, NULL, 0);
            }
            modcp_event_t ev =
                modcp_scan_map(env->p, env->areas, (uint16_t)(x->wstart + k), true, &o);
            if (ev != MODCP_EV_NONE) {
                return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
            }
            if (o.area == MODCP_AREA_NONE) {
                continue; /* unused scanner entry: the value is discarded */
            }
            if (x->wop == MODCP_JOB_MASKWRITE) {
                return job(s, x->wop, &o, 4, pdu + x->woff, NULL, 0);
            }
            return job(s, x->wop, &o, 2, pdu + x->woff + 2u * k, NULL, 0);
        }
        uint16_t n = x->rqty == 0u ? 0u : (x->rscan ? x->rqty : 1u);
        if (x->idx >= n) {
            break;
        }
        uint16_t k = x->idx++;
        if (!x->rscan) {
            return job(s, MODCP_JOB_READ, &x->rdir, x->rdir.count, NULL, pdu + x->roff,
                       (uint16_t)(x->cap - x->roff));
        }
        modcp_event_t ev = modcp_scan_map(env->p, env->areas, (uint16_t)(x->rstart + k), false, &o);
        if (ev != MODCP_EV_NONE) {
            return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
        }
        uint8_t *r = pdu + x->roff + 2u * k;
        if (o.area == MODCP_AREA_NONE) {
            r[0] = 0;
            r[1] = 0;
            continue;
        }
        return job(s, MODCP_JOB_READ, &o, 2, NULL, r, 2);
    }
    if (s->broadcast) {
        modcp_diag_count(env->diag, MODCP_CNT_NO_RESPONSE);
        return MODCP_PDU_NO_REPLY;
    }
    if (x->echo != 0u) {
        *out_len = x->echo; /* the request's first bytes, untouched */
        return MODCP_PDU_REPLY;
    }
    pdu[0] = s->fc;
    pdu[1] = (uint8_t)x->rbytes;
    *out_len = (uint16_t)(2u + x->rbytes);
    return MODCP_PDU_REPLY;
}

modcp_pdu_action_t modcp_pdu_ext_complete(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                          modcp_event_t ev, uint8_t *pdu, uint16_t *out_len)
{
    *out_len = 0;
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 4, pdu, out_len);
    }
    return step(s, env, pdu, out_len);
}

/* ---- scanner: FC03, FC06, FC16 on scanner addresses ------------------------------- */

static modcp_pdu_action_t scan_read(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                    uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len != 5u) {
        return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = get16(pdu + 3);
    if (s->qty < 1u || s->qty > modcp_qty_max(env->p, 3u, 0u)) {
        return modcp_pdu_fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    modcp_event_t ev = modcp_scan_check(env->p, env->areas, s->addr, s->qty, false);
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
    }
    s->x.rscan = true;
    s->x.rstart = s->addr;
    s->x.rqty = s->qty;
    s->x.roff = 2;
    s->x.rbytes = (uint16_t)(2u * s->qty);
    if (2u + s->x.rbytes > cap) {
        return modcp_pdu_fail(s, env, MODCP_EV_JOB_LENGTH, 4, pdu, out_len);
    }
    return step(s, env, pdu, out_len);
}

static modcp_pdu_action_t scan_write(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                     uint16_t len, uint16_t *out_len)
{
    if (s->fc == 0x06u) {
        if (len != 5u) {
            return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
        }
        s->addr = get16(pdu + 1);
        s->qty = 1;
        s->x.woff = 3;
    } else {
        if (len < 6u) {
            return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
        }
        s->addr = get16(pdu + 1);
        s->qty = get16(pdu + 3);
        uint8_t bc = pdu[5];
        if (s->qty < 1u || s->qty > modcp_qty_max(env->p, 16u, 0u)) {
            return modcp_pdu_fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
        }
        if (bc != 2u * s->qty || len != 6u + bc) {
            return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
        }
        s->x.woff = 6;
    }
    modcp_event_t ev = modcp_scan_check(env->p, env->areas, s->addr, s->qty, true);
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
    }
    s->x.wop = MODCP_JOB_WRITE;
    s->x.wscan = true;
    s->x.wstart = s->addr;
    s->x.wqty = s->qty;
    s->x.echo = 5; /* FC06: the whole request; FC16: fc, start, quantity */
    return step(s, env, pdu, out_len);
}

/* ---- FC22 mask write register ----------------------------------------------------- */

static modcp_pdu_action_t mask_write(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                     uint16_t len, uint16_t *out_len)
{
    if (len != 7u) {
        return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = 1;
    modcp_event_t ev;
    if (modcp_scan_touches(env->p, s->addr, 1u)) {
        ev = modcp_scan_check(env->p, env->areas, s->addr, 1u, true);
        s->x.wscan = true;
        s->x.wstart = s->addr;
        s->x.wqty = 1;
    } else {
        ev = modcp_map_regs(env->p, env->areas, s->fc, s->addr, 1u, &s->x.wdir);
        s->x.wdir.bit = 0;
        s->x.wlen = 4;
    }
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
    }
    s->x.wop = MODCP_JOB_MASKWRITE;
    s->x.woff = 3;
    s->x.echo = 7; /* the request, unchanged */
    return step(s, env, pdu, out_len);
}

/* ---- FC23 read/write multiple registers ----------------------------------------- */

static modcp_pdu_action_t read_write(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                     uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len < 10u) {
        return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    modcp_pdu_x_t *x = &s->x;
    x->rstart = get16(pdu + 1);
    x->rqty = get16(pdu + 3);
    x->wstart = get16(pdu + 5);
    x->wqty = get16(pdu + 7);
    const uint8_t bc = pdu[9];
    s->addr = x->rstart;
    s->qty = x->rqty;
    x->rscan = modcp_scan_touches(env->p, x->rstart, x->rqty);
    x->wscan = modcp_scan_touches(env->p, x->wstart, x->wqty);
    /* quantities and byte count (exception 03) before any address (02) */
    const uint8_t rk = x->rscan ? 0u : modcp_regs32_kind(env->p, 3u, x->rstart);
    const uint8_t wk = x->wscan ? 0u : modcp_regs32_kind(env->p, 23u, x->wstart);
    const uint16_t rmax = modcp_reg_bytes(rk) == 4u ? FC23_READ_MAX32 : FC23_READ_MAX;
    const uint16_t wmax = modcp_reg_bytes(wk) == 4u ? FC23_WRITE_MAX32 : FC23_WRITE_MAX;
    if (x->rqty < 1u || x->rqty > rmax || x->wqty < 1u || x->wqty > wmax) {
        return modcp_pdu_fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    if (bc != (uint32_t)x->wqty * modcp_reg_bytes(wk) || len != 10u + bc) {
        return modcp_pdu_fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    /* both ranges are checked before anything is written */
    modcp_event_t ev;
    if (x->wscan) {
        ev = modcp_scan_check(env->p, env->areas, x->wstart, x->wqty, true);
    } else {
        ev = modcp_map_regs(env->p, env->areas, 23u, x->wstart, x->wqty, &x->wdir);
        x->wdir.bit = 0;
        if (ev == MODCP_EV_NONE && x->wdir.count != bc) {
            ev = MODCP_EV_BYTE_COUNT;
        }
    }
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
    }
    if (x->rscan) {
        ev = modcp_scan_check(env->p, env->areas, x->rstart, x->rqty, false);
        x->rbytes = (uint16_t)(2u * x->rqty);
    } else {
        /* the read range is mapped like FC03: read rules, no write limits */
        ev = modcp_map_regs(env->p, env->areas, 3u, x->rstart, x->rqty, &x->rdir);
        x->rdir.bit = 0;
        x->rbytes = x->rdir.count;
    }
    if (ev != MODCP_EV_NONE) {
        return modcp_pdu_fail(s, env, ev, 0, pdu, out_len);
    }
    if (x->rbytes > 250u || 2u + (uint32_t)x->rbytes > cap) {
        return modcp_pdu_fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    x->wop = MODCP_JOB_WRITE;
    x->woff = 10;
    x->wlen = bc;
    x->roff = 2; /* read data replace the request only after the write has been done */
    return step(s, env, pdu, out_len);
}

modcp_pdu_action_t modcp_pdu_ext_request(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                         uint8_t *pdu, uint16_t len, uint16_t cap,
                                         uint16_t *out_len)
{
    s->x.seq = 1; /* completions come to modcp_pdu_ext_complete() */
    s->x.cap = cap;
    switch (s->fc) {
    case 0x03:
        return scan_read(s, env, pdu, len, cap, out_len);
    case 0x06:
    case 0x10:
        return scan_write(s, env, pdu, len, out_len);
    case 0x08:
        return modcp_pdu_fc08(s, env, pdu, len, out_len);
    case 0x0B:
        return modcp_pdu_fc11(s, env, pdu, len, out_len);
    case 0x0C:
        return modcp_pdu_fc12(s, env, pdu, len, cap, out_len);
    case 0x11:
        return modcp_pdu_fc17(s, env, pdu, len, cap, out_len);
    case 0x16:
        return mask_write(s, env, pdu, len, out_len);
    case 0x17:
        return read_write(s, env, pdu, len, cap, out_len);
    case 0x2B:
        return modcp_pdu_fc43(s, env, pdu, len, cap, out_len);
    default:
        return modcp_pdu_fail(s, env, MODCP_EV_ILLEGAL_FC, 1, pdu, out_len);
    }
}

/* ---- end of a request ------------------------------------------------------------- */

static bool write_fc(uint8_t fc)
{
    return fc == 0x05u || fc == 0x06u || fc == 0x0Fu || fc == 0x10u || fc == 0x16u ||
           fc == 0x17u;
}

static bool write_op(uint8_t op)
{
    return op == MODCP_JOB_WRITE || op == MODCP_JOB_BITWRITE || op == MODCP_JOB_MASKWRITE;
}

static uint8_t send_event(const modcp_pdu_t *s, const modcp_comm_t *c)
{
    uint8_t ev = MODCP_COMM_TX;
    switch (s->x.exc) {
    case 0:
        break;
    case 1:
    case 2:
    case 3:
        ev |= MODCP_COMM_TX_READ_EXC;
        break;
    case 4:
        ev |= MODCP_COMM_TX_ABORT_EXC;
        break;
    case 5:
    case 6:
        ev |= MODCP_COMM_TX_BUSY_EXC;
        break;
    default:
        ev |= MODCP_COMM_TX_NAK_EXC;
        break;
    }
    if (s->x.timeout != 0u && write_op(s->job.op)) {
        ev |= MODCP_COMM_TX_WRITE_TIMEOUT;
    }
    if (c->listen_only) {
        ev |= MODCP_COMM_TX_LISTEN;
    }
    return ev;
}

void modcp_pdu_finished(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_pdu_action_t a,
                        uint32_t now_us)
{
    (void)a;
    modcp_diag_t *d = env->diag;
    modcp_ext_t *x = env->ext;
    if (x != NULL && !s->broadcast) {
        modcp_commloss_request(x, now_us); /* a valid request for our address */
    }
    if (s->x.quiet == 0u) {
        modcp_comm_log(&d->comm, send_event(s, &d->comm));
        if (s->x.exc == 0u && s->fc != 0x0Bu && s->fc != 0x0Cu) {
            d->comm.event_count++; /* successful completion; wraps 65535 -> 0 */
        }
        if (x != NULL) {
            if (s->x.timeout != 0u) {
                x->cpu_stalled = true;
            } else if (s->job.op != 0u && s->x.exc == 0u) {
                x->cpu_stalled = false;
            }
            if (!s->broadcast && s->x.exc == 0u && write_fc(s->fc)) {
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
