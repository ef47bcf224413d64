/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP side wired together.
 *
 * Start-up (docs/parameters.md, §6): the CP is "not ready" (SF on, line ignored) until the CPU
 * side's PARAMS record arrives and validates. A bad record leaves it not ready with
 * the record's first fatal event in the diagnostics; never half-configured. The FB's
 * INIT then brings the controller's area sizes and the work area; until it has been
 * acknowledged every request gets exception 04 / (0E)56H. */
#include "modcp/cp.h"

#include <stddef.h>
#include <string.h>

#include "modcp/crc.h"
#include "backplane_internal.h"
#include "cpdiag_internal.h"
#include "diag_internal.h"
#include "ext_internal.h"
#include "job_internal.h"
#include "leds_internal.h"
#include "link_internal.h"
#include "params_internal.h"
#include "pdu_internal.h"
#include "cp_signals_internal.h"
#include "signals_internal.h"

/* ---- line discipline and diagnostics (signals.c, leds.c, cpdiag.c) ---------- */

/* SF ([RTU-2003] §7.2, [ASCII-32] §10.1): no or invalid parameters (on at power-on until the CP is
 * parameterised), a wire break, or RS232 automatic signals with CTS / DSR not asserted.
 * An FB not (yet) initialised does not light it: the CP is parameterised and fine, the
 * requests get exception 04 / (0E)56H. */
static bool sf_on(const modcp_cp_t *cp)
{
#if MODCP_WITH_RS232_SIGNALS
    if (modcp_sig_fault(&cp->sig)) {
        return true;
    }
#endif
    return !cp->configured || cp->cpdiag.wire_break;
}

/* Hand a reply to the link; with RS232 automatic signals it waits for RTS / CTS. */
static void line_reply(modcp_cp_t *cp, uint16_t out_len, uint32_t now_us)
{
    /* FC05 / FC06: the reply is the request, unchanged (out_len is the request's
     * length; RTU sends the frame with its CRC as received) */
    modcp_link_reply(&cp->link, out_len, cp->pdu.same, now_us);
#if MODCP_WITH_RS232_SIGNALS
    if (cp->sig.enabled) { /* disabled signals are idle (see sig_on_timer) */
        modcp_sig_on_reply(&cp->sig, &cp->link, now_us);
    }
#endif
}

/* A PARAMS record was taken (ok: applied); irq: its diag_irq, -1 if undecodable. */
static void line_params(modcp_cp_t *cp, bool ok, int irq)
{
    modcp_cpdiag_params(&cp->cpdiag, ok, irq);
}

/* CP task: SYSTAT requests of the CPU side, LEDs (from the link's receive / transmit
 * record: no hook per byte or per transmission). Returns SF as shown (publish() shows
 * the same: nothing after this in the poll changes it). */
static bool line_poll(modcp_cp_t *cp, uint32_t now_us)
{
    /* (the poll always has its backplane: modcp_job_poll and publish() use it too) */
    uint32_t req = atomic_load_explicit(&cp->job.bp->systat_req, memory_order_acquire);
    if (req != cp->cpdiag.systat_ack) { /* a new SYSTAT request */
        /* the image straight into the status area (publish() then publishes the answer,
         * systat_ack, at the end of this poll); byte 0 ([RTU-2003] §7.4): RUN once
         * parameterised, fault without valid parameters */
        modcp_cpdiag_systat(&cp->cpdiag, &cp->diag, cp->job.bp, req, cp->configured);
    }
    const uint8_t errors = modcp_job_take_errors(&cp->job);
    if (errors != 0u) { /* new backplane errors */
        modcp_cpdiag_backplane(&cp->diag, errors);
    }
    if (cp->cpdiag.wire_break && cp->link.last_us != cp->err_mark_us) {
        modcp_cpdiag_good_char(&cp->cpdiag); /* a character arrived after the BREAK */
        cp->published = false; /* (the character may have been a stored one: see
                                  modcp_cp_on_rx) */
    }
    const bool sf = sf_on(cp);
    modcp_leds_poll(&cp->leds, sf, &cp->link, now_us);
    return sf;
}

