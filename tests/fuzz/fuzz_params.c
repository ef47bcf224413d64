/* SPDX-License-Identifier: Apache-2.0 */
/* Fuzz target: the parameter record the CPU side hands the CP (docs/parameters.md), through
 * decode, validate, apply and the CP's configuration over the backplane.
 * Input: byte 0 selects the form of the rest:
 *   bit 0 = 0  the rest is the record as it is (any length up to 2 x the record size):
 *              exercises magic, version, length and CRC checks;
 *   bit 0 = 1  the rest overwrites the payload of a valid record (the example parameter
 *              set) from its first field on; the harness then writes the header and the
 *              CRC, so the mutations reach the field checks and the configuration.
 * Invariants:
 *   - decode: a record that decodes re-encodes to a record that decodes to the same
 *     parameters; validate lists a fatal issue exactly when apply refuses, and apply's
 *     event is the first fatal issue's; every issue names the rule it breaks (an overlap
 *     or a shared DB the earlier entry); apply's output applies again unchanged;
 *   - configure: the FB hands the record to the CP; after the start the CP is ready
 *     exactly when the record decodes and applies (otherwise it stays not ready);
 *   - a ready CP answers a diagnostic echo (FC08/0000) in its own framing at its own
 *     address and speed with the echo (in this world CTS and DSR are always ON, for the
 *     RS232 automatic secondary signals), unless the ASCII character delay time is
 *     shorter than one character (then no ASCII frame can be received at all). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/crc.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "params_internal.h"

#define HEADER 8u /* "MCPR", version, payload length */
#define RAW_MAX (2u * MODCP_PARAMS_RECORD_MAX)

typedef struct {
    modcp_backplane_t bp;
    modcp_cp_t cp;
    modcp_fb_t fb;
    modcp_plcmem_t mem;
    modcp_db_t dbs[3];
    uint8_t db_data[3][256];
    uint8_t i[64], q[64], m[256];
    uint16_t t[32], c[32];
    modcp_hal_t hal;
    uint8_t record[RAW_MAX];
    uint16_t record_len;
    uint32_t now_us;
    uint32_t timer_at; /* 0 = disarmed */
    uint8_t tx[600];
    uint16_t tx_len;
    int tx_pending;
    unsigned replies;
} pworld_t;

static pworld_t W;

static void die(const char *what)
{
    fprintf(stderr, "fuzz invariant violated: %s\n", what);
    abort();
}

static void f_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    pworld_t *w = ctx;
    if (len > sizeof w->tx) {
        die("reply length");
    }
    memcpy(w->tx, buf, len);
    w->tx_len = len;
    w->tx_pending = 1;
    w->replies++;
}

static void f_arm(void *ctx, uint32_t us)
{
    pworld_t *w = ctx;
    w->timer_at = us ? w->now_us + us : 0;
    if (us != 0 && w->timer_at == 0) {
        w->timer_at = 1;
    }
}

static void advance(uint32_t us)
{
    uint32_t end = W.now_us + us;
    while ((int32_t)(end - W.now_us) > 0) {
        if (W.timer_at != 0 && (int32_t)(W.timer_at - end) <= 0) {
            W.now_us = W.timer_at;
            W.timer_at = 0;
            modcp_cp_on_timer(&W.cp, W.now_us);
        } else {
            W.now_us = end;
        }
        if (W.tx_pending) {
            W.tx_pending = 0;
            modcp_cp_on_tx_done(&W.cp, W.now_us);
        }
    }
}

static void fb_cycle(void)
{
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    modcp_fb_call(&W.fb, &in, &out, W.now_us / 1000u);
    modcp_cp_poll(&W.cp, W.now_us);
    advance(1000);
}

/* A small parameter set for this target's smaller memory (slave 5, coils on M and Q,
 * inputs on I, registers in DB 100 / 200); not the manuals' example set of
 * tests/unit/support/example_params.h, which needs the larger areas of the unit world. */
