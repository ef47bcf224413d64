/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console: diag (the diagnostic buffer in words) and status (FB, CP,
 * serial-line counters, the CP's status area); names of FB states and events.
 * Portable C11: no OS, no heap, no globals. */
#include "console_internal.h"
#include "modcp/signals.h"
#include "modcp/version.h"

#include <stdio.h>

/* ---- names ------------------------------------------------------------------- */

const char *modcp_console_fb_state(uint8_t state)
{
    switch (state) {
    case MODCP_FBST_STOPPED: return "STOPPED";
    case MODCP_FBST_INIT_SEND: return "INIT_SEND";
    case MODCP_FBST_INIT_WAIT: return "INIT_WAIT";
    case MODCP_FBST_RUN: return "RUN";
    case MODCP_FBST_FAILED: return "FAILED";
    default: return "UNKNOWN";
    }
}

size_t modcp_console_event_name(modcp_event_t ev, char *out, size_t cap)
{
    if (cap == 0u) {
        return 0;
    }
    int n = snprintf(out, cap, "(%02X)%02XH", (unsigned)MODCP_EVENT_CLASS(ev),
                     (unsigned)MODCP_EVENT_NUMBER(ev));
    if (n < 0) {
        out[0] = '\0';
        return 0;
    }
    return (size_t)n < cap ? (size_t)n : cap - 1u;
}

int con_cmd_diag(modcp_console_env_t *env, out_t *o)
{
    const modcp_diag_t *d = env->diag;
    if (d == NULL) {
        return con_fail(o, "diagnostics not available");
    }
    char flags[8];
    size_t fl = 0;
    if ((d->systat_flags & MODCP_SYSTAT_F) != 0u) {
        flags[fl++] = 'F';
    }
    if ((d->systat_flags & MODCP_SYSTAT_U) != 0u) {
        flags[fl++] = 'U';
    }
    if ((d->systat_flags & MODCP_SYSTAT_B) != 0u) {
        flags[fl++] = 'B';
    }
    if (fl == 0u) {
        flags[fl++] = '-';
    }
    flags[fl] = '\0';
    unsigned n = d->buffer_len <= MODCP_DIAG_BUFFER ? d->buffer_len : MODCP_DIAG_BUFFER;
    con_printf(o, "diag: %u events (newest first), total %lu, STATUS 0x%04X, SYSTAT %s", n,
               (unsigned long)d->events_total, (unsigned)d->status, flags);
    for (unsigned i = 0; i < n; i++) {
        modcp_event_t ev = d->buffer[i];
        char en[16];
        (void)modcp_console_event_name(ev, en, sizeof en);
        con_nl(o);
        con_printf(o, "event %u: %s class %02XH %s, number %02XH: %s. Remedy: %s", i + 1u, en,
                   (unsigned)MODCP_EVENT_CLASS(ev), modcp_event_class_text(MODCP_EVENT_CLASS(ev)),
                   (unsigned)MODCP_EVENT_NUMBER(ev), modcp_event_text(ev), modcp_event_remedy(ev));
    }
    return MODCP_CONSOLE_OK;
}

static void status_fb(const modcp_fb_t *fb, out_t *o)
{
    con_printf(o, " fb=%s cp_start_ok=%u cp_start_error=%u cp_start_ndr=%u error_nr=%u"
                  " error_info=0x%04X jobs=%lu",
               modcp_console_fb_state(fb->state), fb->out.cp_start_ok ? 1u : 0u,
               fb->out.cp_start_error ? 1u : 0u, fb->out.cp_start_ndr ? 1u : 0u,
               (unsigned)fb->out.error_nr, (unsigned)fb->out.error_info,
               (unsigned long)fb->jobs_done);
}

static void status_counters(const modcp_console_env_t *env, const modcp_diag_t *d, out_t *o)
{
    con_printf(o, " bus_msg=%u bus_crc=%u exceptions=%u slave_msg=%u no_response=%u nak=%u"
                  " busy=%u overrun=%u events=%lu char_errors=%u breaks=%u too_long=%u t15=%u",
               (unsigned)d->counters[MODCP_CNT_BUS_MSG], (unsigned)d->counters[MODCP_CNT_BUS_CRC],
               (unsigned)d->counters[MODCP_CNT_EXCEPTION],
               (unsigned)d->counters[MODCP_CNT_SLAVE_MSG],
               (unsigned)d->counters[MODCP_CNT_NO_RESPONSE], (unsigned)d->counters[MODCP_CNT_NAK],
               (unsigned)d->counters[MODCP_CNT_BUSY],
               (unsigned)d->counters[MODCP_CNT_CHAR_OVERRUN], (unsigned long)d->events_total,
               (unsigned)d->char_errors, (unsigned)d->breaks, (unsigned)d->frames_too_long,
               (unsigned)d->t15_discards);
#if MODCP_WITH_EXTENDED
    /* extended set: FC08 sub 04 listen-only, comm-loss supervision (MODCP_CPST_*) */
    con_printf(o, " listen_only=%u commloss=%u comm_events=%u", d->comm.listen_only ? 1u : 0u,
               (env->cp_status != NULL && (env->cp_status->flags & MODCP_CPST_COMMLOSS)) ? 1u : 0u,
               (unsigned)d->comm.event_count);
#else
    (void)env;
#endif
}

/* The names of the bits set in bits ("off" when none). */
static void status_bits(out_t *o, uint8_t bits, const uint8_t *mask, const char *const *names,
                        unsigned n)
{
    bool any = false;
    for (unsigned k = 0; k < n; k++) {
        if ((bits & mask[k]) != 0u) {
            con_printf(o, "%s%s", any ? "," : "", names[k]);
            any = true;
        }
    }
    if (!any) {
        con_printf(o, "off");
    }
}

static void status_cp(const modcp_cp_status_t *st, out_t *o)
{
    static const uint8_t led_bits[3] = {1u, 2u, 4u};
    static const char *const led_names[3] = {"SF", "TXD", "RXD"};
    static const uint8_t sig_bits[4] = {MODCP_SIGBIT_RTS, MODCP_SIGBIT_DTR, MODCP_SIGBIT_CTS,
                                        MODCP_SIGBIT_DSR};
    static const char *const sig_names[4] = {"RTS", "DTR", "CTS", "DSR"};
    con_printf(o, " leds=");
    status_bits(o, st->leds, led_bits, led_names, 3u);
    con_printf(o, " signals=");
    status_bits(o, st->signals, sig_bits, sig_names, 4u);
    con_printf(o, "%s line=%s signal_aborts=%u diag_irq=",
               (st->signals & MODCP_SIGBIT_AUTO) != 0u ? "(auto)" : "",
               (st->flags & MODCP_CPST_WIRE_BREAK) != 0u ? "wire-break" : "ok",
               (unsigned)st->signal_aborts);
    if (st->diag_irq_count == 0u) {
        con_printf(o, "none");
    } else {
        con_printf(o, "%02X.%02X.%02X.%02X(#%lu)", (unsigned)st->diag_irq[0],
                   (unsigned)st->diag_irq[1], (unsigned)st->diag_irq[2],
                   (unsigned)st->diag_irq[3], (unsigned long)st->diag_irq_count);
    }
}

int con_cmd_status(modcp_console_env_t *env, out_t *o)
{
    con_printf(o, "status:");
    if (env->fb != NULL) {
        status_fb(env->fb, o);
    }
    if (env->paused != NULL) {
        con_printf(o, " paused=%u", *env->paused ? 1u : 0u);
    }
    con_printf(o, " cycles=%lu", (unsigned long)env->cycles);
    char en[16];
    (void)modcp_console_event_name(env->cp_param_event, en, sizeof en);
    con_printf(o, " cp=%s param_event=%s",
               env->cp_ready ? "ready" : (env->cp_configured ? "configured" : "not-configured"),
               env->cp_param_event == MODCP_EV_NONE ? "none" : en);
    if (env->diag != NULL) {
        status_counters(env, env->diag, o);
    }
    if (env->cp_status != NULL) {
        status_cp(env->cp_status, o);
    }
    con_printf(o, " version=%s", MODCP_VERSION); /* modcp/version.h */
    return MODCP_CONSOLE_OK;
}