void modcp_cp_on_signals(modcp_cp_t *cp, bool cts, bool dsr, uint32_t now_us)
{
#if MODCP_WITH_RS232_SIGNALS
    modcp_sig_on_inputs(&cp->sig, &cp->link, cts, dsr, now_us);
    cp->published = false;
    cp->publish_all = true; /* the inputs are shown in the status area */
#else
    (void)cp; /* no RS232 automatic signals in this build: inputs not used */
    (void)cts;
    (void)dsr;
    (void)now_us;
#endif
}

void modcp_cp_init(modcp_cp_t *cp, const modcp_hal_t *hal, modcp_backplane_t *bp)
{
    (void)memset(cp, 0, sizeof *cp); /* diagnostics and CP diagnostics empty (no _init of their own) */
    modcp_params_defaults(&cp->params);
    modcp_link_init(&cp->link, hal, &cp->diag, cp->buf, (uint16_t)MODCP_LINK_BUF_MAX);
#if MODCP_SHARED_PARAMS_BUFFER
    modcp_job_init(&cp->job, bp, cp->buf, (uint16_t)sizeof cp->buf); /* see features.h */
#else
    modcp_job_init(&cp->job, bp, cp->record, (uint16_t)sizeof cp->record);
#endif
    cp->param_event = MODCP_EV_PARAM_RECORD; /* nothing received yet */
    cp->env.p = &cp->params; /* env.fb_ready false: no INIT yet */
    cp->env.areas = &cp->areas;
    cp->env.diag = &cp->diag;
#if MODCP_WITH_EXTENDED
    cp->env.ext = &cp->ext;
#endif
    cp->publish_all = true;
#if MODCP_WITH_RS232_SIGNALS
    modcp_sig_init(&cp->sig, hal, &cp->diag);   /* RTS, DTR OFF */
#endif
    modcp_leds_init(&cp->leds, hal);            /* SF on, TXD, RXD off */
#if MODCP_WITH_EXTENDED
    modcp_ext_init(&cp->ext);
#endif
}

bool modcp_cp_ready(const modcp_cp_t *cp)
{
    return cp->configured && cp->env.fb_ready;
}

/* Carry the request on: the PDU engine's decision on the frame f that has just ended
 * or (f NULL) on the result of its job, then its next job (a request of the extended set
 * may need several in sequence: modcp_pdu_complete() then returns the next) or the end
 * of the request. The request's PDU, where the reply is built, is at buf + 1 (after the
 * address, RTU and ASCII alike: rtu.c deliver, ascii_on_timer); the frame is not kept.
 * Built for size one copy, shared by the end of a frame and the poll; built for speed
 * inline in each (no call and no stack frame of its own per request). */
static MODCP_SIZE_NOINLINE_SPEED_INLINE void advance(modcp_cp_t *cp, modcp_frame_t *f,
                                                      uint32_t now_us)
{
    const modcp_pdu_env_t *env = &cp->env;
    uint8_t *pdu = cp->buf + 1;
    uint16_t out_len = 0;
    modcp_pdu_action_t a;
    if (f != NULL) {
        uint8_t *const req = f->pdu; /* in cp->buf, after the address */
        a = modcp_pdu_request(&cp->pdu, env, f->addr, req, f->pdu_len, f->pdu_cap, &out_len);
#if MODCP_PDU_COMPLETE_FINISHES
        if (a != MODCP_PDU_JOB) { /* (modcp_pdu_complete accounts for the others) */
            modcp_pdu_finished(&cp->pdu, env, a, now_us); /* FC11/12 accounting, comm loss */
        }
#endif
    } else {
        a = modcp_pdu_complete(&cp->pdu, env, cp->job.event, pdu, &out_len, now_us);
    }
    while (a == MODCP_PDU_JOB) { /* a job's first blocks go out at once */
        modcp_event_t ev = modcp_job_start(&cp->job, &cp->pdu.job, cp->pdu.wdata, cp->pdu.rdata,
                                           cp->pdu.rcap, now_us);
        if (ev == MODCP_EV_NONE) {
            cp->request_pending = true;
            return;
        }
        a = modcp_pdu_complete(&cp->pdu, env, ev, pdu, &out_len, now_us);
    }
#if MODCP_WITH_EXTENDED
#if !MODCP_PDU_COMPLETE_FINISHES
    modcp_pdu_finished(&cp->pdu, env, a, now_us); /* FC11/12 accounting, comm loss */
#endif
    uint8_t delim;
    if (modcp_ext_take_delimiter(&cp->ext, &delim)) { /* FC08 sub 03 / 01 */
        modcp_link_set_delimiter(&cp->link, delim); /* the ASCII input delimiter */
    }
#endif
    if (a == MODCP_PDU_REPLY) {
        line_reply(cp, out_len, now_us);
    } else {
        modcp_link_done(&cp->link);
    }
}

