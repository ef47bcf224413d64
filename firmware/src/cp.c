/* modcp — the CP side wired together.
 *
 * Start-up (SPEC §2, §6): the CP is "not ready" (SF on, line ignored) until the CPU
 * side's PARAMS record arrives and validates. A bad record leaves it not ready with
 * the record's first fatal event in the diagnostics; never half-configured. The FB's
 * INIT then brings the controller's area sizes and the work area; until it has been
 * acknowledged every request gets exception 04 / (0E)56H. */
#include "modcp/cp.h"

#include <string.h>

#include "modcp/crc.h"

static modcp_pdu_env_t env_of(modcp_cp_t *cp)
{
    modcp_pdu_env_t e = {&cp->params, &cp->areas, &cp->diag, cp->fb_ready};
    return e;
}

static void set_led(modcp_cp_t *cp, modcp_led_t led, bool on)
{
    if (cp->hal != NULL && cp->hal->set_led != NULL) {
        cp->hal->set_led(cp->hal->ctx, led, on);
    }
}

void modcp_cp_init(modcp_cp_t *cp, const modcp_hal_t *hal, modcp_backplane_t *bp)
{
    memset(cp, 0, sizeof *cp);
    cp->hal = hal;
    cp->bp = bp;
    modcp_diag_init(&cp->diag);
    modcp_params_defaults(&cp->params);
    modcp_link_init(&cp->link, hal, &cp->diag, cp->buf, (uint16_t)sizeof cp->buf);
    modcp_job_init(&cp->job, bp, cp->record, (uint16_t)sizeof cp->record);
    cp->param_event = MODCP_EV_PARAM_RECORD; /* nothing received yet */
    set_led(cp, MODCP_LED_SF, true);
}

bool modcp_cp_ready(const modcp_cp_t *cp)
{
    return cp->configured && cp->fb_ready;
}

/* Finish the current request with the PDU engine's decision. */
static void finish(modcp_cp_t *cp, modcp_pdu_action_t a, uint16_t out_len, uint32_t now_us)
{
    if (a == MODCP_PDU_REPLY) {
        modcp_link_reply(&cp->link, out_len, now_us);
    } else {
        modcp_link_done(&cp->link);
    }
}

static void process_request(modcp_cp_t *cp, uint32_t now_us)
{
    modcp_pdu_env_t env = env_of(cp);
    modcp_frame_t *f = &cp->frame;
    uint16_t out_len = 0;
    modcp_pdu_action_t a =
        modcp_pdu_request(&cp->pdu, &env, f->addr, f->pdu, f->pdu_len, f->pdu_cap, &out_len);
    if (a == MODCP_PDU_JOB) {
        uint32_t timeout_us = (uint32_t)cp->params.cpu_timeout_ms * 1000u;
        modcp_event_t ev = modcp_job_start(&cp->job, &cp->pdu.job, cp->pdu.wdata, cp->pdu.rdata,
                                           cp->pdu.rcap, modcp_params_job_limit(&cp->params),
                                           timeout_us, now_us);
        if (ev == MODCP_EV_NONE) {
            cp->request_pending = true;
            modcp_cp_poll(cp, now_us); /* push the first blocks at once */
            return;
        }
        a = modcp_pdu_complete(&cp->pdu, &env, ev, f->pdu, &out_len);
    }
    finish(cp, a, out_len, now_us);
}

void modcp_cp_on_rx(modcp_cp_t *cp, uint8_t byte, uint32_t now_us)
{
    modcp_link_on_byte(&cp->link, byte, now_us);
}

void modcp_cp_on_line_error(modcp_cp_t *cp, uint8_t line_errors, uint32_t now_us)
{
    modcp_link_on_error(&cp->link, line_errors, now_us);
}

void modcp_cp_on_timer(modcp_cp_t *cp, uint32_t now_us)
{
    if (modcp_link_on_timer(&cp->link, now_us, &cp->frame)) {
        process_request(cp, now_us);
    }
}

