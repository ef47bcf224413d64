/* modcp — PDU engine: the manual's function set (004 §6): FC 01, 02, 03, 04, 05, 06,
 * 08 (sub-function 0000), 15, 16.
 *
 * Order of checks (Modbus application protocol §6 state diagrams, 004 ch. 7):
 *   broadcast rule ((08)30H, silence) -> function code ((08)31H, exception 01)
 *   -> FB initialised ((0E)56H, exception 04) -> length / quantity / value
 *   ((08)32H..35H, exception 03) -> address mapping ((0E)5xH, exception 02)
 *   -> job on the CPU side (exception 04 on any error it reports).
 * Replies are built in place in the request buffer: every field of the request is
 * read before the first reply byte is written.
 * Function set `extended` (SPEC §5.3): listen-only and the FC12 receive event come
 * first (modcp_pdu_ext_pre); FC08, 11, 12, 17, 22, 23, 43 and scanner addresses of
 * FC03/06/16 go to pdu_ext.c after the FB check; `cp341` answers them with 01. Built
 * without the extended set (MODCP_WITH_EXTENDED 0) the engine is the cp341 set. */
#include "modcp/pdu.h"

#include <string.h>

#include "modcp/quantity.h" /* limits by framing and register width (003 §5, §8.5) */
#include "pdu_internal.h"      /* the extended set (SPEC §5.3): pdu_ext.c */

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(((unsigned)p[0] << 8) | p[1]);
}

uint16_t modcp_pdu_exception(uint8_t *pdu, uint8_t fc, uint8_t code)
{
    pdu[0] = (uint8_t)(fc | 0x80u);
    pdu[1] = code;
    return 2;
}

/* ---- exceptions (manual set and extended set) ----------------------------------------------------------------- */

modcp_pdu_action_t modcp_pdu_fail(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_event_t ev,
                                  uint8_t code, uint8_t *pdu, uint16_t *out_len)
{
    modcp_diag_event(env->diag, ev);
    if (code == 0u) {
        code = modcp_event_exception(ev);
        if (code == 0u) {
            code = 4;
        }
    }
    s->x.exc = code;
    if (ev == MODCP_EV_XFER_TIMEOUT || ev == MODCP_EV_FB_TIMEOUT) {
        s->x.timeout = 1;
    }
    /* Serial Line V1.02 §6.1: exceptions detected in broadcast messages count too */
    modcp_diag_count(env->diag, MODCP_CNT_EXCEPTION);
    if (code == 7u) {
        modcp_diag_count(env->diag, MODCP_CNT_NAK);
    } else if (code == 6u) {
        modcp_diag_count(env->diag, MODCP_CNT_BUSY);
    }
    if (s->broadcast) {
        modcp_diag_count(env->diag, MODCP_CNT_NO_RESPONSE);
        return MODCP_PDU_NO_REPLY;
    }
    *out_len = modcp_pdu_exception(pdu, s->fc, code);
    return MODCP_PDU_REPLY;
}

/* Record ev and answer with its exception code (04 when it has none); counts the
 * exception, also for a broadcast. */
static modcp_pdu_action_t fail(modcp_pdu_t *s, const modcp_pdu_env_t *env, modcp_event_t ev,
                               uint8_t code, uint8_t *pdu, uint16_t *out_len)
{
    return modcp_pdu_fail(s, env, ev, code, pdu, out_len);
}

static bool fc_supported(uint8_t fc)
{
    switch (fc) {
    case 0x01: case 0x02: case 0x03: case 0x04: case 0x05:
    case 0x06: case 0x08: case 0x0F: case 0x10:
        return true;
    default:
        return false;
    }
}

static bool fc_broadcast_allowed(uint8_t fc)
{
    return fc == 0x05 || fc == 0x06 || fc == 0x0F || fc == 0x10;
}

static modcp_pdu_action_t start_job(modcp_pdu_t *s, uint8_t op, const modcp_operand_t *o,
                                    uint16_t len, const uint8_t *wdata, uint8_t *pdu,
                                    uint16_t cap)
{
    s->job.op = op;
    s->job.opnd = *o;
    s->job.len = len;
    s->wdata = wdata;
    s->rdata = pdu + 2; /* FC01..04 replies: fc, byte count, data */
    s->rcap = (uint16_t)(cap > 2u ? cap - 2u : 0u);
    return MODCP_PDU_JOB;
}