/* RS232 automatic signals configured: DSR gates the reception, a character ends the
 * time to RTS off. */
static void rx_signals(modcp_cp_t *cp, uint8_t byte, uint32_t now_us)
{
    if (!sig_rx_allowed(cp)) {
        return; /* RS232 automatic signals: no reception while DSR is OFF */
    }
    sig_on_rx(cp, now_us);
    cp->published = false;
    modcp_link_on_byte(&cp->link, byte, now_us);
}

/* The cold part of modcp_cp_on_rx: every character the link does not store at once (a
 * frame's start and end, the framing's checks, ASCII) and every one with the RS232
 * automatic signals. */
static MODCP_NOINLINE void rx_other(modcp_cp_t *cp, uint8_t byte, uint32_t now_us)
{
    if (sig_enabled(cp)) {
        rx_signals(cp, byte, now_us);
        return;
    }
    cp->published = false; /* see publish() */
    modcp_link_on_byte(&cp->link, byte, now_us);
}

/* The receive interrupt's entry. A character inside a frame the link stores as it is
 * (RTU) costs a store and its time (link_rx_store); the rest is rx_other. Such a
 * character changes nothing the status area shows but what the poll reads from the
 * link's record of the last received character (link.last_us): the LEDs, which
 * publish() compares, and the end of a wire break, which line_poll marks. So nothing
 * else runs per byte, not even the mark that the status area may change. */
void modcp_cp_on_rx(modcp_cp_t *cp, uint8_t byte, uint32_t now_us)
{
    if (link_rx_store(&cp->link, byte, now_us)) { /* (never with the RS232 automatic
                                                      signals: link_set_stop) */
        return;
    }
    rx_other(cp, byte, now_us);
}

/* Characters back to back (DMA, FIFO): the link's block path; with RS232 automatic
 * signals each goes through the per-character entry at its own time. */
static MODCP_NOINLINE void rx_block_signals(modcp_cp_t *cp, const uint8_t *b, uint16_t n,
                                               uint32_t end_us)
{
    uint32_t t = end_us - ((uint32_t)n - 1u) * cp->link.char_us;
    for (uint16_t k = 0; k < n; k++) {
        rx_signals(cp, b[k], t);
        t += cp->link.char_us;
    }
}

void modcp_cp_on_rx_block(modcp_cp_t *cp, const uint8_t *b, uint16_t n, uint32_t end_us)
{
    if (sig_enabled(cp)) {
        rx_block_signals(cp, b, n, end_us); /* kept out: no stack frame on the plain path */
        return;
    }
    cp->published = false; /* see publish() */
    modcp_link_on_block(&cp->link, b, n, end_us);
}

void modcp_cp_on_line_error(modcp_cp_t *cp, uint8_t line_errors, uint32_t now_us)
{
    if (!sig_rx_allowed(cp)) {
        return;
    }
    sig_on_rx(cp, now_us);
    bool reported = modcp_link_on_error(&cp->link, line_errors, now_us);
    modcp_cpdiag_line_error(&cp->cpdiag, line_errors, reported); /* wire break */
    cp->err_mark_us = cp->link.last_us; /* a character after this one ends a wire break */
    cp->published = false;
}

/* An expiry that is more than a re-arm: the RS232 signals' times, or the end of a frame
 * (the link decides) and, for a frame for us, the request carried on. Out of line in
 * every build (built for speed with advance inline), so that the re-arms
 * (modcp_cp_on_timer) pay for no stack frame: at -Os too, where it costs 20 B and saves
 * a frame per re-arm (FC16 x 123 per character: 10,667 -> 9,735 instructions, bench_core_os). */