void modcp_cp_on_tx_done(modcp_cp_t *cp, uint32_t now_us)
{
    modcp_link_on_tx_done(&cp->link, now_us);
}

/* A PARAMS record arrived: validate and apply, or stay not ready. */
static void take_params(modcp_cp_t *cp)
{
    if (cp->request_pending) {
        modcp_job_abort(&cp->job);
        cp->request_pending = false;
    }
    modcp_link_disable(&cp->link);
    cp->configured = false;
    cp->fb_ready = false;
    set_led(cp, MODCP_LED_SF, true);

    modcp_params_t rec;
    modcp_event_t ev = modcp_params_decode(cp->record, cp->job.msglen, &rec);
    modcp_event_t warning = MODCP_EV_NONE;
    if (ev == MODCP_EV_NONE) {
        ev = modcp_params_apply(&rec, &cp->params, &warning);
    }
    modcp_diag_event(&cp->diag, warning);
    cp->param_event = ev;
    if (ev != MODCP_EV_NONE) {
        modcp_diag_event(&cp->diag, ev);
        modcp_params_defaults(&cp->params);
        return;
    }
    cp->record_crc = modcp_crc16(cp->record, cp->job.msglen);
    cp->configured = true;
    modcp_link_configure(&cp->link, &cp->params);
}

/* The FB's INIT: accept it when our parameters are the ones the CPU side holds. */
static void take_init(modcp_cp_t *cp)
{
    modcp_event_t ev = MODCP_EV_NONE;
    if (!cp->configured) {
        ev = cp->param_event;
    } else if (cp->job.init.record_crc != cp->record_crc) {
        ev = MODCP_EV_PARAM_RECORD;
    }
    if (ev == MODCP_EV_NONE) {
        cp->areas = cp->job.init.areas;
        cp->fb_ready = true;
        set_led(cp, MODCP_LED_SF, false);
    } else {
        cp->fb_ready = false;
    }
    cp->ack_event = ev;
    cp->ack_pending = !modcp_job_send_ack(&cp->job, ev);
}

/* Publish the status area when anything in it changed. */
static void publish(modcp_cp_t *cp)
{
    modcp_cp_status_t st;
    memset(&st, 0, sizeof st);
    st.flags = (cp->configured ? MODCP_CPST_CONFIGURED : 0u) |
               (modcp_cp_ready(cp) ? MODCP_CPST_READY : 0u) |
               (modcp_cp_ready(cp) ? 0u : MODCP_CPST_SF) | cp->status_flags;
    st.events_total = cp->diag.events_total;
    memcpy(st.buffer, cp->diag.buffer, sizeof st.buffer);
    st.buffer_len = cp->diag.buffer_len;
    st.status = cp->diag.status;
    memcpy(st.counters, cp->diag.counters, sizeof st.counters);
    st.param_event = cp->param_event;
    if (cp->published && memcmp(&st, &cp->last_status, sizeof st) == 0) {
        return;
    }
    cp->last_status = st;
    cp->published = true;
    modcp_bp_publish_status(cp->bp, &st);
}

void modcp_cp_poll(modcp_cp_t *cp, uint32_t now_us)
{
    if (cp->ack_pending) {
        cp->ack_pending = !modcp_job_send_ack(&cp->job, cp->ack_event);
    }
    for (;;) {
        modcp_jobp_t r = modcp_job_poll(&cp->job, now_us);
        if (r == MODCP_JOBP_NOTHING) {
            break;
        }
        if (r == MODCP_JOBP_DONE) {
            if (!cp->request_pending) {
                continue;
            }
            cp->request_pending = false;
            modcp_pdu_env_t env = env_of(cp);
            uint16_t out_len = 0;
            modcp_event_t ev = cp->job.event;
            modcp_pdu_action_t a = modcp_pdu_complete(&cp->pdu, &env, ev, cp->frame.pdu, &out_len);
            finish(cp, a, out_len, now_us);
        } else if (r == MODCP_JOBP_PARAMS) {
            take_params(cp);
        } else if (r == MODCP_JOBP_INIT) {
            take_init(cp);
        }
    }
    publish(cp);
}