static void small_params(modcp_params_t *p)
{
    modcp_params_defaults(p);
    p->slave_addr = 5;
    p->coils[0] = (modcp_bitwin_t){MODCP_AREA_M, 0, 2047, 0, 0};
    p->coils[1] = (modcp_bitwin_t){MODCP_AREA_Q, 2048, 2559, 0, 0};
    p->inputs[0] = (modcp_bitwin_t){MODCP_AREA_I, 0, 511, 0, 0};
    p->hr_base_db = 100;
    p->ir_base_db = 200;
    p->lim_db = (modcp_limit_t){100, 199};
    p->lim_m = (modcp_limit_t){0, 255};
    p->cpu_timeout_ms = 50;
}

static size_t ascii_encode(const uint8_t *b, size_t n, uint8_t *out)
{
    static const char hx[] = "0123456789ABCDEF";
    size_t m = 0;
    uint8_t sum = 0;
    out[m++] = ':';
    for (size_t k = 0; k <= n; k++) {
        uint8_t v = k < n ? b[k] : (uint8_t)(0u - sum);
        if (k < n) sum = (uint8_t)(sum + v);
        out[m++] = (uint8_t)hx[v >> 4];
        out[m++] = (uint8_t)hx[v & 15u];
    }
    out[m++] = '\r';
    out[m++] = '\n';
    return m;
}

/* The record keeps ID string bytes after a NUL, the encoder writes zeros there: both
 * are the same string. */
static void canonical_ids(modcp_params_t *p)
{
    char *ids[4] = {p->vendor, p->product, p->revision, p->app_name};
    for (size_t k = 0; k < 4; k++) {
        size_t n = strlen(ids[k]);
        memset(ids[k] + n, 0, MODCP_ID_STRING_MAX + 1u - n);
    }
}

/* decode / validate / apply; returns true when the record is usable. */
static int check_record(const uint8_t *rec, size_t len, modcp_params_t *eff)
{
    static modcp_params_t p, p2, eff2;
    static uint8_t again[MODCP_PARAMS_RECORD_MAX];
    if (modcp_params_decode(rec, len, &p) != MODCP_EV_NONE) {
        return 0;
    }
    size_t n = modcp_params_encode(&p, again, sizeof again);
    p2 = p;
    canonical_ids(&p2);
    if (n == 0 || modcp_params_decode(again, n, &p) != MODCP_EV_NONE ||
        memcmp(&p, &p2, sizeof p) != 0) {
        die("record does not survive encode + decode");
    }
    modcp_param_issue_t issues[64];
    size_t count = modcp_params_validate(&p, issues, 64);
    modcp_event_t first_fatal = MODCP_EV_NONE;
    for (size_t k = 0; k < count && k < 64; k++) {
        if (issues[k].fatal && first_fatal == MODCP_EV_NONE) {
            first_fatal = issues[k].event;
        }
        bool pair = issues[k].rule == MODCP_PR_OVERLAP || issues[k].rule == MODCP_PR_SAME_DB;
        if (issues[k].rule == MODCP_PR_NONE || issues[k].rule > MODCP_PR_SAME_DB ||
            pair != (issues[k].other < issues[k].index)) {
            die("an issue names no rule, or no earlier entry for an overlap");
        }
    }
    modcp_event_t warning;
    modcp_event_t ev = modcp_params_apply(&p, eff, &warning);
    if (count <= 64 && ev != first_fatal) {
        die("apply's event is not validate's first fatal issue");
    }
    if (ev != MODCP_EV_NONE) {
        return 0;
    }
    if (modcp_params_apply(eff, &eff2, NULL) != MODCP_EV_NONE || memcmp(eff, &eff2, sizeof *eff) != 0) {
        die("effective parameters do not apply unchanged");
    }
    /* timing helpers must be defined for every usable record */
    if (modcp_params_char_us(eff) == 0 || modcp_params_t35_us(eff) == 0 || modcp_params_t15_us(eff) == 0) {
        die("zero character time / t1.5 / t3.5");
    }
    (void)modcp_params_job_limit(eff);
    return 1;
}