static MODCP_NOINLINE void timer_expired(modcp_cp_t *cp, uint32_t now_us)
{
    cp->published = false;
    if (sig_on_timer(cp, now_us)) {
        return; /* data output waiting time / time to RTS off */
    }
    modcp_frame_t f;
    if (modcp_link_on_timer(&cp->link, now_us, &f)) {
        advance(cp, &f, now_us); /* a frame for us has ended */
    }
}

void modcp_cp_on_timer(modcp_cp_t *cp, uint32_t now_us)
{
    /* the common expiry while a frame arrives (armed at its first character, bytes
     * kept coming): only the rest of the silence is armed again, nothing published;
     * the RS232 signals never run a timer of their own while the link receives (RX /
     * SKIP): theirs run in TURNAROUND and TX */
    if (link_timer_rearm(&cp->link, now_us)) {
        return;
    }
    timer_expired(cp, now_us);
}

/* Transmission complete with RS232 automatic signals: RTS OFF after its delay, then
 * receive (the signals' timer), unless they leave it to the link. */
static MODCP_NOINLINE void tx_done_signals(modcp_cp_t *cp, uint32_t now_us)
{
    modcp_link_tx_complete(&cp->link, now_us); /* TXD: the last stop bit is out */
    if (!sig_on_tx_done(cp, now_us)) {
        modcp_link_on_tx_done(&cp->link, now_us);
    }
}

void modcp_cp_on_tx_done(modcp_cp_t *cp, uint32_t now_us)
{
    cp->published = false;
    if (sig_enabled(cp)) {
        tx_done_signals(cp, now_us);
        return;
    }
    modcp_link_on_tx_done(&cp->link, now_us); /* TXD off (the last stop bit is out) too */
}

/* Drop the request in progress and stop the line (and the RS232 signals): the CP is not
 * configured; the status area is published in full. */
static void stop_line(modcp_cp_t *cp)
{
    if (cp->request_pending) {
        modcp_job_abort(&cp->job);
        cp->request_pending = false;
    }
    modcp_link_disable(&cp->link);
#if MODCP_WITH_RS232_SIGNALS
    modcp_sig_disable(&cp->sig);
#endif
    cp->configured = false;
    cp->publish_all = true; /* signals off; PARAMS clears the buffer, sets param_event */
}

/* Drop the request in progress, stop the line: the CP is not ready. */
static void unconfigure(modcp_cp_t *cp)
{
    stop_line(cp);
    cp->env.fb_ready = false;
}

#if MODCP_SHARED_PARAMS_BUFFER
/* A PARAMS record starts and will be stored in the frame buffer: nothing may use the
 * buffer any more. A reply on the line is sent from it, so the record waits until
 * its transmission is complete (false); a request being received or processed, or a
 * reply not yet started, is dropped. The line is off until the record is taken; the
 * rest (FB initialised, diagnostics) stays until take_params finds the record changed. */
static bool params_start(modcp_cp_t *cp)
{
    if (cp->link.state == (uint8_t)MODCP_LINK_TX) {
        return false;
    }
    stop_line(cp);
    return true;
}
#endif

/* The receive-line preset in force ([RTU-2009] Table 5-8): `default` is BREAK detection on
 * RS422, HIGH on RS485 (the manual's recommendation for the bus), none on RS232. */
static uint8_t rx_preset(const modcp_params_t *p)
{
    if (p->rx_preset != (uint8_t)MODCP_RXP_DEFAULT) {
        return p->rx_preset;
    }
    uint8_t preset = (uint8_t)MODCP_RXP_NONE;
    if (p->iface == (uint8_t)MODCP_IFACE_RS485) {
        preset = (uint8_t)MODCP_RXP_HIGH;
    } else if (p->iface == (uint8_t)MODCP_IFACE_RS422) {
        preset = (uint8_t)MODCP_RXP_BREAK;
    } else {
        /* RS232: none */
    }
    return preset;
}

/* The parameters in force, on the line: link, job limits, RS232 signals, receive-line
 * preset. */