/* FC01 / FC02: read bits. */
static modcp_pdu_action_t read_bits(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                    uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len != 5u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = get16(pdu + 3);
    if (s->qty < 1u || s->qty > modcp_qty_max(env->p, s->fc, 0u)) {
        return fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_bits(env->p, env->areas, s->fc, s->addr, s->qty, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    uint16_t bytes;
    if (o.area == MODCP_AREA_T || o.area == MODCP_AREA_C) {
        bytes = (uint16_t)(o.count * 2u); /* whole words, high byte first */
        s->shift = 0;
    } else {
        bytes = (uint16_t)((o.bit + s->qty + 7u) / 8u);
        s->shift = o.bit;
        o.count = bytes; /* the job reads whole bytes; bits are aligned by the CP */
        o.bit = 0;
    }
    return start_job(s, MODCP_JOB_READ, &o, bytes, NULL, pdu, cap);
}

/* FC03 / FC04: read registers. */
static modcp_pdu_action_t read_regs(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                    uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len != 5u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = get16(pdu + 3);
    s->r32_kind = modcp_regs32_kind(env->p, s->fc, s->addr); /* 003 §4.5: by the start */
    if (s->qty < 1u || s->qty > modcp_qty_max(env->p, s->fc, s->r32_kind)) {
        return fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_regs(env->p, env->areas, s->fc, s->addr, s->qty, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    s->r32_kind = o.bit;
    o.bit = 0;
    return start_job(s, MODCP_JOB_READ, &o, o.count, NULL, pdu, cap);
}

/* FC05: write single coil. */
static modcp_pdu_action_t write_coil(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                     uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len != 5u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = 1;
    uint16_t value = get16(pdu + 3);
    if (value != 0xFF00u && value != 0x0000u) {
        return fail(s, env, MODCP_EV_COIL_VALUE, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_bits(env->p, env->areas, s->fc, s->addr, 1, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    s->bitval = value == 0xFF00u ? 1u : 0u;
    return start_job(s, MODCP_JOB_BITWRITE, &o, 1, &s->bitval, pdu, cap);
}

/* FC06: write single register. */
static modcp_pdu_action_t write_reg(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                    uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len < 3u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = 1;
    s->r32_kind = modcp_regs32_kind(env->p, s->fc, s->addr);
    if (len != 3u + modcp_reg_bytes(s->r32_kind)) { /* int32 / float: 4 data bytes */
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_regs(env->p, env->areas, s->fc, s->addr, 1, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    s->r32_kind = o.bit;
    o.bit = 0;
    s->reply_len = len; /* echo: 5, or 7 for an int32 / float register (003 §4.5) */
    return start_job(s, MODCP_JOB_WRITE, &o, o.count, pdu + 3, pdu, cap);
}

/* FC15: write multiple coils. */
static modcp_pdu_action_t write_coils(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                      uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len < 6u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = get16(pdu + 3);
    uint8_t bc = pdu[5];
    if (s->qty < 1u || s->qty > modcp_qty_max(env->p, s->fc, 0u)) {
        return fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    if (bc != (s->qty + 7u) / 8u || len != 6u + bc) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_bits(env->p, env->areas, s->fc, s->addr, s->qty, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    return start_job(s, MODCP_JOB_BITWRITE, &o, bc, pdu + 6, pdu, cap);
}

/* FC16: write multiple registers. */
static modcp_pdu_action_t write_regs(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                     uint16_t len, uint16_t cap, uint16_t *out_len)
{
    if (len < 6u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    s->addr = get16(pdu + 1);
    s->qty = get16(pdu + 3);
    uint8_t bc = pdu[5];
    s->r32_kind = modcp_regs32_kind(env->p, s->fc, s->addr); /* 003 §4.5: by the start */
    if (s->qty < 1u || s->qty > modcp_qty_max(env->p, s->fc, s->r32_kind)) {
        return fail(s, env, MODCP_EV_QUANTITY, 3, pdu, out_len);
    }
    if (bc != (unsigned)modcp_reg_bytes(s->r32_kind) * s->qty || len != 6u + bc) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    modcp_operand_t o;
    modcp_event_t ev = modcp_map_regs(env->p, env->areas, s->fc, s->addr, s->qty, &o);
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 0, pdu, out_len);
    }
    s->r32_kind = o.bit;
    o.bit = 0;
    if (o.count != bc) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    return start_job(s, MODCP_JOB_WRITE, &o, bc, pdu + 6, pdu, cap);
}

/* FC08: diagnostics, sub-function 0000 (return query data). */
static modcp_pdu_action_t diagnostics(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                      uint16_t len, uint16_t *out_len)
{
    if (len < 3u) {
        return fail(s, env, MODCP_EV_BYTE_COUNT, 3, pdu, out_len);
    }
    uint16_t sub = get16(pdu + 1);
    if (sub != 0x0000u) {
        return fail(s, env, MODCP_EV_DIAG_SUBFC, 3, pdu, out_len);
    }
    *out_len = len; /* echo, unchanged */
    return MODCP_PDU_REPLY;
}

modcp_pdu_action_t modcp_pdu_request(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t addr,
                                     uint8_t *pdu, uint16_t len, uint16_t cap, uint16_t *out_len)
{
    *out_len = 0;
    memset(s, 0, sizeof *s);
    if (len < 1u) {
        return MODCP_PDU_NO_REPLY;
    }
    s->fc = pdu[0];
    s->broadcast = addr == 0u;

#if MODCP_WITH_EXTENDED
    modcp_pdu_action_t pre;
    if (modcp_pdu_ext_pre(s, env, pdu, len, &pre)) {
        return pre; /* listen-only mode */
    }
#endif
    if (s->broadcast && !fc_broadcast_allowed(s->fc)) {
        return fail(s, env, MODCP_EV_BCAST_FC, 1, pdu, out_len); /* silent, counted */
    }
#if MODCP_WITH_EXTENDED
    if (!fc_supported(s->fc) && !modcp_pdu_ext_supported(env, s->fc)) {
        return fail(s, env, MODCP_EV_ILLEGAL_FC, 1, pdu, out_len);
    }
#else
    if (!fc_supported(s->fc)) { /* built without the extended set: the cp341 set */
        return fail(s, env, MODCP_EV_ILLEGAL_FC, 1, pdu, out_len);
    }
#endif
    if (!env->fb_ready) {
        return fail(s, env, MODCP_EV_FB_NOT_RUNNING, 4, pdu, out_len);
    }
#if MODCP_WITH_EXTENDED
    if (modcp_pdu_ext_claims(env, pdu, len)) {
        return modcp_pdu_ext_request(s, env, pdu, len, cap, out_len);
    }
#endif
    switch (s->fc) {
    case 0x01:
    case 0x02:
        return read_bits(s, env, pdu, len, cap, out_len);
    case 0x03:
    case 0x04:
        return read_regs(s, env, pdu, len, cap, out_len);
    case 0x05:
        return write_coil(s, env, pdu, len, cap, out_len);
    case 0x06:
        return write_reg(s, env, pdu, len, cap, out_len);
    case 0x08:
        return diagnostics(s, env, pdu, len, out_len);
    case 0x0F:
        return write_coils(s, env, pdu, len, cap, out_len);
    case 0x10:
        return write_regs(s, env, pdu, len, cap, out_len);
    default:
        return fail(s, env, MODCP_EV_ILLEGAL_FC, 1, pdu, out_len);
    }
}

/* Align a bit string read from byte boundaries: drop `shift` low bits of the first
 * byte, keep qty bits, clear the unused high bits of the last byte. */
static void align_bits(uint8_t *d, uint8_t shift, uint16_t qty)
{
    uint16_t n = (uint16_t)((qty + 7u) / 8u);
    if (shift != 0u) {
        for (uint16_t i = 0; i < n; i++) {
            d[i] = (uint8_t)((d[i] >> shift) | (d[i + 1u] << (8u - shift)));
        }
    }
    if ((qty & 7u) != 0u) {
        d[n - 1u] &= (uint8_t)((1u << (qty & 7u)) - 1u);
    }
}

modcp_pdu_action_t modcp_pdu_complete(modcp_pdu_t *s, const modcp_pdu_env_t *env,
                                      modcp_event_t ev, uint8_t *pdu, uint16_t *out_len)
{
    *out_len = 0;
#if MODCP_WITH_EXTENDED
    if (s->x.seq != 0u) {
        return modcp_pdu_ext_complete(s, env, ev, pdu, out_len); /* extended set */
    }
#endif
    if (ev != MODCP_EV_NONE) {
        return fail(s, env, ev, 4, pdu, out_len);
    }
    if (s->broadcast) {
        modcp_diag_count(env->diag, MODCP_CNT_NO_RESPONSE);
        return MODCP_PDU_NO_REPLY;
    }
    switch (s->fc) {
    case 0x01:
    case 0x02: {
        uint16_t bytes;
        if (s->job.opnd.area == MODCP_AREA_T || s->job.opnd.area == MODCP_AREA_C) {
            bytes = s->job.len;
        } else {
            align_bits(s->rdata, s->shift, s->qty);
            bytes = (uint16_t)((s->qty + 7u) / 8u);
        }
        pdu[0] = s->fc;
        pdu[1] = (uint8_t)bytes;
        *out_len = (uint16_t)(2u + bytes);
        return MODCP_PDU_REPLY;
    }
    case 0x03:
    case 0x04:
        pdu[0] = s->fc;
        pdu[1] = (uint8_t)s->job.len;
        *out_len = (uint16_t)(2u + s->job.len);
        return MODCP_PDU_REPLY;
    case 0x05:
    case 0x06:
        *out_len = s->fc == 0x06 ? s->reply_len : 5u; /* echo of the request */
        return MODCP_PDU_REPLY;
    case 0x0F:
    case 0x10:
        *out_len = 5; /* fc, start, quantity: the request's first five bytes */
        return MODCP_PDU_REPLY;
    default:
        return fail(s, env, MODCP_EV_INTERNAL_SEND, 4, pdu, out_len);
    }
}