static void echo_answered(const modcp_params_t *eff)
{
    uint8_t bin[8] = {eff->slave_addr, 0x08, 0x00, 0x00, 0xA5, 0x5A};
    uint8_t req[32];
    size_t n;
    if (eff->framing == MODCP_FRAMING_ASCII) {
        n = ascii_encode(bin, 6, req);
    } else {
        uint16_t crc = modcp_crc16(bin, 6);
        bin[6] = (uint8_t)crc;
        bin[7] = (uint8_t)(crc >> 8);
        memcpy(req, bin, 8);
        n = 8;
    }
    uint32_t char_us = modcp_params_char_us(eff);
    advance(modcp_params_t35_us(eff) * 2u + 1000u);
    unsigned before = W.replies;
    for (size_t k = 0; k < n; k++) {
        modcp_cp_on_rx(&W.cp, req[k], W.now_us);
        advance(char_us);
    }
    for (int k = 0; k < 50 && W.replies == before; k++) {
        fb_cycle();
    }
    /* turnaround / data output waiting time, the reply, the time to RTS off */
    advance(1000u * ((uint32_t)eff->turnaround_ms + eff->rts_on_delay_ms + eff->rts_off_delay_ms) +
            char_us * 40u + 100000u);
    if (W.replies != before + 1 || W.tx_len != n || memcmp(W.tx, req, n) != 0) {
        die("a ready CP does not answer the echo");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t base[MODCP_PARAMS_RECORD_MAX];
    static size_t base_len;
    if (base_len == 0) {
        modcp_params_t p;
        small_params(&p);
        base_len = modcp_params_encode(&p, base, sizeof base);
        if (base_len <= HEADER + 2u) {
            die("example record");
        }
    }
    if (size == 0) {
        return 0;
    }
    memset(&W, 0, sizeof W);
    if (data[0] & 1u) {
        memcpy(W.record, base, base_len);
        size_t n = size - 1u;
        if (n > base_len - HEADER - 2u) {
            n = base_len - HEADER - 2u;
        }
        memcpy(W.record + HEADER, data + 1, n);
        uint16_t crc = modcp_crc16(W.record, base_len - 2u);
        W.record[base_len - 2u] = (uint8_t)crc;
        W.record[base_len - 1u] = (uint8_t)(crc >> 8);
        W.record_len = (uint16_t)base_len;
    } else {
        size_t n = size - 1u < RAW_MAX ? size - 1u : RAW_MAX;
        memcpy(W.record, data + 1, n);
        W.record_len = (uint16_t)n;
    }

    static modcp_params_t eff;
    int usable = check_record(W.record, W.record_len, &eff);

    /* configure: the FB sends the record, the CP takes it */
    static const uint16_t db_numbers[3] = {100, 101, 200};
    for (unsigned k = 0; k < 3; k++) {
        W.dbs[k] = (modcp_db_t){db_numbers[k], (uint16_t)sizeof W.db_data[k], W.db_data[k]};
    }
    W.mem = (modcp_plcmem_t){.i = W.i, .q = W.q, .m = W.m, .t = W.t, .c = W.c,
                             .i_size = sizeof W.i, .q_size = sizeof W.q, .m_size = sizeof W.m,
                             .t_count = 32, .c_count = 32, .dbs = W.dbs, .db_count = 3};
    W.hal = (modcp_hal_t){.ctx = &W, .uart_tx = f_tx, .timer_arm = f_arm};
    modcp_bp_init(&W.bp);
    modcp_fb_init(&W.fb, &W.bp, &W.mem, W.record, W.record_len, 80, 5000);
    modcp_cp_init(&W.cp, &W.hal, &W.bp);
    W.now_us = 5000000;
    modcp_cp_on_signals(&W.cp, true, true, W.now_us); /* CTS, DSR ON */
    for (int k = 0; k < 60 && !modcp_cp_ready(&W.cp); k++) {
        fb_cycle();
    }
    if (modcp_cp_ready(&W.cp) != (usable != 0)) {
        die(usable ? "usable record, CP not ready" : "unusable record, CP ready");
    }
    if (usable && (eff.framing != MODCP_FRAMING_ASCII ||
                   1000u * (uint32_t)eff.ascii_timeout_ms > modcp_params_char_us(&eff))) {
        echo_answered(&eff);
    }
    return 0;
}