static void configure(modcp_cp_t *cp)
{
    const modcp_hal_t *hal = cp->link.hal;
    if (hal->set_rx_preset != NULL) {
        hal->set_rx_preset(hal->ctx, rx_preset(&cp->params));
    }
    cp->configured = true;
    modcp_job_configure(&cp->job, modcp_params_job_limit(&cp->params),
                        (uint32_t)cp->params.cpu_timeout_ms * 1000u);
    modcp_link_configure(&cp->link, &cp->params);
#if MODCP_WITH_EXTENDED && MODCP_WITH_ASCII
    modcp_link_set_delimiter(&cp->link, cp->ext.ascii_delimiter); /* FC08 sub 03's, kept */
#endif
#if MODCP_WITH_RS232_SIGNALS
    modcp_sig_configure(&cp->sig, &cp->params);
#endif
}

/* A PARAMS record arrived: validate and apply, or stay not ready. The record the CP
 * holds already (the same identity and length: the CPU side re-sends it at an FB
 * restart, [RTU-2003] §4.2, §5.5) is no re-parameterisation (VIPA CP 341 manual §7.2, (00)04H
 * "parameters already on the CP"): the request in progress, the diagnostic buffer, a
 * wire break, comm-loss arming and listen-only mode stay; with the record in the frame
 * buffer (features.h) the request in progress was dropped and the line comes back on. */
static MODCP_NOINLINE void take_params(modcp_cp_t *cp)
{
    const uint8_t *record = cp->job.msgbuf; /* cp->record, or cp->buf (features.h) */
    uint16_t id = modcp_bp_record_id(record, cp->job.msglen);
    if (cp->param_event == MODCP_EV_NONE && id == cp->record_crc &&
        cp->job.msglen == cp->record_len) {
        if (!cp->configured) { /* MODCP_SHARED_PARAMS_BUFFER: params_start stopped it */
            configure(cp);
        }
        modcp_diag_event(&cp->diag, MODCP_EV_PARAMS_SAME); /* (00)04H */
        return;
    }
    unconfigure(cp);
    modcp_diag_clear_buffer(&cp->diag); /* [VIPA-341] §8.3: re-parameterisation clears it */
#if MODCP_WITH_EXTENDED
    modcp_ext_reset(&cp->ext, &cp->diag); /* comm loss disarmed, listen-only left */
#endif

    /* decoded and validated in place: the CP is not configured while it runs, and a
     * record that does not validate whole leaves the defaults (below) */
    modcp_event_t ev = modcp_params_decode(record, cp->job.msglen, &cp->params);
    int irq = -1;
    modcp_event_t warning = MODCP_EV_NONE;
    if (ev == MODCP_EV_NONE) {
        irq = cp->params.diag_irq;
        ev = modcp_params_apply(&cp->params, &cp->params, &warning);
    }
    if (ev == MODCP_EV_NONE) {
        modcp_diag_event(&cp->diag, MODCP_EV_PARAMS_TAKEN); /* (00)03H, [VIPA-341] §7.2 */
    }
    modcp_diag_event(&cp->diag, warning);
    cp->param_event = ev;
    if (ev != MODCP_EV_NONE) {
        modcp_diag_event(&cp->diag, ev);
        modcp_params_defaults(&cp->params);
        line_params(cp, false, irq);
        return;
    }
    cp->record_crc = id;
    cp->record_len = cp->job.msglen;
    configure(cp);
    line_params(cp, true, irq);
}

/* The FB's INIT: accept it when our parameters are the ones the CPU side holds. */
static void take_init(modcp_cp_t *cp, const modcp_bp_init_t *init)
{
    modcp_event_t ev = MODCP_EV_NONE;
    if (!cp->configured) {
        ev = cp->param_event;
    } else if (init->record_crc != cp->record_crc) {
        ev = MODCP_EV_PARAM_RECORD;
    } else {
        /* configured with the record the CPU side holds */
    }
    if (ev == MODCP_EV_NONE) {
        cp->areas = init->areas;
        cp->env.fb_ready = true;
    } else {
        cp->env.fb_ready = false;
    }
    cp->ack_event = ev;
    cp->ack_pending = !modcp_job_send_ack(&cp->job, ev);
}

