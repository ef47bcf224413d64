/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — serial-line diagnostics of the extended set: FC08 (Modbus Application
 * Protocol V1.1b3 §6.8, Modbus over Serial Line V1.02 §6.1), FC11 get comm event
 * counter (§6.9), FC12 get comm event log (§6.10).
 *
 * FC08 sub-functions (request data 0000 unless noted; reply = echo unless noted):
 *   00 return query data: any data, echoed
 *   01 restart communications: data 0000 (keep the event log) or FF00 (clear it); the
 *      echo goes out first, then counters, event counter and diagnostic register are
 *      cleared, listen-only is left, the ASCII delimiter is LF again and event 0x00 is
 *      logged. In listen-only mode it is processed without a reply.
 *   02 return diagnostic register: reply data = the register (commlog.h)
 *   03 change ASCII input delimiter: data = CHAR 00; CHAR must not be a hex digit or
 *      ':', nor above 7FH in ASCII with 7 data bits (exception 03); takes effect for
 *      ASCII framing, stored but without effect in RTU
 *   04 force listen-only mode: no reply; from now on nothing is answered or executed
 *   0A clear counters and diagnostic register (after the echo: a following 0B..12
 *      reads only what came after the 0A)
 *   0B..12 return the counters: bus messages, bus communication errors, exceptions,
 *      slave messages, no response, NAK, busy, character overrun
 *   14 clear overrun counter and flag
 * Unsupported sub-function (05..09, 13, 15..FFFF): exception 01 with (08)35H (Modbus
 * Application Protocol FC08 state diagram). Data other than allowed, or a request
 * that is not exactly sub-function + 2 data bytes: exception 03 ((08)35H / (08)33H). */
#include <stddef.h>

#include "pdu_internal.h"
#include "commlog_internal.h"
#include "diag_internal.h"
#include "ext_internal.h"

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(((unsigned)p[0] << 8) | p[1]);
}

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)(v & 0xFFu);
}

void modcp_ext_clear_counters(modcp_diag_t *d)
{
    modcp_diag_clear_counters(d);
}

void modcp_ext_restart(modcp_ext_t *x, modcp_diag_t *d, bool clear_log)
{
    modcp_diag_clear_counters(d);
    modcp_comm_restart(&d->comm, clear_log);
    if (x != NULL) {
        modcp_ext_set_delimiter(x, MODCP_ASCII_DELIMITER_DEFAULT);
    }
}

uint16_t modcp_ext_diag_register(const modcp_ext_t *x, const modcp_diag_t *d)
{
    uint16_t r = d->comm.diag_reg;
    if (x != NULL && x->cl_lost) {
        r |= MODCP_DREG_COMMLOSS;
    }
    if (x != NULL && x->cpu_stalled) {
        r |= MODCP_DREG_CPU_STALLED;
    }
    return r;
}

static bool sub_supported(uint16_t sub)
{
    return sub <= 0x0004u || (sub >= 0x000Au && sub <= 0x0012u) || sub == 0x0014u;
}

static bool delimiter_ok(uint8_t ch, const modcp_params_t *p)
{
    bool hex = (ch >= 0x30u && ch <= 0x39u) || (ch >= 0x41u && ch <= 0x46u) || /* 0-9 A-F */
               (ch >= 0x61u && ch <= 0x66u);                              /* a-f */
    /* ASCII with 7 data bits masks the eighth bit of every received character: a
     * delimiter above 7FH could never be received and would lock the master out */
    bool unreceivable = ch > 0x7Fu && p != NULL && p->framing == (uint8_t)MODCP_FRAMING_ASCII &&
                        p->data_bits == 7u;
    return !hex && ch != 0x3Au && !unreceivable; /* ':' */
}

modcp_pdu_action_t modcp_pdu_fc08(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)cap; /* length >= 3: the function-code table */
    const uint16_t sub = get16(pdu + 1);
    if (sub == 0x0000u) {
        *out_len = len; /* return query data: echo, unchanged */
        return MODCP_PDU_REPLY;
    }
    if (!sub_supported(sub)) {
        return modcp_pdu_err(s, MODCP_EV_DIAG_SUBFC, MODCP_EXC_ILLEGAL_FUNCTION);
    }
    if (len != 5u) {
        return modcp_pdu_err(s, MODCP_EV_BYTE_COUNT, MODCP_EXC_ILLEGAL_VALUE);
    }
    const uint16_t data = get16(pdu + 3);
    modcp_diag_t *d = env->diag;
    modcp_ext_t *x = env->ext;
    bool ok;
    switch (sub) {
    case 0x0001:
        ok = data == 0x0000u || data == 0xFF00u;
        break;
    case 0x0003:
        ok = (data & 0xFFu) == 0u && delimiter_ok((uint8_t)(data >> 8), env->p);
        break;
    default:
        ok = data == 0x0000u;
        break;
    }
    if (!ok) {
        return modcp_pdu_err(s, MODCP_EV_DIAG_SUBFC, MODCP_EXC_ILLEGAL_VALUE);
    }
    *out_len = 5; /* fc, sub-function, data */
    switch (sub) {
    case 0x0001:
        s->x.after = data == 0xFF00u ? MODCP_X_AFTER_RESTART_CLEAR : MODCP_X_AFTER_RESTART;
        break;
    case 0x0002:
        put16(pdu + 3, modcp_ext_diag_register(x, d));
        break;
    case 0x0003:
        if (x != NULL) {
            modcp_ext_set_delimiter(x, (uint8_t)(data >> 8)); /* for the next frames */
        }
        break;
    case 0x0004:
        modcp_comm_listen(&d->comm, true);
        modcp_diag_count(d, MODCP_CNT_NO_RESPONSE);
        s->x.quiet = 1;
        *out_len = 0;
        return MODCP_PDU_NO_REPLY;
    case 0x000A:
        s->x.after = MODCP_X_AFTER_CLEAR;
        break;
    case 0x0014:
        modcp_diag_clear_overrun(d);
        break;
    default: /* 0B .. 12: the counters in modcp_counter_t order */
        put16(pdu + 3, d->counters[sub - 0x000Bu]);
        break;
    }
    return MODCP_PDU_REPLY;
}

modcp_pdu_action_t modcp_pdu_fc11(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)s; /* length 1: the function-code table */
    (void)len;
    (void)cap;
    put16(pdu + 1, 0x0000u); /* status: never busy (one request at a time) */
    put16(pdu + 3, env->diag->comm.event_count);
    *out_len = 5;
    return MODCP_PDU_REPLY;
}

modcp_pdu_action_t modcp_pdu_fc12(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                  uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)s; /* length 1: the function-code table */
    (void)len;
    const modcp_diag_t *d = env->diag;
    uint16_t n = d->comm.log_len;
    if (8u + (uint32_t)n > cap) {
        n = cap > 8u ? (uint16_t)(cap - 8u) : 0u; /* never with the CP's buffer */
    }
    pdu[1] = (uint8_t)(6u + n);
    put16(pdu + 2, 0x0000u); /* status */
    put16(pdu + 4, d->comm.event_count);
    put16(pdu + 6, d->counters[MODCP_CNT_BUS_MSG]); /* message count = FC08 sub 0B */
    for (uint16_t i = 0; i < n; i++) {
        pdu[8u + i] = modcp_comm_log_at(&d->comm, i); /* newest first */
    }
    *out_len = (uint16_t)(8u + n);
    return MODCP_PDU_REPLY;
}
