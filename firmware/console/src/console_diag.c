/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console: diag (the diagnostic buffer in words) and status (FB, CP,
 * serial-line counters, the CP's status area); names of FB states and events.
 * Portable C11: no OS, no heap, no globals. */
#include "console_internal.h"
#include "modcp/signals.h"

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

int con_cmd_status(modcp_console_env_t *env, out_t *o)
{
    con_printf(o, "status:");
    if (env->fb != NULL) {
        const modcp_fb_t *fb = env->fb;
        con_printf(o, " fb=%s cp_start_ok=%u cp_start_error=%u cp_start_ndr=%u error_nr=%u"
                      " error_info=0x%04X jobs=%lu",
                   modcp_console_fb_state(fb->state), fb->out.cp_start_ok ? 1u : 0u,
                   fb->out.cp_start_error ? 1u : 0u, fb->out.cp_start_ndr ? 1u : 0u,
                   (unsigned)fb->out.error_nr, (unsigned)fb->out.error_info,
                   (unsigned long)fb->jobs_done);
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
    const modcp_diag_t *d = env->diag;
    if (d != NULL) {
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
        con_printf(o, " listen_only=%u commloss=%u comm_events=%u",
                   d->comm.listen_only ? 1u : 0u,
                   (env->cp_status != NULL && (env->cp_status->flags & MODCP_CPST_COMMLOSS)) ? 1u : 0u,
                   (unsigned)d->comm.event_count);
#endif
    }
    const modcp_cp_status_t *st = env->cp_status;
    if (st != NULL) {
        static const char *const led_names[3] = {"SF", "TXD", "RXD"};
        static const struct {
            uint8_t bit;
            const char *name;
        } sig_names[4] = {{MODCP_SIGBIT_RTS, "RTS"}, {MODCP_SIGBIT_DTR, "DTR"},
                          {MODCP_SIGBIT_CTS, "CTS"}, {MODCP_SIGBIT_DSR, "DSR"}};
        con_printf(o, " leds=");
        bool any = false;
        for (unsigned k = 0; k < 3u; k++) {
            if ((st->leds & (1u << k)) != 0u) {
                con_printf(o, "%s%s", any ? "," : "", led_names[k]);
                any = true;
            }
        }
        con_printf(o, "%s signals=", any ? "" : "off");
        any = false;
        for (unsigned k = 0; k < 4u; k++) {
            if ((st->signals & sig_names[k].bit) != 0u) {
                con_printf(o, "%s%s", any ? "," : "", sig_names[k].name);
                any = true;
            }
        }
        con_printf(o, "%s%s line=%s signal_aborts=%u diag_irq=", any ? "" : "off",
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
    return MODCP_CONSOLE_OK;
}