/* The status area is published only when something in it changed, never rebuilt and
 * compared on every poll. cp->published is true while the status area shows the CP's
 * state: every entry point that can change it (a character the link does not store
 * as it is, a line error, a timer, a transmission complete, RS232 inputs), the end of a
 * wire break and every job result, PARAMS or INIT taken by a poll clear it. What
 * changes without any of them (time, the CPU side) is compared with the published
 * values, a few words: LEDs, comm-loss / listen-only flags, the event count (an event
 * logged by a poll: comm loss, backplane errors), the SYSTAT / diagnostic interrupt count.
 * A publication is a few copies: the flags and LEDs, the diagnostics' run (event count,
 * counters, line error counts, STATUS word, diagnostic buffer) and the CP diagnostics'
 * run (diagnostic interrupt record, SYSTAT answer and image) each as one copy — the
 * status area holds them in their owners' order (modcp/backplane.h) —, the parameter
 * event; the RS232 signals while the automatic signals run or after PARAMS / an input
 * change (cp->publish_all). */
/* MODCP_CPST_COMMLOSS / LISTEN_ONLY straight from their owners: the comm-loss
 * supervision (commloss.c, ext.cl_lost) and the FC08 listen-only mode (diag). */
static uint32_t ext_flags(const modcp_cp_t *cp)
{
#if MODCP_WITH_EXTENDED
    return (cp->ext.cl_lost ? MODCP_CPST_COMMLOSS : 0u) |
           (cp->diag.comm.listen_only ? MODCP_CPST_LISTEN_ONLY : 0u);
#else
    (void)cp;
    return 0u; /* no comm-loss supervision, no FC08 in this build */
#endif
}

/* The two runs of the status area laid out as their owners hold them. */
#define ST_AT(f) offsetof(modcp_cp_status_t, f)
#define ST_SAME(first, f, T, tfirst, tf)                                                          \
    (ST_AT(f) - ST_AT(first) == offsetof(T, tf) - offsetof(T, tfirst))
#define ST_DIAG(f) ST_SAME(events_total, f, modcp_diag_t, events_total, f)
#define ST_CPDIAG(f, tf) ST_SAME(diag_irq, f, modcp_cpdiag_t, irq, tf)
#define ST_DIAG_RUN ((ST_AT(buffer_len) - ST_AT(events_total)) + ST_SIZE(modcp_cp_status_t, buffer_len))
#define ST_CPDIAG_RUN ((ST_AT(systat_ack) - ST_AT(diag_irq)) + ST_SIZE(modcp_cp_status_t, systat_ack))
#define ST_SIZE(T, f) sizeof(((T *)0)->f)
_Static_assert(ST_DIAG(counters) && ST_DIAG(frames_too_long) && ST_DIAG(char_errors) &&
                   ST_DIAG(breaks) && ST_DIAG(t15_discards) && ST_DIAG(status) &&
                   ST_DIAG(buffer) && ST_DIAG(buffer_len) &&
                   ST_SIZE(modcp_cp_status_t, counters) == ST_SIZE(modcp_diag_t, counters) &&
                   ST_SIZE(modcp_cp_status_t, buffer) == ST_SIZE(modcp_diag_t, buffer),
               "status area: events_total ... buffer_len as in modcp_diag_t");
_Static_assert(ST_CPDIAG(diag_irq_count, irq_count) && ST_CPDIAG(systat_ack, systat_ack) &&
                   ST_SIZE(modcp_cp_status_t, diag_irq) == MODCP_DIAG_IRQ_BYTES &&
                   ST_SIZE(modcp_cp_status_t, systat) == 16u,
               "status area: diag_irq ... systat_ack as in modcp_cpdiag_t");

/* A run of the status area from its owner's struct (the static asserts above), 16
 * bytes at a time, then the rest: built for size a memcpy of the whole run is a byte
 * loop (newlib-nano's memcpy; x86's rep movsb), 16 bytes a couple of loads and stores.
 * Both runs start with a uint32_t on both sides: 4-aligned. */
#if defined(__GNUC__)
#define ALIGNED4(p) __builtin_assume_aligned((p), 4)
#else
#define ALIGNED4(p) (p)
#endif
static MODCP_ALWAYS_INLINE void copy_run(uint8_t *dst, const uint8_t *src, size_t n)
{
    size_t k = 0;
    for (; k + 16u <= n; k += 16u) {
        (void)memcpy(ALIGNED4(dst + k), ALIGNED4(src + k), 16);
    }
    for (; k < n; k++) {
        dst[k] = src[k];
    }
}

/* Publish the status area, written in place under the seqlock (no copy of it). */
static MODCP_SIZE_NOINLINE void publish(modcp_cp_t *cp, bool sf)
{
    modcp_cp_status_t *st = &cp->job.bp->status; /* only the CP writes it */
    uint32_t ext = ext_flags(cp);
    uint8_t leds = modcp_leds_bits(&cp->leds);
    if (cp->published && st->events_total == cp->diag.events_total &&
        st->systat_ack == cp->cpdiag.systat_ack && st->diag_irq_count == cp->cpdiag.irq_count &&
        st->leds == leds && (st->flags & (MODCP_CPST_COMMLOSS | MODCP_CPST_LISTEN_ONLY)) == ext) {
        return;
    }
    (void)modcp_bp_status_begin(cp->job.bp);
    st->flags = (cp->configured ? MODCP_CPST_CONFIGURED : 0u) |
                (modcp_cp_ready(cp) ? MODCP_CPST_READY : 0u) |
                (sf ? MODCP_CPST_SF : 0u) | ext |
                (cp->cpdiag.wire_break ? MODCP_CPST_WIRE_BREAK : 0u) |
                (cp->cpdiag.param_error ? MODCP_CPST_PARAM_ERROR : 0u);
    st->leds = leds;
    copy_run((uint8_t *)st + ST_AT(events_total),
             (const uint8_t *)&cp->diag + offsetof(modcp_diag_t, events_total), ST_DIAG_RUN);
    (void)memcpy(st->diag_irq, cp->cpdiag.irq, ST_CPDIAG_RUN);
    st->param_event = cp->param_event;
#if MODCP_WITH_RS232_SIGNALS
    if (cp->publish_all || cp->sig.enabled) {
        st->signals = modcp_sig_bits(&cp->sig);
        st->signal_aborts = cp->sig.aborts;
    }
#endif /* else: stay 0 from modcp_bp_init (the CP is the status area's only writer) */
    modcp_bp_status_end(cp->job.bp);
    cp->published = true;
    cp->publish_all = false;
}

void modcp_cp_poll(modcp_cp_t *cp, uint32_t now_us)
{
    if (cp->ack_pending) {
        cp->ack_pending = !modcp_job_send_ack(&cp->job, cp->ack_event);
    }
    modcp_bp_init_t init; /* an INIT's payload, until take_init has taken it */
    for (;;) {
        modcp_jobp_t r = modcp_job_poll(&cp->job, now_us, &init);
        if (r == MODCP_JOBP_NOTHING) {
            break;
        }
        cp->published = false;
        if (r == MODCP_JOBP_DONE) {
            if (!cp->request_pending) {
                continue;
            }
            cp->request_pending = false;
            advance(cp, NULL, now_us); /* the next job, or the reply */
            if (cp->job.state == (uint8_t)MODCP_JOBST_IDLE && modcp_ring_peek(&cp->job.bp->to_cp) == NULL) {
                break; /* what another modcp_job_poll would find: nothing */
            }
        } else if (r == MODCP_JOBP_PARAMS) {
            take_params(cp);
        } else if (r == MODCP_JOBP_INIT) {
            take_init(cp, &init);
        } else { /* MODCP_JOBP_PARAMS_START: only with the record in the frame buffer */
#if MODCP_SHARED_PARAMS_BUFFER
            if (!params_start(cp)) {
                break; /* a reply is on the line: the record waits for its end */
            }
            modcp_job_params_grant(&cp->job);
#endif
        }
    }
    const bool sf = line_poll(cp, now_us);
#if MODCP_WITH_EXTENDED
    /* comm-loss time; the flags are published from ext / diag (ext_flags) */
    uint32_t reset = atomic_load_explicit(&cp->job.bp->commloss_reset, memory_order_acquire);
    if (cp->params.commloss_ms != 0u || cp->ext.cl_armed || cp->ext.cl_lost ||
        reset != cp->ext.cl_reset_seen) {
        modcp_commloss_poll(&cp->ext, &cp->params, &cp->diag, reset, now_us);
    }
#endif
    publish(cp, sf);
}
